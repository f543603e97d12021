"""The ``[airbrakes]`` and ``[[airstart]]`` sections of the rocket TOML format (docs/rocket-toml.md).

Numeric-only: reads and checks the keys; :func:`airbrake_schedule` turns the
spec into the :class:`~ironbark_opt.aero.airbrakes.BrakeSchedule` the flight
core evaluates.
"""
from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

from ironbark_opt.aero.airbrakes import DRAG_MEANINGS, TRIGGER_UNITS, TRIGGERS, BrakeSchedule, load_controller, read_brake_drag
from ironbark_opt.errors import InputError

AIRBRAKE_KEYS = ("drag", "drag_is", "reference_area", "trigger", "start", "level", "rate", "ramp",
                 "controller", "sampling_rate")


@dataclass(frozen=True)
class AirbrakeSpec:
    """Air brakes as a file describes them (SI; see :mod:`ironbark_opt.aero.airbrakes`).

    Parameters
    ----------
    drag : Path
        ``deployment_level, mach, cd`` CSV, absolute.
    drag_is : {'increment', 'total'}
    reference_area : float or None [m^2]
    trigger : str
    start : float [trigger unit]
    level : float [-]
    rate : float or None [1/s]
    ramp : float or None [trigger unit]
    controller : str or None
        ``"file.py:function"`` with an absolute file path.
    sampling_rate : float or None [Hz]
    """

    drag: Path
    drag_is: str = "increment"
    reference_area: float | None = None
    trigger: str = "time"
    start: float = 0.0
    level: float = 1.0
    rate: float | None = None
    ramp: float | None = None
    controller: str | None = None
    sampling_rate: float | None = None


def read_airbrakes(rd, d) -> AirbrakeSpec:
    """``[airbrakes]`` table -> :class:`AirbrakeSpec`; ``rd`` is the TOML reader
    (errors name the file, line and key)."""
    table = "airbrakes"
    rd.check_keys(d, AIRBRAKE_KEYS, table)
    kw = {"drag": rd.file(d, "drag", table, required=True)}
    for key, choices in (("drag_is", DRAG_MEANINGS), ("trigger", TRIGGERS)):
        if key in d:
            if d[key] not in choices:
                raise rd.error(f"expected one of {', '.join(choices)}, got {d[key]!r}", table, key)
            kw[key] = d[key]
    for key in ("reference_area", "start", "level", "rate", "ramp", "sampling_rate"):
        val = rd.number(d, key, table)
        if val is None:
            continue
        if key != "start" and val <= 0:
            raise rd.error(f"must be > 0, got {val}", table, key)
        if key == "level" and val > 1:
            raise rd.error(f"deployment level must be in (0, 1], got {val}", table, key)
        kw[key] = val
    if "controller" in d:
        spec = d["controller"]
        if not isinstance(spec, str) or ":" not in spec:
            raise rd.error(f"expected 'file.py:function', got {spec!r}", table, "controller")
        file, _, name = spec.rpartition(":")
        path = (rd.path.parent / file).resolve()
        if not path.is_file():
            raise rd.error(f"controller file not found: {path}", table, "controller")
        kw["controller"] = f"{path}:{name}"
    trig = kw.get("trigger", "time")
    need = {"time": ("start", "rate"), "controller": ("controller", "sampling_rate", "rate"),
            "altitude": ("start", "ramp"), "mach": ("start", "ramp"), "vertical_speed": ("start", "ramp")}[trig]
    for key in need:
        if key not in kw:
            raise rd.error(f"missing required key '{key}' for trigger = '{trig}'", table)
    # a time after ignition, an altitude above ground and a Mach number are never negative
    if trig in ("time", "altitude", "mach") and (kw["start"] < 0 or (trig == "mach" and kw["start"] == 0)):
        raise rd.error(f"must be {'> 0' if trig == 'mach' else '>= ' + '0 ' + TRIGGER_UNITS[trig]} for "
                       f"trigger = '{trig}', got {kw['start']}", table, "start")
    try:
        spec = AirbrakeSpec(**kw)
        airbrake_schedule(spec)                  # reads the table: its errors point here
    except InputError as exc:
        if exc.source is not None:
            raise
        raise rd.error(exc.message, table, exc.field) from None
    return spec


def airbrake_schedule(spec: AirbrakeSpec | None) -> BrakeSchedule | None:
    """The flight core's schedule of a spec (None passes through)."""
    if spec is None:
        return None
    drag = read_brake_drag(spec.drag, meaning=spec.drag_is, reference_area=spec.reference_area)
    controller = load_controller(spec.controller) if spec.controller else None
    return BrakeSchedule(drag=drag, trigger=spec.trigger, start=spec.start, level=spec.level, rate=spec.rate,
                         ramp=spec.ramp, controller=controller, sampling_rate=spec.sampling_rate)


AIRSTART_KEYS = ("file", "designation", "nozzle_x", "ignition_time")


def read_airstart(rd, items) -> tuple:
    """``[[airstart]]`` tables -> ((MotorSpec, ignition time [s after launch]), ...):
    further motors of the (single) stage lit in flight, flown with ``[motor]`` as one
    :class:`~ironbark_opt.motors.composite.CompositeMotor`."""
    from ironbark_opt.rocket.specs import MotorSpec

    out = []
    for i, d, label in rd.tables(items, "airstart", AIRSTART_KEYS):
        file = rd.table_file(d, "airstart", i, label, "a thrust-curve path")
        des = d.get("designation")
        if des is not None and not isinstance(des, str):
            raise rd.error(f"expected a string, got {des!r}", "airstart", "designation", i, field=f"{label}.designation")
        nozzle = rd.number(d, "nozzle_x", "airstart", i, label, required=True)
        t_ign = rd.number(d, "ignition_time", "airstart", i, label, required=True)
        if nozzle < 0:
            raise rd.error(f"must be >= 0 m, got {nozzle}", "airstart", "nozzle_x", i, field=f"{label}.nozzle_x")
        if t_ign <= 0:
            raise rd.error(f"must be > 0 s after launch (the [motor] lights at launch), got {t_ign}", "airstart",
                           "ignition_time", i, field=f"{label}.ignition_time")
        out.append((MotorSpec(file=file, designation=des, nozzle_x=nozzle), t_ign))
    return tuple(out)
