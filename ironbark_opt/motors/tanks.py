"""Propellant tanks of liquid and hybrid motors: fluid masses, CG and inertia versus time.

A tank is a cylinder (inner radius ``R``, inner length ``L``) whose centre sits
``position`` [m] forward of the motor's nozzle exit.  It holds a liquid (density
rho_l) and a gas (rho_g).  Under thrust the liquid settles at the aft end (the
end nearest the nozzle) as a column of height h_l = m_l / (rho_l pi R^2); the
gas fills the ullage above it.  Each phase is treated as a solid cylinder of
its column (I_axial = m R^2 / 2, I_transverse = m (3 R^2 + h^2) / 12, about its
own centre; Hibbeler, *Engineering Mechanics: Dynamics*, table of mass moments
of inertia), as RocketPy's ``Tank`` does.  The liquid is taken to turn with the
rocket (its axial inertia is an upper bound; the roll inertia barely matters
for apogee).

How the masses change (the ``schedule``), as teams give them (the same four
kinds as RocketPy's ``MassFlowRateBasedTank``, ``MassBasedTank``,
``UllageBasedTank`` and ``LevelBasedTank``, plus one from the thrust curve):

- ``mass_flow``: initial liquid and gas masses and their outflow rates [kg/s],
  each a constant over a time window or a ``time_s, kg/s`` table (linear in
  time, integrated exactly at sub-steps of each interval);
- ``mass``: a ``time_s, liquid_kg[, gas_kg]`` table;
- ``ullage``: a ``time_s, ullage_m3`` table; liquid = rho_l (V - V_u),
  gas = rho_g V_u (the gas fills the ullage at its density);
- ``level``: a ``time_s, level_m`` table of the liquid's height above the aft
  end; liquid = rho_l pi R^2 h, gas = rho_g pi R^2 (L - h);
- ``thrust``: the tank drains in proportion to the impulse delivered after
  ignition, m(t) = m_0 (1 - I(t) / I_total): constant effective exhaust
  velocity and constant mixture ratio (Sutton & Biblarz, *Rocket Propulsion
  Elements*, 9th ed., eq. 2-16, F = mdot c), so the O/F ratio is the ratio of
  the tanks' initial masses.

All schedules are held at their end values outside their tables.  Times are
on the motor's clock (t = 0 when the valves open; ignition may come later).
The functions of time are symbolic-safe (one ``casadi.interpolant`` per tank).
"""
from __future__ import annotations

import hashlib
import math
from dataclasses import dataclass, field

import casadi as ca
import numpy as np

from ironbark_opt import _math as sm
from ironbark_opt.errors import InputError

SCHEDULES = ("mass_flow", "mass", "ullage", "level", "thrust")

#: Sub-steps per interval of a tabulated mass-flow rate: the integral of a
#: linear rate is quadratic; mass is tabulated at these points and read back
#: linearly (error < max|d mdot/dt| dt^2 / (8 * SUBSTEPS^2)).
SUBSTEPS = 8

#: Relative tolerance on a tank holding more liquid than its volume.
OVERFILL_TOLERANCE = 1e-6


class LinearTable:
    """Piecewise-linear table ``t -> (columns...)``, held constant outside.

    Symbolic-safe :meth:`__call__` (a ``casadi.interpolant`` for symbols, built on
    first use and not pickled; ``np.interp`` for numbers).
    """

    def __init__(self, t, columns, name: str):
        self.t = np.asarray(t, dtype=float)
        self.columns = np.atleast_2d(np.asarray(columns, dtype=float))
        if self.t.size == 1:                       # a constant: two equal knots
            self.t = np.r_[self.t, self.t + 1.0]
            self.columns = np.repeat(self.columns, 2, axis=1)
        digest = hashlib.sha1(np.r_[self.t, self.columns.ravel()].tobytes()).hexdigest()[:12]
        self.name = f"{name}_{digest}"
        self._fn = None

    def __getstate__(self):
        state = dict(self.__dict__)
        state["_fn"] = None
        return state

    def __call__(self, tau):
        """Tuple of the columns at ``tau``; symbolic-safe."""
        if sm.is_symbolic(tau):
            if self._fn is None:
                self._fn = ca.interpolant(self.name, "linear", [self.t],
                                          self.columns.T.ravel())
            out = self._fn(sm.clip(tau, self.t[0], self.t[-1]))
            return tuple(out[k] for k in range(self.columns.shape[0]))
        x = np.asarray(tau, dtype=float)
        vals = tuple(np.interp(x, self.t, c) for c in self.columns)
        return vals if isinstance(tau, np.ndarray) else tuple(float(v) for v in vals)


def integrate_rate(t, rate, m0: float):
    """Mass left after draining at the piecewise-linear ``rate`` [kg/s] from
    ``m0`` [kg]: (times, masses) at ``SUBSTEPS`` points per interval, exact at
    each point (trapezoid rule on a linear rate). Numeric-only."""
    t = np.asarray(t, dtype=float)
    rate = np.asarray(rate, dtype=float)
    if t.size == 1:
        return t, np.array([m0])
    frac = np.linspace(0.0, 1.0, SUBSTEPS + 1)[:-1]
    tt = np.r_[(t[:-1, None] + np.diff(t)[:, None] * frac).ravel(), t[-1]]
    rr = np.interp(tt, t, rate)
    out = np.r_[0.0, np.cumsum(np.diff(tt) * (rr[1:] + rr[:-1]) / 2.0)]
    return tt, m0 - out


@dataclass(frozen=True, eq=False)
class Tank:
    """A cylindrical tank of liquid and gas with a mass schedule.

    Parameters
    ----------
    name : str
    position : float [m]
        Centre of the tank forward of the nozzle exit.
    radius, length : float [m]
        Inner radius and inner length (flat ends).
    liquid_density, gas_density : float [kg/m^3]
    schedule : str
        One of :data:`SCHEDULES` (module docstring).
    time : array [s]
        Times of the schedule's table (motor clock); unused for ``thrust``.
    liquid_mass, gas_mass : array [kg]
        Liquid and gas masses at ``time`` (``thrust``: one value each, the
        masses at ignition).  The file readers turn every schedule into these
        two tables (:func:`tank_from_schedule`).
    source : str, optional
        File or TOML table the tank came from (named in errors).
    """

    name: str
    position: float
    radius: float
    length: float
    liquid_density: float
    gas_density: float
    schedule: str
    time: np.ndarray
    liquid_mass: np.ndarray
    gas_mass: np.ndarray
    source: str | None = None
    _table: LinearTable = field(init=False, repr=False)

    def __post_init__(self):
        src = self.source
        for name in ("radius", "length", "liquid_density", "gas_density"):
            v = float(getattr(self, name))
            if not math.isfinite(v) or v <= 0:
                raise InputError(f"expected a positive number, got {v!r}", source=src,
                                 field=f"tank {self.name}: {name}")
            object.__setattr__(self, name, v)
        object.__setattr__(self, "position", float(self.position))
        if self.schedule not in SCHEDULES:
            raise InputError(f"expected one of {', '.join(SCHEDULES)}, got {self.schedule!r}",
                             source=src, field=f"tank {self.name}: schedule")
        t = np.atleast_1d(np.asarray(self.time, dtype=float))
        ml = np.atleast_1d(np.asarray(self.liquid_mass, dtype=float))
        mg = np.atleast_1d(np.asarray(self.gas_mass, dtype=float))
        if not (t.size == ml.size == mg.size) or t.size < 1:
            raise InputError("schedule times and masses differ in length", source=src,
                             field=f"tank {self.name}: schedule")
        if np.any(np.diff(t) <= 0):
            raise InputError("schedule times must increase", source=src,
                             field=f"tank {self.name}: time")
        tol = 1e-5 + 1e-6 * float(np.max(ml) + np.max(mg))   # round-off of ramps
        neg = np.nonzero((ml < -tol) | (mg < -tol))[0]
        if neg.size:
            k = int(neg[0])
            raise InputError(f"the tank would hold a negative mass at t = {t[k]:g} s "
                             f"(liquid {ml[k]:.4g} kg, gas {mg[k]:.4g} kg): the outflow "
                             f"exceeds the initial mass", source=src,
                             field=f"tank {self.name}: schedule")
        ml, mg = np.maximum(ml, 0.0), np.maximum(mg, 0.0)
        fill = ml / self.liquid_density / self.volume
        if np.max(fill) > 1.0 + OVERFILL_TOLERANCE:
            k = int(np.argmax(fill))
            raise InputError(f"{ml[k]:.4g} kg of liquid at t = {t[k]:g} s needs "
                             f"{ml[k] / self.liquid_density:.4g} m^3 but the tank holds "
                             f"{self.volume:.4g} m^3", source=src,
                             field=f"tank {self.name}: liquid_mass")
        for arr in (t, ml, mg):
            arr.flags.writeable = False
        object.__setattr__(self, "time", t)
        object.__setattr__(self, "liquid_mass", ml)
        object.__setattr__(self, "gas_mass", mg)
        object.__setattr__(self, "_table", LinearTable(t, np.vstack([ml, mg]), f"tank_{self.name}"))

    # ------------------------------------------------------------------ data
    @property
    def area(self) -> float:
        """Inner cross-section [m^2]."""
        return math.pi * self.radius ** 2

    @property
    def volume(self) -> float:
        """Inner volume [m^3]."""
        return self.area * self.length

    @property
    def initial_mass(self) -> float:
        """Liquid + gas at the start of the schedule [kg]."""
        return float(self.liquid_mass[0] + self.gas_mass[0])

    @property
    def end_time(self) -> float:
        """Last time of the schedule [s] (0 for ``thrust``)."""
        return float(self.time[-1])

    # ------------------------------------------------------------- histories
    def masses(self, tau, impulse_fraction=None):
        """(liquid [kg], gas [kg]) at motor time ``tau`` [s]; symbolic-safe.

        ``impulse_fraction`` = I(tau) / I_total is required for the ``thrust``
        schedule (masses m_0 (1 - I / I_total))."""
        if self.schedule == "thrust":
            left = 1.0 - impulse_fraction
            return self.liquid_mass[0] * left, self.gas_mass[0] * left
        return self._table(tau)

    def mass_properties(self, liquid, gas):
        """(mass [kg], CG [m fwd of nozzle exit], (I_t, I_a) [kg m^2] about
        that CG) of the tank's contents; symbolic-safe in the two masses."""
        R2, L = self.radius ** 2, self.length
        h_l = liquid / (self.liquid_density * self.area)        # liquid column from the aft end
        h_g = L - h_l                                            # ullage above it
        aft = self.position - L / 2.0
        x_l = aft + h_l / 2.0
        x_g = aft + h_l + h_g / 2.0
        m = liquid + gas
        # the tank empty of both: CG at its centre (no 0/0)
        x = (liquid * x_l + gas * x_g + 1e-12 * self.position) / (m + 1e-12)
        i_t = (liquid * (3.0 * R2 + h_l * h_l) / 12.0 + liquid * (x_l - x) ** 2
               + gas * (3.0 * R2 + h_g * h_g) / 12.0 + gas * (x_g - x) ** 2)
        i_a = m * R2 / 2.0
        return m, x, (i_t, i_a)


def _rate_masses(t_rate, rate, m0, kind, tank):
    if np.any(np.asarray(rate) < 0):
        raise InputError(f"{kind} outflow must be >= 0 kg/s", source=tank.get("source"),
                         field=f"tank {tank['name']}: {kind}_mass_flow")
    return integrate_rate(t_rate, rate, m0)


def tank_from_schedule(*, name, position, radius, length, liquid_density, gas_density,
                       schedule, liquid_mass=0.0, gas_mass=0.0, liquid_flow=None,
                       gas_flow=None, table=None, source=None) -> Tank:
    """Build a :class:`Tank` from a schedule as a user gives it. Numeric-only.

    Parameters
    ----------
    liquid_mass, gas_mass : float [kg]
        Initial masses (``mass_flow``; ``thrust``: at ignition).
    liquid_flow, gas_flow : (times [s], rates [kg/s]) or None
        Outflow of each phase for ``mass_flow`` (None: no flow).
    table : (times [s], columns) for ``mass`` (liquid, gas), ``ullage``
        (ullage volume [m^3]) and ``level`` (liquid height [m]).
    """
    area = math.pi * radius ** 2
    volume = area * length
    info = {"name": name, "source": source}
    if schedule == "thrust":
        t, ml, mg = [0.0], [liquid_mass], [gas_mass]
    elif schedule == "mass_flow":
        parts = []
        for m0, flow, kind in ((liquid_mass, liquid_flow, "liquid"), (gas_mass, gas_flow, "gas")):
            if flow is None:
                parts.append((np.array([0.0]), np.array([m0])))
            else:
                parts.append(_rate_masses(flow[0], flow[1], m0, kind, info))
        t = np.union1d(parts[0][0], parts[1][0])
        ml = np.interp(t, *parts[0])
        mg = np.interp(t, *parts[1])
    elif schedule in ("mass", "ullage", "level"):
        if table is None:
            raise InputError(f"schedule {schedule!r} needs a table file", source=source,
                             field=f"tank {name}: file")
        t, cols = np.asarray(table[0], float), [np.asarray(c, float) for c in table[1]]
        if schedule == "mass":
            ml, mg = cols[0], cols[1] if len(cols) > 1 else np.zeros_like(cols[0])
        elif schedule == "ullage":
            vu = cols[0]
            if np.any(vu < 0) or np.any(vu > volume * (1 + OVERFILL_TOLERANCE)):
                raise InputError(f"ullage volume must lie in [0, {volume:.4g}] m^3 (the tank's)",
                                 source=source, field=f"tank {name}: file")
            ml, mg = liquid_density * (volume - vu), gas_density * vu
        else:
            h = cols[0]
            if np.any(h < 0) or np.any(h > length * (1 + OVERFILL_TOLERANCE)):
                raise InputError(f"liquid level must lie in [0, {length:g}] m (the tank's length)",
                                 source=source, field=f"tank {name}: file")
            ml, mg = liquid_density * area * h, gas_density * area * (length - h)
    else:
        raise InputError(f"expected one of {', '.join(SCHEDULES)}, got {schedule!r}",
                         source=source, field=f"tank {name}: schedule")
    return Tank(name=name, position=position, radius=radius, length=length,
                liquid_density=liquid_density, gas_density=gas_density, schedule=schedule,
                time=t, liquid_mass=ml, gas_mass=mg, source=source)
