"""Barrowman normal-force slope and centre of pressure from geometry.

Linear normal-force slope ``CN_alpha`` [1/rad] and centre of pressure
``x_cp`` [m aft of the nose tip] of each component (slender body + Barrowman),
the baseline and cross-check of the panel solver.  Functions take plain
numbers, so any geometry class can feed them.

Sources: [B66] J. S. and J. A. Barrowman, "The Theoretical Prediction of the
Center of Pressure", NARAM-8, 1966.  [B67] J. S. Barrowman, "The Practical
Calculation of the Aerodynamic Characteristics of Slender Finned Vehicles",
M.Sc. thesis, 1967.  [N13] S. Niskanen, "OpenRocket technical documentation",
v13.05, 2013, ch. 3.

Choices:

* ``CN_alpha`` is the **linear** part only (slope at alpha = 0); a body tube
  has none, its large-angle lift is :func:`body_lift` (viscous cross-flow).
* Symbolic-safe in ``mach`` (floats, NumPy, CasADi SX/MX); geometry is plain
  floats checked with :class:`~ironbark_opt.errors.InputError`.
* Fin slope: Diederich/Barrowman with beta = sqrt(1 - M^2) ([N13] eq. 3.40)
  up to ``MACH_SUBSONIC``; the linear supersonic flat-plate slope 4/beta,
  beta = sqrt(M^2 - 1), from ``MACH_SUPERSONIC``; a cubic Hermite (values
  and slopes matched) between, so it is C1 in Mach.  OpenRocket's code uses
  the one-surface Busemann coefficient K1 = 2/beta for the fin normal force
  ([N13] eq. 3.41-3.45), half the pressure jump across a plate; we use the
  two-surface (Ackeret) value c_l = 4 alpha / sqrt(M^2 - 1) (e.g. J. D.
  Anderson, "Fundamentals of Aerodynamics", ch. 12), which meets the
  subsonic curve of typical fins nearly continuously.  No fin-tip Mach-cone
  loss (as [N13]).
* Fin CP: quarter MAC for M <= 0.5 ([B66] eq. 75); (A beta - 0.67) /
  (2 A beta - 1) of the MAC for M >= 2 ([N13] eq. 3.35 = NACA Report 1307
  eq. 63, valid for A beta >= 1, so A beta is held >= 1); a cubic Hermite
  between (OpenRocket: a quintic with the same end values).
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import NamedTuple, Sequence

import numpy as np

from ironbark_opt import _math as m
from ironbark_opt.aero import crossflow
from ironbark_opt.errors import InputError
from ironbark_opt.validate import nonnegative as _non_negative
from ironbark_opt.validate import number as _number
from ironbark_opt.validate import positive as _positive

MACH_SUBSONIC = 0.9        #: subsonic fin formulas up to this Mach number
MACH_SUPERSONIC = 1.5      #: supersonic fin formulas from this Mach number
MACH_CP_SUBSONIC = 0.5     #: fin CP at the quarter MAC up to this Mach number
MACH_CP_SUPERSONIC = 2.0   #: supersonic empirical fin CP from this Mach number

# fin-fin interference by total fin count, [N13] eq. 3.54 (six and eight fins give
# 1.37 and 1.62 times the four-fin slope, MIL-HDBK/DATCOM p. 5-24)
_FIN_COUNT_FACTOR = {5: 0.948, 6: 0.913, 7: 0.854, 8: 0.810}


class Lift(NamedTuple):
    """Linear normal-force slope of one component and where it acts.

    cn_alpha : float or CasADi [1/rad], referenced to the caller's area;
    x_cp : float or CasADi [m] aft of the nose tip; name : str label.
    """
    cn_alpha: object
    x_cp: object
    name: str = ""


# ---------------------------------------------------------------- bodies of revolution

def nose_volume(shape: str, length: float, radius: float, parameter: float | None = None) -> float:
    """Volume of a standard nose shape [m^3]; numeric-only.

    Closed forms of the integral of pi r(x)^2 over the profiles of [N13]
    appendix A.  Other shapes (secant ogive, ...): pass ``volume`` to
    :func:`nose_cone`.

    Parameters
    ----------
    shape : str
        ``conical``, ``ogive`` (tangent), ``ellipsoid``, ``power`` (n in
        (0, 1]), ``parabolic`` (K in [0, 1]), ``haack`` (C in [0, 2/3]),
        ``von_karman`` (C = 0), ``lv_haack`` (C = 1/3).
    length, radius : float [m]
        Nose length and base radius.
    parameter : float, optional [-]
        Shape parameter (n, K or C).
    """
    L = _positive(length, "length")
    R = _positive(radius, "radius")
    key = str(shape).strip().lower().replace(" ", "_").replace("-", "_")
    need = {"power": (0.0, 1.0), "parabolic": (0.0, 1.0), "haack": (0.0, 2.0 / 3.0)}
    if key in need:
        if parameter is None:
            raise InputError(f"shape '{key}' needs a shape parameter", field="parameter")
        p = _number(parameter, "parameter")
        lo, hi = need[key]
        if not (lo <= p <= hi) or (key == "power" and p == 0.0):
            raise InputError(f"parameter of shape '{key}' must be in "
                             f"{'(' if key == 'power' else '['}{lo:g}, {hi:.4g}], got {p:g}",
                             field="parameter")
    base = math.pi * R * R * L
    if key in ("conical", "cone"):
        return base / 3.0
    if key in ("ogive", "tangent_ogive"):
        # r = sqrt(rho^2 - (L - x)^2) + R - rho, rho = (R^2 + L^2)/(2R), integrated
        rho = (R * R + L * L) / (2.0 * R)
        return math.pi * (rho * rho * L - L ** 3 / 3.0 - (rho - R) * rho * rho * math.asin(L / rho))
    if key in ("ellipsoid", "elliptical"):
        return 2.0 * base / 3.0
    if key == "power":
        return base / (2.0 * p + 1.0)
    if key == "parabolic":                    # r = R (2u - K u^2)/(2 - K), u = x/L
        return base * (4.0 / 3.0 - p + p * p / 5.0) / (2.0 - p) ** 2
    if key in ("haack", "von_karman", "lv_haack"):
        # r^2 = R^2/pi (th - sin(2 th)/2 + C sin^3 th), x = L/2 (1 - cos th)
        c = {"von_karman": 0.0, "lv_haack": 1.0 / 3.0}.get(key, parameter)
        return 0.5 * base * (1.0 + 3.0 * float(c) / 8.0)
    raise InputError(f"unknown nose shape '{shape}'; expected conical, ogive, ellipsoid, "
                     "power, parabolic, haack, von_karman or lv_haack", field="shape")


def _body(x_fore, length, radius_fore, radius_aft, volume, reference_area, name) -> Lift:
    a_fore, a_aft = math.pi * radius_fore ** 2, math.pi * radius_aft ** 2
    if abs(a_aft - a_fore) <= 1e-12 * max(a_aft, a_fore):
        return Lift(0.0, x_fore + 0.5 * length, name)
    cna = 2.0 * (a_aft - a_fore) / reference_area          # [B66] eq. 10
    # [B66] eq. 28: x_cp = (L S(L) - V)/(S(L) - S(0)) from the fore end
    return Lift(cna, x_fore + (length * a_aft - volume) / (a_aft - a_fore), name)


def nose_cone(length: float, base_radius: float, reference_area: float, *,
              volume: float | None = None, shape: str = "conical",
              parameter: float | None = None, x_tip: float = 0.0) -> Lift:
    """Nose: CN_alpha = 2 A_base/A_ref, x_cp = L - V/A_base ([B66] eq. 12, 28).

    Mach-independent (slender-body theory; [B67] leaves body compressibility
    out).  Numeric-only.

    Parameters
    ----------
    length, base_radius : float [m]
    reference_area : float [m^2]
    volume : float, optional [m^3]
        Nose volume; default :func:`nose_volume` of ``shape``/``parameter``.
    shape : str; parameter : float, optional [-]
        For :func:`nose_volume` (ignored when ``volume`` is given).
    x_tip : float [m]
        Station of the tip.
    """
    L = _positive(length, "length")
    R = _positive(base_radius, "base_radius")
    aref = _positive(reference_area, "reference_area", "m^2")
    V = nose_volume(shape, L, R, parameter) if volume is None else _positive(volume, "volume", "m^3")
    if V >= math.pi * R * R * L:
        raise InputError(f"nose volume {V:g} m^3 exceeds that of its enclosing cylinder",
                         field="volume")
    return _body(_number(x_tip, "x_tip"), L, 0.0, R, V, aref, "nose")


def transition(x_fore: float, length: float, radius_fore: float, radius_aft: float,
               reference_area: float, *, volume: float | None = None) -> Lift:
    """Shoulder/boattail: CN_alpha = 2 (A_aft - A_fore)/A_ref ([B66] eq. 14-15).

    CP from the volume ([B66] eq. 28); for a conical frustum (``volume``
    omitted) that is x = L/3 [1 + (1 - r)/(1 - r^2)], r = d_fore/d_aft
    ([B66] eq. 44).  A boattail's slope is negative.  Numeric-only.

    Parameters
    ----------
    x_fore : float [m]
        Fore end, aft of the nose tip.
    length, radius_fore, radius_aft : float [m]
    reference_area : float [m^2]
    volume : float, optional [m^3]
        Volume of a non-conical transition.
    """
    L = _positive(length, "length")
    r1 = _non_negative(radius_fore, "radius_fore")
    r2 = _non_negative(radius_aft, "radius_aft")
    aref = _positive(reference_area, "reference_area", "m^2")
    if volume is None:
        V = math.pi * L / 3.0 * (r1 * r1 + r1 * r2 + r2 * r2)  # frustum
    else:
        V = _positive(volume, "volume", "m^3")
    return _body(_number(x_fore, "x_fore"), L, r1, r2, V, aref, "transition")


def body_tube(x_fore: float, length: float, radius: float) -> Lift:
    """Cylinder: no linear normal force ([B66] eq. 13); Lift(0, mid-length).

    Parameters: x_fore [m] aft of the nose tip, length [m], radius [m].
    Numeric-only.
    """
    _positive(radius, "radius")
    return Lift(0.0, _number(x_fore, "x_fore") + 0.5 * _positive(length, "length"), "body")


BODY_LIFT_K = 1.1
"""Galejs' constant cross-flow coefficient K ([N13] eq. 3.26), for ``body_lift(k=...)``."""


def body_lift(alpha, planform_area: float, planform_centroid_x: float,
              reference_area: float, *, mach=0.0, fineness_ratio: float | None = None,
              k: float | None = None):
    """Non-linear (viscous cross-flow) body lift at the planform centroid.

    By default Allen & Perkins' viscous cross-flow as Jorgensen (NASA TR R-474,
    eq. 1): CN = eta(l/d) Cdc(M sin alpha) (A_plan/A_ref) sin^2(alpha), see
    :mod:`ironbark_opt.aero.crossflow`.  With ``k``: the constant-coefficient
    form CN = K (A_plan/A_ref) sin^2(alpha) of R. Galejs, "Wind instability -
    what Barrowman left out" (NAR Sentinel 39), as [N13] eq. 3.26 (K = 1.1,
    :data:`BODY_LIFT_K`).  Zero slope at alpha = 0, so not part of :class:`Lift`.
    Symbolic-safe in ``alpha`` and ``mach``.

    Parameters
    ----------
    alpha : float, array or CasADi [rad]
        Total angle of attack (0 .. pi).
    planform_area : float [m^2]
        Side-view area of the body.
    planform_centroid_x : float [m]
        Its centroid, aft of the nose tip.
    reference_area : float [m^2]
    mach : float, array or CasADi [-]
        Free-stream Mach number (the cross-flow Mach number is M sin alpha).
    fineness_ratio : float [-]
        Body length over maximum diameter; needed unless ``k`` is given.
    k : float or None [-]
        Constant cross-flow coefficient (Galejs) instead of eta Cdc.

    Returns (CN [-], x_cp [m]).
    """
    a_plan = _non_negative(planform_area, "planform_area", "m^2")
    aref = _positive(reference_area, "reference_area", "m^2")
    x_cp = _number(planform_centroid_x, "planform_centroid_x")
    if k is not None:
        s = m.sin_angle(alpha)
        return _non_negative(k, "k", "") * a_plan / aref * s * s, x_cp
    if fineness_ratio is None:
        raise InputError("the viscous cross-flow needs the body's fineness ratio (or a constant k)",
                         field="fineness_ratio")
    return crossflow.normal_force(alpha, mach, a_plan, aref, fineness_ratio), x_cp


# ---------------------------------------------------------------- fin planforms

@dataclass(frozen=True)
class FinPlanform:
    """One fin's planform, x aft from the root leading edge, y spanwise from the root.

    span [m]; area [m^2] (one fin); mac_length [m] (int c^2 dy / area);
    mac_x_le [m] (MAC leading edge); mac_y [m] (MAC station = area
    centroid); cos_midchord_sweep [-]; chord_moment_1 = int c y dy [m^3];
    chord_moment_2 = int c y^2 dy [m^4].
    """
    span: float
    area: float
    mac_length: float
    mac_x_le: float
    mac_y: float
    cos_midchord_sweep: float
    chord_moment_1: float
    chord_moment_2: float

    @property
    def aspect_ratio(self) -> float:
        """Aspect ratio of one fin, 2 s^2 / A_fin [-] ([N13] symbol list)."""
        return 2.0 * self.span ** 2 / self.area

    def roll_integral(self, body_radius: float) -> float:
        """int c(xi) xi^2 dxi over the fin, xi = body_radius [m] + y [m^4]."""
        r = body_radius
        return r * r * self.area + 2.0 * r * self.chord_moment_1 + self.chord_moment_2


def trapezoid_planform(root_chord: float, tip_chord: float, span: float,
                       sweep_length: float) -> FinPlanform:
    """Trapezoidal fin in closed form ([B66] eq. 69-76); numeric-only.

    Parameters
    ----------
    root_chord, tip_chord, span : float [m]
        (tip chord may be 0).
    sweep_length : float [m]
        Axial distance from the root to the tip leading edge.
    """
    cr = _positive(root_chord, "root_chord")
    ct = _non_negative(tip_chord, "tip_chord")
    s = _positive(span, "span")
    xt = _number(sweep_length, "sweep_length")
    area = 0.5 * (cr + ct) * s
    # [B66] eq. 69: MAC; eq. 70: its span station; eq. 74: its leading edge
    mac = 2.0 / 3.0 * (cr + ct - cr * ct / (cr + ct))
    y_mac = s / 3.0 * (cr + 2.0 * ct) / (cr + ct)
    x_mac = xt / 3.0 * (cr + 2.0 * ct) / (cr + ct)
    cos_g = s / math.hypot(s, xt + 0.5 * ct - 0.5 * cr)   # mid-chord line
    # c(y) = cr + (ct - cr) y/s: int c y dy and int c y^2 dy ([N13] eq. 3.70 terms)
    return FinPlanform(s, area, mac, x_mac, y_mac, cos_g,
                       s * s * (cr + 2.0 * ct) / 6.0, s ** 3 * (cr + 3.0 * ct) / 12.0)


def elliptical_planform(root_chord: float, span: float) -> FinPlanform:
    """Elliptical fin, c(y) = Cr sqrt(1 - (y/s)^2), straight mid-chord; numeric-only.

    Closed forms of [N13] eq. 3.30-3.32 and 3.71.  root_chord, span [m].
    """
    cr = _positive(root_chord, "root_chord")
    s = _positive(span, "span")
    mac = 8.0 * cr / (3.0 * math.pi)          # int c^2 dy = 2/3 Cr^2 s
    return FinPlanform(s, math.pi * cr * s / 4.0, mac, 0.5 * (cr - mac),  # x_le = (Cr - c)/2
                       4.0 * s / (3.0 * math.pi), 1.0,
                       cr * s * s / 3.0, math.pi * cr * s ** 3 / 16.0)


def polygon_planform(points: Sequence[Sequence[float]], n_strips: int = 400) -> FinPlanform:
    """Free-form fin by strip integration of its outline polygon; numeric-only.

    As [N13] §3.2.2: each spanwise strip's chord runs from the leading to the
    trailing edge (a jagged edge is filled in for the MAC, CP and roll
    integrals); the area used for the normal force is the true polygon area;
    the mid-chord sweep is the mean angle between consecutive strip
    mid-points ([N13] fig. 3.4).

    Parameters
    ----------
    points : sequence of (x, y) [m]
        Outline in order, x aft from the root leading edge, y >= 0 spanwise
        from the root; the closing edge is implied.  At least 3 points.
    n_strips : int
        Number of spanwise strips (midpoint rule).
    """
    try:
        pts = np.asarray(points, dtype=float)
    except (TypeError, ValueError):
        raise InputError("fin points must be a sequence of (x, y) pairs [m]", field="points") from None
    if pts.ndim != 2 or pts.shape[1] != 2 or pts.shape[0] < 3:
        raise InputError(f"expected at least 3 (x, y) points, got array of shape {pts.shape}",
                         field="points")
    if not np.all(np.isfinite(pts)):
        raise InputError("fin points must be finite numbers", field="points")
    if np.min(pts[:, 1]) < -1e-12:
        raise InputError("fin points must have y >= 0 (y is spanwise from the root)",
                         field="points")
    x, y = pts[:, 0], pts[:, 1]
    s = float(np.max(y))
    area = 0.5 * abs(float(np.dot(x, np.roll(y, -1)) - np.dot(y, np.roll(x, -1))))
    if s <= 0.0 or area <= 0.0:
        raise InputError("fin outline has zero span or zero area", field="points")
    n = int(n_strips)
    if n < 10:
        raise InputError(f"n_strips must be >= 10, got {n_strips}", field="n_strips")
    dy = s / n
    ys = (np.arange(n) + 0.5) * dy
    lead, trail = np.full(n, np.inf), np.full(n, -np.inf)
    for xa, ya, xb, yb in zip(x, y, np.roll(x, -1), np.roll(y, -1)):
        if ya == yb:
            continue
        sel = (ys >= min(ya, yb)) & (ys <= max(ya, yb))
        xi = xa + (ys[sel] - ya) * (xb - xa) / (yb - ya)
        lead[sel] = np.minimum(lead[sel], xi)
        trail[sel] = np.maximum(trail[sel], xi)
    ok = np.isfinite(lead) & np.isfinite(trail)
    c = np.where(ok, trail - lead, 0.0)
    lead = np.where(ok, lead, 0.0)
    a_strip = float(np.sum(c) * dy)
    mid = lead + 0.5 * c
    cos_g = float(np.mean(dy / np.hypot(np.diff(mid[ok]), dy))) if np.sum(ok) > 1 else 1.0
    return FinPlanform(s, area, float(np.sum(c * c) * dy / a_strip),
                       float(np.sum(lead * c) * dy / a_strip), float(np.sum(ys * c) * dy / a_strip),
                       cos_g, float(np.sum(c * ys) * dy), float(np.sum(c * ys * ys) * dy))


# ---------------------------------------------------------------- Mach blending

def hermite_bridge(mach, m0: float, m1: float, y0: float, y1: float, d0: float, d1: float):
    """Cubic Hermite on [m0, m1] (clipped) with end values y0, y1 and slopes d0, d1 [per Mach].

    Symbolic-safe.
    """
    h = m1 - m0
    t = (m.clip(mach, m0, m1) - m0) / h
    t2 = t * t
    t3 = t2 * t
    return ((2 * t3 - 3 * t2 + 1) * y0 + (t3 - 2 * t2 + t) * h * d0
            + (-2 * t3 + 3 * t2) * y1 + (t3 - t2) * h * d1)


def transonic_blend(mach, sub, sup, m_sub: float = MACH_SUBSONIC, m_sup: float = MACH_SUPERSONIC):
    """Join a subsonic and a supersonic law C1-continuously across [m_sub, m_sup].

    ``sub(M)`` / ``sup(M)`` return ``(value, d value/dM)``, symbolic-safe in
    M; they are evaluated at min(M, m_sub) and max(M, m_sup), so neither
    branch (nor its derivative) sees the other's Mach range.  Symbolic-safe
    in ``mach`` [-].
    """
    v0, d0 = sub(m_sub)
    v1, d1 = sup(m_sup)
    low = sub(m.fmin(mach, m_sub))[0]
    high = sup(m.fmax(mach, m_sup))[0]
    mid = hermite_bridge(mach, m_sub, m_sup, float(v0), float(v1), float(d0), float(d1))
    out = m.if_else(mach <= m_sub, low, m.if_else(mach >= m_sup, high, mid))
    if not m.is_symbolic(out) and np.ndim(out) == 0:
        return float(out)
    return out


# ---------------------------------------------------------------- fins

def fin_count_factor(count: int) -> float:
    """Fin-fin interference factor [-] of [N13] eq. 3.54: 1 up to 4 fins,
    0.948/0.913/0.854/0.810 for 5-8, 0.75 beyond."""
    n = int(count) if isinstance(count, (int, float, np.integer, np.floating)) else -1
    if n != count or n < 1:
        raise InputError(f"fin count must be a positive integer, got {count!r}", field="count")
    return 1.0 if n <= 4 else _FIN_COUNT_FACTOR.get(n, 0.75)


def interference_factor(span: float, body_radius: float) -> float:
    """Fin-in-body factor K_T(B) = 1 + r_t/(s + r_t) [-] ([B66] eq. 77); span, body_radius [m]."""
    s = _positive(span, "span")
    r = _non_negative(body_radius, "body_radius")
    return 1.0 + r / (s + r)


def slender_body_interference(span: float, body_radius: float) -> float:
    """Fin-body lift factor with the body's carry-over, K_W(B) + K_B(W) = (1 + r/(s + r))^2 [-]
    (slender-body theory, Pitts, Nielsen & Kaattari, NACA Report 1307, 1957), for
    references; Barrowman's :func:`interference_factor` is its first factor only (no
    lift carried over onto the body).  span, body_radius [m]."""
    return interference_factor(span, body_radius) ** 2


def single_fin_cn_alpha(planform: FinPlanform, mach, reference_area: float, section_slope=None):
    """Slope of one isolated fin, angle to its plane [1/rad]; symbolic-safe in ``mach``.

    Subsonic, [N13] eq. 3.40 (Diederich; [B66] eq. 57 at M = 0):
    2 pi s^2/A_ref / (1 + sqrt(1 + (beta s^2/(A_fin cos G_c))^2)).
    Supersonic (Ackeret, see module notes): 4/beta A_fin/A_ref.  Bridged by
    :func:`transonic_blend`.  planform : FinPlanform; mach [-];
    reference_area [m^2].

    ``section_slope``: a callable c(M) [1/rad], the 2-D section lift-curve slope
    (:mod:`ironbark_opt.rocket.fin_files`; numeric ``mach`` only) replacing the
    thin-airfoil 2 pi / beta in Diederich's formula (as RocketPy does for airfoil
    fins): 2 pi s^2/A_ref / (1 + sqrt(1 + (2 pi s^2/(A_fin cos G_c c(M)))^2)),
    the thin airfoil's c = 2 pi / beta giving eq. 3.40 back.  Subsonic branch only.
    """
    aref = _positive(reference_area, "reference_area", "m^2")
    s2 = planform.span ** 2
    k = s2 / (planform.area * planform.cos_midchord_sweep)
    a_sub = 2.0 * math.pi * s2 / aref
    a_sup = 4.0 * planform.area / aref

    def sub(M):
        if section_slope is not None:
            if m.is_symbolic(M):
                raise InputError("a fin lift-curve or polar file needs numeric Mach numbers (the flight "
                                 "tabulates the fin slopes)", field="lift_curve")
            M = np.asarray(M, dtype=float)
            h = 1e-5
            c = section_slope(M)
            dc = (section_slope(M + h) - section_slope(np.maximum(M - h, 0.0))) / (M + h - np.maximum(M - h, 0.0))
            r = 2.0 * math.pi * k / c
            q = np.sqrt(1.0 + r * r)
            return a_sub / (1.0 + q), a_sub / (1.0 + q) ** 2 * (r / q) * (2.0 * math.pi * k * dc / (c * c))
        q = m.sqrt(1.0 + (1.0 - M * M) * k * k)
        return a_sub / (1.0 + q), a_sub * M * k * k / (q * (1.0 + q) ** 2)

    def sup(M):
        b2 = M * M - 1.0
        return a_sup / m.sqrt(b2), -a_sup * M / (b2 * m.sqrt(b2))

    return transonic_blend(mach, sub, sup)


def fin_cp_fraction(aspect_ratio: float, mach):
    """Fin CP as a fraction of the MAC aft of its leading edge [-]; symbolic-safe in ``mach``.

    0.25 up to M = 0.5 ([B66] eq. 75); from M = 2, (A beta - 0.67)/(2 A beta
    - 1) with A beta held >= 1 ([N13] eq. 3.35); cubic Hermite between (zero
    slope at 0.5, matched slope at 2).  aspect_ratio = 2 s^2/A_fin [-].
    """
    ar = _positive(aspect_ratio, "aspect_ratio", "-")

    def sup(M):
        beta = m.sqrt(M * M - 1.0)
        x = ar * beta
        xc = m.fmax(x, 1.0)
        dfdx = 0.34 / (2.0 * xc - 1.0) ** 2
        return (xc - 0.67) / (2.0 * xc - 1.0), m.if_else(x < 1.0, 0.0 * x, dfdx * ar * M / beta)

    def sub(M):
        return 0.25 + 0.0 * M, 0.0 * M

    return transonic_blend(mach, sub, sup, MACH_CP_SUBSONIC, MACH_CP_SUPERSONIC)


def fins(planform: FinPlanform, count: int, x_root_le: float, body_radius: float,
         reference_area: float, mach=0.0, section_slope=None) -> Lift:
    """Fin set in the presence of the body ([B66] eq. 57-59, 76-78; [N13] §3.2.2).

    CN_alpha = K_T(B) f_N (N/2) (CN_alpha)_1: fin-in-body factor K_T(B),
    fin-count factor f_N ([N13] eq. 3.54), N/2 = sum of sin^2 of the fin
    dihedral angles ([N13] eq. 3.53; exact for N >= 3, the roll average for
    1-2 fins).  For 3 and 4 fins at M = 0 this is Barrowman's
    K_T(B) {12, 16} (s/d)^2 / (1 + sqrt(1 + (2 l/(Cr + Ct))^2)) ([B66] eq.
    58-59).  x_cp = x_root_le + MAC LE + :func:`fin_cp_fraction` * MAC.
    Symbolic-safe in ``mach``.  Elliptical and free-form fins enter through
    :func:`elliptical_planform` / :func:`polygon_planform`.

    Parameters
    ----------
    planform : FinPlanform
    count : int
        Fins N in the set.
    x_root_le : float [m]
        Root leading edge, aft of the nose tip.
    body_radius : float [m]
        Body radius at the fins.
    reference_area : float [m^2]
    mach : float, array or CasADi [-]
    section_slope : callable or None
        The section's lift-curve slope c(M) [1/rad] from a file
        (:func:`single_fin_cn_alpha`); None: thin airfoil.
    """
    f_n = fin_count_factor(count)
    k_tb = interference_factor(planform.span, body_radius)
    cna = k_tb * f_n * 0.5 * int(count) * single_fin_cn_alpha(planform, mach, reference_area, section_slope)
    frac = fin_cp_fraction(planform.aspect_ratio, mach)
    x_cp = _number(x_root_le, "x_root_le") + planform.mac_x_le + frac * planform.mac_length
    return Lift(cna, x_cp, "fins")


def tube_fins(count: int, x_le: float, length: float, inner_radius: float,
              reference_area: float, mach=0.0) -> Lift:
    """A tube fin set: each of the ``count`` tubes a ring wing of diameter 2 r_i and chord
    l, CN_alpha = 2 A'/(1 + A') pi^2 r_i l / S_ref with A' = 2 A / pi, A = 2 r_i / l
    (Ribner, "The ring airfoil in nonaxial flow", J. Aeronaut. Sci. 14(9), 1947, eq. 5, as
    OpenRocket 23.09's TubeFinSetCalc applies it): a ring's lift does not depend on its
    roll position, so every tube counts; interference between the tubes and with the
    body is neglected (as there).  x_cp = x_le + :func:`fin_cp_fraction` (A) l.
    Symbolic-safe in ``mach``; lengths [m], reference_area [m^2]."""
    r, c = _positive(inner_radius, "inner_radius", "m"), _positive(length, "length", "m")
    ar = 2.0 * r / c
    a_prime = 2.0 * ar / math.pi
    cna = int(count) * 2.0 * a_prime / (1.0 + a_prime) * math.pi ** 2 * r * c \
        / _positive(reference_area, "reference_area", "m^2")
    x_cp = _number(x_le, "x_le") + fin_cp_fraction(ar, mach) * c
    return Lift(cna + 0.0 * mach, x_cp, "tube fins")


def trapezoidal_fins(count: int, root_chord: float, tip_chord: float, span: float,
                     sweep_length: float, x_root_le: float, body_radius: float,
                     reference_area: float, mach=0.0) -> Lift:
    """:func:`fins` of :func:`trapezoid_planform`; symbolic-safe in ``mach``.

    count [-]; root_chord, tip_chord, span, sweep_length (leading-edge sweep
    distance), x_root_le (aft of the nose tip), body_radius [m];
    reference_area [m^2]; mach [-].
    """
    plan = trapezoid_planform(root_chord, tip_chord, span, sweep_length)
    return fins(plan, count, x_root_le, body_radius, reference_area, mach)


# ---------------------------------------------------------------- combination

def total(components: Sequence[Lift]):
    """(sum CN_alpha [1/rad], slope-weighted x_cp [m]) ([B66] eq. 79-80); symbolic-safe."""
    comps = list(components)
    if not comps:
        raise InputError("need at least one component", field="components")
    cna = 0.0
    moment = 0.0
    for c in comps:
        cna = cna + c.cn_alpha
        moment = moment + c.cn_alpha * c.x_cp
    if not m.is_symbolic(cna) and np.any(np.asarray(cna) == 0.0):
        raise InputError("total normal-force slope is zero: the CP is undefined",
                         field="components")
    return cna, moment / cna


def pitch_moment_slope(components: Sequence[Lift], x_ref, reference_length: float):
    """Cm_alpha about ``x_ref`` [1/rad], nose-up positive: -sum CN_alpha_i (x_cp_i - x_ref)/d.

    Symbolic-safe.  x_ref [m] aft of the nose tip; reference_length d [m].
    """
    d = _positive(reference_length, "reference_length")
    cm = 0.0
    for c in components:
        cm = cm - c.cn_alpha * (c.x_cp - x_ref) / d
    return cm


def static_margin(x_cp, x_cg, reference_length: float):
    """Static margin (x_cp - x_cg)/d [calibers], positive = stable; symbolic-safe.

    x_cp, x_cg [m] aft of the nose tip; reference_length d [m].
    """
    return (x_cp - x_cg) / _positive(reference_length, "reference_length")
