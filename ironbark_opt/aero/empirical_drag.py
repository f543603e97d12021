"""Interim pressure-drag estimate from geometry (an AeroTable with ``includes=("pressure",)``).

Used when a rocket file (e.g. an OpenRocket .ork) carries no drag data;
:func:`~ironbark_opt.aero.model.build_aero_model` adds skin friction and
base drag.  The built-in panel solver will replace it.  Parts, all from
S. Niskanen, *Development of an Open Source model rocket simulation
software* (OpenRocket technical documentation, 2013), sec. 3.4:

- stagnation pressure ratio q_stag/q = 1 + M^2/4 + M^4/40 (M < 1),
  1.84 - 0.76/M^2 + 0.166/M^4 + 0.035/M^6 (M > 1)  (eq. 3.85-3.86);
- nose cone: subsonic 0.8 sin^2(phi) with phi the joint half-angle of the
  nose profile (eq. 3.81; above M = 1 times q_stag/q), or, where larger, its
  wave drag by McCoy's MC DRAG (BRL ARBRL-TR-02293, 1981): transonic head drag
  from his critical Mach number to Mach 1, supersonic head drag (with his
  head-shape parameter R_T/R) from Mach 1.15 (:func:`nose_pressure_ca`; before
  session 16 a nose meeting the body tangentially had no wave drag here at all);
- a blunt (flat) forward face, e.g. a booster's front after separation, whose
  body starts with a tube: the stagnation pressure on it, 0.85 q_stag/q on
  its area pi r_front^2 (eq. 3.87; Hoerner, *Fluid-Dynamic Drag*, 1965,
  ch. 3, the flat-faced cylinder; eq. 3.81 at phi = 90 deg gives 0.8 subsonic);
- fin leading edges, square: 0.85 q_stag/q (eq. 3.87), on the frontal area
  thickness x span x count, times cos^2 of the leading-edge sweep;
- streamlined fin sections (rounded, airfoil, bevelled double wedge): no
  pressure drag below their critical Mach number (attached subcritical flow,
  d'Alembert; Korn's drag divergence minus Lock's offset,
  :mod:`ironbark_opt.aero.compressibility`), Lock's rise 20 (M - M_cr)^4 on the
  exposed planform above it until it reaches the sonic value or Mach 0.95, then
  linear to the sonic value at Mach 1: OpenRocket's rounded-edge drag
  1.214 - 0.502/M^2 + 0.1095/M^4 (M >= 1, eq. 3.89) on the frontal area, which
  carries on above Mach 1.  (OpenRocket applies eq. 3.89's subsonic branch
  (1 - M^2)^-0.417 - 1 from Mach 0, which makes drag rise from Mach 0.5 on
  thick or airfoil fins: Calisto's NACA 0012 fins gave CA 0.18 of leading-edge
  drag at Mach 0.82, where its measured curve is flat.)
- fin trailing edges: the base-drag coefficient (eq. 3.94) on the same
  frontal area for a square (blunt) trailing edge, half of it for a rounded
  one, none for sharp ones (as OpenRocket's FinSetCalc; see
  :attr:`~ironbark_opt.rocket.fin_sections.FinSection.trailing_edge_base_fraction`);
- boattail transitions: the base-drag coefficient times the annulus area
  and a length factor 1 (gamma < 1), (3 - gamma)/2 (1-3), 0 (> 3) with
  gamma = L / (d_fore - d_aft) (eq. 3.88).

Numeric-only (builds a table); the table itself is evaluated symbolically.
"""
from __future__ import annotations

import numpy as np

from ironbark_opt import _math
from ironbark_opt.aero.base_drag import cd_base
from ironbark_opt.aero.compressibility import LOCK_MACH_MAX, korn_critical_mach, lock_rise
from ironbark_opt.aero.table import AeroTable
from ironbark_opt.rocket.body import Transition
from ironbark_opt.rocket.nose import NoseCone

#: Mach grid of the table [-]
MACH = np.concatenate([np.linspace(0.0, 0.8, 9), np.linspace(0.85, 1.2, 8), np.linspace(1.3, 3.0, 9)])


def stagnation_ratio(mach):
    """q_stag / q [-] (Niskanen 2013, eq. 3.85-3.86); symbolic-safe."""
    m = mach if _math.is_symbolic(mach) else np.asarray(mach, dtype=float)
    ms = _math.fmax(m, 1.0)
    return _math.if_else(m < 1.0, 1.0 + m ** 2 / 4.0 + m ** 4 / 40.0,
                         1.84 - 0.76 / ms ** 2 + 0.166 / ms ** 4 + 0.035 / ms ** 6)


def rounded_le(mach):
    """Rounded fin leading-edge pressure drag [-] (Niskanen 2013, eq. 3.89); numeric-only."""
    m = np.asarray(mach, dtype=float)
    sub = np.clip(1.0 - np.minimum(m, 0.9) ** 2, 1e-9, None) ** -0.417 - 1.0
    trans = 1.0 - 1.785 * (m - 0.9)
    ms = np.maximum(m, 1.0)
    sup = 1.214 - 0.502 / ms ** 2 + 0.1095 / ms ** 4
    return np.where(m < 0.9, sub, np.where(m < 1.0, trans, sup))


def leading_edge_cd(mach, kind: str):
    """Fin leading-edge pressure drag on its frontal area [-] (Niskanen 2013): a
    square edge 0.85 q_stag/q (eq. 3.87); streamlined ones (rounded, airfoil,
    bevelled double wedge) eq. 3.89, as OpenRocket does for airfoils; numeric-only."""
    m = np.asarray(mach, dtype=float)
    return 0.85 * stagnation_ratio(m) if kind == "square" else rounded_le(m)


def joint_half_angle(comp) -> float:
    """Angle [rad] between a nose (or transition) profile's last segment and the axis:
    the half-angle of its joint with the next part (2001-point profile)."""
    x, r = comp.profile(2001)
    return float(np.arctan(abs(r[-1] - r[-2]) / (x[-1] - x[-2])))


def separated_pressure_ca(rocket, mach, streamlined_edges: bool = True,
                          nose_wave: bool = False) -> np.ndarray:
    """Zero-lift pressure drag a potential-flow solution cannot have [-] on the
    rocket's reference area vs Mach (numeric-only): a flat forward face (eq. 3.87),
    blunt nose joints (eq. 3.81),
    boattails and other contracting transitions as separated flow with
    base-like pressure on the annulus (eq. 3.88; an abrupt step down between two
    components as one of length 0, a step up as a flat forward face), fin leading edges (eq. 3.87,
    3.89).  Fin trailing edges are base drag (:class:`~ironbark_opt.aero.base_drag.BaseDrag`).

    ``streamlined_edges=False`` leaves out the leading-edge drag of streamlined
    (rounded, airfoil, bevelled) edges, keeping only square (separated) ones: below
    the critical Mach number their flow is attached and subcritical, so they have no
    pressure drag (d'Alembert); eq. 3.89's rise stands for their compressibility
    drag, which the panel tables take from the critical-Mach model instead
    (:mod:`panair.transonic`).  ``nose_wave=True`` gives the nose at the front its
    wave drag too (:func:`nose_pressure_ca`, the empirical path's :func:`pressure_ca`);
    the panel tables have their own."""
    m = np.asarray(mach, dtype=float)
    a_ref = rocket.reference_area()
    ca = np.zeros_like(m)
    q = stagnation_ratio(m)
    front = rocket.front_component()
    r_front = 0.0 if isinstance(front, NoseCone) else float(getattr(front, "fore_radius", getattr(front, "radius", 0.0)))
    if r_front > 0.0:                       # blunt forward face (eq. 3.87, Hoerner ch. 3)
        ca += 0.85 * q * np.pi * r_front ** 2 / a_ref
    for comp in rocket.body_components():
        if isinstance(comp, NoseCone):
            # a nose further aft (after a separation) has only its joint
            ca += (nose_pressure_ca(comp, m, a_ref) if nose_wave and comp is front
                   else _nose_joint_ca(comp, m, a_ref))
        elif isinstance(comp, Transition) and comp.aft_radius < comp.fore_radius:
            ca += boattail_separation_fraction(comp) * np.asarray(cd_base(m), dtype=float) \
                * np.pi * (comp.fore_radius ** 2 - comp.aft_radius ** 2) / a_ref
    body = sorted(rocket.body_components(), key=lambda c: c.x)
    for a, b in zip(body[:-1], body[1:]):
        # an abrupt step between two components (no transition): a step down is a
        # contracting transition of length 0, fully separated (eq. 3.88, gamma 0 < 1),
        # base pressure on its annulus; a step up a flat forward face (eq. 3.87)
        step = b.fore_radius - a.aft_radius
        if abs(step) <= 1e-9 * a.aft_radius:                 # a joint, rounding apart
            continue
        annulus = np.pi * abs(a.aft_radius ** 2 - b.fore_radius ** 2) / a_ref
        ca += (np.asarray(cd_base(m), dtype=float) if step < 0 else 0.85 * q) * annulus
    for fins in rocket.fin_sets():
        edge = fins.section.leading_edge_kind
        if not streamlined_edges and edge != "square":
            continue
        frontal = fins.thickness * fins.span * fins.count / a_ref
        sweep = np.arctan2(fins.sweep_length, fins.span)
        ca += leading_edge_cd(m, edge) * np.cos(sweep) ** 2 * frontal
    return ca


def _nose_joint_ca(nose, mach, a_ref: float) -> np.ndarray:
    """Separated-flow drag of a nose's joint [-] (eq. 3.81, times q_stag/q above Mach 1)."""
    m = np.asarray(mach, dtype=float)
    sub = 0.8 * np.sin(joint_half_angle(nose)) ** 2 * nose.radius ** 2 * np.pi / a_ref
    return np.where(m < 1.0, sub, sub * stagnation_ratio(m))


#: Largest angle [rad] between a nose's profile and the body at its shoulder for the nose
#: to meet the body tangentially (an ogival nose: McCoy's R_T / R = 0 here, and the panel
#: tables' transonic nose model, :func:`panair.rocket_table.ogival_nose`)
OGIVAL_JOINT_MAX = float(np.radians(1.0))


def head_shape_ratio(nose) -> float:
    """McCoy's head-shape parameter R_T / R [-] of a nose (MC DRAG: 0 a tangent ogive, 1 a
    cone): a secant ogive's tangent-ogive radius over its own; a cone 1; a nose meeting
    the body tangentially (joint angle below :data:`OGIVAL_JOINT_MAX`) 0; any other shape (power series,
    parabolic K < 1) its joint angle over the half-angle of the cone of the same length
    and base (our interpolation between McCoy's two ends)."""
    if nose.shape == "conical":
        return 1.0
    if nose.shape == "secant_ogive":
        rho_t = (nose.radius ** 2 + nose.length ** 2) / (2.0 * nose.radius)
        return float(np.clip(rho_t / nose.ogive_radius, 0.0, 1.0))
    joint = joint_half_angle(nose)
    if joint < OGIVAL_JOINT_MAX:
        return 0.0
    return float(np.clip(joint / np.arctan(nose.radius / nose.length), 0.0, 1.0))


#: Mach numbers over which the empirical nose drag goes from McCoy's transonic to his
#: supersonic equation (quintic smooth step; our choice: MC DRAG's two equations meet there)
NOSE_BLEND_MACH = (1.0, 1.15)


def nose_pressure_ca(nose, mach, a_ref: float) -> np.ndarray:
    """Pressure drag of a pointed nose [-] on ``a_ref`` [m^2] vs ``mach`` [-]
    (numeric-only): the larger of its joint's separated-flow drag (eq. 3.81) and its wave
    drag by McCoy's MC DRAG (1981): none below his critical Mach number, his transonic
    head drag up to Mach 1, his supersonic head drag (R_T / R from
    :func:`head_shape_ratio`) from Mach 1.15, a smooth step between
    (:data:`NOSE_BLEND_MACH`).  McCoy's supersonic equation is within -9 ... +9 % of the
    exact cone (Taylor-Maccoll) at Mach 1.2-4.3 on a 10 deg cone; an ogive-family fit,
    it stands for the other pointed shapes too."""
    from ironbark_opt.aero.compressibility import (mccoy_head_drag_supersonic,
                                                   mccoy_head_drag_transonic)
    from ironbark_opt.aero.friction_flatplate import smooth_step
    m = np.asarray(mach, dtype=float)
    tau = 2.0 * nose.radius / nose.length
    sonic = mccoy_head_drag_transonic(np.minimum(m, 1.0), tau)
    sup = mccoy_head_drag_supersonic(m, tau, head_shape_ratio(nose))
    lo, hi = NOSE_BLEND_MACH
    w = np.asarray(smooth_step(m, lo, hi), dtype=float)
    wave = np.where(m <= lo, sonic, (1.0 - w) * sonic + w * sup)
    return np.maximum(_nose_joint_ca(nose, m, a_ref), wave * nose.radius ** 2 * np.pi / a_ref)


def boattail_separation_fraction(transition) -> float:
    """Fraction [-] of a contracting transition's annulus that carries base
    pressure (Niskanen 2013, eq. 3.88): 1 for gamma < 1, (3 - gamma)/2 for
    1 <= gamma <= 3, 0 above, gamma = length / (fore diameter - aft diameter)."""
    d1, d2 = 2 * transition.fore_radius, 2 * transition.aft_radius
    if d2 >= d1:
        return 0.0
    gamma = transition.length / (d1 - d2)
    return 1.0 if gamma < 1 else ((3.0 - gamma) / 2.0 if gamma < 3 else 0.0)


def streamlined_fin_ca(fins, mach, reference_area: float) -> np.ndarray:
    """Compressibility pressure drag [-] of a fin set with a streamlined section
    (rounded, airfoil, bevelled) on ``reference_area`` [m^2] vs ``mach`` [-]: 0 below
    the critical Mach number, Lock's rise, the rounded-edge sonic and supersonic value
    (see the module docstring); numeric-only."""
    m = np.asarray(mach, dtype=float)
    _, le, chord = fins.outline(1)
    m_cr = korn_critical_mach(float(chord[0]), float(chord[-1]), float(le[-1]), fins.span,
                              fins.thickness)
    frontal = fins.thickness * fins.span * fins.count / reference_area
    edge = np.cos(np.arctan2(fins.sweep_length, fins.span)) ** 2 * frontal
    sonic = float(rounded_le(1.0)) * edge
    planform = fins.count * fins.planform_area() / reference_area
    rise = np.minimum(lock_rise(m, m_cr, planform), sonic)
    at_max = float(np.minimum(lock_rise(LOCK_MACH_MAX, m_cr, planform), sonic))
    ramp = at_max + (sonic - at_max) * (m - LOCK_MACH_MAX) / (1.0 - LOCK_MACH_MAX)
    return np.where(m >= 1.0, rounded_le(m) * edge, np.where(m > LOCK_MACH_MAX, ramp, rise))


def pressure_ca(rocket, mach) -> np.ndarray:
    """Pressure-drag CA [-] on the rocket's reference area vs Mach (numeric-only):
    :func:`separated_pressure_ca` (square fin edges, the nose's wave drag), :func:`streamlined_fin_ca`
    (other fin sections) and blunt fin trailing edges (eq. 3.94)."""
    m = np.asarray(mach, dtype=float)
    ca = separated_pressure_ca(rocket, m, streamlined_edges=False, nose_wave=True)
    for fins in rocket.fin_sets():
        if fins.section.leading_edge_kind != "square":
            ca += streamlined_fin_ca(fins, m, rocket.reference_area())
    for fins in rocket.fin_sets():
        ca += np.asarray(cd_base(m), dtype=float) * fins.trailing_edge_base_area() / rocket.reference_area()
    return ca


def pressure_drag_table(rocket) -> AeroTable:
    """AeroTable of CA (pressure parts only) over :data:`MACH`, independent of alpha."""
    ca = pressure_ca(rocket, MACH)
    return AeroTable(MACH, [0.0], {"CA": ca[:, None]}, reference_area=rocket.reference_area(),
                     reference_length=2.0 * rocket.reference_radius(), moment_reference_x=0.0,
                     includes=("pressure",),
                     metadata={"generator": "ironbark_opt.aero.empirical_drag",
                               "method": "Niskanen 2013 sec. 3.4 pressure drag (interim estimate)"})
