"""Unit names found in log headers -> SI factors (numeric-only).

Factors from NIST SP 811 (2008), appendix B: ft = 0.3048 m exactly,
mi = 1609.344 m, standard gravity g = 9.80665 m/s^2.
"""
from __future__ import annotations

from ironbark_opt.errors import InputError

_G = 9.80665
FACTORS = {
    "time": {"s": 1.0, "ms": 1e-3, "ds": 0.1, "min": 60.0},
    "altitude": {"m": 1.0, "ft": 0.3048, "km": 1000.0, "mi": 1609.344},
    "vertical_speed": {"m/s": 1.0, "mps": 1.0, "ft/s": 0.3048, "fps": 0.3048, "km/h": 1 / 3.6,
                       "mph": 1609.344 / 3600.0},
    "acceleration": {"m/s²": 1.0, "m/s2": 1.0, "m/s^2": 1.0, "mps2": 1.0, "ft/s²": 0.3048, "ft/s2": 0.3048,
                     "ft/s^2": 0.3048, "g": _G, "g's": _G, "G": _G, "G's": _G},
}


def factor(channel: str, unit: str, *, source=None, line=None, field: str | None = None) -> float:
    """SI factor of ``unit`` for ``channel`` (InputError naming the known units otherwise)."""
    table = FACTORS[channel]
    u = unit.strip()
    if u in table:
        return table[u]
    low = {k.lower(): v for k, v in table.items()}
    if u.lower() in low:
        return low[u.lower()]
    raise InputError(f"unknown {channel} unit '{unit}'; known: {', '.join(table)}", source=source, line=line,
                     field=field or channel)
