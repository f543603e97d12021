"""The ``Atmosphere`` interface, gas constants and the one wind-convention helper.

Every atmosphere model (ISA 1976, a tabulated ``Profile`` from a forecast or a
sounding) answers the same symbolic-safe questions at a geometric altitude
``h`` [m above mean sea level]:

- ``temperature(h, dT=0)`` [K], ``pressure(h)`` [Pa],
- ``density(h, dT=0)`` [kg/m^3], ``speed_of_sound(h, dT=0)`` [m/s],
- ``dynamic_viscosity(h, dT=0)`` [Pa s] (Sutherland's law),
- ``wind_l(h) -> (east, north)`` [m/s], the wind vector in the local-level
  frame (the direction the air moves *towards*),
- ``describe() -> dict`` (source, run time, valid time, ...).

``dT`` is a temperature offset [K] applied **at constant pressure**: it changes
temperature, density, speed of sound and viscosity but not ``pressure(h)``.
It is a dispersion parameter (a CasADi symbol in Monte Carlo / sensitivity
runs).  A *site* temperature offset that is hydrostatically consistent (warm
air also changes the pressure lapse) is a constructor argument of the model
instead (``ISA(temperature_offset=...)``).

Wind convention (the only place conversions live)
-------------------------------------------------
Meteorological wind direction is the direction the wind blows **from**,
measured clockwise from true north: a wind from 270 deg (a westerly) blows
towards the east.  With speed ``V`` and direction-from ``psi`` [rad]::

    east  = -V sin(psi)
    north = -V cos(psi)

and back: ``V = hypot(east, north)``, ``psi = atan2(-east, -north)`` wrapped
to [0, 2 pi).  Use :func:`wind_from_speed_direction` and
:func:`wind_to_speed_direction`; never re-derive the signs elsewhere.
"""
from __future__ import annotations

import abc

import numpy as np

from ironbark_opt import _math as m

# U.S. Standard Atmosphere 1976 (NOAA-S/T 76-1562), Table 2 / section 1.2:
# universal gas constant R* = 8.31432e3 J/(kmol K) and sea-level mean molecular
# weight M0 = 28.9644 kg/kmol; the specific gas constant is their ratio.
R_STAR = 8.31432e3           # [J/(kmol K)]
M0 = 28.9644                 # [kg/kmol]
R_AIR = R_STAR / M0          # [J/(kg K)] = 287.0528...
GAMMA_AIR = 1.40             # [-] ratio of specific heats, 1976 standard eq. 50
# Sutherland's law constants, 1976 standard eq. 51: beta [kg/(s m K^0.5)], S [K].
SUTHERLAND_BETA = 1.458e-6
SUTHERLAND_S = 110.4


def sutherland_viscosity(temperature):
    """Dynamic viscosity of air by Sutherland's law [Pa s]; symbolic-safe.

    mu = beta T^1.5 / (T + S), U.S. Standard Atmosphere 1976, eq. 51.

    Parameters
    ----------
    temperature : float, array, SX or MX [K]
    """
    t = temperature
    return SUTHERLAND_BETA * t * m.sqrt(t) / (t + SUTHERLAND_S)


def wind_from_speed_direction(speed, direction_from):
    """(east, north) wind components [m/s] from speed and direction-from; symbolic-safe.

    Parameters
    ----------
    speed : float, array, SX or MX [m/s]
    direction_from : float, array, SX or MX [rad]
        Meteorological direction the wind blows from, clockwise from north.
    """
    return -speed * m.sin(direction_from), -speed * m.cos(direction_from)


def wind_to_speed_direction(east, north):
    """(speed [m/s], direction-from [rad] in [0, 2 pi)) from wind components; numeric-only.

    Parameters
    ----------
    east, north : float or array [m/s]
        Components of the direction the air moves towards.
    """
    east = np.asarray(east, dtype=float)
    north = np.asarray(north, dtype=float)
    speed = np.hypot(east, north)
    direction = np.mod(np.arctan2(-east, -north), 2.0 * np.pi)
    return speed, direction


def constant_like(h, value: float):
    """``value`` broadcast to the shape and kind of ``h``; symbolic-safe.

    Parameters
    ----------
    h : float, array, SX, MX or DM [any unit]
    value : float [unit of the result]

    Floats give a float, NumPy arrays an array of the same shape, CasADi
    SX/MX/DM a matrix of the same kind and shape.
    """
    if m.is_symbolic(h):
        return 0.0 * h + value
    if isinstance(h, np.ndarray):
        return np.full(h.shape, float(value))
    return float(value)


class Atmosphere(abc.ABC):
    """Abstract atmosphere: state of the air vs geometric altitude.

    Subclasses implement :meth:`_temperature` (the model temperature without
    the dispersion offset), :meth:`pressure`, :meth:`wind_l` and
    :meth:`describe`, and may override :meth:`_thermo` / :meth:`_thermo_wind`
    to share one table or layer lookup; density, speed of sound and viscosity
    follow from the ideal gas law and Sutherland's law here, once.
    :meth:`state` returns everything from one lookup -- inside a CasADi step it
    is 3-5x cheaper than calling the single-property methods one by one.
    All altitudes ``h`` are geometric [m above mean sea level].
    """

    @abc.abstractmethod
    def _temperature(self, h):
        """Model temperature [K] at ``h`` [m], without ``dT``; symbolic-safe."""

    @abc.abstractmethod
    def pressure(self, h):
        """Static pressure [Pa] at geometric altitude ``h`` [m]; symbolic-safe."""

    @abc.abstractmethod
    def wind_l(self, h):
        """Wind (east, north) [m/s] in the local-level frame at ``h`` [m]; symbolic-safe."""

    @abc.abstractmethod
    def describe(self) -> dict:
        """Where the data came from: ``{"model", "source", "run_time", "valid_time", ...}``."""

    def _thermo(self, h):
        """(temperature [K] without dT, pressure [Pa]); subclasses share one lookup."""
        return self._temperature(h), self.pressure(h)

    def _thermo_wind(self, h):
        """(temperature [K] without dT, pressure [Pa], wind east, north [m/s])."""
        return (*self._thermo(h), *self.wind_l(h))

    def state(self, h, dT=0.0) -> dict:
        """All air properties at ``h`` from one table/layer lookup; symbolic-safe.

        The cheap way to get several properties inside a CasADi step (each
        single-property method does its own lookup).

        Parameters
        ----------
        h : float, array, SX or MX [m]
            Geometric altitude above mean sea level.
        dT : float, array, SX or MX [K]
            Temperature offset at constant pressure.

        Returns
        -------
        dict with ``temperature`` [K], ``pressure`` [Pa], ``density``
        [kg/m^3], ``speed_of_sound`` [m/s], ``dynamic_viscosity`` [Pa s],
        ``wind_east``, ``wind_north`` [m/s].
        """
        t_model, p, east, north = self._thermo_wind(h)
        t = t_model + dT
        return {
            "temperature": t,
            "pressure": p,
            "density": p / (R_AIR * t),
            "speed_of_sound": m.sqrt(GAMMA_AIR * R_AIR * t),
            "dynamic_viscosity": sutherland_viscosity(t),
            "wind_east": east,
            "wind_north": north,
        }

    def temperature(self, h, dT=0.0):
        """Static temperature [K]; symbolic-safe.

        Parameters
        ----------
        h : float, array, SX or MX [m]
            Geometric altitude above mean sea level.
        dT : float, array, SX or MX [K]
            Temperature offset at constant pressure (dispersion parameter).
        """
        return self._temperature(h) + dT

    def density(self, h, dT=0.0):
        """Air density [kg/m^3] from the ideal gas law rho = p / (R T); symbolic-safe.

        Parameters
        ----------
        h : float, array, SX or MX [m]
        dT : float, array, SX or MX [K]
            Temperature offset at constant pressure.
        """
        t_model, p = self._thermo(h)
        return p / (R_AIR * (t_model + dT))

    def speed_of_sound(self, h, dT=0.0):
        """Speed of sound [m/s], a = sqrt(gamma R T) (1976 standard eq. 50); symbolic-safe.

        Parameters
        ----------
        h : float, array, SX or MX [m]
        dT : float, array, SX or MX [K]
        """
        return m.sqrt(GAMMA_AIR * R_AIR * self.temperature(h, dT))

    def dynamic_viscosity(self, h, dT=0.0):
        """Dynamic viscosity [Pa s] by Sutherland's law (1976 standard eq. 51); symbolic-safe.

        Parameters
        ----------
        h : float, array, SX or MX [m]
        dT : float, array, SX or MX [K]
        """
        return sutherland_viscosity(self.temperature(h, dT))

    def __repr__(self) -> str:
        d = self.describe()
        return f"{type(self).__name__}({d.get('source', '')!r})"
