"""Any delimited log, given a column map.

``columns`` maps channels to ``(column name, unit)``: ``time`` and
``altitude`` are required, ``vertical_speed`` and ``acceleration``
optional; on the command line ``--columns "time=T:ms,altitude=Alt:ft"``.
Altitude is taken as above ground unless ``altitude_is_agl=False``, in
which case the median of the samples before the first time >= 0 (or the
first sample) is subtracted.  Decimal commas are accepted with
``decimal_comma=True``.
"""
from __future__ import annotations

from typing import Mapping

import numpy as np

from ironbark_opt.errors import InputError
from ironbark_opt.telemetry import units
from ironbark_opt.telemetry._text import TextFile, column, split_rows
from ironbark_opt.telemetry.flightlog import FlightLog, build_log

FORMAT = "generic"


def parse_column_map(text: str) -> dict[str, tuple[str, str]]:
    """``"time=T:ms,altitude=Alt:ft"`` -> ``{"time": ("T", "ms"), ...}``."""
    out = {}
    for part in filter(None, (p.strip() for p in text.split(","))):
        if "=" not in part:
            raise InputError(f"expected CHANNEL=COLUMN[:UNIT], got '{part}'", field="--columns")
        ch, rest = (s.strip() for s in part.split("=", 1))
        if ch not in units.FACTORS:
            raise InputError(f"unknown channel '{ch}'; channels: {', '.join(units.FACTORS)}", field="--columns")
        name, _, unit = rest.partition(":")
        out[ch] = (name.strip(), unit.strip() or {"time": "s", "altitude": "m", "vertical_speed": "m/s",
                                                  "acceleration": "m/s2"}[ch])
        if not out[ch][0]:
            raise InputError(f"no column name for '{ch}' in '{part}'", field="--columns")
        units.factor(ch, out[ch][1], field="--columns")          # an unknown unit names the option
    for req in ("time", "altitude"):
        if req not in out:
            raise InputError(f"the column map needs '{req}' (e.g. time=T:s,altitude=Alt:m)", field="--columns")
    return out


def read(file: TextFile, columns: Mapping[str, tuple[str, str]], *, sep: str | None = None,
         decimal_comma: bool = False, altitude_is_agl: bool = True) -> FlightLog:
    for req in ("time", "altitude"):
        if req not in columns:
            raise InputError(f"the column map needs '{req}'", field="columns")
    head_line = next((k for k, l in enumerate(file.lines) if l.strip() and not l.startswith("#")), None)
    if head_line is None:
        raise file.error("empty file", line=1)
    head = file.lines[head_line]
    if sep is None:
        sep = max((";", ",", "\t"), key=head.count)
    rows = split_rows(file, head_line + 1, sep, strip_trailing_sep=True, comment="#")
    data = {}
    for ch, (name, unit) in columns.items():
        idx = rows.index(name, file)
        data[ch] = column(rows, file, idx, decimal_comma=decimal_comma,
                          scale=units.factor(ch, unit, source=file.path, line=head_line + 1))
    h = data["altitude"]
    if not altitude_is_agl:
        pad = data["time"] < 0
        h = h - (np.median(h[pad]) if pad.any() else h[np.argmin(data["time"])])
    return build_log(file.path, FORMAT, "generic CSV", data["time"], h, v=data.get("vertical_speed"),
                     a=data.get("acceleration"), line_numbers=rows.line_numbers)
