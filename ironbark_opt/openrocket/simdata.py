"""Simulations stored in an .ork file: launch conditions and flight data (numeric-only).

Units in ``<conditions>`` (OpenRocket ``OpenRocketSaver``): rod length [m];
``launchrodangle`` from vertical and ``launchroddirection`` (compass azimuth)
in **degrees**; ``winddirection`` in **radians** (direction the wind comes
from, clockwise from north); latitude/longitude [deg]; altitude [m];
``<atmosphere model="extendedisa">`` with ``basetemperature`` [K] and
``basepressure`` [Pa] at the launch site (OpenRocket ``ExtendedISAModel``
is built from the launch altitude, temperature and pressure).  Stored flight data (``<databranch types=...>``) is
looked up by column name, never position.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import pandas as pd

from ironbark_opt.errors import InputError
from ironbark_opt.openrocket.xmlread import Element
from ironbark_opt.rocket.specs import LaunchSpec
from ironbark_opt.validate import is_float

#: OpenRocket column name -> our unit-suffixed name (SI; OpenRocket stores SI)
COLUMNS = {
    "Time": "time_s", "Altitude": "altitude_m", "Altitude above sea level": "altitude_asl_m",
    "Vertical velocity": "vertical_velocity_mps", "Vertical acceleration": "vertical_acceleration_mps2",
    "Total velocity": "total_velocity_mps", "Total acceleration": "total_acceleration_mps2",
    "Position East of launch": "east_m", "Position North of launch": "north_m",
    "Lateral distance": "lateral_distance_m", "Lateral velocity": "lateral_velocity_mps",
    "Angle of attack": "angle_of_attack_rad", "Mass": "mass_kg", "Motor mass": "motor_mass_kg",
    "Longitudinal moment of inertia": "inertia_longitudinal_kgm2",
    "Rotational moment of inertia": "inertia_rotational_kgm2", "CP location": "cp_x_m",
    "CG location": "cg_x_m", "Stability margin calibers": "stability_margin_cal",
    "Mach number": "mach", "Reynolds number": "reynolds", "Thrust": "thrust_n",
    "Drag force": "drag_n", "Drag coefficient": "cd", "Axial drag coefficient": "ca",
    "Friction drag coefficient": "cd_friction", "Pressure drag coefficient": "cd_pressure",
    "Base drag coefficient": "cd_base", "Air temperature": "air_temperature_k",
    "Air pressure": "air_pressure_pa", "Air density": "air_density_kgpm3",
    "Speed of sound": "speed_of_sound_mps", "Wind velocity": "wind_speed_mps",
    "Gravitational acceleration": "gravity_mps2", "Reference length": "reference_length_m",
    "Reference area": "reference_area_m2", "Lateral direction": "lateral_direction_rad",
    "Lateral acceleration": "lateral_acceleration_mps2", "Latitude": "latitude_deg",
    "Longitude": "longitude_deg", "Roll rate": "roll_rate_radps", "Pitch rate": "pitch_rate_radps",
    "Yaw rate": "yaw_rate_radps", "Vertical orientation (zenith)": "zenith_rad",
    "Lateral orientation (azimuth)": "azimuth_rad", "Wind direction": "wind_direction_rad",
    "Normal force coefficient": "cn", "Pitch moment coefficient": "cm",
    "Simulation time step": "time_step_s", "Computation time": "computation_time_s",
    "Coriolis acceleration": "coriolis_acceleration_mps2", "Thrust-to-weight ratio": "thrust_to_weight",
}


def column_name(or_name: str) -> str:
    """Our column name for an OpenRocket data type (snake case when unknown)."""
    if or_name in COLUMNS:
        return COLUMNS[or_name]
    return "_".join(w for w in "".join(ch.lower() if ch.isalnum() else " "
                                       for ch in or_name).split())


@dataclass
class OrkSimulation:
    """One ``<simulation>``: name, configuration id, launch conditions, stored results.

    ``summary`` holds OpenRocket's ``<flightdata>`` attributes in SI with
    unit-suffixed keys (``apogee_m``, ``max_speed_mps``, ``max_acceleration_mps2``,
    ...); ``branches`` maps branch name -> DataFrame (columns: :data:`COLUMNS`).
    """

    name: str
    config_id: str
    launch: LaunchSpec
    launch_into_wind: bool
    summary: dict = field(default_factory=dict)
    branch_elements: dict = field(default_factory=dict, repr=False)
    #: OpenRocket's ``status`` when saved: "uptodate" (flown with the design as saved),
    #: "outdated" (the design changed since), "cantrun", "notsimulated", ...; "" if absent
    status: str = ""
    _frames: dict = field(default_factory=dict, repr=False)

    @property
    def branches(self) -> dict:
        """Branch name -> DataFrame of stored flight data (parsed on first use)."""
        for name, el in self.branch_elements.items():
            if name not in self._frames:
                self._frames[name] = _branch(el)
        return self._frames

    def has_data(self) -> bool:
        return bool(self.branch_elements)

    def events(self, branch: str | None = None) -> list[tuple[float, str, str]]:
        """OpenRocket's flight events of a branch (default the first):
        ``(time [s], type, source component id)`` in file order."""
        if not self.branch_elements:
            return []
        el = self.branch_elements[branch if branch is not None else next(iter(self.branch_elements))]
        out = []
        for ev in el.children("event"):
            try:
                out.append((float(ev.attr("time", "nan")), ev.attr("type", ""), ev.attr("source", "")))
            except ValueError:
                raise ev.error(f"event time must be a number, got {ev.attr('time')!r}") from None
        return out

    def data(self) -> pd.DataFrame | None:
        """The first (sustainer) branch of stored flight data, or None."""
        if not self.branch_elements:
            return None
        first = next(iter(self.branch_elements))
        if first not in self._frames:
            self._frames[first] = _branch(self.branch_elements[first])
        return self._frames[first]

    def at_launch(self) -> dict:
        """Stored values at t = 0 of the first branch (column -> value), or {}."""
        df = self.data()
        if df is None or df.empty:
            return {}
        return {k: float(v) for k, v in df.iloc[0].items()}


_SUMMARY = {"maxaltitude": "apogee_m", "maxvelocity": "max_speed_mps",
            "maxacceleration": "max_acceleration_mps2", "maxmach": "max_mach",
            "timetoapogee": "time_to_apogee_s", "flighttime": "flight_time_s",
            "groundhitvelocity": "ground_hit_speed_mps", "launchrodvelocity": "rail_exit_speed_mps",
            "deploymentvelocity": "deployment_speed_mps", "optimumdelay": "optimum_delay_s"}


#: LaunchSpec field -> the <conditions> element it comes from
_TAGS = {"rail_length": "launchrodlength", "inclination": "launchrodangle",
         "heading": "launchroddirection", "site_elevation": "launchaltitude",
         "latitude": "launchlatitude", "longitude": "launchlongitude",
         "site_temperature": "atmosphere/basetemperature", "site_pressure": "atmosphere/basepressure",
         "wind_speed": "windaverage", "wind_from": "winddirection"}


def _launch(cond: Element) -> tuple[LaunchSpec, bool]:
    angle = math.radians(cond.number("launchrodangle", 0.0))
    if not abs(angle) < math.pi / 2:
        raise cond.error(f"launch rod angle must be within (-90, 90) deg from vertical, got "
                         f"{math.degrees(angle):g}", "launchrodangle")
    into_wind = cond.flag("launchintowind", False)
    wind_from = cond.number("winddirection", math.pi / 2)
    heading = math.radians(cond.number("launchroddirection", 0.0))
    if angle < 0.0:        # OpenRocket tilts either way: -a towards d is +a towards d + 180 deg
        angle, heading = -angle, heading + math.pi
    if into_wind:
        heading = wind_from           # the rod leans into the wind
    temperature = pressure = None
    atm = cond.child("atmosphere")
    if atm is not None and (atm.attr("model") or "isa").lower() != "isa":
        temperature = atm.number("basetemperature", None, minimum=0.0)
        pressure = atm.number("basepressure", None, minimum=0.0)
    lat = cond.number("launchlatitude", None)
    lon = cond.number("launchlongitude", None)
    try:
        spec = LaunchSpec(rail_length=cond.number("launchrodlength", 1.0, minimum=0.0),
                          inclination=math.pi / 2 - angle, heading=heading,
                          site_elevation=cond.number("launchaltitude", 0.0),
                          latitude=None if lat is None else math.radians(lat),
                          longitude=None if lon is None else math.radians(lon),
                          site_temperature=temperature, site_pressure=pressure,
                          wind_speed=cond.number("windaverage", 0.0, minimum=0.0),
                          wind_from=wind_from)
    except InputError as err:         # name the .ork element behind LaunchSpec's field
        raise cond.error(err.message, _TAGS.get(err.field)) from None
    return spec, into_wind


def _branch(db: Element) -> pd.DataFrame:
    types = [t.strip() for t in (db.attr("types") or "").split(",")]
    if not types or not types[0]:
        raise db.error("a <databranch> needs a types attribute")
    rows = []
    for dp in db.children("datapoint"):
        vals = (dp.node.text or "").split(",")
        if len(vals) != len(types):
            raise dp.error(f"datapoint has {len(vals)} values, the branch declares "
                           f"{len(types)} types")
        try:
            rows.append([float(v) for v in vals])      # float() also reads NaN
        except ValueError:
            bad = next(v for v in vals if not is_float(v))
            raise dp.error(f"datapoint value {bad.strip()!r} is not a number") from None
    df = pd.DataFrame(rows, columns=[column_name(t) for t in types], dtype=float)
    return df


def simulations(root: Element) -> list[OrkSimulation]:
    """All ``<simulation>`` elements of the file."""
    sims = root.child("simulations")
    out = []
    for s in (sims.children("simulation") if sims is not None else []):
        cond = s.require("conditions")
        launch, into_wind = _launch(cond)
        sim = OrkSimulation(s.text("name") or "simulation", cond.text("configid") or "",
                            launch, into_wind, status=(s.attr("status") or "").lower())
        fd = s.child("flightdata")
        if fd is not None:
            for key, name in _SUMMARY.items():
                raw = fd.attr(key)
                if raw not in (None, "", "NaN"):
                    try:
                        sim.summary[name] = float(raw)
                    except ValueError:
                        raise fd.error(f"flightdata attribute {key} must be a number, got "
                                       f"{raw!r}") from None
            for db in fd.children("databranch"):
                sim.branch_elements[db.attr("name") or f"branch {len(sim.branch_elements) + 1}"] = db
        out.append(sim)
    return out
