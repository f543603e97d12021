"""Eggtimer (Quasar, Proton, TRS, ...) flight CSV.

Columns ``T,Alt,Veloc,Filt_Alt,FVeloc,LDA,LowV,Apogee,N-O,Drogue,Main``;
``T`` [ms] at 50 ms steps, ``Alt`` [ft AGL], ``Veloc`` [ft/s] raw
difference, ``Filt_Alt``/``FVeloc`` filtered; event columns are 0 except on
the row where the event fired (they then hold the altitude [ft]).  The
delimiter is ``,`` or ``;``.  Some exports write ``Veloc``, ``Filt_Alt`` and
``FVeloc`` as integers x100: detected when the median of
``Filt_Alt / Alt`` over the climb is above 20 (a filter cannot exceed the
altitude it filters by that much) and divided back.
"""
from __future__ import annotations

import numpy as np

from ironbark_opt.telemetry._text import FT, TextFile, column, split_rows
from ironbark_opt.telemetry.flightlog import FlightLog, build_log

FORMAT = "eggtimer"
_COLS = ("T", "Alt", "Veloc", "Filt_Alt", "FVeloc")


def _sep(line: str) -> str:
    return ";" if line.count(";") > line.count(",") else ","


def sniff(file: TextFile) -> bool:
    head = file.lines[0] if file.lines else ""
    cells = [c.strip() for c in head.split(_sep(head))]
    return cells[:5] == list(_COLS)


def read(file: TextFile) -> FlightLog:
    rows = split_rows(file, 1, _sep(file.lines[0]))
    t = column(rows, file, rows.index("T", file)) / 1000.0
    alt_ft = column(rows, file, rows.index("Alt", file))
    filt = column(rows, file, rows.index("Filt_Alt", file))
    fvel = column(rows, file, rows.index("FVeloc", file))
    notes = []
    climb = alt_ft > 50.0
    if climb.sum() > 5 and np.median(filt[climb] / alt_ft[climb]) > 20.0:
        fvel = fvel / 100.0
        notes.append("Veloc, Filt_Alt, FVeloc written as integers x100: divided by 100")
    events, device_apogee = {}, None
    for name, key in (("launch_detect", "LDA"), ("apogee_event", "Apogee"), ("nose_over", "N-O"),
                      ("drogue", "Drogue"), ("main", "Main")):
        if key not in rows.header:
            continue
        val = column(rows, file, rows.index(key, file))
        fired = np.nonzero(val[1:] != 0)[0] + 1        # the first row holds power-up values
        if fired.size:
            events[name] = float(t[fired[0]])
            if key == "Apogee":
                device_apogee = float(val[fired[0]]) * FT
    return build_log(file.path, FORMAT, "Eggtimer", t, alt_ft * FT, v=fvel * FT,
                     events=events, resolution={"altitude": FT, "vertical_speed": 0.01 * FT},
                     device_apogee=device_apogee, notes=notes, line_numbers=rows.line_numbers)
