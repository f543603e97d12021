"""The Rocket: an ordered set of components plus an optional mass override."""
from __future__ import annotations

import warnings
from typing import Sequence

import numpy as np

from ironbark_opt.errors import InputError
from ironbark_opt.rocket.body import BodyTube
from ironbark_opt.rocket.fins import FinSet
from ironbark_opt.rocket.hardware import InnerTube, LaunchLug, PointMass, RailButtons, TubeFins
from ironbark_opt.rocket.mass import MassProperties, combine_properties
from ironbark_opt.rocket.revolution import BodyOfRevolution

#: gap or overlap [m] tolerated between consecutive body components
JOINT_TOLERANCE = 1e-6
#: reference_radius / the largest body radius refused outside this range [-] (a unit slip:
#: m for mm gives 1e-3, mm for m 1e3); above REFERENCE_WARN_RATIO it is warned about
REFERENCE_RATIO = (0.1, 10.0)
REFERENCE_WARN_RATIO = 1.5

_COMPONENT_TYPES = (BodyOfRevolution, FinSet, RailButtons, LaunchLug, PointMass, InnerTube, TubeFins)


def _share_a_fin_line(a: FinSet, b: FinSet) -> bool:
    """True when a fin of set ``a`` and one of set ``b`` stand at the same roll angle."""
    def angles(f):
        return f.roll_angle + 2 * np.pi * np.arange(f.count) / f.count
    gap = (angles(a)[:, None] - angles(b)[None, :] + np.pi) % (2 * np.pi) - np.pi
    return bool(np.any(np.abs(gap) < 1e-6))


class Rocket:
    """A rocket without motor and ballast (value object; all methods numeric-only).

    Parameters
    ----------
    name : str
    components : sequence
        Nose cone, body tubes, transitions (``BodyOfRevolution``, placed
        end to end from x = 0 without gaps), fin sets, rail buttons, launch
        lugs and point masses.
    mass_override : MassProperties or None
        Dry mass, CG and inertia of the rocket without motor (e.g. from CAD
        or a swing test); replaces the component build-up.
    reference_radius : float [m] or None
        Aerodynamic reference radius; default the largest body radius.
    """

    def __init__(self, name: str, components: Sequence, *,
                 mass_override: MassProperties | None = None,
                 reference_radius: float | None = None):
        self.name = str(name)
        self.components = tuple(components)
        for i, comp in enumerate(self.components):
            if not isinstance(comp, _COMPONENT_TYPES):
                raise InputError(f"component {i} is a {type(comp).__name__}, not a rocket "
                                 f"component", field=f"components[{i}]")
        if mass_override is not None and not isinstance(mass_override, MassProperties):
            raise InputError("mass_override must be MassProperties", field="mass_override")
        self.mass_override = mass_override
        body = sorted(self.body_components(), key=lambda c: c.x)
        if not body:
            raise InputError("a rocket needs at least one body component (nose cone, body "
                             "tube or transition)", field="components")
        if abs(body[0].x) > JOINT_TOLERANCE:
            raise InputError(f"the body must start at the nose tip x = 0, first component "
                             f"'{body[0].name}' starts at x = {body[0].x} m",
                             field=f"components[{self._index(body[0])}].x")
        for a, b in zip(body[:-1], body[1:]):
            if abs(b.x - a.x_end) > JOINT_TOLERANCE:
                kind = "gap" if b.x > a.x_end else "overlap"
                raise InputError(f"{kind} of {abs(b.x - a.x_end):.6g} m between '{a.name}' "
                                 f"(ends at x = {a.x_end:.6g} m) and '{b.name}' (starts at "
                                 f"x = {b.x:.6g} m)", field=f"components[{self._index(b)}].x")
        self._body = tuple(body)
        if reference_radius is not None:
            if isinstance(reference_radius, bool) or not float(reference_radius) > 0.0:
                raise InputError(f"reference_radius must be > 0 m, got {reference_radius!r}",
                                 field="reference_radius")
            reference_radius = float(reference_radius)
            ratio = reference_radius / max(c.max_radius() for c in body)
            if not REFERENCE_RATIO[0] <= ratio <= REFERENCE_RATIO[1]:
                raise InputError(f"reference_radius {reference_radius:g} m is {ratio:.3g} x the largest "
                                 f"body radius; expected about the body's radius (m, not mm)",
                                 field="reference_radius")
            if ratio > REFERENCE_WARN_RATIO:
                warnings.warn(f"reference_radius {reference_radius:g} m is {ratio:.3g} x the largest "
                              "body radius: a diameter given as the radius? (the coefficients of "
                              "drag curves and tables are on this area)", UserWarning, stacklevel=2)
        self._reference_radius = reference_radius
        fin_sets = self.fin_sets()
        for fins in fin_sets:
            if fins.x < 0.0 or fins.x > self.length():
                raise InputError(f"fin set '{fins.name}' root leading edge x = {fins.x} m is "
                                 f"off the body (0 to {self.length():.6g} m)",
                                 field=f"components[{self._index(fins)}].x")
        for fins in fin_sets:
            girth = 2 * np.pi * float(self.radius_at(fins.x))
            if fins.count * fins.thickness > girth:
                raise InputError(f"{fins.count} fins of {fins.thickness:.4g} m do not fit around the "
                                 f"body ({girth:.4g} m round at the root leading edge)",
                                 field=f"components[{self._index(fins)}].count")
            front = fins.x + float(np.min(fins.planform_points()[:, 0]))
            if front < -JOINT_TOLERANCE:
                raise InputError(f"fin set '{fins.name}' reaches {-front:.4g} m ahead of the nose tip "
                                 f"(a tip swept forward of x = 0)",
                                 field=f"components[{self._index(fins)}].x")
        for k, a in enumerate(fin_sets):
            for b in fin_sets[k + 1:]:
                if a.x < b.x_end and b.x < a.x_end and _share_a_fin_line(a, b):
                    raise InputError(f"fin sets '{a.name}' and '{b.name}' overlap along the axis with "
                                     f"fins at the same roll angle (one fin inside another: a "
                                     f"duplicated [[component]]?); turn one set with roll_deg",
                                     field=f"components[{self._index(b)}].x")
        for tube in (c for c in self.components if isinstance(c, InnerTube)):
            if tube.outer_radius > self.max_radius() + JOINT_TOLERANCE:
                raise InputError(f"inner tube '{tube.name}' (outer_radius {tube.outer_radius:.6g} m) "
                                 f"does not fit inside the body (largest radius "
                                 f"{self.max_radius():.6g} m)",
                                 field=f"components[{self._index(tube)}].outer_radius")
        for i, comp in enumerate(self.components):    # items that sit on or in the body
            if isinstance(comp, RailButtons):
                stations = (("x_fore", comp.x_fore), ("x_aft", comp.x_aft))
            elif isinstance(comp, LaunchLug):
                stations = (("x", comp.x), ("length", comp.x_end))
            elif isinstance(comp, PointMass):
                stations = (("x", comp.x),)
            else:
                continue
            for key, x in stations:
                if not -JOINT_TOLERANCE <= x <= self.length() + JOINT_TOLERANCE:
                    raise InputError(f"'{comp.name}' at x = {x:g} m is off the body (0 to "
                                     f"{self.length():.6g} m)", field=f"components[{i}].{key}")
        guides = [c for c in self.components if isinstance(c, (RailButtons, LaunchLug))]
        if len(guides) > 1:
            raise InputError("give one rail-button pair or one launch lug, not several",
                             field="components")

    def _index(self, comp) -> int:
        return next(i for i, c in enumerate(self.components) if c is comp)

    def __repr__(self) -> str:
        return (f"Rocket({self.name!r}, {len(self.components)} components, "
                f"length={self.length():.4g} m, mass_override={self.mass_override is not None})")

    # -- component access ---------------------------------------------------------------
    def body_components(self) -> list[BodyOfRevolution]:
        """Nose cone, tubes and transitions in the given order."""
        return [c for c in self.components if isinstance(c, BodyOfRevolution)]

    def front_component(self) -> BodyOfRevolution:
        """The body component at the front (smallest ``x``): the nose, or a booster's
        tube after a separation."""
        return min(self.body_components(), key=lambda c: c.x)

    def fin_sets(self) -> list[FinSet]:
        return [c for c in self.components if isinstance(c, FinSet)]

    def tube_fin_sets(self) -> list[TubeFins]:
        return [c for c in self.components if isinstance(c, TubeFins)]

    def point_masses(self) -> list[PointMass]:
        return [c for c in self.components if isinstance(c, PointMass)]

    def rail_guides(self) -> tuple[float, float] | None:
        """``(x_fore, x_aft)`` [m] of the rail buttons or lug ends, or None."""
        for c in self.components:
            if isinstance(c, (RailButtons, LaunchLug)):
                return c.rail_guides
        return None

    # -- geometry -----------------------------------------------------------------------
    def length(self) -> float:
        """Nose tip to the aft end of the body [m]."""
        return self._body[-1].x_end

    def radius_at(self, x):
        """Outer body radius [m] at ``x`` [m] (0 off the body); numeric-only.

        At a joint the aft component's radius is used.
        """
        x = np.asarray(x, dtype=float)
        r = np.zeros_like(x)
        for comp in self._body:
            inside = (x >= comp.x) & (x <= comp.x_end)
            r = np.where(inside, comp.radius_at(x), r)
        return r

    def body_profile(self, n: int = 400):
        """Stations ``(x [m], r [m])`` along the whole body, nose tip to tail.

        Each component gets stations in proportion to its length (at least
        two; nose cones and transitions at least 16, cosine-clustered);
        a radius step at a joint appears as two stations at the same x.
        Numeric-only.
        """
        xs, rs = [], []
        total = self.length()
        for comp in self._body:
            k = max(2, int(round(n * comp.length / total)))
            xc, rc = comp.profile(k, "uniform") if isinstance(comp, BodyTube) \
                else comp.profile(max(k, 16))
            if xs and abs(xc[0] - xs[-1][-1]) <= JOINT_TOLERANCE \
                    and abs(rc[0] - rs[-1][-1]) <= 1e-12:
                xc, rc = xc[1:], rc[1:]
            xs.append(xc)
            rs.append(rc)
        return np.concatenate(xs), np.concatenate(rs)

    def max_radius(self) -> float:
        """Largest body radius [m]."""
        return max(c.max_radius() for c in self._body)

    def reference_radius(self) -> float:
        """Aerodynamic reference radius [m] (given, or the largest body radius)."""
        return self._reference_radius if self._reference_radius is not None \
            else self.max_radius()

    def reference_area(self) -> float:
        """pi r_ref^2 [m^2]."""
        return float(np.pi * self.reference_radius() ** 2)

    def fineness(self) -> float:
        """Body length over maximum diameter [-]."""
        return self.length() / (2.0 * self.max_radius())

    def wetted_area(self) -> float:
        """Body lateral surface plus both faces of all fins [m^2]."""
        return float(sum(c.wetted_area() for c in self._body)
                     + sum(f.wetted_area() for f in self.fin_sets()))

    # -- mass -----------------------------------------------------------------------------
    def component_mass_properties(self) -> list[tuple[str, MassProperties]]:
        """``(name, MassProperties)`` of every component's build-up (numeric-only)."""
        out = []
        for c in self.components:
            mp = c.mass_properties(self.radius_at) if isinstance(c, (FinSet, RailButtons)) \
                else c.mass_properties()
            out.append((c.name, mp))
        return out

    def built_up_mass_properties(self) -> MassProperties:
        """Sum of the component build-up, ignoring any override (numeric-only)."""
        return combine_properties(mp for _, mp in self.component_mass_properties())

    def dry_mass_properties(self) -> MassProperties:
        """Rocket without motor and ballast: the override if given, else the build-up.

        Raises InputError when neither gives any mass.
        """
        if self.mass_override is not None:
            return self.mass_override
        mp = self.built_up_mass_properties()
        if mp.mass <= 0.0:
            raise InputError("the rocket has no mass: give component densities (material) "
                             "or a mass override", field="mass_override")
        return mp

    def with_mass_override(self, mass_override: MassProperties | None) -> "Rocket":
        """A copy with another mass override."""
        return Rocket(self.name, self.components, mass_override=mass_override,
                      reference_radius=self._reference_radius)
