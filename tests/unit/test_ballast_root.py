"""The one-variable ballast root (optimise/ballast._mass_root) on apogee curves with
known roots: the regula falsi must land within its 1e-6 m tolerance of the analytic
ballast, keep to the bracket, and report the flights it flew."""
import math

import numpy as np
import pytest

from ironbark_opt.optimise.ballast import ROOT_TOL_M, _mass_root


def _solve(apogee, target, m_max):
    flown = []

    def fly(m):
        flown.append(m)
        return {"x_apogee": np.array([0.0, 0.0, apogee(m)])}
    lo, hi = (0.0, fly(0.0)), (m_max, fly(m_max))
    frac = (apogee(0.0) - target) / (apogee(0.0) - apogee(m_max))
    guess = (frac * m_max, fly(frac * m_max))
    m, run, n = _mass_root(fly, target, lo, hi, guess)
    return m, run, n, flown


@pytest.mark.parametrize("name, apogee, root", [
    # apogee(m) = 3300 - 190 m + 4 m^2 (Calisto-like slope): root of 4 m^2 - 190 m + 300 = 0
    ("quadratic", lambda m: 3300.0 - 190.0 * m + 4.0 * m * m, (190.0 - math.sqrt(190.0 ** 2 - 4 * 4 * 300)) / 8),
    # strongly convex: apogee(m) = 3000 exp(-m) + 500, target 1500 -> m = ln 3
    ("exponential", lambda m: 3000.0 * math.exp(-m) + 500.0, math.log(3.0)),
])
def test_root_matches_the_analytic_ballast(name, apogee, root):
    target = apogee(root)
    m, run, n, flown = _solve(apogee, target, 5.0)
    print(f"{name}: ballast {m:.12f} kg (analytic {root:.12f}), apogee error {run['x_apogee'][2] - target:.1e} m, "
          f"{n} flights after the bracket")
    assert abs(run["x_apogee"][2] - target) <= ROOT_TOL_M
    assert abs(m - root) < 1e-6                              # 1e-6 m over slopes >= 190 m/kg: < 1e-8 kg
    assert all(0.0 <= x <= 5.0 for x in flown)
    assert n < 15


def test_guess_on_target_is_taken_without_another_flight():
    m, run, n, flown = _solve(lambda m: 3000.0 - 100.0 * m, 2800.0, 4.0)     # linear: the guess is exact
    assert m == pytest.approx(2.0, abs=1e-12) and n == 1 and len(flown) == 3
