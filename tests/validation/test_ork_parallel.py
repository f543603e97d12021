"""OpenRocket's 'Parallel booster staging.ork': two strap-on boosters (E12-0) burning with
the core's I115W and separating at their ejection (= burnout, delay 0), the core flying on
to apogee; and the same rocket carrying its unlit boosters the whole flight.  Against
both stored simulations: apogee (10 %), the events (5 %), the boosters' own flight."""
from pathlib import Path

import pytest

from ironbark_opt.dynamics.setup import FlightSetup
from ironbark_opt.dynamics.staged import StagedSetup
from ironbark_opt.flight import simulate
from ironbark_opt.openrocket import read_ork
from ironbark_opt.vehicle import load_setup

ORK = Path(__file__).parents[1] / "data" / "ork" / "Parallel booster staging.ork"


pytestmark = pytest.mark.usefixtures("ork_offline")     # tests/conftest.py


def _event(sim, kind, branch=None):
    return [t for t, k, _ in sim.events(branch) if k == kind]


@pytest.mark.filterwarnings("ignore::UserWarning")
@pytest.mark.parametrize("index", [0, 1])
def test_each_stored_simulation(index):
    doc = read_ork(ORK)
    sim = doc.simulations[index]
    setup = load_setup(ORK, config=sim.config_id, rail_exit="travel")     # OpenRocket: launch-rod travel
    flight = simulate(setup)
    stored = sim.summary["apogee_m"]
    err = flight.apogee_agl / stored - 1
    print(f"{sim.name}: core apogee {flight.apogee_agl:.1f} m, OpenRocket {stored:.1f} m ({100 * err:+.2f} %)")
    assert abs(err) < 0.10                                              # the tolerance
    df = flight.to_dataframe()
    assert df["mass_kg"].iloc[0] == pytest.approx(sim.data()["mass_kg"].iloc[0], abs=1e-3)   # stored to 1 g
    core_burnout = max(_event(sim, "burnout"))
    s = flight.summary_values
    print(f"  core burnout {s['burnout_time_s']:.3f} s (OpenRocket {core_burnout:.3f} s)")
    assert s["burnout_time_s"] == pytest.approx(core_burnout, rel=0.05)
    if index == 1:                         # no booster motors: carried all the way (no separation event)
        assert isinstance(setup, FlightSetup) and not _event(sim, "stageseparation")
        return
    assert isinstance(setup, StagedSetup) and setup.parallel
    (sep,) = _event(sim, "stageseparation")
    b_burn = min(_event(sim, "burnout"))
    print(f"  booster burnout {s['booster_burnout_time_s']:.3f} s (OpenRocket {b_burn:.3f} s), separation "
          f"{s['separation_time_s']:.3f} s (OpenRocket {sep:.3f} s)")
    assert s["booster_burnout_time_s"] == pytest.approx(b_burn, rel=0.05)
    assert s["separation_time_s"] == pytest.approx(sep, rel=0.05)
    jump = df.loc[df["phase"] == "sustainer_boost", "mass_kg"].iloc[0]
    before = df.loc[df["phase"] == "boost", "mass_kg"].iloc[-1]
    stored = sim.data()
    after_or = stored.loc[stored["time_s"] > sep, "mass_kg"].iloc[0]
    print(f"  mass {before:.3f} kg -> {jump:.3f} kg at separation (OpenRocket just after: {after_or:.3f} kg)")
    assert jump == pytest.approx(after_or, abs=0.005)
    # one booster from separation to the ground: statically unstable, so it tumbles
    # (Niskanen 2013 sec. 3.5 drag, as OpenRocket's 'tumble' event in this branch)
    b = sim.branches["Booster Set"]
    print(f"  booster apogee {s['booster_apogee_agl_m']:.1f} m at {s['booster_apogee_time_s']:.2f} s (OpenRocket "
          f"{b['altitude_m'].max():.1f} m at {min(_event(sim, 'apogee', 'Booster Set')):.2f} s), lands at "
          f"{s['booster_landing_time_s']:.1f} s (OpenRocket {b['time_s'].iloc[-1]:.1f} s), tumbling Cd A "
          f"{s['booster_tumble_cd_area_m2'] * 1e4:.1f} cm^2")
    assert _event(sim, "tumble", "Booster Set") and s["booster_tumble_cd_area_m2"] > 0
    assert s["booster_apogee_agl_m"] == pytest.approx(b["altitude_m"].max(), rel=0.10)
    assert s["booster_landing_time_s"] == pytest.approx(b["time_s"].iloc[-1], rel=0.10)


def test_ork_info_lists_the_boosters():
    from ironbark_opt.cli.ork import ork_summary
    info = ork_summary(read_ork(ORK))
    names = [(s["name"], s.get("instances")) for s in info["stage_list"]]
    print(names)
    assert names == [("Sustainer", None), ("Booster Set", 2)]
    core, pods = info["stage_list"]
    # OpenRocket's launch mass minus its motors: 1.308 - 0.580 - 2 x 0.0599 kg (stored to 1 g)
    assert core["dry_mass_kg"] + pods["dry_mass_kg"] == pytest.approx(1.308 - 0.580 - 2 * 0.0599, abs=1.5e-3)
    assert pods["separation"] == "ejection" and pods["radial_distance_m"] == pytest.approx(0.028702 + 0.0168275)


@pytest.mark.filterwarnings("ignore::UserWarning")
def test_parallel_boosters_are_differentiable_for_ballast_and_sensitivities():
    """The boosters' sequence is one MX graph like serial staging: the AD derivative of
    apogee equals a central difference, and a ballast for a target re-simulates onto it."""
    from ironbark_opt import params
    from ironbark_opt.analysis.sensitivity import sensitivities
    from ironbark_opt.flight import flight_model
    from ironbark_opt.optimise.ballast import solve_ballast

    setup = load_setup(ORK, config="6e25", rail_exit="travel")
    sens = sensitivities(setup, names=["drag_scale"])
    model, p0 = flight_model(setup), setup.nominal_parameters()
    up, down = p0.copy(), p0.copy()
    up[params.index("drag_scale")] += 0.01
    down[params.index("drag_scale")] -= 0.01
    fd = (model.run(up)["x_apogee"][2] - model.run(down)["x_apogee"][2]) / 0.02
    print(f"d apogee / d drag_scale: AD {sens.jacobian[0, 0]:.3f} m, central difference {fd:.3f} m")
    assert sens.jacobian[0, 0] == pytest.approx(fd, rel=0.01)
    sol = solve_ballast(setup, 1100.0)            # nominal 1140.7 m
    again = simulate(setup, parameters={"ballast_mass": sol.ballast, "ballast_x": sol.values["ballast_x_m"]})
    print(f"ballast {sol.ballast:.4f} kg for 1100 m: re-simulated {again.apogee_agl:.3f} m")
    assert sol.feasible and abs(again.apogee_agl - 1100.0) < 1.0
