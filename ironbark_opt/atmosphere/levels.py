"""Pressure-level columns -> a tabulated profile above the launch site.

Forecasts (RAP, GFS), reanalyses (ERA5) and radiosonde soundings all give
temperature, wind and height on pressure levels.  This module converts them
once into :class:`ProfileColumns` — geometric altitude above sea level [m],
temperature [K], pressure [Pa], east/north wind [m/s], sorted upwards,
starting at the site's ground — and from there into the package's
``Profile`` atmosphere.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field
from datetime import datetime

import numpy as np

from ironbark_opt.atmosphere.base import wind_to_speed_direction
from ironbark_opt.atmosphere.isa import geometric_altitude
from ironbark_opt.errors import InputError

#: Standard gravity [m/s^2] that defines geopotential metres
#: (WMO; U.S. Standard Atmosphere 1976, Table 2).
G0 = 9.80665
#: Specific gas constant of dry air [J/(kg K)] (U.S. Standard Atmosphere 1976,
#: R* / M0 = 8314.32 / 28.9644).
R_AIR = 287.05287


def geometric_height(geopotential_height, latitude=None):
    """Geometric height above sea level [m] from geopotential height [m'].

    Symbolic-safe in ``geopotential_height`` (plain arithmetic); ``latitude``
    must be a number.

    Parameters
    ----------
    geopotential_height : float, array or CasADi [m] (geopotential metres)
    latitude : float [rad], optional
        With a latitude, the latitude-dependent form of List (1968),
        Smithsonian Meteorological Tables, 6th ed., Table 51, as written by
        Mahoney, "A discussion of various measures of altitude" (2008):
        ``z = R(phi) H / (g(phi)/g0 R(phi) - H)``, with normal gravity
        ``g(phi) = 9.780356 (1 + 0.0052885 sin^2 phi - 0.0000059 sin^2 2phi)``
        and ``R(phi) = 6378.137 km / sqrt(1.006803 - 0.006706 sin^2 phi)``.
        Without, the U.S. Standard Atmosphere 1976 inverse of its eq. 18,
        ``z = r0 H / (r0 - H)`` with r0 = 6356.766 km.
    """
    H = geopotential_height
    if latitude is None:
        return geometric_altitude(H)
    s = math.sin(latitude)
    g_phi = 9.780356 * (1.0 + 0.0052885 * s * s - 0.0000059 * math.sin(2.0 * latitude) ** 2)
    r_phi = 6378137.0 / math.sqrt(1.006803 - 0.006706 * s * s)
    return r_phi * H / (g_phi / G0 * r_phi - H)


@dataclass(frozen=True)
class ProfileColumns:
    """A tabulated atmosphere over one site, sorted by altitude, from the ground up.

    Attributes: ``altitude`` [m, geometric above sea level], ``temperature``
    [K], ``pressure`` [Pa], ``wind_east``/``wind_north`` [m/s] (wind blowing
    towards east/north), ``source`` (what and where it came from),
    ``valid_time`` and ``run_time`` (UTC datetimes or None), ``latitude``/
    ``longitude`` [rad] of the data point, ``ground_elevation`` [m].
    """
    altitude: np.ndarray
    temperature: np.ndarray
    pressure: np.ndarray
    wind_east: np.ndarray
    wind_north: np.ndarray
    source: str
    valid_time: datetime | None = None
    run_time: datetime | None = None
    latitude: float | None = None
    longitude: float | None = None
    ground_elevation: float | None = None
    notes: tuple = field(default_factory=tuple)

    def __repr__(self) -> str:
        return (f"ProfileColumns({self.source!r}, {len(self.altitude)} levels, "
                f"{self.altitude[0]:.0f}-{self.altitude[-1]:.0f} m, valid {self.valid_time})")

    def to_profile(self):
        """The package's tabulated ``Profile`` atmosphere (ISA above the top)."""
        from ironbark_opt.atmosphere.profile import Profile
        return Profile(self.altitude, self.temperature, self.pressure, self.wind_east,
                       self.wind_north, source=self.source, valid_time=self.valid_time,
                       run_time=self.run_time,
                       latitude_deg=None if self.latitude is None else math.degrees(self.latitude),
                       longitude_deg=None if self.longitude is None else math.degrees(self.longitude),
                       metadata={"ground_elevation_m": self.ground_elevation,
                                 "notes": list(self.notes)})

    def to_dataframe(self):
        """pandas DataFrame with unit-suffixed columns, one row per level."""
        import pandas as pd
        speed, direction = wind_to_speed_direction(self.wind_east, self.wind_north)
        return pd.DataFrame({
            "altitude_m": self.altitude,
            "altitude_agl_m": self.altitude - self.altitude[0],
            "pressure_Pa": self.pressure, "temperature_K": self.temperature,
            "wind_east_mps": self.wind_east, "wind_north_mps": self.wind_north,
            "wind_speed_mps": speed, "wind_direction_deg": np.degrees(direction)})

    def to_dict(self) -> dict:
        """JSON-friendly dict (unit-suffixed keys, lists per column)."""
        def iso(t):
            return None if t is None else t.strftime("%Y-%m-%dT%H:%M:%SZ")
        d = {"source": self.source, "valid_time": iso(self.valid_time),
             "run_time": iso(self.run_time),
             "latitude_deg": None if self.latitude is None else math.degrees(self.latitude),
             "longitude_deg": None if self.longitude is None else math.degrees(self.longitude),
             "ground_elevation_m": self.ground_elevation, "notes": list(self.notes)}
        d["levels"] = {k: v.tolist() for k, v in self.to_dataframe().items()}
        return d


def build_columns(pressure, height, temperature, wind_east, wind_north, *, source: str,
                  ground_elevation: float | None = None, valid_time=None, run_time=None,
                  latitude=None, longitude=None, notes=()) -> ProfileColumns:
    """Sort, clean and cut pressure-level data at the ground.  Numeric-only.

    Parameters
    ----------
    pressure : array [Pa]
    height : array [m]
        Geometric height above sea level of each level (convert geopotential
        height with :func:`geometric_height` first).
    temperature : array [K]
    wind_east, wind_north : array [m/s]
    source : str
        Names the data source in messages and in the profile.
    ground_elevation : float [m], optional
        Site ground.  Levels below it (filled in by the model's extrapolation
        under the terrain) are dropped and a level at the ground is
        interpolated: temperature and wind linear in altitude, pressure
        linear in log-pressure.  If every level is above the ground, the
        ground level is extrapolated from the lowest one hydrostatically with
        a 6.5 K/km lapse rate (U.S. Standard Atmosphere 1976 troposphere) and
        the lowest level's wind.  None keeps all levels.

    Raises
    ------
    InputError
        Unequal lengths, non-finite data only, fewer than two levels above
        the ground, or non-physical values (T outside 150..350 K, p <= 0).
    """
    cols = [np.asarray(a, dtype=float).ravel()
            for a in (pressure, height, temperature, wind_east, wind_north)]
    if len({c.size for c in cols}) != 1:
        raise InputError("pressure, height, temperature and wind columns differ in length "
                         f"({[c.size for c in cols]})", source=source)
    ok = np.all(np.isfinite(np.vstack(cols)), axis=0)
    p, z, T, u, v = (c[ok] for c in cols)
    order = np.argsort(z, kind="stable")
    p, z, T, u, v = (c[order] for c in (p, z, T, u, v))
    if p.size and (np.any(p <= 0) or np.any(T < 150) or np.any(T > 350)):
        raise InputError("non-physical values (pressure <= 0 or temperature outside "
                         "150-350 K): check the units of the input", source=source)
    keep = np.concatenate(([True], np.diff(z) > 0)) if z.size else np.zeros(0, bool)
    p, z, T, u, v = (c[keep] for c in (p, z, T, u, v))
    if ground_elevation is not None and z.size:
        zg = float(ground_elevation)
        above = z > zg + 1e-6
        if not above.all() and above.any():
            i = int(np.argmax(above))          # first level above the ground
            w = (zg - z[i - 1]) / (z[i] - z[i - 1])
            pg = math.exp((1 - w) * math.log(p[i - 1]) + w * math.log(p[i]))
            g = [(1 - w) * c[i - 1] + w * c[i] for c in (T, u, v)]
        elif above.all():
            dz = z[0] - zg
            Tg = T[0] + 0.0065 * dz
            # Hydrostatic equation with a constant lapse rate (U.S. Standard
            # Atmosphere 1976, eq. 33a): p = p0 (T0 / T)^(g0 / (R L)).
            pg = p[0] * (Tg / T[0]) ** (G0 / (R_AIR * 0.0065))
            g = [Tg, u[0], v[0]]
            notes = tuple(notes) + (f"ground level extrapolated {dz:.0f} m below the lowest level",)
        else:
            raise InputError(f"every level lies below the ground elevation {zg:.0f} m",
                             source=source)
        p = np.concatenate(([pg], p[above]))
        z = np.concatenate(([zg], z[above]))
        T, u, v = (np.concatenate(([gv], c[above])) for gv, c in zip(g, (T, u, v)))
    if z.size < 2:
        raise InputError(f"fewer than two valid levels above the ground ({z.size})",
                         source=source)
    return ProfileColumns(z, T, p, u, v, source, valid_time, run_time, latitude, longitude,
                          ground_elevation if ground_elevation is not None else float(z[0]),
                          tuple(notes))
