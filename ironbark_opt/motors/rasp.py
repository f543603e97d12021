"""RASP ``.eng`` thrust-curve files (numeric-only file I/O).

Format (RASP, G. Harry Stine's program; as documented by ThrustCurve.org,
"RASP Engine Format"): ``;`` starts a comment (whole line or the rest of a
line); each motor is a header line

    name  diameter_mm  length_mm  delays  propellant_kg  total_kg  manufacturer

followed by ``time_s thrust_N`` rows.  ``delays`` is a dash-separated list of
seconds, ``P`` for plugged; a file may hold several motors.

Choices where files in the wild disagree (tested in tests/unit/test_motor_rasp.py):

- a UTF-8 byte-order mark is ignored; non-UTF-8 files are read as Latin-1;
- the curve starts from (0, 0) when the first row is after t = 0; a last row
  with non-zero thrust ends the burn there (thrust drops to 0);
- delay ``P`` is stored as ``math.inf``; delays of 100 s or more are
  placeholders some tools write (RASAero ``1000``, ThrustCurve ``1000``) and
  are dropped;
- a file without a header (data from the first line) and the three-number
  header ``Isp_s propellant_kg total_kg`` of some team tools are accepted only
  with the missing fields given as keyword arguments (``diameter``,
  ``length``, and for headerless files ``propellant_mass`` and ``dry_mass``);
  the three numbers are checked against the curve (the specific impulse they
  imply must be within 10 % of the first number) before they are trusted.
"""
from __future__ import annotations

import dataclasses
import math
import re
from os import PathLike
from pathlib import Path

import numpy as np

from ironbark_opt.errors import InputError
from ironbark_opt.motors.base import G0
from ironbark_opt.motors.solid import SolidMotor
from ironbark_opt.validate import is_float

#: Delays at or above this [s] are placeholders, not real delays.
PLACEHOLDER_DELAY = 100.0

_HEADER_FIELDS = ("name", "diameter_mm", "length_mm", "delays", "propellant_kg",
                  "total_kg", "manufacturer")
_OVERRIDABLE = tuple(f.name for f in dataclasses.fields(SolidMotor)
                     if f.name not in ("time", "thrust", "source"))


def read_text(path: str | PathLike) -> str:
    """Text of a motor file; UTF-8 (byte-order mark dropped) or Latin-1. Numeric-only."""
    p = Path(path)
    try:
        raw = p.read_bytes()
    except FileNotFoundError:
        raise InputError("motor file not found", source=p) from None
    except IsADirectoryError:
        raise InputError("is a directory, expected a motor file (.eng, .rse, .csv)", source=p) from None
    except OSError as exc:
        raise InputError(f"cannot read motor file: {exc.strerror}", source=p) from None
    try:
        return raw.decode("utf-8-sig")
    except UnicodeDecodeError:
        return raw.decode("latin-1")


def parse_number(token: str, *, source, line, field) -> float:
    """float(token) or an InputError naming file, line and field."""
    try:
        x = float(token)
    except ValueError:
        raise InputError(f"expected a number, got {token!r}", source=source, line=line,
                         field=field) from None
    if not math.isfinite(x):
        raise InputError(f"expected a finite number, got {token!r}", source=source, line=line,
                         field=field)
    return x


def parse_delays(text: str, *, source, line, separators: str = "-,") -> tuple:
    """Delay list [s] from '4-7', '6,10,14', 'P', '0'; P -> inf, >= 100 s dropped."""
    out = []
    for tok in re.split(f"[{re.escape(separators)}\\s]+", text.strip()):
        if not tok:
            continue
        if tok.upper() == "P":
            out.append(math.inf)
            continue
        d = parse_number(tok, source=source, line=line, field="delays")
        if d < 0:
            raise InputError(f"negative delay {tok!r}", source=source, line=line, field="delays")
        if d < PLACEHOLDER_DELAY:
            out.append(d)
    return tuple(out)


def common_name(designation: str) -> str:
    """Impulse-class letter + average thrust, e.g. '2245-K1075-SK-P' -> 'K1075'
    ('' if there is none). Numeric-only."""
    m = re.search(r"(?<![A-Z])([A-O])(\d+)", designation.upper())
    return m.group(1) + m.group(2) if m else ""


def build_motor(time, thrust, fields: dict, overrides: dict, *, source, line) -> SolidMotor:
    """SolidMotor from a file's fields with the caller's overrides applied."""
    unknown = sorted(set(overrides) - set(_OVERRIDABLE))
    if unknown:
        raise InputError(f"unknown motor field(s) {', '.join(unknown)}; expected some of "
                         f"{', '.join(_OVERRIDABLE)}", source=source)
    kw = {**fields, **overrides}
    try:
        return SolidMotor(time, thrust, source=str(source), **kw)
    except InputError as exc:
        if exc.line is None and exc.source == str(source):
            raise InputError(exc.message, source=source, line=line, field=exc.field) from None
        raise


def _tokens(text: str):
    """(line_number, tokens) for lines with content after removing comments."""
    for n, raw in enumerate(text.splitlines(), start=1):
        body = raw.split(";", 1)[0].strip()
        if body:
            yield n, body.split()


def read_eng(path: str | PathLike, **overrides) -> list[SolidMotor]:
    """All motors of a RASP ``.eng`` file. Numeric-only.

    Parameters
    ----------
    path : str or path-like
        The ``.eng`` file.
    **overrides
        ``SolidMotor`` fields applied to every motor (SI units, e.g.
        ``dry_mass=1.815`` [kg], ``diameter=0.098`` [m]); required for
        headerless and three-number-header files (see the module docstring).

    Returns
    -------
    list of SolidMotor, in file order.

    Raises
    ------
    InputError
        Naming the file, line and field: missing or incomplete header,
        non-numeric or truncated rows, decreasing times, negative thrust,
        a motor without data rows.
    """
    src = Path(path)
    blocks = []          # (header_line, header_tokens or None, [(line, t, F)])
    for n, toks in _tokens(read_text(path)):
        if not is_float(toks[0]):
            if len(toks) < len(_HEADER_FIELDS):
                missing = ", ".join(_HEADER_FIELDS[len(toks):])
                raise InputError(
                    f"neither a data row 'time_s thrust_N' nor a complete motor header "
                    f"'{' '.join(_HEADER_FIELDS)}' (missing: {missing}): {' '.join(toks)!r}",
                    source=src, line=n, field="header")
            blocks.append((n, toks, []))
            continue
        if not blocks:   # numbers before any header: headerless or 3-number header
            if len(toks) == 3 and all(is_float(x) for x in toks):
                blocks.append((n, toks, []))
                continue
            blocks.append((n, None, []))
        if len(toks) != 2:
            what = "truncated row" if len(toks) < 2 else "too many values"
            raise InputError(f"{what}: expected 'time_s thrust_N', got {' '.join(toks)!r}",
                             source=src, line=n, field="data")
        t = parse_number(toks[0], source=src, line=n, field="time")
        f = parse_number(toks[1], source=src, line=n, field="thrust")
        rows = blocks[-1][2]
        if rows and t < rows[-1][1]:
            raise InputError(f"time decreases: {t} s after {rows[-1][1]} s", source=src,
                             line=n, field="time")
        if t < 0 or f < 0:
            raise InputError(f"negative {'time' if t < 0 else 'thrust'} in row {' '.join(toks)!r}",
                             source=src, line=n, field="time" if t < 0 else "thrust")
        rows.append((n, t, f))
    if not blocks:
        raise InputError("no motor in file (empty or only comments)", source=src)
    motors = []
    for hline, header, rows in blocks:
        if not rows:
            name = header[0] if header else "?"
            raise InputError(f"motor {name!r} has no thrust rows (file truncated?)",
                             source=src, line=hline, field="data")
        t = np.array([r[1] for r in rows])
        F = np.array([r[2] for r in rows])
        if header is None:
            fields = _headerless_fields(src, overrides)
        elif len(header) == 3:
            fields = _three_number_fields(src, hline, header, t, F, overrides)
        else:
            fields = _header_fields(src, hline, header)
        motors.append(build_motor(t, F, fields, overrides, source=src, line=hline))
    return motors


def _header_fields(src, n, toks) -> dict:
    dia = parse_number(toks[1], source=src, line=n, field="diameter_mm")
    length = parse_number(toks[2], source=src, line=n, field="length_mm")
    mp = parse_number(toks[4], source=src, line=n, field="propellant_kg")
    mt = parse_number(toks[5], source=src, line=n, field="total_kg")
    for field, val in (("diameter_mm", dia), ("length_mm", length), ("propellant_kg", mp)):
        if val < 0 or (val == 0 and field != "propellant_kg"):   # read even when overridden
            raise InputError(f"{field} must be {'>= 0' if field == 'propellant_kg' else '> 0'}, got {val:g}",
                             source=src, line=n, field=field)
    # equal masses: a dry mass of 0 (the casing counted in the rocket's mass, as the rocket
    # TOML's dry_mass = 0 allows; a RocketPy case converted with dry mass 1e-06 kg and 6
    # decimals in the header rounds to it: juno3, 8.169384 and 8.169384)
    if mt < mp:
        raise InputError(f"total mass {mt} kg must be at least the propellant mass {mp} kg",
                         source=src, line=n, field="total_kg")
    return dict(designation=toks[0], manufacturer=" ".join(toks[6:]),
                delays=parse_delays(toks[3], source=src, line=n),
                diameter=dia / 1000.0, length=length / 1000.0,
                propellant_mass=mp, dry_mass=mt - mp)


def _name_from_file(src: Path) -> str:
    return common_name(src.stem) or src.stem


def _require(src, line, overrides, needed, what):
    missing = [k for k in needed if k not in overrides]
    if missing:
        raise InputError(f"{what}; pass {', '.join(f'{k}=...' for k in missing)} "
                         f"(SI units) to read it", source=src, line=line, field="header")


def _headerless_fields(src, overrides) -> dict:
    _require(src, 1, overrides, ("propellant_mass", "dry_mass", "diameter", "length"),
             "no motor header line (data starts on the first line), so propellant and "
             "dry mass, diameter and length are unknown")
    return dict(designation=_name_from_file(src))


def _three_number_fields(src, n, toks, t, F, overrides) -> dict:
    isp, mp, mt = (float(x) for x in toks)
    tt, FF = (np.r_[0.0, t], np.r_[0.0, F]) if t[0] > 0 else (t, F)
    impulse = float(np.sum(np.diff(tt) * (FF[1:] + FF[:-1]) / 2.0))
    implied = impulse / (mp * G0) if mp > 0 else math.nan
    reading = (f"non-standard header '{' '.join(toks)}' read as specific impulse {isp:g} s, "
               f"propellant {mp:g} kg, total mass {mt:g} kg")
    if not (0 < mp < mt) or not (abs(implied - isp) <= 0.10 * isp):
        raise InputError(f"{reading}, but that does not fit the curve (impulse {impulse:.0f} N s "
                         f"gives a specific impulse of {implied:.0f} s); expected the standard "
                         f"header '{' '.join(_HEADER_FIELDS)}'", source=src, line=n,
                         field="header")
    _require(src, n, overrides, ("diameter", "length"),
             f"{reading} (curve check: {implied:.0f} s); it has no diameter or length")
    return dict(designation=_name_from_file(src), propellant_mass=mp, dry_mass=mt - mp)


def write_eng(motor: SolidMotor, path: str | PathLike) -> None:
    """Write ``motor`` as a one-motor RASP ``.eng`` file. Numeric-only."""
    delays = "-".join("P" if math.isinf(d) else f"{d:g}" for d in motor.delays) or "0"
    lines = [f"; written by ironbark-opt from {motor.source or 'memory'}",
             f"{motor.designation or 'motor'} {motor.diameter * 1000:g} {motor.length * 1000:g} "
             f"{delays} {motor.propellant_mass_initial:.6g} {motor.total_mass:.6g} "
             f"{motor.manufacturer or 'unknown'}"]
    lines += [f"{ti:.6g} {fi:.6g}" for ti, fi in zip(motor.time, np.asarray(motor.thrust))]
    Path(path).write_text("\n".join(lines) + "\n", encoding="utf-8")
