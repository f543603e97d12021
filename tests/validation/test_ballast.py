"""Ballast solve: re-simulated optimum hits the target, agrees with a
bracketing root-finder on ``simulate``, and infeasible targets are reported."""
from pathlib import Path

import pytest
from scipy.optimize import brentq

from ironbark_opt.flight import simulate
from ironbark_opt.optimise.ballast import solve_ballast
from ironbark_opt.optimise.target import parse_target
from ironbark_opt.vehicle import load_setup

ROOT = Path(__file__).resolve().parents[2]
ROCKETS = {"calisto": ROOT / "examples/calisto/calisto.toml", "kestrel": ROOT / "examples/kestrel/kestrel.toml"}
TARGETS = {"calisto": ["3200m", "10000ft", "2600m"], "kestrel": ["3150m", "10000ft", "2950m"]}


@pytest.fixture(scope="module", params=sorted(ROCKETS))
def rocket(request):
    return request.param, load_setup(ROCKETS[request.param])


def test_optimum_hits_target_and_matches_root_finder(rocket):
    """Both solvers (the default one-variable root on the flown apogee, and IPOPT's
    NLP) against scipy's brentq on ``simulate``."""
    name, setup = rocket
    for target in TARGETS[name]:
        goal = parse_target(target).agl(setup.site_elevation)
        m_root = brentq(lambda m: simulate(setup, parameters={"ballast_mass": m}).apogee_agl - goal,
                        0.0, 10.0, xtol=1e-6)
        for method in ("auto", "ipopt"):
            sol = solve_ballast(setup, target, method=method)
            assert sol.feasible, sol.status
            flown = simulate(setup, parameters={"ballast_mass": sol.ballast}).apogee_agl
            print(f"{name} {target}: {method} {sol.ballast:.5f} kg, brentq {m_root:.5f} kg "
                  f"(diff {1000 * (sol.ballast - m_root):+.3f} g), re-simulated apogee error {flown - goal:+.2e} m "
                  f"({sol.values['solve_time_s']:.2f} s)")
            assert abs(flown - goal) < (0.5 if method == "ipopt" else 1e-6)    # tolerance 0.5 m; root: its 1e-6 m
            assert abs(sol.ballast - m_root) < 1e-3              # tolerance 1 g


def test_unreachable_target_reports_closest_apogee(rocket):
    name, setup = rocket
    high = solve_ballast(setup, "100 km")
    assert not high.feasible
    assert high.ballast == 0.0
    zero = simulate(setup, parameters={"ballast_mass": 0.0}).apogee_agl
    assert high.values["apogee_agl_m"] == pytest.approx(zero, abs=1e-6)
    assert any("ballast_kg >= 0" in a for a in high.active)
    low = solve_ballast(setup, "50 m", mass_max=2.0)
    assert not low.feasible and low.ballast == 2.0
    assert any("ballast_kg <=" in a for a in low.active)


def test_flight_constraint_makes_target_unreachable(rocket):
    """A rail-exit speed the loaded rocket cannot reach: closest feasible apogee."""
    name, setup = rocket
    free = solve_ballast(setup, TARGETS[name][1])
    v_free = free.values["rail_exit_speed_mps"]
    sol = solve_ballast(setup, TARGETS[name][1], min_rail_speed=v_free + 0.5)
    print(sol.summary())
    assert not sol.feasible
    assert sol.values["rail_exit_speed_mps"] >= v_free + 0.5 - 1e-3
    assert sol.values["apogee_agl_m"] > free.values["apogee_agl_m"]    # less ballast than needed
    assert any("rail_exit_speed" in a for a in sol.active)
