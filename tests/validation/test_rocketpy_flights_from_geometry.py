"""Six more real student-rocket flights (EuRoC 2022/2023, Spaceport America Cup
2022/2023) on tables built from their geometry alone, against the recorded
apogee, next to the team's own pre-flight prediction.

Source: tests/data/flights_rocketpy (converted from RocketPy's example
notebooks; the README there names the notebooks, the recorded apogees and what
the conversion assumed).  These are not the issue's five visible flights
(tests/validation/test_flights_from_geometry.py); nothing is fitted to either.
Slow: one table build per flight.
"""
from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

DATA = Path(__file__).parents[1] / "data" / "flights_rocketpy"

#: recorded apogee AGL [m] and the team's pre-flight prediction [m] (README)
RECORDED = {"cavour": (2789.0, 2806.0), "andromeda": (3443.0, 3614.95),
            "erebus": (3020.0, 2750.90), "lince": (3587.0, 3284.115),
            "juno3": (3213.0, 3026.054), "prometheus": (3898.37, 4190.05)}


@pytest.mark.slow
def test_rocketpy_example_flights_on_tables_from_geometry(tmp_path):
    from ironbark_opt import load_setup, simulate
    from ironbark_opt.vehicle import load_rocket_geometry
    from panair.rocket_table import rocket_table
    errs, team_errs = [], []
    print("\nflight       recorded  geometry table  err %   team pre-flight  err %   max Mach"
          "   local-inclination Mach")
    for name, (rec, team) in RECORDED.items():
        geo = DATA / name / "rocket_geometry.toml"
        rk, spec = load_rocket_geometry(geo)
        table = rocket_table(rk, spec, workers=2)
        table.save(tmp_path / name)
        fl = simulate(load_setup(geo, table=str(tmp_path / name) + ".csv")).summary_values
        e, et = 100 * (fl["apogee_agl_m"] / rec - 1), 100 * (team / rec - 1)
        errs.append(abs(e))
        team_errs.append(abs(et))
        print(f"{name:11s} {rec:9.1f} {fl['apogee_agl_m']:12.1f} {e:+8.2f} {team:12.1f} {et:+9.2f}"
              f" {fl['max_mach']:9.3f}   {table.metadata['mach_local_inclination']}")
    print(f"median |error| {np.median(errs):.2f} % (teams' own: {np.median(team_errs):.2f} %), "
          f"max {np.max(errs):.2f} % (teams' own: {np.max(team_errs):.2f} %)")
    # measured (session 7): cavour -0.79, andromeda +3.75, erebus -5.69, lince +4.24,
    # juno3 -5.74, prometheus -6.26 % (median 4.97 %, max 6.26 %; the teams' own pre-flight
    # predictions: median 6.65 %, max 8.91 %); a regression beyond it fails
    assert np.median(errs) <= 6.0 and np.max(errs) <= 8.0
