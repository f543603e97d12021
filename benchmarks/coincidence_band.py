"""The measurement behind :data:`panair.coincidence.COINCIDENCE_BAND`: CA(0), CN(2 deg),
Cm(2 deg) on a rocket's shared supersonic mesh against the same Mach number on a mesh
free of the cross-body Mach-cone coincidence (phase >= 0.4), over a fine Mach sweep,
with the shared mesh's phase (panel lengths) beside each.

Run:  python benchmarks/coincidence_band.py ROCKET.toml MACH_LO MACH_HI STEP [--no-fins]

Session 17: the TR R-100 body (tests/unit/test_panair_supersonic_coincidence.py's) over
1.33-1.46 and 1.88-2.14, Defiance (/work/shared/reference/flights/defiance) over
1.30-1.42; the numbers are in panair/coincidence.py.
"""
from __future__ import annotations

import argparse
import sys
from dataclasses import replace
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from ironbark_opt.errors import SolverError                       # noqa: E402
from ironbark_opt.vehicle import load_rocket_geometry              # noqa: E402
from panair.coincidence import coincidence_free_options, coincidence_phase  # noqa: E402
from panair.geometry_adapter import from_rocket, is_symmetric      # noqa: E402
from panair.mesh import MeshOptions, mesh_rocket, tip_options      # noqa: E402
from panair.solver import build_panels, make_solver                # noqa: E402
from panair.solver.panels import mirror_plane                      # noqa: E402
from panair.sweep import supersonic_mesh_options                   # noqa: E402


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("rocket")
    ap.add_argument("lo", type=float)
    ap.add_argument("hi", type=float)
    ap.add_argument("step", type=float)
    ap.add_argument("--no-fins", action="store_true")
    a = ap.parse_args()
    rk, _ = load_rocket_geometry(a.rocket)
    g = from_rocket(rk)
    if a.no_fins:
        g = replace(g, fins=())
    sym = is_symmetric(g)
    sref, lref = rk.reference_area(), 2 * rk.reference_radius()
    machs = np.round(np.arange(a.lo, a.hi + 1e-9, a.step), 4)
    shared = supersonic_mesh_options(MeshOptions(), machs)
    cache = {}

    def solve(opt, m):
        if opt not in cache:
            cache[opt] = build_panels(mesh_rocket(g, symmetric=sym, options=opt), symmetric=sym)
            mirror_plane(cache[opt])
        try:
            r = make_solver(cache[opt], m, sref=sref, lref=lref, xref=0.0,
                            mirror=True).solve(np.radians([0.0, 2.0]))
            return r[0].CA, r[1].CN, r[1].Cm
        except SolverError:
            return (float("nan"),) * 3

    print("Mach    phase  shared CA(0) CN(2) Cm(2)       free: spacing phase  CA(0) CN(2) Cm(2)"
          "       err CN, Cm")
    for m in machs:
        own = tip_options(g, shared, m)          # the Mach number's own nose tip, as the sweep
        free = coincidence_free_options(g, own, m, band=np.inf)
        s, f = solve(own, m), solve(free, m)
        print(f"{m:.4f}  {coincidence_phase(g, own, m):.3f}  {s[0]:.4f} {s[1]:.4f} {s[2]:+.4f}"
              f"   {free.body_spacing:.3f} {coincidence_phase(g, free, m):.3f}  {f[0]:.4f} "
              f"{f[1]:.4f} {f[2]:+.4f}   {100 * (s[1] / f[1] - 1):+.2f} % {100 * (s[2] / f[2] - 1):+.2f} %",
              flush=True)


if __name__ == "__main__":
    main()
