"""Mass and inertia rates by the chain rule through the motor's impulse (rhs.mass_rates)
against the symbolic derivative of the thrust-curve table (the former method), the
coast's burnt-out motor against the motor's own mass model, and sin of the angle of
attack without atan2 (_math.sin_angle)."""
from pathlib import Path

import casadi as ca
import numpy as np

from ironbark_opt import _math, params
from ironbark_opt.dynamics import rhs
from ironbark_opt.vehicle import load_setup

ROOT = Path(__file__).resolve().parents[2]


def _setup():
    return load_setup(ROOT / "examples" / "calisto" / "calisto.toml")


def test_mass_rates_through_the_impulse_equal_the_derivative_of_the_table():
    setup = _setup()
    t, p = ca.SX.sym("t"), ca.SX.sym("p", params.SIZE)
    P = params.unpack(p)
    m, _, inertia = rhs.mass_properties(setup, t, P)
    mdot, idot = rhs.mass_rates(setup, t, P, setup.motor, m, inertia)
    assert setup.motor.mass_driver(t) is not None               # the chain-rule path is the one tested
    ref = [ca.jacobian(m, t), ca.jacobian(ca.vec(inertia), t)]
    f = ca.Function("rates", [t, p], [mdot, ca.vec(idot), *ref])
    p0 = np.array(setup.nominal_parameters())
    p0[params.index("burn_time_scale")] = 1.07                   # a stretched burn: the 1/s factor counts
    burn = setup.motor.burn_time * 1.07
    # inside segments (knot times themselves are where the table's derivative picks a side)
    times = np.linspace(0.013, burn - 0.013, 301)
    rows = f.map(times.size)(times[None, :], np.tile(p0[:, None], times.size))
    got_m, got_i, want_m, want_i = (np.array(v) for v in rows)
    err_m = np.max(np.abs(got_m - want_m)) / np.max(np.abs(want_m))
    err_i = np.max(np.abs(got_i - want_i)) / np.max(np.abs(want_i))
    print(f"mass rate {err_m:.1e}, inertia rate {err_i:.1e} (max relative to the largest rate; tolerance 1e-12)")
    assert np.max(np.abs(want_m)) > 0.5                          # kg/s: the burn is sampled
    assert err_m < 1e-12 and err_i < 1e-12
    after = np.array(f(burn + 0.5, p0)[0])                       # after burnout: no mass change
    assert after.item() == 0.0


def test_coast_motor_is_the_motor_at_burnout():
    setup = _setup()
    motor = setup.motor
    mp, cg, (it, ia) = rhs._burnt_out(motor)
    for t in (motor.burn_time, motor.burn_time + 3.0, 2 * motor.burn_time):
        assert abs(motor.propellant_mass(t) - mp) <= 1e-15 * motor.propellant_mass_initial
        assert motor.cg(t) == cg
        assert motor.inertia(t) == (it, ia)


def test_sin_angle_of_atan2_equals_sin():
    y, x = ca.SX.sym("y"), ca.SX.sym("x")
    alpha = ca.atan2(y, x)
    f = ca.Function("s", [y, x], [_math.sin_angle(alpha), ca.sin(alpha)])
    rng = np.random.default_rng(3)
    ys, xs = rng.uniform(1e-3, 50, 2000), rng.uniform(-300, 300, 2000)
    a, b = (np.array(v).ravel() for v in f.map(ys.size)(ys[None, :], xs[None, :]))
    err = np.max(np.abs(a - b))
    print(f"sin(atan2(y, x)) vs y / hypot: max difference {err:.1e} (tolerance 1e-15)")
    assert err < 1e-15
    assert _math.sin_angle(0.3) == np.sin(0.3)                   # numbers: plain sin
