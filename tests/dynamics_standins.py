"""Minimal stand-ins for the dynamics tests: analytic motors, air and aero.

They implement the same interfaces as the real models (Motor, Atmosphere,
AeroModel), so the flight core is tested against closed-form solutions
without any table or file.
"""
from __future__ import annotations

import numpy as np

from ironbark_opt import _math as m
from ironbark_opt.dynamics.setup import DryMass, FlightSetup
from ironbark_opt.motors.base import Motor


class ConstantMotor(Motor):
    """Constant thrust F [N] and mass flow F/ve for ``burn_time`` [s]."""

    def __init__(self, thrust, burn_time, propellant_mass, dry_mass=1.0):
        self.designation, self.manufacturer = "CONST", "test"
        self.F, self.burn_time = float(thrust), float(burn_time)
        self.propellant_mass_initial, self.dry_mass = float(propellant_mass), float(dry_mass)
        self.total_impulse = self.F * self.burn_time
        self.diameter, self.length = 0.05, 0.5
        self.nozzle_exit_area, self.reference_pressure = None, 101325.0

    def _thrust_unscaled(self, tau):
        return m.if_else((tau >= 0) * (tau <= self.burn_time * (1 + 1e-9)), self.F + 0 * tau, 0 * tau)  # tolerant of round-off at the phase end

    def _impulse_unscaled(self, tau):
        return self.F * m.fmin(m.fmax(tau, 0.0), self.burn_time)

    def _mass_properties_unscaled(self, tau):
        mp = self.propellant_mass_initial * (1 - self._impulse_unscaled(tau) / self.total_impulse)
        return mp, 0.25 + 0 * tau, (0.01 + 0 * tau, 0.001 + 0 * tau)


class UniformAir:
    """Constant density, temperature and viscosity; no wind."""

    def __init__(self, density=1.2, temperature=288.15):
        self.rho, self.T = density, temperature

    def temperature(self, h, dT=0.0):
        return self.T + dT + 0 * h

    def pressure(self, h):
        return self.rho * 287.05287 * self.T + 0 * h

    def density(self, h, dT=0.0):
        return self.rho + 0 * h

    def speed_of_sound(self, h, dT=0.0):
        return m.sqrt(1.4 * 287.05287 * (self.T + dT)) + 0 * h

    def dynamic_viscosity(self, h, dT=0.0):
        return 1.8e-5 + 0 * h

    def wind_l(self, h):
        return 0 * h, 0 * h

    def state(self, h, dT=0.0):
        return {"temperature": self.temperature(h, dT), "pressure": self.pressure(h),
                "density": self.density(h, dT), "speed_of_sound": self.speed_of_sound(h, dT),
                "dynamic_viscosity": self.dynamic_viscosity(h, dT), "wind_east": 0 * h, "wind_north": 0 * h}


class AxialOnlyAero:
    """CA constant, no normal force, no damping."""

    reference_area = 0.01
    reference_length = 0.1128
    moment_reference_x = 0.0

    def __init__(self, ca0=0.5, cn_alpha=0.0, x_cp=1.0):
        self.ca0, self.cn_alpha, self.x_cp = ca0, cn_alpha, x_cp

    def coefficients(self, mach, alpha, reynolds, power_on):
        cn = self.cn_alpha * m.sin(alpha)
        return self.ca0 + 0 * mach, cn, -cn * (self.x_cp - self.moment_reference_x) / self.reference_length

    def pitch_damping(self, mach, x_cg):
        return 0 * mach

    def roll_coefficients(self, mach):
        return 0 * mach, 0 * mach

    def center_of_pressure(self, mach, alpha):
        return self.x_cp + 0 * mach


def vertical_setup(motor, air, aero, *, g=9.80665, dry_mass=10.0, inertia=None, rail_length=1.0):
    dry = DryMass(dry_mass, 0.8, np.diag([0.02, 2.0, 2.0]) if inertia is None else inertia)
    return FlightSetup(motor=motor, nozzle_x=1.5, dry=dry, aero=aero, atmosphere=air,
                       nominal={"rail_length": rail_length, "inclination": np.pi / 2, "heading": 0.0},
                       gravity=(lambda h: g + 0 * h), name="analytic")
