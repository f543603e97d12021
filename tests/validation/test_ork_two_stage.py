"""OpenRocket's 'Two stage high power rocket.ork' flown as two serial stages
(stack to the booster's burnout, separation and sustainer ignition there,
sustainer alone to apogee) against both stored simulations."""
from pathlib import Path

import numpy as np
import pytest

from ironbark_opt.dynamics.staged import StagedSetup
from ironbark_opt.errors import InputError
from ironbark_opt.flight import simulate
from ironbark_opt.openrocket import read_ork
from ironbark_opt.vehicle import load_setup

ORK = Path(__file__).parents[1] / "data" / "ork" / "Two stage high power rocket.ork"


pytestmark = pytest.mark.usefixtures("ork_offline")     # tests/conftest.py


def _edges(t, thrust):
    on = np.asarray(thrust) > 1e-3
    k = np.nonzero(np.diff(on.astype(int)))[0] + 1
    return [(float(np.asarray(t)[i - 1]), float(np.asarray(t)[i])) for i in k]


@pytest.mark.parametrize("index", [0, 1])
def test_each_stored_simulation(index):
    sim = read_ork(ORK).simulations[index]
    setup = load_setup(ORK, config=sim.config_id, rail_exit="travel")     # OpenRocket: launch-rod travel
    assert isinstance(setup, StagedSetup)
    flight = simulate(setup)
    stored = sim.summary["apogee_m"]
    err = flight.apogee_agl / stored - 1
    print(f"{sim.name} ({setup.stack.motor.motors[0].designation} + {setup.sustainer.motor.designation}): "
          f"sustainer apogee {flight.apogee_agl:.1f} m, OpenRocket {stored:.1f} m ({100 * err:+.2f} %)")
    assert abs(err) < 0.10                                              # the tolerance
    df = flight.to_dataframe()
    assert df["mass_kg"].iloc[0] == pytest.approx(sim.data()["mass_kg"].iloc[0], abs=1e-3)   # stored to 1 g
    # OpenRocket's stored thrust: booster burnout, sustainer ignition, sustainer burnout, each
    # as the pair of samples it lies between.  Ours: the event times of the fixed sequence.
    (_, _), (b_lo, b_hi), (i_lo, i_hi), (s_lo, s_hi) = _edges(sim.data()["time_s"], sim.data()["thrust_n"])
    t_b1 = setup.stack.motor.burn_time
    t_sep = t_b1 + setup.separation_delay
    t_b2 = setup.sustainer.motor.burn_time
    print(f"  booster burnout {t_b1:.3f} s (OpenRocket {b_lo:.3f}..{b_hi:.3f}), separation and ignition "
          f"{t_sep:.3f} s ({i_lo:.3f}..{i_hi:.3f}), sustainer burnout {t_b2:.3f} s ({s_lo:.3f}..{s_hi:.3f})")
    for ours, lo, hi in ((t_b1, b_lo, b_hi), (t_sep, i_lo, i_hi), (t_b2, s_lo, s_hi)):
        assert 0.95 * lo <= ours <= 1.05 * hi                           # 5 % around OpenRocket's interval
    assert df["phase"].tolist().count("sustainer_boost") > 0
    jump = df.loc[df["phase"] == "sustainer_boost", "mass_kg"].iloc[0]
    print(f"  mass {df.loc[df['phase'] == 'boost', 'mass_kg'].iloc[-1]:.3f} kg -> {jump:.3f} kg at separation")
    assert jump < df.loc[df["phase"] == "boost", "mass_kg"].iloc[-1] - 0.5
    # The booster after separation: its own apogee and landing point against OpenRocket's
    # booster branch (10 %).  Its flat front carries the stagnation pressure (Niskanen 2013
    # eq. 3.87, Hoerner ch. 3): without it the apogees were +21 % / +35 %, now -4.4 % / -1.7 %.
    s, b = flight.summary_values, sim.branches["Booster"]
    print(f"  booster apogee {s['booster_apogee_agl_m']:.1f} m (OpenRocket {b['altitude_m'].max():.1f} m), lands at "
          f"{s['booster_landing_time_s']:.1f} s (OpenRocket {b['time_s'].iloc[-1]:.1f} s), "
          f"{s['booster_landing_east_m']:.1f} m east (OpenRocket {b['east_m'].iloc[-1]:.1f} m)")
    assert s["booster_apogee_agl_m"] == pytest.approx(b["altitude_m"].max(), rel=0.10)
    assert s["booster_landing_time_s"] == pytest.approx(b["time_s"].iloc[-1], rel=0.10)
    assert s["booster_landing_east_m"] * b["east_m"].iloc[-1] > 0          # same side of the pad
    # The sustainer down under its drogue and main: landing time against OpenRocket's
    # sustainer branch (10 %), on the same side of the pad.
    down = simulate(setup, descent=True).summary_values
    sus = sim.branches["Sustainer"]
    print(f"  sustainer lands at {down['landing_time_s']:.1f} s (OpenRocket {sus['time_s'].iloc[-1]:.1f} s), "
          f"{down['landing_east_m']:.1f} m east (OpenRocket {sus['east_m'].iloc[-1]:.1f} m)")
    assert down["landing_time_s"] == pytest.approx(sus["time_s"].iloc[-1], rel=0.10)
    assert down["landing_east_m"] * sus["east_m"].iloc[-1] > 0


def test_ballast_sensitivities_and_montecarlo_of_a_staged_rocket(tmp_path):
    """The staged sequence is one differentiable graph: the ballast for a target
    re-simulates onto it, AD derivatives equal central differences, and Monte
    Carlo flies each sample like a single run."""
    from ironbark_opt import params
    from ironbark_opt.analysis.distributions import load_spec
    from ironbark_opt.analysis.montecarlo import montecarlo
    from ironbark_opt.analysis.sensitivity import sensitivities
    from ironbark_opt.flight import flight_model
    from ironbark_opt.optimise.ballast import solve_ballast

    setup = load_setup(ORK, config="fadeeef3", rail_exit="travel")
    sol = solve_ballast(setup, 1250.0)
    again = simulate(setup, parameters={"ballast_mass": sol.ballast, "ballast_x": sol.values["ballast_x_m"]})
    print(f"ballast {sol.ballast:.4f} kg at {sol.values['ballast_x_m']:.3f} m for 1250 m: re-simulated "
          f"{again.apogee_agl:.3f} m")
    assert sol.feasible and abs(again.apogee_agl - 1250.0) < 1.0
    assert sol.values["ballast_x_m"] == pytest.approx(setup.sustainer.dry.cg_x)     # in the sustainer
    sens = sensitivities(setup, names=["ballast_mass", "drag_scale"])
    model, p0 = flight_model(setup), setup.nominal_parameters()
    for j, name in enumerate(("ballast_mass", "drag_scale")):
        up, down = p0.copy(), p0.copy()
        up[params.index(name)] += 0.01
        down[params.index(name)] -= 0.01
        fd = (model.run(up)["x_apogee"][2] - model.run(down)["x_apogee"][2]) / 0.02
        print(f"d apogee / d {name}: AD {sens.jacobian[0, j]:.3f}, central difference {fd:.3f}")
        assert sens.jacobian[0, j] == pytest.approx(fd, rel=0.01)
    spec_file = tmp_path / "dispersions.toml"
    spec_file.write_text('seed = 3\n[parameters.drag_scale]\ndistribution = "normal"\nstd = 0.05\n')
    df = montecarlo(setup, load_spec(spec_file), 4, progress=False).to_dataframe()
    print(df[["drag_scale", "apogee_agl_m"]])
    for _, row in df.iterrows():                                   # each sample = a single run
        p = setup.nominal_parameters(drag_scale=row["drag_scale"])
        assert row["apogee_agl_m"] == pytest.approx(model.run(p)["x_apogee"][2], abs=1e-6)


def test_launch_environment_replaces_every_vehicles():
    """dataclasses.replace(staged, site_elevation=...) (the CLI's --elevation, a forecast)
    reaches the stack, the sustainer and the booster alike."""
    import dataclasses

    setup = load_setup(ORK, rail_exit="travel")
    high = dataclasses.replace(setup, site_elevation=1500.0)
    assert {high.stack.site_elevation, high.sustainer.site_elevation, high.booster.site_elevation} == {1500.0}
    low, up = simulate(setup).apogee_agl, simulate(high).apogee_agl
    print(f"apogee at sea level {low:.1f} m AGL, at 1500 m {up:.1f} m AGL")
    assert up > low                                   # thinner air
