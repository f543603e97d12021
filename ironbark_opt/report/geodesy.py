"""Local east/north offsets [m] to latitude/longitude on the WGS-84 ellipsoid (numeric-only).

A flight drifts a few kilometres, so the flat-Earth (local tangent plane)
map is exact to millimetres: an east/north offset is divided by the
ellipsoid's radii of curvature at the launch site,

    d(lat) = north / (M + h),   d(lon) = east / ((N + h) cos(lat)),

with the meridian radius ``M = a (1 - e^2) / (1 - e^2 sin^2 lat)^(3/2)`` and
the prime-vertical radius ``N = a / sqrt(1 - e^2 sin^2 lat)`` (Groves,
*Principles of GNSS, Inertial, and Multisensor Integrated Navigation
Systems*, 2nd ed., Artech House 2013, section 2.4: the radii of curvature
and the curvilinear-position rate equations; WGS-84 constants from NIMA
TR8350.2, 3rd ed., Table 3.1).  Heights above sea level stand in for
ellipsoidal heights: the geoid undulation (< 110 m) changes the scale by
< 2e-5.
"""
from __future__ import annotations

import math

import numpy as np

from ironbark_opt.errors import InputError

#: WGS-84 semi-major axis [m] and flattening (NIMA TR8350.2, Table 3.1)
WGS84_A = 6378137.0
WGS84_F = 1.0 / 298.257223563
WGS84_E2 = WGS84_F * (2.0 - WGS84_F)


def radii_of_curvature(latitude: float) -> tuple[float, float]:
    """(meridian M, prime vertical N) radii of curvature [m] at ``latitude`` [rad]."""
    s2 = math.sin(latitude) ** 2
    w = 1.0 - WGS84_E2 * s2
    return WGS84_A * (1.0 - WGS84_E2) / w ** 1.5, WGS84_A / math.sqrt(w)


def local_to_geodetic(east, north, latitude: float, longitude: float, height=0.0):
    """(latitude_deg, longitude_deg) arrays of points ``east``/``north`` [m] of
    the origin at ``latitude``/``longitude`` [rad]; ``height`` [m] (scalar or
    per point) above the ellipsoid."""
    m, n = radii_of_curvature(latitude)
    h = np.asarray(height, dtype=float)
    lat = latitude + np.asarray(north, dtype=float) / (m + h)
    lon = longitude + np.asarray(east, dtype=float) / ((n + h) * math.cos(latitude))
    return np.degrees(lat), (np.degrees(lon) + 180.0) % 360.0 - 180.0


def site_position(setup, option: str = "--kml") -> tuple[float, float]:
    """(latitude, longitude) [rad] of ``setup``'s launch site, or ``InputError``
    naming ``option`` when the rocket file does not give them."""
    lat, lon = getattr(setup, "latitude", None), getattr(setup, "longitude", None)
    if lat is None or lon is None:
        raise InputError("the launch site's position is unknown: give latitude_deg and longitude_deg in the "
                         "rocket file's [launch] table (or fly a --forecast --site preset)", field=option)
    return float(lat), float(lon)


def position_text(latitude: float, longitude: float, decimals: int = 5) -> str:
    """``"32.99025 N, 106.97500 W"`` of a position given in radians."""
    la, lo = math.degrees(latitude), (math.degrees(longitude) + 180.0) % 360.0 - 180.0
    return f"{abs(la):.{decimals}f} {'N' if la >= 0 else 'S'}, {abs(lo):.{decimals}f} {'E' if lo >= 0 else 'W'}"
