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


def _canted_kestrel(tmp_path, cant_deg):
    """The Kestrel example with its fins canted ``cant_deg`` (a spin-stabilised variant:
    its light airframe, I_axial 0.019 kg m^2, makes roll the stiffest mode, c_roll ~ -180
    1/s at burnout), written to ``tmp_path`` with absolute file paths."""
    src = ROOT / "examples/kestrel"
    text = (src / "kestrel.toml").read_text()
    text = text.replace('section = "double_wedge"', f'section = "double_wedge"\ncant_deg = {cant_deg}', 1)
    text = text.replace('file = "Cesaroni_4263L1350-P.eng"',
                        f'file = "{(src / "Cesaroni_4263L1350-P.eng").as_posix()}"')
    text = text.replace('table = "../../tables/Kestrel.csv"',
                        f'table = "{(ROOT / "tables/Kestrel.csv").as_posix()}"')
    path = tmp_path / "kestrel_canted.toml"
    path.write_text(text)
    return path


def _spinning_random(tmp_path):
    """Random rocket 2 (tests/random_rockets.py: 76 mm, 1.95 kg, I_axial 0.0014 kg m^2,
    K1000T) with its elliptical fins canted 1.5 deg: 198 rad/s at burnout.  Until session
    19 its flight was refused: the provisional 0.02 s boost blew up before burnout (the
    roll couples pitch and yaw at ~280 rad/s), so the stiffness check had no finite state
    (grid.GridMixin._finite_boost); then the stability-chosen coast left it -8.5 m short
    (grid.SPIN_LAMBDA_FACTOR: -1.7 m)."""
    import sys
    sys.path.insert(0, str(ROOT / "tests"))
    from random_rockets import random_rocket
    text = random_rocket(2).replace("thickness = ", "cant_deg = 1.5\nthickness = ", 1)
    path = tmp_path / "random2_canted.toml"
    path.write_text(text)
    return path


@pytest.mark.parametrize("name", ["calisto", "kestrel", "kestrel_canted",
                                  pytest.param("random2_canted", marks=pytest.mark.slow)])
def test_rk4_matches_dop853_on_the_same_rhs(name, tmp_path):
    """Tolerance 0.5 m in apogee (DOP853 rtol 1e-10); the canted Kestrel also in its
    roll rate at burnout (2 %): the roll channel's damping and forcing advanced
    together (integrator.rk4_step) keep the equilibrium roll rate."""
    path = _canted_kestrel(tmp_path, 1.5) if name == "kestrel_canted" else \
        _spinning_random(tmp_path) if name == "random2_canted" else \
        ROOT / f"examples/{name}/{name}.toml"
    setup = load_setup(path)
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
    if name in ("kestrel_canted", "random2_canted"):
        wx_rk4 = float(np.asarray(run["x_burnout"]).ravel()[10])
        wx_ref = float(boost.y[10, -1])
        print(f"roll rate at burnout: RK4 {wx_rk4:.4f}, DOP853 {wx_ref:.4f} rad/s")
        assert wx_ref > 5.0 and abs(wx_rk4 / wx_ref - 1) < 0.02
        # a rolling rocket's pitch-yaw motion (frequencies shifted by the roll rate) is
        # resolved less finely by the stability-chosen grid: measured -1.19 m, 4th order
        # (twice the steps: -0.11 m); bound 0.05 % of the apogee
        assert abs(d_apogee) < 5e-4 * coast.y[2, -1]
        return
    assert abs(d_apogee) < 0.5
    assert abs(d_time) < 0.01
    assert abs(d_rail) < 1e-3
