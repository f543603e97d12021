"""Rail buttons, launch lugs, tube fins, point masses and inner tubes (value objects; numeric-only).

These items are treated as lying on the rocket axis for the mass build-up:
the radial offset of a few grams of rail hardware at the body radius adds
of order 1e-5 kg m^2 and a sub-millimetre lateral CG shift, both neglected.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ironbark_opt.errors import InputError
from ironbark_opt import validate as v
from ironbark_opt.rocket.mass import MassProperties, combine_properties


def _check_tube(tube, **extra) -> None:
    """Validate and normalise the fields every tube-like item has."""
    ro = v.positive(tube.outer_radius, "outer_radius")
    ri = v.nonnegative(tube.inner_radius, "inner_radius")
    if not ri < ro:
        raise InputError(f"inner_radius ({ri} m) must be smaller than outer_radius "
                         f"({ro} m)", field="inner_radius")
    v.set_fields(tube, x=v.nonnegative(tube.x, "x"), length=v.positive(tube.length, "length"),
                 outer_radius=ro, inner_radius=ri,
                 density=v.optional(v.positive, tube.density, "density", "kg/m^3"), **extra)


@dataclass(frozen=True, kw_only=True)
class PointMass:
    """A concentrated mass (avionics, recovery gear, bulkheads, ...).

    Parameters
    ----------
    mass : float [kg]
    x : float [m]
        Its CG, aft of the nose tip.
    I_transverse, I_axial : float [kg m^2]
        Own moments about its CG (default 0).
    name : str
    """

    mass: float = 0.0
    x: float = 0.0
    I_transverse: float = 0.0
    I_axial: float = 0.0
    name: str = "point mass"

    def __post_init__(self):
        v.set_fields(self, mass=v.nonnegative(self.mass, "mass", "kg"),
                     x=v.number(self.x, "x"),
                     I_transverse=v.nonnegative(self.I_transverse, "I_transverse", "kg m^2"),
                     I_axial=v.nonnegative(self.I_axial, "I_axial", "kg m^2"))

    def mass_properties(self) -> MassProperties:
        """The point mass as MassProperties (numeric-only)."""
        return MassProperties.axisymmetric(self.mass, self.x, self.I_transverse, self.I_axial)


#: OpenRocket's default rail button (``RailButton()``, OpenRocket 23.09) [m]: the size the
#: drag model assumes when a file gives none (said in a warning when flown)
DEFAULT_BUTTON = {"outer_diameter": 0.0097, "inner_diameter": 0.008, "height": 0.0097,
                  "base_height": 0.002, "flange_height": 0.002}


@dataclass(frozen=True, kw_only=True)
class RailButtons:
    """A pair of rail buttons (the rocket leaves the rail when the aft one does).

    Parameters
    ----------
    x_fore, x_aft : float [m]
        Button positions aft of the nose tip, ``x_fore < x_aft``.
    height : float [m]
        Standoff of the button from the body surface to the top of its flange
        (drag and mass); 0 = not given.
    mass_each : float [kg]
        Per button (all of them, ``x_other`` too).
    name : str
    angle : float [rad] or None
        Angular position of the buttons around the body, from its +y axis toward
        +z (the fin sets' ``roll`` convention; OpenRocket's angle offset).  None:
        point masses on the axis.
    outer_diameter : float [m] or None
        Button diameter (drag, :mod:`ironbark_opt.aero.protuberance`).  None: the
        size is not given and the drag model assumes OpenRocket's default button
        (:data:`DEFAULT_BUTTON`; the flight warns that it did).
    inner_diameter : float [m] or None
        Diameter of the notch the rail's lips ride in; None: ``outer_diameter``
        (a plain cylinder).  Only with ``outer_diameter``.
    base_height, flange_height : float [m]
        Heights of the full-diameter standoff at the foot and flange at the top
        (the notch is between them); default 0.  Only with ``outer_diameter``.
    x_other : tuple of float [m]
        Stations of further buttons of the same size (drag and mass only; the rail
        exit is set by ``x_fore`` and ``x_aft``).
    """

    x_fore: float = 0.0
    x_aft: float = 0.0
    height: float = 0.0
    mass_each: float = 0.0
    name: str = "rail buttons"
    angle: float | None = None
    outer_diameter: float | None = None
    inner_diameter: float | None = None
    base_height: float = 0.0
    flange_height: float = 0.0
    x_other: tuple = ()

    def __post_init__(self):
        x1 = v.nonnegative(self.x_fore, "x_fore")
        x2 = v.nonnegative(self.x_aft, "x_aft")
        if not x2 > x1:
            raise InputError(f"x_aft ({x2} m) must lie aft of x_fore ({x1} m)", field="x_aft")
        if isinstance(self.x_other, (str, bytes)) or not hasattr(self.x_other, "__iter__"):
            raise InputError(f"expected a list of stations [m], got {self.x_other!r}", field="x_other")
        h = v.nonnegative(self.height, "height")
        od = v.optional(v.positive, self.outer_diameter, "outer_diameter")
        idia = v.optional(v.nonnegative, self.inner_diameter, "inner_diameter")
        base = v.nonnegative(self.base_height, "base_height")
        flange = v.nonnegative(self.flange_height, "flange_height")
        if od is None:
            for key, val in (("inner_diameter", idia), ("base_height", base or None),
                             ("flange_height", flange or None)):
                if val is not None:
                    raise InputError(f"{key} needs the button's outer_diameter", field="outer_diameter")
        else:
            if not h > 0:
                raise InputError("a button with an outer_diameter needs its height > 0 m", field="height")
            if idia is not None and idia > od:
                raise InputError(f"inner_diameter ({idia} m) exceeds outer_diameter ({od} m)",
                                 field="inner_diameter")
            if base + flange > h:
                raise InputError(f"base_height + flange_height ({base + flange} m) exceed the height "
                                 f"({h} m)", field="flange_height")
        v.set_fields(self, x_fore=x1, x_aft=x2, height=h,
                     mass_each=v.nonnegative(self.mass_each, "mass_each", "kg"),
                     outer_diameter=od, inner_diameter=idia, base_height=base, flange_height=flange,
                     x_other=tuple(v.nonnegative(x, "x_other") for x in self.x_other))

    def stations(self) -> tuple[float, ...]:
        """Every button's station [m]: ``x_fore``, ``x_aft``, then ``x_other``."""
        return (self.x_fore, self.x_aft) + self.x_other

    def button_size(self) -> tuple[dict, tuple[str, ...]]:
        """(``{outer_diameter, inner_diameter, height, base_height, flange_height}`` [m],
        the names taken from :data:`DEFAULT_BUTTON` because the file did not give them).

        Without ``outer_diameter`` the button is OpenRocket's default one, its height
        kept when given (> 0); with it, a missing ``inner_diameter`` is the outer one."""
        if self.outer_diameter is None:
            size = dict(DEFAULT_BUTTON)
            if self.height > 0:
                size["height"] = self.height
            return size, tuple(k for k in DEFAULT_BUTTON if k != "height" or not self.height > 0)
        return {"outer_diameter": self.outer_diameter,
                "inner_diameter": self.outer_diameter if self.inner_diameter is None else self.inner_diameter,
                "height": self.height, "base_height": self.base_height,
                "flange_height": self.flange_height}, ()

    @property
    def rail_guides(self) -> tuple[float, float]:
        """``(x_fore, x_aft)`` [m] of the points that ride the rail."""
        return self.x_fore, self.x_aft

    def mass_properties(self, radius_at=None) -> MassProperties:
        """Point masses at :meth:`stations` (numeric-only): on the axis, or with ``angle`` (and the
        body's ``radius_at(x)`` [m]) at radius r = body radius + height/2 in the
        direction (y, z) = r (cos angle, sin angle).  The inertia is taken about the
        axis point at the buttons' mean x (their small lateral CG offset is
        neglected, as for every component): I = sum m (|d|^2 1 - d d^T),
        d = (x_i - x_mean, y, z), so the roll inertia gains 2 m r^2 and the product
        I_yz = -2 m y z appears (a button off the pitch or yaw plane)."""
        xs = self.stations()
        m = len(xs) * self.mass_each
        if self.x_other:
            cg = sum(xs) / len(xs)
            i_t = self.mass_each * sum((x - cg) ** 2 for x in xs)
        else:
            cg = 0.5 * (self.x_fore + self.x_aft)
            i_t = self.mass_each * 2 * (0.5 * (self.x_aft - self.x_fore)) ** 2
        if self.angle is None or radius_at is None:
            return MassProperties.axisymmetric(m, cg, i_t, 0.0)
        inertia = np.zeros((3, 3))
        for x in xs:
            r = float(radius_at(x)) + 0.5 * self.height
            d = np.array([x - cg, r * np.cos(self.angle), r * np.sin(self.angle)])
            inertia += self.mass_each * (d @ d * np.eye(3) - np.outer(d, d))
        return MassProperties(m, cg, inertia)


@dataclass(frozen=True, kw_only=True)
class LaunchLug:
    """A launch lug: a tube of ``length`` [m] from ``x`` [m], radii in [m]; ``count``
    identical lugs in a row (OpenRocket's ``instancecount``), fronts ``separation`` [m]
    apart.

    Parameters
    ----------
    x : float [m]
        Front end of the first lug, aft of the nose tip.
    length : float [m]
    outer_radius, inner_radius : float [m]
        ``inner_radius < outer_radius``.
    density : float [kg/m^3] or None
    name : str
    count : int [-]
        Number of lugs (default 1); each has its own drag.
    separation : float [m]
        Front-to-front distance of consecutive lugs (>= length when ``count`` > 1).
    """

    x: float = 0.0
    length: float = 0.0
    outer_radius: float = 0.0
    inner_radius: float = 0.0
    density: float | None = None
    name: str = "launch lug"
    count: int = 1
    separation: float = 0.0

    def __post_init__(self):
        if isinstance(self.count, bool) or not isinstance(self.count, (int, np.integer)) or self.count < 1:
            raise InputError(f"count must be a whole number >= 1, got {self.count!r}", field="count")
        _check_tube(self, count=int(self.count), separation=v.nonnegative(self.separation, "separation"))
        if self.count > 1 and self.separation < self.length:
            raise InputError(f"separation {self.separation} m of {self.count} lugs is shorter than "
                             f"their length {self.length} m", field="separation")

    @property
    def fronts(self) -> tuple[float, ...]:
        """Front end of each lug [m], aft of the nose tip."""
        return tuple(self.x + i * self.separation for i in range(self.count))

    @property
    def x_end(self) -> float:
        """Aft end of the last lug [m]."""
        return self.fronts[-1] + self.length

    @property
    def rail_guides(self) -> tuple[float, float]:
        """``(x_fore, x_aft)`` [m]: the first lug's front and the last one's aft end ride the rod."""
        return self.x, self.x_end

    def wetted_area(self) -> float:
        """Outer lateral surface of all the lugs [m^2]."""
        return 2.0 * np.pi * self.outer_radius * self.length * self.count

    def mass_properties(self) -> MassProperties:
        """Thick-walled tubes treated as on-axis: m L^2/12 transverse each (numeric-only)."""
        if self.density is None:
            return MassProperties(0.0, self.x, np.zeros((3, 3)))
        ro, ri, L = self.outer_radius, self.inner_radius, self.length
        m = self.density * np.pi * (ro * ro - ri * ri) * L
        return combine_properties([MassProperties.axisymmetric(m, x + 0.5 * L, m * L * L / 12.0, 0.0)
                                   for x in self.fronts])


@dataclass(frozen=True, kw_only=True)
class TubeFins:
    """A tube fin set (OpenRocket ``TubeFinSet``): ``count`` open tubes of ``length`` [m]
    lying along the body, each touching the body surface (their axes at
    ``body_radius + outer_radius`` from the rocket's).

    Lift: each tube a ring wing (Ribner, :func:`~ironbark_opt.aero.barrowman.tube_fins`);
    drag: open tubes (:class:`~ironbark_opt.aero.protuberance.LaunchLugDrag`, ``count``).
    The wetted and interstice areas are OpenRocket 23.09's ``TubeFinSetCalc`` geometry.

    Parameters
    ----------
    x : float [m]
        Front end, aft of the nose tip.
    length : float [m]
    outer_radius, inner_radius : float [m]
    count : int
    body_radius : float [m]
        Body radius under the tubes.
    density : float [kg/m^3] or None
    name : str
    """

    x: float = 0.0
    length: float = 0.0
    outer_radius: float = 0.0
    inner_radius: float = 0.0
    count: int = 6
    body_radius: float = 0.0
    density: float | None = None
    name: str = "tube fins"

    def __post_init__(self):
        _check_tube(self, count=int(v.positive(self.count, "count")),
                    body_radius=v.positive(self.body_radius, "body_radius"))

    def _angles(self) -> tuple[float, float]:
        """(theta1, theta2) [rad]: at a tube's tangent point from the body's axis, the
        angle between the tube's radius and the line of centres, and its complement."""
        t1 = float(np.arccos(self.outer_radius / (self.outer_radius + self.body_radius)))
        return t1, 0.5 * np.pi - t1

    def wetted_area_each(self) -> float:
        """Outer surface of one tube not masked by the body [m^2] (TubeFinSetCalc)."""
        t1, t2 = self._angles()
        outer = self.length * 2.0 * (np.pi - t1) * self.outer_radius
        return float(outer - self.length * 2.0 * t2 * self.body_radius)

    def interstice_area_each(self) -> float:
        """Frontal area between one tube and the body, both sides [m^2] (TubeFinSetCalc:
        the kite of the two tangent triangles less the tube's and the body's sectors)."""
        ro, rb = self.outer_radius, self.body_radius
        t1, t2 = self._angles()
        d = np.sqrt((rb + ro) ** 2 - ro ** 2)
        return float(max(d * ro - ro * ro * t1 - rb * rb * t2, 0.0))

    def mass_properties(self) -> MassProperties:
        """The tubes as thick-walled tubes at their radial offset (numeric-only)."""
        if self.density is None:
            return MassProperties(0.0, self.x, np.zeros((3, 3)))
        ro, ri, L, n = self.outer_radius, self.inner_radius, self.length, self.count
        m_each = self.density * np.pi * (ro * ro - ri * ri) * L
        r_axis = self.body_radius + ro
        i_axial = n * m_each * (0.5 * (ro * ro + ri * ri) + r_axis ** 2)
        # transverse: own moment plus the offsets, n >= 3 evenly spaced: sum sin^2 = n/2
        i_t = n * m_each * (0.25 * (ro * ro + ri * ri) + L * L / 12.0) \
            + m_each * r_axis ** 2 * (0.5 * n if n >= 3 else 1.0)
        return MassProperties.axisymmetric(n * m_each, self.x + 0.5 * L, i_t, i_axial)


@dataclass(frozen=True, kw_only=True)
class InnerTube:
    """An internal, on-axis tube or disc: coupler, motor mount, shoulder,
    centering ring, bulkhead (``inner_radius = 0``), engine block.

    Internal components carry mass only (no wetted area, not in the body
    profile).  Moments of a thick-walled tube about its CG: I_axial =
    m (ro^2 + ri^2)/2, I_transverse = m ((ro^2 + ri^2)/4 + L^2/12)
    (Meriam & Kraige, *Dynamics*, App. B table B/4).

    Parameters
    ----------
    x : float [m]
        Front end, aft of the nose tip.
    length : float [m]
    outer_radius, inner_radius : float [m]
        ``0 <= inner_radius < outer_radius``.
    density : float [kg/m^3] or None
    mass : float [kg] or None
        Mass override (keeps the tube's distribution).
    name : str
    """

    x: float = 0.0
    length: float = 0.0
    outer_radius: float = 0.0
    inner_radius: float = 0.0
    density: float | None = None
    mass: float | None = None
    name: str = "inner tube"

    def __post_init__(self):
        _check_tube(self, mass=v.optional(v.nonnegative, self.mass, "mass", "kg"))

    def mass_properties(self) -> MassProperties:
        """The tube's mass build-up (numeric-only).

        A mass override without a density keeps the tube's distribution.
        """
        if self.density is None and self.mass is None:
            return MassProperties(0.0, self.x, np.zeros((3, 3)))
        rho = 1.0 if self.density is None else self.density
        ro, ri, L = self.outer_radius, self.inner_radius, self.length
        m = rho * np.pi * (ro * ro - ri * ri) * L
        mp = MassProperties.axisymmetric(m, self.x + 0.5 * L,
                                         m * ((ro * ro + ri * ri) / 4.0 + L * L / 12.0),
                                         m * (ro * ro + ri * ri) / 2.0)
        return mp if self.mass is None else mp.scaled_to(self.mass)
