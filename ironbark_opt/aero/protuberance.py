"""Zero-lift axial force of the launch guides: rail buttons and launch lugs.

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

**Launch lug** (Niskanen, *OpenRocket technical documentation*, 2013, sec. 3.4.4,
"parasitic drag", after Hoerner 1965, pp. 3-11 and 5-8):
CD = max(1.3 - 0.3 l/d, 1) * 0.85 q_stag/q on the area
pi r_o^2 - pi r_i^2 max(1 - l/d, 0), d = 2 r_o, with the stagnation-pressure ratio
of eq. 3.85-3.86 (:func:`~ironbark_opt.aero.empirical_drag.stagnation_ratio`); the
skin friction of its outer surface is a friction component
(:func:`~ironbark_opt.aero.model.friction_components`).

All ``CA`` methods are symbolic-safe.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ironbark_opt import _math as m
from ironbark_opt import validate as v
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


@dataclass(frozen=True)
class LaunchLugDrag:
    """A launch lug's pressure drag (Niskanen 2013, sec. 3.4.4; module docstring).

    Parameters
    ----------
    length, outer_radius, inner_radius : float [m]
    name : str
    """

    length: float
    outer_radius: float
    inner_radius: float
    name: str = "launch lug"

    def __post_init__(self):
        v.set_fields(self, length=v.positive(self.length, "length"),
                     outer_radius=v.positive(self.outer_radius, "outer_radius"),
                     inner_radius=v.nonnegative(self.inner_radius, "inner_radius"))

    def drag_area(self) -> float:
        """CD_stag-multiplied area [m^2]: max(1.3 - 0.3 l/d, 1) (pi r_o^2 - pi r_i^2 max(1 - l/d, 0))."""
        ld = self.length / (2.0 * self.outer_radius)
        area = math.pi * (self.outer_radius ** 2 - self.inner_radius ** 2 * max(1.0 - ld, 0.0))
        return max(1.3 - 0.3 * ld, 1.0) * area

    def CA(self, mach, reynolds_per_m, reference_area: float):
        """CA [-] on ``reference_area`` [m^2] (no Reynolds dependence); symbolic-safe."""
        return 0.85 * stagnation_ratio(mach) * (self.drag_area() / reference_area) + 0.0 * reynolds_per_m


def reference_ca(mach: float, reynolds_per_m: float, guides, reference_area: float) -> float:
    """Sum of the guides' CA [-] at one flight condition (numeric; for reports)."""
    return float(np.sum([float(g.CA(mach, reynolds_per_m, reference_area)) for g in guides]))
