"""Propellant geometry and the mass-property models of burning propellant.

Two models of the propellant's own inertia, both burning "from the inside
out" (the bore grows, the outer radius and the length stay fixed), so the
squared bore radius is linear in the remaining mass:

    r^2(f) = R^2 - (R^2 - r0^2) * f,        f = m_p / m_p0 in [0, 1]

- :class:`Grains`: a stack of BATES grains (hollow cylinders) of one size,
  ``count`` grains ``height`` long, ``separation`` apart, centred on the
  grains' CG.
- :func:`hollow_cylinder_inertia`: the default when no grains are given, a
  single hollow cylinder filling the motor case.

The inertia functions are symbolic-safe (floats, NumPy arrays, CasADi SX/MX):
they use only arithmetic, so they are polynomial in the remaining mass.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

from ironbark_opt.errors import InputError

#: Default initial bore radius as a fraction of the outer radius when no
#: grain geometry is known (typical BATES port; the Calisto M1670 has 0.45).
DEFAULT_BORE_RATIO = 0.5


@dataclass(frozen=True)
class Grains:
    """A stack of identical BATES propellant grains.

    Parameters
    ----------
    count : int [-]
        Number of grains (>= 1).
    density : float [kg/m^3]
        Propellant density.
    outer_radius : float [m]
        Outer radius of a grain.
    inner_radius : float [m]
        Initial bore (core) radius, 0 <= inner_radius < outer_radius.
    height : float [m]
        Length of one grain (kept fixed while burning).
    separation : float [m]
        Axial gap between neighbouring grains (>= 0).
    """

    count: int
    density: float
    outer_radius: float
    inner_radius: float
    height: float
    separation: float = 0.0

    def __post_init__(self):
        count = self.count
        if isinstance(count, float) and count.is_integer():
            count = int(count)
        if isinstance(count, bool) or not isinstance(count, int) or count < 1:
            raise InputError(f"expected a whole number of grains >= 1, got {self.count!r}",
                             field="grains.count")
        object.__setattr__(self, "count", count)
        for name in ("density", "outer_radius", "inner_radius", "height", "separation"):
            value = getattr(self, name)
            try:
                value = float(value)
            except (TypeError, ValueError):
                raise InputError(f"expected a number, got {value!r}", field=f"grains.{name}") from None
            if not math.isfinite(value) or value < 0:
                raise InputError(f"expected a finite number >= 0, got {value!r}", field=f"grains.{name}")
            object.__setattr__(self, name, value)
        for name in ("density", "outer_radius", "height"):
            if getattr(self, name) <= 0:
                raise InputError(f"expected a positive number, got {getattr(self, name)!r}",
                                 field=f"grains.{name}")
        if self.inner_radius >= self.outer_radius:
            raise InputError(
                f"inner radius {self.inner_radius} m must be smaller than the outer radius "
                f"{self.outer_radius} m", field="grains.inner_radius")

    @property
    def mass(self) -> float:
        """Initial propellant mass of all grains [kg], numeric.

        m = count * density * pi * (R^2 - r0^2) * height (hollow cylinder).
        """
        return (self.count * self.density * math.pi
                * (self.outer_radius ** 2 - self.inner_radius ** 2) * self.height)

    @property
    def stack_length(self) -> float:
        """Length of the grain stack including the gaps [m], numeric."""
        return self.count * self.height + (self.count - 1) * self.separation

    def _offset_sum(self) -> float:
        """Sum over grains of the squared axial offset of each grain's centre
        from the stack's centre [m^2] (grains equally spaced by height + gap)."""
        pitch = self.height + self.separation
        mid = (self.count - 1) / 2.0
        return sum(((k - mid) * pitch) ** 2 for k in range(self.count))

    def inertia(self, propellant_mass, initial_mass: float | None = None):
        """Inertia of the burning grain stack about the stack's CG.

        Symbolic-safe.  Each grain is a hollow cylinder (outer radius R, bore
        r, height h, mass m_g = m_p / count); its inertia about its own centre
        is I_axial = m_g (R^2 + r^2) / 2, I_transverse = m_g (3 (R^2 + r^2) +
        h^2) / 12 (hollow circular cylinder; Hibbeler, Engineering Mechanics:
        Dynamics, table of mass moments of inertia), moved to the stack's CG
        by the parallel-axis theorem.  The bore follows from the remaining
        mass fraction as in the module docstring.

        Parameters
        ----------
        propellant_mass : float, array or CasADi SX/MX [kg]
            Remaining propellant mass.
        initial_mass : float [kg], optional
            Propellant mass at ignition (default: :attr:`mass`); the bore is
            r0 at ``initial_mass`` and R when empty.

        Returns
        -------
        (I_transverse, I_axial) : tuple [kg m^2]
        """
        m0 = self.mass if initial_mass is None else float(initial_mass)
        R2 = self.outer_radius ** 2
        r02 = self.inner_radius ** 2
        mp = propellant_mass
        r2 = R2 - (R2 - r02) * (mp / m0)
        i_axial = mp * (R2 + r2) / 2.0
        i_trans = (mp * (3.0 * (R2 + r2) + self.height ** 2) / 12.0
                   + (mp / self.count) * self._offset_sum())
        return i_trans, i_axial

    def to_dict(self) -> dict:
        """Plain dict with unit-named keys, for files and the CLI."""
        return {"count": self.count, "density_kg_m3": self.density,
                "outer_radius_m": self.outer_radius, "inner_radius_m": self.inner_radius,
                "height_m": self.height, "separation_m": self.separation}


def hollow_cylinder_inertia(propellant_mass, initial_mass: float, outer_radius: float,
                            length: float, bore_ratio: float = DEFAULT_BORE_RATIO):
    """Default propellant inertia: one hollow cylinder burning from the inside out.

    Symbolic-safe.  Used when no :class:`Grains` are given: the propellant
    fills the motor case (outer radius = case radius, length = motor length)
    with an initial bore of ``bore_ratio`` times the outer radius.  Hollow
    cylinder formulas as in :meth:`Grains.inertia` (Hibbeler, Engineering
    Mechanics: Dynamics, table of mass moments of inertia).

    Parameters
    ----------
    propellant_mass : float, array or CasADi SX/MX [kg]
        Remaining propellant mass.
    initial_mass : float [kg]
        Propellant mass at ignition (> 0).
    outer_radius : float [m]
        Outer radius of the propellant (the case radius).
    length : float [m]
        Length of the propellant column.
    bore_ratio : float [-]
        Initial bore radius / outer radius.

    Returns
    -------
    (I_transverse, I_axial) : tuple [kg m^2] about the propellant's CG
    """
    R2 = outer_radius ** 2
    r02 = (bore_ratio * outer_radius) ** 2
    mp = propellant_mass
    r2 = R2 - (R2 - r02) * (mp / initial_mass)
    i_axial = mp * (R2 + r2) / 2.0
    i_trans = mp * (3.0 * (R2 + r2) + length ** 2) / 12.0
    return i_trans, i_axial


def thin_tube_inertia(mass: float, radius: float, length: float) -> tuple[float, float]:
    """Default dry (case) inertia: a thin-walled tube of the dry mass.

    Numeric.  I_axial = m R^2, I_transverse = m (R^2 / 2 + L^2 / 12) about the
    tube's centre (thin-walled cylinder; Hibbeler, Engineering Mechanics:
    Dynamics, table of mass moments of inertia).

    Parameters
    ----------
    mass : float [kg]
    radius : float [m]
    length : float [m]

    Returns
    -------
    (I_transverse, I_axial) : tuple [kg m^2]
    """
    return mass * (radius ** 2 / 2.0 + length ** 2 / 12.0), mass * radius ** 2
