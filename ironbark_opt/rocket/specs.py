"""Launch-ready vehicle specifications other packages consume (frozen dataclasses).

All values SI and radians; file paths are absolute (resolved relative to the
TOML file by the loader).
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field
from pathlib import Path

from ironbark_opt.errors import InputError
from ironbark_opt import validate as v
from ironbark_opt.rocket.materials import DEFAULT_ROUGHNESS

#: ``SolidMotor`` keyword names a motor override may set (docs/ARCHITECTURE.md)
MOTOR_OVERRIDE_KEYS = ("dry_mass", "dry_cg", "dry_inertia", "propellant_mass",
                       "propellant_cg", "nozzle_exit_area", "grains", "diameter", "length")
#: Overrides that stand in for a motor file's header line: with them a headerless
#: (RocketPy-style) or three-number-header thrust curve reads from a rocket file
MOTOR_HEADER_KEYS = ("propellant_mass", "dry_mass", "diameter", "length")
GRAIN_KEYS = ("count", "density", "outer_radius", "inner_radius", "height", "separation")


@dataclass(frozen=True)
class MotorSpec:
    """Which motor and where.

    Parameters
    ----------
    file : Path
        Thrust-curve file (.eng, .rse, .csv), absolute.
    designation : str or None
        Motor to pick when the file holds several.
    nozzle_x : float [m]
        Nozzle exit, aft of the nose tip.
    overrides : dict
        ``SolidMotor`` keywords in SI: dry_mass [kg], dry_cg [m fwd of nozzle
        exit], dry_inertia (I_transverse, I_axial) [kg m^2], propellant_mass
        [kg], propellant_cg [m fwd of nozzle exit], nozzle_exit_area [m^2],
        grains {count, density [kg/m^3], outer_radius, inner_radius, height,
        separation [m]}.
    airstart : tuple of (MotorSpec, float)
        Further motors of the same stage and their ignition times [s after
        launch] (air-start); flown with this one as a
        :class:`~ironbark_opt.motors.composite.CompositeMotor`.
    kind : {'solid', 'hybrid', 'liquid'}
        Hybrid and liquid motors take their propellant from ``tanks`` (and
        ``grain``), see :mod:`ironbark_opt.rocket.tank_spec`.
    ignition_time : float [s]
        Thrust-curve delay after the valves open (hybrid/liquid).
    tanks : tuple of Tank
    grain : dict or None
        Hybrid fuel grain: ``Grains`` keywords + ``position`` [m fwd of nozzle exit].
    ejection_delay : float or None [s]
        Ejection charge after burnout; recovery with ``deploy = "ejection"``
        opens then (None: the file's or ``.ork`` configuration's delay).
    """

    file: Path
    designation: str | None = None
    nozzle_x: float = 0.0
    overrides: dict = field(default_factory=dict)
    airstart: tuple = ()
    kind: str = "solid"
    ignition_time: float = 0.0
    tanks: tuple = ()
    grain: dict | None = None
    ejection_delay: float | None = None

    def __post_init__(self):
        object.__setattr__(self, "file", Path(self.file))
        object.__setattr__(self, "nozzle_x", v.nonnegative(self.nozzle_x, "nozzle_x"))
        unknown = set(self.overrides) - set(MOTOR_OVERRIDE_KEYS)
        if unknown:
            raise InputError(f"unknown motor override(s) {sorted(unknown)}; accepted: "
                             f"{', '.join(MOTOR_OVERRIDE_KEYS)}", field="overrides")

    def motor_cg_x(self, motor_cg):
        """Rocket-frame CG [m aft of nose tip] of a motor CG [m fwd of its nozzle exit]; symbolic-safe."""
        return self.nozzle_x - motor_cg


@dataclass(frozen=True)
class AeroSpec:
    """Aerodynamic inputs.

    Parameters
    ----------
    table : Path or None
        An AeroTable (CSV + JSON) replacing the built-in aero model.
    drag_power_off, drag_power_on : Path or None
        (Mach, Cd) curves on the rocket's reference area; power-on is used
        while the motor burns.
    drag_duplicates : {"error", "mean"}
        What a Mach number repeated in a drag curve with different values
        means: an error (default) or their average.
    surface_roughness : float [m]
        Equivalent sand-grain roughness (default regular paint, 60 um).
    re_transition : float [-]
        Laminar-turbulent transition Reynolds number (default 5e5).
    """

    table: Path | None = None
    drag_power_off: Path | None = None
    drag_power_on: Path | None = None
    drag_duplicates: str = "error"
    surface_roughness: float = DEFAULT_ROUGHNESS
    re_transition: float = 5e5

    def __post_init__(self):
        for name in ("table", "drag_power_off", "drag_power_on"):
            val = getattr(self, name)
            if val is not None:
                object.__setattr__(self, name, Path(val))
        if self.drag_duplicates not in ("error", "mean"):
            raise InputError(f"expected \"error\" or \"mean\", got {self.drag_duplicates!r}",
                             field="drag_duplicates")
        object.__setattr__(self, "surface_roughness",
                           v.nonnegative(self.surface_roughness, "surface_roughness"))
        object.__setattr__(self, "re_transition",
                           v.positive(self.re_transition, "re_transition", ""))


@dataclass(frozen=True)
class LaunchSpec:
    """Launch site and rail.

    Parameters
    ----------
    rail_length : float [m] (default 5.2, a 17 ft rail)
    inclination : float [rad] above horizontal (default 85 deg)
    heading : float [rad] clockwise from north (default 0)
    site_elevation : float [m] above sea level (default 0)
    latitude, longitude : float [rad] or None
    site_temperature : float [K] or None (None: standard atmosphere)
    site_pressure : float [Pa] or None
    wind_speed : float [m/s] (default 0)
    wind_from : float [rad] meteorological: direction the wind blows from,
        clockwise from north (default 0)
    atmosphere_file : Path or None
        A sounding, ERA5-style reanalysis netCDF or saved profile
        (:mod:`ironbark_opt.atmosphere.files`) flown instead of the ISA
        through the site values; the file's wind replaces ``wind_speed``.
    atmosphere_time : str or None
        ISO 8601 UTC launch time picking the record of a multi-time file.
    gravity : float [m/s^2] or None
        A constant gravitational acceleration (e.g. RocketPy's 9.80665) instead
        of WGS-84 normal gravity with latitude and height.
    """

    rail_length: float = 5.2
    inclination: float = math.radians(85.0)
    heading: float = 0.0
    site_elevation: float = 0.0
    latitude: float | None = None
    longitude: float | None = None
    site_temperature: float | None = None
    site_pressure: float | None = None
    wind_speed: float = 0.0
    wind_from: float = 0.0
    atmosphere_file: Path | None = None
    atmosphere_time: str | None = None
    gravity: float | None = None

    def __post_init__(self):
        s = object.__setattr__
        if self.gravity is not None:
            s(self, "gravity", v.positive(self.gravity, "gravity", "m/s^2"))
        s(self, "rail_length", v.positive(self.rail_length, "rail_length"))
        inc = v.number(self.inclination, "inclination")
        if not 0.0 < inc <= math.pi / 2:
            raise InputError(f"inclination must be in (0, 90] deg, got {math.degrees(inc):.6g}"
                             f" deg", field="inclination")
        s(self, "inclination", inc)
        s(self, "heading", v.number(self.heading, "heading") % (2 * math.pi))
        s(self, "site_elevation", v.number(self.site_elevation, "site_elevation"))
        if self.latitude is not None:
            lat = v.number(self.latitude, "latitude")
            if abs(lat) > math.pi / 2:
                raise InputError(f"latitude must be within +-90 deg, got {math.degrees(lat)}",
                                 field="latitude")
            s(self, "latitude", lat)
        if self.longitude is not None:
            lon = v.number(self.longitude, "longitude")
            if not -math.pi <= lon <= 2 * math.pi:
                raise InputError(f"longitude must be within -180..360 deg, got {math.degrees(lon)}",
                                 field="longitude")
            s(self, "longitude", lon)
        s(self, "site_temperature", v.optional(v.positive, self.site_temperature,
                                               "site_temperature", "K"))
        s(self, "site_pressure", v.optional(v.positive, self.site_pressure,
                                            "site_pressure", "Pa"))
        s(self, "wind_speed", v.nonnegative(self.wind_speed, "wind_speed", "m/s"))
        s(self, "wind_from", v.number(self.wind_from, "wind_from") % (2 * math.pi))


@dataclass(frozen=True)
class RecoverySpec:
    """A parachute or streamer.

    Parameters
    ----------
    name : str
    cd_area : float [m^2]
        Drag coefficient times reference area, Cd S.
    deploy : "apogee", "ejection" or float [m]
        Deploy at apogee, at the motor's ejection charge (burnout + the
        motor's ejection delay), or at this altitude above ground on the way down.
    lag : float [s]
        Delay from the trigger to full inflation (default 0).
    """

    name: str
    cd_area: float
    deploy: str | float = "apogee"
    lag: float = 0.0

    def __post_init__(self):
        object.__setattr__(self, "cd_area", v.positive(self.cd_area, "cd_area", "m^2"))
        if isinstance(self.deploy, str):
            if self.deploy not in ("apogee", "ejection"):
                raise InputError(f"deploy must be 'apogee', 'ejection' or an altitude above ground [m], "
                                 f"got {self.deploy!r}", field="deploy")
        else:
            object.__setattr__(self, "deploy", v.positive(self.deploy, "deploy"))
        object.__setattr__(self, "lag", v.nonnegative(self.lag, "lag", "s"))


@dataclass(frozen=True)
class BallastSpec:
    """Ballast (an optimisation variable): a point mass in a ballast bay.

    Parameters
    ----------
    mass : float [kg] (default 0)
    x : float [m] aft of the nose tip, or None (no position yet; default
        mid-bay when a bay is given)
    x_min, x_max : float [m] or None
        Ballast bay limits.
    mass_max : float [kg] or None
        Most ballast the bay holds.
    """

    mass: float = 0.0
    x: float | None = None
    x_min: float | None = None
    x_max: float | None = None
    mass_max: float | None = None

    def __post_init__(self):
        s = object.__setattr__
        s(self, "mass", v.nonnegative(self.mass, "mass", "kg"))
        s(self, "mass_max", v.optional(v.nonnegative, self.mass_max, "mass_max", "kg"))
        for name in ("x", "x_min", "x_max"):
            s(self, name, v.optional(v.nonnegative, getattr(self, name), name))
        if (self.x_min is None) != (self.x_max is None):
            raise InputError("give both x_min and x_max [m] of the ballast bay", field="x_max")
        if self.x_min is not None:
            if self.x_max < self.x_min:
                raise InputError(f"x_max ({self.x_max} m) is forward of x_min ({self.x_min} m)",
                                 field="x_max")
            if self.x is None:
                s(self, "x", 0.5 * (self.x_min + self.x_max))
            elif not self.x_min <= self.x <= self.x_max:
                raise InputError(f"x = {self.x} m is outside the bay [{self.x_min}, "
                                 f"{self.x_max}] m", field="x")
        if self.mass_max is not None and self.mass > self.mass_max:
            raise InputError(f"mass {self.mass} kg exceeds mass_max {self.mass_max} kg",
                             field="mass")
        if self.mass > 0.0 and self.x is None:
            raise InputError("ballast with mass needs a position x [m]", field="x")
