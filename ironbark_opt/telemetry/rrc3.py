"""Missile Works RRC3 (mDACS export).

``Time;Altitude;Pressure;Velocity;Temperature;Events;Voltages;`` with
decimal commas, a trailing ``;`` on each row and a final empty row; units
(not in the file; from the data and the mDACS manual): s, m AGL (when the
export is metric), mbar, m/s, degC, V.  mDACS writes rows in text order of
the time string (``1,95 -> 10 -> 100``): they are sorted numerically.
``Events`` holds ``-`` or an event name (``Drogue``, ``Main``).
"""
from __future__ import annotations

import numpy as np

from ironbark_opt.telemetry._text import TextFile, column, split_rows
from ironbark_opt.telemetry.flightlog import FlightLog, build_log

FORMAT = "rrc3"


def sniff(file: TextFile) -> bool:
    return bool(file.lines) and file.lines[0].startswith("Time;Altitude;Pressure;Velocity;")


def read(file: TextFile) -> FlightLog:
    rows = split_rows(file, 1, ";", strip_trailing_sep=True)
    t = column(rows, file, rows.index("Time", file), decimal_comma=True)
    h = column(rows, file, rows.index("Altitude", file), decimal_comma=True)
    v = column(rows, file, rows.index("Velocity", file), decimal_comma=True)
    ev_col = rows.index("Events", file)
    events = {}
    for i, r in enumerate(rows.cells):
        name = r[ev_col].strip().lower()
        if name and name != "-" and name not in events:
            events[name] = float(t[i])
    return build_log(file.path, FORMAT, "Missile Works RRC3", t, h, v=v, events=events,
                     resolution={"altitude": 0.01, "vertical_speed": 0.01},
                     notes=["decimal commas; rows sorted numerically by time"] if np.any(np.diff(t) < 0) else
                     ["decimal commas"], line_numbers=rows.line_numbers)
