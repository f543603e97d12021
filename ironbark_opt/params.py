"""The one parameter registry: every quantity a user may vary, by name.

The flight model takes a single parameter vector ``p``.  This module names its
entries, their units and what they mean, so that sensitivities, Monte Carlo
dispersions and optimisation variables are all reported by name and the
dynamics never index ``p`` with a bare number.

Nominal values of some entries (rail length, launch angles, ballast position)
come from the case being flown; :func:`nominal_values` fills them in.
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import Mapping

import numpy as np

from ironbark_opt.errors import InputError


@dataclass(frozen=True)
class ParameterInfo:
    """One named entry of ``p``.

    Parameters
    ----------
    name : str
        Registry name (used in sensitivities, dispersions, the CLI).
    unit : str
        SI unit, ``"-"`` for dimensionless, ``"rad"`` for angles.
    default : float
        Value used when the case does not set one.
    description : str
        One line for tables and help texts.
    """

    name: str
    unit: str
    default: float
    description: str


PARAMETERS: tuple[ParameterInfo, ...] = (
    ParameterInfo("ballast_mass", "kg", 0.0, "ballast mass"),
    ParameterInfo("ballast_x", "m", 0.0, "ballast CG, aft of the nose tip"),
    ParameterInfo("dry_mass_offset", "kg", 0.0, "mass added to the dry rocket at its CG"),
    ParameterInfo("dry_cg_offset", "m", 0.0, "shift of the dry CG (aft positive)"),
    ParameterInfo("dry_inertia_scale", "-", 1.0, "factor on the dry inertia tensor"),
    ParameterInfo("thrust_scale", "-", 1.0, "factor on thrust (and total impulse)"),
    ParameterInfo("burn_time_scale", "-", 1.0, "factor on burn time at equal impulse"),
    ParameterInfo("drag_scale", "-", 1.0, "factor on the axial-force coefficient"),
    ParameterInfo("normal_force_scale", "-", 1.0, "factor on normal force and pitching moment"),
    ParameterInfo("wind_scale", "-", 1.0, "factor on the atmosphere profile's wind"),
    ParameterInfo("wind_east", "m/s", 0.0, "constant wind added toward east"),
    ParameterInfo("wind_north", "m/s", 0.0, "constant wind added toward north"),
    ParameterInfo("rail_length", "m", 5.2, "launch rail length"),
    ParameterInfo("inclination", "rad", np.deg2rad(85.0), "rail angle above horizontal"),
    ParameterInfo("heading", "rad", 0.0, "rail heading, clockwise from north"),
    ParameterInfo("temperature_offset", "K", 0.0, "air temperature offset at constant pressure"),
    ParameterInfo("airbrake_level", "-", 0.0, "air-brake deployment once open (0 stowed, 1 open)"),
    ParameterInfo("airbrake_start_time", "s", 0.0, "air brakes start opening (time trigger), after ignition"),
)

NAMES: tuple[str, ...] = tuple(info.name for info in PARAMETERS)
INDEX: Mapping[str, int] = {name: i for i, name in enumerate(NAMES)}
INFO: Mapping[str, ParameterInfo] = {info.name: info for info in PARAMETERS}
SIZE = len(PARAMETERS)


def index(name: str) -> int:
    """Position of ``name`` in ``p``; InputError listing the names otherwise."""
    try:
        return INDEX[name]
    except KeyError:
        raise InputError(f"unknown parameter '{name}'; known parameters: {', '.join(NAMES)}",
                         field=name) from None


def unpack(p) -> dict:
    """Split ``p`` (NumPy vector or CasADi column) into a dict by name."""
    return {name: p[i] for i, name in enumerate(NAMES)}


def nominal_values(overrides: Mapping[str, float] | None = None) -> np.ndarray:
    """Vector of defaults with ``overrides`` (name -> value, SI) applied [mixed units]."""
    p = np.array([info.default for info in PARAMETERS], dtype=float)
    for name, value in (overrides or {}).items():
        try:
            p[index(name)] = float(value)
        except (TypeError, ValueError):
            raise InputError(f"expected a number, got {value!r}", field=name) from None
    return p


def to_dict(p) -> dict[str, float]:
    """Numeric ``p`` as a plain dict name -> float."""
    values = np.asarray(p, dtype=float).ravel()
    if values.size != SIZE:
        raise InputError(f"parameter vector has {values.size} entries, expected {SIZE}")
    return {name: float(values[i]) for i, name in enumerate(NAMES)}
