"""Transonic zero-lift pressure drag from the geometry and the panel solutions.

Linearised potential flow has no solution near Mach 1, and below it a
Prandtl-Glauert panel solution has no compressibility drag at all, so the
zero-lift pressure drag ``P(M)`` of a table is assembled from three sourced
pieces (the angle-of-attack increments stay the panel solutions', faired
across the gap by :func:`panair.bridge.transonic_bridge`):

1. **Below the critical Mach number** ``M_cr``: attached subsonic flow has no
   pressure drag (d'Alembert), so the panel solution's zero-lift residual is
   discretisation error (measured about -0.02 ... +0.02 on finned bodies) and
   is replaced by the separated-flow and edge drag a potential solution cannot
   have: blunt nose joints, boattails and fin leading edges (Niskanen 2013,
   OpenRocket technical documentation sec. 3.4, eq. 3.81, 3.88, 3.89;
   :func:`ironbark_opt.aero.empirical_drag.separated_pressure_ca`).  A
   boattail that eq. 3.88 calls separated carries base pressure on its
   annulus, never the panel method's attached-flow suction.
2. **The critical Mach number of the configuration** is the lowest of
   - the body's: the free-stream Mach number at which the body's minimum
     surface pressure coefficient, taken from the lowest-Mach panel solution
     (scaled back to incompressible by its Prandtl-Glauert factor) and
     corrected for compressibility by the Karman-Tsien rule
     (Tsien, J. Aeronaut. Sci. 6, 1939), reaches the sonic pressure
     coefficient Cp* (isentropic, gamma = 1.4) — :func:`body_critical_mach`;
   - each fin set's: Korn's drag-divergence equation with simple sweep theory
     (Korn 1970, as extended by Mason, "Configuration Aerodynamics", Virginia
     Tech, ch. 7, eq. 7-1: M_dd = kappa_A / cos L - (t/c) / cos^2 L, kappa_A =
     0.87 for conventional sections, zero lift) and Lock's fourth-power
     drag-rise law, which puts the critical Mach number (0.1/80)^(1/3) = 0.108
     below M_dd (Mason ch. 7; Gur, Mason & Schetz, J. Aircraft 47(6), 2010) —
     :func:`fin_critical_mach`.
3. **Between M_cr and the first supersonic panel solution** the drag rises
   by Lock's fourth-power law, dCA = 20 (M - M_cr)^4 on the exposed fin
   planform (Lock; Mason ch. 7) — through the drag-divergence Mach number
   M_dd = M_cr + 0.108 and on (it follows measured section drag to about
   Mach 0.9, e.g. NACA 0012) until it reaches the sonic value or Mach 0.95 —
   then monotonically to the wave drag at Mach 1, and joins the supersonic
   solutions.  The sonic value
   is the first supersonic solution's zero-lift pressure drag: by the
   transonic area rule (Whitcomb, NACA Rep. 1273, 1956) and slender-body
   theory (Ward, Q. J. Mech. Appl. Math. 2, 1949) the wave drag of a slender
   configuration near Mach 1 is that of its equivalent body and independent
   of Mach number, so the supersonic linear-theory value carries down to
   Mach 1.  The fairing is the monotone cubic Hermite interpolant of
   Fritsch & Carlson (1980), as :mod:`panair.bridge`.
4. **An ogival nose** (one meeting the body tangentially: tangent ogive,
   Haack / von Karman, parabolic K = 1, elliptical) does not carry its
   supersonic wave drag down to Mach 1: free-flight data of fineness-3 noses
   (Stoney, NASA TR R-100, 1961, p. 16; tests/data/aero/stoney_tr_r100)
   measure a quarter to a third of their Mach 1.2 drag at Mach 1 (von Karman
   0.027 / 0.081, LV-Haack 0.024 / 0.100, parabolic K = 1 0.041 / 0.119).  Its
   drag rises by McCoy's transonic head-drag equation (MC DRAG, BRL
   ARBRL-TR-02293, 1981: critical Mach number (1 + 0.552 tau^(4/5))^(-1/2),
   0.368 tau^(9/5) at Mach 1, tau = base diameter / length;
   :func:`nose_transonic`), and in the sonic anchor its share of the first
   supersonic solution (:func:`nose_supersonic_share`) is replaced by that
   sonic value; the fairing then carries it up to the supersonic solution.
   Noses with a shoulder angle (cones, power series, parabolic K < 1, secant
   ogives) keep the area-rule anchor: their data stay near the Mach 1.2 value
   at Mach 1 (power 3/4, parabolic K = 1/2 and 3/4: 0.7-0.9 of it), and
   McCoy's equation, fitted to ogive-headed projectiles, gives a 10 deg cone a
   third of Hoerner's sonic cone drag sin(half-angle).

Numeric-only (:func:`nose_supersonic_share` runs the supersonic solver).
"""
from __future__ import annotations

import numpy as np
from scipy.interpolate import PchipInterpolator
from scipy.optimize import brentq

from ironbark_opt.aero.compressibility import (LOCK_MACH_MAX, LOCK_OFFSET, MACH_CR_MAX,
                                                korn_critical_mach, lock_rise,
                                                mccoy_head_critical_mach,
                                                mccoy_head_drag_transonic)

GAMMA = 1.4
#: Mach number of the sonic anchor of the fairing [-]
MACH_SONIC = 1.0

__all__ = ["cp_sonic", "karman_tsien", "body_critical_mach", "fin_critical_mach",
           "zero_lift_pressure", "nose_transonic", "nose_supersonic_share", "LOCK_OFFSET"]


def cp_sonic(mach):
    """Sonic (critical) pressure coefficient Cp* [-] at free-stream ``mach`` [-]
    (isentropic flow, gamma = 1.4)."""
    m2 = np.asarray(mach, float) ** 2
    g = GAMMA
    return 2.0 / (g * m2) * (((2.0 + (g - 1.0) * m2) / (g + 1.0)) ** (g / (g - 1.0)) - 1.0)


def karman_tsien(cp0, mach):
    """Compressible pressure coefficient [-] from the incompressible ``cp0`` [-]
    at ``mach`` [-] (Karman-Tsien rule, Tsien 1939)."""
    m2 = np.asarray(mach, float) ** 2
    beta = np.sqrt(1.0 - m2)
    return cp0 / (beta + m2 / (1.0 + beta) * cp0 / 2.0)


def body_critical_mach(cp0_min: float) -> float:
    """Free-stream Mach number [-] at which the minimum pressure coefficient
    ``cp0_min`` [-] (incompressible) becomes sonic (Karman-Tsien = Cp*).

    ``cp0_min >= 0`` (no suction anywhere) returns :data:`MACH_CR_MAX`.
    """
    if not (cp0_min < 0):
        return MACH_CR_MAX
    f = lambda m: float(karman_tsien(cp0_min, m) - cp_sonic(m))
    # scan upward (the Karman-Tsien denominator vanishes for strong suction near Mach 1;
    # the critical Mach number is the first crossing below that)
    grid = np.linspace(0.05, 0.999, 400)
    beta = np.sqrt(1.0 - grid ** 2)
    ok = beta + grid ** 2 / (1.0 + beta) * cp0_min / 2.0 > 0
    vals = np.array([f(m) if k else -1.0 for m, k in zip(grid, ok)])
    if vals[0] < 0:          # sonic already at Mach 0.05: a singular panel, not the body
        return float(grid[0])
    neg = np.nonzero(vals < 0)[0]
    if not len(neg):
        return MACH_CR_MAX
    i = int(neg[0])
    return min(float(brentq(f, grid[i - 1], grid[i], xtol=1e-7)), MACH_CR_MAX)


def fin_critical_mach(fin) -> float:
    """Critical Mach number [-] of a fin set (:class:`panair.mesh.FinGeometry`):
    Korn's equation with the mid-chord sweep, minus Lock's offset.

    t/c is the thickness over the mean geometric chord; the sweep is that of
    the line joining root and tip mid-chords.
    """
    return korn_critical_mach(float(fin.chord_at(0.0)), float(fin.chord_at(1.0)),
                              float(fin.le_at(1.0)), fin.span, fin.thickness)


def nose_transonic(tau: float, area_ratio: float):
    """(critical Mach number [-], ``rise(mach)`` [-]) of an ogival nose (item 4 of the
    module docstring): McCoy's transonic head drag on the nose's base area times
    ``area_ratio`` [-] (nose base area / reference area), held at its sonic value
    above Mach 1; ``tau`` [-] = base diameter / nose length."""
    return (mccoy_head_critical_mach(tau),
            lambda m: mccoy_head_drag_transonic(np.minimum(np.asarray(m, float), MACH_SONIC),
                                                tau) * float(area_ratio))


def nose_supersonic_share(body, mach: float, x_end: float, *, sref: float, options=None,
                          pressure_rule: str = "second-order"):
    """Zero-lift pressure CA [-] (on ``sref`` [m^2]) of the body's panels ahead of
    ``x_end`` [m] (the nose) in the built-in supersonic solution at ``mach`` [-] of the
    body alone (``body``: :class:`panair.mesh.BodyGeometry`), meshed with ``options``
    (the sweep's supersonic options, :func:`panair.sweep.supersonic_mesh_options`); None
    where linear theory has no solution there.  Supersonic flow at zero incidence: nothing aft of the nose
    (fins, boattails) acts on it, so the body alone gives the full configuration's
    nose share."""
    from ironbark_opt.errors import SolverError

    from .mesh import MeshOptions, RocketGeometry, mesh_rocket
    from .solver import build_panels, make_solver
    from .solver.pressure import integrate_forces
    opt = options or MeshOptions().for_mach(mach)
    panels = build_panels(mesh_rocket(RocketGeometry(body), symmetric=True, options=opt),
                          symmetric=True)
    try:
        res = make_solver(panels, mach, sref=sref, lref=1.0, xref=0.0,
                          pressure_rule=pressure_rule).solve(0.0)[0]
    except SolverError:
        return None
    _, c, n, a = panels.geometry()
    sel = c[:, 0] < x_end
    return float(integrate_forces(res.cp[sel], c[sel], n[sel], a[sel], sref=sref, lref=1.0,
                                  xref=0.0, symmetric=True)["CA"])


def zero_lift_pressure(mach_out, mach_cr: float, subsonic, mach_sup, p_sup,
                       lock_sets=(), nose=None):
    """Zero-lift pressure CA P(M) [-] at ``mach_out`` [-] (see module docstring).

    Parameters
    ----------
    mach_out : 1-D array [-]
    mach_cr : float [-]
        Critical Mach number of the configuration.
    subsonic : callable mach -> P [-]
        The subsonic (separated-flow and edge) pressure drag, used up to ``mach_cr``.
    mach_sup : 1-D array [-]
        Supersonic Mach numbers solved (>= 1.2), may be empty only if every
        ``mach_out`` is <= ``mach_cr``.
    p_sup : 1-D array [-]
        Their zero-lift pressure CA.
    lock_sets : sequence of (float, float), optional
        Each fin set's own critical Mach number [-] and exposed planform over the
        reference area [-]: the rise is then the sum of Lock's law of every set from
        its own critical Mach number (a section property: a thick camera pod meshed as
        a fin set must not put the main fins' planform into drag rise at its Mach
        number).  Between the critical Mach number and drag divergence the rise is
        the sum of ``20 (M - M_cr,i)^4 * ratio_i`` (Lock; Mason ch. 7), above it the
        monotone fairing to the sonic value.
    nose : (callable, float), optional
        An ogival nose's own transonic drag ``rise(mach)`` [-] (on the reference area,
        0 below its critical Mach number; :func:`nose_transonic`) and its share [-] of
        the first supersonic solution's zero-lift pressure drag.  The nose then rises
        by ``rise`` up to Mach 1 and its sonic value is ``rise(1)`` instead of its
        first supersonic value (module docstring, item 4).

    Returns
    -------
    ndarray [-], same length as ``mach_out``.
    """
    m = np.asarray(mach_out, float)
    mach_sup = np.asarray(mach_sup, float)
    p_sup = np.asarray(p_sup, float)
    out = np.asarray(subsonic(np.minimum(m, mach_cr)), float).copy()
    gap = m > mach_cr
    if not np.any(gap):
        return out
    if len(mach_sup) == 0:
        raise ValueError("a supersonic solution is needed above the critical Mach number")
    # anchors: the subsonic curve just below M_cr (its slope), M_cr, Lock's law to M_dd,
    # Mach 1 (sonic value), the supersonic solutions
    m_lo = np.array([max(mach_cr - 0.05, 0.0), mach_cr])
    p_lo = np.asarray(subsonic(m_lo), float)
    # Lock's law as the shape of the rise, through drag divergence, until it reaches the
    # sonic value or Mach LOCK_MACH_MAX; then the monotone fairing to Mach 1
    step = LOCK_OFFSET / 4.0
    m_lock = mach_cr + step * np.arange(1, int(np.ceil((LOCK_MACH_MAX - mach_cr) / step)) + 1)
    m_lock = m_lock[m_lock <= LOCK_MACH_MAX + 1e-12]
    rise = sum((lock_rise(m_lock, m_i, a_i) for m_i, a_i in lock_sets), 0.0 * m_lock)
    p_sonic = float(p_sup[0])
    if nose is not None:
        nose_rise, nose_share = nose
        rise = rise + np.asarray(nose_rise(m_lock), float)
        p_sonic += float(nose_rise(MACH_SONIC)) - float(nose_share)
    p_lock = np.asarray(subsonic(m_lock), float) + rise
    below = p_lock < p_sonic
    below[:min(4, len(below))] = True                 # always through M_dd = M_cr + 0.108
    m_lock, p_lock = m_lock[below], p_lock[below]
    p_sonic = max(p_sonic, float(p_lock[-1]) if len(p_lock) else p_sonic)
    xs = np.concatenate([m_lo, m_lock, [MACH_SONIC], mach_sup])
    ys = np.concatenate([p_lo, p_lock, [p_sonic], np.maximum(p_sup, 0.0 * p_sup)])
    keep = np.concatenate([[True], np.diff(xs) > 1e-9])
    fair = PchipInterpolator(xs[keep], ys[keep], extrapolate=True)
    sup = m >= mach_sup[0]
    out[gap & ~sup] = fair(m[gap & ~sup])
    out[sup] = np.interp(m[sup], mach_sup, p_sup) if len(mach_sup) > 1 else p_sup[0]
    return out
