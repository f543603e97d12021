"""Bracketed scalar root finding shared by the numeric event and ballast solves.

Numeric-only.
"""
from __future__ import annotations

from typing import Any, Callable


def illinois(f: Callable[[float], tuple[float, Any]], x0: float, g0: float, x1: float, g1: float, *,
             gtol: float, xtol: float, max_iter: int = 60, best: bool = False):
    """Root of ``g`` between ``x0`` and ``x1`` by Illinois regula falsi (Dowell &
    Jarratt, BIT 11, 1971): the false-position point replaces the end of its sign, and
    an end kept twice in a row has its value halved.

    Parameters
    ----------
    f : callable ``x -> (g, payload)``
        The residual and whatever the caller keeps from that evaluation (states, a run).
    x0, g0, x1, g1 : float
        A bracket: ``g0`` and ``g1`` of opposite signs.
    gtol, xtol : float
        Stop when ``|g| <= gtol`` or the bracket is at most ``xtol`` wide.
    max_iter : int
        Evaluations of ``f`` at most.
    best : bool
        Return the evaluated point of smallest ``|g|`` instead of the last one.

    Returns
    -------
    (x, g, payload, evaluations, converged)
    """
    side, kept, last = 0, None, None
    for n in range(1, max_iter + 1):
        x = x1 - g1 * (x1 - x0) / (g1 - g0)
        g, payload = f(x)
        last = (x, g, payload)
        if kept is None or abs(g) < abs(kept[1]):
            kept = last
        if abs(g) <= gtol or abs(x1 - x0) <= xtol:
            return (*(kept if best else last), n, True)
        if (g > 0) == (g1 > 0):
            x1, g1 = x, g
            if side == 1:
                g0 *= 0.5
            side = 1
        else:
            x0, g0 = x, g
            if side == -1:
                g1 *= 0.5
            side = -1
    return (*(kept if best else last), max_iter, False)
