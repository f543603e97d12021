"""Calisto cross-check against RocketPy's reference run (same inputs).

Tolerances are the ones stated with the reference data
(../shared/reference/calisto/README.md, copied to tests/data/calisto).
"""
import json
import math
from pathlib import Path

import pytest

from ironbark_opt.flight import simulate
from ironbark_opt.vehicle import load_setup

ROOT = Path(__file__).resolve().parents[2]
REF = json.loads((ROOT / "tests/data/calisto/reference.json").read_text())
EXAMPLE = ROOT / "examples/calisto/calisto.toml"


@pytest.fixture(scope="module")
def setup():
    return load_setup(EXAMPLE)


def test_launch_mass(setup):
    flight = simulate(setup)
    assert flight.summary_values["launch_mass_kg"] == pytest.approx(REF["launch_mass_kg"], abs=5e-4)


@pytest.mark.parametrize("case", REF["cases"], ids=lambda c: f"incl{c['inclination_deg']:.0f}-hdg{c['heading_deg']:.0f}")
def test_calisto_matches_rocketpy(setup, case):
    flight = simulate(setup, parameters={"inclination": math.radians(case["inclination_deg"]),
                                         "heading": math.radians(case["heading_deg"])})
    s = flight.summary_values
    tol = REF["tolerances"]
    for key in ("apogee_agl_m", "apogee_time_s", "max_speed_mps", "rail_exit_speed_mps"):
        err = s[key] / case[key] - 1
        print(f"{key}: ours {s[key]:.3f}, RocketPy {case[key]:.3f}, error {100 * err:+.3f} % "
              f"(tolerance {100 * tol[key]:.0f} %)")
        assert abs(err) <= tol[key]
    if "static_margin_initial_cal" in case:
        d = s["static_margin_initial_cal"] - case["static_margin_initial_cal"]
        print(f"static margin: ours {s['static_margin_initial_cal']:.3f} cal, error {d:+.3f} cal (tolerance 0.3)")
        assert abs(d) <= tol["static_margin_initial_cal_abs"]


def test_calisto_on_its_panel_table_vs_rocketpy():
    """Independent aerodynamics: Calisto flying tables/Calisto (built from the geometry
    alone by panair.rocket_table: panel solution, zero-lift drag model with the
    transonic rise, base drag, cross-flow; friction at the flight's Reynolds number;
    NACA 0012 fins of one thickness as RocketPy's model) against RocketPy's run on
    its own drag curves.  Goal (issue 13): 2 %.  Measured (session 4): -6.2 %, (session 6,
    table with the transonic gap sampled) -6.0 %; the
    table's zero-lift CA is above the curve: +11 % subsonic (friction + base), and
    from Mach 0.75 the fins' transonic rise (critical Mach 0.66 from Korn's equation
    with t/c = 0.14 of one thickness over a tapered fin) and their supersonic wave
    drag (the sonic anchor) where the curve stays flat to Mach 0.9.  Session 13: -6.58 %
    (the launch guides' drag, OpenRocket's default button assumed since the file gives no
    size, and the table rebuilt with the supersonic half-model fix).  The bound below
    is the measured state, so a regression fails."""
    case = REF["cases"][0]
    flight = simulate(load_setup(EXAMPLE, table=ROOT / "tables/Calisto.csv"),
                      parameters={"inclination": math.radians(case["inclination_deg"]),
                                  "heading": math.radians(case["heading_deg"])})
    err = flight.summary_values["apogee_agl_m"] / case["apogee_agl_m"] - 1
    print(f"\nCalisto on its panel table: apogee {flight.summary_values['apogee_agl_m']:.1f} m vs "
          f"RocketPy {case['apogee_agl_m']:.1f} m ({100 * err:+.2f} %; goal 2 %: "
          f"{'met' if abs(err) <= 0.02 else 'NOT MET'})")
    assert abs(err) < 0.08
