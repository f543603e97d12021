"""Launch-day solve speed on the bundled Calisto example.

Prints the ballast solve wall time cold (model and NLP built in this
process, everything included) and warm (same model, new target) by the
default method (a fixed position: the root on the flown apogee) and by
IPOPT's NLP (``method="ipopt"``, the path of a free position or flight
constraints), and the motor choice over 10 candidate motors.
Goal: warm ballast solve under 1 s.

Run: ``python benchmarks/bench_ballast.py``.
"""
from __future__ import annotations

import statistics
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from ironbark_opt.optimise.ballast import solve_ballast  # noqa: E402
from ironbark_opt.optimise.motor_choice import choose_motor  # noqa: E402
from ironbark_opt.vehicle import load_setup  # noqa: E402

EXAMPLE = ROOT / "examples" / "calisto" / "calisto.toml"
MOTORS = ROOT / "tests" / "data" / "motors"
CANDIDATES = ["Cesaroni_M1670.eng", "Cesaroni_7579M1520-P.eng", "Cesaroni_6438M1300-P.eng", "AeroTech_M1340W.eng",
              "AeroTech_M1939W.eng", "AeroTech_M2100G.eng", "Cesaroni_8088M1790-P.eng", "AMW_6774M2050-P.eng",
              "Loki_M1378LR.eng", "AeroTech_M1845NT.eng"]


def main():
    t0 = time.perf_counter()
    setup = load_setup(EXAMPLE)
    sol = solve_ballast(setup, "3000m")
    cold = time.perf_counter() - t0
    print(f"ballast solve, cold (load + build + solve): {cold:6.2f} s  -> {sol!r}")
    warm = []
    for target in ("3100m", "2900m", "10000ft", "2800m", "3050m"):
        t0 = time.perf_counter()
        solve_ballast(setup, target)
        warm.append(time.perf_counter() - t0)
    print(f"ballast solve, warm (median of {len(warm)}):   {statistics.median(warm):6.3f} s  (goal < 1 s)")
    solve_ballast(setup, "3000m", method="ipopt")                 # the NLP built (not timed)
    warm = []
    for target in ("3100m", "2900m", "10000ft", "2800m", "3050m"):
        t0 = time.perf_counter()
        solve_ballast(setup, target, method="ipopt")
        warm.append(time.perf_counter() - t0)
    print(f"ballast solve, warm, IPOPT's NLP:           {statistics.median(warm):6.3f} s")
    files = [str(MOTORS / name) for name in CANDIDATES if (MOTORS / name).exists()]
    t0 = time.perf_counter()
    ranking = choose_motor(setup, files, "3000m")
    elapsed = time.perf_counter() - t0
    print(f"motor choice over {len(files)} candidates:       {elapsed:6.2f} s  "
          f"(best: {ranking.best.motor if ranking.best else 'none'})")


if __name__ == "__main__":
    main()
