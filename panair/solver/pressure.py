"""Surface velocity from the doublet solution, pressure rules, and the
integration of pressure into forces and moments.  Numeric-only.
"""
from __future__ import annotations

import numpy as np

from ironbark_opt.errors import InputError

__all__ = ["surface_gradient", "pressure_coefficient", "integrate_forces", "PRESSURE_RULES"]

PRESSURE_RULES = ("linear", "second-order", "slender-body", "isentropic")
GAMMA = 1.4


def surface_gradient(phi, centroid, normal, neighbours):
    """Tangential gradient of a panel-centred surface potential.

    Least-squares fit over the structured-grid neighbours, in the tangent
    plane of each panel (the finite-difference approach of Katz & Plotkin,
    *Low-Speed Aerodynamics*, 2001, sec. 12.5, generalised to a weighted
    least-squares fit so one-sided and mirror neighbours need no special
    formula).

    Parameters
    ----------
    phi : ndarray (n,) [m^2/s per (m/s)]
        Potential per unit free-stream speed at panel centroids.
    centroid, normal : ndarray (n, 3)
        Panel centroids [m] and unit normals [-].
    neighbours : ndarray (n, 4) of int
        Neighbour indices, -1 none, -2 mirror image in y = 0.

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
    valid &= np.einsum("nkj,nj->nk", nq, normal) > 0.5
    dphi = np.where(nb >= 0, phi[idx] - phi[:, None], 0.0)  # mirror: same phi
    dx = cq - centroid[:, None, :]
    dx -= np.einsum("nkj,nj->nk", dx, normal)[..., None] * normal[:, None, :]
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
