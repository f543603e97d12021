"""Featherweight Blue Raven phone-app CSV (LR / HR export).

Columns include ``Flight_Time_(s)`` [s from liftoff], ``Baro_Altitude_AGL_(feet)``,
``Velocity_Up`` [ft/s, inertial], and 0/1 flag columns (``Liftoff``,
``Burnout_Coast``, ``Apogee``, ``Apo_fired``, ``Main_fired``, ...).  Some
header names repeat (``Reserved``) or contain spaces (``Apo_FER_H  ex``):
columns are looked up by their first occurrence, so repeats are harmless.
``Time`` (``mm:ss.s`` wall clock) is not used.
"""
from __future__ import annotations

from ironbark_opt.telemetry._text import FT, TextFile, column, split_rows
from ironbark_opt.telemetry.flightlog import FlightLog, build_log, transitions

FORMAT = "blueraven"


def sniff(file: TextFile) -> bool:
    head = file.lines[0] if file.lines else ""
    return "Flight_Time_(s)" in head and "Baro_Altitude_AGL_(feet)" in head


def read(file: TextFile) -> FlightLog:
    rows = split_rows(file, 1, ",")
    t = column(rows, file, rows.index("Flight_Time_(s)", file))
    h = column(rows, file, rows.index("Baro_Altitude_AGL_(feet)", file), scale=FT)
    asl = column(rows, file, rows.index("Baro_Altitude_ASL_(feet)", file), scale=FT)
    v = column(rows, file, rows.index("Velocity_Up", file), scale=FT) if "Velocity_Up" in rows.header else None
    events = {}
    for name, key in (("burnout", "Burnout_Coast"), ("drogue", "Apo_fired"), ("main", "Main_fired")):
        if key in rows.header:
            te = transitions(t, column(rows, file, rows.index(key, file)) > 0.5)
            if te is not None:
                events[name] = te
    pad = t <= 0
    ground = float((asl - h)[pad].mean()) if pad.any() else None
    return build_log(file.path, FORMAT, "Featherweight Blue Raven", t, h, v=v, events=events,
                     resolution={"altitude": 0.1 * FT, "vertical_speed": 0.1 * FT}, ground_elevation=ground,
                     notes=["repeated header names (Reserved, ...) looked up by first occurrence"],
                     line_numbers=rows.line_numbers)
