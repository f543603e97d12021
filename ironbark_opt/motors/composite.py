"""Several motors in one stage lit at different times (air-start), as one ``Motor``.

OpenRocket's ignition settings for motors in the same stage ("automatic" /
"launch" + a delay, or the burnout of another motor + a delay) fix each
motor's ignition time ``t_i`` [s after launch] per configuration, so the
stage's propulsion is one motor with

    F(t) = sum_i F_i(t - t_i),       m(t) = sum_i m_i(t - t_i),
    x_cg(t) = sum_i m_i x_i / m,     I_t = sum_i (I_t,i + m_i (x_i - x_cg)^2),  I_a = sum_i I_a,i

with ``x_i`` each motor's CG on the rocket axis (its nozzle exit ``nozzle_x_i``
minus its own CG); a motor before its ignition is full and gives no thrust.
Off-axis mounts are placed on the axis (their radial offset adds m d^2 to
the roll inertia only, neglected as for clusters).  The burn-time scale of
:class:`~ironbark_opt.motors.base.Motor` stretches the whole sequence
(ignition delays included).  Symbolic-safe like every motor.

The flight core splits the boost phase at every ignition and burnout in
between (:attr:`CompositeMotor.events`, scaled by the burn-time scale), so
no thrust jump falls inside an RK4 step and apogee stays smooth in the
parameters (an event before rail exit is not supported).
"""
from __future__ import annotations

from dataclasses import dataclass

from ironbark_opt.errors import InputError
from ironbark_opt.motors.base import Motor


@dataclass(frozen=True)
class CompositeMotor(Motor):
    """Motors of one stage with ignition times, on one reference nozzle.

    Parameters
    ----------
    motors : tuple of Motor
    ignition_times : tuple of float [s after launch]
        The first must be 0 (the motor that launches the rocket).
    nozzle_x : tuple of float [m aft of the nose tip]
        Each motor's nozzle exit.
    reference_nozzle_x : float [m aft of the nose tip]
        The rocket's nozzle position; :meth:`cg` is measured forward of it.
    """

    motors: tuple
    ignition_times: tuple
    nozzle_x: tuple
    reference_nozzle_x: float

    def __post_init__(self):
        if not (len(self.motors) == len(self.ignition_times) == len(self.nozzle_x)) or not self.motors:
            raise InputError("a composite motor needs one ignition time and nozzle position per motor",
                             field="motors")
        if min(self.ignition_times) != 0.0:  # noqa: SIM102
            raise InputError("one motor must ignite at launch (ignition time 0)", field="ignition_times")
        if any(t < 0 for t in self.ignition_times):
            raise InputError("ignition times must be >= 0 s", field="ignition_times")

    # -- plain data of the Motor interface --------------------------------------
    @property
    def designation(self) -> str:
        return "+".join(f"{m.designation}" + (f"@{t:g}s" if t else "")
                        for m, t in zip(self.motors, self.ignition_times))

    @property
    def manufacturer(self) -> str:
        return "/".join(sorted({m.manufacturer for m in self.motors}))

    @property
    def burn_time(self) -> float:
        """Launch to the last motor's burnout [s]."""
        return max(t + m.burn_time for m, t in zip(self.motors, self.ignition_times))

    @property
    def events(self) -> tuple:
        """Ignition and burnout times after launch [s], sorted, without 0 and the end."""
        times = {t for t in self.ignition_times} | {t + m.burn_time for m, t in zip(self.motors, self.ignition_times)}
        return tuple(sorted(t for t in times if 0.0 < t < self.burn_time))

    @property
    def total_impulse(self) -> float:
        return sum(m.total_impulse for m in self.motors)

    @property
    def dry_mass(self) -> float:
        return sum(m.dry_mass for m in self.motors)

    @property
    def propellant_mass_initial(self) -> float:
        return sum(m.propellant_mass_initial for m in self.motors)

    @property
    def diameter(self) -> float:
        return max(m.diameter for m in self.motors)

    @property
    def length(self) -> float:
        return max(m.length for m in self.motors)

    nozzle_exit_area = None          # pressure correction per motor not modelled
    reference_pressure = 101325.0

    # -- unscaled histories ---------------------------------------------------
    def _thrust_unscaled(self, tau):
        return sum(m._thrust_unscaled(tau - t) for m, t in zip(self.motors, self.ignition_times))

    def _impulse_unscaled(self, tau):
        return sum(m._impulse_unscaled(tau - t) for m, t in zip(self.motors, self.ignition_times))

    def _parts(self, tau):
        out = []
        for m, t, xn in zip(self.motors, self.ignition_times, self.nozzle_x):
            mp, cg, (it, ia) = m._mass_properties_unscaled(tau - t)
            out.append((m.dry_mass + mp, mp, xn - cg, it, ia))     # CG on the rocket axis [m aft of tip]
        return out

    def _mass_properties_unscaled(self, tau):
        parts = self._parts(tau)
        mass = sum(p[0] for p in parts)
        x_cg = sum(p[0] * p[2] for p in parts) / mass
        i_t = sum(p[3] + p[0] * (p[2] - x_cg) ** 2 for p in parts)
        i_a = sum(p[4] for p in parts)
        # Motor.mass() = dry_mass + propellant: the propellant share is the rest.
        return mass - self.dry_mass, self.reference_nozzle_x - x_cg, (i_t, i_a)


@dataclass(frozen=True)
class DelayedMotor(Motor):
    """``motor`` ignited ``delay`` [s] (unscaled) after launch: an upper stage lit at
    the lower stage's burnout.  The burn-time scale stretches the delay too (it
    is the lower stage's burn time).  Symbolic-safe.

    Parameters
    ----------
    motor : Motor
    delay : float [s]
    """

    motor: Motor
    delay: float

    designation = property(lambda self: self.motor.designation)
    manufacturer = property(lambda self: self.motor.manufacturer)
    total_impulse = property(lambda self: self.motor.total_impulse)
    dry_mass = property(lambda self: self.motor.dry_mass)
    propellant_mass_initial = property(lambda self: self.motor.propellant_mass_initial)
    diameter = property(lambda self: self.motor.diameter)
    length = property(lambda self: self.motor.length)
    nozzle_exit_area = property(lambda self: self.motor.nozzle_exit_area)
    reference_pressure = property(lambda self: self.motor.reference_pressure)

    @property
    def burn_time(self) -> float:
        """Launch to burnout [s] (unscaled)."""
        return self.delay + self.motor.burn_time

    def _thrust_unscaled(self, tau):
        return self.motor._thrust_unscaled(tau - self.delay)

    def _impulse_unscaled(self, tau):
        return self.motor._impulse_unscaled(tau - self.delay)

    def _mass_properties_unscaled(self, tau):
        return self.motor._mass_properties_unscaled(tau - self.delay)


@dataclass(frozen=True)
class UnlitMotor(Motor):
    """``motor`` carried unlit (an upper stage's motor while the booster burns):
    no thrust, its full mass, CG and inertia at ignition.  Symbolic-safe."""

    motor: Motor

    designation = property(lambda self: f"{self.motor.designation} (unlit)")
    manufacturer = property(lambda self: self.motor.manufacturer)
    dry_mass = property(lambda self: self.motor.dry_mass)
    propellant_mass_initial = property(lambda self: self.motor.propellant_mass_initial)
    diameter = property(lambda self: self.motor.diameter)
    length = property(lambda self: self.motor.length)
    nozzle_exit_area = None
    reference_pressure = 101325.0
    burn_time = 0.0
    total_impulse = 0.0

    def _thrust_unscaled(self, tau):
        return 0.0 * tau

    def _impulse_unscaled(self, tau):
        return 0.0 * tau

    def _mass_properties_unscaled(self, tau):
        mp, cg, inertia = self.motor._mass_properties_unscaled(0.0)
        return mp + 0.0 * tau, cg + 0.0 * tau, (inertia[0] + 0.0 * tau, inertia[1] + 0.0 * tau)
