"""Fixed-step RK4 as a CasADi Function, applied N times with ``mapaccum``.

The final time of a phase is an *input* (``dt = (t_end - t_start) / N``), so
event times (rail exit, apogee) can be roots and optimisation variables.
Optional compilation to C with an on-disk cache keyed by the generated
code's hash (:func:`compile_function`).
"""
from __future__ import annotations

import hashlib
import os
import shutil
import subprocess
import tempfile
from pathlib import Path

import casadi as ca
import numpy as np


def _splitting(rhs: ca.Function, p):
    """``(f, damp, split)`` of :func:`rk4_step` for ``rhs`` and parameters ``p``: the
    right-hand side without the roll equation's damping and forcing terms, and that
    linear roll equation advanced exactly over ``h`` (coefficients frozen)."""
    nx = rhs.size1_in(0)
    split = "c_roll" in rhs.name_out()          # with it, rhs.build gives f_roll too
    if split:
        e = ca.DM.zeros(nx)
        e[10] = 1

        def f(xx, tt):
            out = rhs(xx, tt, p)
            return out[0] - e * (out[2] * xx[10] + out[3])

        def damp(xx, tt, h):
            out = rhs(xx, tt, p)
            z = out[2] * h
            # w(h) - w(0) = h phi1(z) (c w + f), phi1(z) = (e^z - 1)/z (z <= 0; series near 0)
            phi1 = ca.if_else(ca.fabs(z) < 1e-6, 1 + z / 2, ca.expm1(z) / ca.if_else(z == 0, 1, z))
            return xx + e * h * phi1 * (out[2] * xx[10] + out[3])
    else:
        def f(xx, tt):
            return rhs(xx, tt, p)[0]

        def damp(xx, tt, h):
            return xx
    return f, damp, split


def _rk4_undamped_end(f, damp, x, t, dt):
    """:func:`rk4_step` from ``x`` up to (not including) its closing half step of damping."""
    x0 = damp(x, t, dt / 2)
    k1 = f(x0, t)
    k2 = f(x0 + dt / 2 * k1, t + dt / 2)
    k3 = f(x0 + dt / 2 * k2, t + dt / 2)
    k4 = f(x0 + dt * k3, t + dt)
    return x0 + dt / 6 * (k1 + 2 * k2 + 2 * k3 + k4)


def rk4_step(rhs: ca.Function, name: str = "rk4") -> ca.Function:
    """One step ``(x, t, dt, p) -> x_next``: classical 4th-order Runge–Kutta,
    with the roll channel's damping and forcing split off and advanced exactly.

    Parameters
    ----------
    rhs : casadi.Function
        ``(x, t, p) -> (xdot, ...)``; if it has outputs ``c_roll`` [1/s] (the
        roll-damping part of d(dw_x/dt)/dw_x, w_x = x[10]) and ``f_roll``
        [rad/s^2] (the roll forcing of canted fins), the linear roll equation
        ``dw_x/dt = c_roll w_x + f_roll`` is integrated by Strang splitting: half
        a step of its exact solution (coefficients frozen), ``w_x -> w_eq + (w_x -
        w_eq) exp(c_roll h/2)``, ``w_eq = -f_roll / c_roll``, an RK4 step of the
        remaining dynamics, another exact half step (Strang, SIAM J. Numer. Anal.
        5, 1968).  Roll damping is the stiffest mode of light rockets with large
        fins (c_roll ~ -170 1/s at burnout on the Kestrel example), which would
        otherwise limit RK4 to steps under ~0.015 s.  The forcing goes with the
        damping: split from the damping alone it would drive the RK4 stages'
        roll rate without the damping that balances it (measured: canted fins
        1.5 deg on the Kestrel example at |c_roll| dt ~ 5 gave stage roll rates of
        ~65 rad/s against an equilibrium of 12, a roll rate off by a third in
        boost, and pitch-yaw coupling that diverged in the first coast steps);
        split together, the scheme keeps the roll equilibrium exactly.  Second-
        order accurate in the roll channel; every other channel's RK4 is
        unchanged when the roll rate and forcing are zero.
    """
    nx = rhs.size1_in(0)
    np_ = rhs.size1_in(2)
    sym = ca.SX if rhs.is_a("SXFunction") else ca.MX
    x = sym.sym("x", nx)
    t = sym.sym("t")
    dt = sym.sym("dt")
    p = sym.sym("p", np_)
    f, damp, _ = _splitting(rhs, p)
    x_next = damp(_rk4_undamped_end(f, damp, x, t, dt), t + dt, dt / 2)
    if sym is ca.SX:
        # k2 and k3 share the time t + dt/2, and the damping coefficient at the
        # step's start shares the air data of k1: evaluated once.
        x_next = ca.cse(x_next)
    return ca.Function(name, [x, t, dt, p], [x_next], ["x", "t", "dt", "p"], ["x_next"])


def carries_damping(rhs) -> bool:
    """Whether :func:`phase_trajectory` given ``rhs`` flies the steps in the carried form
    (an SX right-hand side with a roll-damping output)."""
    return rhs is not None and rhs.is_a("SXFunction") and "c_roll" in rhs.name_out()


def carried_steps(rhs: ca.Function, name: str) -> tuple[ca.Function, ca.Function]:
    """The RK4 steps of :func:`rk4_step` regrouped so that a step boundary's air data
    are evaluated once, not twice (an SX ``rhs`` with ``c_roll``):

    - ``body(x_pre, f0_prev, df_prev, f0, df, t0, span, p) -> (x_pre_next, x_prev)``:
      the closing half step of damping of the previous step (grid fractions
      ``f0_prev, df_prev`` of the phase ``[t0, t0 + span]``), which gives that step's
      state ``x_prev``, then this step (``f0, df``) up to its own closing half step,
      ``x_pre_next``;
    - ``close(x_pre, f0, df, t0, span, p) -> x``: the closing half step alone (the
      phase's last step).

    The closing half step evaluates ``c_roll`` at the step's end state before
    damping, the next step's opening half step and its ``k1`` at the state after
    it; the two differ only in the roll rate, on which the air data (altitude,
    air-relative velocity, Mach tables) do not depend, so in one SX expression
    common-subexpression elimination evaluates them once: 4 evaluations of the air
    data a step instead of 5.  Every operation is the one :func:`rk4_step` does on
    the same operands (a first step's ``df_prev = 0`` damps by ``h = 0``,
    the state as it is), so a trajectory is the same to the bit."""
    nx, np_ = rhs.size1_in(0), rhs.size1_in(2)
    x = ca.SX.sym("x", nx)
    f0p, dfp, f0, df, t0, span = (ca.SX.sym(s) for s in ("f0_prev", "df_prev", "f0", "df", "t0", "span"))
    p = ca.SX.sym("p", np_)
    f, damp, _ = _splitting(rhs, p)

    def closed(xx, f0_, df_):
        t, dt = t0 + span * f0_, span * df_
        return damp(xx, t + dt, dt / 2)
    x_prev = closed(x, f0p, dfp)
    x_pre = _rk4_undamped_end(f, damp, x_prev, t0 + span * f0, span * df)
    x_pre, x_prev = ca.cse([x_pre, x_prev])
    body = ca.Function(f"{name}_body", [x, f0p, dfp, f0, df, t0, span, p], [x_pre, x_prev])
    close = ca.Function(f"{name}_close", [x, f0, df, t0, span, p], [ca.cse(closed(x, f0, df))])
    return body, close


def carried_trajectory(rhs: ca.Function, name: str, x0, starts, lengths, t0, span, p):
    """States (nx x n, MX) after each of the n steps of :func:`carried_steps` from ``x0``
    on the grid fractions ``starts``, ``lengths`` (1 x n, DM or MX) of ``[t0, t0 + span]``:
    the same numbers as n :func:`rk4_step` steps (an SX ``rhs``; without ``c_roll`` the
    damping is the identity and the body the plain step)."""
    n = starts.shape[1]
    body, close = carried_steps(rhs, name)
    acc = body.mapaccum(f"{name}_acc", n)
    prev_starts = ca.horzcat(starts[:, 0], starts[:, :n - 1])
    prev_lengths = ca.horzcat(ca.DM.zeros(1, 1), lengths[:, :n - 1])
    rep = ca.repmat
    X_pre, X_prev = acc(x0, prev_starts, prev_lengths, starts, lengths, rep(t0, 1, n), rep(span, 1, n),
                        rep(p, 1, n))
    last = close(X_pre[:, n - 1], starts[:, n - 1], lengths[:, n - 1], t0, span, p)
    return ca.horzcat(X_prev[:, 1:], last)


def grid_fractions(n_steps: int, grading: float = 1.0) -> np.ndarray:
    """Step boundaries as fractions of a phase, ``g(s) = a s + (1 - a) s^2`` at
    ``s = k / n`` (``a = grading``; 1 is a uniform grid, smaller values put
    finer steps at the start, where the flight is stiffest)."""
    if not 0.0 < grading <= 1.0:
        raise ValueError(f"grading must be in (0, 1], got {grading}")
    s = np.arange(n_steps + 1) / n_steps
    return grading * s + (1.0 - grading) * s * s


def padded_grid(n_steps: int, capacity: int, grading: float = 1.0) -> np.ndarray:
    """The grid of :func:`grid_fractions` as ``phase_trajectory(..., grid_offset=)``
    reads it from ``p``: ``capacity`` step starts then ``capacity`` step lengths,
    the steps after the ``n_steps``-th of length 0 (at the phase's end)."""
    if n_steps > capacity:
        raise ValueError(f"{n_steps} steps do not fit a grid of {capacity}")
    fr = grid_fractions(n_steps, grading)
    starts = np.full(capacity, fr[-1])
    lengths = np.zeros(capacity)
    starts[:n_steps], lengths[:n_steps] = fr[:-1], np.diff(fr)
    return np.concatenate([starts, lengths])


def phase_trajectory(step: ca.Function, n_steps: int, name: str, grading: float = 1.0,
                     grid_offset: int | None = None, rhs: ca.Function | None = None) -> ca.Function:
    """``(x0, t0, t1, p) -> X`` with X (nx x n_steps) the states after each step.

    ``n_steps`` RK4 steps over ``[t0, t1]`` on the grid of
    :func:`grid_fractions` (uniform for ``grading = 1``), built with
    ``Function.mapaccum`` (one call node, linear memory, fast VM).  The final
    time is an input, so events and optimisers can move it.

    ``grid_offset``: the grid is read from ``p`` instead, step starts
    ``p[o:o+n]`` and lengths ``p[o+n:o+2n]`` as fractions of the phase
    (:func:`padded_grid`); steps of length 0 leave the state exactly as it is,
    so one Function flies any grid of up to ``n_steps`` steps.

    ``rhs``: the right-hand side ``step`` was made of (:func:`rk4_step`); where it
    has a roll-damping output (:func:`carries_damping`) the steps are flown as
    :func:`carried_trajectory` (the same numbers, ~1/5 fewer air-data evaluations).
    """
    if carries_damping(rhs) and grid_offset is None:
        fr = grid_fractions(n_steps, grading)
        x0, t0, t1, p = ca.MX.sym("x0", step.size1_in(0)), ca.MX.sym("t0"), ca.MX.sym("t1"), ca.MX.sym("p", step.size1_in(3))
        X = carried_trajectory(rhs, name, x0, ca.DM(fr[:-1]).T, ca.DM(np.diff(fr)).T, t0, t1 - t0, p)
        return ca.Function(name, [x0, t0, t1, p], [X], ["x0", "t0", "t1", "p"], ["X"])
    nx = step.size1_in(0)
    np_ = step.size1_in(3)
    x = ca.SX.sym("x", nx)
    f0 = ca.SX.sym("f0")
    df = ca.SX.sym("df")
    t0 = ca.SX.sym("t0")
    span = ca.SX.sym("span")
    if grid_offset is None:
        p = ca.SX.sym("p", np_)
        p_step = p
    else:                   # the grid entries of p are not the step's: not copied to every step
        p = ca.SX.sym("p", grid_offset)
        p_step = ca.vertcat(p, ca.SX.zeros(np_ - grid_offset))
    body = ca.Function(f"{name}_body", [x, f0, df, t0, span, p], [step(x, t0 + span * f0, span * df, p_step)])
    acc = body.mapaccum(f"{name}_acc", n_steps)
    x0 = ca.MX.sym("x0", nx)
    t0m = ca.MX.sym("t0")
    t1m = ca.MX.sym("t1")
    pm = ca.MX.sym("p", np_)
    rep = ca.repmat
    if grid_offset is None:
        fr = grid_fractions(n_steps, grading)
        starts, lengths = ca.DM(fr[:-1]).T, ca.DM(np.diff(fr)).T
    else:
        starts = pm[grid_offset:grid_offset + n_steps].T
        lengths = pm[grid_offset + n_steps:grid_offset + 2 * n_steps].T
    p_body = pm if grid_offset is None else pm[:grid_offset]
    states = acc(x0, starts, lengths, rep(t0m, 1, n_steps), rep(t1m - t0m, 1, n_steps), rep(p_body, 1, n_steps))
    return ca.Function(name, [x0, t0m, t1m, pm], [states], ["x0", "t0", "t1", "p"], ["X"])


# ----------------------------------------------------------------------------- JIT
def cache_root() -> Path:
    """``$IRONBARK_CACHE_DIR`` or ``~/.cache/ironbark`` (``$XDG_CACHE_HOME``)."""
    base = os.environ.get("IRONBARK_CACHE_DIR")
    return Path(base) if base else Path(os.environ.get("XDG_CACHE_HOME", Path.home() / ".cache")) / "ironbark"


def default_cache_dir() -> Path:
    """Where compiled functions are kept: ``$IRONBARK_CACHE_DIR/jit`` or ~/.cache."""
    return cache_root() / "jit"


def jit_mode(jit) -> bool | str:
    """Normalise a ``jit`` argument: ``True`` (compile now), ``False`` (VM) or ``"auto"``.

    ``"auto"`` (the default of ``simulate``, Monte Carlo and the CLI) uses a compiled
    library when the cache has it and otherwise the VM, compiling in a detached
    background process for the next run, so a first run is never slower than the
    VM.  The environment variable ``IRONBARK_JIT`` overrides ``"auto"``: ``vm``
    (never compile; the test suite sets it), ``always`` (compile now).
    """
    if jit is None or (isinstance(jit, str) and jit == "auto"):
        env = os.environ.get("IRONBARK_JIT", "auto").lower()
        return {"vm": False, "0": False, "always": True, "1": True}.get(env, "auto")
    if isinstance(jit, str):
        raise ValueError(f"jit must be True, False or 'auto', got {jit!r}")
    return bool(jit)


#: C compiler flags of the compiled Functions.  ``-fno-semantic-interposition`` lets the
#: compiler inline CasADi's runtime helpers (``casadi_sq``, ``casadi_low``,
#: ``casadi_interpn``, ``casadi_copy``...), which a shared library otherwise calls
#: through the PLT; ``-O3`` adds loop and inlining passes over the generated code.
#: Neither changes floating-point semantics (no ``-ffast-math``): compiled flights are
#: bit-identical to ``-O2``'s (1000 Calisto Monte Carlo samples, to landing) and take
#: ~13 % less CPU (compiled Calisto ascent: 3.78e6 -> 3.09e6 instructions, callgrind);
#: the compile itself takes ~1.5x longer (once per rocket, in the background).
CFLAGS = ("-O3", "-fno-semantic-interposition")
#: flags for a compiler that refuses :data:`CFLAGS`
FALLBACK_CFLAGS = ("-O2",)


def compiler_available() -> bool:
    """True when a C compiler (``$CC`` or gcc/cc) is on PATH."""
    return _compiler() is not None


def _compiler() -> str | None:
    for cc in (os.environ.get("CC"), "gcc", "cc", "clang"):
        if cc and shutil.which(cc):
            return shutil.which(cc)
    return None


def cached_library(name: str, key: str, cache_dir: Path | None = None) -> ca.Function | None:
    """The compiled Function ``name`` stored under ``key`` by :func:`compile_function`,
    or None (not compiled yet, or no C compiler to have made it)."""
    lib = (Path(cache_dir) if cache_dir else default_cache_dir()) / f"{name}_{key}.so"
    if _compiler() is None or not lib.exists():
        return None
    from ironbark_opt.dynamics.cache_limit import touch
    touch(lib)                                     # used now: the last the size limit deletes
    return ca.external(name, str(lib))


def library_member(name: str, library: str, key: str, cache_dir: Path | None = None) -> ca.Function:
    """Function ``name`` of the library that :func:`compile_function` stored for the
    Function ``library`` under ``key`` (one generated with it through ``extra``)."""
    return ca.external(name, str((Path(cache_dir) if cache_dir else default_cache_dir()) / f"{library}_{key}.so"))


def compile_function(func: ca.Function, cache_dir: Path | None = None, *, key: str | None = None,
                     background: bool = False, extra=None) -> ca.Function:
    """C-compiled copy of ``func`` loaded with ``casadi.external``.

    Without ``key`` the generated C source is hashed (SHA-256) and the shared
    library is kept in ``cache_dir`` under that hash, so the second run (same
    model, same tables) loads it instead of paying the compile again.  With
    ``key`` (a digest of everything ``func`` depends on, see
    :mod:`~ironbark_opt.dynamics.model_cache`) the library is named by it and a
    cached one is loaded without generating code at all.

    ``background``: when the library is not cached yet, start the compiler in a
    detached process (:func:`_compile_detached`: it outlives this one, starts once
    this one has exited, and renames its output into place atomically; within the
    machine-wide cap on background compiles, and without a free slot it gives up
    and the next call starts it again) and return ``func`` itself, the VM,
    meanwhile.  Falls back to ``func`` when no compiler exists or compiling fails.

    ``extra``: a callable returning more Functions generated into the same
    library (called only when code is generated), e.g. the Jacobian
    named ``jac_<name>`` that ``casadi.external`` finds, so a solver
    differentiating the loaded function runs compiled derivatives too (the
    ballast NLP).
    """
    cc = _compiler()
    if cc is None:
        return func
    cache = Path(cache_dir) if cache_dir else default_cache_dir()
    if key is not None:
        found = cached_library(func.name(), key, cache)
        if found is not None:
            return found
        lib = cache / f"{func.name()}_{key}.so"
    cache.mkdir(parents=True, exist_ok=True)
    with tempfile.TemporaryDirectory() as tmp:
        cname = f"{func.name()}.c"
        gen = ca.CodeGenerator(cname, {"with_header": False})
        gen.add(func)
        for f in (extra() if extra is not None else ()):
            gen.add(f)
        src_path = Path(tmp) / cname
        gen.generate(str(Path(tmp)) + os.sep)
        if key is None:
            digest = hashlib.sha256(src_path.read_bytes() + ca.__version__.encode()).hexdigest()[:20]
            lib = cache / f"{func.name()}_{digest}.so"
        if lib.exists():
            return ca.external(func.name(), str(lib))
        if background:
            _compile_detached(cc, src_path, lib)
            return func
        tmp_lib = Path(tmp) / lib.name
        if not _run_compiler(cc, src_path, tmp_lib):
            return func
        staged = cache / f".{lib.name}.{os.getpid()}.tmp"
        shutil.copyfile(tmp_lib, staged)
        os.replace(staged, lib)          # atomic: never a half-written library
    return ca.external(func.name(), str(lib))


#: a background compile whose source is younger than this is taken as still running [s]
_PENDING_S = 600.0
#: A detached compile runs in its own session, and Linux with autogroup scheduling
#: (``/proc/sys/kernel/sched_autogroup_enabled``) shares the CPU between sessions, not
#: processes, so ``nice`` alone does not make it yield: its session's group gets nice 19
#: too (``/proc/self/autogroup``, sched(7)).  Without it a first run that starts a
#: compile measured 1.4-1.8x the VM path's wall time on a loaded machine.
#: The shell sets it (the group is the session's, so the Python or compiler it then
#: execs keeps it): once, before anything else of the child runs.
_LOWEST_GROUP_SH = "(echo 19 > /proc/self/autogroup) 2>/dev/null; "
#: A detached compile starts only once the process that asked for it has exited (at
#: most this long after [s]): the library is for the next run, and a compile running
#: beside the run that asked (on the other core, or on a busy machine's shared cores)
#: would slow it down whatever its priority.  A long-running process (a notebook, a
#: study) still gets its library after this wait.
AFTER_PARENT_MAX_S = 60.0


def _after_parent_sh() -> str:
    """Shell prefix that waits until this process has exited (or ``AFTER_PARENT_MAX_S``)."""
    ticks = int(AFTER_PARENT_MAX_S * 10)
    return (f"i=0; while [ $i -lt {ticks} ] && kill -0 {os.getpid()} 2>/dev/null; "
            "do sleep 0.1; i=$((i+1)); done; ")


def _run_compiler(cc: str, src: Path, out: Path) -> bool:
    """Compile the C file ``src`` to the shared library ``out`` with :data:`CFLAGS`, or
    :data:`FALLBACK_CFLAGS` if the compiler refuses them; True when it succeeded."""
    for flags in (CFLAGS, FALLBACK_CFLAGS):
        cmd = [cc, *flags, "-shared", "-fPIC", str(src), "-o", str(out), "-lm"]
        if subprocess.run(cmd, capture_output=True, text=True).returncode == 0:
            return True
    return False


def _compile_detached(cc: str, src: Path, lib: Path) -> None:
    """Compile ``src`` to ``lib`` in a detached, lowest-priority process (:func:`run_detached`:
    after this process exits, within the machine-wide cap on background compiles), at
    most one per library: its source is copied to the marker ``.<lib stem>.c``, and a
    marker younger than ``_PENDING_S`` means a compile is already under way."""
    pending = lib.with_name(f".{lib.stem}.c")
    if not _claim(pending):
        return
    try:
        shutil.copyfile(src, pending)
    except OSError:
        pending.unlink(missing_ok=True)
        return
    run_detached("ironbark_opt.dynamics.integrator:_compile_source", [cc, str(pending), str(lib)], [pending])


def _compile_source(cc: str, src: str, lib: str) -> None:
    """:func:`_compile_detached`'s child: compile ``src`` next to ``lib`` and rename the
    result into place (atomic: never a half-written library); a failure leaves nothing."""
    lib = Path(lib)
    staged = lib.with_name(f".{lib.name}.{os.getpid()}.tmp")
    try:
        if _run_compiler(cc, Path(src), staged):
            os.replace(staged, lib)
    finally:
        staged.unlink(missing_ok=True)


def _claim(pending: Path) -> bool:
    """Write the marker ``pending`` of a background compile unless a young one exists
    (at most one compile per library at a time; benchmarks wait for the markers)."""
    import time
    try:
        pending.parent.mkdir(parents=True, exist_ok=True)
        if pending.exists() and time.time() - pending.stat().st_mtime < _PENDING_S:
            return False
        pending.write_text("pending\n")
        return True
    except OSError:
        return False


def run_detached(target: str, args: list[str], cleanup: list[Path]) -> None:
    """Call ``target`` (``"module:function"``, a background compile) with ``args``
    (strings) in a detached Python process at the lowest priority (own session,
    ``nice``, its autogroup at nice 19), which outlives this one and starts only once
    this one has exited (at most ``AFTER_PARENT_MAX_S`` later).  It deletes the files
    ``cleanup`` (the compile's marker, written by the caller with :func:`_claim`, and
    its inputs) when done, whatever happens; if it cannot start they are deleted here.

    Machine-wide cap (:mod:`~ironbark_opt.dynamics.compile_slots`): the child first
    takes one of ``IRONBARK_MAX_BACKGROUND_COMPILES`` (default: the processors) slots,
    before importing anything heavy, and holds it until it exits; when every slot is
    held it gives up at once without calling ``target`` (this run keeps the VM, the
    next run of the rocket starts another compile).  Nothing waits for a slot, least
    of all this process.  ``IRONBARK_MAX_BACKGROUND_COMPILES=0``: no child at all;
    a value that is not an integer >= 0 raises
    :class:`~ironbark_opt.errors.InputError` (the files ``cleanup`` deleted first).
    """
    import sys

    from ironbark_opt.dynamics.compile_slots import max_background_compiles
    try:
        n_slots = max_background_compiles()
    except ValueError:
        _unlink_all(cleanup)
        raise
    if n_slots == 0:
        _unlink_all(cleanup)
        return
    script = ("import sys, os, importlib\n"
              "n = int(sys.argv[2])\n"
              "files, args = sys.argv[3:3 + n], sys.argv[3 + n:]\n"
              "mod, name = sys.argv[1].split(':')\n"
              "try:\n"
              "    from ironbark_opt.dynamics.compile_slots import compile_slot\n"
              "    with compile_slot() as free:\n"
              "        if free:\n"
              "            getattr(importlib.import_module(mod), name)(*args)\n"
              "finally:\n"
              "    for path in files:\n"
              "        try: os.unlink(path)\n"
              "        except OSError: pass\n")
    nice = shutil.which("nice")
    # the shell moves the session's group to nice 19 before Python starts (its start-up,
    # ~40 ms, would otherwise share the CPU equally with the process that asked)
    cmd = ([nice, "-n", "10"] if nice else []) + ["sh", "-c", _LOWEST_GROUP_SH + _after_parent_sh() + 'exec "$0" "$@"',
                                                   sys.executable, "-c", script, target, str(len(cleanup)),
                                                   *map(str, cleanup), *args]
    try:
        subprocess.Popen(cmd, stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
                         start_new_session=True, close_fds=True)
    except OSError:
        _unlink_all(cleanup)


def _unlink_all(paths) -> None:
    for path in paths:
        Path(path).unlink(missing_ok=True)


def compile_detached(func: ca.Function, key: str, extra: str | None = None) -> None:
    """Generate and compile ``func`` (as :func:`compile_function` with ``key``) in a
    detached, low-priority Python process (:func:`run_detached`), so this process pays
    only for saving the Function, not for generating its C code (the ballast NLP: ~0.5 s).

    ``extra``: ``"module:function"``, called there with ``func`` to give the
    Function(s) generated into the same library (e.g. its Jacobian).  At most one
    such compile per library runs, within the machine-wide cap of :func:`run_detached`
    (no free slot: it gives up, and the next call starts another); a missing
    compiler or a failure only means the VM stays in use.
    """
    if _compiler() is None:
        return
    lib = default_cache_dir() / f"{func.name()}_{key}.so"
    pending = lib.with_name(f".{lib.stem}.c")          # the marker background compiles leave (benchmarks wait)
    if lib.exists() or not _claim(pending):
        return
    saved = lib.with_name(f".{lib.stem}.casadi")
    try:
        func.save(str(saved))
    except (OSError, RuntimeError):
        pending.unlink(missing_ok=True)
        return
    run_detached("ironbark_opt.dynamics.integrator:_compile_saved", [str(saved), key, extra or ""],
                 [saved, pending])


def _compile_saved(saved: str, key: str, extra: str = "") -> None:
    """:func:`compile_detached`'s child: load the saved Function and compile it."""
    import importlib
    f = ca.Function.load(saved)
    build = None
    if extra:
        mod, name = extra.split(":")
        fn = getattr(importlib.import_module(mod), name)

        def build():
            return (fn(f),)
    compile_function(f, key=key, extra=build)
