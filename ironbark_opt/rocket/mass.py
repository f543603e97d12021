"""Mass properties: the value object, combination and wet/dry conversion.

Convention (docs/ARCHITECTURE.md): body axes with x along the rocket axis,
x [m] aft from the nose tip; every item's inertia is about its own CG.  All
items here lie on the rocket axis (axisymmetric build-up), so moving an
inertia from a CG at ``x1`` to ``x2`` adds ``m (x2 - x1)^2`` to the two
transverse moments only (parallel-axis / Huygens-Steiner theorem, e.g.
Meriam & Kraige, *Engineering Mechanics: Dynamics*, eq. B/3 in App. B).

``combine``, ``total_mass_properties`` and ``dry_from_wet`` on 4-tuples
``(mass, cg_x, I_transverse, I_axial)`` are plain arithmetic and therefore
symbolic-safe (floats, NumPy arrays, CasADi SX/MX).
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import Iterable, Sequence

import numpy as np

from ironbark_opt import _math
from ironbark_opt.errors import InputError


@dataclass(frozen=True, eq=False)
class MassProperties:
    """Mass, axial CG and inertia tensor of a rigid item (numeric-only).

    Parameters
    ----------
    mass : float [kg]
    cg_x : float [m] aft of the nose tip
    inertia : array_like (3, 3) [kg m^2]
        About the CG, body axes, x along the rocket axis (so ``inertia[0, 0]``
        is the axial moment).  A pair ``(I_transverse, I_axial)`` is also
        accepted and expanded to ``diag(I_axial, I_transverse, I_transverse)``.
    """

    mass: float
    cg_x: float
    inertia: np.ndarray

    def __post_init__(self):
        try:
            mass = float(self.mass)
            cg_x = float(self.cg_x)
            inertia = np.asarray(self.inertia, dtype=float)
        except (TypeError, ValueError) as exc:
            raise InputError(f"mass properties must be numbers: {exc}", field="mass_properties")
        if inertia.shape == (2,):
            inertia = np.diag([inertia[1], inertia[0], inertia[0]])
        if inertia.shape != (3, 3):
            raise InputError(f"inertia must be a 3x3 tensor or (I_transverse, I_axial), "
                             f"got shape {inertia.shape}", field="inertia")
        if not (np.isfinite(mass) and mass >= 0.0):
            raise InputError(f"mass must be >= 0 kg, got {mass}", field="mass")
        if not np.isfinite(cg_x):
            raise InputError(f"cg_x must be finite, got {cg_x}", field="cg_x")
        if not np.allclose(inertia, inertia.T, rtol=1e-9, atol=1e-12):
            raise InputError("inertia tensor must be symmetric", field="inertia")
        if np.any(np.diag(inertia) < -1e-12):
            raise InputError(f"principal moments must be >= 0, got diagonal {np.diag(inertia)}",
                             field="inertia")
        inertia = inertia.copy()
        inertia.setflags(write=False)
        object.__setattr__(self, "mass", mass)
        object.__setattr__(self, "cg_x", cg_x)
        object.__setattr__(self, "inertia", inertia)

    def __eq__(self, other) -> bool:
        if not isinstance(other, MassProperties):
            return NotImplemented
        return (self.mass == other.mass and self.cg_x == other.cg_x
                and bool(np.array_equal(self.inertia, other.inertia)))

    __hash__ = None

    @classmethod
    def axisymmetric(cls, mass, cg_x, I_transverse, I_axial) -> "MassProperties":
        """Build from ``mass`` [kg], ``cg_x`` [m], ``I_transverse`` and ``I_axial`` [kg m^2]."""
        return cls(mass, cg_x, np.diag([I_axial, I_transverse, I_transverse]))

    @property
    def I_axial(self) -> float:
        """Moment about the rocket axis [kg m^2]."""
        return float(self.inertia[0, 0])

    @property
    def I_transverse(self) -> float:
        """Mean of the two transverse moments about the CG [kg m^2]."""
        return float(0.5 * (self.inertia[1, 1] + self.inertia[2, 2]))

    def as_tuple(self) -> tuple[float, float, float, float]:
        """``(mass [kg], cg_x [m], I_transverse [kg m^2], I_axial [kg m^2])``."""
        return (self.mass, self.cg_x, self.I_transverse, self.I_axial)

    def scaled_to(self, mass: float) -> "MassProperties":
        """Same CG and mass distribution, total ``mass`` [kg] (a component mass override)."""
        k = 0.0 if self.mass == 0.0 else mass / self.mass
        if self.mass == 0.0 and mass > 0.0:
            return MassProperties(mass, self.cg_x, np.zeros((3, 3)))
        return MassProperties(mass, self.cg_x, self.inertia * k)

    def __add__(self, other: "MassProperties") -> "MassProperties":
        return combine_properties([self, other])


ZERO = MassProperties(0.0, 0.0, np.zeros((3, 3)))


def _as_tuple(item):
    if isinstance(item, MassProperties):
        return item.as_tuple()
    try:
        m, x, it, ia = item
    except (TypeError, ValueError):
        raise InputError("a mass item must be MassProperties or (mass, cg_x, I_transverse, I_axial)",
                         field="mass_item")
    return m, x, it, ia


def combine(items: Iterable[Sequence]):
    """Combine on-axis items into one (symbolic-safe).

    Parameters
    ----------
    items : iterable of (mass [kg], cg_x [m], I_transverse [kg m^2], I_axial [kg m^2])
        Inertias about each item's own CG; any entry may be a CasADi SX/MX.

    Returns
    -------
    (mass [kg], cg_x [m], I_transverse [kg m^2] about the combined CG, I_axial [kg m^2])
    """
    items = [_as_tuple(it) for it in items]
    if not items:
        raise InputError("combine() needs at least one item", field="items")
    mass = sum(m for m, _, _, _ in items)
    moment = sum(m * x for m, x, _, _ in items)
    if not _math.is_symbolic(mass) and np.all(np.asarray(mass) == 0):
        raise InputError("total mass is zero: the CG is undefined", field="mass")
    cg = moment / mass
    # parallel-axis theorem about the combined CG (see module docstring)
    it = sum(i_t + m * (x - cg) ** 2 for m, x, i_t, _ in items)
    ia = sum(i_a for _, _, _, i_a in items)
    return mass, cg, it, ia


def combine_properties(items: Iterable[MassProperties]) -> MassProperties:
    """Combine numeric items keeping full 3x3 tensors (numeric-only).

    Products of inertia carry over unchanged because all CGs lie on the x axis.
    """
    items = [it for it in items if it.mass > 0.0]
    if not items:
        return ZERO
    mass = sum(it.mass for it in items)
    cg = sum(it.mass * it.cg_x for it in items) / mass
    inertia = np.zeros((3, 3))
    for it in items:
        d2 = (it.cg_x - cg) ** 2
        inertia = inertia + it.inertia + it.mass * d2 * np.diag([0.0, 1.0, 1.0])
    return MassProperties(mass, cg, inertia)


def total_mass_properties(dry, ballast_mass, ballast_x, motor_mass, motor_cg_x,
                          motor_I_transverse, motor_I_axial):
    """Rocket + ballast + motor at one instant (symbolic-safe).

    Parameters
    ----------
    dry : MassProperties or (mass [kg], cg_x [m], I_transverse [kg m^2], I_axial [kg m^2])
        The rocket without motor and without ballast.
    ballast_mass : float or SX [kg]
        Point mass (no own inertia).
    ballast_x : float or SX [m] aft of the nose tip
    motor_mass : float or SX [kg]
        The motor's current mass ``motor.mass(t)``.
    motor_cg_x : float or SX [m] aft of the nose tip
        ``nozzle_x - motor.cg(t)`` (motor CGs are given forward of the nozzle exit).
    motor_I_transverse, motor_I_axial : float or SX [kg m^2]
        About the motor's current CG.

    Returns
    -------
    (mass [kg], cg_x [m], I_transverse [kg m^2], I_axial [kg m^2]) about the total CG.
    """
    return combine([_as_tuple(dry), (ballast_mass, ballast_x, 0.0, 0.0),
                    (motor_mass, motor_cg_x, motor_I_transverse, motor_I_axial)])


def dry_from_wet(wet, motor_mass, motor_cg_x, motor_I_transverse, motor_I_axial):
    """Rocket without motor from the rocket with its loaded motor (symbolic-safe on tuples).

    Inverts :func:`combine` for two items: with the wet CG ``c_w`` and the dry
    CG ``c_d = (m_w c_w - m_m x_m) / (m_w - m_m)``, the parallel-axis theorem
    gives ``I_t,d = I_t,w - I_t,m - m_m (x_m - c_w)^2 - m_d (c_d - c_w)^2``.

    Parameters
    ----------
    wet : MassProperties or (mass [kg], cg_x [m], I_transverse [kg m^2], I_axial [kg m^2])
        Measured (or CAD) properties with the loaded motor installed.
    motor_mass : float [kg]
        Loaded motor mass (``motor.mass(0)``).
    motor_cg_x : float [m] aft of the nose tip
    motor_I_transverse, motor_I_axial : float [kg m^2] about the motor CG

    Returns
    -------
    Same kind as ``wet``: MassProperties (full tensor kept, motor moments
    subtracted from the diagonal) or a 4-tuple.
    """
    m_w, c_w, it_w, ia_w = _as_tuple(wet)
    m_d = m_w - motor_mass
    symbolic = _math.is_symbolic(m_w, c_w, it_w, ia_w, motor_mass, motor_cg_x,
                                 motor_I_transverse, motor_I_axial)
    if not symbolic and np.any(np.asarray(m_d) <= 0):
        raise InputError(f"wet mass {m_w} kg is not larger than the motor mass {motor_mass} kg",
                         field="mass")
    c_d = (m_w * c_w - motor_mass * motor_cg_x) / m_d
    d_it = motor_I_transverse + motor_mass * (motor_cg_x - c_w) ** 2 + m_d * (c_d - c_w) ** 2
    it_d = it_w - d_it
    ia_d = ia_w - motor_I_axial
    if not symbolic and (np.any(np.asarray(it_d) < 0) or np.any(np.asarray(ia_d) < 0)):
        raise InputError("the motor's inertia exceeds the wet rocket's: check the wet "
                         "inertia and the motor position", field="inertia")
    if isinstance(wet, MassProperties):
        inertia = np.array(wet.inertia, dtype=float)
        inertia[0, 0] -= motor_I_axial
        inertia[1, 1] -= d_it
        inertia[2, 2] -= d_it
        return MassProperties(float(m_d), float(c_d), inertia)
    return m_d, c_d, it_d, ia_d
