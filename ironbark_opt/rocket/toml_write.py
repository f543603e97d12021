"""Write a RocketFile back to the rocket TOML format (docs/rocket-toml.md).

``load_rocket_toml(path)`` of the written file gives the same objects
(round trip); comments and key order of an original file are not kept.
"""
from __future__ import annotations

import json
import math
import os
from pathlib import Path

import numpy as np

from ironbark_opt.rocket.body import BodyTube, Transition
from ironbark_opt.rocket.fins import EllipticalFins, FreeformFins, TrapezoidalFins
from ironbark_opt.rocket.hardware import InnerTube, LaunchLug, PointMass, RailButtons
from ironbark_opt.rocket.mass import MassProperties
from ironbark_opt.rocket.nose import NoseCone

_TYPES = ((NoseCone, "nose_cone"), (BodyTube, "body_tube"), (Transition, "transition"),
          (TrapezoidalFins, "trapezoidal_fins"), (EllipticalFins, "elliptical_fins"),
          (FreeformFins, "freeform_fins"), (RailButtons, "rail_buttons"),
          (LaunchLug, "launch_lug"), (PointMass, "point_mass"), (InnerTube, "inner_tube"))
_BODY = ("name", "x", "length", "thickness", "filled", "density", "mass")
_FIN = ("name", "x", "count", "thickness", "density", "mass")
_FIELDS = {
    "nose_cone": _BODY + ("shape", "radius", "shape_parameter", "ogive_radius"),
    "body_tube": _BODY + ("radius",),
    "transition": _BODY + ("shape", "fore_radius", "aft_radius", "shape_parameter",
                           "ogive_radius", "clipped"),
    "trapezoidal_fins": _FIN + ("root_chord", "tip_chord", "span", "sweep_length"),
    "elliptical_fins": _FIN + ("root_chord", "span"),
    "freeform_fins": _FIN + ("points",),
    "rail_buttons": ("name", "x_fore", "x_aft", "height", "mass_each", "outer_diameter",
                     "inner_diameter", "base_height", "flange_height", "x_other"),
    "launch_lug": ("name", "x", "length", "outer_radius", "inner_radius", "density", "count",
                   "separation"),
    "point_mass": ("name", "x", "mass", "I_transverse", "I_axial"),
    "inner_tube": ("name", "x", "length", "outer_radius", "inner_radius", "density", "mass"),
}


def _value(v) -> str:
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, (int, np.integer)):
        return str(int(v))
    if isinstance(v, (float, np.floating)):
        return repr(float(v))
    if isinstance(v, str):
        return json.dumps(v)
    if isinstance(v, (list, tuple, np.ndarray)):
        return "[" + ", ".join(_value(x) for x in v) + "]"
    raise TypeError(f"cannot write {type(v).__name__} to TOML")


def _table(header: str, items: dict) -> list[str]:
    lines = [header] if header else []
    lines += [f"{k} = {_value(v)}" for k, v in items.items() if v is not None]
    return lines + [""]


def _component(comp) -> dict:
    kind = next(name for cls, name in _TYPES if isinstance(comp, cls))
    out = {"type": kind}
    for key in _FIELDS[kind]:
        val = getattr(comp, key)
        if key in ("filled", "clipped") and not val:
            continue
        if kind == "launch_lug" and key in ("count", "separation") and comp.count == 1:
            continue
        if kind == "rail_buttons" and key in ("base_height", "flange_height", "x_other") and not val:
            continue
        if key == "points":
            val = [list(map(float, p)) for p in val]
        out[key] = val
    if kind == "rail_buttons" and comp.angle is not None:
        out["angle_deg"] = math.degrees(comp.angle)
    if kind.endswith("_fins"):
        if comp.roll is not None:
            out["roll_deg"] = math.degrees(comp.roll)
        out["cant_deg"] = math.degrees(comp.cant)
        out["section"] = comp.section.kind
        out["le_bevel"] = comp.section.le_bevel
        out["te_bevel"] = comp.section.te_bevel
    return out


def _mass_override(mp: MassProperties, includes_motor: bool) -> dict:
    out = {"mass": mp.mass, "cg_x": mp.cg_x}
    diag = np.diag(mp.inertia)
    if np.count_nonzero(mp.inertia - np.diag(diag)) == 0 and diag[1] == diag[2]:
        out.update(I_transverse=float(diag[1]), I_axial=float(diag[0]))
    else:
        out["inertia"] = [list(map(float, row)) for row in mp.inertia]
    if includes_motor:
        out["includes_motor"] = True
    return out


def _path(p, folder: Path):
    if p is None:
        return None
    try:
        return Path(os.path.relpath(p, folder)).as_posix()
    except ValueError:      # another drive on Windows
        return str(p)


def to_toml(rf, folder=None) -> str:
    """The rocket TOML text of a :class:`~ironbark_opt.rocket.toml_io.RocketFile` (numeric-only).

    Parameters
    ----------
    rf : RocketFile
    folder : path or None
        Folder the text will be saved in; file paths are written relative
        to it (default: the folder of ``rf.source``).
    """
    folder = Path(folder if folder is not None else Path(rf.source).parent).resolve()
    r = rf.rocket
    lines = [f"# Rocket file written by Ironbark-Opt (format: docs/rocket-toml.md)", ""]
    lines += _table("[rocket]", {"name": r.name, "reference_radius": r._reference_radius})
    if r.mass_override is not None:
        lines += _table("[rocket.mass_override]", _mass_override(r.mass_override, False))
    elif rf.wet_mass_override is not None:
        lines += _table("[rocket.mass_override]", _mass_override(rf.wet_mass_override, True))
    for comp in r.components:
        lines += _table("[[component]]", _component(comp))
    m = rf.motor
    if m.kind != "solid":
        from ironbark_opt.errors import InputError
        raise InputError(f"writing a {m.kind} motor's tanks back to TOML is not supported; keep the "
                         f"original file", source=rf.source, field="motor.kind")
    delay = m.ejection_delay if m.ejection_delay is not None and math.isfinite(m.ejection_delay) else None
    lines += _table("[motor]", {"file": _path(m.file, folder), "designation": m.designation,
                                "nozzle_x": m.nozzle_x, "ejection_delay": delay})
    simple = {k: v for k, v in m.overrides.items() if k != "grains"}
    if m.overrides:
        lines += _table("[motor.overrides]", simple)
    if "grains" in m.overrides:
        lines += _table("[motor.overrides.grains]", m.overrides["grains"])
    a = rf.aero
    lines += _table("[aero]", {"table": _path(a.table, folder),
                               "drag_power_off": _path(a.drag_power_off, folder),
                               "drag_power_on": _path(a.drag_power_on, folder),
                               "surface_roughness": a.surface_roughness,
                               "re_transition": a.re_transition})
    L = rf.launch
    deg = lambda v: None if v is None else math.degrees(v)
    lines += _table("[launch]", {"rail_length": L.rail_length,
                                 "inclination_deg": deg(L.inclination),
                                 "heading_deg": deg(L.heading),
                                 "site_elevation": L.site_elevation,
                                 "latitude_deg": deg(L.latitude),
                                 "longitude_deg": deg(L.longitude),
                                 "site_temperature": L.site_temperature,
                                 "site_pressure": L.site_pressure,
                                 "wind_speed": L.wind_speed,
                                 "wind_from_deg": deg(L.wind_from),
                                 "gravity": L.gravity})
    if L.atmosphere_file is not None:
        when = "" if L.atmosphere_time is None else f", time = {_value(L.atmosphere_time)}"
        lines.insert(len(lines) - 1, f"atmosphere = {{file = {_value(_path(L.atmosphere_file, folder))}{when}}}")
    for rec in rf.recovery:
        # a plugged motor has no charge: its "ejection" chutes open at apogee (vehicle.recovery_of)
        deploy = "apogee" if rec.deploy == "ejection" and m.ejection_delay is not None and \
            math.isinf(m.ejection_delay) else rec.deploy
        lines += _table("[[recovery]]", {"name": rec.name, "cd_area": rec.cd_area,
                                         "deploy": deploy, "lag": rec.lag})
    b = rf.ballast
    lines += _table("[ballast]", {"mass": b.mass, "x": b.x, "x_min": b.x_min,
                                  "x_max": b.x_max, "mass_max": b.mass_max})
    return "\n".join(lines)


def dump_rocket_toml(rf, path) -> Path:
    """Write ``rf`` to ``path`` as rocket TOML (numeric-only); returns the path."""
    path = Path(path)
    path.write_text(to_toml(rf, path.parent), encoding="utf-8")
    return path
