"""Illinois regula falsi (ironbark_opt.roots) against analytic roots."""
import math

import pytest

from ironbark_opt.roots import illinois


def test_converges_where_plain_false_position_stalls():
    """exp(x) - 2 on [0, 3]: convex, plain regula falsi keeps the right end for ever and
    converges linearly; Illinois reaches ln 2 to 1e-12 in a dozen evaluations."""
    calls = []

    def f(x):
        calls.append(x)
        return math.exp(x) - 2.0, x * x
    x, g, payload, n, ok = illinois(f, 0.0, -1.0, 3.0, math.exp(3.0) - 2.0, gtol=1e-12, xtol=0.0)
    assert ok and x == pytest.approx(math.log(2.0), abs=1e-12) and payload == x * x
    assert n == len(calls) <= 15


def test_best_point_and_failure_flag():
    """``best`` returns the evaluated point of smallest |g|; an exhausted budget says so."""
    f = lambda x: (x ** 3 - 2.0, None)          # noqa: E731
    last = illinois(f, 0.0, -2.0, 2.0, 6.0, gtol=0.0, xtol=0.0, max_iter=4)
    best = illinois(f, 0.0, -2.0, 2.0, 6.0, gtol=0.0, xtol=0.0, max_iter=4, best=True)
    assert not last[4] and not best[4] and last[3] == best[3] == 4
    assert abs(best[1]) <= abs(last[1])
    assert abs(best[0] - 2 ** (1 / 3)) < 0.2
