"""CATS Vega telemetry as logged by the CATS Ground Station (radio downlink).

``link, ts[deciseconds], state, errors, lat[deg/10000], lon[deg/10000],
altitude[m], velocity[m/s], battery[decivolts], pyro1, pyro2``; two radio
links interleave rows that mostly duplicate each other (a repeated ``ts``
keeps the first row).  Altitude and velocity are the Vega's state estimate
as integers [m], [m/s].  Flight states (CATS firmware ``flight_fsm``):
3 THRUSTING, 4 COASTING, 5 DROGUE, 6 MAIN, 7 TOUCHDOWN; time zero is the
first THRUSTING sample (the Vega's liftoff detection).
"""
from __future__ import annotations

import numpy as np

from ironbark_opt.telemetry._text import TextFile, column, split_rows
from ironbark_opt.telemetry.flightlog import FlightLog, build_log

FORMAT = "cats"
_STATES = {"burnout": 4, "drogue": 5, "main": 6, "touchdown": 7}


def sniff(file: TextFile) -> bool:
    return bool(file.lines) and file.lines[0].replace(" ", "").startswith("link,ts[deciseconds],state")


def read(file: TextFile) -> FlightLog:
    rows = split_rows(file, 1, ",")
    hdr = [h.replace(" ", "") for h in rows.header]
    rows = type(rows)(tuple(hdr), rows.cells, rows.line_numbers, rows.header_line)
    ts = column(rows, file, rows.index("ts[deciseconds]", file), scale=0.1)
    state = column(rows, file, rows.index("state", file))
    h = column(rows, file, rows.index("altitude[m]", file))
    v = column(rows, file, rows.index("velocity[m/s]", file))
    thrust = ts[state >= 3]
    if thrust.size == 0:
        raise file.error("no sample in flight state THRUSTING (3) or later: no flight in this log",
                         line=rows.line_numbers[-1])
    t0 = float(thrust.min())
    events = {name: float(ts[state >= code].min()) - t0 for name, code in _STATES.items() if np.any(state >= code)}
    return build_log(file.path, FORMAT, "CATS Vega (ground-station log)", ts - t0, h, v=v, events=events,
                     resolution={"altitude": 1.0, "vertical_speed": 1.0},
                     notes=["radio downlink: two links interleaved, repeated time stamps dropped",
                            "the ground station misses samples during flight: see gaps"],
                     line_numbers=rows.line_numbers)
