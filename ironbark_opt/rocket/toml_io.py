"""Read the rocket TOML format (documented in docs/rocket-toml.md).

Rule for units: every key is in SI base units (m, kg, s, K, Pa, kg/m^3,
kg m^2) except angles, which are given in degrees and always end in
``_deg``.  Relative file paths are resolved against the TOML file's folder.
"""
from __future__ import annotations

import math
import re
import tomllib
from dataclasses import dataclass
from pathlib import Path

from ironbark_opt.errors import InputError
from ironbark_opt.rocket.body import BodyTube, Transition
from ironbark_opt.rocket.fin_sections import FinSection
from ironbark_opt.rocket.fins import EllipticalFins, FreeformFins, TrapezoidalFins
from ironbark_opt.rocket.hardware import InnerTube, LaunchLug, PointMass, RailButtons
from ironbark_opt.rocket.mass import MassProperties, dry_from_wet
from ironbark_opt.rocket.materials import finish_roughness, material_density
from ironbark_opt.rocket.nose import NoseCone
from ironbark_opt.rocket.revolution import BodyOfRevolution
from ironbark_opt.rocket.rocket import Rocket
from ironbark_opt.rocket.specs import (GRAIN_KEYS, MOTOR_OVERRIDE_KEYS, AeroSpec, BallastSpec,
                                       LaunchSpec, MotorSpec, RecoverySpec)

#: largest magnitude accepted for any number (guards overflow in the mass sums)
MAX_MAGNITUDE = 1e9
#: longest ``[[stage]] separation_delay`` [s]: the stack's coast is integrated in
#: boost-sized RK4 steps (1e6 s hung the flight); 600 s of coast is past the apogee
#: of any vehicle below ~5.9 km/s at burnout (t = v/g)
MAX_SEPARATION_DELAY = 600.0

TOP_KEYS = ("rocket", "component", "motor", "aero", "launch", "recovery", "ballast", "airbrakes", "airstart",
            "stage")
STAGE_KEYS = ("file", "name", "separation_delay", "table", "drag_power_off", "drag_power_on",
              "drag_duplicates")
ROCKET_KEYS = ("name", "reference_radius", "mass_override")
OVERRIDE_KEYS = ("mass", "cg_x", "I_transverse", "I_axial", "inertia", "includes_motor")
_BODY = ("type", "name", "x", "length", "thickness", "filled", "material", "density", "mass",
         "finish", "surface_roughness")
_FINS = ("type", "name", "x", "count", "thickness", "cant_deg", "section", "le_bevel",
         "te_bevel", "material", "density", "mass", "finish", "surface_roughness", "roll_deg",
         "lift_curve", "airfoil_polar")
COMPONENT_KEYS = {
    "nose_cone": _BODY + ("shape", "radius", "shape_parameter", "ogive_radius"),
    "body_tube": _BODY + ("radius",),
    "transition": _BODY + ("shape", "fore_radius", "aft_radius", "shape_parameter",
                           "ogive_radius", "clipped"),
    "trapezoidal_fins": _FINS + ("root_chord", "tip_chord", "span", "sweep_length",
                                 "sweep_angle_deg"),
    "elliptical_fins": _FINS + ("root_chord", "span"),
    "freeform_fins": _FINS + ("points",),
    "rail_buttons": ("type", "name", "x_fore", "x_aft", "height", "mass_each", "angle_deg",
                     "outer_diameter", "inner_diameter", "base_height", "flange_height", "x_other"),
    "launch_lug": ("type", "name", "x", "length", "outer_radius", "inner_radius",
                   "material", "density", "count", "separation"),
    "point_mass": ("type", "name", "x", "mass", "I_transverse", "I_axial"),
    "inner_tube": ("type", "name", "x", "length", "outer_radius", "inner_radius", "material",
                   "density", "mass"),
}
#: keys without a default, per component type (radii may follow the previous component)
REQUIRED_KEYS = {
    "nose_cone": ("length", "radius"), "body_tube": ("length",),
    "transition": ("length", "aft_radius"),
    "trapezoidal_fins": ("x", "thickness", "root_chord", "tip_chord", "span"),
    "elliptical_fins": ("x", "thickness", "root_chord", "span"),
    "freeform_fins": ("x", "thickness", "points"),
    "rail_buttons": ("x_fore", "x_aft"), "launch_lug": ("x", "length", "outer_radius"),
    "point_mass": ("x", "mass"), "inner_tube": ("x", "length", "outer_radius"),
}
MOTOR_KEYS = ("file", "designation", "nozzle_x", "overrides", "kind", "ignition_time", "grain", "tank",
              "ejection_delay")
AERO_KEYS = ("table", "drag_power_off", "drag_power_on", "drag_duplicates", "surface_roughness",
             "finish", "re_transition")
LAUNCH_KEYS = ("rail_length", "inclination_deg", "heading_deg", "site_elevation",
               "latitude_deg", "longitude_deg", "site_temperature", "site_pressure",
               "wind_speed", "wind_from_deg", "atmosphere", "gravity")
RECOVERY_KEYS = ("name", "cd_area", "cd", "diameter", "deploy", "lag")
BALLAST_KEYS = ("mass", "x", "x_min", "x_max", "mass_max")


@dataclass(frozen=True)
class RocketFile:
    """Everything one rocket TOML file describes.

    ``wet_mass_override`` holds the user's mass properties *with* the loaded
    motor (``includes_motor = true``); then ``rocket`` has no override and
    :meth:`dry_rocket` derives the dry one from the motor.
    """

    rocket: Rocket
    motor: MotorSpec
    aero: AeroSpec
    launch: LaunchSpec
    recovery: tuple
    ballast: BallastSpec
    source: Path
    wet_mass_override: MassProperties | None = None
    airbrakes: object = None          # AirbrakeSpec or None (rocket/airbrake_spec.py)
    #: lower stages below this rocket (``[[stage]]``; :class:`ironbark_opt.staged_vehicle.StageSpec`)
    stages: tuple = ()

    def dry_rocket(self, motor=None) -> Rocket:
        """The rocket with dry mass properties (numeric-only).

        Parameters
        ----------
        motor : Motor or None
            Needed only when the file gives wet mass properties: its
            ``mass(0)`` [kg], ``cg(0)`` [m fwd of nozzle exit] and
            ``inertia(0)`` [kg m^2] are removed with :func:`dry_from_wet`.
        """
        if self.wet_mass_override is None:
            return self.rocket
        if motor is None:
            raise InputError("this file gives mass properties with the motor loaded "
                             "(includes_motor = true): pass the motor to derive the dry rocket",
                             source=self.source, field="rocket.mass_override")
        i_t, i_a = motor.inertia(0.0)
        dry = dry_from_wet(self.wet_mass_override, float(motor.mass(0.0)),
                           float(self.motor.motor_cg_x(motor.cg(0.0))), float(i_t), float(i_a))
        return self.rocket.with_mass_override(dry)


class _Lines:
    """Best-effort line numbers of ``[table]`` headers and ``key =`` lines."""

    _HEADER = re.compile(r"^\s*(\[\[?)\s*([A-Za-z0-9_.\-\s]+?)\s*\]\]?")
    _KEY = re.compile(r"^\s*([A-Za-z0-9_\-]+)\s*=")

    def __init__(self, text: str):
        self.index: dict[tuple, int] = {}
        counts: dict[str, int] = {}
        table, occ = "", 0
        for n, line in enumerate(text.splitlines(), start=1):
            h = self._HEADER.match(line)
            if h:
                table = h.group(2).replace(" ", "")
                if h.group(1) == "[[":
                    counts[table] = counts.get(table, -1) + 1
                # a sub-table of an array element belongs to the latest element; an
                # array inside a plain table ([[motor.tank]]) counts its own elements
                own = counts.get(table, 0) if h.group(1) == "[[" else 0
                occ = counts.get(table.split(".")[0], own)
                self.index.setdefault((table, occ, None), n)
                continue
            k = self._KEY.match(line)
            if k:
                self.index.setdefault((table, occ, k.group(1)), n)

    def find(self, table: str, occ: int, key: str | None):
        return self.index.get((table, occ, key)) or self.index.get((table, occ, None))


class _Reader:
    def __init__(self, path: Path, text: str):
        self.path = path
        self.lines = _Lines(text)

    def error(self, message, table, key=None, occ=0, field=None):
        return InputError(message, source=self.path, line=self.lines.find(table, occ, key),
                          field=field or (f"{table}.{key}" if key else table))

    def check_keys(self, data, allowed, table, occ=0, label=None):
        if not isinstance(data, dict):
            raise self.error(f"expected a table [{table}]", table, occ=occ, field=label)
        for key in data:
            if key not in allowed:
                raise self.error(f"unknown key '{key}'; accepted keys: {', '.join(allowed)}",
                                 table, key, occ, field=f"{label or table}.{key}")

    def wrap(self, exc: InputError, table, occ, label, data=None):
        """Re-raise a constructor's InputError with file, line and full field.

        A field given in degrees in the file (``cant`` <- ``cant_deg``) is
        reported under its TOML key.
        """
        key = exc.field.split(".")[-1] if exc.field else None
        if key and data is not None and key not in data and f"{key}_deg" in data:
            key = f"{key}_deg"
            return self.error(exc.message, table, key, occ, field=f"{label}.{key}")
        return self.error(exc.message, table, key, occ,
                          field=f"{label}.{exc.field}" if exc.field else label)

    def number(self, data, key, table, occ=0, label=None, default=None, required=False):
        if key not in data:
            if required:
                raise self.error(f"missing required key '{key}'", table, None, occ,
                                 field=f"{label or table}.{key}")
            return default
        val = data[key]
        if isinstance(val, bool) or not isinstance(val, (int, float)):
            raise self.error(f"expected a number, got {val!r}", table, key, occ,
                             field=f"{label or table}.{key}")
        if not math.isfinite(val) or abs(val) > MAX_MAGNITUDE:
            raise self.error(f"expected a finite number of at most {MAX_MAGNITUDE:g} in size "
                             f"(SI units), got {val!r}", table, key, occ,
                             field=f"{label or table}.{key}")
        return float(val)

    def tables(self, items, table, keys):
        """``(index, table dict, label)`` of each ``[[table]]``, keys checked."""
        if not isinstance(items, list):
            raise self.error(f"expected [[{table}]] tables", table)
        for i, d in enumerate(items):
            label = f"{table}[{i}]"
            self.check_keys(d, keys, table, i, label)
            yield i, d, label

    def table_file(self, d, table, i, label, what, key="file"):
        """The existing file named by ``key`` of the ``i``-th ``[[table]]`` (required)."""
        if not isinstance(d.get(key), str):
            raise self.error(f"missing required key '{key}' ({what})", table, None, i, field=f"{label}.{key}")
        path = (self.path.parent / d[key]).resolve()
        if not path.is_file():
            raise self.error(f"file not found: {path}", table, key, i, field=f"{label}.{key}")
        return path

    def file(self, data, key, table, required=False):
        if key not in data:
            if required:
                raise self.error(f"missing required key '{key}'", table)
            return None
        if not isinstance(data[key], str):
            raise self.error(f"expected a file path string, got {data[key]!r}", table, key)
        p = (self.path.parent / data[key]).resolve()
        if p.is_dir():
            raise self.error(f"{p} is a directory, expected a file", table, key)
        if not p.is_file():
            raise self.error(f"file not found: {p}", table, key)
        return p

    def density(self, data, table, occ, label):
        if "material" in data and "density" in data:
            raise self.error("give material or density, not both", table, "density", occ,
                             field=f"{label}.density")
        if "material" in data:
            try:
                return material_density(data["material"])
            except InputError as exc:
                raise self.error(exc.message, table, "material", occ,
                                 field=f"{label}.material") from None
        return self.number(data, "density", table, occ, label)


def load_rocket_toml(path) -> RocketFile:
    """Read a rocket TOML file into a :class:`RocketFile` (numeric-only).

    Raises InputError naming the file, line and key for syntax errors,
    unknown keys, missing keys and invalid values.
    """
    path = Path(path)
    try:
        text = path.read_text(encoding="utf-8")
    except OSError as exc:
        raise InputError(f"cannot read the rocket file: {exc.strerror}", source=path) from None
    except UnicodeDecodeError as exc:
        raise InputError(f"not a UTF-8 text file (byte {exc.start}): a rocket TOML file is expected "
                         "(OpenRocket files need the .ork suffix)", source=path) from None
    return loads_rocket_toml(text, path)


def loads_rocket_toml(text: str, path) -> RocketFile:
    """Parse TOML ``text`` as if read from ``path`` (paths resolve against its folder)."""
    path = Path(path).resolve()
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        line = getattr(exc, "lineno", None)
        match = re.search(r"\(at line (\d+), column (\d+)\)", str(exc))
        if line is None and match:
            line = int(match.group(1))
        msg = getattr(exc, "msg", None) or re.sub(r"\s*\(at line.*\)$", "", str(exc))
        field = None
        if "overwrite" in msg.lower() and line is not None and 0 < line <= len(text.splitlines()):
            key = text.splitlines()[line - 1].split("=", 1)[0].strip()
            if key:
                field = key
                msg = f"duplicate key '{key}' (a key may be given once per table)"
        raise InputError(f"TOML syntax error: {msg}", source=path, line=line, field=field) from None
    rd = _Reader(path, text)
    rd.check_keys(data, TOP_KEYS, "", label="(top level)")
    for required in ("rocket", "component", "motor"):
        if required not in data:
            raise InputError(f"missing section [{required}]"
                             + (" (use [[component]] tables)" if required == "component" else ""),
                             source=path, field=required)
    rocket, wet = _read_rocket(rd, data)
    ballast = _read_simple(rd, data.get("ballast", {}), "ballast", BALLAST_KEYS, BallastSpec)
    for key in ("x", "x_max"):
        val = getattr(ballast, key)
        if val is not None and val > rocket.length():
            raise rd.error(f"{val} m lies aft of the rocket's end ({rocket.length():.6g} m)",
                           "ballast", key)
    motor = _read_motor(rd, data["motor"])
    if "airstart" in data:
        import dataclasses

        from ironbark_opt.rocket.airbrake_spec import read_airstart
        motor = dataclasses.replace(motor, airstart=read_airstart(rd, data["airstart"]))
    return RocketFile(rocket=rocket, motor=motor,
                      aero=_read_aero(rd, data.get("aero", {})),
                      launch=_read_launch(rd, data.get("launch", {})),
                      recovery=_read_recovery(rd, data.get("recovery", [])),
                      ballast=ballast, source=path, wet_mass_override=wet,
                      airbrakes=_read_airbrakes(rd, data), stages=_read_stages(rd, data.get("stage", [])))


def _read_stages(rd: _Reader, items) -> tuple:
    """``[[stage]]`` tables -> StageSpecs (a lower stage in its own rocket file)."""
    from ironbark_opt.staged_vehicle import StageSpec

    out = []
    for i, d, label in rd.tables(items, "stage", STAGE_KEYS):
        file = rd.table_file(d, "stage", i, label, "the stage's own rocket file")
        if file.resolve() == rd.path.resolve():
            raise rd.error("a stage cannot be the file itself", "stage", "file", i, field=f"{label}.file")
        delay = rd.number(d, "separation_delay", "stage", i, label, default=0.0)
        if delay < 0 or delay > MAX_SEPARATION_DELAY:
            raise rd.error(f"must be >= 0 s after the stage's burnout, got {delay}" if delay < 0 else
                           f"must be at most {MAX_SEPARATION_DELAY:g} s after the stage's burnout (a "
                           f"stack coasting longer is past its apogee), got {delay}", "stage",
                           "separation_delay", i, field=f"{label}.separation_delay")
        name = d.get("name", "")
        if not isinstance(name, str):
            raise rd.error(f"expected a string, got {name!r}", "stage", "name", i, field=f"{label}.name")
        aero = {k: rd.file(d, k, "stage") for k in ("table", "drag_power_off", "drag_power_on") if k in d}
        if "drag_duplicates" in d:
            aero["drag_duplicates"] = _drag_duplicates(rd, d, "stage", i, label)
        out.append(StageSpec(file=file, separation_delay=delay, name=name, aero=aero or None))
    return tuple(out)


def _read_airbrakes(rd: _Reader, data):
    if "airbrakes" not in data:
        return None
    from ironbark_opt.rocket.airbrake_spec import read_airbrakes
    return read_airbrakes(rd, data["airbrakes"])


def _read_rocket(rd: _Reader, data):
    meta = data["rocket"]
    rd.check_keys(meta, ROCKET_KEYS, "rocket")
    comps_data = data["component"]
    if not isinstance(comps_data, list) or not comps_data:
        raise rd.error("expected one or more [[component]] tables", "component")
    components, prev = [], None
    for i, comp in enumerate(comps_data):
        c = _read_component(rd, comp, i, prev)
        components.append(c)
        if isinstance(c, BodyOfRevolution):
            prev = c
    override, wet = None, None
    if "mass_override" in meta:
        mp, includes_motor = _read_override(rd, meta["mass_override"])
        override, wet = (None, mp) if includes_motor else (mp, None)
    name = meta.get("name", rd.path.stem)
    if not isinstance(name, str):
        raise rd.error(f"expected a string, got {name!r}", "rocket", "name")
    try:
        rocket = Rocket(name, components, mass_override=override,
                        reference_radius=rd.number(meta, "reference_radius", "rocket"))
    except InputError as exc:
        match = re.fullmatch(r"components\[(\d+)\]\.(\w+)", exc.field or "")
        if match:
            i, key = int(match.group(1)), match.group(2)
            raise rd.error(exc.message, "component", key, i,
                           field=f"component[{i}].{key}") from None
        raise rd.error(exc.message, "rocket", exc.field, field=f"rocket.{exc.field}") from None
    if wet is None and override is None:
        try:
            rocket.dry_mass_properties()
        except InputError as exc:
            raise InputError(exc.message, source=rd.path, field="rocket.mass_override") from None
    return rocket, wet


def _read_override(rd: _Reader, d):
    table = "rocket.mass_override"
    rd.check_keys(d, OVERRIDE_KEYS, table)
    mass = rd.number(d, "mass", table, required=True)
    cg = rd.number(d, "cg_x", table, required=True)
    has_pair = "I_transverse" in d or "I_axial" in d
    if has_pair == ("inertia" in d):
        raise rd.error("give either I_transverse and I_axial [kg m^2] or a 3x3 inertia "
                       "[kg m^2] (x along the rocket axis)", table)
    try:
        if has_pair:
            mp = MassProperties.axisymmetric(mass, cg,
                                             rd.number(d, "I_transverse", table, required=True),
                                             rd.number(d, "I_axial", table, required=True))
        else:
            mp = MassProperties(mass, cg, d["inertia"])
    except InputError as exc:
        raise rd.wrap(exc, table, 0, table) from None
    inc = d.get("includes_motor", False)
    if not isinstance(inc, bool):
        raise rd.error(f"expected true or false, got {inc!r}", table, "includes_motor")
    return mp, inc


def _read_component(rd: _Reader, d, i, prev):
    label = f"component[{i}]"
    if not isinstance(d, dict) or "type" not in d:
        raise rd.error(f"every [[component]] needs a type: {', '.join(COMPONENT_KEYS)}",
                       "component", None, i, field=f"{label}.type")
    kind = d["type"]
    if not isinstance(kind, str) or kind not in COMPONENT_KEYS:
        raise rd.error(f"unknown component type {kind!r}; expected one of "
                       f"{', '.join(COMPONENT_KEYS)}", "component", "type", i,
                       field=f"{label}.type")
    rd.check_keys(d, COMPONENT_KEYS[kind], "component", i, label)
    required = REQUIRED_KEYS[kind] + (("radius",) if kind == "body_tube" and prev is None else ()) \
        + (("fore_radius",) if kind == "transition" and prev is None else ())
    for key in required:
        if key not in d:
            raise rd.error(f"missing required key '{key}' for a {kind}", "component", None, i,
                           field=f"{label}.{key}")
    kw = {}
    for key, val in d.items():
        if key in ("type", "material", "cant_deg", "sweep_angle_deg", "section", "le_bevel",
                   "te_bevel", "finish", "surface_roughness", "roll_deg", "lift_curve",
                   "airfoil_polar", "angle_deg"):
            continue
        if key in ("name", "shape"):
            if not isinstance(val, str):
                raise rd.error(f"expected a string, got {val!r}", "component", key, i,
                               field=f"{label}.{key}")
            kw[key] = val
        elif key in ("filled", "clipped"):
            if not isinstance(val, bool):
                raise rd.error(f"expected true or false, got {val!r}", "component", key, i,
                               field=f"{label}.{key}")
            kw[key] = val
        elif key == "count":
            if isinstance(val, bool) or not isinstance(val, int):
                raise rd.error(f"expected a whole number, got {val!r}", "component", key, i,
                               field=f"{label}.{key}")
            kw[key] = val
        elif key == "points":
            kw[key] = val
        elif key == "x_other":
            if not isinstance(val, list):
                raise rd.error(f"expected a list of stations [m], got {val!r}", "component", key, i,
                               field=f"{label}.{key}")
            kw[key] = tuple(val)
        else:
            kw[key] = rd.number(d, key, "component", i, label)
    if kind in ("nose_cone", "body_tube", "transition", "trapezoidal_fins", "elliptical_fins",
                "freeform_fins", "launch_lug", "inner_tube"):
        dens = rd.density(d, "component", i, label)
        if dens is not None:
            kw["density"] = dens
    if "finish" in d or "surface_roughness" in d:
        kw["roughness"] = _component_roughness(rd, d, i, label)
    if kind in ("nose_cone", "body_tube", "transition") and "x" not in d:
        kw["x"] = 0.0 if prev is None else prev.x_end
    if kind == "body_tube" and "radius" not in d and prev is not None:
        kw["radius"] = prev.aft_radius
    if kind == "transition" and "fore_radius" not in d and prev is not None:
        kw["fore_radius"] = prev.aft_radius
    if kind == "rail_buttons" and "angle_deg" in d:
        kw["angle"] = math.radians(rd.number(d, "angle_deg", "component", i, label))
    if kind.endswith("_fins"):
        kw["cant"] = math.radians(rd.number(d, "cant_deg", "component", i, label, default=0.0))
        if "roll_deg" in d:
            kw["roll"] = math.radians(rd.number(d, "roll_deg", "component", i, label))
        kw["section_lift"] = _read_section_lift(rd, d, i, label)
        try:
            kw["section"] = FinSection(kind=d.get("section", "square"),
                                       le_bevel=d.get("le_bevel"), te_bevel=d.get("te_bevel"))
        except InputError as exc:
            raise rd.wrap(exc, "component", i, label) from None
        if "sweep_angle_deg" in d:
            if "sweep_length" in d:
                raise rd.error("give sweep_length or sweep_angle_deg, not both", "component",
                               "sweep_angle_deg", i, field=f"{label}.sweep_angle_deg")
            ang = rd.number(d, "sweep_angle_deg", "component", i, label)
            if not -90.0 < ang < 90.0:
                raise rd.error(f"must be within +-90 deg (exclusive), got {ang}", "component",
                               "sweep_angle_deg", i, field=f"{label}.sweep_angle_deg")
            kw["sweep_length"] = rd.number(d, "span", "component", i, label,
                                           required=True) * math.tan(math.radians(ang))
    cls = {"nose_cone": NoseCone, "body_tube": BodyTube, "transition": Transition,
           "trapezoidal_fins": TrapezoidalFins, "elliptical_fins": EllipticalFins,
           "freeform_fins": FreeformFins, "rail_buttons": RailButtons,
           "launch_lug": LaunchLug, "point_mass": PointMass, "inner_tube": InnerTube}[kind]
    try:
        return cls(**kw)
    except InputError as exc:
        raise rd.wrap(exc, "component", i, label, d) from None


def _component_roughness(rd: _Reader, d, i, label) -> float:
    """A component's own ``finish`` (named) or ``surface_roughness`` [m]."""
    if "finish" in d:
        if "surface_roughness" in d:
            raise rd.error("give finish or surface_roughness, not both", "component", "finish",
                           i, field=f"{label}.finish")
        try:
            return finish_roughness(d["finish"])
        except InputError as exc:
            raise rd.error(exc.message, "component", "finish", i, field=f"{label}.finish") from None
    return rd.number(d, "surface_roughness", "component", i, label)


def _read_section_lift(rd: _Reader, d, i, label):
    """A fin set's ``lift_curve`` or ``airfoil_polar`` file -> its ``section_lift``."""
    from ironbark_opt.rocket import fin_files
    given = [k for k in ("lift_curve", "airfoil_polar") if k in d]
    if not given:
        return None
    if len(given) > 1:
        raise rd.error("give lift_curve or airfoil_polar, not both", "component", "airfoil_polar", i,
                       field=f"{label}.airfoil_polar")
    key = given[0]
    if not isinstance(d[key], str):
        raise rd.error(f"expected a file path string, got {d[key]!r}", "component", key, i, field=f"{label}.{key}")
    path = (rd.path.parent / d[key]).resolve()
    if not path.is_file():
        raise rd.error(f"file not found: {path}", "component", key, i, field=f"{label}.{key}")
    try:
        if key == "lift_curve":
            return ("curve", fin_files.read_lift_curve(path, f"{label}.{key}"))
        return ("polar", fin_files.read_airfoil_polar(path, f"{label}.{key}"))
    except InputError as exc:
        raise rd.error(f"{path.name}: {exc.message}", "component", key, i, field=f"{label}.{key}") from None


def _read_motor(rd: _Reader, d):
    rd.check_keys(d, MOTOR_KEYS, "motor")
    file = rd.file(d, "file", "motor", required=True)
    des = d.get("designation")
    if des is not None and not isinstance(des, str):
        raise rd.error(f"expected a string, got {des!r}", "motor", "designation")
    nozzle_x = rd.number(d, "nozzle_x", "motor", required=True)
    ov_in = d.get("overrides", {})
    rd.check_keys(ov_in, MOTOR_OVERRIDE_KEYS, "motor.overrides")
    ov = {}
    for key, val in ov_in.items():
        if key == "grains":
            rd.check_keys(val, GRAIN_KEYS, "motor.overrides.grains")
            g = {}
            for gk in GRAIN_KEYS:
                num = rd.number(val, gk, "motor.overrides.grains", required=True)
                if gk == "count":
                    if num != int(num) or num < 1:
                        raise rd.error(f"expected a whole number >= 1, got {val[gk]!r}",
                                       "motor.overrides.grains", gk)
                    num = int(num)
                elif num < 0 or (num == 0 and gk != "inner_radius" and gk != "separation"):
                    raise rd.error(f"must be > 0, got {num}", "motor.overrides.grains", gk)
                g[gk] = num
            if g["inner_radius"] >= g["outer_radius"]:
                raise rd.error("inner_radius must be smaller than outer_radius",
                               "motor.overrides.grains", "inner_radius")
            ov[key] = g
        elif key == "dry_inertia":
            if (not isinstance(val, list) or len(val) != 2 or
                    not all(isinstance(q, (int, float)) and not isinstance(q, bool)
                            and 0 <= q <= MAX_MAGNITUDE for q in val)):
                raise rd.error(f"expected [I_transverse, I_axial] >= 0 [kg m^2], got {val!r}",
                               "motor.overrides", key)
            ov[key] = (float(val[0]), float(val[1]))
        else:
            num = rd.number(ov_in, key, "motor.overrides")
            # dry_mass = 0: the casing is counted in the rocket's mass (docs/rocket-toml.md);
            # the CGs are measured forward of the nozzle exit: 0 is the exit itself
            at_least_zero = key in ("dry_mass", "dry_cg", "propellant_cg")
            if num < 0 if at_least_zero else num <= 0:
                raise rd.error(f"must be {'>= 0' if at_least_zero else '> 0'}, got {num}",
                               "motor.overrides", key)
            ov[key] = num
    extra = _read_motor_kind(rd, d, ov)
    try:
        return MotorSpec(file=file, designation=des, nozzle_x=nozzle_x, overrides=ov, **extra)
    except InputError as exc:
        raise rd.wrap(exc, "motor", 0, "motor") from None


def _read_motor_kind(rd: _Reader, d, ov):
    """``kind``, ``ignition_time``, ``[motor.grain]``, ``[[motor.tank]]`` and
    ``ejection_delay`` of ``[motor]`` (docs/rocket-toml.md)."""
    from ironbark_opt.rocket import tank_spec as ts

    out = {}
    delay = rd.number(d, "ejection_delay", "motor")
    if delay is not None:
        if delay < 0:
            raise rd.error(f"must be >= 0 s, got {delay}", "motor", "ejection_delay")
        out["ejection_delay"] = delay
    kind = d.get("kind", "solid")
    if kind not in ts.MOTOR_KINDS:
        raise rd.error(f"expected one of {', '.join(ts.MOTOR_KINDS)}, got {kind!r}", "motor", "kind")
    if kind == "solid":
        for key in ("ignition_time", "grain", "tank"):
            if key in d:
                raise rd.error(f"'{key}' needs kind = \"hybrid\" or \"liquid\"", "motor", key)
        return out
    out["kind"] = kind
    t_ig = rd.number(d, "ignition_time", "motor", default=0.0)
    if t_ig < 0:
        raise rd.error(f"must be >= 0 s, got {t_ig}", "motor", "ignition_time")
    out["ignition_time"] = t_ig
    bad = [k for k in ov if k not in ts.TANK_MOTOR_OVERRIDES]
    if bad:
        raise rd.error(f"a {kind} motor's propellant comes from its tanks and grain; "
                       f"[motor.overrides] accepts {', '.join(ts.TANK_MOTOR_OVERRIDES)}",
                       "motor.overrides", bad[0])
    for key in ("dry_mass", "dry_cg", "dry_inertia"):
        if key not in ov:
            raise rd.error(f"a {kind} motor needs [motor.overrides] {key}", "motor", None,
                           field=f"motor.overrides.{key}")
    if "tank" not in d:
        raise rd.error(f"a {kind} motor needs [[motor.tank]] tables", "motor", field="motor.tank")
    out["tanks"] = ts.read_tanks(rd, d["tank"])
    if kind == "hybrid":
        if "grain" not in d:
            raise rd.error("a hybrid motor needs a [motor.grain] table", "motor", field="motor.grain")
        out["grain"] = ts.read_grain(rd, d["grain"])
    elif "grain" in d:
        raise rd.error("a liquid motor has no grain (use kind = \"hybrid\")", "motor.grain")
    return out


def _read_aero(rd: _Reader, d):
    rd.check_keys(d, AERO_KEYS, "aero")
    kw = {k: rd.file(d, k, "aero") for k in ("table", "drag_power_off", "drag_power_on")}
    if "drag_duplicates" in d:
        kw["drag_duplicates"] = _drag_duplicates(rd, d, "aero")
    if "finish" in d:
        if "surface_roughness" in d:
            raise rd.error("give finish or surface_roughness, not both", "aero", "finish")
        try:
            kw["surface_roughness"] = finish_roughness(d["finish"])
        except InputError as exc:
            raise rd.error(exc.message, "aero", "finish") from None
    for k in ("surface_roughness", "re_transition"):
        if k in d:
            kw[k] = rd.number(d, k, "aero")
    try:
        return AeroSpec(**kw)
    except InputError as exc:
        raise rd.wrap(exc, "aero", 0, "aero") from None


def _drag_duplicates(rd: _Reader, d, table, occ=0, label=None):
    """``drag_duplicates``: what a repeated Mach number in a drag curve means."""
    val = d["drag_duplicates"]
    if val not in ("error", "mean"):
        raise rd.error(f'expected "error" or "mean", got {val!r}', table, "drag_duplicates", occ,
                       field=f"{label or table}.drag_duplicates")
    return val


def _read_launch(rd: _Reader, d):
    rd.check_keys(d, LAUNCH_KEYS, "launch")
    kw = {}
    if "atmosphere" in d:
        kw["atmosphere_file"], kw["atmosphere_time"] = _read_atmosphere(rd, d["atmosphere"])
    for key in d:
        if key == "atmosphere":
            continue
        val = rd.number(d, key, "launch")
        if key.endswith("_deg"):
            kw[key[:-4].replace("_deg", "")] = math.radians(val)
        else:
            kw[key] = val
    try:
        spec = LaunchSpec(**kw)
    except InputError as exc:
        raise rd.wrap(exc, "launch", 0, "launch", d) from None
    from ironbark_opt.atmosphere.isa import ISA
    try:                     # the ISA the flight builds from the site values
        ISA.from_site(spec.site_elevation, spec.site_temperature, spec.site_pressure)
    except InputError as exc:
        key = {"temperature": "site_temperature", "temperature_offset": "site_temperature",
               "pressure": "site_pressure", "pressure_offset": "site_pressure"}.get(exc.field,
                                                                                  "site_elevation")
        raise rd.error(exc.message, "launch", key) from None
    return spec


def _read_atmosphere(rd: _Reader, value):
    """``atmosphere = "file"`` or ``{file = "...", time = "ISO 8601 UTC"}``."""
    if isinstance(value, str):
        value = {"file": value}
    if not isinstance(value, dict):
        raise rd.error('expected a file path or {file = "...", time = "2020-02-22T13:00Z"}',
                       "launch", "atmosphere")
    for key in value:
        if key not in ("file", "time"):
            raise rd.error(f"unknown key '{key}' in atmosphere; accepted keys: file, time",
                           "launch", "atmosphere", field="launch.atmosphere." + str(key))
    path = rd.file(value, "file", "launch", required=True)
    time = value.get("time")
    if time is not None:
        from ironbark_opt.atmosphere.ncss import parse_iso
        if not isinstance(time, str):
            time = time.isoformat() if hasattr(time, "isoformat") else time
        try:
            parse_iso(str(time))
        except InputError as exc:
            raise rd.error(exc.message + " (expected ISO 8601 UTC, e.g. 2020-02-22T13:00Z)",
                           "launch", "atmosphere", field="launch.atmosphere.time") from None
        time = str(time)
    return path, time


def _read_recovery(rd: _Reader, items):
    if not isinstance(items, list):
        raise rd.error("expected [[recovery]] tables", "recovery")
    out = []
    for i, d in enumerate(items):
        label = f"recovery[{i}]"
        rd.check_keys(d, RECOVERY_KEYS, "recovery", i, label)
        if ("cd_area" in d) == ("cd" in d or "diameter" in d):
            raise rd.error("give cd_area [m^2] or both cd and diameter [m]", "recovery", None,
                           i, field=label)
        if "cd_area" in d:
            cd_area = rd.number(d, "cd_area", "recovery", i, label)
        else:
            cd = rd.number(d, "cd", "recovery", i, label, required=True)
            diam = rd.number(d, "diameter", "recovery", i, label, required=True)
            for key, val in (("cd", cd), ("diameter", diam)):
                if val <= 0:        # a negative diameter would square to a positive area
                    raise rd.error(f"must be > 0, got {val}", "recovery", key, i, field=f"{label}.{key}")
            cd_area = cd * math.pi * diam * diam / 4.0
        deploy = d.get("deploy", "apogee")
        if not isinstance(deploy, str):
            deploy = rd.number(d, "deploy", "recovery", i, label)
        name = d.get("name", f"recovery {i + 1}")
        if not isinstance(name, str):
            raise rd.error(f"expected a string, got {name!r}", "recovery", "name", i, field=f"{label}.name")
        try:
            out.append(RecoverySpec(name=str(name), cd_area=cd_area, deploy=deploy,
                                    lag=rd.number(d, "lag", "recovery", i, label, default=0.0)))
        except InputError as exc:
            raise rd.wrap(exc, "recovery", i, label) from None
    return tuple(out)


def _read_simple(rd: _Reader, d, table, keys, cls):
    rd.check_keys(d, keys, table)
    kw = {k: rd.number(d, k, table) for k in d}
    try:
        return cls(**kw)
    except InputError as exc:
        raise rd.wrap(exc, table, 0, table) from None
