"""Apogee targets as users write them: ``30000ft``, ``3048 m``, ``10000 ft ASL``."""
from __future__ import annotations

import re
from dataclasses import dataclass

from ironbark_opt.errors import InputError

FT = 0.3048  # [m] international foot

_PATTERN = re.compile(r"^\s*([0-9]*\.?[0-9]+(?:[eE][-+]?[0-9]+)?)\s*(m|ft|feet|foot|km)?\s*(agl|asl)?\s*$",
                      re.IGNORECASE)


@dataclass(frozen=True)
class Target:
    """An apogee target.

    Parameters
    ----------
    altitude : float [m]
        Target height in metres.
    reference : {'agl', 'asl'}
        Above ground level (the launch site) or above mean sea level.
    text : str
        What the user wrote (for reports).
    """

    altitude: float
    reference: str = "agl"
    text: str = ""

    def agl(self, site_elevation: float) -> float:
        """The target above ground [m] for a site at ``site_elevation`` [m ASL]."""
        return self.altitude - site_elevation if self.reference == "asl" else self.altitude


def parse_target(text) -> Target:
    """Parse ``"30000ft"``, ``"3000 m"``, ``"3 km"``, ``"10000ft ASL"`` or a number [m AGL]."""
    if isinstance(text, Target):
        return text
    if isinstance(text, (int, float)):
        return Target(float(text), "agl", f"{text} m")
    match = _PATTERN.match(str(text))
    if not match:
        raise InputError(f"cannot read the target {text!r}: expected a number with a unit, e.g. '30000ft', "
                         "'3000m', '10000 ft ASL'", field="target")
    value, unit, ref = match.groups()
    scale = {"ft": FT, "feet": FT, "foot": FT, "km": 1000.0}.get((unit or "m").lower(), 1.0)
    altitude = float(value) * scale
    if altitude <= 0:
        raise InputError(f"target must be positive, got {text!r}", field="target")
    return Target(altitude, (ref or "agl").lower(), str(text))
