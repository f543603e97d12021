"""Launch-site presets: position and ground elevation of well-known fields.

Built-in presets can be extended or overridden by ``[sites.NAME]`` tables in
the user config file (see :mod:`ironbark_opt.config`).  Numeric-only.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

from ironbark_opt import config
from ironbark_opt.errors import InputError


@dataclass(frozen=True)
class Site:
    """A launch site.

    Parameters
    ----------
    name : str
        Preset key (lower case, no spaces).
    latitude : float [rad]
        Geodetic latitude, north positive.
    longitude : float [rad]
        Longitude, east positive, in (-pi, pi].
    elevation : float [m]
        Ground elevation above mean sea level.
    description : str
    """
    name: str
    latitude: float
    longitude: float
    elevation: float
    description: str = ""

    @property
    def latitude_deg(self) -> float:
        """Latitude [deg]."""
        return math.degrees(self.latitude)

    @property
    def longitude_deg(self) -> float:
        """Longitude [deg], east positive."""
        return math.degrees(self.longitude)

    def to_dict(self) -> dict:
        """JSON-friendly dict with unit-suffixed keys."""
        return {"name": self.name, "latitude_deg": self.latitude_deg,
                "longitude_deg": self.longitude_deg, "elevation_m": self.elevation,
                "description": self.description}


def _site(name, lat_deg, lon_deg, elev_m, description):
    return Site(name, math.radians(lat_deg), math.radians(lon_deg), float(elev_m), description)


# Spaceport America Cup: Spaceport America vertical launch area, New Mexico
# (position and elevation as used by the RocketPy Spaceport America example
# and the ESRA launch guide: 32.990254 N, 106.974998 W, 1400 m).
# EuRoC: Ponte de Sor, Portugal, and Bella Lui 2020: Kaltbrunn, Switzerland,
# as in the RocketPy flight examples (39.389700 N, 8.288964 W, 113 m;
# 47.213476 N, 9.003336 E, 407 m).
BUILTIN_SITES: dict[str, Site] = {s.name: s for s in (
    _site("spaceport_america", 32.990254, -106.974998, 1400.0,
          "Spaceport America Cup, Spaceport America, NM, USA"),
    _site("euroc", 39.389700, -8.288964, 113.0,
          "European Rocketry Challenge, Ponte de Sor, Portugal"),
    _site("kaltbrunn", 47.213476, 9.003336, 407.0, "Kaltbrunn, Switzerland (Bella Lui 2020)"),
)}
_ALIASES = {"sac": "spaceport_america", "spaceport": "spaceport_america",
            "spaceport_america_cup": "spaceport_america"}


def _from_config(name: str, table: dict, source) -> Site:
    values = {}
    for key, lo, hi in (("latitude_deg", -90, 90), ("longitude_deg", -180, 360),
                        ("elevation_m", -500, 9000)):
        if key not in table:
            raise InputError(f"missing {key}", source=source, field=f"sites.{name}.{key}")
        val = table[key]
        if isinstance(val, bool) or not isinstance(val, (int, float)) or not lo <= val <= hi:
            raise InputError(f"expected a number in [{lo}, {hi}], got {val!r}",
                             source=source, field=f"sites.{name}.{key}")
        values[key] = float(val)
    lon = values["longitude_deg"]
    lon = lon - 360.0 if lon > 180.0 else lon
    return _site(name, values["latitude_deg"], lon, values["elevation_m"],
                 str(table.get("description", "")))


def all_sites() -> dict[str, Site]:
    """Built-in presets updated with the user config file's ``[sites]``."""
    sites = dict(BUILTIN_SITES)
    for name, table in config.load().get("sites", {}).items():
        if not isinstance(table, dict):
            raise InputError("expected a table", source=config.config_path(), field=f"sites.{name}")
        sites[name.lower()] = _from_config(name.lower(), table, config.config_path())
    return sites


def get_site(name: str) -> Site:
    """The preset called ``name`` (case-insensitive; ``sac`` = Spaceport America).

    Raises
    ------
    InputError
        Unknown name; the message lists the known sites and how to add one.
    """
    key = name.strip().lower().replace(" ", "_").replace("-", "_")
    sites = all_sites()
    key = key if key in sites else _ALIASES.get(key, key)
    if key not in sites:
        raise InputError(
            f"unknown launch site {name!r}; known: {', '.join(sorted(sites))}. Add one as "
            f"[sites.{key}] with latitude_deg, longitude_deg, elevation_m in {config.config_path()}",
            field="site")
    return sites[key]
