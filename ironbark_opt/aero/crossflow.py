"""Viscous cross-flow normal force of a body of revolution (Allen & Perkins; Jorgensen).

The body's non-linear (separated-flow) normal force, the part a potential
solution or slender-body theory lacks, as the drag of the flow component normal
to the axis on each cross-section:

    CN_viscous = eta(l/d) * Cdc(M_c) * (A_plan / A_ref) * sin^2(alpha),  M_c = M sin(alpha)

acting at the centroid of the body's planform.

Sources: [AP51] H. J. Allen and E. W. Perkins, "A Study of Effects of
Viscosity on Flow over Slender Inclined Bodies of Revolution", NACA Report
1048, 1951 (the cross-flow term eta Cdc (A_p/A_ref) sin^2 alpha, and eta as the
ratio of the drag of a finite circular cylinder to that of an infinite one,
from Goldstein's finite-cylinder data).  [J77] L. H. Jorgensen, "Prediction of
Static Aerodynamic Characteristics for Slender Bodies Alone and with Lifting
Surfaces to Very High Angles of Attack", NASA TR R-474, 1977, eq. (1) and the
two figures of the method: eta against the body's fineness ratio l/d, and the
cross-flow drag coefficient Cdc of a circular cylinder against the cross-flow
Mach number M_c = M sin(alpha) (the latter from Gowen & Perkins, NACA TN 2960,
1953, and other cylinder data); repeated in L. H. Jorgensen, NASA TP-1376, 1979.

Choices:

* Both curves are tabulated below as read from [J77]'s figures at round
  abscissae (reading accuracy about +-0.01 in eta, +-0.05 in Cdc); nothing is
  fitted to any validation case.
* Reynolds number: the **subcritical** cylinder curve of [J77] (Cdc = 1.2 at
  low M_c) is used at all Reynolds numbers.  The supercritical (drag-crisis)
  values at low M_c (~0.3-0.5) need a cross-flow Reynolds number
  rho V sin(alpha) d / mu above ~3e5 for a smooth cylinder; a rocket body
  reaches large angles of attack at low speed (rail exit in wind: V ~ 30 m/s,
  d ~ 0.1 m, V sin(alpha) d / nu ~ 1e5, subcritical), and by M_c ~ 0.4-0.5 the
  two curves of [J77] have merged (compressibility removes the drag crisis,
  Gowen & Perkins).  Where a fast rocket sees a small angle, the cross-flow
  term is small (sin^2 alpha) and its zero slope at alpha = 0 leaves CN-alpha
  and the static margin unchanged.  An aero table has no Reynolds axis for CN
  either, so a Reynolds-dependent Cdc could not be flown consistently.
* eta(l/d): piecewise linear in the fineness ratio (a geometry constant),
  clamped to the figure's range (l/d 1 ... 40).  Cdc(M_c): an interpolating
  cubic B-spline (CasADi ``bspline``) through the tabulated points, M_c
  clamped to [0, 4]; the same CasADi function evaluates numbers and symbols,
  so tables, the VM and compiled code agree exactly, and CN is C2 in Mach and
  angle of attack.
* Fineness ratio l/d: body length over maximum body diameter (Jorgensen's
  bodies: length over base = maximum diameter).

Symbolic-safe in ``alpha`` and ``mach`` (floats, NumPy arrays, CasADi SX/MX).
"""
from __future__ import annotations

import casadi as ca
import numpy as np

from ironbark_opt import _math as m
from ironbark_opt.validate import nonnegative as _non_negative
from ironbark_opt.validate import positive as _positive

#: [AP51] fig. (eta against l/d, Goldstein's finite cylinders), as [J77]'s eta figure:
#: fineness ratio l/d [-] and eta [-]
ETA_FINENESS = np.array([1.0, 2.0, 4.0, 6.0, 8.0, 10.0, 12.0, 16.0, 20.0, 24.0, 28.0, 32.0, 40.0])
ETA = np.array([0.55, 0.57, 0.61, 0.64, 0.66, 0.68, 0.70, 0.73, 0.75, 0.77, 0.785, 0.80, 0.81])

#: [J77] cross-flow drag coefficient of a circular cylinder, subcritical cross-flow
#: Reynolds number, against the cross-flow Mach number M_c = M sin(alpha) [-]
#: (from Gowen & Perkins, NACA TN 2960)
CDC_MACH = np.array([0.0, 0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7, 0.8, 0.9, 1.0, 1.1, 1.2, 1.4,
                     1.6, 1.8, 2.0, 2.5, 3.0, 4.0])
CDC = np.array([1.20, 1.20, 1.20, 1.21, 1.25, 1.33, 1.45, 1.62, 1.80, 1.95, 2.02, 2.00, 1.90, 1.70,
                1.58, 1.52, 1.48, 1.42, 1.38, 1.32])

_CDC_FN: list = []


def eta(fineness_ratio: float) -> float:
    """Finite-length cross-flow factor eta [-] of a body of fineness ratio l/d [-]
    ([AP51]/[J77] figure, piecewise linear, clamped to l/d 1 ... 40); numeric-only."""
    fr = _positive(fineness_ratio, "fineness_ratio", "")
    return float(np.interp(fr, ETA_FINENESS, ETA))


def _cdc_function() -> ca.Function:
    """The interpolating cubic B-spline ``M_c -> Cdc`` (built once)."""
    if not _CDC_FN:
        _CDC_FN.append(ca.interpolant("crossflow_cdc", "bspline", [CDC_MACH], CDC))
    return _CDC_FN[0]


def cdc(mach_crossflow):
    """Cross-flow drag coefficient Cdc [-] of a circular cylinder at the cross-flow
    Mach number [-] ([J77] figure, subcritical Reynolds number); symbolic-safe."""
    mc = m.clip(mach_crossflow, float(CDC_MACH[0]), float(CDC_MACH[-1]))
    fn = _cdc_function()
    if m.is_symbolic(mc):
        return fn(mc)
    flat = np.ravel(np.asarray(mc, dtype=float))
    out = np.array(fn(flat[None, :])).ravel()
    return float(out[0]) if np.ndim(mc) == 0 else out.reshape(np.shape(mc))


def normal_force(alpha, mach, planform_area: float, reference_area: float, fineness_ratio: float):
    """CN_viscous = eta Cdc(M sin alpha) (A_plan/A_ref) sin^2 alpha [-] ([J77] eq. 1).

    Parameters
    ----------
    alpha : float, array or CasADi [rad]
        Total angle of attack (0 .. pi).
    mach : float, array or CasADi [-]
        Free-stream Mach number (broadcast against ``alpha``).
    planform_area : float [m^2]
        Side-view area of the body.
    reference_area : float [m^2]
    fineness_ratio : float [-]
        Body length over maximum diameter.
    """
    a_plan = _non_negative(planform_area, "planform_area", "m^2")
    aref = _positive(reference_area, "reference_area", "m^2")
    k = eta(fineness_ratio) * a_plan / aref
    s = m.sin_angle(alpha)
    return k * cdc(mach * m.fabs(s)) * s * s


def axial_factor(alpha):
    """Angle-of-attack factor of an axial-force part that has no incidence model of its
    own (skin friction, base drag, a zero-lift drag curve) [-]; symbolic-safe.

    Jorgensen's axial force of a body to very high angles of attack, NASA TR R-474,
    1977, eq. (2): CA(alpha) = CA(alpha = 0) cos^2 alpha, 0 <= alpha <= 90 deg (the flow
    component along the axis carries the axial force).  ``alpha`` [rad] is the total
    angle of attack; past 90 deg (flying tail first) the factor is held at 0, as the
    tables hold their last angle.
    """
    c = m.fmax(m.cos_angle(alpha), 0.0)
    return c * c

