"""Compiled panel-influence kernels (Numba), one scalar loop per point-panel pair.

The formulas are those of :mod:`.influence` (Laplace source and doublet:
Van Oosterom & Strackee 1983 eq. (8), Newman 1986 eq. (2.8)-(2.9)) and
:mod:`.supersonic_influence` (supersonic source with the Mach-cone domain of
dependence); those modules keep the vectorised NumPy implementations as the
reference (``backend="numpy"``) and the fallback when Numba is missing.  The
kernels follow the NumPy code branch for branch (a ``np.where`` becomes an
``if`` on the branch NumPy keeps) and sum in the same order, so the two agree
bitwise on this machine (tests/unit/test_panair_kernels.py asserts 1e-12
relative on the matrices and forces; the Kestrel table is byte-identical).
Caveat: the supersonic potential was sensitive to rounding where an edge meets
the Mach cone (sqrt of a vanishing R: a single-ulp difference in a dot product
moved some coefficients by up to ~1e-6 relative); sqrt(R) is now exactly 0 at a
root inside the edge, but the kernel still reproduces NumPy's einsum order for
3-vectors ((x + z) + y, measured here), which another NumPy build or CPU could
change.

Measured (Kestrel, 2352 / 3072 panels, CPU s per Mach number, loaded 2-core
machine): subsonic setup 5.4 -> ~2.5 s (LU 0.5 s), supersonic 50.8 -> 11-14 s
(LU 0.7-1.1 s); the one-off compile of both kernels 4-11 s CPU (first build
with an empty cache 69.9 / 69.2 s CPU against 65.7 / 58.1 s with it, two runs).
Later (session 14), the supersonic pair kernel with its helpers inlined and without the
sqrt and libm calls a value already known makes redundant (see :func:`_pair`,
:func:`_in_cone`): 0.57-0.69x its time on the Kestrel's Mach 1.2-2 matrices, bitwise the
same coefficients.  The Laplace kernel is bound by its 2 atan2 + 4 log per pair (the
same loop with those calls replaced by arithmetic: ~0.35x its time).

Why Numba (and not CasADi code generation or a C kernel built with the
system compiler):

* the work is branchy scalar code — the supersonic kernel clips each edge
  to the part of it inside the upstream Mach cone, chooses one of three
  forms of the edge integral per sub-interval and skips the point-panel pairs outside the
  domain of dependence.  Compiled scalar loops do exactly the arithmetic
  NumPy's masked arrays do without their temporaries (the NumPy path spends
  most of its time allocating, sorting and masking (m, n, 4) arrays);
  CasADi's ``if_else`` evaluates both branches and its generated code has
  no data-dependent pair skipping;
* Numba is a maintained library (NumFOCUS-sponsored, releases follow NumPy:
  0.68 supports this venv's NumPy 2.4 without a downgrade), ships its own
  LLVM in the wheel (no C compiler needed on the user's machine, unlike
  cffi/ctypes + gcc or CasADi's codegen), and ``cache=True`` keeps the
  machine code on disk next to this module (``__pycache__``), so a build
  compiles once per installation, not per process;
* the kernels stay Python source next to the NumPy reference, readable
  by whoever checks the physics.

Serial kernels (no ``parallel=True``): ``panair.sweep`` already runs one
Mach number per process.

The supersonic solver calls :func:`supersonic_source_pair`: both finite-difference
potentials (and the half model's mirror images) in one pass, the pairs a fin
separates skipped instead of computed and zeroed, rows aft first, stopping at the
first row with a non-finite coefficient (such a system is not solved: the Mach
number goes to local inclination, so the rest of the matrix was wasted; measured
on Defiance Mk. IV at Mach 1.5, 6947 panels: 18.8 s CPU to the failure instead of
~31 s for the whole matrix).  Same values bitwise as the separate calls (measured:
the Calisto Mach 1.5 solution's CA, CN, Cm and Cp identical); the one pass itself
is not faster (the pair integrals dominate; measured equal within the noise).
:func:`dense_to_csc` builds the causal LU's permuted sparse matrix (scipy's
dense -> COO -> CSC -> fancy-indexing path took 1-4 s CPU at 5000-7000 panels).

Numeric-only.
"""
from __future__ import annotations

import math
import os

import numpy as np

__all__ = ["HAVE_NUMBA", "use_compiled", "laplace_influence", "supersonic_source",
           "supersonic_source_pair", "dense_to_csc", "fold_columns",
           "fold_difference", "warm_up"]

try:                                     # pragma: no cover - depends on the environment
    if os.environ.get("IRONBARK_NO_NUMBA"):
        raise ImportError("IRONBARK_NO_NUMBA set")
    from numba import njit
    HAVE_NUMBA = True
except ImportError:                      # pragma: no cover
    HAVE_NUMBA = False

    def njit(*args, **kwargs):
        """Stand-in decorator: the functions stay plain Python (never called
        by the solvers, which use the NumPy path without Numba)."""
        if args and callable(args[0]):
            return args[0]
        return lambda f: f

_FOUR_PI = 4.0 * math.pi
_TWO_PI = 2.0 * math.pi
_SQRT2 = math.sqrt(2.0)


def use_compiled(backend: str) -> bool:
    """True when ``backend`` ("auto", "compiled", "numpy") selects the kernels."""
    if backend not in ("auto", "compiled", "numpy"):
        raise ValueError(f"backend must be 'auto', 'compiled' or 'numpy', got {backend!r}")
    if backend == "compiled" and not HAVE_NUMBA:
        raise ImportError("backend='compiled' needs numba")
    return backend != "numpy" and HAVE_NUMBA


# ---------------------------------------------------------------- Laplace (subsonic)

# error_model="numpy": a float division by zero gives inf/nan as in the NumPy reference
# (which masks such entries afterwards) instead of raising ZeroDivisionError (Numba's
# default "python" model; it stopped a real rocket's supersonic build)
@njit(cache=True, nogil=True, error_model="numpy")
def _tri_angle(Rx, Ry, Rz, r, i, j, k, dij, dik, djk):
    """2 x signed solid angle term of triangle (i, j, k): Van Oosterom & Strackee eq. (8)."""
    num = (Rx[i] * (Ry[j] * Rz[k] - Rz[j] * Ry[k])
           + Ry[i] * (Rz[j] * Rx[k] - Rx[j] * Rz[k])
           + Rz[i] * (Rx[j] * Ry[k] - Ry[j] * Rx[k]))
    rrr = r[i] * r[j] * r[k]
    if abs(num) <= 1e-13 * (rrr + 1e-300):
        return 0.0
    den = rrr + dij * r[k] + dik * r[j] + djk * r[i]
    return 2.0 * math.atan2(num, den)


@njit(cache=True, nogil=True, error_model="numpy")
def laplace_influence(points, qx, qy, qz, nux, nuy, nuz, normal, L, ok_edge, D, S, add):
    """Doublet ``D`` and source ``S`` influence (m, n) of flat quads on points (m, 3).

    ``qx, qy, qz``, ``nux, nuy, nuz``, ``L``, ``ok_edge``: (4, n) corners, in-plane
    edge normals, edge lengths and usable edges, as prepared by
    :func:`panair.solver.influence.influence_matrices`.  With ``add`` the values
    are added to ``D`` and ``S``."""
    m = points.shape[0]
    n = qx.shape[1]
    Rx = np.empty(4)
    Ry = np.empty(4)
    Rz = np.empty(4)
    r = np.empty(4)
    for i in range(m):
        px, py, pz = points[i, 0], points[i, 1], points[i, 2]
        for j in range(n):
            for k in range(4):
                Rx[k] = qx[k, j] - px
                Ry[k] = qy[k, j] - py
                Rz[k] = qz[k, j] - pz
                r[k] = math.sqrt(Rx[k] ** 2 + Ry[k] ** 2 + Rz[k] ** 2)
            d02 = Rx[0] * Rx[2] + Ry[0] * Ry[2] + Rz[0] * Rz[2]
            d03 = Rx[0] * Rx[3] + Ry[0] * Ry[3] + Rz[0] * Rz[3]
            d32 = Rx[3] * Rx[2] + Ry[3] * Ry[2] + Rz[3] * Rz[2]
            d01 = Rx[0] * Rx[1] + Ry[0] * Ry[1] + Rz[0] * Rz[1]
            d21 = Rx[2] * Rx[1] + Ry[2] * Ry[1] + Rz[2] * Rz[1]
            # triangles (Q1, Q4, Q3) and (Q1, Q3, Q2)
            om = 0.0
            om += _tri_angle(Rx, Ry, Rz, r, 0, 3, 2, d03, d02, d32)
            om += _tri_angle(Rx, Ry, Rz, r, 0, 2, 1, d02, d01, d21)
            dmat = -om / _FOUR_PI
            integral = 0.0
            for k in range(4):
                k1 = (k + 1) % 4
                d = -(Rx[k] * nux[k, j] + Ry[k] * nuy[k, j] + Rz[k] * nuz[k, j])
                if ok_edge[k, j] and abs(d) > 1e-14:
                    rs = r[k] + r[k1]
                    lo = rs - L[k, j]
                    if lo < 1e-300:
                        lo = 1e-300
                    integral += d * math.log((rs + L[k, j]) / lo)
            z = -(Rx[0] * normal[j, 0] + Ry[0] * normal[j, 1] + Rz[0] * normal[j, 2])
            integral -= abs(z) * abs(om)
            if add:
                S[i, j] -= integral / _FOUR_PI
                D[i, j] += dmat
            else:
                S[i, j] = -integral / _FOUR_PI
                D[i, j] = dmat


# ---------------------------------------------------------------- supersonic source

@njit(cache=True, nogil=True, error_model="numpy", inline="always")
def _edge_term(ta, tb, s_a, s_b, a, q, b, h, delta):
    """delta * Integral_ta^tb sqrt(R) / (R + H2) dtau, R = a tau^2 + b tau + c, over
    one sub-interval with sqrt(R) = s_a, s_b at its ends: the scalar form of
    :func:`panair.solver.supersonic_influence._edge_term` (derivation, sources and
    the continuity at a sonic edge, a = 0, and at delta = 0 there).  ``q`` =
    sqrt(|a|) (per panel edge) and ``h`` = sqrt(H2) (per point-panel pair) are the
    caller's: the same values, not computed again for every sub-interval."""
    if delta == 0.0:
        return 0.0
    dt = tb - ta
    S = s_a + s_b
    x = q * dt / S if S > 0 else math.inf
    ga = a * ta + 0.5 * b
    gb = a * tb + 0.5 * b
    if x < 1e-4:
        j0 = 2.0 * dt / S * (1.0 + math.copysign(x * x, a) / 3.0)
    elif a > 0:
        if x < 0.5:
            j0 = 2.0 * dt / S * (math.atanh(x) / x)
        else:
            gm = a * (0.5 * (ta + tb)) + 0.5 * b
            j0 = (math.copysign(1.0, gm)
                  * math.log((q * s_b + abs(gb) + 1e-300) / (q * s_a + abs(ga) + 1e-300)) / q)
    else:
        j0 = 2.0 * math.atan2(q * dt, S) / q
    ad = abs(delta)
    ek = math.copysign(h, delta) * (math.atan2(ad * s_b, h * gb) - math.atan2(ad * s_a, h * ga))
    return delta * j0 - ek


@njit(cache=True, nogil=True, error_model="numpy", inline="always")
def _end_sqrt(has, raw, clipped, Lb, s0, sL):
    """sqrt(R) at a sub-interval end of a panel edge: 0 at a root of R inside the edge
    (``raw``, the root; ``has``: R has real roots), else the value at the edge end the
    root was clipped to (``clipped`` = 0 or Lb), ``s0`` or ``sL``."""
    if has and 0.0 < raw < Lb:
        return 0.0
    return s0 if clipped == 0.0 else sL


@njit(cache=True, nogil=True, error_model="numpy", inline="always")
def _pair(px, py, pz, j, q0, normal, e1, e2, g1, sg, e1x_nx, uk, tk, L, okL, ep_all, eq_all,
          nup_all, nuq_all, a_all, qa_all):
    """Scalar form of :func:`panair.solver.supersonic_influence._pair_potential`
    (``qa_all`` = sqrt(|a_all|))."""
    dx, dy, dz = px - q0[j, 0], py - q0[j, 1], pz - q0[j, 2]
    # summed in the order of NumPy's einsum ("kj,kj->k": (x + z) + y), the reference's:
    # the potential is sensitive to rounding near the Mach cone (sqrt of a vanishing R)
    h = (dx * normal[j, 0] + dz * normal[j, 2]) + dy * normal[j, 1]
    d1 = (dx * e1[j, 0] + dz * e1[j, 2]) + dy * e1[j, 1]
    d2 = (dx * e2[j, 0] + dz * e2[j, 2]) + dy * e2[j, 1]
    gj = g1[j] if g1[j] > 1e-12 else 1e-12
    sgj = sg[j]
    U = sgj * (d1 + 2.0 * e1x_nx[j] * h / gj)
    H2 = h * h / gj
    hs = math.sqrt(H2)
    integral = 0.0
    for k in range(4):
        pk = U - uk[j, k]
        qk = d2 - tk[j, k]
        ep, eq = ep_all[j, k], eq_all[j, k]
        delta = pk * nup_all[j, k] + qk * nuq_all[j, k]
        a = a_all[j, k]
        b = 2.0 * (pk * ep - qk * eq)
        c = pk * pk - qk * qk - H2
        Lb = L[j, k]
        # real roots, cancellation-free (supersonic_influence._roots)
        disc = b * b - 4.0 * a * c
        has = disc >= 0
        r1 = 0.0
        r2 = 0.0
        if has:
            qq = -0.5 * (b + math.copysign(math.sqrt(disc), b))
            r2 = c / qq if qq != 0 else 0.0
            r1 = qq / a if a != 0 else r2
        lo_raw = min(r1, r2)
        hi_raw = max(r1, r2)
        lo = min(max(lo_raw, 0.0), Lb)
        hi = min(max(hi_raw, 0.0), Lb)
        # sqrt(R) at the sub-interval ends: exactly 0 at a root inside the edge; lo (hi)
        # is otherwise clipped to 0 or Lb (no real root: lo = hi = 0), where R is the
        # same expression as at the edge's ends, so sqrt(R) there is s0 or sL, bit for
        # bit (R(0) = a*0 + b*0 + c = c exactly: c is never -0)
        s0 = math.sqrt(max(c, 0.0))
        sL = math.sqrt(max(a * (Lb * Lb) + b * Lb + c, 0.0))
        s_lo = _end_sqrt(has, lo_raw, lo, Lb, s0, sL)
        s_hi = _end_sqrt(has, hi_raw, hi, Lb, s0, sL)
        # sub-intervals [0, lo], [lo, hi], [hi, Lb]; the part inside the upstream
        # Mach cone is one of them (the cone is convex); as NumPy: the last valid one,
        # so they are tried from the last and only that one is integrated
        total = 0.0
        for s in range(2, -1, -1):
            ta = 0.0 if s == 0 else (lo if s == 1 else hi)
            tb = lo if s == 0 else (hi if s == 1 else Lb)
            mid = 0.5 * (ta + tb)
            if (tb - ta > 1e-15 * (1 + Lb)) and (a * (mid * mid) + b * mid + c > 0) \
                    and (pk + ep * mid > 0):
                sa_ = s0 if s == 0 else (s_lo if s == 1 else s_hi)
                sb_ = s_lo if s == 0 else (s_hi if s == 1 else sL)
                total = _edge_term(ta, tb, sa_, sb_, a, qa_all[j, k], b, hs, delta)
                break
        if okL[j, k]:
            integral += total
    integral = integral / sgj
    return -integral / _TWO_PI


@njit(cache=True, nogil=True, error_model="numpy", inline="always")
def _in_cone(ex, ey, ez, thr):
    """The bounding-sphere test of a source panel: ``(hypot(ey, ez) - ex) / sqrt(2) <
    thr``, ``thr`` = its radius (1 + 1e-9) + 1e-12 (outside: the sphere is outside the
    upstream Mach cone, 45 deg in scaled coordinates, no influence).  Decided with
    sqrt(ey^2 + ez^2) (a few ulps from hypot, a quarter of its cost) unless the two
    sides are within 1e-13 relative of each other, where libm's hypot decides: the
    same outcome as hypot's test for every pair."""
    t = math.sqrt(ey * ey + ez * ez)
    d = (t - ex) / _SQRT2
    tol = 1e-13 * (t + abs(ex)) + 1e-150
    if d < thr - tol:
        return True
    if d > thr + tol:
        return False
    return (math.hypot(ey, ez) - ex) / _SQRT2 < thr


@njit(cache=True, nogil=True, error_model="numpy")
def supersonic_source(points, cen, rho, q0, normal, e1, e2, g1, sg, e1x_nx, uk, tk, L, okL,
                      ep_all, eq_all, nup_all, nuq_all, a_all, out):
    """Potential per unit source strength (m, n) into ``out`` (zeros outside each
    point's upstream Mach cone); inputs as prepared by
    :func:`panair.solver.supersonic_influence.source_potential`."""
    m = points.shape[0]
    n = cen.shape[0]
    qa_all = np.sqrt(np.abs(a_all))
    thr = rho * (1 + 1e-9) + 1e-12
    for i in range(m):
        px, py, pz = points[i, 0], points[i, 1], points[i, 2]
        for j in range(n):
            # bounding sphere outside the upstream Mach cone (45 deg scaled): no influence
            if _in_cone(px - cen[j, 0], py - cen[j, 1], pz - cen[j, 2], thr[j]):
                out[i, j] = _pair(px, py, pz, j, q0, normal, e1, e2, g1, sg, e1x_nx, uk, tk, L,
                                  okL, ep_all, eq_all, nup_all, nuq_all, a_all, qa_all)
            else:
                out[i, j] = 0.0


@njit(cache=True, nogil=True, error_model="numpy")
def supersonic_source_pair(p0, p1, mirror, rows, recv, recv_m, src_fin, src_side, cen, rho, q0, normal,
                           e1, e2, g1, sg, e1x_nx, uk, tk, L, okL, ep_all, eq_all, nup_all,
                           nuq_all, a_all, out0, out1):
    """The two potentials of the supersonic solver in one pass: at the points ``p0``
    and ``p1`` (m, 3) into ``out0`` and ``out1`` (m, n), each the direct value, 0 for
    a source-receiver pair separated by a fin (``recv`` (n_fins, m) receiver side,
    ``src_fin`` (n,) the source's fin or -1, ``src_side`` (n,) its side; see
    :func:`panair.solver.supersonic._fin_sides`), plus with ``mirror`` the value at
    the mirror image (x, -y, z), 0 for a pair separated by a fin there (``recv_m``
    the mirror images' sides, :func:`panair.solver.supersonic._mirror_sides`) — the
    same operations in the same order as :func:`supersonic_source` then
    ``out[shadow] = 0`` then ``out += mirror`` (its shadowed pairs 0).

    Rows are computed in the order ``rows``; the first row with a non-finite value
    stops the pass and is returned (its system has no solution: the caller raises),
    else -1."""
    n = cen.shape[0]
    qa_all = np.sqrt(np.abs(a_all))
    thr = rho * (1 + 1e-9) + 1e-12
    pts = np.empty((4, 3))
    val = np.empty(4)
    npts = 4 if mirror else 2
    for i in rows:
        for k in range(3):
            pts[0, k] = p0[i, k]
            pts[1, k] = p1[i, k]
            pts[2, k] = p0[i, k]
            pts[3, k] = p1[i, k]
        pts[2, 1] = p0[i, 1] * -1.0
        pts[3, 1] = p1[i, 1] * -1.0
        bad = False
        for j in range(n):
            f = src_fin[j]
            shadow = f >= 0 and recv[f, i] * src_side[j] < 0
            shadow_m = f >= 0 and recv_m[f, i] * src_side[j] < 0
            for k in range(npts):
                val[k] = 0.0
                if (k < 2 and shadow) or (k >= 2 and shadow_m):
                    continue
                px, py, pz = pts[k, 0], pts[k, 1], pts[k, 2]
                # bounding sphere outside the upstream Mach cone (45 deg scaled): no influence
                if _in_cone(px - cen[j, 0], py - cen[j, 1], pz - cen[j, 2], thr[j]):
                    val[k] = _pair(px, py, pz, j, q0, normal, e1, e2, g1, sg, e1x_nx, uk, tk, L,
                                   okL, ep_all, eq_all, nup_all, nuq_all, a_all, qa_all)
            v0 = val[0]
            v1 = val[1]
            if mirror:
                v0 += val[2]
                v1 += val[3]
            out0[i, j] = v0
            out1[i, j] = v1
            if not (math.isfinite(v0) and math.isfinite(v1)):
                bad = True
        if bad:
            return i
    return -1


@njit(cache=True, nogil=True)
def dense_to_csc(A, order):
    """CSC arrays (data, indices, indptr) of ``A[order][:, order]`` without its zeros,
    row indices ascending in each column (as ``scipy.sparse.csc_matrix`` of the
    permuted dense matrix holds them), in two row-wise passes over ``A``."""
    n = len(order)
    inv = np.empty(n, np.int64)
    for c in range(n):
        inv[order[c]] = c
    indptr = np.zeros(n + 1, np.int64)
    for r in range(n):
        for c in range(n):
            if A[r, c] != 0.0:
                indptr[inv[c] + 1] += 1
    for c in range(n):
        indptr[c + 1] += indptr[c]
    cursor = indptr[:n].copy()
    data = np.empty(indptr[n])
    indices = np.empty(indptr[n], np.int32)
    for r in range(n):                   # permuted rows in ascending order
        row = order[r]
        for c in range(n):
            v = A[row, c]
            if v != 0.0:
                k = cursor[inv[c]]
                data[k] = v
                indices[k] = r
                cursor[inv[c]] = k + 1
    return data, indices, indptr


@njit(cache=True, nogil=True)
def fold_columns(M, rows, a, b, sign):
    """``out[i, c] = M[rows[i], a[c]] + sign * M[rows[i], b[c]]`` (just ``M[rows[i], a[c]]``
    where ``b[c] < 0``; ``sign`` +1 or -1, an addition or a subtraction as NumPy's
    ``out += ...`` / ``out -= ...``): a mirror fold
    (:class:`panair.solver.panels.MirrorFold`) in one pass over the rows, without the
    fancy-indexed copies (measured 0.14 s against 1.3 s for 4380 x 8760)."""
    out = np.empty((len(rows), len(a)))
    for i in range(len(rows)):
        r = rows[i]
        for c in range(len(a)):
            v = M[r, a[c]]
            if b[c] >= 0:
                if sign > 0:
                    v = v + M[r, b[c]]
                else:
                    v = v - M[r, b[c]]
            out[i, c] = v
    return out


@njit(cache=True, nogil=True)
def fold_difference(M0, M1, rows, a, b, sign, step):
    """:func:`fold_columns` of ``M0`` and the folded divided difference
    ``(fold(M1) - fold(M0)) / step[i]`` (``step`` per output row) in one pass: the
    supersonic solver's folded potential and influence matrix, the same operations
    as folding both and differencing them in NumPy."""
    out0 = np.empty((len(rows), len(a)))
    outd = np.empty((len(rows), len(a)))
    for i in range(len(rows)):
        r = rows[i]
        for c in range(len(a)):
            v0 = M0[r, a[c]]
            v1 = M1[r, a[c]]
            if b[c] >= 0:
                if sign > 0:
                    v0 = v0 + M0[r, b[c]]
                    v1 = v1 + M1[r, b[c]]
                else:
                    v0 = v0 - M0[r, b[c]]
                    v1 = v1 - M1[r, b[c]]
            out0[i, c] = v0
            outd[i, c] = (v1 - v0) / step[i]
    return out0, outd


def warm_up():
    """Compile (or load from the on-disk cache) the kernels the solvers call (subsonic
    influence, the supersonic source pair, the causal CSC) on a one-panel case, so
    worker processes forked afterwards inherit the machine code [s spent returned]."""
    import time
    t0 = time.perf_counter()
    if HAVE_NUMBA:
        from .influence import influence_matrices
        from .supersonic_influence import source_potential_pair
        flat = np.array([[[0.0, 0.0, 0.0], [0.0, 1.0, 0.0], [1.0, 1.0, 0.0], [1.0, 0.0, 0.0]]])
        nrm = np.array([[0.0, 0.0, 1.0]])
        influence_matrices(np.array([[0.5, 0.5, 1.0]]), flat, nrm, backend="compiled")
        flat_s = np.array([[[0.0, 0.0, 0.0], [0.0, 1.0, 0.1], [1.0, 1.0, 0.1], [1.0, 0.0, 0.0]]])
        nrm_s = np.array([[0.1, -0.1, 0.99]]) / np.linalg.norm([0.1, -0.1, 0.99])
        pt = np.array([[3.0, 0.5, 0.5]])
        source_potential_pair(pt, pt, flat_s, nrm_s, mirror=True, backend="compiled")
        dense_to_csc(np.eye(2), np.arange(2))
        fold_columns(np.eye(2), np.arange(2), np.arange(1), np.ones(1, np.int64), -1.0)
        fold_difference(np.eye(2), np.eye(2), np.arange(2), np.arange(1), np.ones(1, np.int64),
                        -1.0, np.ones(2))
    return time.perf_counter() - t0
