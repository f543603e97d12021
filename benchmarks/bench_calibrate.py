"""Compare + calibrate of a 2 MB flight log against one ``simulate`` of the same rocket.

NUSTARS FT1: its .ork and its 2.26 MB TeleMega log (read from
../shared/fixtures/telemetry when present, else the gzipped copy in
tests/data/telemetry).  Each measurement starts from the files, as the
commands do: ``simulate`` = load the rocket + build its model + one flight;
``compare + calibrate`` = read the log + load the rocket + build the model +
simulate and compare + the fit (Levenberg-Marquardt on the exact Jacobian)
+ the calibrated flight.  Goal (issue 17): ratio < 3.

Run: ``python benchmarks/bench_calibrate.py [--repeat N]``.  Medians.
"""
from __future__ import annotations

import argparse
import statistics
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from ironbark_opt.flight import simulate  # noqa: E402
from ironbark_opt.telemetry import read_log  # noqa: E402
from ironbark_opt.telemetry.calibrate import calibrate  # noqa: E402
from ironbark_opt.telemetry.compare import compare_flight  # noqa: E402
from ironbark_opt.vehicle import load_setup  # noqa: E402

ORK = ROOT / "tests/data/telemetry/nustars-2026-ft1-telemega.ork"
SHARED = ROOT.parent / "shared" / "fixtures" / "telemetry" / "altos" / "nustars-2026-ft1-telemega.csv"
LOG = SHARED if SHARED.exists() else ROOT / "tests/data/telemetry/nustars-2026-ft1-telemega.csv.gz"


def one_simulate():
    return simulate(load_setup(ORK))


def compare_and_calibrate():
    log = read_log(LOG)
    setup = load_setup(ORK)
    comparison = compare_flight(setup, log)
    cal = calibrate(setup, log, until_fraction=0.6)
    calibrated = simulate(setup, parameters=cal.parameter_values())
    return comparison, cal, calibrated


def median(func, repeat):
    times = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        func()
        times.append(time.perf_counter() - t0)
    return statistics.median(times)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--repeat", type=int, default=3)
    args = ap.parse_args()
    one_simulate()                                    # warm imports / disk cache
    t_sim = median(one_simulate, args.repeat)
    t_read = median(lambda: read_log(LOG), args.repeat)
    t_cc = median(compare_and_calibrate, args.repeat)
    _, cal, calibrated = compare_and_calibrate()
    print(f"log: {LOG} ({LOG.stat().st_size / 1e6:.2f} MB)")
    print(f"simulate (load + model + flight)      {t_sim:7.2f} s")
    print(f"read_log                              {t_read:7.2f} s")
    print(f"compare + calibrate (+ calibrated run) {t_cc:7.2f} s   ({cal.stats['iterations']} iterations)")
    print(f"ratio compare+calibrate / simulate    {t_cc / t_sim:7.2f}   (goal < 3)")


if __name__ == "__main__":
    main()
