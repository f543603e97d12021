"""Robust ballast solve time against one nominal ballast solve, measured in the same run.

For Calisto (target 3000 m AGL) and Kestrel (10,000 ft AGL) with their example
dispersion specs: one nominal ``solve_ballast`` (warm: model built, libraries
loaded), then ``solve_robust_ballast`` with the default 40 SAA samples and no
check (the robust solve includes its own nominal solve, the starting point, and
the validation of the SAA optimum on 200 fresh samples per ballast).  Both
warm figures are the best of ``--repeat`` runs (default 3) with the compiled
libraries: ``IRONBARK_JIT=always`` (unless set otherwise) builds them in the
foreground on the first calls, whose times are printed too.  Wall and CPU
seconds (the mapped flights run on 2 threads).  Goal: robust <= 10 x nominal.

Run: ``python benchmarks/bench_robust_ballast.py [--samples 40] [--repeat 3] [rocket ...]``.
"""
from __future__ import annotations

import argparse
import os
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))
os.environ.setdefault("IRONBARK_JIT", "always")

from ironbark_opt.optimise.ballast import solve_ballast  # noqa: E402
from ironbark_opt.optimise.robust import solve_robust_ballast  # noqa: E402
from ironbark_opt.vehicle import load_setup  # noqa: E402

CASES = {"calisto": "3000m", "kestrel": "10000ft"}


def timed(fn):
    """(result, wall [s], cpu [s]) of ``fn()``."""
    t0, c0 = time.perf_counter(), time.process_time()
    out = fn()
    return out, time.perf_counter() - t0, time.process_time() - c0


def best(fn, repeat):
    """(last result, least wall [s], least cpu [s]) of ``repeat`` calls."""
    runs = [timed(fn) for _ in range(repeat)]
    return runs[-1][0], min(r[1] for r in runs), min(r[2] for r in runs)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("rockets", nargs="*", default=list(CASES))
    ap.add_argument("--samples", type=int, default=40)
    ap.add_argument("--repeat", type=int, default=3)
    args = ap.parse_args()
    print(f"IRONBARK_JIT={os.environ['IRONBARK_JIT']}, {args.samples} SAA samples, best of {args.repeat}")
    for name in args.rockets:
        target = CASES[name]
        setup = load_setup(ROOT / "examples" / name / f"{name}.toml")
        spec = ROOT / "examples" / name / "dispersions.toml"
        _, first_nominal, _ = timed(lambda: solve_ballast(setup, target))          # builds model and libraries

        def robust():
            return solve_robust_ballast(setup, target, spec, samples=args.samples, check_samples=0)
        _, first_robust, _ = timed(robust)                                        # compiles or loads its own
        _, nominal, nominal_cpu = best(lambda: solve_ballast(setup, target), args.repeat)
        sol, wall, cpu = best(robust, args.repeat)
        v = sol.values
        print(f"{name:8s} target {target}: nominal solve {nominal:6.3f} s wall ({nominal_cpu:6.3f} s cpu); "
              f"robust {wall:6.3f} s wall ({cpu:6.3f} s cpu) = {wall / nominal:5.1f} x nominal wall, "
              f"{cpu / nominal_cpu:5.1f} x cpu (goal <= 10)")
        print(f"{'':8s} last robust run: its nominal solve {v['nominal_solve_time_s']:.3f} s, SAA "
              f"{v['saa_time_s']:.3f} s ({v['sample_evaluations']} evaluations of the samples, "
              f"{v['ipopt_iterations']} IPOPT iterations on their models), selection "
              f"{v.get('select_time_s', 0.0):.3f} s ({v.get('select_samples', 0)} fresh samples x 2 ballasts); "
              f"ballast {v['nominal_ballast_kg']:.3f} -> {v['ballast_kg']:.3f} kg "
              f"(SAA optimum {v['saa_optimum_ballast_kg']:.3f})")
        print(f"{'':8s} first calls (build/compile or load): nominal {first_nominal:6.1f} s, robust "
              f"{first_robust:6.1f} s")


if __name__ == "__main__":
    main()
