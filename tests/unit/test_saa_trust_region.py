"""The trust-region SAA minimiser (ironbark_opt.optimise.saa_trust_region) on problems whose
optimum is known independently: per-sample apogees given in closed form (quadratic and
exponential in the ballast), the optimum found by SciPy's bounded scalar search / Nelder-Mead
on the exact objective (no gradients, no models)."""
from __future__ import annotations

import numpy as np
import pytest
from scipy.optimize import minimize, minimize_scalar

from ironbark_opt.optimise.robust_objective import smoothed_terms, symbolic_terms
from ironbark_opt.optimise.saa_trust_region import minimise


def _samples(n=40, seed=5):
    rng = np.random.default_rng(seed)
    return 3000 + 70 * rng.standard_normal(n), -190 * (1 + 0.05 * rng.standard_normal(n))


@pytest.mark.parametrize("objective", ["in_band", "expected_abs_miss"])
def test_one_variable_optimum_matches_a_derivative_free_search(objective):
    c, b = _samples()
    m0 = 1.5

    def apogee(m):              # curved in the mass (as a flight is): exact values and derivatives
        return c + b * (m - m0) + 25.0 * (m - m0) ** 2 + 3.0 * (m - m0) ** 3, \
            (b + 50.0 * (m - m0) + 9.0 * (m - m0) ** 2)[None, :]

    def evaluate(w):
        a, g = apogee(w[0])
        return a, g, np.zeros(0), np.zeros((0, 1))

    def exact(m):
        return float(np.mean(smoothed_terms(apogee(m)[0], 3050.0, objective, 50.0, 25.0)[0]))

    best, done, _ = minimise(evaluate, lambda a: symbolic_terms(a, 3050.0, objective, 50.0, 25.0),
                             [m0], [0.0], [5.0])
    ref = minimize_scalar(exact, bounds=(0.0, 5.0), method="bounded", options={"xatol": 1e-9})
    print(objective, "trust region", best.w[0], "in", len(done), "evaluations; bounded search", ref.x)
    assert best.w[0] == pytest.approx(ref.x, abs=1e-5)
    assert best.f == pytest.approx(ref.fun, abs=1e-10)
    assert len(done) <= 8
    # the start was evaluated first and every accepted step lowered the exact objective
    assert done[0].w[0] == m0 and best.f <= done[0].f


def test_two_variables_and_an_active_limit():
    c, b = _samples(seed=9)
    bx = 30.0 * (1 + 0.1 * np.random.default_rng(2).standard_normal(c.size))
    w0 = np.array([1.5, 1.2])

    def apogee(w):
        dm, dx = w - w0
        a = c + b * dm + bx * dx + 20.0 * dm * dm - 8.0 * dm * dx + 5.0 * dx * dx
        g = np.vstack([b + 40.0 * dm - 8.0 * dx, bx - 8.0 * dm + 10.0 * dx])
        return a, g

    def limit(w):                # e.g. a margin rising with mass and position; 2.0 at the start
        return np.array([2.0 + 0.8 * (w[0] - 1.5) + 1.5 * (w[1] - 1.2) - 0.3 * (w[0] - 1.5) ** 2]), \
            np.array([[0.8 - 0.6 * (w[0] - 1.5), 1.5]])

    def evaluate(w):
        return (*apogee(w), *limit(w))

    def exact(w):
        return float(np.mean(smoothed_terms(apogee(w)[0], 3100.0, "in_band", 50.0, 25.0)[0]))

    lo, hi, bound = np.array([0.0, 1.0]), np.array([4.0, 1.5]), 1.9
    best, done, _ = minimise(evaluate, lambda a: symbolic_terms(a, 3100.0, "in_band", 50.0, 25.0), w0, lo, hi,
                             [bound])
    # independent: SciPy's SLSQP on the exact objective and limit from several starts, no models
    cons = {"type": "ineq", "fun": lambda w: limit(w)[0][0] - bound}
    refs = [minimize(exact, x0, method="SLSQP", bounds=list(zip(lo, hi)), constraints=[cons],
                     options={"ftol": 1e-14, "maxiter": 500}) for x0 in (w0, [1.0, 1.3], [2.0, 1.1])]
    ref = min((r for r in refs if r.success), key=lambda r: r.fun)
    print("trust region", best.w, best.f, len(done), "evaluations; SLSQP", ref.x, ref.fun)
    assert best.f == pytest.approx(ref.fun, abs=1e-7)
    np.testing.assert_allclose(best.w, ref.x, atol=1e-3)
    assert limit(best.w)[0][0] == pytest.approx(bound, abs=1e-6)        # active: on the limit


@pytest.mark.parametrize("objective", ["in_band", "expected_abs_miss"])
def test_symbolic_terms_equal_the_numeric_ones(objective):
    """The model problem's CasADi terms (erf) and the exact evaluations' NumPy terms (ndtr) are
    one function: equal to rounding, so the ratio test compares like with like."""
    import casadi as ca

    a = 3000 + 80 * np.random.default_rng(1).standard_normal(50)
    x = ca.SX.sym("a", a.size)
    f = ca.Function("terms", [x], [symbolic_terms(x, 3020.0, objective, 50.0, 22.0)])
    np.testing.assert_allclose(np.array(f(a)).ravel(), smoothed_terms(a, 3020.0, objective, 50.0, 22.0)[0],
                               rtol=1e-12, atol=1e-15)
