"""Argument checks shared by constructors and model builders (numeric-only)."""
from __future__ import annotations

import math

from ironbark_opt.errors import InputError


def number(value, field: str, unit: str = "") -> float:
    """``value`` as a finite float, or InputError naming ``field``."""
    if isinstance(value, bool):
        raise InputError(f"expected a number, got {value!r}", field=field)
    try:
        out = float(value)
    except (TypeError, ValueError):
        raise InputError(f"expected a number, got {value!r}", field=field) from None
    if not math.isfinite(out):
        raise InputError(f"expected a finite number, got {value!r}", field=field)
    return out


def positive(value, field: str, unit: str = "m") -> float:
    out = number(value, field)
    if out <= 0.0:
        raise InputError(f"must be > 0 {unit}, got {out}", field=field)
    return out


def nonnegative(value, field: str, unit: str = "m") -> float:
    out = number(value, field)
    if out < 0.0:
        raise InputError(f"must be >= 0 {unit}, got {out}", field=field)
    return out


def optional(check, value, field: str, unit: str = "m"):
    """``None`` passes through; anything else goes through ``check``."""
    return None if value is None else check(value, field, unit)


def set_fields(obj, **values) -> None:
    """Store validated values on a frozen dataclass instance."""
    for key, val in values.items():
        object.__setattr__(obj, key, val)


def is_float(text: str) -> bool:
    """True when ``text`` parses as a float (table/CSV sniffing)."""
    try:
        float(text)
        return True
    except ValueError:
        return False
