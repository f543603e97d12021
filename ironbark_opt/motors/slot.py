"""A motor slot: any tabulated solid motor as numbers in the parameter vector.

Motor choice solves the same ballast problem for many motors.  Instead of one
flight model and one NLP per motor, the motor's data become parameters: the
thrust curve's knots and values, its impulse table, and the constants of the
mass model (propellant and dry mass, CGs, dry inertia, case radius and
length, nozzle exit area).  One symbolic model, built (and compiled) once,
then flies every candidate by changing numbers.

The bound motor is a :class:`~ironbark_opt.motors.solid.SolidMotor` whose
data are symbols, so its thrust, impulse and mass properties are the very
same expressions (linear table of thrust and ``H = I - tau F / 2`` on the
knots, propellant burned in proportion to impulse, hollow-cylinder
propellant inertia) — a candidate flies the same numbers in a slot as on
its own.  Curves with fewer knots than the slot are padded after burnout
with their last value (time is clipped to the burn, so the padding is
never interpolated into).

Only :class:`SolidMotor` without grain geometry fits a slot
(:func:`fits`); other motors keep the one-model-per-motor path.
"""
from __future__ import annotations

import numpy as np

from ironbark_opt.motors.solid import SolidMotor

#: constants before the tables, in this order
_CONSTANTS = ("burn_time", "total_impulse", "propellant_mass", "dry_mass", "dry_cg", "propellant_cg",
              "dry_inertia_transverse", "dry_inertia_axial", "radius", "length", "nozzle_exit_area",
              "reference_pressure")


def fits(motor) -> bool:
    """True when ``motor`` can fly in a slot (a plain tabulated solid motor)."""
    return type(motor) is SolidMotor and motor.grains is None


def knots(motor) -> int:
    """Number of thrust-curve knots of ``motor`` (as the slot stores them)."""
    return int(motor._knots[0].size)


class MotorSlot:
    """Place of a motor in the parameter vector: ``n_knots`` knots from ``offset``.

    Put it as the ``motor`` of a setup (``dataclasses.replace(setup,
    motor=MotorSlot(...))``) and build the right-hand sides with a longer ``p``
    (:func:`ironbark_opt.dynamics.rhs.build` binds it to its ``p``).
    """

    designation = "motor slot"
    events = ()

    def __init__(self, n_knots: int, offset: int):
        self.n_knots, self.offset = int(n_knots), int(offset)

    def __repr__(self) -> str:
        return f"MotorSlot({self.n_knots} knots at p[{self.offset}:])"

    def __eq__(self, other) -> bool:
        return isinstance(other, MotorSlot) and (self.n_knots, self.offset) == (other.n_knots, other.offset)

    def __hash__(self) -> int:
        return hash((self.n_knots, self.offset))

    @property
    def n_data(self) -> int:
        """Entries of ``p`` the slot uses."""
        return len(_CONSTANTS) + 3 * self.n_knots

    def burn_time(self, p):
        """Unscaled burn time [s] stored in ``p`` (numbers or symbols)."""
        return p[self.offset]

    def pack(self, motor) -> np.ndarray:
        """``motor``'s data as the slot's entries of ``p`` (numeric)."""
        if not fits(motor):
            raise ValueError(f"{motor!r} does not fit a motor slot")
        t, F, H = motor._knots
        n = t.size
        if n > self.n_knots:
            raise ValueError(f"{motor.designation}: {n} knots do not fit a slot of {self.n_knots}")
        pad = self.n_knots - n
        t = np.r_[t, t[-1] + np.arange(1, pad + 1)]
        F, H = np.r_[F, np.full(pad, F[-1])], np.r_[H, np.full(pad, H[-1])]
        i_t, i_a = motor.dry_inertia_value
        area = motor.nozzle_exit_area
        const = [motor.burn_time, motor.total_impulse, motor.propellant_mass_initial, motor.dry_mass,
                 motor.dry_cg_value, motor.propellant_cg_value, i_t, i_a, motor.diameter / 2.0, motor.length,
                 0.0 if area is None else area, motor.reference_pressure]
        return np.concatenate([np.asarray(const, dtype=float), t, np.column_stack([F, H]).ravel()])

    def bind(self, p) -> SolidMotor:
        """The motor whose data are ``p``'s slot entries (symbolic)."""
        return _bound(self, p)


def _bound(slot: MotorSlot, p) -> SolidMotor:
    import casadi as ca

    d = p[slot.offset:slot.offset + slot.n_data]
    c = dict(zip(_CONSTANTS, (d[i] for i in range(len(_CONSTANTS)))))
    k0 = len(_CONSTANTS)
    grid, coeff = d[k0:k0 + slot.n_knots], d[k0 + slot.n_knots:]
    table = ca.interpolant(f"slot_curve_{slot.n_knots}", "linear", [slot.n_knots], 2)
    motor = object.__new__(SolidMotor)
    state = {
        "time": None, "_thrust_data": None, "_propellant_mass_data": None, "designation": "motor slot",
        "manufacturer": "", "delays": (), "grains": None, "source": None,
        "dry_mass": c["dry_mass"], "diameter": 2.0 * c["radius"], "length": c["length"],
        "dry_cg": c["dry_cg"], "propellant_cg": c["propellant_cg"],
        "dry_inertia": None, "_dry_inertia": (c["dry_inertia_transverse"], c["dry_inertia_axial"]),
        "nozzle_exit_area": c["nozzle_exit_area"], "reference_pressure": c["reference_pressure"],
        "_mp0": c["propellant_mass"], "_burnout": c["burn_time"], "_total_impulse": c["total_impulse"],
        "_max_thrust": None, "_knots": None,
        "_interpolant": lambda tau: table(tau, grid, coeff),
    }
    motor.__dict__.update(state)
    return motor
