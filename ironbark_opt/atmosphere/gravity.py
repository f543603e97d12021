"""Gravitational acceleration vs altitude (and latitude).

Two models, chosen by whether a latitude is known:

- ``latitude`` given: WGS-84 normal gravity.  Somigliana's closed formula on
  the ellipsoid (NIMA TR8350.2, 3rd ed., 2000, eq. 4-1) with the second-order
  free-air correction for height above the ellipsoid (TR8350.2 eq. 4-3).
  The height correction is accurate to ~1e-6 m/s^2 below 20 km; ``h`` is
  used as the height above the ellipsoid (the geoid undulation, < 110 m, is
  ignored: 3e-4 m/s^2 at most, and it is a constant shift of altitude).
- ``latitude=None``: the U.S. Standard Atmosphere 1976 gravity,
  ``g = g0 (r0 / (r0 + Z))^2`` with g0 = 9.80665 m/s^2, r0 = 6 356 766 m
  (1976 standard eq. 17) -- the gravity the ISA pressure profile is built
  on, for runs that do not know where they are.

Both are symbolic-safe in ``h`` and ``latitude``.  ``gravity`` is the
magnitude of normal gravity (gravitation plus centrifugal), directed along
the local vertical; the dynamics applies it as ``-g`` along local-level up.
"""
from __future__ import annotations

import math

from ironbark_opt import _math as m

# WGS-84 defining and derived constants, NIMA TR8350.2 Tables 3.1 and 3.3.
WGS84_A = 6378137.0                       # semi-major axis [m]
WGS84_F = 1.0 / 298.257223563             # flattening [-]
WGS84_GM = 3.986004418e14                 # [m^3/s^2]
WGS84_OMEGA = 7.292115e-5                 # Earth rotation rate [rad/s]
WGS84_B = WGS84_A * (1.0 - WGS84_F)       # semi-minor axis [m]
WGS84_E2 = WGS84_F * (2.0 - WGS84_F)      # first eccentricity squared [-]
# TR8350.2 Table 3.4: normal gravity at the equator and at the poles [m/s^2].
GAMMA_EQUATOR = 9.7803253359
GAMMA_POLE = 9.8321849378
# Somigliana's constant k = b gamma_p / (a gamma_e) - 1 (TR8350.2 eq. 4-1).
SOMIGLIANA_K = WGS84_B * GAMMA_POLE / (WGS84_A * GAMMA_EQUATOR) - 1.0
# m = omega^2 a^2 b / GM (TR8350.2 Table 3.4, 0.00344978650684).
WGS84_M = WGS84_OMEGA ** 2 * WGS84_A ** 2 * WGS84_B / WGS84_GM

# U.S. Standard Atmosphere 1976, eq. 17 and Table 2.
STANDARD_GRAVITY = 9.80665                # [m/s^2]
R0_1976 = 6356766.0                       # [m]

LATITUDE_45 = math.radians(45.0)


def normal_gravity_ellipsoid(latitude):
    """WGS-84 normal gravity on the ellipsoid [m/s^2]; symbolic-safe.

    Somigliana: gamma = gamma_e (1 + k sin^2 phi) / sqrt(1 - e^2 sin^2 phi),
    NIMA TR8350.2 eq. 4-1.

    Parameters
    ----------
    latitude : float, array, SX or MX [rad]
        Geodetic latitude.
    """
    s2 = m.sin(latitude) ** 2
    return GAMMA_EQUATOR * (1.0 + SOMIGLIANA_K * s2) / m.sqrt(1.0 - WGS84_E2 * s2)


def gravity(h, latitude=None):
    """Gravitational acceleration [m/s^2] at altitude ``h``; symbolic-safe.

    Parameters
    ----------
    h : float, array, SX or MX [m]
        Geometric altitude above mean sea level (taken as the height above
        the WGS-84 ellipsoid when ``latitude`` is given).
    latitude : float, array, SX, MX or None [rad]
        Geodetic latitude.  None selects the 1976 standard-atmosphere gravity
        ``9.80665 (r0 / (r0 + h))^2`` (eq. 17), consistent with ``ISA``.

    Returns
    -------
    Same kind as the inputs [m/s^2].
    """
    if latitude is None:
        # U.S. Standard Atmosphere 1976, eq. 17 (inverse-square law, r0 = 6 356 766 m).
        ratio = R0_1976 / (R0_1976 + h)
        return STANDARD_GRAVITY * ratio * ratio
    gamma = normal_gravity_ellipsoid(latitude)
    s2 = m.sin(latitude) ** 2
    # NIMA TR8350.2 eq. 4-3, second-order free-air (normal gravity) correction.
    first = 2.0 / WGS84_A * (1.0 + WGS84_F + WGS84_M - 2.0 * WGS84_F * s2)
    return gamma * (1.0 - first * h + 3.0 / WGS84_A ** 2 * h * h)


class ConstantGravity:
    """A gravity model that is one constant [m/s^2] at every height.

    What RocketPy flies by default (``Environment(gravity=9.80665)``, or the
    9.81 its example notebooks give); used when a rocket file sets
    ``[launch] gravity``, so a comparison with such a flight flies the same
    physics.  Picklable (executors ship setups to other processes).
    """

    def __init__(self, value: float):
        self.value = float(value)

    def __call__(self, h):
        from ironbark_opt.atmosphere.base import constant_like
        return constant_like(h, self.value)

    def __repr__(self) -> str:
        return f"ConstantGravity({self.value:g} m/s^2)"
