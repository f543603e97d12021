"""Fixed-step RK4 (default discretisation) against SciPy's DOP853 on the same
CasADi right-hand side, with exact events, for both example rockets."""
from pathlib import Path

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from ironbark_opt import params
from ironbark_opt.dynamics.frames import rail_direction_l
from ironbark_opt.flight import flight_model
from ironbark_opt.vehicle import load_setup

ROOT = Path(__file__).resolve().parents[2]


@pytest.mark.parametrize("name", ["calisto", "kestrel"])
def test_rk4_matches_dop853_on_the_same_rhs(name):
    """Tolerance 0.5 m in apogee (DOP853 rtol 1e-10)."""
    setup = load_setup(ROOT / f"examples/{name}/{name}.toml")
    model = flight_model(setup)
    p = setup.nominal_parameters()
    opts = dict(method="DOP853", rtol=1e-10, atol=1e-10)

    def f(phase):
        rhs = model.rhs[phase]
        return lambda t, x: np.array(rhs(x, t, p)[0]).ravel()

    x0 = np.array(model.initial_state(p)).ravel()
    e = np.array(rail_direction_l(p[params.index("inclination")], p[params.index("heading")])).ravel()
    exit_distance = p[params.index("rail_length")] - setup.rail_exit_offset

    def off_rail(t, x):
        return e @ x[:3] - exit_distance
    off_rail.terminal = True

    def apogee(t, x):
        return float(model.vz_l(x))
    apogee.terminal, apogee.direction = True, -1

    rail = solve_ivp(f("rail"), (0, 2), x0, events=off_rail, **opts)
    t_b = setup.motor.burn_time
    boost = solve_ivp(f("boost"), (rail.t[-1], t_b), rail.y[:, -1], **opts)
    coast = solve_ivp(f("coast"), (t_b, 60), boost.y[:, -1], events=apogee, **opts)
    run = model.run(p)
    d_apogee = run["x_apogee"][2] - coast.y[2, -1]
    d_time = run["t_apogee"] - coast.t[-1]
    d_rail = run["t_rail"] - rail.t[-1]
    print(f"RK4 - DOP853: apogee {d_apogee:+.4f} m, apogee time {d_time:+.5f} s, rail exit {d_rail:+.2e} s "
          f"(RK4 steps: rail {model.steps.n_rail}, boost {model.n_boost}, coast {model.n_coast})")
    assert abs(d_apogee) < 0.5
    assert abs(d_time) < 0.01
    assert abs(d_rail) < 1e-3
