"""Liquid and hybrid motors: a thrust curve, propellant tanks and (hybrid) a fuel grain.

The thrust and its impulse come from a measured curve (any file the solid
readers take; its mass data are not used), shifted by ``ignition_time`` [s]:
the motor's clock starts when the valves open (t = 0, the flight's t = 0), so
oxidiser may drain on the pad before ignition.  The tanks drain on their own
schedules (:mod:`ironbark_opt.motors.tanks`).

Hybrid fuel grain: the propellant still in the motor after ignition follows
the thrust at a constant effective exhaust velocity c = I_total / m_ig
(Sutton & Biblarz, *Rocket Propulsion Elements*, 9th ed., eq. 2-16,
F = mdot c), with m_ig the propellant in the motor at ignition; the grain
holds what the tanks do not:

    m_fuel(t) = m_ig (1 - I(t) / I_total) - sum_tanks m_tank(max(t, t_ig))

(before ignition the grain is untouched; oxidiser drained on the pad leaves
through the nozzle unburned).  This is how RocketPy's ``HybridMotor`` splits
the mass flow between grain and tanks, except that RocketPy takes c from the
propellant at t = 0 and so lets the grain absorb the oxidiser lost on the pad.
The grain's CG is fixed; its inertia is that of BATES grains burning from the
bore out (:class:`~ironbark_opt.motors.grains.Grains`).  A liquid motor has
no grain: its propellant is the tanks' contents alone.

Everything is moved to the motor's current CG by the parallel-axis theorem.
Symbolic-safe like every :class:`~ironbark_opt.motors.base.Motor`; the
thrust-scale / burn-time-scale hook of the base class applies unchanged (all
schedules are stretched with the burn).
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ironbark_opt.errors import InputError
from ironbark_opt.motors.base import Motor
from ironbark_opt.motors.grains import Grains
from ironbark_opt.motors.solid import SolidMotor
from ironbark_opt.motors.tanks import Tank

#: Fuel mass [fraction of the grain's initial mass] the derived fuel history may
#: leave [0, 1] by before a warning (the tank schedule disagrees with the thrust).
FUEL_BALANCE_TOLERANCE = 0.02


@dataclass(frozen=True, eq=False)
class TankMotor(Motor):
    """Liquid (tanks only) or hybrid (tanks + fuel grain) motor.

    Parameters
    ----------
    curve : SolidMotor
        The thrust curve (its mass model is not used).
    tanks : tuple of Tank
    dry_mass : float [kg]
        Motor without propellant (case, tanks' walls, plumbing, nozzle); >= 0.
    dry_cg : float [m]
        Dry CG forward of the nozzle exit.
    dry_inertia : (float, float) [kg m^2]
        (I_transverse, I_axial) of the dry motor about ``dry_cg``.
    grain : Grains or None
        Hybrid fuel grain (None: a liquid motor).
    grain_position : float [m]
        Grain stack's centre forward of the nozzle exit (hybrid only).
    ignition_time : float [s]
        Delay of the thrust curve after the valves open (t = 0).
    diameter, length : float [m]
        Envelope (for the base-drag jet area when no nozzle exit area is known).
    nozzle_exit_area : float [m^2] or None
    reference_pressure : float [Pa]
    designation, manufacturer : str
    """

    curve: SolidMotor
    tanks: tuple
    dry_mass: float
    dry_cg: float
    dry_inertia: tuple
    grain: Grains | None = None
    grain_position: float = 0.0
    ignition_time: float = 0.0
    diameter: float = 0.0
    length: float = 0.0
    nozzle_exit_area: float | None = None
    reference_pressure: float = 101325.0
    designation: str = ""
    manufacturer: str = ""

    def __post_init__(self):
        src = self.curve.source
        if not self.tanks or not all(isinstance(t, Tank) for t in self.tanks):
            raise InputError("a liquid or hybrid motor needs at least one tank", source=src,
                             field="motor.tank")
        object.__setattr__(self, "tanks", tuple(self.tanks))
        if not math.isfinite(self.ignition_time) or self.ignition_time < 0:
            raise InputError(f"ignition_time must be >= 0 s, got {self.ignition_time!r}",
                             source=src, field="motor.ignition_time")
        if self.dry_mass < 0:
            raise InputError(f"dry_mass must be >= 0, got {self.dry_mass}", source=src,
                             field="motor.overrides.dry_mass")
        if not self.designation:
            object.__setattr__(self, "designation", self.curve.designation)
        if not self.manufacturer:
            object.__setattr__(self, "manufacturer", self.curve.manufacturer)
        # ignition: where the thrust starts to rise (the knot before the first
        # non-zero one) on the motor clock
        t, F, _ = self.curve._knots
        k = int(np.argmax(F > 0))
        t_ig = self.ignition_time + float(t[k - 1] if k > 0 else t[0])
        object.__setattr__(self, "_t_ig", t_ig)
        m_tanks_ig = sum(self._tank_mass_at(k, t_ig, 0.0) for k in self.tanks)
        m_fuel0 = self.grain.mass if self.grain is not None else 0.0
        object.__setattr__(self, "_m_ig", m_tanks_ig + m_fuel0)
        object.__setattr__(self, "_m_fuel0", m_fuel0)
        if self.grain is not None:
            self._check_fuel_balance()

    @staticmethod
    def _tank_mass_at(tank, tau, fraction):
        liquid, gas = tank.masses(tau, fraction)
        return float(liquid + gas)

    def _check_fuel_balance(self):
        """Warn when the fuel history derived from the thrust and the tank
        schedules leaves [0, m_fuel0]: oxidiser leaving faster than the thrust
        consumes propellant (numeric)."""
        import warnings
        tau = np.linspace(0.0, self.burn_time, 2001)
        fuel = self._fuel_mass(tau, self._impulse_unscaled(tau) / self.total_impulse)
        lo, hi = float(np.min(fuel)), float(np.max(fuel))
        tol = FUEL_BALANCE_TOLERANCE * self._m_fuel0
        if lo < -tol or hi > self._m_fuel0 + tol:
            k = int(np.argmax(fuel) if hi > self._m_fuel0 + tol else np.argmin(fuel))
            warnings.warn(
                f"{self.designation}: the fuel mass derived from the thrust curve and the tank "
                f"schedule reaches {fuel[k]:.3f} kg at t = {tau[k]:.2f} s (grain {self._m_fuel0:.3f} kg): "
                f"the oxidiser schedule and the thrust curve disagree (RocketPy's HybridMotor "
                f"makes the same split)", stacklevel=3)

    # ---- plain data of the Motor interface --------------------------------
    @property
    def burn_time(self) -> float:
        """Valves open to the end of the thrust curve [s] (unscaled)."""
        return self.ignition_time + self.curve.burn_time

    @property
    def ignition(self) -> float:
        """First instant of thrust on the motor clock [s] (unscaled)."""
        return self._t_ig

    @property
    def total_impulse(self) -> float:
        return self.curve.total_impulse

    @property
    def propellant_mass_initial(self) -> float:
        """Propellant at t = 0 (valves opening) [kg]: tanks + grain."""
        return sum(k.initial_mass for k in self.tanks) + self._m_fuel0

    @property
    def propellant_mass_at_ignition(self) -> float:
        """Propellant in the motor at ignition [kg]."""
        return self._m_ig

    @property
    def kind(self) -> str:
        return "hybrid" if self.grain is not None else "liquid"

    @property
    def specific_impulse(self) -> float:
        """Total impulse / (propellant burned * g0) [s] (propellant at ignition)."""
        from ironbark_opt.motors.base import G0
        return self.total_impulse / (self._m_ig * G0)

    delays = ()

    # ---- unscaled histories -------------------------------------------------
    def _thrust_unscaled(self, tau):
        return self.curve._curve(tau - self.ignition_time)[0]

    def _impulse_unscaled(self, tau):
        return self.curve._curve(tau - self.ignition_time)[1]

    def _thrust_and_mass_properties_unscaled(self, tau):
        f, i = self.curve._curve(tau - self.ignition_time)
        return f, self._mass_properties_from_impulse(tau, i)

    def _mass_properties_unscaled(self, tau):
        return self._mass_properties_from_impulse(tau, self._impulse_unscaled(tau))

    def _fuel_mass(self, tau, fraction):
        """Grain mass [kg] (module docstring); symbolic-safe."""
        from ironbark_opt import _math as sm
        tau_lit = sm.fmax(tau, self._t_ig)
        tanks = sum(sum(k.masses(tau_lit, fraction)) for k in self.tanks)
        return self._m_ig * (1.0 - fraction) - tanks

    def _mass_properties_from_impulse(self, tau, impulse):
        fraction = impulse / self.total_impulse
        parts = []                       # (mass, cg, I_t, I_a) about each part's own CG
        for k in self.tanks:
            m, x, (it, ia) = k.mass_properties(*k.masses(tau, fraction))
            parts.append((m, x, it, ia))
        if self.grain is not None:
            mf = self._fuel_mass(tau, fraction)
            it, ia = self.grain.inertia(mf, self._m_fuel0)
            parts.append((mf, self.grain_position + 0.0 * mf, it, ia))
        mp = sum(p[0] for p in parts)
        md, xd = self.dry_mass, self.dry_cg
        m = md + mp
        x = (md * xd + sum(p[0] * p[1] for p in parts)) / m
        id_t, id_a = self.dry_inertia
        i_t = id_t + md * (xd - x) ** 2 + sum(p[2] + p[0] * (p[1] - x) ** 2 for p in parts)
        i_a = id_a + sum(p[3] for p in parts)
        return mp, x, (i_t, i_a)

    def propellant_table(self, tau) -> dict:
        """Numeric history at times ``tau`` [s]: propellant mass [kg] and its CG
        [m fwd of the nozzle exit], per tank and grain (for checks and reports)."""
        tau = np.asarray(tau, dtype=float)
        fraction = self._impulse_unscaled(tau) / self.total_impulse
        out = {}
        total_m, total_mx = 0.0 * tau, 0.0 * tau
        for k in self.tanks:
            m, x, _ = k.mass_properties(*k.masses(tau, fraction))
            out[k.name] = m
            total_m, total_mx = total_m + m, total_mx + m * x
        if self.grain is not None:
            mf = self._fuel_mass(tau, fraction)
            out["grain"] = mf
            total_m, total_mx = total_m + mf, total_mx + mf * self.grain_position
        out["propellant_mass_kg"] = total_m
        with np.errstate(invalid="ignore", divide="ignore"):     # no propellant: no CG (NaN)
            out["propellant_cg_m"] = np.where(total_m > 1e-9, total_mx / total_m, np.nan)
        return out

    def to_dict(self) -> dict:
        d = super().to_dict()
        d["kind"] = self.kind
        d["ignition_time_s"] = self._t_ig
        d["propellant_mass_at_ignition_kg"] = self._m_ig
        d["tanks"] = [{"name": k.name, "schedule": k.schedule, "initial_mass_kg": k.initial_mass}
                      for k in self.tanks]
        d["grain_mass_kg"] = self._m_fuel0 if self.grain is not None else None
        return d
