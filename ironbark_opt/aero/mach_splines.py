"""Several cubic splines of Mach number as one B-spline with several outputs (speed).

The flight step reads, at each RK4 stage, the tabulated lift sums of
:class:`~ironbark_opt.aero.model.AeroModel` (one B-spline over
``LIFT_MACH_GRID``) and a Mach-only drag table (``CA``, ``CA_power_on``: a
B-spline over the drag curve's own Mach grid), each clamped to its own grid.
Each call searches its knot vector and runs de Boor's recursion (de Boor,
*A Practical Guide to Splines*, 1978, ch. X), which measured ~45 % of a
compiled Calisto trajectory (callgrind).

A spline is unchanged by knot insertion (Boehm, "Inserting new knots into
B-spline curves", Computer-Aided Design 12, 1980): on the union of the knot
vectors every one of these splines is a B-spline again, and a knot of full
multiplicity (degree + 1) at each end of a curve's own grid lets it continue
as the constant it is clamped to.  So one B-spline on the union knots, with
one output per curve, equals every curve (with its clamping) to rounding: one
knot search and one basis evaluation per stage serve all of them.

Its coefficients are fitted (least squares on 4 points inside every knot
interval, exact because each curve lies in the spline space; banded normal
equations with one step of iterative refinement) to the curves' own CasADi
B-splines, so it reproduces the splines the flight used before (measured
~1e-15 relative, ``tests/unit/test_mach_splines.py``).

Compiled code (C) reads the same splines in piecewise-polynomial form instead
(:func:`table_form`, de Boor, ch. VII: between consecutive knots a cubic spline
is one cubic polynomial): an interval search and one Horner evaluation per
output, ~1/6 of the B-spline's de Boor recursion in C (callgrind).  Its table of coefficients is
a constant that the CasADi virtual machine would copy on every call (~17,000
numbers), so the VM keeps the B-spline; both agree to ~1e-15.
"""
from __future__ import annotations

from collections.abc import Sequence
from contextlib import contextmanager

import casadi as ca
import numpy as np

DEGREE = 3
#: the form :func:`merged_spline` builds: "bspline" (default) or "pp" (see :func:`table_form`)
_FORM = ["bspline"]


@contextmanager
def table_form(form: str):
    """Inside this block :func:`merged_spline` (and so the flight's right-hand sides
    built meanwhile) uses ``form``: "pp", the piecewise-polynomial table for generated
    C code, or "bspline"."""
    if form not in ("bspline", "pp"):
        raise ValueError(f"form must be 'bspline' or 'pp', got {form!r}")
    _FORM.append(form)
    try:
        yield
    finally:
        _FORM.pop()


def current_form() -> str:
    """The form :func:`merged_spline` builds now (see :func:`table_form`)."""
    return _FORM[-1]


def spline_knots(grid: np.ndarray, degree: int = DEGREE) -> np.ndarray:
    """Knots of CasADi's interpolating ``bspline`` through ``grid`` (not-a-knot):
    the ends ``degree + 1`` times, the interior grid points but the second and the
    second-to-last."""
    g = np.asarray(grid, dtype=float)
    return np.r_[[g[0]] * (degree + 1), g[2:-2], [g[-1]] * (degree + 1)]


def merged_spline(name: str, grids: Sequence[np.ndarray],
                  curves: Sequence[ca.Function]) -> tuple[ca.Function, float, float]:
    """One B-spline Function ``mach -> (outputs of every curve)`` on ``[lo, hi]``, the
    union of the grids, and ``(lo, hi)`` (callers clamp to them).

    Parameters
    ----------
    grids : sequence of 1-D arrays
        The Mach grid of each curve (4 or more points: cubic).
    curves : sequence of casadi.Function
        ``mach -> values (m_k)``: CasADi's cubic ``bspline`` interpolant through
        the data on the matching grid, evaluated inside it (clamped here).
    """
    grids = [np.asarray(g, dtype=float).ravel() for g in grids]
    lo, hi = min(g[0] for g in grids), max(g[-1] for g in grids)
    mult: dict[float, int] = {}
    for g in grids:
        for k in spline_knots(g)[DEGREE + 1:-DEGREE - 1]:
            mult[float(k)] = max(mult.get(float(k), 0), 1)
        for end in (g[0], g[-1]):           # the curve's ends: free to switch to its clamped constant
            if lo < end < hi:
                mult[float(end)] = DEGREE + 1
    interior = [k for k in sorted(mult) for _ in range(mult[k])]
    knots = np.r_[[lo] * (DEGREE + 1), interior, [hi] * (DEGREE + 1)]
    edges = np.unique(knots)
    # 4 points inside every knot interval (Chebyshev nodes of its cubic piece), where
    # 4 B-splines are non-zero: a banded least-squares problem, solved by its normal
    # equations and one step of iterative refinement
    u = (1 - np.cos((2 * np.arange(DEGREE + 1) + 1) * np.pi / (2 * DEGREE + 2))) / 2
    x = (edges[:-1, None] + np.diff(edges)[:, None] * u[None, :]).ravel()
    target = np.vstack([np.array(f(np.clip(x, g[0], g[-1])[None, :])).reshape(-1, x.size)
                        for g, f in zip(grids, curves)]).T                      # (N, m)
    if current_form() == "pp":
        return _piecewise_cubic(name, edges, u, target), float(lo), float(hi)
    first, vals = _basis_rows(knots, x)                                         # (N,), (N, 4)
    n = knots.size - DEGREE - 1
    cols = first[:, None] + np.arange(DEGREE + 1)[None, :]
    band = np.zeros((n, DEGREE + 1))            # band[j, k - j + 3] = (B^T B)[j, k], k = j-3..j
    for r in range(DEGREE + 1):
        for c in range(r + 1):
            np.add.at(band, (cols[:, r], c - r + DEGREE), vals[:, r] * vals[:, c])

    def apply(c):
        return np.einsum("nk,nkm->nm", vals, c[cols])

    def normal(r):
        out = np.zeros((n, r.shape[1]))
        np.add.at(out, cols, vals[:, :, None] * r[:, None, :])
        return out
    factor = _band_ldl(band)
    coef = _band_solve(factor, normal(target))
    coef = coef + _band_solve(factor, normal(target - apply(coef)))
    # never inlined: an SX graph calls it as one node (its B-spline is an MX node)
    fn = ca.Function.bspline(name, [knots.tolist()], coef.ravel().tolist(), [DEGREE], coef.shape[1],
                             {"lookup_mode": ["binary"], "never_inline": True})
    return fn, float(lo), float(hi)


def _piecewise_cubic(name: str, edges: np.ndarray, s: np.ndarray, target: np.ndarray) -> ca.Function:
    """``mach -> (outputs of every curve)`` as one cubic per interval of ``edges`` (every
    curve is one cubic there): coefficients fitted to the curves' values ``target``
    ((4 n, m), at the 4 Chebyshev nodes ``s`` of each interval, as :func:`merged_spline`
    samples them; a 4 x 4 Vandermonde solve in s = (x - a) / h, exact to rounding),
    evaluated by an interval search (binary) and Horner's rule in u = x - a, all outputs
    at once.

    The search stays binary: a constant-time bucket index (CasADi's equidistant ``low``
    on ~1200 buckets, then at most two comparisons; the same intervals to the bit) cut
    the compiled Calisto ascent from 2.92e6 to 2.72e6 instructions (callgrind) but took
    ~10 % more time (1000 samples, one thread, 4 paired runs): its float-to-index chain
    (divide, truncate, load, compare, truncate, load) is one long dependency, while the
    binary search's branches are predicted well (the Mach number moves little between
    calls)."""
    h = np.diff(edges)
    values = target.T                                                        # (m, 4 n)
    m, n = values.shape[0], edges.size - 1
    vander = np.vander(s, DEGREE + 1, increasing=True)
    local = np.linalg.solve(vander, values.reshape(m, n, DEGREE + 1).transpose(2, 1, 0).reshape(DEGREE + 1, -1))
    coef = local.reshape(DEGREE + 1, n, m) / h[None, :, None] ** np.arange(DEGREE + 1)[:, None, None]
    # one column per interval: its left edge, then the coefficients of u^3, u^2, u, 1 (m each)
    table = np.vstack([edges[:-1][None, :], coef[::-1].transpose(0, 2, 1).reshape(m * (DEGREE + 1), n)])
    mach = ca.MX.sym("mach")
    i = ca.low(ca.DM(edges), mach, {"lookup_mode": "binary"})   # interval, clamped to [0, n - 1]
    col = ca.MX(ca.DM(table))[:, i]
    u = mach - col[0]
    out = []
    for k in range(m):                 # scalar Horner per output: register code in C
        y = col[1 + k]
        for j in range(1, DEGREE + 1):
            y = y * u + col[1 + j * m + k]
        out.append(y)
    return ca.Function(name, [mach], [ca.vertcat(*out)], {"never_inline": True})


def _band_ldl(band: np.ndarray) -> tuple[list, list]:
    """``A = L D L^T`` of a symmetric positive-definite banded matrix given by its lower
    band (``band[j, k - j + p] = A[j, k]``, ``p = band.shape[1] - 1``); ``L`` in the same
    layout.  A few hundred rows: plain loops (no BLAS threads)."""
    n, p = band.shape[0], band.shape[1] - 1
    a = band.tolist()
    low = [[0.0] * p for _ in range(n)]
    d = [0.0] * n
    for j in range(n):
        for k in range(max(0, j - p), j):
            s = a[j][k - j + p]
            for i in range(max(0, j - p), k):
                s -= low[j][i - j + p] * low[k][i - k + p] * d[i]
            low[j][k - j + p] = s / d[k]
        s = a[j][p]
        for k in range(max(0, j - p), j):
            s -= low[j][k - j + p] ** 2 * d[k]
        d[j] = s
    return low, d


def _band_solve(factor: tuple[list, list], b: np.ndarray) -> np.ndarray:
    """Solve ``L D L^T x = b`` (``factor`` from :func:`_band_ldl`) for the columns of ``b``."""
    low, d = factor
    n, p = len(d), len(low[0])
    y = np.array(b, dtype=float).T.tolist()                   # one list per right-hand side
    for col in y:
        for j in range(n):
            s = col[j]
            for k in range(max(0, j - p), j):
                s -= low[j][k - j + p] * col[k]
            col[j] = s
        for j in range(n):
            col[j] /= d[j]
        for j in range(n - 1, -1, -1):              # L^T x = D^-1 L^-1 b
            s = col[j]
            for k in range(j + 1, min(n, j + p + 1)):
                s -= low[k][j - k + p] * col[k]
            col[j] = s
    return np.array(y).T


def _basis_rows(knots: np.ndarray, x: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """For each ``x`` strictly inside a knot interval ``[t_i, t_i+1)``: ``i - 3`` (the first
    non-zero B-spline) and the 4 non-zero cubic B-spline values (Cox-de Boor recursion)."""
    i = np.searchsorted(knots, x, side="right") - 1
    b = np.zeros((x.size, DEGREE + 1))
    b[:, 0] = 1.0
    for k in range(1, DEGREE + 1):              # de Boor, ch. X, algorithm BSPLVB
        new = np.zeros_like(b)
        for r in range(k):
            tl = knots[i + r + 1 - k]
            tr = knots[i + r + 1]
            w = b[:, r] / (tr - tl)
            new[:, r] += (tr - x) * w
            new[:, r + 1] += (x - tl) * w
        b = new
    return i - DEGREE, b
