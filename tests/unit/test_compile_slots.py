"""compile_slots: at most N detached background compiles at once (flock'd slot files,
released when the holder dies, however); a compile finding no free slot gives up, starts
no compiler and leaves the VM; without fcntl there is no cap (every compile runs)."""
import os
import shutil
import signal
import subprocess
import sys
import time
from pathlib import Path

import casadi as ca
import numpy as np
import pytest

from ironbark_opt.dynamics import compile_slots
from ironbark_opt.dynamics.compile_slots import compile_slot, max_background_compiles, slot_dir
from ironbark_opt.dynamics.integrator import cached_library, compile_function, compiler_available, run_detached
from ironbark_opt.errors import InputError

ROOT = Path(__file__).resolve().parents[2]
#: a process holding one slot until its stdin closes; prints True (held) or False (none free)
HOLDER = ("import sys\n"
          "from ironbark_opt.dynamics.compile_slots import compile_slot\n"
          "with compile_slot() as got:\n"
          "    print(got, flush=True)\n"
          "    sys.stdin.read()\n")


@pytest.fixture
def slots(tmp_path, monkeypatch):
    """A private slot directory (XDG_RUNTIME_DIR in tmp: other processes' compiles on this
    machine hold none of its slots) and one slot."""
    run = tmp_path / "run"
    run.mkdir()
    monkeypatch.setenv("XDG_RUNTIME_DIR", str(run))
    monkeypatch.setenv("IRONBARK_MAX_BACKGROUND_COMPILES", "1")
    monkeypatch.setenv("PYTHONPATH", os.pathsep.join([str(ROOT), os.environ.get("PYTHONPATH", "")]))
    return run / "ironbark-compile-slots"


def _holder() -> subprocess.Popen:
    proc = subprocess.Popen([sys.executable, "-c", HOLDER], stdin=subprocess.PIPE, stdout=subprocess.PIPE, text=True)
    assert proc.stdout.readline().strip() == "True"
    return proc


def test_n_slots_hold_n_and_release_on_exit(slots):
    """Two slots: two holders (nested in this process: flock treats each open file
    description apart) get one each, a third gets none; leaving a block frees its slot."""
    assert slot_dir() == slots
    with compile_slot(2) as a, compile_slot(2) as b:
        assert (a, b) == (True, True)
        assert sorted(p.name for p in slots.iterdir()) == ["slot-0", "slot-1"]
        assert (slots / "slot-0").read_text() == f"{os.getpid()}\n"
        with compile_slot(2) as c:
            assert c is False
    with compile_slot(2) as a, compile_slot(2) as b:
        assert (a, b) == (True, True)


def test_a_dead_holders_slot_is_reclaimed(slots):
    """A holder killed with SIGKILL (no clean-up of its own) frees its slot: the kernel
    drops the lock with its last descriptor."""
    holder = _holder()
    try:
        assert (slots / "slot-0").read_text() == f"{holder.pid}\n"
        with compile_slot() as got:
            assert got is False                     # held by a live process
    finally:
        holder.send_signal(signal.SIGKILL)
        holder.wait()
    with compile_slot() as got:
        assert got is True


def test_without_fcntl_there_is_no_cap(slots, monkeypatch):
    """Windows (no fcntl): every compile runs, as before the cap; no slot files."""
    monkeypatch.setattr(compile_slots, "fcntl", None)
    with compile_slot(1) as a, compile_slot(1) as b:
        assert (a, b) == (True, True)
    assert not slots.exists()


def test_the_setting(monkeypatch):
    """Default: the processors; 0 allowed (no background compiles); anything else that is
    not an integer >= 0 is an InputError naming the variable."""
    monkeypatch.delenv("IRONBARK_MAX_BACKGROUND_COMPILES", raising=False)
    assert max_background_compiles() == max(1, os.cpu_count() or 1)
    monkeypatch.setenv("IRONBARK_MAX_BACKGROUND_COMPILES", " 3 ")
    assert max_background_compiles() == 3
    for bad in ("two", "-1", "1.5"):
        monkeypatch.setenv("IRONBARK_MAX_BACKGROUND_COMPILES", bad)
        with pytest.raises(InputError, match="IRONBARK_MAX_BACKGROUND_COMPILES"):
            max_background_compiles()


def test_run_detached_starts_nothing_for_zero_and_cleans_up_on_a_bad_setting(tmp_path, monkeypatch):
    """IRONBARK_MAX_BACKGROUND_COMPILES=0 starts no process; a bad value raises before
    starting one; either way the caller's marker files are removed (the next run retries)."""
    started = []
    monkeypatch.setattr(subprocess, "Popen", lambda *a, **k: started.append(a))
    for value, raises in (("0", False), ("lots", True)):
        marker = tmp_path / f".lib_{value}.c"
        marker.write_text("pending\n")
        monkeypatch.setenv("IRONBARK_MAX_BACKGROUND_COMPILES", value)
        if raises:
            with pytest.raises(InputError):
                run_detached("ironbark_opt.dynamics.integrator:_compile_source", [], [marker])
        else:
            run_detached("ironbark_opt.dynamics.integrator:_compile_source", [], [marker])
        assert not marker.exists()
    assert started == []


def _settle(jit: Path) -> None:
    """Wait (not a timed assert: the asserts are on the state after) until the detached
    child has removed its marker; it runs at the lowest priority, so on a busy machine
    that can take a while."""
    deadline = time.time() + 300
    while list(jit.glob(".*")) and time.time() < deadline:
        time.sleep(0.2)


@pytest.mark.skipif(not compiler_available(), reason="no C compiler on this machine")
def test_a_detached_compile_without_a_free_slot_starts_no_compiler(tmp_path, monkeypatch, slots):
    """N = 1 and the slot held by another process: the detached compile gives up (no
    compiler started, no library, no file left; this run keeps the VM).  Once the holder
    has exited the same call compiles: one compiler run, and the library agrees with the
    VM to the bit."""
    from ironbark_opt.dynamics.integrator import _compiler
    monkeypatch.setenv("IRONBARK_CACHE_DIR", str(tmp_path / "cache"))
    monkeypatch.setattr("ironbark_opt.dynamics.integrator.AFTER_PARENT_MAX_S", 0.0)
    log = tmp_path / "compiler-runs"
    cc = tmp_path / "cc"                          # counts its runs, then compiles for real
    cc.write_text(f'#!/bin/sh\necho "$$" >> {log}\nexec {shutil.which(_compiler())} "$@"\n')
    cc.chmod(0o755)
    monkeypatch.setenv("CC", str(cc))
    jit = tmp_path / "cache" / "jit"
    x = ca.SX.sym("x", 2)
    f = ca.Function("capped", [x], [ca.vertcat(ca.sin(x[0]) * x[1], x[0] ** 3)])

    holder = _holder()
    try:
        assert compile_function(f, key="k1", background=True) is f          # the VM, now
        _settle(jit)
        assert not log.exists()                                           # no compiler started
        assert sorted(p.name for p in jit.iterdir()) == []                # no library, marker removed
    finally:
        holder.stdin.close()
        holder.wait()
    assert compile_function(f, key="k1", background=True) is f            # retried by the next run
    _settle(jit)
    assert len(log.read_text().splitlines()) == 1
    assert sorted(p.name for p in jit.iterdir()) == ["capped_k1.so"]
    lib = cached_library("capped", "k1")
    w = [0.4, -1.3]
    assert np.array_equal(np.array(lib(w)), np.array(f(w)))
