"""The ``Motor`` interface: thrust, mass, CG and inertia versus time.

A motor is described by its *unscaled* histories (subclasses implement
``_thrust_unscaled``, ``_impulse_unscaled`` and ``_mass_properties_unscaled``
of the time since ignition).  The thrust-scale / burn-time-scale hook is
applied once, here, for every kind of motor:

    F(t) = k_F / s * F0(t / s),    I(t) = k_F * I0(t / s)

with ``thrust_scale`` = k_F and ``time_scale`` = s, so k_F scales the total
impulse and s stretches the burn at constant impulse.  Propellant is burned in
proportion to delivered impulse, so the propellant mass, CG and inertia
histories depend only on ``t / s`` (not on k_F: a hotter motor delivers more
impulse from the same propellant).

Conventions: times [s] since ignition; motor positions [m] measured forward
from the nozzle exit; inertia ``(I_transverse, I_axial)`` [kg m^2] about the
motor's *current* CG.  Hybrid and liquid motors implement the same three
abstract methods.
"""
from __future__ import annotations

import abc
import math
from typing import NamedTuple

import numpy as np


#: Standard gravity [m/s^2] (specific impulse in seconds).
G0 = 9.80665


class MotorState(NamedTuple):
    """All motor quantities at one time, sharing subexpressions.

    Fields: ``thrust`` [N], ``propellant_mass`` [kg], ``mass`` [kg],
    ``cg`` [m forward of the nozzle exit], ``inertia`` (I_transverse, I_axial)
    [kg m^2] about ``cg``.
    """

    thrust: object
    propellant_mass: object
    mass: object
    cg: object
    inertia: tuple


def impulse_class(total_impulse: float) -> str:
    """Impulse class letter of a total impulse [N s], numeric.

    Classes double from A = (1.25, 2.5] N s (NFPA 1125 / NAR motor
    classification table): B = (2.5, 5], ..., O = (20480, 40960]; below A
    the fractional classes 1/2A, 1/4A, 1/8A.
    """
    I = float(total_impulse)
    if I <= 0:
        return "-"
    if I <= 1.25:
        n = max(1, math.ceil(math.log2(1.25 / I) - 1e-12))
        return f"1/{2 ** min(n, 3)}A"
    n = max(0, math.ceil(math.log2(I / 2.5) - 1e-12))
    if n > 25:
        return "?"
    return chr(ord("A") + n)


class Motor(abc.ABC):
    """A rocket motor: thrust, mass, CG and inertia as functions of time.

    Required attributes (plain data, numeric): ``designation`` (str),
    ``manufacturer`` (str), ``burn_time`` [s], ``total_impulse`` [N s],
    ``dry_mass`` [kg], ``propellant_mass_initial`` [kg], ``diameter`` [m],
    ``length`` [m], ``nozzle_exit_area`` [m^2] or None,
    ``reference_pressure`` [Pa] (ambient pressure the thrust curve was measured
    at).  All unscaled (``thrust_scale`` = ``time_scale`` = 1).

    The public methods are symbolic-safe: ``t``, ``thrust_scale`` and
    ``time_scale`` may be floats, NumPy arrays or CasADi SX/MX.
    """

    # ---- to be implemented by each kind of motor (unscaled, tau = t / s) ----
    @abc.abstractmethod
    def _thrust_unscaled(self, tau):
        """F0(tau) [N], 0 before ignition and after burnout. Symbolic-safe."""

    @abc.abstractmethod
    def _impulse_unscaled(self, tau):
        """I0(tau) = integral of F0 from 0 to tau [N s]. Symbolic-safe."""

    @abc.abstractmethod
    def _mass_properties_unscaled(self, tau):
        """(propellant_mass [kg], cg [m fwd of nozzle exit],
        (I_transverse, I_axial) [kg m^2] about cg) at tau. Symbolic-safe."""

    # ---- scaling hook, done once for every motor ----
    def thrust(self, t, thrust_scale=1.0, time_scale=1.0):
        """Thrust [N] at time ``t`` [s]: k_F / s * F0(t / s). Symbolic-safe.

        Parameters
        ----------
        t : float, array or CasADi SX/MX [s]
            Time since ignition.
        thrust_scale : [-]
            Impulse (thrust) multiplier k_F.
        time_scale : [-]
            Burn-time multiplier s (impulse unchanged).
        """
        return thrust_scale / time_scale * self._thrust_unscaled(t / time_scale)

    def impulse(self, t, thrust_scale=1.0, time_scale=1.0):
        """Impulse delivered from ignition to ``t`` [N s]: k_F * I0(t / s).
        Symbolic-safe; arguments as in :meth:`thrust`."""
        return thrust_scale * self._impulse_unscaled(t / time_scale)

    def propellant_mass(self, t, thrust_scale=1.0, time_scale=1.0):
        """Remaining propellant mass [kg] at ``t`` [s]. Symbolic-safe;
        independent of ``thrust_scale``; arguments as in :meth:`thrust`."""
        return self._mass_properties_unscaled(t / time_scale)[0]

    def mass(self, t, thrust_scale=1.0, time_scale=1.0):
        """Motor mass (dry + remaining propellant) [kg] at ``t`` [s].
        Symbolic-safe; arguments as in :meth:`thrust`."""
        return self.dry_mass + self.propellant_mass(t, thrust_scale, time_scale)

    def cg(self, t, thrust_scale=1.0, time_scale=1.0):
        """Motor CG [m forward of the nozzle exit] at ``t`` [s].
        Symbolic-safe; arguments as in :meth:`thrust`."""
        return self._mass_properties_unscaled(t / time_scale)[1]

    def inertia(self, t, thrust_scale=1.0, time_scale=1.0):
        """(I_transverse, I_axial) [kg m^2] about the motor's current CG at
        ``t`` [s]. Symbolic-safe; arguments as in :meth:`thrust`."""
        return self._mass_properties_unscaled(t / time_scale)[2]

    def state(self, t, thrust_scale=1.0, time_scale=1.0) -> MotorState:
        """Thrust, propellant mass, mass, CG and inertia at ``t`` [s] in one
        call, building the shared subexpressions once (use this inside an
        integrator step). Symbolic-safe; arguments as in :meth:`thrust`."""
        f0, (mp, cg, inertia) = self._thrust_and_mass_properties_unscaled(t / time_scale)
        return MotorState(thrust_scale / time_scale * f0, mp, self.dry_mass + mp, cg, inertia)

    def _thrust_and_mass_properties_unscaled(self, tau):
        """(F0(tau), mass properties at tau); override to share work."""
        return self._thrust_unscaled(tau), self._mass_properties_unscaled(tau)

    def mass_driver(self, t, time_scale=1.0):
        """``(d, d_dot, props)`` when the mass properties depend on time only through
        one scalar ``d(t)`` whose rate ``d_dot`` is known in closed form, with
        ``props(d)`` -> (propellant mass, cg, (I_t, I_a)) as
        :meth:`_mass_properties_unscaled`; else None (the flight then differentiates
        the mass histories symbolically).  Symbolic-safe; ``time_scale`` as in :meth:`thrust`."""
        return None

    def pressure_thrust_correction(self, p_ambient):
        """Thrust change [N] from ambient pressure ``p_ambient`` [Pa] differing
        from the pressure the curve was measured at. Symbolic-safe.

        dF = (p_ref - p_ambient) * A_exit, the pressure term of the rocket
        thrust equation F = mdot v_e + (p_e - p_a) A_e (Sutton & Biblarz,
        Rocket Propulsion Elements, 9th ed., eq. 2-14).  0 when the exit area
        is unknown.  Add it only while the motor burns.
        """
        if self.nozzle_exit_area is None:
            return 0.0 * p_ambient
        return (self.reference_pressure - p_ambient) * self.nozzle_exit_area

    # ---- numeric summaries ----
    def burn_time_scaled(self, time_scale: float = 1.0) -> float:
        """Burn time [s] with a numeric burn-time scale s [-]."""
        return self.burn_time * time_scale

    @property
    def average_thrust(self) -> float:
        """Total impulse / burn time [N], numeric."""
        return self.total_impulse / self.burn_time

    @property
    def max_thrust(self) -> float:
        """Peak thrust [N], numeric (subclasses may override with an exact value)."""
        t = np.linspace(0.0, self.burn_time, 2001)
        return float(np.max(self._thrust_unscaled(t)))

    @property
    def total_mass(self) -> float:
        """Mass at ignition [kg], numeric."""
        return self.dry_mass + self.propellant_mass_initial

    @property
    def impulse_class(self) -> str:
        """Impulse class letter (A, B, ..., O), numeric."""
        return impulse_class(self.total_impulse)

    @property
    def specific_impulse(self) -> float:
        """Total impulse / (propellant mass * g0) [s], numeric."""
        return self.total_impulse / (self.propellant_mass_initial * G0)

    def to_dict(self) -> dict:
        """Plain dict of the motor's headline numbers, keys named for their unit."""
        return {
            "designation": self.designation,
            "manufacturer": self.manufacturer,
            "impulse_class": self.impulse_class,
            "total_impulse_Ns": float(self.total_impulse),
            "burn_time_s": float(self.burn_time),
            "average_thrust_N": float(self.average_thrust),
            "max_thrust_N": float(self.max_thrust),
            "propellant_mass_kg": float(self.propellant_mass_initial),
            "dry_mass_kg": float(self.dry_mass),
            "total_mass_kg": float(self.total_mass),
            "specific_impulse_s": float(self.specific_impulse),
            "diameter_m": float(self.diameter),
            "length_m": float(self.length),
            "nozzle_exit_area_m2": (None if self.nozzle_exit_area is None
                                    else float(self.nozzle_exit_area)),
        }

    def summary(self) -> str:
        """Multi-line human-readable summary (returned, not printed)."""
        d = self.to_dict()
        name = " ".join(x for x in (d["manufacturer"], d["designation"]) if x) or "(unnamed motor)"
        return "\n".join([
            f"{name}  [class {d['impulse_class']}]",
            f"  total impulse   {d['total_impulse_Ns']:10.1f} N s",
            f"  burn time       {d['burn_time_s']:10.3f} s",
            f"  average thrust  {d['average_thrust_N']:10.1f} N",
            f"  max thrust      {d['max_thrust_N']:10.1f} N",
            f"  propellant mass {d['propellant_mass_kg']:10.3f} kg",
            f"  total mass      {d['total_mass_kg']:10.3f} kg",
            f"  Isp             {d['specific_impulse_s']:10.1f} s",
        ])

    def __repr__(self) -> str:
        return (f"{type(self).__name__}({self.designation or '?'}, I={self.total_impulse:.1f} N s, "
                f"t_b={self.burn_time:.3f} s, m={self.total_mass:.3f} kg)")

