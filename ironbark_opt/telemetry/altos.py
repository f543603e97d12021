"""Altus Metrum AltOS CSV (TeleMega, TeleMetrum, EasyMega; AltosUI export v6).

Header line ``#version,serial,flight,...``; values padded with spaces.
Units (AltOS v6, AltosUI ``AltosCSV``): ``time`` [s] from boost detect,
``height`` [m AGL], ``altitude`` [m MSL] (the first is barometric, a
second one is GPS), ``speed`` [m/s] (Kalman estimate), ``acceleration``
[m/s^2] axial; ``state_name`` boost/fast/coast/drogue/main/landed.
Radio-received (.telem) exports carry ``rssi``/``lqi`` and have gaps.
"""
from __future__ import annotations

import numpy as np

from ironbark_opt.telemetry._text import TextFile, column, split_rows
from ironbark_opt.telemetry.flightlog import FlightLog, build_log

FORMAT = "altos"


def sniff(file: TextFile) -> bool:
    head = file.lines[0] if file.lines else ""
    return head.startswith("#version,") and ",height," in head and ",time," in head


def read(file: TextFile) -> FlightLog:
    rows = split_rows(file, 1, ",")
    col = {name: rows.index(name, file) for name in ("serial", "flight", "time", "height", "altitude",
                                                     "speed", "acceleration", "state_name")}
    t = column(rows, file, col["time"])
    h = column(rows, file, col["height"])
    v = column(rows, file, col["speed"])
    a = column(rows, file, col["acceleration"])
    baro_msl = column(rows, file, col["altitude"])       # first 'altitude': barometric [m MSL]
    state = np.array([r[col["state_name"]] for r in rows.cells])
    first = rows.cells[0]
    radio = "rssi" in rows.header
    device = f"AltOS serial {first[col['serial']]} flight {first[col['flight']]}" + (" (radio)" if radio else "")
    order = np.argsort(t, kind="stable")
    events = {}
    for name, states in (("burnout", ("fast", "coast")), ("drogue", ("drogue",)), ("main", ("main",)),
                         ("landed", ("landed",))):
        hit = np.nonzero(np.isin(state[order], states))[0]
        if hit.size:
            events[name] = float(t[order][hit[0]])
    pad = t <= 0
    ground = float(np.median((baro_msl - h)[pad])) if pad.any() else float(baro_msl[0] - h[0])
    notes = ["duplicate column 'altitude': the first (barometric, m MSL) is used, the second is GPS"]
    if radio:
        notes.append("radio-received telemetry (rssi/lqi columns): low, irregular rate")
    return build_log(file.path, FORMAT, device, t, h, v=v, a=a, events=events,
                     resolution={"altitude": 0.01, "vertical_speed": 0.01, "acceleration": 0.01},
                     ground_elevation=ground, notes=notes, line_numbers=rows.line_numbers)
