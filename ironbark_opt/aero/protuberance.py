"""Zero-lift axial force of the launch guides (rail buttons, launch lugs) and tube fins.

Both are small bluff bodies on the body surface; their drag is an increment of CA
[-, on the rocket's reference area] that depends on the Mach number and, for the
buttons, on the flight's unit Reynolds number (through the body's boundary layer).
They are therefore evaluated at flight conditions like skin friction:
:class:`~ironbark_opt.aero.friction.FrictionDrag` tabulates them with the friction
build-up on its (Mach, log10 Re per metre) grid (``protuberances=``), so every
flight that adds friction (panel tables, the empirical table) adds them too, and a
table or drag curve that already includes friction (a team's measured or
OpenRocket/RASAero curve) is taken to include them.

**Rail button** (each button a short circular cylinder standing on the wall):

- drag coefficient of a circular cylinder in cross-flow vs Mach: Gowen & Perkins,
  "Drag of circular cylinders for a wide range of Reynolds numbers and Mach
  numbers", NACA TN 2960 (1953), fig. 7 (points as transcribed in OpenRocket
  23.09's ``RailButtonCalc``), linear between them, held above Mach 2.8;
- that curve is for a two-dimensional cylinder (1.20 at low speed).  A pin
  protruding from a wall has 0.80 on its frontal area (Hoerner, *Fluid-Dynamic
  Drag*, 1965, p. 5-8; quoted by Niskanen 2013, sec. 3.4.4): the free end relieves
  the pressure behind it.  The button's coefficient is Gowen & Perkins' curve times
  0.80 / 1.20 -- an assumption that the end relief keeps its low-speed share at all
  Mach numbers (OpenRocket uses the two-dimensional value times its stagnation
  pressure coefficient instead);
- the dynamic pressure the button sees: the body's turbulent boundary layer at the
  button's station x (from the nose tip), thickness
  delta = 0.37 x Re_x^-1/5 (Prandtl's 1/7-power flat plate; Schlichting,
  *Boundary-Layer Theory*, 7th ed., eq. 21.8) with the velocity profile
  u/U = (y/delta)^(1/7) (ibid., eq. 21.4), so q(y)/q = (y/delta)^(2/7) below delta
  (density constant across the layer).  The force is the integral of q(y) over the
  button's frontal width w(y):  CA = Cd(M_loc) * int w(y) q(y)/q dy / S_ref, with
  int_0^y (y'/delta)^(2/7) dy' = (7/9) delta (y/delta)^(9/7) (y <= delta);
  M_loc = M sqrt(q_mean/q) is the Mach number of the mean dynamic pressure on the
  frontal area (where Cd is read).  OpenRocket 23.09 uses a linear profile with
  Mach at mid-height instead;
- frontal shape as OpenRocket's ``RailButton``: outer diameter over the base
  (standoff) and the flange, inner diameter over the notch between them.

**Launch lug**, an open tube on the wall (the model of OpenRocket 23.09's
``TubeCalc``, with sourced coefficients), all of it at the mean dynamic pressure of
the boundary layer over its height 2 r_o (as the buttons; Mach and Reynolds numbers
at the matching local speed):

- its frontal annulus pi (r_o^2 - r_i^2) carries the stagnation pressure of a blunt
  face, 0.85 q_stag/q (Niskanen, *OpenRocket technical documentation*, 2013,
  eq. 3.85-3.87; :func:`~ironbark_opt.aero.empirical_drag.stagnation_ratio`), and its
  rear annulus base drag (eq. 3.94, :func:`~ironbark_opt.aero.base_drag.cd_base`).
  OpenRocket multiplies their sum by 0.7 (no source given) and ignores the boundary
  layer; not here;
- the flow through the bore: the Darcy-Weisbach pressure drop f (l/d_i) q on the bore
  area pi r_i^2, f from Churchill's (1977) all-regime friction factor at
  Re_d = (Re per metre) d_i with the rocket's finish (:func:`churchill_friction_factor`;
  OpenRocket uses Swamee & Jain's turbulent formula);
- skin friction on its outer surface 2 pi r_o l: the flat plate of its own length
  (:func:`~ironbark_opt.aero.friction_flatplate.cf_flat_plate`; OpenRocket: none).
  (Niskanen's older solid-cylinder estimate, sec. 3.4.4, max(1.3 - 0.3 l/d, 1)
  0.85 q_stag/q on pi r_o^2 for l > d, treats a lug as closed; a lug of l/d ~ 5
  passes air.)

**Tube fins** (OpenRocket's ``TubeFinSet``): each tube is such an open tube
(``count`` of them), with OpenRocket 23.09's ``TubeFinSetCalc`` geometry: skin
friction only on the outer surface the body does not mask, and the interstice
between two neighbouring tubes and the body (its frontal area) carrying the blunt
face's stagnation and base pressure like the annulus
(:class:`~ironbark_opt.rocket.hardware.TubeFins`).

All ``CA`` methods are symbolic-safe.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

from ironbark_opt import _math as m
from ironbark_opt import validate as v
from ironbark_opt.aero.base_drag import cd_base
from ironbark_opt.aero.empirical_drag import stagnation_ratio
from ironbark_opt.errors import InputError

#: Gowen & Perkins (NACA TN 2960, fig. 7): Mach [-] and 2-D circular-cylinder Cd [-]
GP_MACH = (0.0, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7, 1.0, 1.6, 2.0, 2.8)
GP_CD = (1.20, 1.22, 1.25, 1.30, 1.40, 1.50, 1.60, 2.10, 1.50, 1.45, 1.33)
#: a circular pin protruding from a wall, low speed, on its frontal area (Hoerner 1965, p. 5-8)
PIN_CD = 0.80
#: Prandtl's turbulent flat plate: delta = 0.37 x Re_x^-1/5 (Schlichting, eq. 21.8)
BL_COEFFICIENT = 0.37
BL_EXPONENT = 0.2


def cylinder_cd(mach):
    """Gowen & Perkins' 2-D circular-cylinder Cd [-] at ``mach`` [-] (linear between the
    figure's points, held outside them); symbolic-safe (a sum of hinges, no table)."""
    xs, ys = GP_MACH, GP_CD
    slopes = [(ys[i + 1] - ys[i]) / (xs[i + 1] - xs[i]) for i in range(len(xs) - 1)]
    mc = m.clip(mach, xs[0], xs[-1])
    out = ys[0] + slopes[0] * (mc - xs[0])
    for i in range(1, len(slopes)):
        out = out + (slopes[i] - slopes[i - 1]) * m.fmax(mc - xs[i], 0.0)
    return out


def button_cd(mach):
    """A rail button's Cd [-] on its frontal area and local dynamic pressure:
    :func:`cylinder_cd` scaled to Hoerner's protruding pin (``PIN_CD / GP_CD[0]``)."""
    return (PIN_CD / GP_CD[0]) * cylinder_cd(mach)


def boundary_layer_thickness(x: float, reynolds_per_m):
    """Turbulent boundary-layer thickness [m] at ``x`` [m] from the nose tip;
    ``reynolds_per_m`` [1/m] (floored at 1); symbolic-safe."""
    re_x = m.fmax(reynolds_per_m, 1.0) * max(x, 1e-6)
    return BL_COEFFICIENT * max(x, 1e-6) * m.power(re_x, -BL_EXPONENT)


def q_height_integral(y: float, delta):
    """int_0^y q(y')/q dy' [m] through a 1/7-power layer of thickness ``delta`` [m]:
    (7/9) delta (y/delta)^(9/7) inside, plus (y - delta) outside; symbolic-safe."""
    inside = m.fmin(y, delta)
    return (7.0 / 9.0) * delta * m.power(inside / delta, 9.0 / 7.0) + m.fmax(y - delta, 0.0)


@dataclass(frozen=True)
class RailButtonDrag:
    """Rail buttons of one shape at stations ``x`` (see the module docstring).

    Parameters
    ----------
    x : tuple of float [m]
        Each button's station, aft of the nose tip.
    outer_diameter, inner_diameter : float [m]
    height : float [m]
        Standoff from the body surface to the top of the flange.
    base_height, flange_height : float [m]
        Outer-diameter parts at the foot and top; the notch (inner diameter) between.
    name : str
    """

    x: tuple
    outer_diameter: float
    inner_diameter: float
    height: float
    base_height: float = 0.0
    flange_height: float = 0.0
    name: str = "rail buttons"

    def __post_init__(self):
        od = v.positive(self.outer_diameter, "outer_diameter")
        idia = v.nonnegative(self.inner_diameter, "inner_diameter")
        h = v.positive(self.height, "height")
        b = v.nonnegative(self.base_height, "base_height")
        f = v.nonnegative(self.flange_height, "flange_height")
        if idia > od:
            raise InputError(f"inner_diameter ({idia} m) exceeds outer_diameter ({od} m)",
                               field="inner_diameter")
        if b + f > h:
            raise InputError(f"base_height + flange_height ({b + f} m) exceed the height ({h} m)",
                               field="flange_height")
        xs = tuple(v.nonnegative(x, "x") for x in self.x)
        if not xs:
            raise InputError("no button station", field="x")
        v.set_fields(self, x=xs, outer_diameter=od, inner_diameter=idia, height=h,
                     base_height=b, flange_height=f)

    def frontal_area(self) -> float:
        """One button's frontal area [m^2]."""
        notch = self.height - self.base_height - self.flange_height
        return self.outer_diameter * self.height - (self.outer_diameter - self.inner_diameter) * notch

    def q_weighted_area(self, delta):
        """int w(y) q(y)/q dy over one button [m^2] in a layer ``delta`` [m]; symbolic-safe."""
        od, idia, h = self.outer_diameter, self.inner_diameter, self.height
        notch = (q_height_integral(h - self.flange_height, delta)
                 - q_height_integral(self.base_height, delta))
        return od * q_height_integral(h, delta) - (od - idia) * notch

    def CA(self, mach, reynolds_per_m, reference_area: float):
        """CA [-] of all the buttons on ``reference_area`` [m^2]; symbolic-safe."""
        total = 0.0 * mach
        area = self.frontal_area()
        for x in self.x:
            qa = self.q_weighted_area(boundary_layer_thickness(x, reynolds_per_m))
            mach_local = mach * m.sqrt(qa / area)
            total = total + button_cd(mach_local) * qa
        return total / reference_area


def churchill_friction_factor(reynolds, relative_roughness: float):
    """Darcy friction factor [-] of a pipe at ``reynolds`` [-] (on its diameter) and
    ``relative_roughness`` eps/D [-], laminar through turbulent in one smooth formula:
    Churchill, "Friction-factor equation spans all fluid-flow regimes", Chemical
    Engineering 84(24), 1977: f = 8 [(8/Re)^12 + (A + B)^-1.5]^(1/12),
    A = [2.457 ln(1 / ((7/Re)^0.9 + 0.27 eps/D))]^16, B = (37530/Re)^16; symbolic-safe.
    (64/Re below Re ~ 2000; Colebrook's turbulent values within ~1 % above 4000.)"""
    re = m.fmax(reynolds, 1.0)
    a = (2.457 * m.log(1.0 / (m.power(7.0 / re, 0.9) + 0.27 * relative_roughness))) ** 16
    b = m.power(37530.0 / re, 16.0)
    return 8.0 * m.power(m.power(8.0 / re, 12.0) + m.power(a + b, -1.5), 1.0 / 12.0)


@dataclass(frozen=True)
class LaunchLugDrag:
    """A launch lug: an open tube on the body wall (module docstring).

    Parameters
    ----------
    x : float [m]
        Station of its middle, aft of the nose tip (boundary layer).
    length, outer_radius, inner_radius : float [m]
    roughness : float [m]
        Sand-grain roughness of its surfaces (the rocket's finish).
    name : str
    """

    x: float
    length: float
    outer_radius: float
    inner_radius: float
    roughness: float = 0.0
    name: str = "launch lug"
    #: outer surface with skin friction [m^2] (None: the whole 2 pi r_o l)
    wetted_area: float | None = None
    #: blunt frontal area besides the annulus [m^2] (stagnation + base, as the annulus)
    extra_frontal_area: float = 0.0
    #: identical tubes (a tube fin set) [-]
    count: int = 1

    def __post_init__(self):
        ro = v.positive(self.outer_radius, "outer_radius")
        ri = v.nonnegative(self.inner_radius, "inner_radius")
        if not ri < ro:
            raise InputError(f"inner_radius ({ri} m) must be smaller than outer_radius ({ro} m)",
                             field="inner_radius")
        length = v.positive(self.length, "length")
        k = v.nonnegative(self.roughness, "roughness")
        if not k < min(length, 2.0 * ri if ri > 0 else length):
            raise InputError(f"roughness ({k} m) must be smaller than the bore and the length",
                             field="roughness")
        wetted = 2.0 * math.pi * ro * length if self.wetted_area is None else \
            v.nonnegative(self.wetted_area, "wetted_area", "m^2")
        v.set_fields(self, x=v.nonnegative(self.x, "x"), length=length, outer_radius=ro,
                     inner_radius=ri, roughness=k, wetted_area=wetted,
                     extra_frontal_area=v.nonnegative(self.extra_frontal_area, "extra_frontal_area", "m^2"),
                     count=int(v.positive(self.count, "count")))

    def q_ratio(self, reynolds_per_m):
        """Mean q over the lug's height 2 r_o in the body's boundary layer / free-stream q [-]."""
        h = 2.0 * self.outer_radius
        return q_height_integral(h, boundary_layer_thickness(self.x, reynolds_per_m)) / h

    def CA(self, mach, reynolds_per_m, reference_area: float):
        """CA [-] on ``reference_area`` [m^2]; symbolic-safe."""
        from ironbark_opt.aero.friction_flatplate import cf_flat_plate
        ro, ri, length = self.outer_radius, self.inner_radius, self.length
        ratio = self.q_ratio(reynolds_per_m)
        speed = m.sqrt(ratio)                                   # local / free-stream velocity
        mach_local, re_local = mach * speed, m.fmax(reynolds_per_m, 1.0) * speed
        ca = (0.85 * stagnation_ratio(mach_local) + cd_base(mach_local)) \
            * (math.pi * (ro * ro - ri * ri) + self.extra_frontal_area)
        if ri > 0.0:
            d = 2.0 * ri
            f = churchill_friction_factor(re_local * d, self.roughness / d)
            ca = ca + f * (length / d) * math.pi * ri * ri
        cf = cf_flat_plate(mach_local, re_local * length, length, self.roughness)
        ca = ca + cf * self.wetted_area
        return self.count * ratio * ca / reference_area
