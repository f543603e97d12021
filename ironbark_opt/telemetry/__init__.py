"""Flight-log import: one reader per device family, detected from content.

``read_log(path) -> FlightLog`` picks the reader whose ``sniff`` accepts
the file's first lines (never the file name); a file none accepts, or one
that is truncated or malformed, raises :class:`~ironbark_opt.errors.InputError`
naming the file and line.  ``read_log(path, columns=...)`` reads any
delimited log through :mod:`~ironbark_opt.telemetry.generic`.

Readers: :mod:`altos` (TeleMega, TeleMetrum, EasyMega), :mod:`perfectflite`
(StratoLogger, Pnut .pf2 and DataCap text), :mod:`eggtimer` (incl. TRS),
:mod:`rrc3` (Missile Works), :mod:`featherweight` (Blue Raven),
:mod:`cats` (CATS Vega ground station), :mod:`openrocket_csv`
(OpenRocket's CSV export).
"""
from __future__ import annotations

from typing import Mapping

from ironbark_opt.errors import InputError
from ironbark_opt.telemetry import altos, cats, eggtimer, featherweight, generic, openrocket_csv, perfectflite, rrc3
from ironbark_opt.telemetry._text import read_text
from ironbark_opt.telemetry.flightlog import CHANNELS, FlightLog, build_log, detect_liftoff

READERS = (altos, perfectflite, eggtimer, rrc3, featherweight, cats, openrocket_csv)
FORMATS = tuple(r.FORMAT for r in READERS)


def detect_format(path) -> str:
    """Name of the reader that recognises ``path`` (InputError if none does)."""
    file = read_text(path)
    return _detect(file).FORMAT


def _detect(file):
    if not file.lines:
        raise InputError("empty file: not a flight log", source=file.path, line=1)
    for reader in READERS:
        if reader.sniff(file):
            return reader
    first = file.lines[0][:60]
    raise InputError(f"not a flight log this tool can read (first line {first!r}); known formats: "
                     f"{', '.join(FORMATS)}; or give a column map (--columns time=COL:s,altitude=COL:m)",
                     source=file.path, line=1)


def read_log(path, *, format: str | None = None, columns: Mapping[str, tuple[str, str]] | str | None = None,
             **generic_options) -> FlightLog:
    """Read a flight log file.

    Parameters
    ----------
    path : str or path-like
    format : str, optional
        Force a reader (one of ``FORMATS``) instead of detecting it.
    columns : mapping channel -> (column, unit), or ``"time=T:ms,altitude=Alt:ft"``
        Read as a generic delimited log with this column map.

    Returns
    -------
    FlightLog
    """
    file = read_text(path)
    if columns is not None:
        if isinstance(columns, str):
            columns = generic.parse_column_map(columns)
        return generic.read(file, columns, **generic_options)
    if format is not None:
        by_name = {r.FORMAT: r for r in READERS}
        if format not in by_name:
            raise InputError(f"unknown log format '{format}'; known: {', '.join(FORMATS)}", field="--format")
        return by_name[format].read(file)
    return _detect(file).read(file)


__all__ = ["CHANNELS", "FORMATS", "FlightLog", "build_log", "detect_format", "detect_liftoff", "read_log"]
