"""Critical Mach number and transonic drag rise of fin sections (numeric-only, no SciPy).

Shared by the panel tables (:mod:`panair.transonic`) and the empirical pressure-drag
estimate (:mod:`ironbark_opt.aero.empirical_drag`):

- **Drag divergence** by Korn's equation with simple sweep theory (Korn 1970, as
  extended by Mason, "Configuration Aerodynamics", Virginia Tech, ch. 7, eq. 7-1:
  ``M_dd = kappa_A / cos L - (t/c) / cos^2 L`` at zero lift, ``kappa_A = 0.87`` for
  conventional sections), L the mid-chord sweep.
- **Critical Mach number** ``M_cr = M_dd - (0.1/80)^(1/3)``: Lock's fourth-power law
  ``dCd = 20 (M - M_cr)^4`` puts ``dCd/dM = 0.1`` at drag divergence (Mason ch. 7;
  Gur, Mason & Schetz, J. Aircraft 47(6), 2010).
"""
from __future__ import annotations

import math

import numpy as np

#: Korn's technology factor for conventional (non-supercritical) sections (Mason ch. 7)
KORN_KAPPA = 0.87
#: Lock's law: M_dd - M_cr = (0.1 / 80)^(1/3) (dCd/dM = 0.1 at M_dd with dCd = 20 (M - M_cr)^4)
LOCK_OFFSET = (0.1 / 80.0) ** (1.0 / 3.0)
#: Lock's law is followed at most to this Mach number, then faired to the sonic value [-]
LOCK_MACH_MAX = 0.95
#: Largest critical Mach number used (the fairing to Mach 1 needs room) [-]
MACH_CR_MAX = 0.95


def korn_critical_mach(root_chord: float, tip_chord: float, tip_le: float, span: float,
                       thickness: float) -> float:
    """Critical Mach number [-] of a fin: Korn's drag divergence with the mid-chord
    sweep, minus Lock's offset, at most :data:`MACH_CR_MAX`.

    ``root_chord``, ``tip_chord`` [m]; ``tip_le`` [m] the tip leading edge aft of the
    root leading edge; ``span`` [m]; ``thickness`` [m] (t/c over the mean geometric
    chord).
    """
    mean_chord = 0.5 * (root_chord + tip_chord)
    tc = thickness / max(mean_chord, 1e-300)
    tan_half = (tip_le + 0.5 * tip_chord - 0.5 * root_chord) / span
    c = math.cos(math.atan(tan_half))
    m_dd = KORN_KAPPA / c - tc / c ** 2                 # Korn / Mason eq. 7-1, c_l = 0
    return float(min(m_dd - LOCK_OFFSET, MACH_CR_MAX))


def lock_rise(mach, mach_cr: float, area_ratio: float = 1.0):
    """Lock's drag rise ``20 (M - M_cr)^4`` [-] (0 below ``mach_cr``) on a section area
    ``area_ratio`` [-] times the reference area."""
    m = np.asarray(mach, dtype=float)
    return 20.0 * np.maximum(m - mach_cr, 0.0) ** 4 * float(area_ratio)


def mccoy_head_critical_mach(tau: float) -> float:
    """Critical Mach number [-] of an ogival nose of thickness ratio ``tau`` [-]
    (base diameter / length): ``(1 + 0.552 tau^(4/5))^(-1/2)`` (McCoy, "MC DRAG - a
    computer program for estimating the drag coefficients of projectiles", BRL
    ARBRL-TR-02293, 1981; also *Modern Exterior Ballistics*, 1999, ch. 4), the Mach
    number where :func:`mccoy_head_drag_transonic` is zero."""
    return float((1.0 + 0.552 * float(tau) ** 0.8) ** -0.5)


def mccoy_head_drag_transonic(mach, tau: float):
    """Transonic pressure drag of an ogival nose [-] on its base area, at ``mach`` [-]
    up to 1: ``0.368 tau^(9/5) + 1.6 tau (M^2 - 1) / ((gamma + 1) M^2)``, 0 below the
    critical Mach number (McCoy 1981, MC DRAG, the transonic head-drag equation, a
    transonic-similarity form fitted by McCoy to ogive-headed projectiles; gamma =
    1.4).  ``tau`` [-] is the base diameter over the nose length; numeric-only."""
    m = np.maximum(np.asarray(mach, dtype=float), 1e-3)
    t = float(tau)
    return np.maximum(0.368 * t ** 1.8 + 1.6 * t * (m * m - 1.0) / (2.4 * m * m), 0.0)


def mccoy_head_drag_supersonic(mach, tau: float, head_shape: float):
    """Supersonic pressure drag of a pointed nose [-] on its base area at ``mach`` [-]
    (> 1): ``(C1 - C2 tau^2) / z (tau sqrt z)^(C3 + C4 tau)``, ``z = M^2 - 1``, with
    C1 = 0.7156 - 0.5313 R + 0.5950 R^2, C2 = 0.0796 + 0.0779 R, C3 = 1.587 + 0.049 R,
    C4 = 0.1122 + 0.1658 R (McCoy 1981, MC DRAG, the supersonic head-drag equation;
    ``head_shape`` R = R_T / R_ogive: 0 a tangent ogive, 1 a cone; ``tau`` [-] = base
    diameter / nose length).  Numeric-only; ``mach`` is floored at 1.001."""
    m = np.maximum(np.asarray(mach, dtype=float), 1.001)
    r, t = float(head_shape), float(tau)
    c1 = 0.7156 - 0.5313 * r + 0.5950 * r * r
    c2 = 0.0796 + 0.0779 * r
    c3 = 1.587 + 0.049 * r
    c4 = 0.1122 + 0.1658 * r
    z = m * m - 1.0
    return (c1 - c2 * t * t) / z * (t * np.sqrt(z)) ** (c3 + c4 * t)
