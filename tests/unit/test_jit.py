"""C compilation of the trajectory Functions: same numbers, cached on disk."""
import os
from pathlib import Path

import numpy as np
import pytest

from ironbark_opt.dynamics.integrator import compile_function, compiler_available
from ironbark_opt.dynamics.model import FlightModel
from ironbark_opt.vehicle import load_setup

ROOT = Path(__file__).resolve().parents[2]


@pytest.mark.skipif(not compiler_available(), reason="no C compiler on this machine")
def test_compiled_flight_equals_vm_and_is_cached(tmp_path, monkeypatch):
    monkeypatch.setenv("IRONBARK_CACHE_DIR", str(tmp_path))
    setup = load_setup(ROOT / "examples/calisto/calisto.toml")
    p = setup.nominal_parameters()
    vm = FlightModel(setup).run(p)
    jit = FlightModel(setup, jit=True).run(p)
    libs = sorted((tmp_path / "jit").glob("*.so"))
    assert len(libs) == 1               # one library: the ascent, the phase trajectories, apogee event, outputs
    print(f"apogee VM {vm['x_apogee'][2]:.9f} m, compiled {jit['x_apogee'][2]:.9f} m")
    assert jit["x_apogee"][2] == pytest.approx(vm["x_apogee"][2], abs=1e-6)
    assert jit["t_apogee"] == pytest.approx(vm["t_apogee"], abs=1e-9)
    # a rebuilt library would be renamed into place (a new inode); loading only marks it
    # used (its mtime, for the cache's size limit)
    inodes = [lib.stat().st_ino for lib in libs]
    FlightModel(setup, jit=True)                            # second build: loads, does not compile
    assert [lib.stat().st_ino for lib in sorted((tmp_path / "jit").glob("*.so"))] == inodes


def test_without_compiler_the_vm_is_used(monkeypatch):
    import casadi as ca
    monkeypatch.setenv("CC", "")
    monkeypatch.setattr("shutil.which", lambda name: None)
    x = ca.SX.sym("x")
    f = ca.Function("sq", [x], [x * x])
    assert compile_function(f) is f
    assert float(f(3.0)) == 9.0


@pytest.mark.skipif(not compiler_available(), reason="no C compiler on this machine")
def test_compiled_and_vm_agree_to_1e_9_relative(tmp_path, monkeypatch):
    """Every sample of the flight (states and derived outputs), compiled vs the VM."""
    from ironbark_opt.flight import simulate
    monkeypatch.setenv("IRONBARK_CACHE_DIR", str(tmp_path))
    setup = load_setup(ROOT / "examples/calisto/calisto.toml")
    vm = simulate(setup, jit=False).to_dataframe()
    cc = simulate(setup, jit=True).to_dataframe()
    cols = [c for c in vm.columns if c != "phase"]
    a, b = vm[cols].to_numpy(), cc[cols].to_numpy()
    scale = np.maximum(np.abs(a).max(axis=0), 1e-300)            # per column
    err = float(np.max(np.abs(a - b) / scale))
    print(f"{a.shape[0]} samples x {len(cols)} columns: max relative difference {err:.2e} (tolerance 1e-9)")
    assert err < 1e-9


def _capture_detached(monkeypatch) -> list:
    """Record the detached processes a first run would start, instead of starting them
    (the real spawn is tested in test_compile_detached.py): on a busy machine a
    lowest-priority compile can wait for minutes."""
    calls = []
    monkeypatch.setattr("ironbark_opt.dynamics.integrator.run_detached",
                        lambda target, args, cleanup: calls.append((target, args, cleanup)))
    return calls


def _run_captured(calls) -> None:
    """Do, here, what the captured detached processes would have done."""
    import importlib
    for target, args, cleanup in calls:
        mod, name = target.split(":")
        getattr(importlib.import_module(mod), name)(*args)
        for path in cleanup:
            Path(path).unlink(missing_ok=True)


@pytest.mark.skipif(not compiler_available(), reason="no C compiler on this machine")
def test_auto_flies_the_vm_now_and_compiles_in_the_background(tmp_path, monkeypatch):
    """A first run ("auto", nothing cached) flies the VM and generates no C code itself:
    it hands the model's pickled constructor arguments to one detached process, which
    rebuilds the model and compiles the library the next run loads."""
    import casadi as ca
    monkeypatch.setenv("IRONBARK_CACHE_DIR", str(tmp_path))
    monkeypatch.setenv("IRONBARK_JIT", "auto")
    calls = _capture_detached(monkeypatch)
    generated = []
    monkeypatch.setattr(ca.CodeGenerator, "generate", lambda self, *a: generated.append(a))
    setup = load_setup(ROOT / "examples/calisto/calisto.toml")
    p = setup.nominal_parameters()
    first = FlightModel(setup, jit="auto")
    assert first._run["coast"] is first.trajectory["coast"]      # nothing cached: the VM
    ref = first.run(p)
    assert generated == [] and not list((tmp_path / "jit").glob("*.so"))
    assert [c[0] for c in calls] == ["ironbark_opt.dynamics.model_cache:_compile_model"]
    assert {Path(f).name for f in calls[0][2]} == {f.name for f in (tmp_path / "jit").glob(".model_*")}
    FlightModel(setup, jit="auto")                                # pending: not started twice
    assert len(calls) == 1
    monkeypatch.undo()
    monkeypatch.setenv("IRONBARK_CACHE_DIR", str(tmp_path))
    monkeypatch.setenv("IRONBARK_JIT", "auto")
    _run_captured(calls)
    assert len(list((tmp_path / "jit").glob("*.so"))) == 1 and not list((tmp_path / "jit").glob(".*"))
    second = FlightModel(setup, jit="auto")
    assert second._run["coast"] is not second.trajectory["coast"]  # the library the background built
    got = second.run(p)
    err = abs(got["x_apogee"][2] - ref["x_apogee"][2]) / ref["x_apogee"][2]
    print(f"apogee VM {ref['x_apogee'][2]:.9f} m, background-compiled {got['x_apogee'][2]:.9f} m ({err:.1e})")
    assert err < 1e-9


@pytest.mark.skipif(not compiler_available(), reason="no C compiler on this machine")
def test_slot_model_compiles_in_the_background(tmp_path, monkeypatch):
    """The motor-slot model of a ranking: the VM on the first run, its seven libraries
    (phase trajectories, apogee event, output rows) from one detached process, and
    the compiled flight and outputs equal to the VM's to 1e-9 relative."""
    from ironbark_opt.dynamics.slot_model import SlotFlightModel
    from ironbark_opt.motors import load_motor
    monkeypatch.setenv("IRONBARK_CACHE_DIR", str(tmp_path))
    monkeypatch.setenv("IRONBARK_JIT", "auto")
    calls = _capture_detached(monkeypatch)
    setup = load_setup(ROOT / "examples/calisto/calisto.toml")
    motor = load_motor(ROOT / "tests/data/motors/AeroTech_M1340W.eng")
    first = SlotFlightModel(setup, 48, (384, 320), jit="auto")
    p = first.parameters(setup.nominal_parameters(), motor, first.grid_for(motor, setup.nominal_parameters()))
    ref = first.run(p)
    y_ref = first.outputs(ref["t"], ref["x"], ref["phase"], p)
    assert len(calls) == 1 and not list((tmp_path / "jit").glob("*.so"))
    monkeypatch.undo()
    monkeypatch.setenv("IRONBARK_CACHE_DIR", str(tmp_path))
    monkeypatch.setenv("IRONBARK_JIT", "auto")
    _run_captured(calls)
    assert len(list((tmp_path / "jit").glob("*.so"))) == 7
    second = SlotFlightModel(setup, 48, (384, 320), jit="auto")
    got = second.run(p)
    assert all(second._run[ph].is_a("External") for ph in ("rail", "boost", "coast"))
    y = second.outputs(got["t"], got["x"], got["phase"], p)
    assert got["x"].shape == ref["x"].shape
    err_x = np.max(np.abs(got["x"] - ref["x"]) / np.maximum(np.abs(ref["x"]).max(axis=1, keepdims=True), 1e-300))
    err_y = np.max(np.abs(y - y_ref) / np.maximum(np.abs(y_ref).max(axis=1, keepdims=True), 1e-300))
    print(f"slot model, compiled vs VM: states {err_x:.1e}, outputs {err_y:.1e} (max relative; tolerance 1e-9)")
    assert err_x < 1e-9 and err_y < 1e-9


def test_cached_model_flies_bit_identically(tmp_path, monkeypatch):
    """The second build loads the stored Functions and grid; the flight is the same to the bit."""
    from ironbark_opt.dynamics import model_cache
    monkeypatch.setenv("IRONBARK_CACHE_DIR", str(tmp_path))
    setup = load_setup(ROOT / "examples/calisto/calisto.toml")
    built = FlightModel(setup)
    key = model_cache.model_key(setup, built.steps)
    assert model_cache.load(key) is not None
    loaded = FlightModel(setup)
    assert loaded.discretisation() == built.discretisation()
    p = setup.nominal_parameters(ballast_mass=0.3)
    a, b = built.run(p), loaded.run(p)
    assert np.array_equal(a["x"], b["x"]) and a["t_apogee"] == b["t_apogee"]
    # one function names every compiled library: the same model and names, the same key
    assert loaded._library_key() == built._library_key() == model_cache.library_key(built)
    names = ((), ("ballast_nlp_000",), ("robust_ascent_1",), (False, "robust_events_rail"))
    assert len({model_cache.library_key(built, *n) for n in names}) == len(names)
    other = load_setup(ROOT / "examples/calisto/calisto.toml", rail_exit="aft_button")
    assert model_cache.model_key(other, built.steps) != key         # another setup, another key


def test_batch_columns_equal_single_runs(tmp_path, monkeypatch):
    """run_batch (only the numbers it needs leave CasADi) flies each column as run() does;
    they differ only by the rail-exit secant's round-off (its iteration count differs
    between one sample and a batch; 6e-12 m at the starting commit too)."""
    monkeypatch.setenv("IRONBARK_CACHE_DIR", str(tmp_path))
    setup = load_setup(ROOT / "examples/calisto/calisto.toml")
    model = FlightModel(setup)
    P = np.column_stack([setup.nominal_parameters(ballast_mass=m, drag_scale=d)
                         for m, d in ((0.0, 1.0), (0.8, 1.05), (2.0, 0.95))])
    batch = model.run_batch(P)
    worst = 0.0
    for j in range(P.shape[1]):
        one = model.run(P[:, j])
        worst = max(worst, abs(batch["t_apogee"][j] - one["t_apogee"]) / one["t_apogee"],
                    float(np.max(np.abs(batch["x_apogee"][:, j] - one["x_apogee"]))) / one["x_apogee"][2])
    print(f"apogees {batch['apogee_agl']} m: batch vs single runs {worst:.1e} relative (tolerance 1e-12)")
    assert worst < 1e-12


@pytest.mark.skipif(not compiler_available(), reason="no C compiler on this machine")
def test_compile_flags_keep_the_numbers_of_plain_o2(tmp_path, monkeypatch):
    """integrator.CFLAGS (inlining, -O3) change no floating-point semantics: Calisto's
    compiled coast step (atmosphere, Mach table, aerodynamics) gives -O2's numbers to the bit."""
    from ironbark_opt.dynamics import integrator
    setup = load_setup(ROOT / "examples/calisto/calisto.toml")
    step = FlightModel(setup)._library_twin().step["coast"]
    rng = np.random.default_rng(7)
    n = 200
    x = np.vstack([rng.uniform(-50, 50, (2, n)), rng.uniform(0, 3000, (1, n)), rng.uniform(-20, 20, (2, n)),
                   rng.uniform(50, 300, (1, n)), rng.normal(size=(4, n)), rng.normal(scale=0.5, size=(3, n))])
    x[6:10] /= np.linalg.norm(x[6:10], axis=0)
    t, dt = rng.uniform(4, 20, (1, n)), rng.uniform(0.01, 0.1, (1, n))
    p = np.repeat(setup.nominal_parameters()[:, None], n, axis=1)
    out = {}
    for flags in (integrator.CFLAGS, integrator.FALLBACK_CFLAGS):
        monkeypatch.setattr(integrator, "CFLAGS", flags)
        lib = compile_function(step, tmp_path / "-".join(flags))
        assert lib is not step
        out[flags] = np.array(lib.map(n)(x, t, dt, p))
    a, b = out.values()
    assert np.all(np.isfinite(a))
    assert np.array_equal(a, b)


@pytest.mark.skipif(not compiler_available(), reason="no C compiler on this machine")
def test_a_compiler_refusing_the_flags_compiles_with_o2(tmp_path, monkeypatch):
    import shutil

    import casadi as ca

    from ironbark_opt.dynamics.integrator import CFLAGS, _compiler
    cc = tmp_path / "cc"
    log = tmp_path / "calls"
    cc.write_text(f'#!/bin/sh\necho "$*" >> {log}\ncase "$*" in *{CFLAGS[-1]}*) exit 1;; esac\n'
                  f'exec {shutil.which(_compiler())} "$@"\n')
    cc.chmod(0o755)
    monkeypatch.setenv("CC", str(cc))
    x = ca.SX.sym("x")
    f = ca.Function("cube_fallback", [x], [x * x * x])
    lib = compile_function(f, tmp_path / "jit")
    assert lib is not f and float(lib(3.0)) == 27.0
    calls = log.read_text().splitlines()
    assert len(calls) == 2 and CFLAGS[-1] in calls[0] and calls[1].startswith("-O2 ")


def test_batch_numbers_do_not_depend_on_the_thread_count(tmp_path, monkeypatch):
    """batch.map_threads picks the thread map's thread count from the processors; each
    sample is its own evaluation, so 1 thread and 4 threads give the same numbers to the
    bit (24 dispersed Calisto samples through the ascent Function)."""
    from ironbark_opt.analysis.distributions import load_spec
    from ironbark_opt.dynamics import batch as batch_mod
    monkeypatch.setenv("IRONBARK_CACHE_DIR", str(tmp_path))
    setup = load_setup(ROOT / "examples/calisto/calisto.toml")
    spec = load_spec(ROOT / "examples/calisto/dispersions.toml")
    P = spec.sample(24, setup.nominal_parameters(), np.random.default_rng(7))
    real = batch_mod.map_threads
    assert 2 <= real(250) <= 2 * (os.cpu_count() or 1)
    assert real(1) == 1 and real(10) == 2
    out = {}
    for threads in (1, 4):
        monkeypatch.setattr(batch_mod, "map_threads", lambda n, k=threads: k)
        model = FlightModel(setup)
        out[threads] = model.run_batch(P)
        assert ("ascent_batch", 24) in model._map_cache
    for key in ("apogee_agl", "t_apogee", "t_rail", "x_apogee"):
        assert np.array_equal(out[1][key], out[4][key])
