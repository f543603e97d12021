"""Radiosonde soundings from the University of Wyoming, as profile columns.

Two access paths, tried in order by :func:`fetch_sounding`:

1. the current service, ``{uwyo}/wsgi/sounding?...&type=TEXT:CSV`` — CSV with
   named, unit-suffixed columns (``pressure_hPa``, ``geopotential height_m``,
   ``temperature_C``, ``wind direction_degree``, ``wind speed_m/s``), blanks
   for missing values; HTTP 404 with a one-line message when there is no
   data;
2. the legacy ``{uwyo}/cgi-bin/sounding?...&TYPE=TEXT:LIST`` page — HTML with a
   fixed-width ``<PRE>`` table (7 characters per column; wind in knots) and
   a station block giving the station elevation.

Both parsers also read saved files (:func:`read_uwyo_csv`,
:func:`read_uwyo_text_list`).  Columns are matched by name, never by
position.  Radiosonde heights are geopotential; they are converted to
geometric height at the station latitude.  Numeric-only (I/O).
"""
from __future__ import annotations

import html
import math
import re
from datetime import datetime, timezone
from pathlib import Path

import numpy as np

from ironbark_opt import net
from ironbark_opt.atmosphere.base import wind_from_speed_direction
from ironbark_opt.atmosphere.levels import ProfileColumns, build_columns, geometric_height
from ironbark_opt.errors import InputError, NetworkError

#: One international knot [m/s] (1852 m per hour, exact).
KNOT = 1852.0 / 3600.0
SOURCE = "University of Wyoming soundings"


def _norm(name: str) -> str:
    return re.sub(r"[^a-z0-9/%_]", "", name.lower())


_CSV_COLUMNS = {"pressure": "pressure_hpa", "height": "geopotentialheight_m",
                "temperature": "temperature_c", "direction": "winddirection_degree",
                "speed": "windspeed_m/s", "time": "time", "latitude": "latitude",
                "longitude": "longitude"}


def read_uwyo_csv(text: str | bytes, *, source: str = "UWyo CSV") -> ProfileColumns:
    """Parse the UWyo CSV sounding service's response (or a saved copy).

    Parameters
    ----------
    text : str or bytes
        The CSV text.
    source : str
        Names the input in messages (URL or file name).

    Raises
    ------
    InputError
        Missing columns (named), unparsable numbers (with the line), or fewer
        than two usable levels.
    """
    if isinstance(text, bytes):
        text = text.decode("utf-8", "replace")
    lines = [ln for ln in text.splitlines() if ln.strip()]
    if not lines or "," not in lines[0]:
        raise InputError("not a CSV sounding (no header line)", source=source, line=1)
    header = [_norm(h) for h in lines[0].split(",")]
    index = {}
    for key, want in _CSV_COLUMNS.items():
        if want not in header:
            if key in ("time", "latitude", "longitude"):
                continue
            raise InputError(f"missing column {want!r} (header: {lines[0].strip()})",
                             source=source, line=1)
        index[key] = header.index(want)
    rows = []
    for n, line in enumerate(lines[1:], start=2):
        cells = line.split(",")
        if len(cells) != len(header):
            raise InputError(f"expected {len(header)} fields, got {len(cells)} "
                             "(truncated response?)", source=source, line=n)
        row = {}
        for key, i in index.items():
            cell = cells[i].strip()
            if key == "time":
                row[key] = cell
                continue
            try:
                row[key] = float(cell) if cell else math.nan
            except ValueError:
                raise InputError(f"not a number: {cell!r}", source=source, line=n,
                                 field=lines[0].split(",")[i].strip()) from None
        rows.append(row)
    if not rows:
        raise InputError("the sounding has no data rows", source=source)
    col = {k: np.array([r[k] for r in rows], dtype=float)
           for k in index if k != "time"}
    lat = _valid_position(col.get("latitude"), -90, 90)
    lon = _valid_position(col.get("longitude"), -180, 180)
    valid = None
    if "time" in index and rows[0]["time"]:
        try:
            valid = datetime.strptime(rows[0]["time"], "%Y-%m-%d %H:%M:%S").replace(
                tzinfo=timezone.utc)
        except ValueError:
            raise InputError(f"unreadable time {rows[0]['time']!r}", source=source, line=2,
                             field="time") from None
    return _columns(col["pressure"] * 100.0, col["height"], col["temperature"] + 273.15,
                    col["direction"], col["speed"], source=source, latitude=lat,
                    longitude=lon, valid_time=valid, ground=None)


def _valid_position(values, lo, hi):
    if values is None:
        return None
    ok = values[np.isfinite(values) & (values >= lo) & (values <= hi)]   # -99.99 = missing
    return math.radians(float(ok[0])) if ok.size else None


def _columns(p, H, T, direction_deg, speed, *, source, latitude, longitude, valid_time,
             ground):
    z = geometric_height(H, latitude)
    east, north = wind_from_speed_direction(speed, np.radians(direction_deg))
    if ground is None:
        finite = np.isfinite(z) & np.isfinite(p)
        if not finite.any():
            raise InputError("no level with both pressure and height", source=source)
        ground = float(np.min(z[finite]))   # the first level of a sounding is the surface
    missing = int(np.sum(~(np.isfinite(T) & np.isfinite(east) & np.isfinite(north))))
    notes = (f"{missing} level(s) with missing values dropped",) if missing else ()
    return build_columns(p, z, T, east, north, source=source, ground_elevation=ground,
                         valid_time=valid_time, latitude=latitude, longitude=longitude,
                         notes=notes)


_PRE = re.compile(r"<PRE>(.*?)</PRE>", re.S | re.I)


def read_uwyo_text_list(text: str | bytes, *, source: str = "UWyo TEXT:LIST") -> ProfileColumns:
    """Parse the legacy UWyo ``TEXT:LIST`` HTML page (or a saved copy).

    The first ``<PRE>`` block is the table (header names, a units line, then
    7-character columns: PRES hPa, HGHT m, TEMP C, DRCT deg, SKNT knot, ...);
    the second holds ``Station elevation``, ``Station latitude`` and
    ``Observation time``.  Levels below the station are dropped.
    """
    if isinstance(text, bytes):
        text = text.decode("utf-8", "replace")
    blocks = _PRE.findall(text)
    if not blocks:
        msg = re.sub(r"<[^>]+>", " ", text)
        msg = " ".join(msg.split())[:160]
        raise InputError(f"no sounding table (<PRE>) in the page: {msg!r}", source=source)
    lines = html.unescape(blocks[0]).splitlines()
    dash = [i for i, ln in enumerate(lines) if ln.strip().startswith("----")]
    if len(dash) < 2:
        raise InputError("sounding table without its dashed header", source=source)
    names = lines[dash[0] + 1].split()
    units = lines[dash[0] + 2].split()
    width = 7
    need = {"PRES": "hPa", "HGHT": "m", "TEMP": "C", "DRCT": "deg", "SKNT": "knot"}
    for name, unit in need.items():
        if name not in names:
            raise InputError(f"missing column {name} (columns: {' '.join(names)})",
                             source=source, field=name)
        if units[names.index(name)] != unit:
            raise InputError(f"column {name} in {units[names.index(name)]!r}, expected {unit}",
                             source=source, field=name)
    data = {n: [] for n in need}
    for k, line in enumerate(lines[dash[1] + 1:], start=dash[1] + 2):
        if not line.strip():
            continue
        for name in need:
            j = names.index(name)
            cell = line[j * width:(j + 1) * width].strip()
            try:
                data[name].append(float(cell) if cell else math.nan)
            except ValueError:
                raise InputError(f"not a number: {cell!r}", source=source, line=k,
                                 field=name) from None
    info = {}
    if len(blocks) > 1:
        for line in html.unescape(blocks[1]).splitlines():
            key, _, val = line.partition(":")
            info[key.strip().lower()] = val.strip()
    col = {n: np.array(v, dtype=float) for n, v in data.items()}
    lat = _float_or_none(info.get("station latitude"))
    lon = _float_or_none(info.get("station longitude"))
    elev = _float_or_none(info.get("station elevation"))
    valid = None
    if info.get("observation time"):
        try:
            valid = datetime.strptime(info["observation time"], "%y%m%d/%H%M").replace(
                tzinfo=timezone.utc)
        except ValueError:
            valid = None
    lat_r = None if lat is None else math.radians(lat)
    ground = None if elev is None else float(geometric_height(elev, lat_r))
    return _columns(col["PRES"] * 100.0, col["HGHT"], col["TEMP"] + 273.15, col["DRCT"],
                    col["SKNT"] * KNOT, source=source, latitude=lat_r,
                    longitude=None if lon is None else math.radians(lon), valid_time=valid,
                    ground=ground)


def _float_or_none(s):
    try:
        return float(s)
    except (TypeError, ValueError):
        return None


def read_sounding(path: str | Path) -> ProfileColumns:
    """Read a saved UWyo sounding (CSV or TEXT:LIST HTML), detected by content."""
    path = Path(path)
    text = path.read_text(encoding="utf-8", errors="replace")
    if "<PRE>" in text.upper():
        return read_uwyo_text_list(text, source=str(path))
    return read_uwyo_csv(text, source=str(path))


def fetch_sounding(station: str | int, time: datetime) -> ProfileColumns:
    """Download a sounding: the CSV service first, then the legacy page.

    Parameters
    ----------
    station : str or int
        WMO station number (``72357``) or identifier the service accepts.
    time : datetime
        Launch time of the sounding (UTC; naive datetimes are taken as UTC).

    Raises
    ------
    NetworkError
        Both paths failed; the message lists each URL and its failure.
    """
    if time.tzinfo is not None:
        time = time.astimezone(timezone.utc).replace(tzinfo=None)
    base = net.endpoint("uwyo")
    errors = []
    paths = (
        (f"{base}/wsgi/sounding",
         {"datetime": time.strftime("%Y-%m-%d %H:%M:%S"), "id": str(station),
          "type": "TEXT:CSV"},
         lambda b, url: read_uwyo_csv(b, source=url)),
        (f"{base}/cgi-bin/sounding",
         {"region": "naconf", "TYPE": "TEXT:LIST", "YEAR": time.strftime("%Y"),
          "MONTH": time.strftime("%m"), "FROM": time.strftime("%d%H"),
          "TO": time.strftime("%d%H"), "STNM": str(station)},
         lambda b, url: read_uwyo_text_list(b, source=url)),
    )
    for url, params, parser in paths:
        try:
            return net.fetch(SOURCE, url, params=params,
                             parse=lambda b, u=url, f=parser: f(b, u)).data
        except NetworkError as err:
            errors.append(str(err))
    raise NetworkError(f"no sounding for station {station} at {time:%Y-%m-%d %H:%M}Z from "
                       "either UWyo service:\n  " + "\n  ".join(errors))
