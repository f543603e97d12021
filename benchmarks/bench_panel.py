"""Wall time of an 84-point aerodynamic table (12 Mach x 7 alpha) for the
Basic Finner (~2000 panels, half model) with the built-in panel solver,
and — when a PANAIR executable is configured (IRONBARK_PANAIR or `panair`
on PATH) — PANAIR's time for the same cases and the ratio.

Run:  python benchmarks/bench_panel.py [--workers 2] [--refine 1.0]

Mach 0.1 ... 0.9 subsonic, 1.2 ... 3.0 supersonic; PANAIR runs the same
cases (one deck per alpha with ALPC = alpha, as the reference runs).
Goal: the whole table < 60 s on a 2-core machine.
"""
from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from panair.a502 import find_panair, run_panair          # noqa: E402
from panair.mesh import (BodyGeometry, FinGeometry, MeshOptions, RocketGeometry,  # noqa: E402
                         mesh_rocket)
from panair.sweep import sweep_pressure                   # noqa: E402

MACH = np.array([0.1, 0.3, 0.5, 0.7, 0.8, 0.9, 1.2, 1.5, 1.8, 2.2, 2.6, 3.0])
ALPHA = np.radians([0.0, 1.0, 2.0, 4.0, 6.0, 8.0, 10.0])


def basic_finner():
    body = BodyGeometry(np.array([0.0, 2.84, 10.0]), np.array([0.0, 0.5, 0.5]))
    fins = (FinGeometry(4, 1.0, 1.0, 1.0, 0.0, 9.0, 0.08, roll=np.pi / 4),)
    return RocketGeometry(body, fins, "basic finner")


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--workers", type=int, default=2)
    ap.add_argument("--refine", type=float, default=1.0)
    args = ap.parse_args()
    geom = basic_finner()
    opt = MeshOptions(refine=args.refine)
    t0 = time.perf_counter()
    coeffs, info = sweep_pressure(geom, MACH, ALPHA, sref=np.pi / 4, lref=1.0, xref=5.0,
                                  options=opt, workers=args.workers, progress=True)
    t_ours = time.perf_counter() - t0
    print(f"built-in panel solver: {len(MACH)} Mach x {len(ALPHA)} alpha = "
          f"{len(MACH) * len(ALPHA)} points, {info['panels']} panels subsonic / "
          f"{info['panels_supersonic']} supersonic, {args.workers} workers: "
          f"{t_ours:.1f} s ({'meets' if t_ours < 60 else 'misses'} the 60 s goal)")
    cna = np.polyfit(ALPHA[:3], coeffs["CN"][:, :3].T, 1)[0]
    print("CN-alpha [1/rad] by Mach:", " ".join(f"{m:g}:{c:.2f}" for m, c in zip(MACH, cna)))
    exe = find_panair()
    if not exe:
        print("PANAIR: not configured (set IRONBARK_PANAIR) - no comparison")
        return
    nets = {o: mesh_rocket(geom, symmetric=True, options=o)      # the meshes the sweep used
            for o in {opt.for_mach(m) for m in MACH}}
    t0 = time.perf_counter()
    for m in MACH:
        for a in np.degrees(ALPHA):
            run_panair(nets[opt.for_mach(m)], mach=float(m), alpha_deg=a, alpc_deg=a, sref=np.pi / 4, cref=1.0,
                       xref=5.0, symmetric=True)
    t_pan = time.perf_counter() - t0
    print(f"PANAIR ({exe}), serial: {t_pan:.1f} s; ratio PANAIR / built-in = {t_pan / t_ours:.1f}")


if __name__ == "__main__":
    main()
