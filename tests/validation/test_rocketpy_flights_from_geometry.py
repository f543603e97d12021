"""Ten more real student-rocket flights (EuRoC 2022/2023/2025, Spaceport America Cup
2022/2023, LASC 2019) on tables built from their geometry alone, against the recorded
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

#: recorded apogee AGL [m] and the team's pre-flight prediction [m] (README; valetudo and
#: hedy state none: the notebook's own RocketPy simulation on the team curve instead)
FIRST_SIX = ("cavour", "andromeda", "erebus", "lince", "juno3", "prometheus")
RECORDED = {"cavour": (2789.0, 2806.0), "andromeda": (3443.0, 3614.95),
            "erebus": (3020.0, 2750.90), "lince": (3587.0, 3284.115),
            "juno3": (3213.0, 3026.054), "prometheus": (3898.37, 4190.05),
            "valetudo": (860.0, 815.26), "halcyon": (3450.0, 3163.0),
            "hedy": (5231.53, 5246.918), "camoes": (3015.0, 3003.0)}


def _team_curve_apogee(name, tmp_path):
    """The same flight in our simulator on the team's own drag curve (copied from
    ../shared/reference/rockets as team_drag_power_off/on.csv; one file = both), or None
    where the team published none we read (prometheus: none; andromeda: its curve is a
    flight export whose Mach number falls back, which the reader refuses)."""
    from ironbark_opt import load_setup, simulate
    off = DATA / name / "team_drag_power_off.csv"
    if not off.exists():
        return None
    on = DATA / name / "team_drag_power_on.csv"
    text = (DATA / name / "rocket_geometry.toml").read_text()
    text = text.replace('file = "thrust.csv"', f'file = "{(DATA / name / "thrust.csv").as_posix()}"')
    text = text.replace('file = "../../weather/', f'file = "{(DATA.parent / "weather").as_posix()}/')
    brakes = (DATA / name / "drag_airbrakes.csv").as_posix()      # camoes
    text = text.replace('drag = "drag_airbrakes.csv"', f'drag = "{brakes}"')
    text = text.replace('controller = "airbrake_controller.py:',
                        f'controller = "{(DATA / name / "airbrake_controller.py").as_posix()}:')
    text += ('\n[aero]\ndrag_duplicates = "mean"\n'
             f'drag_power_off = "{off.as_posix()}"\ndrag_power_on = "{(on if on.exists() else off).as_posix()}"\n')
    path = tmp_path / f"{name}_team.toml"
    path.write_text(text)
    return simulate(load_setup(path)).summary_values["apogee_agl_m"]


@pytest.mark.slow
def test_rocketpy_example_flights_on_tables_from_geometry(tmp_path):
    from ironbark_opt import load_setup, simulate
    from ironbark_opt.vehicle import load_rocket_geometry
    from panair.rocket_table import rocket_table
    errs, team_errs, first_six = [], [], []
    print("\nflight       recorded  geometry table  err %   team pre-flight  err %   "
          "team curve, ours  err %   max Mach   local-inclination Mach")
    for name, (rec, team) in RECORDED.items():
        geo = DATA / name / "rocket_geometry.toml"
        rk, spec = load_rocket_geometry(geo)
        table = rocket_table(rk, spec, workers=2)
        table.save(tmp_path / name)
        fl = simulate(load_setup(geo, table=str(tmp_path / name) + ".csv")).summary_values
        e, et = 100 * (fl["apogee_agl_m"] / rec - 1), 100 * (team / rec - 1)
        errs.append(abs(e))
        if name in FIRST_SIX:
            first_six.append(abs(e))
        team_errs.append(abs(et))
        curve = _team_curve_apogee(name, tmp_path)
        curve_txt = f"{curve:12.1f} {100 * (curve / rec - 1):+9.2f}" if curve else f"{'-':>12s} {'-':>9s}"
        print(f"{name:11s} {rec:9.1f} {fl['apogee_agl_m']:12.1f} {e:+8.2f} {team:12.1f} {et:+9.2f}"
              f"    {curve_txt} {fl['max_mach']:9.3f}   {table.metadata['mach_local_inclination']}")
    print(f"median |error| {np.median(errs):.2f} % (teams' own: {np.median(team_errs):.2f} %), "
          f"max {np.max(errs):.2f} % (teams' own: {np.max(team_errs):.2f} %); the first six: "
          f"median {np.median(first_six):.2f} %, max {np.max(first_six):.2f} %")
    # measured (session 7): cavour -0.79, andromeda +3.75, erebus -5.69, lince +4.24,
    # juno3 -5.74, prometheus -6.26 % (median 4.97 %, max 6.26 %; the teams' own pre-flight
    # predictions: median 6.65 %, max 8.91 %); session 10, supersonic fin wakes: andromeda
    # +3.81, prometheus -6.27 %, the others unchanged; session 12, the launch guides' drag
    # (ironbark_opt.aero.protuberance; no button size in these files: OpenRocket's default
    # button assumed, with a warning): cavour -1.66, andromeda +3.30, erebus -7.12, lince
    # +3.12, juno3 -6.07, prometheus -6.76 % (median 4.68 %, max 7.12 %); a regression beyond
    # it fails; sessions 13-22 measured cavour -1.66, andromeda +3.78, erebus -7.08, lince +3.26,
    # juno3 -6.07, prometheus -6.72 % (session 23 too).  The bound stays on those six; the four added with the converter's hybrid,
    # liquid, free-form-fin and air-brake support (session 23) measured: valetudo +5.73,
    # halcyon -7.18, hedy -11.59 (its team curve, ours: +1.95 %: our skin friction on its
    # l/d 28 body is 0.43 of the 0.55 Cd we fly at Mach 0.6, the team's curve says 0.38 in
    # all), camoes +8.37 % with its air brakes (team curve + brakes, ours: 3006 m against
    # RocketPy's 3003 m); all ten: median 6.40 %, max 11.59 % (first six: 4.93, 7.08 %); bounded so a
    # regression on them fails too, not loosened for the six
    assert np.median(first_six) <= 6.0 and np.max(first_six) <= 8.0
    assert np.median(errs) <= 7.0 and np.max(errs) <= 12.5
