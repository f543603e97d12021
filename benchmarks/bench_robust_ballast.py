"""Robust ballast solve time against one nominal ballast solve.

For Calisto (target 3000 m AGL) and Kestrel (10,000 ft AGL) with their example
dispersion specs: one nominal ``solve_ballast`` (warm: model and NLP built),
then ``solve_robust_ballast`` with the default 40 SAA samples and no check
(the robust solve includes its own nominal solve, the starting point, and the
validation of the SAA optimum on 200 fresh samples per ballast).  The
compiled per-sample event function is built (or loaded from the disk cache)
by a first, untimed robust call; its one-off compile time is printed too.
Goal: robust <= 10 x nominal.

Run: ``python benchmarks/bench_robust_ballast.py [samples]``.
"""
from __future__ import annotations

import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from ironbark_opt.optimise.ballast import solve_ballast  # noqa: E402
from ironbark_opt.optimise.robust import solve_robust_ballast  # noqa: E402
from ironbark_opt.vehicle import load_setup  # noqa: E402

CASES = [("calisto", "3000m"), ("kestrel", "10000ft")]


def main():
    samples = int(sys.argv[1]) if len(sys.argv) > 1 else 40
    for name, target in CASES:
        setup = load_setup(ROOT / "examples" / name / f"{name}.toml")
        spec = ROOT / "examples" / name / "dispersions.toml"
        solve_ballast(setup, target)                               # builds model and NLP
        t0 = time.perf_counter()
        solve_ballast(setup, target)
        nominal = time.perf_counter() - t0
        t0 = time.perf_counter()
        solve_robust_ballast(setup, target, spec, samples=samples, check_samples=0)   # compile or load
        first = time.perf_counter() - t0
        t0 = time.perf_counter()
        sol = solve_robust_ballast(setup, target, spec, samples=samples, check_samples=0)
        robust = time.perf_counter() - t0
        v = sol.values
        print(f"{name:8s} target {target}: nominal solve {nominal:6.2f} s; robust ({samples} samples) "
              f"{robust:6.2f} s = {robust / nominal:5.1f} x nominal (goal <= 10); first robust call incl. "
              f"compile/load {first:6.1f} s; {v['ipopt_iterations']} IPOPT iterations, "
              f"{v['sample_evaluations']} mapped evaluations; ballast {v['nominal_ballast_kg']:.3f} -> "
              f"{v['ballast_kg']:.3f} kg")


if __name__ == "__main__":
    main()
