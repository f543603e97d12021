"""OpenRocket's "Export as CSV" of a simulation.

Comment lines start with ``#``; one of them is the field header
``# Time (s),Altitude (m),Vertical velocity (m/s),Vertical acceleration
(m/s²),...`` with units in parentheses (whatever unit set the user chose),
and events are comments ``# Event APOGEE occurred at t=20.41 seconds``.
Altitude is above the launch site.  The field separator is the user's
choice (``,`` ``;`` or tab).
"""
from __future__ import annotations

import re

import numpy as np

from ironbark_opt.telemetry import units
from ironbark_opt.telemetry._text import Rows, TextFile, column
from ironbark_opt.telemetry.flightlog import FlightLog, build_log

FORMAT = "openrocket"
_HEADER = re.compile(r"^#\s*Time \(([^)]*)\)")
_EVENT = re.compile(r"Event\s+(\w+)\s+occurred at t=([-+\d.eE]+)")
_FIELDS = {"altitude": "Altitude", "vertical_speed": "Vertical velocity", "acceleration": "Vertical acceleration"}
_EVENTS = {"BURNOUT": "burnout", "APOGEE": "apogee_event", "RECOVERY_DEVICE_DEPLOYMENT": "deployment",
           "LAUNCHROD": "rail_exit", "GROUND_HIT": "landed", "LIFTOFF": "liftoff_event"}


def _header_line(file: TextFile):
    return next((k for k, l in enumerate(file.lines[:200]) if _HEADER.match(l)), None)


def sniff(file: TextFile) -> bool:
    return _header_line(file) is not None


def read(file: TextFile) -> FlightLog:
    k = _header_line(file)
    head = file.lines[k].lstrip("#").strip()
    sep = "\t" if "\t" in head else (";" if ";" in head else ",")
    names = [c.strip() for c in head.split(sep)]
    fields = {}
    for i, n in enumerate(names):
        m = re.match(r"(.*?)\s*\(([^)]*)\)\s*$", n)
        if m:
            fields.setdefault(m.group(1), (i, m.group(2)))
    cells, numbers, events = [], [], {}
    for j in range(k + 1, len(file.lines)):
        line = file.lines[j].strip()
        if not line:
            continue
        if line.startswith("#"):
            m = _EVENT.search(line)
            if m and m.group(1) in _EVENTS:
                events.setdefault(_EVENTS[m.group(1)], float(m.group(2)))
            continue
        row = [c.strip() for c in line.split(sep)]
        if len(row) < len(names):
            raise file.error(f"row has {len(row)} of the header's {len(names)} fields (truncated file?)",
                             line=j + 1)
        cells.append(row)
        numbers.append(j + 1)
    if not cells:
        raise file.error("no data rows after the header", line=k + 1)
    rows = Rows(tuple(names), cells, numbers, k + 1)
    t_i, t_unit = fields["Time"]
    t = column(rows, file, t_i, scale=units.factor("time", t_unit, source=file.path, line=k + 1))
    if "Altitude" not in fields:
        raise file.error("the export has no 'Altitude' field: export it from OpenRocket", line=k + 1,
                         field="Altitude")
    out = {}
    for ch, label in _FIELDS.items():
        if label in fields:
            i, unit = fields[label]
            vals = column(rows, file, i, scale=units.factor(ch, unit, source=file.path, line=k + 1))
            out[ch] = vals
    ok = np.isfinite(out["altitude"])
    out = {c: v[ok] for c, v in out.items()}
    return build_log(file.path, FORMAT, "OpenRocket simulation export", t[ok], out["altitude"],
                     v=out.get("vertical_speed"), a=out.get("acceleration"), events=events,
                     notes=["simulated data (OpenRocket), not a measurement"], line_numbers=numbers)
