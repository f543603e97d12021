"""NOAA GRIB2 forecasts: NOMADS filter and public-archive ``.idx`` byte ranges.

Two access paths to the same GRIB2 files:

- the NOMADS "grib filter" CGI (``{nomads}/cgi-bin/filter_gfs_0p25.pl``,
  ``filter_rap.pl``), which cuts variables, levels and a lat/lon box out of a
  run file on the server;
- the NOAA public cloud archives (``{gfs_archive}``, ``{rap_archive}``): the
  run file's wgrib2-style ``.idx`` inventory
  (``n:offset:d=YYYYMMDDHH:VAR:LEVEL:FORECAST:``) gives each message's byte
  offset; only the wanted messages are downloaded with HTTP ``Range``
  requests (the method Herbie uses).

GRIB2 decoding uses ecCodes (``pip install eccodes``: Python bindings plus
the ``eccodeslib`` binary wheel; optional).  Without it these paths fail
with a clear message and the forecast falls back to the other sources.
Numeric-only (I/O and parsing).
"""
from __future__ import annotations

import math
import re
from dataclasses import dataclass
from datetime import datetime, timedelta, timezone

import numpy as np

from ironbark_opt import net
from ironbark_opt.errors import InputError, NetworkError

#: Variables on pressure levels: GRIB abbreviation -> column name.
GRIB_VARS = {"HGT": "height", "TMP": "temperature", "UGRD": "u", "VGRD": "v"}
_SHORT = {"gh": "height", "t": "temperature", "u": "u", "v": "v"}


@dataclass(frozen=True)
class ModelFiles:
    """Where one model's GRIB2 run files live and how often it runs."""
    name: str
    archive: str                 # endpoint name of the cloud archive
    cycle_hours: int             # [h] between runs
    latency_hours: int           # [h] after the run time until files appear
    max_forecast_hours: int      # [h] longest forecast of every run
    nomads_script: str

    def archive_key(self, run: datetime, fhour: int) -> str:
        if self.name == "gfs":
            return f"gfs.{run:%Y%m%d}/{run:%H}/atmos/gfs.t{run:%H}z.pgrb2.0p25.f{fhour:03d}"
        return f"rap.{run:%Y%m%d}/rap.t{run:%H}z.awp130pgrbf{fhour:02d}.grib2"

    def nomads_dir(self, run: datetime) -> str:
        if self.name == "gfs":
            return f"/gfs.{run:%Y%m%d}/{run:%H}/atmos"
        return f"/rap.{run:%Y%m%d}"

    def forecast_hours(self) -> list[int]:
        if self.name == "gfs":   # hourly to 120 h, then 3-hourly to 384 h
            return list(range(0, 121)) + list(range(123, self.max_forecast_hours + 1, 3))
        return list(range(0, self.max_forecast_hours + 1))


MODELS = {
    "gfs": ModelFiles("gfs", "gfs_archive", 6, 5, 384, "filter_gfs_0p25.pl"),
    "rap": ModelFiles("rap", "rap_archive", 1, 2, 21, "filter_rap.pl"),
}


@dataclass(frozen=True)
class IdxEntry:
    """One line of a wgrib2 ``.idx`` inventory."""
    number: int
    offset: int        # [bytes] start of the message in the file
    date: str
    variable: str
    level: str
    forecast: str


def parse_idx(text: str | bytes, source: str = ".idx") -> list[IdxEntry]:
    """Parse a wgrib2-style index; raises InputError naming the bad line."""
    if isinstance(text, bytes):
        text = text.decode("utf-8", "replace")
    out = []
    for n, line in enumerate(text.splitlines(), start=1):
        if not line.strip():
            continue
        parts = line.split(":")
        if len(parts) < 6 or not parts[0].strip().isdigit() or not parts[1].strip().isdigit():
            raise InputError(f"not an index line: {line[:80]!r}", source=source, line=n)
        out.append(IdxEntry(int(parts[0]), int(parts[1]), parts[2].removeprefix("d="),
                            parts[3], parts[4], parts[5]))
    if not out:
        raise InputError("empty index", source=source)
    if any(b.offset <= a.offset for a, b in zip(out, out[1:])):
        raise InputError("offsets do not increase", source=source)
    return out


_MB = re.compile(r"^(\d+(?:\.\d+)?) mb$")


def select_ranges(entries: list[IdxEntry], variables=tuple(GRIB_VARS)) -> list[tuple[int, int | None]]:
    """Byte ranges (inclusive start, inclusive end or None = to EOF) of the
    messages of ``variables`` on pressure levels (``"500 mb"``), adjacent
    messages merged into one range."""
    ranges = []
    for i, e in enumerate(entries):
        if e.variable in variables and _MB.match(e.level.strip()):
            end = entries[i + 1].offset - 1 if i + 1 < len(entries) else None
            if ranges and ranges[-1][1] is not None and ranges[-1][1] + 1 == e.offset:
                ranges[-1] = (ranges[-1][0], end)
            else:
                ranges.append((e.offset, end))
    return ranges


def _eccodes():
    try:
        import eccodes
    except (ModuleNotFoundError, RuntimeError, OSError):
        raise InputError("decoding GRIB2 needs ecCodes: pip install eccodes "
                         "(or use the THREDDS source)", field="grib") from None
    return eccodes


def split_messages(content: bytes, source: str) -> list[bytes]:
    """Split concatenated GRIB2 messages; InputError if one is cut short."""
    msgs, pos = [], 0
    while pos < len(content):
        if content[pos:pos + 4] != b"GRIB":
            raise InputError(f"no GRIB message at byte {pos}", source=source)
        if len(content) < pos + 16 or content[pos + 7] != 2:
            raise InputError("not a GRIB edition 2 message", source=source)
        length = int.from_bytes(content[pos + 8:pos + 16], "big")
        msg = content[pos:pos + length]
        if len(msg) < length or msg[-4:] != b"7777":
            raise InputError(f"GRIB message at byte {pos} is truncated "
                             f"({len(msg)} of {length} bytes)", source=source)
        msgs.append(msg)
        pos += length
    if not msgs:
        raise InputError("no GRIB message", source=source)
    return msgs


def decode_point(messages: list[bytes], latitude: float, longitude: float,
                 source: str = "GRIB2") -> dict:
    """Values of HGT/TMP/UGRD/VGRD on pressure levels at the grid point nearest the site.

    Parameters
    ----------
    messages : list of bytes (GRIB2 messages)
    latitude, longitude : float [rad]

    Returns ``{"pressure": [Pa], "height": [m'], "temperature": [K], "u", "v":
    [m/s] earth-relative, "valid_time", "run_time", "latitude", "longitude"
    [rad] of the grid point}``.  Grid-relative Lambert winds are rotated with
    :func:`ironbark_opt.atmosphere.ncss.rotate_grid_winds`.
    """
    from ironbark_opt.atmosphere.ncss import rotate_grid_winds
    ec = _eccodes()
    lat_d, lon_d = math.degrees(latitude), math.degrees(longitude)
    levels: dict[float, dict] = {}
    meta = {}
    for msg in messages:
        gid = ec.codes_new_from_message(msg)
        try:
            if ec.codes_get(gid, "typeOfLevel") != "isobaricInhPa":
                continue
            key = _SHORT.get(ec.codes_get(gid, "shortName"))
            if key is None:
                continue
            p = float(ec.codes_get(gid, "level")) * 100.0
            near = ec.codes_grib_find_nearest(gid, lat_d, lon_d)[0]
            levels.setdefault(p, {})[key] = float(near["value"])
            if not meta:
                grid = ec.codes_get(gid, "gridType")
                meta = {"lat": near["lat"], "lon": near["lon"], "grid": grid,
                        "relative": bool(ec.codes_get(gid, "uvRelativeToGrid")),
                        "run": _grib_time(ec, gid, "dataDate", "dataTime"),
                        "valid": _grib_time(ec, gid, "validityDate", "validityTime")}
                if grid == "lambert":
                    meta["projection"] = {
                        "standard_parallel": f"{ec.codes_get(gid, 'Latin1InDegrees')} "
                                             f"{ec.codes_get(gid, 'Latin2InDegrees')}",
                        "longitude_of_central_meridian": str(ec.codes_get(gid, "LoVInDegrees"))}
        except ec.GribInternalError as err:
            raise InputError(f"undecodable GRIB2 message ({err})", source=source) from None
        finally:
            ec.codes_release(gid)
    full = sorted(p for p, d in levels.items() if len(d) == 4)
    if len(full) < 2:
        raise InputError("fewer than two pressure levels with HGT, TMP, UGRD and VGRD",
                         source=source)
    out = {k: np.array([levels[p][k] for p in full]) for k in _SHORT.values()}
    out["pressure"] = np.array(full)
    lon_r = math.radians((meta["lon"] + 180.0) % 360.0 - 180.0)
    if meta["relative"]:
        if meta["grid"] != "lambert":
            raise InputError(f"grid-relative winds on a {meta['grid']} grid are not supported",
                             source=source)
        out["u"], out["v"] = rotate_grid_winds(out["u"], out["v"], lon_r, meta["projection"])
    out.update(valid_time=meta["valid"], run_time=meta["run"],
               latitude=math.radians(meta["lat"]), longitude=lon_r)
    return out


def _grib_time(ec, gid, dkey, tkey) -> datetime:
    d, t = int(ec.codes_get(gid, dkey)), int(ec.codes_get(gid, tkey))
    return datetime(d // 10000, d // 100 % 100, d % 100, t // 100, t % 100, tzinfo=timezone.utc)


def candidate_runs(model: ModelFiles, time: datetime, now: datetime | None = None,
                   count: int = 4) -> list[tuple[datetime, int]]:
    """(run, forecast hour) pairs to try, newest run first.

    The newest run is the latest cycle at or before both ``time`` and
    ``now - latency``; the forecast hour is the one nearest ``time``.

    Raises
    ------
    InputError
        ``time`` lies beyond the longest forecast of the newest run.
    """
    now = now or datetime.now(timezone.utc)
    latest = min(time, now - timedelta(hours=model.latency_hours))
    step = model.cycle_hours
    run = latest.replace(minute=0, second=0, microsecond=0)
    run -= timedelta(hours=run.hour % step)
    hours = np.array(model.forecast_hours())
    out = []
    for k in range(count):
        r = run - timedelta(hours=k * step)
        lead = (time - r).total_seconds() / 3600.0
        if lead > model.max_forecast_hours + 0.5:
            if k == 0:
                raise InputError(
                    f"{time:%Y-%m-%dT%H:%MZ} is {lead:.0f} h after the newest {model.name.upper()} "
                    f"run ({r:%Y-%m-%dT%HZ}); its forecasts reach {model.max_forecast_hours} h. "
                    "Choose an earlier time or another model", field="time")
            break
        out.append((r, int(hours[np.argmin(abs(hours - lead))])))
    return out


def _grib_parser(source: str):
    def parse(content: bytes):
        return split_messages(content, source)
    return parse


def archive_point(model_name: str, latitude: float, longitude: float, time: datetime,
                  now: datetime | None = None) -> dict:
    """Forecast columns from the cloud archive via ``.idx`` and byte ranges.

    Tries the newest run first and older runs when a file is missing (HTTP
    404, not yet published).  Returns the dict of :func:`decode_point`.
    """
    model = MODELS[model_name]
    base = net.endpoint(model.archive)
    source = f"NOAA {model.name.upper()} archive"
    errors = []
    for run, fhour in candidate_runs(model, time, now):
        url = f"{base}/{model.archive_key(run, fhour)}"
        try:
            idx = net.fetch(source, url + ".idx",
                            parse=lambda b, u=url: parse_idx(b, u + ".idx")).data
        except NetworkError as err:
            errors.append(str(err))
            continue
        ranges = select_ranges(idx)
        if not ranges:
            raise InputError("the index lists no HGT/TMP/UGRD/VGRD on pressure levels",
                             source=url + ".idx")
        messages = []
        for rng in ranges:
            messages += net.fetch(source, url, byte_range=rng, parse=_grib_parser(url)).data
        return decode_point(messages, latitude, longitude, source=url)
    raise NetworkError(f"{source}: no run file found:\n  " + "\n  ".join(errors))


def nomads_point(model_name: str, latitude: float, longitude: float, time: datetime,
                 now: datetime | None = None) -> dict:
    """Forecast columns from the NOMADS grib filter (a 1-degree box around the site)."""
    model = MODELS[model_name]
    url = f"{net.endpoint('nomads')}/cgi-bin/{model.nomads_script}"
    source = f"NOMADS {model.name.upper()} filter"
    lat_d, lon_d = math.degrees(latitude), math.degrees(longitude)
    errors = []
    for run, fhour in candidate_runs(model, time, now):
        key = model.archive_key(run, fhour).rsplit("/", 1)[1]
        params = {"dir": model.nomads_dir(run), "file": key, "all_lev": "on",
                  "subregion": "", "leftlon": f"{lon_d - 0.5:.2f}",
                  "rightlon": f"{lon_d + 0.5:.2f}", "toplat": f"{lat_d + 0.5:.2f}",
                  "bottomlat": f"{lat_d - 0.5:.2f}"}
        params.update({f"var_{v}": "on" for v in GRIB_VARS})
        try:
            messages = net.fetch(source, url, params=params, parse=_grib_parser(url)).data
        except NetworkError as err:
            errors.append(str(err))
            continue
        return decode_point(messages, latitude, longitude, source=url)
    raise NetworkError(f"{source}: no run file found:\n  " + "\n  ".join(errors))
