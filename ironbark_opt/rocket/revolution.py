"""Bodies of revolution: the base of nose cones, tubes and transitions.

A component of this kind has a front position ``x`` [m], a ``length`` [m]
and an outer profile r(x).  Geometry (volume, wetted and side areas) comes
from the profile sampled at cosine-clustered stations and summed as
frustums, which converges even where r'(x) is infinite (Haack, elliptical
and power-series tips).  Mass comes from thin-disc slicing of the solid
between the outer profile and an inner one offset by the wall thickness
normal to the surface (or the whole solid when ``filled``):

    m   = rho pi  Int (ro^2 - ri^2) dx
    I_a = rho pi/2 Int (ro^4 - ri^4) dx
    I_t = rho pi  Int [(ro^4 - ri^4)/4 + (x - x_cg)^2 (ro^2 - ri^2)] dx

(the thin-disc moments of an annulus: I_axial = m (ro^2 + ri^2)/2,
I_diametral = m (ro^2 + ri^2)/4; Meriam & Kraige, *Dynamics*, App. B table
B/4).  The integrals use 3-point Gauss-Legendre on each frustum, exact for
the piecewise-linear profile.
"""
from __future__ import annotations

import abc

from dataclasses import dataclass

import numpy as np

from ironbark_opt.errors import InputError
from ironbark_opt import validate as v
from ironbark_opt.rocket.mass import MassProperties

#: stations used for geometry and mass integrals of one component
N_STATIONS = 2001

_GL_T, _GL_W = np.polynomial.legendre.leggauss(3)


@dataclass(frozen=True, kw_only=True)
class BodyOfRevolution(abc.ABC):
    """Common storage of axisymmetric body components (methods numeric-only).

    Parameters
    ----------
    length : float [m]
    x : float [m]
        Front end, aft of the nose tip.
    thickness : float [m] or None
        Wall thickness (normal to the surface) of a shell.
    filled : bool
        Solid component (e.g. a solid nose cone); ignores ``thickness``.
    density : float [kg/m^3] or None
        Bulk density of the material; None = massless in the build-up.
    mass : float [kg] or None
        Mass override: scales the built-up distribution to this mass.
    name : str
    surface_roughness : float [m] or None
        Equivalent sand-grain roughness of this component's surface (an .ork
        component's finish); None: the rocket's ``[aero] surface_roughness``.
    """

    length: float
    x: float = 0.0
    thickness: float | None = None
    filled: bool = False
    density: float | None = None
    mass: float | None = None
    name: str = ""
    surface_roughness: float | None = None

    def _check_common(self) -> None:
        v.set_fields(self, length=v.positive(self.length, "length"),
                     x=v.nonnegative(self.x, "x"),
                     thickness=v.optional(v.positive, self.thickness, "thickness"),
                     density=v.optional(v.positive, self.density, "density", "kg/m^3"),
                     mass=v.optional(v.nonnegative, self.mass, "mass", "kg"),
                     filled=bool(self.filled))
        if self.mass is not None and self.density is None:
            raise InputError("a mass override scales the built-up distribution and needs a "
                             "material or density (or use a point mass)", field="mass")
        if self.density is not None and not self.filled and self.thickness is None:
            raise InputError("a component with a density needs a wall thickness [m] "
                             "or filled = true", field="thickness")

    # -- profile ----------------------------------------------------------------
    def radius_at(self, x):
        """Outer radius [m] at absolute ``x`` [m] (0 outside the component); numeric-only."""
        x = np.asarray(x, dtype=float)
        local = x - self.x
        tol = 1e-9                       # [m]: x - self.x rounds off at the ends (x_end = x + length)
        inside = (local >= -tol) & (local <= self.length + tol)
        return np.where(inside, self._local_radius(np.clip(local, 0.0, self.length)), 0.0)

    @abc.abstractmethod
    def _local_radius(self, local):
        """Implemented by each subclass."""

    @property
    def x_end(self) -> float:
        """Aft end [m] aft of the nose tip."""
        return self.x + self.length

    @property
    def fore_radius(self) -> float:
        """Radius at the front end [m]."""
        return float(self._local_radius(np.array(0.0)))

    @property
    def aft_radius(self) -> float:
        """Radius at the aft end [m]."""
        return float(self._local_radius(np.array(self.length)))

    def profile(self, n: int = N_STATIONS, spacing: str = "cosine"):
        """Stations ``(x [m], r [m])`` along the component (numeric-only).

        Parameters
        ----------
        n : int
            Number of stations (>= 2).
        spacing : "cosine" (clustered at both ends) or "uniform"
        """
        if n < 2:
            raise InputError(f"need at least 2 stations, got {n}", field="n")
        s = np.linspace(0.0, 1.0, int(n))
        if spacing == "cosine":
            s = 0.5 * (1.0 - np.cos(np.pi * s))
        local = s * self.length
        return self.x + local, np.asarray(self._local_radius(local), dtype=float)

    def max_radius(self) -> float:
        """Largest outer radius [m]."""
        return float(np.max(self.profile()[1]))

    # -- geometry -------------------------------------------------------------------
    def volume(self) -> float:
        """Volume enclosed by the outer surface [m^3] (frustum sum; numeric-only)."""
        x, r = self.profile()
        dx = np.diff(x)
        return float(np.sum(np.pi * dx / 3.0 * (r[:-1] ** 2 + r[:-1] * r[1:] + r[1:] ** 2)))

    def wetted_area(self) -> float:
        """Lateral (outer) surface area [m^2], without end faces (numeric-only)."""
        x, r = self.profile()
        return float(np.sum(np.pi * (r[:-1] + r[1:]) * np.hypot(np.diff(x), np.diff(r))))

    def planform_area(self) -> float:
        """Side-projected area Int 2 r dx [m^2] (body-lift term; numeric-only)."""
        x, r = self.profile()
        return float(np.sum(np.diff(x) * (r[:-1] + r[1:])))

    def fineness(self) -> float:
        """Length over base diameter [-]."""
        return self.length / (2.0 * self.max_radius())

    # -- mass ----------------------------------------------------------------------------
    def inner_radius_profile(self):
        """Stations ``(x, r_inner)`` [m] of the inner surface (0 where solid)."""
        x, r = self.profile()
        if self.filled or self.thickness is None:
            return x, np.zeros_like(r)
        slope = np.gradient(r, x)
        return x, np.maximum(r - self.thickness * np.sqrt(1.0 + slope * slope), 0.0)

    def material_volume(self) -> float:
        """Volume of material [m^3] (shell or solid)."""
        return self._slices(1.0)[0]

    def _slices(self, density):
        x, ro = self.profile()
        _, ri = self.inner_radius_profile()
        x0, x1 = x[:-1], x[1:]
        h = x1 - x0
        m = x1c = i0 = ia = 0.0
        for t, w in zip(_GL_T, _GL_W):
            f = 0.5 * (1.0 + t)
            xs = x0 + f * h
            ros = ro[:-1] + f * (ro[1:] - ro[:-1])
            ris = ri[:-1] + f * (ri[1:] - ri[:-1])
            wh = 0.5 * w * h
            a2 = ros ** 2 - ris ** 2
            a4 = ros ** 4 - ris ** 4
            m += np.sum(wh * a2)
            x1c += np.sum(wh * a2 * xs)
            i0 += np.sum(wh * (a4 / 4.0 + xs ** 2 * a2))
            ia += np.sum(wh * a4 / 2.0)
        k = density * np.pi
        return k * m, k * x1c, k * i0, k * ia

    def mass_properties(self) -> MassProperties:
        """Mass build-up of this component (numeric-only).

        Returns a zero MassProperties when no density is given and no mass
        override, so a purely geometric component contributes nothing.
        """
        if self.density is None:
            return MassProperties(0.0, self.x + 0.5 * self.length, np.zeros((3, 3)))
        m, mx, i0, ia = self._slices(self.density)
        cg = mx / m
        it = i0 - m * cg * cg
        mp = MassProperties.axisymmetric(m, cg, it, ia)
        return mp if self.mass is None else mp.scaled_to(self.mass)
