"""PerfectFlite StratoLogger / Pnut: ``.pf2`` (DataCap save) and DataCap text export.

``.pf2``: ``Key: value`` header lines (``Apogee: N' AGL``, ``Ground
Elevation: N' MSL``, ``Drogue At: T Seconds``, ``Main At: ...``), then
``Data: (Time, Altitude, Velocity, Temperature (F|C), Voltage)`` and rows
``t, alt, vel, temp, volt`` — time [s] from launch detect, altitude [ft AGL],
velocity [ft/s] (baro-derived).  The file may be named ``.csv``.
DataCap export: tab-separated ``Time  Altitude  Temp.  Voltage``,
temperature written ``58.7F``; no velocity, no metadata.  20 Hz, 1 ft steps.
"""
from __future__ import annotations

import re

from ironbark_opt.telemetry._text import FT, TextFile, column, header_value, split_rows
from ironbark_opt.telemetry.flightlog import FlightLog, build_log

FORMAT = "perfectflite"


def sniff(file: TextFile) -> bool:
    head = file.lines[0] if file.lines else ""
    if head.startswith("PerfectFlite") or any(l.startswith("Data: (Time") for l in file.lines[:40]):
        return True
    return re.match(r"Time\tAltitude\tTemp", head) is not None


def _feet(text: str) -> float | None:
    m = re.match(r"\s*(-?[\d.]+)\s*'", text)
    return float(m.group(1)) * FT if m else None


def _seconds(text: str) -> float | None:
    m = re.match(r"\s*(-?[\d.]+)\s*Seconds", text)
    return float(m.group(1)) if m else None


def read(file: TextFile) -> FlightLog:
    res = {"altitude": 1 * FT, "vertical_speed": 1 * FT}
    if file.lines[0].startswith("Time\t"):
        rows = split_rows(file, 1, "\t")
        t = column(rows, file, 0)
        h = column(rows, file, 1, scale=FT)
        return build_log(file.path, FORMAT, "PerfectFlite (DataCap export)", t, h, resolution=res,
                         notes=["DataCap tab-separated export: no velocity, no metadata"],
                         line_numbers=rows.line_numbers)
    data = next((k for k, l in enumerate(file.lines) if l.startswith("Data:")), None)
    if data is None:
        raise file.error("no 'Data: (Time, Altitude, ...)' line: not a complete .pf2 file", line=len(file.lines))
    # The 'Data:' line names the 5 columns; rows are ', '-separated.
    rows = split_rows(file, data + 1, ",")
    t = column(rows, file, 0)
    h = column(rows, file, 1, scale=FT)
    v = column(rows, file, 2, scale=FT)
    model = file.lines[0].strip()
    serial = header_value(file, "Serial Number", "Data:")
    flight = header_value(file, "Flight Number", "Data:")
    device = model + (f" serial {serial[0]}" if serial else "") + (f" flight {flight[0]}" if flight else "")
    apo = header_value(file, "Apogee", "Data:")
    ground = header_value(file, "Ground Elevation", "Data:")
    events = {}
    for key, name in (("Drogue At", "drogue"), ("Main At", "main")):
        hv = header_value(file, key, "Data:")
        if hv and _seconds(hv[0]) is not None:
            events[name] = _seconds(hv[0])
    return build_log(file.path, FORMAT, device, t, h, v=v, events=events, resolution=res,
                     ground_elevation=_feet(ground[0]) if ground else None,
                     device_apogee=_feet(apo[0]) if apo else None, line_numbers=rows.line_numbers)
