"""Manual thrust curves from CSV / text tables (numeric-only file I/O).

A file of two columns, time and thrust, separated by commas, semicolons,
tabs or spaces; lines starting with ``#`` or ``;`` are comments.  Columns are
found by name in a header row (case and spacing ignored):

- time: ``time_s``, ``time``, ``t``, ``t_s``, ``time (s)``, ``time [s]``;
  ``time_ms`` / ``t_ms`` / ``time (ms)`` in milliseconds;
- thrust: ``thrust_N``, ``thrust``, ``force``, ``force_N``, ``f``, ``f_n``,
  ``thrust (N)``, ``thrust [N]``; ``thrust_lbf`` / ``thrust (lbf)`` in
  pound-force;

or, without a header row, the first two numeric columns are time [s] and
thrust [N].  A file has no motor data, so masses and size come as keyword
arguments (``propellant_mass`` or ``grains``, ``dry_mass``, ``diameter``,
``length`` and any other ``SolidMotor`` field).
"""
from __future__ import annotations

import re
from os import PathLike
from pathlib import Path

import numpy as np

from ironbark_opt.errors import InputError
from ironbark_opt.motors.rasp import build_motor, common_name, parse_number, read_text
from ironbark_opt.motors.solid import SolidMotor
from ironbark_opt.validate import is_float

#: 1 lbf in N (exact, NIST SP 811, appendix B.8).
LBF = 4.4482216152605

_TIME = {"time_s": 1.0, "time": 1.0, "t": 1.0, "t_s": 1.0, "time_sec": 1.0, "seconds": 1.0,
         "time_ms": 1e-3, "t_ms": 1e-3}
_THRUST = {"thrust_n": 1.0, "thrust": 1.0, "force": 1.0, "force_n": 1.0, "f": 1.0, "f_n": 1.0,
           "thrust_newton": 1.0, "thrust_newtons": 1.0,
           "thrust_lbf": LBF, "thrust_lb": LBF, "force_lbf": LBF}


def _key(name: str) -> str:
    """'Thrust (N)' -> 'thrust_n', ' time [s] ' -> 'time_s'."""
    s = re.sub(r"[\[\]\(\)]", " ", name.strip().lower())
    return re.sub(r"[\s\-]+", "_", s.strip())


def _split(line: str) -> list[str]:
    for sep in (",", ";", "\t"):
        if sep in line:
            return [c.strip() for c in line.split(sep)]
    return line.split()


def read_thrust_csv(path: str | PathLike, **mass_kwargs) -> SolidMotor:
    """A SolidMotor from a two-column time / thrust table. Numeric-only.

    Parameters
    ----------
    path : str or path-like
        The CSV / text file.
    **mass_kwargs
        ``SolidMotor`` fields in SI units: ``propellant_mass`` [kg] (or
        ``grains``), ``dry_mass`` [kg], ``diameter`` [m], ``length`` [m]
        are required; ``designation`` defaults to the file's name.

    Raises
    ------
    InputError
        Naming file, line and column: unknown column names, non-numeric
        cells, decreasing times, missing mass data.
    """
    src = Path(path)
    rows, cols, scales, header_line = [], None, (1.0, 1.0), None
    for n, raw in enumerate(read_text(path).splitlines(), start=1):
        line = raw.strip()
        if not line or line[0] in "#;":
            continue
        cells = _split(line)
        if cols is None and header_line is None and not rows and not is_float(cells[0]):
            cols, scales = _columns(cells, src, n)
            header_line = n
            continue
        if cols is None:
            cols = (0, 1)
        if len(cells) <= max(cols):
            raise InputError(f"expected at least {max(cols) + 1} columns, got {len(cells)}: "
                             f"{line!r}", source=src, line=n, field="data")
        t = parse_number(cells[cols[0]], source=src, line=n, field="time") * scales[0]
        f = parse_number(cells[cols[1]], source=src, line=n, field="thrust") * scales[1]
        if rows and t < rows[-1][0]:
            raise InputError(f"time decreases: {t} s after {rows[-1][0]} s", source=src,
                             line=n, field="time")
        if t < 0 or f < 0:
            raise InputError(f"negative {'time' if t < 0 else 'thrust'}: {line!r}", source=src,
                             line=n, field="time" if t < 0 else "thrust")
        rows.append((t, f, n))
    if not rows:
        raise InputError("no thrust data rows", source=src, line=header_line, field="data")
    needed = ["dry_mass", "diameter", "length"]
    if "grains" not in mass_kwargs or mass_kwargs.get("grains") is None:
        needed.insert(0, "propellant_mass")
    missing = [k for k in needed if mass_kwargs.get(k) is None]
    if missing:
        raise InputError(f"a thrust table has no motor data; pass {', '.join(missing)} "
                         f"(SI units) as keyword arguments", source=src, field=missing[0])
    fields = {"designation": common_name(src.stem) or src.stem}
    t = np.array([r[0] for r in rows])
    F = np.array([r[1] for r in rows])
    return build_motor(t, F, fields, mass_kwargs, source=src, line=None)


def _columns(cells, src, n):
    keys = [_key(c) for c in cells]
    ti = next((i for i, k in enumerate(keys) if k in _TIME), None)
    fi = next((i for i, k in enumerate(keys) if k in _THRUST), None)
    if ti is None or fi is None:
        which = "time" if ti is None else "thrust"
        raise InputError(f"no {which} column among {cells}; expected e.g. 'time_s' and "
                         f"'thrust_N' (or two unnamed numeric columns)", source=src, line=n,
                         field=which)
    return (ti, fi), (_TIME[keys[ti]], _THRUST[keys[fi]])
