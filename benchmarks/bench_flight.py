"""Speed of the flight core on the bundled Calisto example.

Prints: milliseconds per trajectory to apogee (interpreted CasADi VM and
C-compiled, the latter also against the operation-count limit of issue 16),
trajectories per second for a batch of 1,000 (the trajectory
Functions mapped over parameter samples), and — when the optional peer
``rocketpy`` is installed (``pip install -e .[bench]``) — RocketPy's time for
the same Calisto flight and the ratio, measured in the same run.

Run: ``python benchmarks/bench_flight.py [--repeat N] [--batch N]``.
Figures are medians; the machine's other load shows in them.
"""
from __future__ import annotations

import argparse
import statistics
import sys
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from ironbark_opt import params  # noqa: E402
from ironbark_opt.dynamics.integrator import compiler_available  # noqa: E402
from ironbark_opt.flight import flight_model  # noqa: E402
from ironbark_opt.vehicle import load_setup  # noqa: E402

EXAMPLE = ROOT / "examples" / "calisto" / "calisto.toml"
from bench_commands import FLOPS_LIMIT_S  # noqa: E402  (one definition of the issue-16 limit)


def median_time(func, repeat: int) -> float:
    func()                                   # warm-up
    times = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        func()
        times.append(time.perf_counter() - t0)
    return statistics.median(times)


def batch_rate(model, p0, n: int) -> float:
    """Trajectories per second for ``n`` dispersed samples through ``run_batch``
    (the phase Functions mapped over the samples, events vectorised)."""
    rng = np.random.default_rng(1)
    P = np.repeat(p0[:, None], n, axis=1)
    P[params.index("thrust_scale")] *= 1 + 0.02 * rng.standard_normal(n)
    P[params.index("drag_scale")] *= 1 + 0.05 * rng.standard_normal(n)
    model.run_batch(P[:, :2])                      # warm-up: maps built
    t0 = time.perf_counter()
    model.run_batch(P)
    return n / (time.perf_counter() - t0)


def rocketpy_time(repeat: int):
    """Median seconds of one RocketPy Calisto Flight to apogee, or None."""
    try:
        import rocketpy  # noqa: F401
    except ImportError:
        return None
    from rocketpy_calisto import build, fly
    env, rocket = build()
    return median_time(lambda: fly(env, rocket), max(3, repeat // 10))


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeat", type=int, default=30)
    ap.add_argument("--batch", type=int, default=1000)
    args = ap.parse_args()
    setup = load_setup(EXAMPLE)
    p0 = setup.nominal_parameters()

    t0 = time.perf_counter()
    vm = flight_model(setup, jit=False)
    build_vm = time.perf_counter() - t0
    t_vm = median_time(lambda: vm.run(p0), args.repeat)
    print(f"model build (VM):                {1e3 * build_vm:8.1f} ms")
    print(f"trajectory to apogee, VM:        {1e3 * t_vm:8.2f} ms   (goal < 10 ms)")
    t_jit = None
    if compiler_available():
        t0 = time.perf_counter()
        jit = flight_model(setup, jit=True)
        build_jit = time.perf_counter() - t0
        t_jit = median_time(lambda: jit.run(p0), args.repeat)
        print(f"model build (JIT, cache-aware): {1e3 * build_jit:8.1f} ms")
        print(f"trajectory to apogee, compiled:  {1e3 * t_jit:8.2f} ms   (goal < 2 ms; "
              f"{t_jit / FLOPS_LIMIT_S:.1f}x the operation-count limit {1e3 * FLOPS_LIMIT_S:.1f} ms, goal <= 3x)")
    else:
        print("trajectory to apogee, compiled:  no C compiler found")
    model = jit if t_jit is not None else vm
    rate = batch_rate(model, p0, args.batch)
    print(f"batch of {args.batch}, mapped:         {rate:8.0f} trajectories/s")
    t_peer = rocketpy_time(args.repeat)
    if t_peer is None:
        print("rocketpy: not installed (pip install -e .[bench]) - no peer ratio")
    else:
        best = t_jit or t_vm
        print(f"rocketpy Flight to apogee:       {1e3 * t_peer:8.1f} ms")
        print(f"ratio rocketpy / ironbark:       {t_peer / best:8.0f}x  (goal >= 300x, issue 16)")


if __name__ == "__main__":
    main()
