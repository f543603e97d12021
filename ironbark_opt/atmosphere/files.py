"""One entry point for every atmosphere file a team may have on disk.

``load_atmosphere_file(path, time=..., latitude=..., longitude=...,
ground_elevation=...)`` returns the :class:`~ironbark_opt.atmosphere.profile.Profile`
to fly, whatever the file is:

- ``.nc`` / ``.nc4`` / ``.netcdf``: an ERA5-style pressure-level reanalysis
  (:mod:`.reanalysis`); the site's latitude and longitude pick the column
  (bilinear), ``time`` the record (linear between records).  A file with
  more than one record needs ``time``.
- ``.json``: what ``ironbark weather get --json`` (or ``--out x.json``)
  writes (``levels`` with unit-suffixed columns), or a saved ``Profile``
  table (``altitude_m``, ``temperature_K``, ``pressure_Pa`` and wind).
- ``.csv`` with an ``altitude_m`` column: ``weather get --csv`` output or a
  profile table (:meth:`Profile.from_dataframe`); any other ``.csv``/text:
  a saved University of Wyoming sounding (:mod:`.sounding`).

A profile that says where it was taken (``latitude_deg``, ``longitude_deg``: forecasts,
soundings) farther than :data:`PROFILE_SITE_WARN_KM` from the launch site is flown with a
warning naming the distance (a reanalysis file is read at the site itself).

Numeric-only (file I/O); the returned ``Profile`` is symbolic-safe.
"""
from __future__ import annotations

import json
import math
import warnings
from datetime import datetime
from pathlib import Path

from ironbark_opt.errors import InputError

_NETCDF = (".nc", ".nc4", ".netcdf", ".cdf")
#: A one-column profile taken farther than this from the launch site is warned about [km]:
#: beyond the distance from any site to its nearest radiosonde station in a network of
#: stations about 400 km apart (the U.S. upper-air network)
PROFILE_SITE_WARN_KM = 300.0
#: Mean Earth radius [km] (IUGG, Moritz 2000: R1 = 6371.0088 km)
EARTH_RADIUS_KM = 6371.0088


def site_distance_km(lat1_deg, lon1_deg, lat2_deg, lon2_deg) -> float:
    """Great-circle distance [km] between two points [deg] (haversine, spherical Earth)."""
    p1, p2 = math.radians(lat1_deg), math.radians(lat2_deg)
    dp, dl = p2 - p1, math.radians(lon2_deg - lon1_deg)
    h = math.sin(dp / 2) ** 2 + math.cos(p1) * math.cos(p2) * math.sin(dl / 2) ** 2
    return 2.0 * EARTH_RADIUS_KM * math.asin(min(1.0, math.sqrt(h)))


def _warn_if_far(profile, latitude, longitude, path: Path) -> None:
    """Warn when ``profile`` was taken farther than :data:`PROFILE_SITE_WARN_KM` from the
    site at ``latitude``, ``longitude`` [rad] (both known)."""
    lat0, lon0 = getattr(profile, "latitude_deg", None), getattr(profile, "longitude_deg", None)
    if None in (lat0, lon0, latitude, longitude):
        return
    lat, lon = math.degrees(latitude), math.degrees(longitude)
    d = site_distance_km(float(lat0), float(lon0), lat, lon)
    if d > PROFILE_SITE_WARN_KM:
        warnings.warn(f"{path}: this atmosphere profile was taken at {float(lat0):.4f}, "
                      f"{float(lon0):.4f} deg, {d:.0f} km from the launch site ({lat:.4f}, "
                      f"{lon:.4f} deg): its winds and temperatures are another place's",
                      UserWarning, stacklevel=3)


def _as_time(time, path) -> datetime | None:
    if time is None or isinstance(time, datetime):
        return time
    from ironbark_opt.atmosphere.ncss import parse_iso
    try:
        return parse_iso(str(time))
    except InputError as exc:
        raise InputError(exc.message, source=path, field="atmosphere time") from None


def _reanalysis(path: Path, time, latitude, longitude, ground_elevation):
    from ironbark_opt.atmosphere.reanalysis import describe_times, read_reanalysis, reanalysis_times
    if latitude is None or longitude is None:
        raise InputError("a reanalysis file needs the site's latitude and longitude "
                         "([launch] latitude_deg, longitude_deg, or --site)", source=path,
                         field="latitude_deg")
    if time is None:
        times = reanalysis_times(path)
        if len(times) > 1:
            raise InputError(f"the file holds several times ({describe_times(times)}): give the "
                             "launch time ([launch] atmosphere = {file = ..., time = \"...Z\"} "
                             "or --atmosphere-time)", source=path, field="time")
    return read_reanalysis(path, latitude=latitude, longitude=longitude, time=time,
                           ground_elevation=ground_elevation).to_profile()


def _from_table(df, path: Path, meta: dict):
    from ironbark_opt.atmosphere.profile import Profile
    kwargs = {k: meta[k] for k in ("valid_time", "run_time", "latitude_deg", "longitude_deg")
              if meta.get(k) is not None}
    source = meta.get("source") or path.name
    return Profile.from_dataframe(df, source=f"{source} (from {path.name})"
                                  if path.name not in str(source) else str(source), **kwargs)


def _json(path: Path):
    import pandas as pd
    try:
        data = json.loads(path.read_text(encoding="utf-8"))
    except (UnicodeDecodeError, json.JSONDecodeError) as exc:
        raise InputError(f"not a JSON file ({exc})", source=path) from None
    if not isinstance(data, dict):
        raise InputError("expected a JSON object (as 'ironbark weather get --json' writes)",
                         source=path)
    levels = data.get("levels", data)
    if not isinstance(levels, dict):
        raise InputError("'levels' must map column names to lists", source=path, field="levels")
    try:
        df = pd.DataFrame(levels)
    except ValueError as exc:
        raise InputError(f"'levels' columns are not a table ({exc})", source=path,
                         field="levels") from None
    return _from_table(df, path, data)


def _csv(path: Path):
    import pandas as pd
    head = path.read_text(encoding="utf-8", errors="replace").lstrip().splitlines()[:1]
    if head and "altitude_m" in head[0].lower():
        try:
            df = pd.read_csv(path)
        except (ValueError, pd.errors.ParserError) as exc:
            raise InputError(f"cannot read the CSV ({exc})", source=path) from None
        return _from_table(df, path, {})
    from ironbark_opt.atmosphere.sounding import read_sounding
    return read_sounding(path).to_profile()


def load_atmosphere_file(path, *, time=None, latitude: float | None = None,
                         longitude: float | None = None, ground_elevation: float | None = None):
    """The tabulated atmosphere a file describes (see the module docstring).

    Parameters
    ----------
    path : path-like
    time : datetime or ISO 8601 str, optional
        UTC launch time; picks the record of a multi-time reanalysis file.
    latitude, longitude : float [rad], optional
        Site position (needed for reanalysis files).
    ground_elevation : float [m], optional
        Site elevation; reanalysis levels under the ground are cut.

    Returns
    -------
    Profile

    Raises
    ------
    InputError
        Missing or unreadable file, a time or site outside the file.
    """
    path = Path(path)
    if not path.is_file():
        raise InputError("atmosphere file not found", source=path, field="atmosphere")
    when = _as_time(time, path)
    suffix = path.suffix.lower()
    if suffix in _NETCDF:
        return _reanalysis(path, when, latitude, longitude, ground_elevation)
    if when is not None:
        raise InputError("a time only selects a record of a reanalysis (.nc) file; this file "
                         "holds one profile", source=path, field="time")
    profile = _json(path) if suffix == ".json" else _csv(path)
    _warn_if_far(profile, latitude, longitude, path)
    return profile


def describe_flown(atmosphere) -> dict:
    """``{"source": ..., "valid_time": ..., "model": ...}`` of the atmosphere a
    setup flies, for summaries and ``--json``."""
    d = atmosphere.describe() if hasattr(atmosphere, "describe") else {}
    out = {"model": d.get("model", type(atmosphere).__name__), "source": d.get("source"),
           "valid_time": d.get("valid_time")}
    for key in ("wind_east_mps", "wind_north_mps", "temperature_offset_K"):
        if key in d:
            out[key] = d[key]
    return out


def flown_line(atmosphere) -> str:
    """One summary line naming the atmosphere flown."""
    d = describe_flown(atmosphere)
    when = f", valid {d['valid_time']}" if d.get("valid_time") else ""
    return f"  atmosphere         {d['model']}: {d['source']}{when}"
