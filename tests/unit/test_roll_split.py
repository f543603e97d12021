"""The roll channel of ``rk4_step``: damping and fin-cant forcing advanced together
(exact for frozen coefficients), and the refusal of a diverged flight."""
import casadi as ca
import numpy as np
import pytest

from ironbark_opt.dynamics.integrator import rk4_step
from ironbark_opt.errors import SolverError


def _roll_rhs(c, f):
    """dw_x/dt = c w_x + f (c [1/s], f [rad/s^2]), every other state still."""
    x, t, p = ca.SX.sym("x", 13), ca.SX.sym("t"), ca.SX.sym("p", 1)
    xdot = ca.vertcat(ca.SX.zeros(10), c * x[10] + f, ca.SX.zeros(2))
    return ca.Function("rhs", [x, t, p], [xdot, x[10], c + 0 * t, f + 0 * t],
                       ["x", "t", "p"], ["xdot", "y", "c_roll", "f_roll"])


@pytest.mark.parametrize("h", [0.001, 0.02, 0.05, 0.2])
def test_roll_equation_is_advanced_exactly(h):
    """Analytic: w(t) = w_eq + (w0 - w_eq) exp(c t), w_eq = -f/c, at any |c| h (here up
    to 40, far outside RK4's stability region)."""
    c, f, w0 = -200.0, 2400.0, 3.0
    step = rk4_step(_roll_rhs(c, f))
    x = np.zeros(13)
    x[10] = w0
    n = 10
    for _ in range(n):
        x = np.array(step(x, 0.0, h, 0.0)).ravel()
    exact = -f / c + (w0 + f / c) * np.exp(c * n * h)
    assert x[10] == pytest.approx(exact, rel=1e-12, abs=1e-12)


def test_small_damping_limit():
    """|c h| below the series threshold: the same exact solution (phi1 series)."""
    c, f, h = -1e-5, 2.0, 0.01
    step = rk4_step(_roll_rhs(c, f))
    x = np.zeros(13)
    x = np.array(step(x, 0.0, h, 0.0)).ravel()
    exact = -f / c * -np.expm1(c * h)
    assert x[10] == pytest.approx(exact, rel=1e-12)


def test_diverged_flight_is_refused():
    from ironbark_opt.flight import _check_converged

    class _Setup:
        name = "R"

    class _Model:
        setup = _Setup()

    df = {"mach": np.array([0.1, 0.9, 1830.0]), "altitude_agl_m": np.array([0.0, 500.0, -6e4])}
    run = {"x_apogee": np.array([0.0, 0.0, -69197.3])}
    with pytest.raises(SolverError, match="diverged"):
        _check_converged(_Model(), run, df, np.ones(3, bool))
    ok = {"mach": np.array([0.1, 0.9]), "altitude_agl_m": np.array([0.0, 500.0])}
    _check_converged(_Model(), {"x_apogee": np.array([0, 0, 3000.0])}, ok, np.ones(2, bool))
