"""Potential induced by constant-strength source and doublet panels in
Laplace's equation (incompressible, or Prandtl-Glauert-transformed space).

Each panel is a flat quadrilateral (the four corners projected on their
mean plane, as in Katz & Plotkin, *Low-Speed Aerodynamics*, 2nd ed., 2001,
sec. 10.4); degenerate (triangular) panels are handled by dropping
zero-length edges.

Conventions (unit strengths, outward panel normal ``n``):

* doublet:  ``D(P) = 1/(4 pi) * Integral n . (P - Q) / |P - Q|^3 dS``
  = signed solid angle / (4 pi); the potential jumps by +1 crossing the
  panel in the direction of ``n`` (D -> +1/2 on the ``n`` side, -1/2 on
  the other side).
* source:   ``S(P) = -1/(4 pi) * Integral dS / |P - Q|``; the normal
  derivative jumps by +1 crossing the panel along ``n``.

Formulas:

* solid angle of a triangle: Van Oosterom & Strackee, "The solid angle of
  a plane triangle", IEEE Trans. Biomed. Eng. BME-30(2), 1983, eq. (8);
* ``Integral dS / r`` over a plane polygon: the divergence-theorem form of
  Newman, "Distributions of sources and normal dipoles over a quadrilateral
  panel", J. Eng. Math. 20, 1986, eq. (2.8)-(2.9): ``Sum_k d_k * ln((r_k +
  r_k+1 + l_k) / (r_k + r_k+1 - l_k)) - |z| * |Omega|`` with ``d_k`` the
  in-plane distance of the field point to edge ``k`` (positive inside).

All functions are numeric-only.  :func:`influence_matrices` runs the
compiled kernel of :mod:`.kernels` (Numba) when available; the vectorised
NumPy loop below is the reference it is tested against and the fallback.
"""
from __future__ import annotations

import numpy as np

from . import kernels

__all__ = ["planar_corners", "solid_angle_quads", "influence_matrices"]

_FOUR_PI = 4.0 * np.pi


def planar_corners(corners: np.ndarray):
    """Project quadrilateral corners on their mean plane.

    Parameters
    ----------
    corners : ndarray (n, 4, 3) [m]

    Returns
    -------
    flat : ndarray (n, 4, 3) [m]
        Corners projected on the plane through their centroid normal to
        ``n``.
    centroid : ndarray (n, 3) [m]
        Mean of the four corners.
    normal : ndarray (n, 3) [-]
        Unit normal ``(Q3 - Q1) x (Q2 - Q4)`` (PANAIR's orientation of a
        LaWGS network: line direction x point direction).
    area : ndarray (n,) [m^2]
        Area of the projected quadrilateral (half the diagonals' cross
        product).
    """
    c = corners.mean(axis=1)
    cr = np.cross(corners[:, 2] - corners[:, 0], corners[:, 1] - corners[:, 3])
    norm = np.linalg.norm(cr, axis=1)
    n = cr / np.where(norm > 0, norm, 1.0)[:, None]
    h = np.einsum("nkj,nj->nk", corners - c[:, None, :], n)
    flat = corners - h[..., None] * n[:, None, :]
    return flat, c, n, 0.5 * norm


def _tri_solid_angle(r1, r2, r3):
    """Signed solid angle of triangles seen from the origin, Van Oosterom &
    Strackee (1983) eq. (8): tan(Omega/2) = R1.(R2xR3) / (r1 r2 r3 +
    (R1.R2) r3 + (R1.R3) r2 + (R2.R3) r1).  Inputs (..., 3) relative
    vectors Q_i - P; positive when P is on the side *opposite* to the
    normal (Q2-Q1)x(Q3-Q1) (checked against quadrature in the tests)."""
    l1 = np.linalg.norm(r1, axis=-1)
    l2 = np.linalg.norm(r2, axis=-1)
    l3 = np.linalg.norm(r3, axis=-1)
    num = np.einsum("...k,...k->...", r1, np.cross(r2, r3))
    den = (l1 * l2 * l3 + np.einsum("...k,...k->...", r1, r2) * l3
           + np.einsum("...k,...k->...", r1, r3) * l2
           + np.einsum("...k,...k->...", r2, r3) * l1)
    om = 2.0 * np.arctan2(num, den)
    # field point in the plane of the triangle and outside it: exactly 0
    scale = (l1 * l2 * l3) + 1e-300
    return np.where(np.abs(num) <= 1e-13 * scale, 0.0, om)


def solid_angle_quads(points: np.ndarray, flat: np.ndarray) -> np.ndarray:
    """Doublet influence D = signed solid angle / (4 pi) of flat quads.

    Parameters
    ----------
    points : ndarray (m, 3) [m]
        Field points.
    flat : ndarray (n, 4, 3) [m]
        Planar quadrilaterals (corner order as in :func:`planar_corners`).

    Returns
    -------
    ndarray (m, n) [-]
    """
    R = flat[None, :, :, :] - points[:, None, None, :]
    # orientation: normal (Q3-Q1)x(Q2-Q4) corresponds to triangles (Q1,Q4,Q3), (Q1,Q3,Q2)
    om = (_tri_solid_angle(R[:, :, 0], R[:, :, 3], R[:, :, 2])
          + _tri_solid_angle(R[:, :, 0], R[:, :, 2], R[:, :, 1]))
    return -om / _FOUR_PI


def influence_matrices(points: np.ndarray, flat: np.ndarray, normal: np.ndarray,
                       self_index: np.ndarray | None = None, chunk: int = 128,
                       out: tuple | None = None, backend: str = "auto"):
    """Doublet and source influence of every flat quad on every field point.

    Parameters
    ----------
    points : ndarray (m, 3) [m]
        Field points.
    flat, normal : ndarray (n, 4, 3), (n, 3)
        Planar panel corners [m] and unit normals [-] (from
        :func:`planar_corners`).
    self_index : ndarray (m,) of int, optional
        Panel on which field point ``i`` lies (its centroid), or -1; that
        entry's doublet influence is set to the interior limit -1/2.
    chunk : int
        Field points per vectorised block.
    out : (D, S) arrays, optional
        Add the influences into these (m, n) arrays instead of allocating.
    backend : str
        ``"auto"`` (compiled kernel when Numba is installed), ``"compiled"``
        or ``"numpy"`` (the vectorised reference).

    Returns
    -------
    D : ndarray (m, n) [-]
        Doublet potential per unit doublet strength.
    S : ndarray (m, n) [m]
        Source potential per unit source strength.
    """
    m, n = len(points), len(flat)
    add = out is not None
    D, S = out if add else (np.empty((m, n)), np.empty((m, n)))
    q_next = np.roll(flat, -1, axis=1)
    edge = q_next - flat                                   # (n, 4, 3)
    length = np.linalg.norm(edge, axis=-1)                 # (n, 4)
    ok_edge = length > 1e-12 * (1.0 + length.max())
    t_edge = edge / np.where(ok_edge, length, 1.0)[..., None]
    nu = np.cross(t_edge, normal[:, None, :])              # in-plane outward edge normal
    qx, qy, qz = (np.ascontiguousarray(flat[:, :, j].T) for j in range(3))   # (4, n)
    nux, nuy, nuz = (np.ascontiguousarray(nu[:, :, j].T) for j in range(3))
    L = length.T
    okT = ok_edge.T
    if kernels.use_compiled(backend):
        if not (D.flags.c_contiguous and S.flags.c_contiguous):
            raise ValueError("out arrays must be C-contiguous")
        kernels.laplace_influence(np.ascontiguousarray(points, float), qx, qy, qz, nux, nuy, nuz,
                                  np.ascontiguousarray(normal, float), np.ascontiguousarray(L),
                                  np.ascontiguousarray(okT), D, S, add)
    else:
        _numpy_blocks(points, qx, qy, qz, nux, nuy, nuz, normal, L, okT, D, S, add, chunk)
    if self_index is not None:
        rows = np.nonzero(self_index >= 0)[0]
        D[rows, self_index[rows]] = -0.5
    return D, S


def _numpy_blocks(points, qx, qy, qz, nux, nuy, nuz, normal, L, okT, D, S, add, chunk):
    """The vectorised NumPy form of :func:`influence_matrices` (reference)."""
    m = len(points)
    nx, ny, nz = normal[:, 0], normal[:, 1], normal[:, 2]
    for a in range(0, m, chunk):
        p = points[a:a + chunk]
        px, py, pz = p[:, 0:1], p[:, 1:2], p[:, 2:3]
        Rx = [qx[k] - px for k in range(4)]
        Ry = [qy[k] - py for k in range(4)]
        Rz = [qz[k] - pz for k in range(4)]
        r = [np.sqrt(Rx[k] ** 2 + Ry[k] ** 2 + Rz[k] ** 2) for k in range(4)]

        def dot(i, j):
            return Rx[i] * Rx[j] + Ry[i] * Ry[j] + Rz[i] * Rz[j]

        def triple(i, j, k):
            return (Rx[i] * (Ry[j] * Rz[k] - Rz[j] * Ry[k])
                    + Ry[i] * (Rz[j] * Rx[k] - Rx[j] * Rz[k])
                    + Rz[i] * (Rx[j] * Ry[k] - Ry[j] * Rx[k]))

        d02 = dot(0, 2)
        om = np.zeros_like(d02)
        # triangles (Q1, Q4, Q3) and (Q1, Q3, Q2): Van Oosterom & Strackee (1983) eq. (8)
        for (i, j, k), (dij, dik, djk) in (((0, 3, 2), (dot(0, 3), d02, dot(3, 2))),
                                           ((0, 2, 1), (d02, dot(0, 1), dot(2, 1)))):
            num = triple(i, j, k)
            rrr = r[i] * r[j] * r[k]
            den = rrr + dij * r[k] + dik * r[j] + djk * r[i]
            om += np.where(np.abs(num) <= 1e-13 * (rrr + 1e-300), 0.0, 2.0 * np.arctan2(num, den))
        dmat = -om / _FOUR_PI
        integral = np.zeros_like(d02)
        for k in range(4):
            k1 = (k + 1) % 4
            d = -(Rx[k] * nux[k] + Ry[k] * nuy[k] + Rz[k] * nuz[k])
            rs = r[k] + r[k1]
            lt = np.log((rs + L[k]) / np.maximum(rs - L[k], 1e-300))
            integral += np.where(okT[k] & (np.abs(d) > 1e-14), d * lt, 0.0)
        z = -(Rx[0] * nx + Ry[0] * ny + Rz[0] * nz)
        integral -= np.abs(z) * np.abs(om)
        if add:
            S[a:a + chunk] -= integral / _FOUR_PI
            D[a:a + chunk] += dmat
        else:
            S[a:a + chunk] = -integral / _FOUR_PI
            D[a:a + chunk] = dmat
