"""Surface velocity from the doublet solution, pressure rules, and the
integration of pressure into forces and moments.  Numeric-only.
"""
from __future__ import annotations

import numpy as np

from ironbark_opt.errors import InputError

__all__ = ["surface_gradient", "pressure_coefficient", "integrate_forces", "PRESSURE_RULES"]

PRESSURE_RULES = ("linear", "second-order", "slender-body", "isentropic")
GAMMA = 1.4


def surface_gradient(phi, centroid, normal, neighbours, corners=None, attached=None):
    """Tangential gradient of a panel-centred surface potential.

    Least-squares fit over the structured-grid neighbours, in the tangent
    plane of each panel (the finite-difference approach of Katz & Plotkin,
    *Low-Speed Aerodynamics*, 2001, sec. 12.5, generalised to a weighted
    least-squares fit so one-sided and mirror neighbours need no special
    formula).

    A neighbour across a sharp edge (normals more than 60 deg apart: a sharp
    fin leading edge) is left out unless ``corners`` are given and both
    panels are ``attached``; then it enters at its offset measured along the
    surface, unfolded about the common edge (:func:`_unfolded_offsets`).  The
    potential is continuous round such an edge and the attached flow goes
    round it: the tangential velocity is the derivative of mu along the
    surface, differenced between adjacent panels round the whole section,
    leading edge included (Katz & Plotkin 2001, sec. 12.5 and the
    two-dimensional Dirichlet doublet programs of ch. 11; distances from
    panel centre through the common side's midpoint to the neighbour's
    centre as in VSAERO, Maskew, NASA CR-4023, 1987).  Left out, the one-sided
    difference dropped the doublet jump between the two leading-edge panels
    (~9 % of the trailing-edge jump Gamma on a 3.9 % double wedge): sharp fins
    carried 0.92 of their Kutta-Joukowski force.

    Parameters
    ----------
    phi : ndarray (n,) [m^2/s per (m/s)]
        Potential per unit free-stream speed at panel centroids.
    centroid, normal : ndarray (n, 3)
        Panel centroids [m] and unit normals [-].
    neighbours : ndarray (n, 4) of int
        Neighbour indices, -1 none, -2 mirror image in y = 0; neighbour k
        shares the side (corners 0-1, 2-3, 0-3, 1-2 for k = 0 ... 3) of a
        structured-grid panel (:func:`panair.solver.panels.build_panels`).
    corners : ndarray (n, 4, 3), optional
        Panel corners (same space as ``centroid``).
    attached : ndarray (n,) of bool, optional
        Panels wetted by attached flow (default all); a sharp edge next to a
        separated panel (a blunt trailing edge's closure) is not unfolded.

    Returns
    -------
    ndarray (n, 3) [-]
        Tangential gradient of ``phi``.
    """
    nb = neighbours
    valid = nb != -1
    idx = np.where(nb >= 0, nb, 0)
    cq = centroid[idx]                                       # (n, 4, 3)
    mirror = nb == -2
    cm = centroid.copy()
    cm[:, 1] *= -1.0
    cq = np.where(mirror[..., None], cm[:, None, :], cq)
    nq = normal[idx]
    nq = np.where(mirror[..., None], (normal * np.array([1.0, -1.0, 1.0]))[:, None, :], nq)
    # neighbours across a sharp edge (fin leading/trailing edge, body-fin corner)
    # are not used: their centroids are not on the local tangent plane
    smooth = np.einsum("nkj,nj->nk", nq, normal) > 0.5
    valid &= smooth
    dphi = np.where(nb >= 0, phi[idx] - phi[:, None], 0.0)  # mirror: same phi
    dx = cq - centroid[:, None, :]
    dx -= np.einsum("nkj,nj->nk", dx, normal)[..., None] * normal[:, None, :]
    if corners is not None:
        sharp = ~smooth & (nb >= 0)
        if attached is not None:
            sharp &= attached[:, None] & attached[idx]
        p, k = np.nonzero(sharp)
        if len(p):
            d, ok = _unfolded_offsets(corners[p], centroid[p], normal[p], centroid[nb[p, k]], k)
            dx[p[ok], k[ok]] = d[ok]
            valid[p[ok], k[ok]] = True
    w = np.where(valid, 1.0 / np.maximum(np.einsum("nkj,nkj->nk", dx, dx), 1e-300), 0.0)
    # local tangent basis
    a = np.where(np.abs(normal[:, [0]]) < 0.9, [[1.0, 0.0, 0.0]], [[0.0, 1.0, 0.0]])
    t1 = np.cross(normal, a)
    t1 /= np.linalg.norm(t1, axis=1)[:, None]
    t2 = np.cross(normal, t1)
    d1 = np.einsum("nkj,nj->nk", dx, t1)
    d2 = np.einsum("nkj,nj->nk", dx, t2)
    m11 = (w * d1 * d1).sum(1)
    m12 = (w * d1 * d2).sum(1)
    m22 = (w * d2 * d2).sum(1)
    b1 = (w * d1 * dphi).sum(1)
    b2 = (w * d2 * dphi).sum(1)
    det = m11 * m22 - m12**2
    ok = det > 1e-10 * (m11 + m22) ** 2
    g1 = np.where(ok, (m22 * b1 - m12 * b2) / np.where(ok, det, 1.0), 0.0)
    g2 = np.where(ok, (m11 * b2 - m12 * b1) / np.where(ok, det, 1.0), 0.0)
    # rank-deficient (a single direction): pseudo-inverse, g = M b / trace(M)^2
    one = ~ok & (m11 + m22 > 0)
    if np.any(one):
        g1[one] = (b1[one] * m11[one] + b2[one] * m12[one]) / ((m11[one] + m22[one]) ** 2 + 1e-300)
        g2[one] = (b1[one] * m12[one] + b2[one] * m22[one]) / ((m11[one] + m22[one]) ** 2 + 1e-300)
    return g1[:, None] * t1 + g2[:, None] * t2


_SIDES = np.array([[0, 1], [2, 3], [0, 3], [1, 2]])
"""Corners of the side a panel shares with neighbour k (grid order of build_panels)."""


def _unfolded_offsets(corners, centroid, normal, centroid_q, k):
    """Offsets [m] in each panel's tangent plane of its neighbours ``centroid_q``
    across side ``k``, measured along the surface: the neighbour rotated about the
    common side into the panel's plane (centre -> side midpoint -> neighbour centre).
    Returns (offsets (m, 3), ok (m,) False where the side is degenerate)."""
    a = corners[np.arange(len(k)), _SIDES[k, 0]]
    b = corners[np.arange(len(k)), _SIDES[k, 1]]
    mid = 0.5 * (a + b)
    t = b - a
    t -= np.einsum("mj,mj->m", t, normal)[:, None] * normal      # side in the panel's plane
    lt = np.linalg.norm(t, axis=1)
    ok = lt > 1e-12 * np.linalg.norm(mid - centroid, axis=1)
    t /= np.where(ok, lt, 1.0)[:, None]
    d1 = mid - centroid
    d1 -= np.einsum("mj,mj->m", d1, normal)[:, None] * normal
    out = d1 - np.einsum("mj,mj->m", d1, t)[:, None] * t           # toward the side
    lo = np.linalg.norm(out, axis=1)
    ok &= lo > 0
    out /= np.where(ok, lo, 1.0)[:, None]
    d2 = centroid_q - mid
    along = np.einsum("mj,mj->m", d2, t)
    across = np.linalg.norm(d2 - along[:, None] * t, axis=1)
    return d1 + along[:, None] * t + across[:, None] * out, ok


def pressure_coefficient(v_pert, v_inf, mach: float, rule: str = "second-order"):
    """Pressure coefficient from the perturbation velocity.

    Parameters
    ----------
    v_pert : ndarray (n, 3) [-]
        Physical perturbation velocity divided by the free-stream speed.
    v_inf : ndarray (3,) [-]
        Unit free-stream direction (the compressibility axis).
    mach : float [-]
        Free-stream Mach number.
    rule : str
        ``"linear"``: Cp = -2u; ``"second-order"`` (PANAIR's default):
        Cp = -2u - (1 - M^2) u^2 - (v^2 + w^2), u along the free stream,
        v, w across it (Epton & Magnus, PAN AIR theory document, NASA
        CR-3251, 1990, sec. E.3; Ward, *Linearized Theory of Steady
        High-Speed Flow*, 1955, eq. 5.6); ``"slender-body"``: Cp = -2u -
        (v^2 + w^2) (Ward 1955, eq. 5.7); ``"isentropic"``: the exact
        isentropic relation Cp = 2/(gamma M^2) [(1 + (gamma-1)/2 M^2 (1 -
        q^2))^(gamma/(gamma-1)) - 1] (NACA Report 1135, 1953, eq. 44 with
        the energy equation), limited at vacuum.

    Returns
    -------
    ndarray (n,) [-]
    """
    u = v_pert @ v_inf
    perp2 = np.einsum("nj,nj->n", v_pert, v_pert) - u**2
    if rule == "linear":
        return -2.0 * u
    if rule == "second-order":
        return -2.0 * u - (1.0 - mach**2) * u**2 - perp2
    if rule == "slender-body":
        return -2.0 * u - perp2
    if rule == "isentropic":
        q2 = np.einsum("nj,nj->n", v_pert + v_inf, v_pert + v_inf)
        if mach < 1e-6:
            return 1.0 - q2
        base = np.maximum(1.0 + 0.5 * (GAMMA - 1.0) * mach**2 * (1.0 - q2), 0.0)
        return 2.0 / (GAMMA * mach**2) * (base ** (GAMMA / (GAMMA - 1.0)) - 1.0)
    raise InputError(f"unknown pressure rule {rule!r}; expected one of {PRESSURE_RULES}",
                     field="pressure_rule")


def integrate_forces(cp, centroid, normal, area, *, sref, lref, xref, symmetric):
    """Force and moment coefficients from panel pressures.

    Parameters
    ----------
    cp : ndarray (n,) [-]
    centroid, normal, area : ndarray (n, 3), (n, 3), (n,)
        Physical panel centroids [m], outward unit normals [-], areas [m^2].
    sref : float [m^2]
    lref : float [m]
    xref : float [m] moment reference point (xref, 0, 0), x aft of the nose.
    symmetric : bool
        Half model: add the mirror image (y -> -y) of the pressure field.

    Returns
    -------
    dict with CA (positive aft), CY, CN (positive up), Cl (roll), Cm
    (pitch, positive nose-up), Cn (yaw) [-], body axes x aft, z up.
    """
    f = -(cp * area)[:, None] * normal
    r = centroid - np.array([xref, 0.0, 0.0])
    m = np.cross(r, f)
    F = f.sum(0)
    M = m.sum(0)
    if symmetric:
        F = np.array([2 * F[0], 0.0, 2 * F[2]])
        M = np.array([0.0, 2 * M[1], 0.0])
    return {"CA": F[0] / sref, "CY": F[1] / sref, "CN": F[2] / sref,
            "Cl": M[0] / (sref * lref), "Cm": M[1] / (sref * lref), "Cn": M[2] / (sref * lref)}
