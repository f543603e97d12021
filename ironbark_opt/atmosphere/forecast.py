"""NOAA RAP (North America, hourly), GFS (global) and GEFS (global ensemble) forecast
profiles over a site.

:func:`forecast_profile` asks the access paths in turn and returns the first
that works, converted to :class:`~ironbark_opt.atmosphere.levels.ProfileColumns`
(geometric altitude above sea level, from the site's ground up, with the
model run and valid time recorded):

1. ``thredds`` — UCAR THREDDS NetCDF Subset Service, point subset as CSV
   (:mod:`ironbark_opt.atmosphere.ncss`);
2. ``nomads`` — the NOMADS grib filter, GRIB2 (:mod:`~ironbark_opt.atmosphere.grib`);
3. ``archive`` — NOAA's public cloud archive, ``.idx`` + byte ranges, GRIB2.

The order can be changed with ``IRONBARK_FORECAST_SOURCES`` (comma
separated) or ``[forecast] sources = [...]`` in the user config file; the
THREDDS dataset paths with ``[forecast.thredds_paths]``.  When every path
fails, the error lists each one's reason.  GEFS members (``member=``) come
from THREDDS only (:mod:`ironbark_opt.atmosphere.ensemble`).  Numeric-only (I/O).
"""
from __future__ import annotations

import math
import os
from datetime import datetime, timezone

from ironbark_opt import config, net
from ironbark_opt.atmosphere import ensemble, grib, ncss
from ironbark_opt.atmosphere.levels import ProfileColumns, build_columns, geometric_height
from ironbark_opt.atmosphere.sites import Site, get_site
from ironbark_opt.errors import InputError, NetworkError

#: NCSS dataset paths below the THREDDS base URL ("Best" = best time series).
THREDDS_PATHS = {"rap": "ncss/grid/grib/NCEP/RAP/CONUS_13km/Best",
                 "gfs": "ncss/grid/grib/NCEP/GFS/Global_0p25deg/Best",
                 "gefs": ensemble.GEFS_PATH}
DEFAULT_SOURCES = ("thredds", "nomads", "archive")
MODEL_NAMES = {"rap": "RAP", "gfs": "GFS", "gefs": "GEFS"}
#: forecasts with ensemble members (flown one member at a time)
ENSEMBLES = ("gefs",)


def sources_order() -> tuple[str, ...]:
    """Access paths in the order they are tried (env, then config, then default)."""
    env = os.environ.get("IRONBARK_FORECAST_SOURCES")
    order = env.split(",") if env else config.load().get("forecast", {}).get(
        "sources", DEFAULT_SOURCES)
    order = tuple(s.strip().lower() for s in order if s.strip())
    bad = [s for s in order if s not in DEFAULT_SOURCES]
    if bad or not order:
        raise InputError(f"unknown forecast source(s) {bad}; expected some of "
                         f"{list(DEFAULT_SOURCES)}", field="forecast.sources")
    return order



def gefs_members(count: int | None = None) -> tuple[int, ...]:
    """The first ``count`` GEFS members of the THREDDS dataset (all when None), control first."""
    url = _thredds_url("gefs")
    return ensemble.choose_members(ensemble.ensemble_members(url), count, url)


def _thredds_url(model: str) -> str:
    paths = config.load().get("forecast", {}).get("thredds_paths", {})
    return f"{net.endpoint('thredds')}/{paths.get(model, THREDDS_PATHS[model]).strip('/')}"


def forecast_profile(model: str, time: datetime | str, *, site: Site | str | None = None,
                     latitude: float | None = None, longitude: float | None = None,
                     elevation: float | None = None, sources=None,
                     now: datetime | None = None, member: int | None = None) -> ProfileColumns:
    """Forecast atmosphere over a launch site.

    Parameters
    ----------
    model : {"rap", "gfs", "gefs"}
    time : datetime or ISO 8601 str
        Launch time (UTC; naive = UTC).  The nearest forecast time is used
        and recorded as ``valid_time``.
    site : Site or str, optional
        A preset (see :mod:`ironbark_opt.atmosphere.sites`) — or give
        ``latitude``, ``longitude`` [rad] and ``elevation`` [m].
    sources : sequence of str, optional
        Access paths to try (default :func:`sources_order`).
    now : datetime, optional
        Current time for choosing the newest published run (tests).
    member : int, optional
        Ensemble member (GEFS only, required there; 0 = control).

    Raises
    ------
    InputError
        Unknown model, no site, or every source said the request is
        outside what it has (e.g. time outside the model run).
    NetworkError
        Every source failed and at least one for a network reason.
    """
    model = model.lower()
    if model not in THREDDS_PATHS:
        raise InputError(f"unknown model {model!r}; expected 'rap', 'gfs' or 'gefs'", field="model")
    if (model in ENSEMBLES) != (member is not None):
        raise InputError(f"{MODEL_NAMES[model]} is an ensemble: give a member" if model in ENSEMBLES else
                         f"{MODEL_NAMES[model]} is deterministic: it has no member {member}", field="member")
    if isinstance(time, str):
        time = ncss.parse_iso(time)
    time = time.replace(tzinfo=timezone.utc) if time.tzinfo is None else \
        time.astimezone(timezone.utc)
    if isinstance(site, str):
        site = get_site(site)
    if site is not None:
        latitude, longitude, elevation = site.latitude, site.longitude, site.elevation
    if latitude is None or longitude is None or elevation is None:
        raise InputError("give a site preset or latitude, longitude and elevation",
                         field="site")
    order = tuple(sources) if sources else sources_order()
    failures, network_failed = [], False
    for src in order:
        try:
            if src != "thredds" and model in ENSEMBLES:
                raise InputError(f"{MODEL_NAMES[model]} members are read through THREDDS NCSS only")
            if src == "thredds" and model in ENSEMBLES:
                url = _thredds_url(model)
                data = ensemble.member_columns(url, latitude, longitude, time, member)
                label = f"{MODEL_NAMES[model]} member {member} via THREDDS NCSS {url}"
            elif src == "thredds":
                url = _thredds_url(model)
                data = ncss.point_columns(url, latitude, longitude, time,
                                          source=f"THREDDS {MODEL_NAMES[model]}")
                label = f"{MODEL_NAMES[model]} via THREDDS NCSS {url}"
            elif src == "nomads":
                data = grib.nomads_point(model, latitude, longitude, time, now)
                label = f"{MODEL_NAMES[model]} via NOMADS grib filter"
            elif src == "archive":
                data = grib.archive_point(model, latitude, longitude, time, now)
                label = f"{MODEL_NAMES[model]} via NOAA archive (.idx byte ranges)"
            else:
                raise InputError(f"unknown forecast source {src!r}", field="sources")
        except NetworkError as err:
            network_failed = True
            failures.append(f"[{src}] {err}")
            continue
        except InputError as err:
            failures.append(f"[{src}] {err}")
            continue
        z = geometric_height(data["height"], data["latitude"])
        notes = [f"grid point {math.degrees(data['latitude']):.3f}, "
                 f"{math.degrees(data['longitude']):.3f} deg"]
        if data["run_time"] is None:
            notes.append("model run not reported by the source (THREDDS 'Best' time series)")
        notes += [f"fell back after: {f.splitlines()[0]}" for f in failures]
        return build_columns(data["pressure"], z, data["temperature"], data["u"], data["v"],
                             source=label, ground_elevation=elevation,
                             valid_time=data["valid_time"], run_time=data["run_time"],
                             latitude=latitude, longitude=longitude, notes=notes)
    text = (f"no {MODEL_NAMES[model]} forecast for {time:%Y-%m-%dT%H:%MZ} from any source:\n  "
            + "\n  ".join(failures))
    raise NetworkError(text) if network_failed else InputError(text, field="time")


def setup_with_forecast(setup, model: str, time, site: Site | str, member: int | None = None):
    """``setup`` flying the ``model`` forecast (its ensemble ``member``) at ``time`` over ``site``
    (its ground as the site elevation, its latitude for gravity): ``(new setup, ProfileColumns)``."""
    import dataclasses

    where = get_site(site) if isinstance(site, str) else site
    columns = forecast_profile(model, time, site=where, member=member)
    elevation = columns.ground_elevation if columns.ground_elevation is not None else where.elevation
    return dataclasses.replace(setup, atmosphere=columns.to_profile(), site_elevation=float(elevation),
                               latitude=where.latitude, longitude=where.longitude), columns
