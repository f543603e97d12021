"""The liquid / hybrid parts of ``[motor]`` in the rocket TOML format (docs/rocket-toml.md).

``kind = "hybrid" | "liquid"``, ``ignition_time``, ``[motor.grain]`` and
``[[motor.tank]]`` tables.  Numeric-only: reads and checks the keys, reads
the tanks' schedule files (errors name the file, line and key) and returns
ready :class:`~ironbark_opt.motors.tanks.Tank` objects;
:func:`tank_motor` builds the :class:`~ironbark_opt.motors.tank_motor.TankMotor`.
"""
from __future__ import annotations

import numpy as np

from ironbark_opt.errors import InputError
from ironbark_opt.motors.tanks import SCHEDULES, tank_from_schedule

MOTOR_KINDS = ("solid", "hybrid", "liquid")
TANK_KEYS = ("name", "position", "radius", "length", "liquid_density", "gas_density", "schedule",
             "liquid_mass", "gas_mass", "liquid_mass_flow", "gas_mass_flow", "flow_start",
             "flow_end", "file")
GRAIN_KEYS = ("count", "density", "outer_radius", "inner_radius", "height", "separation", "position")
#: Overrides a liquid or hybrid motor takes (its propellant comes from tanks and grain).
TANK_MOTOR_OVERRIDES = ("dry_mass", "dry_cg", "dry_inertia", "nozzle_exit_area")

#: Keys each schedule uses besides the geometry and fluids.
SCHEDULE_KEYS = {"mass_flow": ("liquid_mass", "gas_mass", "liquid_mass_flow", "gas_mass_flow",
                               "flow_start", "flow_end", "file"),
                 "mass": ("file",), "ullage": ("file",), "level": ("file",),
                 "thrust": ("liquid_mass", "gas_mass")}
_COMMON = ("name", "position", "radius", "length", "liquid_density", "gas_density", "schedule")

#: Columns of a schedule file, by schedule: (required, optional).
FILE_COLUMNS = {"mass_flow": (("time_s", "liquid_kg_s"), ("gas_kg_s",)),
                "mass": (("time_s", "liquid_kg"), ("gas_kg",)),
                "ullage": (("time_s", "ullage_m3"), ()),
                "level": (("time_s", "level_m"), ())}


def read_schedule_file(path, schedule):
    """``time_s, ...`` CSV of a tank schedule -> (time [s], [columns]) (numeric-only).

    A header row names the columns (:data:`FILE_COLUMNS`); ``#`` lines are comments."""
    from ironbark_opt.motors.rasp import parse_number, read_text
    from ironbark_opt.motors.thrust_csv import _key, _split

    required, optional = FILE_COLUMNS[schedule]
    cols, rows = None, []
    for n, raw in enumerate(read_text(path).splitlines(), start=1):
        line = raw.strip()
        if not line or line[0] == "#":
            continue
        cells = _split(line)
        if cols is None:
            keys = [_key(c) for c in cells]
            missing = [c for c in required if c not in keys]
            if missing:
                raise InputError(f"schedule {schedule!r} needs a header with columns "
                                 f"{', '.join(required + optional)}; missing {', '.join(missing)}",
                                 source=path, line=n, field=missing[0])
            cols = [keys.index(c) for c in required] + [keys.index(c) for c in optional if c in keys]
            names = [keys[i] for i in cols]
            continue
        if len(cells) < len(keys):
            raise InputError(f"expected {len(keys)} columns, got {len(cells)}", source=path,
                             line=n, field="data")
        row = [parse_number(cells[i], source=path, line=n, field=names[j]) for j, i in enumerate(cols)]
        if rows and row[0] <= rows[-1][0]:
            raise InputError(f"time must increase: {row[0]} s after {rows[-1][0]} s", source=path,
                             line=n, field="time_s")
        if row[0] < 0 or any(x < 0 for x in row[1:]):
            raise InputError(f"negative value in {line!r}", source=path, line=n, field="data")
        rows.append(row)
    if len(rows) < 2:
        raise InputError("a schedule file needs at least two data rows", source=path, field="data")
    a = np.array(rows)
    return a[:, 0], [a[:, k] for k in range(1, a.shape[1])]


def _flow(rd, d, key, table, occ, label, start, end):
    """A constant outflow [kg/s] over [flow_start, flow_end] as a rate table."""
    rate = rd.number(d, key, table, occ, label)
    if rate is None or rate == 0:
        return None
    if rate < 0:
        raise rd.error(f"must be >= 0 kg/s, got {rate}", table, key, occ, field=f"{label}.{key}")
    if end is None:
        raise rd.error(f"a constant {key} needs flow_end [s]", table, key, occ, field=f"{label}.flow_end")
    t = [0.0, start, start, end, end] if start > 0 else [0.0, end, end]
    r = [0.0, 0.0, rate, rate, 0.0] if start > 0 else [rate, rate, 0.0]
    # a step is a ramp of 1 us (the rate tables are linear, times must increase)
    t = np.array(t) + 1e-6 * np.r_[0, np.cumsum(np.diff(t) == 0)]
    return t, np.array(r)


def read_tanks(rd, items):
    """``[[motor.tank]]`` tables -> tuple of Tank."""
    table = "motor.tank"
    if not isinstance(items, list) or not items:
        raise rd.error("expected [[motor.tank]] tables", table)
    tanks = []
    for i, d in enumerate(items):
        label = f"motor.tank[{i}]"
        rd.check_keys(d, TANK_KEYS, table, i, label)
        name = d.get("name", f"tank{i + 1}")
        if not isinstance(name, str):
            raise rd.error(f"expected a string, got {name!r}", table, "name", i, field=f"{label}.name")
        kw = {"name": name}
        for key in ("position", "radius", "length", "liquid_density", "gas_density"):
            kw[key] = rd.number(d, key, table, i, label, required=True)
            if kw[key] <= 0 and key != "position":
                raise rd.error(f"must be > 0, got {kw[key]}", table, key, i, field=f"{label}.{key}")
        schedule = d.get("schedule", "mass_flow")
        if schedule not in SCHEDULES:
            raise rd.error(f"expected one of {', '.join(SCHEDULES)}, got {schedule!r}", table,
                           "schedule", i, field=f"{label}.schedule")
        kw["schedule"] = schedule
        for key in d:
            if key not in _COMMON and key not in SCHEDULE_KEYS[schedule]:
                raise rd.error(f"'{key}' is not used by schedule = '{schedule}' (it uses "
                               f"{', '.join(SCHEDULE_KEYS[schedule])})", table, key, i,
                               field=f"{label}.{key}")
        if "file" in d and ("liquid_mass_flow" in d or "gas_mass_flow" in d):
            raise rd.error("give the outflow as a file or as constant rates, not both", table,
                           "file", i, field=f"{label}.file")
        for key in ("liquid_mass", "gas_mass", "flow_start", "flow_end"):
            val = rd.number(d, key, table, i, label)
            if val is not None and val < 0:
                raise rd.error(f"must be >= 0, got {val}", table, key, i, field=f"{label}.{key}")
            if val is not None and key in ("liquid_mass", "gas_mass"):
                kw[key] = val
        if schedule in ("mass_flow", "thrust") and "liquid_mass" not in kw:
            raise rd.error(f"missing required key 'liquid_mass' for schedule = '{schedule}'",
                           table, None, i, field=f"{label}.liquid_mass")
        start = rd.number(d, "flow_start", table, i, label, default=0.0)
        end = rd.number(d, "flow_end", table, i, label)
        if end is not None and end <= start:
            raise rd.error(f"flow_end {end} s must be after flow_start {start} s", table, "flow_end",
                           i, field=f"{label}.flow_end")
        path = None
        if "file" in d:
            path = _tank_file(rd, d, table, i, label)
        if schedule == "mass_flow":
            if path is not None:
                t, cols = read_schedule_file(path, schedule)
                kw["liquid_flow"] = (t, cols[0])
                kw["gas_flow"] = (t, cols[1]) if len(cols) > 1 else None
            else:
                kw["liquid_flow"] = _flow(rd, d, "liquid_mass_flow", table, i, label, start, end)
                kw["gas_flow"] = _flow(rd, d, "gas_mass_flow", table, i, label, start, end)
        elif schedule in FILE_COLUMNS:
            if path is None:
                raise rd.error(f"schedule = '{schedule}' needs file = a CSV with columns "
                               f"{', '.join(sum(FILE_COLUMNS[schedule], ()))}", table, "schedule",
                               i, field=f"{label}.file")
            kw["table"] = read_schedule_file(path, schedule)
        try:
            tanks.append(tank_from_schedule(source=str(path) if path else None, **kw))
        except InputError as exc:
            if exc.source is not None and exc.line is not None:
                raise
            key = exc.field.split(": ")[-1] if exc.field else None
            raise rd.error(exc.message, table, key if key in d else None, i,
                           field=f"{label}.{key}" if key else label) from None
    return tuple(tanks)


def _tank_file(rd, d, table, i, label):
    if not isinstance(d["file"], str):
        raise rd.error(f"expected a file path string, got {d['file']!r}", table, "file", i,
                       field=f"{label}.file")
    p = (rd.path.parent / d["file"]).resolve()
    if not p.is_file():
        raise rd.error(f"file not found: {p}", table, "file", i, field=f"{label}.file")
    return p


def read_grain(rd, d):
    """``[motor.grain]`` -> dict of :class:`~ironbark_opt.motors.grains.Grains`
    keywords plus ``position`` [m fwd of the nozzle exit]."""
    table = "motor.grain"
    rd.check_keys(d, GRAIN_KEYS, table)
    g = {}
    for key in GRAIN_KEYS:
        val = rd.number(d, key, table, required=key not in ("separation", "count"),
                        default=1.0 if key == "count" else 0.0)
        if key == "count" and (val != int(val) or val < 1):
            raise rd.error(f"expected a whole number >= 1, got {d[key]!r}", table, key)
        if val < 0 or (val == 0 and key not in ("inner_radius", "separation", "position")):
            raise rd.error(f"must be > 0, got {val}", table, key)
        g[key] = int(val) if key == "count" else val
    if g["inner_radius"] >= g["outer_radius"]:
        raise rd.error("inner_radius must be smaller than outer_radius", table, "inner_radius")
    return g


def tank_motor(spec):
    """The :class:`~ironbark_opt.motors.tank_motor.TankMotor` a hybrid/liquid
    :class:`~ironbark_opt.rocket.specs.MotorSpec` describes (numeric-only)."""
    from ironbark_opt.motors import load_motor
    from ironbark_opt.motors.grains import Grains
    from ironbark_opt.motors.tank_motor import TankMotor

    ov = spec.overrides
    missing = [k for k in ("dry_mass", "dry_cg", "dry_inertia") if k not in ov]
    if missing:
        raise InputError(f"a {spec.kind} motor needs [motor.overrides] {', '.join(missing)}",
                         source=spec.file, field=f"motor.overrides.{missing[0]}")
    grain = None
    grain_position = 0.0
    if spec.grain is not None:
        gk = dict(spec.grain)
        grain_position = gk.pop("position")
        grain = Grains(**gk)
    tanks = spec.tanks
    # envelope: the widest tank or grain; from the nozzle to the forward-most end
    radius = max([k.radius for k in tanks] + ([grain.outer_radius] if grain else []))
    length = max([k.position + k.length / 2.0 for k in tanks]
                 + ([grain_position + grain.stack_length / 2.0] if grain else []))
    m_prop = sum(k.initial_mass for k in tanks) + (grain.mass if grain else 0.0)
    curve = load_motor(spec.file, spec.designation, propellant_mass=m_prop,
                       dry_mass=ov["dry_mass"], diameter=2.0 * radius, length=length)
    return TankMotor(curve=curve, tanks=tanks, dry_mass=ov["dry_mass"], dry_cg=ov["dry_cg"],
                     dry_inertia=tuple(ov["dry_inertia"]), grain=grain,
                     grain_position=grain_position, ignition_time=spec.ignition_time,
                     diameter=2.0 * radius, length=length,
                     nozzle_exit_area=ov.get("nozzle_exit_area"))
