"""Motor slot (motors/slot.py) and grids read from p (integrator.padded_grid):
the symbolic slot flies the same numbers as the motor itself, and a padded
grid the same RK4 steps as the constant one."""
import dataclasses
from pathlib import Path

import casadi as ca
import numpy as np
import pytest

from ironbark_opt.dynamics.integrator import grid_fractions, padded_grid, phase_trajectory, rk4_step
from ironbark_opt.motors import load_motor
from ironbark_opt.motors.slot import MotorSlot, fits, knots

DATA = Path(__file__).resolve().parents[1] / "data" / "motors"


def _motors():
    base = load_motor(DATA / "Cesaroni_7579M1520-P.eng")
    return [base, load_motor(DATA / "AeroTech_M1340W.eng"),
            dataclasses.replace(base, dry_mass=0.0),                      # casing counted in the rocket
            dataclasses.replace(base, nozzle_exit_area=2.0e-3)]


@pytest.mark.parametrize("i", range(4))
def test_slot_motor_equals_the_motor(i):
    motor = _motors()[i]
    assert fits(motor)
    slot = MotorSlot(knots(motor) + 7, offset=3)        # padded, and not at the start of p
    p = ca.SX.sym("p", 3 + slot.n_data)
    t = ca.SX.sym("t")
    bound = slot.bind(p)
    f = ca.Function("m", [t, p], [bound.thrust(t, 1.1, 0.95), bound.mass(t, 1.1, 0.95), bound.cg(t, 1.1, 0.95),
                                  *bound.inertia(t, 1.1, 0.95), bound.pressure_thrust_correction(80000.0 + t)])
    values = np.r_[np.zeros(3), slot.pack(motor)]
    assert float(slot.burn_time(values)) == motor.burn_time
    for tau in np.r_[np.linspace(-0.1, motor.burn_time * 0.95 + 0.2, 57), motor.burn_time * 0.95]:
        got = [float(v) for v in f(tau, values)]
        want = [motor.thrust(tau, 1.1, 0.95), motor.mass(tau, 1.1, 0.95), motor.cg(tau, 1.1, 0.95),
                *motor.inertia(tau, 1.1, 0.95), motor.pressure_thrust_correction(80000.0 + tau)]
        # the same expressions on the same numbers: equal to round-off
        np.testing.assert_allclose(got, want, rtol=1e-13, atol=1e-12)


def test_slot_refuses_motors_it_cannot_hold():
    motor = _motors()[0]
    with pytest.raises(ValueError):
        MotorSlot(knots(motor) - 1, 0).pack(motor)


def test_padded_grid_flies_the_same_steps():
    # dx/dt = -x + t, p[0] a rate; grid fractions read from p (padded) or constant
    x, t, p = ca.SX.sym("x", 2), ca.SX.sym("t"), ca.SX.sym("p", 1 + 2 * 12)
    rhs = ca.Function("rhs", [x, t, p], [ca.vertcat(-p[0] * x[0] + t, x[0])])
    step = rk4_step(rhs, "s")
    fixed = phase_trajectory(step, 9, "fixed", 0.5)
    padded = phase_trajectory(step, 12, "padded", grid_offset=1)
    pv = np.r_[0.7, padded_grid(9, 12, 0.5)]
    a = np.array(fixed([1.0, 0.0], 0.3, 2.3, pv))
    b = np.array(padded([1.0, 0.0], 0.3, 2.3, pv))
    assert np.array_equal(a, b[:, :9])                              # bit for bit
    assert np.array_equal(b[:, 9:], np.repeat(a[:, -1:], 3, axis=1))  # zero-length steps: state unchanged
    assert np.allclose(np.r_[pv[1:13], 1.0][:10], grid_fractions(9, 0.5))


def test_slot_model_from_the_cache_flies_and_outputs_bit_identically(tmp_path, monkeypatch):
    """A slot model loaded from the model cache (Functions deserialised when used, the
    grid choice read back) flies a candidate bit for bit as the one that was built, and
    the outputs' shared-p blocks equal the per-sample map (tolerance: exact)."""
    from ironbark_opt.dynamics.slot_model import SlotFlightModel
    from ironbark_opt.vehicle import load_setup

    monkeypatch.setenv("IRONBARK_CACHE_DIR", str(tmp_path))
    setup = load_setup(Path(__file__).resolve().parents[2] / "examples/calisto/calisto.toml")
    motor = load_motor(DATA / "AeroTech_M1340W.eng")
    p_nom = setup.nominal_parameters()
    n_knots = 16 * -(-knots(motor) // 16)
    built = SlotFlightModel(setup, n_knots, (320, 320))
    grid = built.grid_for(motor, p_nom)
    loaded = SlotFlightModel(setup, n_knots, (320, 320))
    assert loaded.grid_for(motor, p_nom) == grid
    p = built.parameters(p_nom, motor, grid)
    a, b = built.run(p), loaded.run(p)
    assert np.array_equal(a["x"], b["x"]) and np.array_equal(a["t"], b["t"]) and a["t_apogee"] == b["t_apogee"]
    y = loaded.outputs(a["t"], a["x"], a["phase"], p)
    assert np.array_equal(built.outputs(a["t"], a["x"], a["phase"], p), y)
    per_sample = built.outputs(a["t"], a["x"], a["phase"], np.repeat(p[:, None], a["t"].size, axis=1))
    assert np.array_equal(per_sample, y)


def test_buffered_call_equals_the_function_call():
    """The slot model's buffered calls (no DM conversion) give the Function's own numbers,
    to the bit: matrices (column-major), a scalar filling a vector input, several
    outputs, a 1 x 1 output as a number; symbolic and mis-sized arguments go through
    the Function itself."""
    from ironbark_opt.dynamics.slot_model import _buffered
    x, t, p = ca.SX.sym("x", 3, 4), ca.SX.sym("t", 1, 4), ca.SX.sym("p", 5)
    f = ca.Function("f", [x, t, p], [ca.sin(x) * ca.repmat(t, 3, 1) + p[1], ca.sumsqr(x) * p[4]])
    g = _buffered(f)
    rng = np.random.default_rng(3)
    X, T, P = rng.normal(size=(3, 4)), rng.normal(size=(1, 4)), rng.normal(size=5)
    for args in ((X, T, P), (X, 0.7, P)):
        a, b = g(*args), f(*args)
        assert np.array_equal(a[0], np.array(b[0])) and a[0].shape == (3, 4)
        assert a[1].shape == () and float(a[1]) == float(b[1])
    sym = g(ca.MX.sym("X", 3, 4), T, P)                     # symbolic: the Function's MX
    assert isinstance(sym[0], ca.MX)
    with pytest.raises(RuntimeError):                       # 2 numbers for a 4-column input: CasADi's error
        g(X, np.ones(2), P)
    assert g.name() == "f" and g.map(2).size2_in(0) == 8    # other attributes: the Function's
