"""Potential of constant-strength source panels in supersonic linearised
flow, with the Mach-cone domain of dependence.

Scaled coordinates X = x / B (B = sqrt(M^2 - 1)), Y = y, Z = z turn the
linearised potential equation into the wave equation
phi_XX = phi_YY + phi_ZZ; a unit source gives phi = -1 / (2 pi R),
R = sqrt(dX^2 - dY^2 - dZ^2), inside its downstream Mach cone only
(e.g. Ward, *Linearized Theory of Steady High-Speed Flow*, 1955, sec. 3.4;
the normalisation is the one whose planar sheet has a mass-flux jump
equal to its strength, Epton & Magnus, NASA CR-3251, sec. D).

For a planar, *subinclined* panel (normal n with n_X^2 < 1/2 in scaled
coordinates) the in-plane basis e2 = x x n / |x x n|, e1 = n x e2
diagonalises the hyperbolic form: with g1 = 1 - 2 n_X^2 and u = sqrt(g1) s
(s, t = panel coordinates along e1, e2)

    R^2 = (U - u)^2 - (T - t)^2 - H^2,   H^2 = h^2 / g1,   dA = du dt / sqrt(g1),

(h = normal distance, U = sqrt(g1) (d1 + 2 e1_X n_X h / g1), T = d2).
Over the part of the panel inside the upstream Mach cone, the divergence
theorem with the field V = (p, q) r / (p^2 - q^2) (p = U - u, q = T - t,
div V = 1 / r, V = 0 on the Mach cone) leaves one integral per edge:
delta_k * Integral sqrt(R) / (R + H^2) dtau, delta_k the distance from the
field point's projection to the edge line, R quadratic in the edge
parameter; done in closed form (:func:`_edge_term`: J0 - H^2 K, our derivation,
one expression continuous through sonic edges and delta_k = 0; checked against
quadrature in tests/unit/test_panair_supersonic.py and, at and near sonic
edges, test_panair_supersonic_sonic.py).

Numeric-only.  :func:`source_potential` runs the compiled kernel of
:mod:`.kernels` (Numba) when available; the vectorised NumPy form below is
the reference it is tested against and the fallback.
"""
from __future__ import annotations

import numpy as np

from . import kernels

__all__ = ["panel_frames", "source_potential", "source_potential_pair"]

_TWO_PI = 2.0 * np.pi


def panel_frames(flat: np.ndarray, normal: np.ndarray):
    """Canonical in-plane frames of subinclined panels (scaled coordinates).

    Returns
    -------
    e1, e2 : ndarray (n, 3)
        Unit in-plane vectors (e1 with e1_X >= 0, e2 with e2_X = 0).
    g1 : ndarray (n,)
        1 - 2 n_X^2: > 0 subinclined, <= 0 superinclined (or Mach-inclined).
    """
    xhat = np.array([1.0, 0.0, 0.0])
    e2 = np.cross(xhat, normal)
    nrm = np.linalg.norm(e2, axis=1)
    e2 = e2 / np.where(nrm > 1e-12, nrm, 1.0)[:, None]
    e1 = np.cross(normal, e2)
    sign = np.where(e1[:, 0] < 0, -1.0, 1.0)
    e1 *= sign[:, None]
    g1 = 1.0 - 2.0 * normal[:, 0] ** 2
    return e1, e2, g1


def _edge_term(ta, tb, s_a, s_b, a, b, H2, delta):
    """delta * Integral_ta^tb sqrt(R) / (R + H2) dtau over one sub-interval of an
    edge where R = a tau^2 + b tau + c > 0 (vectorised; :func:`.kernels._edge_term`
    is the same formula, scalar).

    ``s_a``, ``s_b`` = sqrt(R) at the ends (0 where an end is a root of R: exact,
    so the result does not depend on the rounding of sqrt(R) at the Mach cone).
    With g = a tau + b/2 (= R'/2), S = s_a + s_b, dtau = tb - ta:

    * J0 = Integral dtau / sqrt(R) = (2 dtau / S) Phi(x), x = sqrt|a| dtau / S,
      Phi = atanh(x)/x (a > 0), atan(x)/x (a < 0), 1 (a = 0, a sonic edge:
      the edge along a Mach line, R linear).  This is the textbook
      log / arcsin antiderivative (Gradshteyn & Ryzhik 2.261) with the
      half-angle identities log(Z_b/Z_a) = 2 atanh((Z_b - Z_a)/(Z_b + Z_a)),
      Z = sqrt(a) sqrt(R) + |g|, where (Z_b - Z_a)/(Z_b + Z_a) = x exactly,
      and the arcsin difference as 2 atan2(sqrt|-a| dtau, S): one expression
      continuous through a = 0 (no "linear edge" switch; the old closed form
      lost ~1e-16/|a| relative near a sonic edge, 5e-4 measured).  For x >= 0.5
      (a > 0) the equal form sign(g) log(Z_b/Z_a) / sqrt(a) is used (atanh
      near 1 loses digits; Z is a sum of non-negative terms, no cancellation).
    * H2 K, K = Integral dtau / ((R + H2) sqrt(R)): with the geometric identity
      D + H2 = -delta^2 / a (D = c - b^2/(4a), delta = the edge's distance
      from the field point's projection, since c + H2 = p^2 - q^2 and
      b = 2 (p e_p - q e_q)), (D + H2)/a = -(delta/a)^2 <= 0, so K is always
      the arctan form and delta H2 K = sign(delta) H [atan2(|delta| sqrt(R),
      H g)] (H = sqrt(H2)), valid for every a including 0.  The old code's
      log branch ((D + H2)/a > 0) is therefore reached only where rounding
      makes (D + H2)/a >= 0, i.e. delta = 0 to rounding, where it divided
      0/0 (an edge whose line passes through the field point's projection:
      the edge line touches the degenerate Mach hyperbola p^2 = q^2 of the
      point in the panel plane; Defiance, session 6).
    * delta = 0: the term is 0, and it is the limit of the formula (delta J0
      -> 0 also where J0 grows like log|delta| with H2 = 0; the atan2 terms of
      one interval have the same branch, since R > 0 keeps |g| away from 0
      for a > 0 and there is no interval for a < 0), so the influence is
      continuous there (tests/unit/test_panair_supersonic.py checks it
      against quadrature at and beside delta = 0 and a = 0).
    """
    dt = tb - ta
    S = s_a + s_b
    q = np.sqrt(np.abs(a))
    S_safe = np.where(S > 0, S, 1.0)
    x = np.where(S > 0, q * dt / S_safe, np.inf)
    ga = a * ta + 0.5 * b
    gb = a * tb + 0.5 * b
    # a > 0, x < 0.5 and the series (x < 1e-4, either sign of a; error x^4/5)
    xs = np.where((x > 0) & (x < 0.5), x, 0.5)
    phi = np.where(x < 1e-4, 1.0 + np.copysign(x * x, a) / 3.0, np.arctanh(xs) / xs)
    j0_ser = 2.0 * dt / S_safe * phi
    q_safe = np.where(q > 0, q, 1.0)
    gm = a * (0.5 * (ta + tb)) + 0.5 * b
    j0_log = (np.copysign(1.0, gm)
              * np.log((q * s_b + np.abs(gb) + 1e-300) / (q * s_a + np.abs(ga) + 1e-300)) / q_safe)
    j0_atan = 2.0 * np.arctan2(q * dt, S) / q_safe
    j0 = np.where(x < 1e-4, j0_ser, np.where(a > 0, np.where(x < 0.5, j0_ser, j0_log), j0_atan))
    h = np.sqrt(H2)
    ad = np.abs(delta)
    ek = np.copysign(h, delta) * (np.arctan2(ad * s_b, h * gb) - np.arctan2(ad * s_a, h * ga))
    return np.where(delta == 0.0, 0.0, delta * j0 - ek)


def _roots(a, b, c):
    """Real roots (r1, r2) of a tau^2 + b tau + c, in the cancellation-free form
    q = -(b + sign(b) sqrt(b^2 - 4ac)) / 2, r1 = q / a, r2 = c / q (Press et
    al., Numerical Recipes, 3rd ed., sec. 5.6): near a sonic edge (a -> 0) the
    textbook (-b +- sqrt(disc)) / 2a loses ~1e-16 |b| / |a| in the finite root
    (the Mach-cone crossing), the form here tends to -c/b; a = 0 gives r1 = r2
    = -c/b.  No real root (disc < 0): r1 = r2 = 0 and ``has`` False."""
    disc = b * b - 4.0 * a * c
    has = disc >= 0
    sq = np.sqrt(np.where(has, disc, 0.0))
    qq = -0.5 * (b + np.copysign(sq, b))
    ok_q = qq != 0
    r2 = np.where(ok_q, c / np.where(ok_q, qq, 1.0), 0.0)
    r1 = np.where(a != 0, qq / np.where(a != 0, a, 1.0), r2)
    return np.where(has, r1, 0.0), np.where(has, r2, 0.0), has


def source_potential(points: np.ndarray, flat: np.ndarray, normal: np.ndarray,
                     chunk: int = 64, backend: str = "auto") -> np.ndarray:
    """Supersonic potential per unit source strength of flat panels.

    Parameters
    ----------
    points : ndarray (m, 3)
        Field points, scaled coordinates (X = x / B).
    flat, normal : ndarray (n, 4, 3), (n, 3)
        Planar panels in scaled coordinates and their unit normals; all
        must be subinclined (``panel_frames`` g1 > 0).
    chunk : int
        Field points per vectorised block (NumPy backend).
    backend : str
        ``"auto"`` (compiled kernel when Numba is installed), ``"compiled"``
        or ``"numpy"`` (the vectorised reference).

    Returns
    -------
    ndarray (m, n)
        phi = -1/(2 pi) Integral_{panel and upstream Mach cone} dA / R.
    """
    m, n = len(points), len(flat)
    out = np.zeros((m, n))
    prep = _prepare(flat, normal)
    if kernels.use_compiled(backend):
        kernels.supersonic_source(np.ascontiguousarray(points, float), *prep, out)
        return out
    cen, rho, q0, normal, e1, e2, g1, sg, e1x_nx, uk, tk, L, okL, ep_all, eq_all, nup_all, \
        nuq_all, a_all = prep
    for a0 in range(0, m, chunk):
        P = points[a0:a0 + chunk]
        d = P[:, None, :] - cen[None, :, :]
        # a panel whose bounding sphere is outside the upstream Mach cone of P
        # (45 deg in scaled coordinates) has no influence
        dist = (np.hypot(d[..., 1], d[..., 2]) - d[..., 0]) / np.sqrt(2.0)
        I, J = np.nonzero(dist < rho[None, :] * (1 + 1e-9) + 1e-12)
        for b0 in range(0, len(I), 20000):
            ii, jj = I[b0:b0 + 20000], J[b0:b0 + 20000]
            out[a0 + ii, jj] = _pair_potential(P[ii], jj, q0, normal, e1, e2, g1, sg, e1x_nx,
                                               uk, tk, L, okL, ep_all, eq_all, nup_all,
                                               nuq_all, a_all)
    return out


def _prepare(flat: np.ndarray, normal: np.ndarray) -> tuple:
    """Per-panel constants of the source kernel (C-contiguous, in the compiled
    kernels' argument order): centroid, bounding radius, first corner, normal,
    frame e1, e2, g1, sqrt(g1), e1_X n_X, corner coordinates (u, t), edge lengths
    and their use, edge directions, edge normals and the quadratic's a."""
    e1, e2, g1 = panel_frames(flat, normal)
    sg = np.sqrt(np.maximum(g1, 1e-12))
    q0 = flat[:, 0, :]
    rel = flat - q0[:, None, :]
    uk = sg[:, None] * np.einsum("nkj,nj->nk", rel, e1)          # (n, 4)
    tk = np.einsum("nkj,nj->nk", rel, e2)
    # counter-clockwise polygons in (u, t) (so in (p, q) too: a point reflection)
    area2 = np.sum(uk * np.roll(tk, -1, 1) - np.roll(uk, -1, 1) * tk, axis=1)
    flip = area2 < 0
    uk = np.where(flip[:, None], uk[:, ::-1], uk)
    tk = np.where(flip[:, None], tk[:, ::-1], tk)
    du = np.roll(uk, -1, 1) - uk
    dt = np.roll(tk, -1, 1) - tk
    L = np.hypot(du, dt)
    okL = L > 1e-14 * (1.0 + L.max())
    Ls = np.where(okL, L, 1.0)
    e1x_nx = e1[:, 0] * normal[:, 0]
    cen = flat.mean(axis=1)
    rho = np.linalg.norm(flat - cen[:, None, :], axis=-1).max(axis=1)
    ep_all = -du / Ls
    eq_all = -dt / Ls
    nup_all = -dt / Ls
    nuq_all = du / Ls
    a_all = ep_all**2 - eq_all**2
    c = np.ascontiguousarray
    return (c(cen), c(rho), c(q0), c(normal, float), c(e1), c(e2), c(g1), c(sg), c(e1x_nx), c(uk),
            c(tk), c(L), c(okL), c(ep_all), c(eq_all), c(nup_all), c(nuq_all), c(a_all))


def source_potential_pair(p0: np.ndarray, p1: np.ndarray, flat: np.ndarray, normal: np.ndarray,
                          sides=None, mirror: bool = False, rows=None, backend: str = "auto"):
    """The supersonic solver's two potentials in one pass (numeric-only).

    ``phi0`` at ``p0`` and ``phi1`` at ``p1`` (m, 3), each :func:`source_potential`
    with the fin-separated pairs set to 0 (``sides`` = (recv, src_fin, src_side) of
    :func:`panair.solver.supersonic._fin_sides`, or None) and, with ``mirror``, plus
    :func:`source_potential` at the mirror image (x, -y, z) of the points, with the
    pairs separated there set to 0 (a fourth element of ``sides``: the mirror
    images' sides (n_fins, m), :func:`panair.solver.supersonic._mirror_sides`;
    without it none are).

    Rows are computed in the order ``rows`` (default 0 .. m-1); the pass stops at the
    first row with a non-finite value.

    Returns
    -------
    phi0, phi1 : ndarray (m, n)
    bad_row : int
        The first row (in ``rows`` order) with a non-finite value (the rows after it
        are not computed), or -1.
    """
    m, n = len(p0), len(flat)
    if sides is None:
        sides = (np.zeros((0, m)), -np.ones(n, np.int64), np.zeros(n))
    recv, src_fin, src_side = sides[:3]
    recv_m = sides[3] if len(sides) > 3 else np.zeros_like(recv)
    rows = np.arange(m) if rows is None else np.asarray(rows, np.int64)
    if kernels.use_compiled(backend):
        phi0, phi1 = np.empty((m, n)), np.empty((m, n))
        bad = kernels.supersonic_source_pair(
            np.ascontiguousarray(p0, float), np.ascontiguousarray(p1, float), bool(mirror), rows,
            np.ascontiguousarray(recv, float), np.ascontiguousarray(recv_m, float),
            np.ascontiguousarray(src_fin, np.int64),
            np.ascontiguousarray(src_side, float), *_prepare(flat, normal), phi0, phi1)
        return phi0, phi1, int(bad)
    def mask(r):
        return ((src_fin[None, :] >= 0)
                & (r[np.maximum(src_fin, 0)].T * src_side[None, :] < 0)) if len(r) else False
    shadow, shadow_m = mask(recv), mask(recv_m)
    out = []
    for pts in (p0, p1):
        val = source_potential(pts, flat, normal, backend=backend)
        val[shadow] = 0.0
        if mirror:
            val_m = source_potential(pts * np.array([1.0, -1.0, 1.0]), flat, normal, backend=backend)
            val_m[shadow_m] = 0.0
            val += val_m
        out.append(val)
    bad = np.nonzero(~np.all(np.isfinite(out[0]) & np.isfinite(out[1]), axis=1)[rows])[0]
    return out[0], out[1], int(rows[bad[0]]) if len(bad) else -1


def _pair_potential(P, jj, q0, normal, e1, e2, g1, sg, e1x_nx, uk, tk, L, okL, ep_all,
                    eq_all, nup_all, nuq_all, a_all):
    """Potential of panel jj[k] at point P[k] (vectorised over pairs)."""
    d = P - q0[jj]
    nj = normal[jj]
    h = np.einsum("kj,kj->k", d, nj)
    d1 = np.einsum("kj,kj->k", d, e1[jj])
    d2 = np.einsum("kj,kj->k", d, e2[jj])
    gj = np.maximum(g1[jj], 1e-12)
    sgj = sg[jj]
    U = sgj * (d1 + 2.0 * e1x_nx[jj] * h / gj)
    H2 = (h**2 / gj)[:, None]
    pk = U[:, None] - uk[jj]
    qk = d2[:, None] - tk[jj]
    ep, eq = ep_all[jj], eq_all[jj]
    delta = pk * nup_all[jj] + qk * nuq_all[jj]
    a = a_all[jj]
    b = 2.0 * (pk * ep - qk * eq)
    c = pk**2 - qk**2 - H2
    Lb = L[jj]
    r1, r2, has = _roots(a, b, c)
    lo_raw, hi_raw = np.minimum(r1, r2), np.maximum(r1, r2)
    lo, hi = np.clip(lo_raw, 0, Lb), np.clip(hi_raw, 0, Lb)
    # sqrt(R) at the ends of the sub-intervals [0, lo], [lo, hi], [hi, Lb]: exactly 0
    # at a root of R inside the edge (the Mach-cone crossing)
    s0 = np.sqrt(np.maximum(c, 0.0))
    sL = np.sqrt(np.maximum(a * Lb**2 + b * Lb + c, 0.0))
    s_lo = np.where(has & (lo_raw > 0) & (lo_raw < Lb), 0.0,
                    np.sqrt(np.maximum(a * lo**2 + b * lo + c, 0.0)))
    s_hi = np.where(has & (hi_raw > 0) & (hi_raw < Lb), 0.0,
                    np.sqrt(np.maximum(a * hi**2 + b * hi + c, 0.0)))
    ends = [(np.zeros_like(c), lo, s0, s_lo), (lo, hi, s_lo, s_hi), (hi, Lb, s_hi, sL)]
    H2b = np.broadcast_to(H2, c.shape)
    total = np.zeros(c.shape)
    # the part inside the upstream Mach cone is one of the three (the cone is convex):
    # the last valid one, as the compiled kernel
    for ta, tb, sa_, sb_ in ends:
        mid = 0.5 * (ta + tb)
        valid = (tb - ta > 1e-15 * (1 + Lb)) & (a * mid**2 + b * mid + c > 0) & (pk + ep * mid > 0)
        if not np.any(valid):
            continue
        v = np.nonzero(valid)
        total[v] = _edge_term(ta[v], tb[v], sa_[v], sb_[v], a[v], b[v], H2b[v], delta[v])
    integral = np.sum(np.where(okL[jj], total, 0.0), axis=-1) / sgj
    return -integral / _TWO_PI

