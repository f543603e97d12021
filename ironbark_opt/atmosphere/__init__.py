"""Atmosphere models: ISA 1976, tabulated profiles, gravity.

- :mod:`.base` -- the ``Atmosphere`` interface, gas constants, Sutherland's
  law and the wind-direction convention (the one place it is converted).
- :mod:`.isa` -- ``ISA``: U.S. Standard Atmosphere 1976 with site offsets.
- :mod:`.profile` -- ``Profile``: a tabulated atmosphere from any source
  (forecast, sounding, another model), NumPy and CasADi evaluation.
- :mod:`.gravity` -- ``gravity(h, latitude)``: WGS-84 normal gravity.
"""
from ironbark_opt.atmosphere.base import (
    Atmosphere,
    sutherland_viscosity,
    wind_from_speed_direction,
    wind_to_speed_direction,
)
from ironbark_opt.atmosphere.gravity import gravity
from ironbark_opt.atmosphere.isa import ISA, geometric_altitude, geopotential_altitude
from ironbark_opt.atmosphere.profile import Profile

__all__ = [
    "Atmosphere", "ISA", "Profile", "gravity",
    "geometric_altitude", "geopotential_altitude", "sutherland_viscosity",
    "wind_from_speed_direction", "wind_to_speed_direction",
]
