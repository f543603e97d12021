"""The Motor interface: scaling hook, state, summaries, for any kind of motor."""
from __future__ import annotations

import pickle
from pathlib import Path

import casadi as ca
import numpy as np
import pytest

from ironbark_opt import _math as sm
from ironbark_opt.motors import Motor, load_motor

DATA = Path(__file__).resolve().parents[1] / "data" / "motors"


class BoxMotor(Motor):
    """A non-solid test motor: constant thrust F for T seconds, point masses."""

    designation, manufacturer = "BOX", "test"
    burn_time, dry_mass, propellant_mass_initial = 2.0, 1.0, 0.5
    diameter, length, nozzle_exit_area, reference_pressure = 0.05, 0.4, 1e-3, 100000.0
    F = 300.0
    total_impulse = F * burn_time

    def _thrust_unscaled(self, tau):
        return self.F * (tau >= 0) * (tau < self.burn_time)

    def _impulse_unscaled(self, tau):
        return self.F * sm.clip(tau, 0.0, self.burn_time)

    def _mass_properties_unscaled(self, tau):
        mp = self.propellant_mass_initial * (1 - self._impulse_unscaled(tau) / self.total_impulse)
        cg = (self.dry_mass * 0.2 + mp * 0.3) / (self.dry_mass + mp)
        return mp, cg, (0.01 + mp * 0.001, 0.001)


def test_motor_is_abstract():
    with pytest.raises(TypeError):
        Motor()


def test_scaling_is_done_once_in_the_base_class():
    m = BoxMotor()
    k, s = 1.1, 1.25
    # F(t) = k / s F0(t / s): 300 * 1.1 / 1.25 over 2.5 s
    assert m.thrust(2.4, k, s) == pytest.approx(264.0)
    assert m.thrust(2.6, k, s) == 0.0
    assert m.impulse(10.0, k, s) == pytest.approx(k * 600.0)
    assert m.propellant_mass(1.25, k, s) == pytest.approx(0.25)      # half-way in t / s
    assert m.mass(1.25, k, s) == pytest.approx(1.25)
    st = m.state(1.25, k, s)
    assert st.thrust == pytest.approx(264.0) and st.mass == pytest.approx(1.25)
    assert st.cg == pytest.approx(m.cg(1.25, k, s)) and st.inertia == m.inertia(1.25, k, s)
    assert m.pressure_thrust_correction(50000.0) == pytest.approx(50.0)


def test_symbolic_scale_parameters():
    m = BoxMotor()
    t, k, s = ca.SX.sym("t"), ca.SX.sym("k"), ca.SX.sym("s")
    f = ca.Function("f", [t, k, s], [m.thrust(t, k, s), m.mass(t, k, s)])
    F, M = f(2.4, 1.1, 1.25)
    assert float(F) == pytest.approx(264.0) and float(M) == pytest.approx(m.mass(2.4, 1.1, 1.25))


def test_summary_of_any_motor():
    m = BoxMotor()
    d = m.to_dict()
    assert d["impulse_class"] == "I" and d["average_thrust_N"] == pytest.approx(300.0)
    assert d["max_thrust_N"] == pytest.approx(300.0) and d["total_mass_kg"] == 1.5
    assert "BOX" in m.summary() and "class I" in m.summary()


def test_solid_motor_pickles_after_symbolic_use():
    m = load_motor(DATA / "Cesaroni_M1670.eng")
    t = ca.SX.sym("t")
    m.thrust(t)                                   # builds the cached interpolant
    m2 = pickle.loads(pickle.dumps(m))
    f = ca.Function("f", [t], [m2.thrust(t)])
    assert float(f(1.0)) == 2034.0 and m2.total_impulse == m.total_impulse
    assert np.array_equal(np.asarray(m2.thrust), np.asarray(m.thrust))
