"""Rocket motors: the ``Motor`` interface, solid motors and their file readers.

- :mod:`.base` — ``Motor`` (thrust, mass, CG, inertia vs time; the
  thrust-scale / burn-time-scale hook), impulse classes.
- :mod:`.solid` — ``SolidMotor`` (tabulated thrust curve, propellant burned
  in proportion to delivered impulse).
- :mod:`.grains` — ``Grains`` (BATES geometry) and propellant/case inertia models.
- :mod:`.rasp`, :mod:`.rse`, :mod:`.thrust_csv` — ``.eng``, ``.rse`` and CSV readers.

``load_motor(path, designation=None, **overrides)`` picks the reader by the
file's extension and one motor by name.
"""
from __future__ import annotations

import re
from os import PathLike
from pathlib import Path

from ironbark_opt.errors import InputError
from ironbark_opt.motors.base import Motor, MotorState, impulse_class
from ironbark_opt.motors.grains import Grains
from ironbark_opt.motors.rasp import common_name, read_eng, write_eng
from ironbark_opt.motors.rse import read_rse
from ironbark_opt.motors.solid import SolidMotor
from ironbark_opt.motors.thrust_csv import read_thrust_csv

__all__ = ["Motor", "MotorState", "SolidMotor", "Grains", "impulse_class", "read_eng",
           "write_eng", "read_rse", "read_thrust_csv", "load_motor", "select_motor",
           "common_name"]


def _norm(name: str) -> str:
    return re.sub(r"[^A-Z0-9]", "", name.upper())


def select_motor(motors, designation: str | None, *, source=None) -> SolidMotor:
    """The motor named ``designation`` among ``motors``. Numeric-only.

    Matches, ignoring case and punctuation, the full designation
    (``M1670-BS``) or the common name (class letter + average thrust,
    ``M1670``).  With ``designation=None`` the list must hold one motor.

    Raises
    ------
    InputError
        No match, several matches, or several motors and no designation;
        the message lists the motors available.
    """
    motors = list(motors)
    listing = ", ".join(m.designation or "?" for m in motors)
    if designation is None:
        if len(motors) == 1:
            return motors[0]
        raise InputError(f"file holds {len(motors)} motors ({listing}); choose one with "
                         f"designation=...", source=source, field="designation")
    want = _norm(designation)
    exact = [m for m in motors if _norm(m.designation) == want]
    found = exact or [m for m in motors if want and _norm(common_name(m.designation)) == want]
    if len(found) == 1:
        return found[0]
    if not found:
        raise InputError(f"no motor {designation!r} in file; available: {listing}",
                         source=source, field="designation")
    raise InputError(f"{designation!r} matches several motors "
                     f"({', '.join(m.designation for m in found)}); give the full designation",
                     source=source, field="designation")


def load_motor(path: str | PathLike, designation: str | None = None, **overrides) -> SolidMotor:
    """Read one motor from a ``.eng``, ``.rse`` or ``.csv``/``.txt`` file. Numeric-only.

    Parameters
    ----------
    path : str or path-like
    designation : str, optional
        Which motor of a multi-motor file (full designation or common name,
        case-insensitive).
    **overrides
        ``SolidMotor`` fields in SI units (``dry_mass=1.815``,
        ``grains=Grains(...)``, ...) applied after reading; required for
        thrust tables (masses, diameter, length).
    """
    p = Path(path)
    ext = p.suffix.lower()
    if ext == ".eng":
        motors = read_eng(p, **overrides)
    elif ext == ".rse":
        motors = read_rse(p, **overrides)
    elif ext in (".csv", ".txt", ".tsv", ".dat"):
        motors = [read_thrust_csv(p, **overrides)]
    else:
        raise InputError(f"unknown motor file type {ext or '(none)'!r}; expected .eng (RASP), "
                         f".rse (RockSim) or .csv (time_s, thrust_N)", source=p)
    return select_motor(motors, designation, source=p)
