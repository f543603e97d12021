"""OpenRocket's 'Airstart timing.ork' (a K550W at launch and a cluster of three
I211W lit 0-6 s later in the same stage): every stored simulation flown with
its own configuration, against OpenRocket's stored apogee and flight data."""
from pathlib import Path

import numpy as np
import pytest

from ironbark_opt.flight import simulate
from ironbark_opt.motors.composite import CompositeMotor
from ironbark_opt.openrocket import read_ork
from ironbark_opt.vehicle import load_setup

ORK = Path(__file__).parents[1] / "data" / "ork" / "Airstart timing.ork"


def _thrust_edges(t, thrust):
    """Times [s] where the thrust switches on or off (first sample of the new state)."""
    on = np.asarray(thrust) > 1e-3
    k = np.nonzero(np.diff(on.astype(int)))[0] + 1
    return np.asarray(t)[k], on[k]


@pytest.mark.parametrize("index", range(5))
def test_every_configuration_matches_openrocket(index, monkeypatch, tmp_path):
    monkeypatch.setenv("IRONBARK_OFFLINE", "1")
    monkeypatch.setenv("IRONBARK_CACHE_DIR", str(tmp_path))
    monkeypatch.setenv("IRONBARK_MOTOR_PATH", str(ORK.parent / "motors"))
    doc = read_ork(ORK)
    sim = doc.simulations[index]
    setup = load_setup(ORK, config=sim.config_id, rail_exit="travel")      # OpenRocket: launch-rod travel
    assert isinstance(setup.motor, CompositeMotor)
    flight = simulate(setup)
    stored = sim.summary["apogee_m"]
    err = flight.apogee_agl / stored - 1
    print(f"{sim.name} ({setup.motor.designation}): apogee {flight.apogee_agl:.1f} m, OpenRocket {stored:.1f} m "
          f"({100 * err:+.2f} %)")
    assert abs(err) < 0.10                                                   # the tolerance
    # Ignition and burnout times against OpenRocket's stored thrust (its samples are
    # ~0.05 s apart during the burn; tolerance 5 %).
    data = sim.data()
    t_or, on_or = _thrust_edges(data["time_s"], data["thrust_n"])
    df = flight.to_dataframe()
    t_us, on_us = _thrust_edges(df["time_s"], df["thrust_N"])
    t_or, on_or, t_us, on_us = t_or[1:], on_or[1:], t_us[1:], on_us[1:]    # drop the launch edge
    assert list(on_us) == list(on_or)
    for a, b, what in zip(t_us, t_or, on_us):
        print(f"  {'ignition' if what else 'burnout '} {a:.3f} s, OpenRocket {b:.3f} s ({100 * (a / b - 1):+.2f} %)")
        assert a == pytest.approx(b, rel=0.05)
    assert setup.motor.burn_time == pytest.approx(t_or[-1], rel=0.05)


def test_airstart_flight_is_smooth_in_the_parameters(monkeypatch, tmp_path):
    """The boost phase is split at the air-start ignition and the first motor's
    burnout, so AD derivatives through the sequence equal central differences
    (burn-time scale moves the ignition time itself) and ballast re-simulates onto
    its target."""
    from ironbark_opt import params
    from ironbark_opt.analysis.sensitivity import sensitivities
    from ironbark_opt.flight import flight_model
    from ironbark_opt.optimise.ballast import solve_ballast

    monkeypatch.setenv("IRONBARK_OFFLINE", "1")
    monkeypatch.setenv("IRONBARK_CACHE_DIR", str(tmp_path))
    monkeypatch.setenv("IRONBARK_MOTOR_PATH", str(ORK.parent / "motors"))
    setup = load_setup(ORK, config="37647ba6", rail_exit="travel")          # air-start at 4 s
    assert setup.motor.events == pytest.approx((setup.motor.motors[0].burn_time, 4.0))
    names = ["ballast_mass", "burn_time_scale", "thrust_scale"]
    sens = sensitivities(setup, names=names)
    model, p0 = flight_model(setup), setup.nominal_parameters()
    for j, (name, h) in enumerate(zip(names, (0.05, 0.002, 0.002))):
        up, down = p0.copy(), p0.copy()
        up[params.index(name)] += h
        down[params.index(name)] -= h
        fd = (model.run(up)["x_apogee"][2] - model.run(down)["x_apogee"][2]) / (2 * h)
        print(f"d apogee / d {name}: AD {sens.jacobian[0, j]:.3f}, central difference {fd:.3f}")
        assert sens.jacobian[0, j] == pytest.approx(fd, rel=0.005)
    sol = solve_ballast(setup, 1200.0)
    again = simulate(setup, parameters={"ballast_mass": sol.ballast, "ballast_x": sol.values["ballast_x_m"]})
    print(f"ballast {sol.ballast:.4f} kg -> re-simulated {again.apogee_agl:.3f} m for 1200 m")
    assert sol.feasible and abs(again.apogee_agl - 1200.0) < 1.0
