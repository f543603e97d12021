"""THREDDS NetCDF Subset Service (NCSS): forecast columns at a point.

Two requests per forecast: the dataset description ``{dataset}/dataset.xml``
(variables, their axes, the time span, the grid projection) and a "grid as
point" subset ``{dataset}?var=...&latitude=...&longitude=...&time=...&accept=csv``.
Axis names differ between datasets (``isobaric``, ``isobaric3``, ...), so
they are read from the description, never hard-coded, and CSV columns are
matched by name.  Variables on different vertical axes are requested
separately and merged on their common pressure levels.

Winds of Lambert-conformal datasets (RAP) are relative to the grid; they are
rotated to east/north here.

Ensemble datasets (GEFS) carry an axis of ``axisType="Ensemble"`` (netCDF-Java
``GribCoverageDataset.makeCoordAxis(CoordinateEns)``: name ``ens``, values the
GRIB2 perturbation numbers, 0 = control); :attr:`DatasetInfo.ensemble` lists its
members per grid, and :func:`point_columns` asks for one member with TDS 5's
``ensCoord`` parameter (``NcssGridParamsBean.ensCoord``).  TDS 4 answers all
members with an ``ensMember`` column (``CSVPointDataWriter.writeGroupHeader``);
its rows are filtered to the member.  Numeric-only (I/O and parsing).
"""
from __future__ import annotations

import math
import re
import xml.etree.ElementTree as ET
from contextlib import contextmanager
from contextvars import ContextVar
from dataclasses import dataclass, field
from datetime import datetime, timezone

import numpy as np

from ironbark_opt import net
from ironbark_opt.errors import InputError

VARIABLES = {"height": "Geopotential_height_isobaric", "temperature": "Temperature_isobaric",
             "u": "u-component_of_wind_isobaric", "v": "v-component_of_wind_isobaric"}


@dataclass(frozen=True)
class DatasetInfo:
    """What ``dataset.xml`` says: grids -> vertical axis, time span, projection."""
    vertical_axis: dict[str, str]
    time_begin: datetime | None
    time_end: datetime | None
    run_time: datetime | None
    projection: dict = field(default_factory=dict)
    latlon_box: tuple | None = None      # (west, east, south, north) [deg]
    #: grid -> (ensemble axis name, member numbers) for grids with an Ensemble axis
    ensemble: dict = field(default_factory=dict)


def parse_iso(text: str) -> datetime:
    """UTC datetime from ISO 8601 text (``Z`` or offset; naive = UTC)."""
    try:
        t = datetime.fromisoformat(text.strip().replace("Z", "+00:00"))
    except ValueError:
        raise InputError(f"not an ISO 8601 time: {text!r}", field="time") from None
    return t.replace(tzinfo=timezone.utc) if t.tzinfo is None else t.astimezone(timezone.utc)


def parse_dataset_xml(content: bytes, source: str = "dataset.xml") -> DatasetInfo:
    """Parse a THREDDS NCSS ``dataset.xml`` description.  Raises InputError."""
    try:
        root = ET.fromstring(content)
    except ET.ParseError as err:
        raise InputError(f"not valid XML ({err})", source=source) from None
    if root.tag != "gridDataset":
        raise InputError(f"expected <gridDataset>, got <{root.tag}>", source=source)
    axis_type = {a.get("name"): a.get("axisType") for a in root.iter("axis")}
    axes = {a.get("name"): a for a in root.iter("axis")}
    vertical, ensemble = {}, {}
    for gs in root.iter("gridSet"):
        refs = [r.get("name") for r in gs.findall("axisRef")]
        vert = [r for r in refs if axis_type.get(r) in ("Pressure", "Height", "GeoZ")]
        ens = [r for r in refs if axis_type.get(r) == "Ensemble"]
        members = (ens[0], _axis_values(axes[ens[0]], source)) if ens and ens[0] in axes else None
        for g in gs.findall("grid"):
            vertical[g.get("name")] = vert[0] if vert else ""
            if members:
                ensemble[g.get("name")] = members
    span = root.find("TimeSpan")
    begin = end = None
    if span is not None and span.findtext("begin") and span.findtext("end"):
        begin, end = parse_iso(span.findtext("begin")), parse_iso(span.findtext("end"))
    run = None
    for a in root.iter("axis"):
        if a.get("axisType") == "RunTime":
            vals = a.find("values")
            units = {x.get("name"): x.get("value") for x in a}.get("units", "")
            m = re.search(r"since\s+(\S+)", units or "")
            if m and vals is not None and vals.get("npts") == "1":
                run = parse_iso(m.group(1))
    proj = {}
    ct = root.find("coordTransform")
    if ct is not None:
        for p in ct:
            if p.get("name"):
                proj[p.get("name")] = p.get("value")
    box = root.find("LatLonBox")
    llb = None
    if box is not None:
        try:
            llb = tuple(float(box.findtext(k)) for k in ("west", "east", "south", "north"))
        except (TypeError, ValueError):
            llb = None
    return DatasetInfo(vertical, begin, end, run, proj, llb, ensemble)


def _axis_values(axis, source: str) -> tuple[float, ...]:
    """Coordinate values of a dataset.xml ``<axis>``: listed in ``<values>`` (irregular axes) or
    ``start + i * resolution`` for ``npts`` points (regular axes; netCDF-Java
    ``CoverageDatasetCapabilities.writeAxis`` lists values only for irregular axes)."""
    vals = axis.find("values")
    name = axis.get("name")
    try:
        if vals is not None and (vals.text or "").strip():
            return tuple(float(v) for v in vals.text.split())
        n = int(vals.get("npts"))
        start = float(vals.get("start"))
        step = float(vals.get("resolution") or 0.0)
    except (AttributeError, TypeError, ValueError):
        raise InputError(f"axis {name!r} has no readable values (npts/start/resolution)",
                         source=source, field=name) from None
    if n < 1 or (n > 1 and step == 0.0):
        raise InputError(f"axis {name!r}: {n} points with resolution {step:g}", source=source, field=name)
    return tuple(start + i * step for i in range(n))


_HEADER = re.compile(r'^\s*([^\[]+?)\s*(?:\[unit="?([^"\]]*)"?\])?\s*$')


def parse_point_csv(content: bytes, source: str = "NCSS CSV") -> dict:
    """Parse an NCSS point CSV: ``{name: (unit, array)}`` plus ``'date'`` strings.

    Columns are found by their name before ``[unit=...]``.  Raises InputError
    on a missing header, a short row (truncated body) or a bad number.
    """
    text = content.decode("utf-8", "replace")
    lines = [ln for ln in text.splitlines() if ln.strip()]
    if not lines or "," not in lines[0]:
        raise InputError("not an NCSS CSV response (no header line)", source=source, line=1)
    cols = []
    for cell in lines[0].split(","):
        m = _HEADER.match(cell)
        cols.append((m.group(1).strip(), (m.group(2) or "").strip()) if m else (cell, ""))
    if len(lines) < 2:
        raise InputError("the response has a header but no data rows", source=source)
    out = {name: (unit, []) for name, unit in cols}
    for n, line in enumerate(lines[1:], start=2):
        cells = line.split(",")
        if len(cells) != len(cols):
            raise InputError(f"expected {len(cols)} fields, got {len(cells)} "
                             "(truncated response?)", source=source, line=n)
        for (name, _), cell in zip(cols, cells):
            out[name][1].append(cell.strip())
    result = {}
    for name, (unit, vals) in out.items():
        if name in ("date", "time", "station"):
            result[name] = (unit, vals)
            continue
        try:
            result[name] = (unit, np.array([float(v) if v not in ("", "NaN") else math.nan
                                            for v in vals]))
        except ValueError as err:
            raise InputError(f"not a number ({err})", source=source, field=name) from None
    return result


def _pressure_column(table: dict, axis: str, source: str) -> np.ndarray:
    # TDS 4 names it vertCoord, TDS 5's station-profile CSV alt (StationProfileSubsetWriterCSV)
    for name in (axis, "vertCoord", "alt"):
        if name in table:
            unit, values = table[name]
            scale = {"pa": 1.0, "hpa": 100.0, "mb": 100.0, "millibar": 100.0}.get(unit.lower())
            if scale is None:
                raise InputError(f"vertical coordinate in {unit!r}, expected Pa or hPa",
                                 source=source, field=name)
            return values * scale
    raise InputError(f"no vertical coordinate column ({axis!r}, 'vertCoord' or 'alt')",
                     source=source)


def rotate_grid_winds(u, v, longitude, projection: dict):
    """Earth-relative (east, north) wind [m/s] from Lambert-conformal grid-relative u, v.

    Symbolic-safe in ``u``, ``v``; ``longitude`` [rad] and the projection
    parameters are numbers.  On a Lambert conformal conic grid the grid's y
    axis is turned from local north by ``theta = n (lambda - lambda0)``
    (Snyder, Map Projections - A Working Manual, USGS PP 1395, 1987,
    eq. 14-4), with cone constant ``n = sin(phi1)`` for a tangent cone
    (eq. 15-3 with phi1 = phi2); then ``east = cos(theta) u + sin(theta) v``,
    ``north = -sin(theta) u + cos(theta) v`` (the rotation NCEP's wgrib2
    ``-new_grid_winds earth`` applies).
    """
    phi1 = math.radians(float(projection.get("standard_parallel", "25").split()[0]))
    phi2 = math.radians(float(projection.get("standard_parallel", "25").split()[-1]))
    lam0 = math.radians(float(projection.get("longitude_of_central_meridian", "265")))
    if abs(phi1 - phi2) < 1e-12:
        n = math.sin(phi1)
    else:   # secant cone, Snyder eq. 15-3
        n = (math.log(math.cos(phi1) / math.cos(phi2))
             / math.log(math.tan(math.pi / 4 + phi2 / 2) / math.tan(math.pi / 4 + phi1 / 2)))
    dlam = (longitude - lam0 + math.pi) % (2 * math.pi) - math.pi
    theta = n * dlam
    c, s = math.cos(theta), math.sin(theta)
    return c * u + s * v, -s * u + c * v


def point_columns(dataset_url: str, latitude: float, longitude: float, time: datetime,
                  source: str = "THREDDS NCSS", variables: dict | None = None,
                  member: float | None = None) -> dict:
    """Fetch and merge the four isobaric variables at one point and time.

    Parameters
    ----------
    dataset_url : str
        NCSS dataset URL (``{thredds}/ncss/grid/grib/NCEP/RAP/CONUS_13km/Best``).
    latitude, longitude : float [rad]
    time : datetime (UTC)
    variables : dict, optional
        ``height``/``temperature``/``u``/``v`` -> dataset variable (default :data:`VARIABLES`).
    member : float, optional
        Ensemble member (a value of the variables' Ensemble axis): requested with
        ``ensCoord``; an ``ensMember`` column in the answer is filtered to it.

    Returns
    -------
    dict with ``pressure`` [Pa], ``height`` [m'], ``temperature`` [K],
    ``u``, ``v`` [m/s] (earth-relative), ``valid_time``, ``run_time``,
    ``latitude``, ``longitude`` [rad] of the returned grid point.

    Raises
    ------
    InputError
        Time outside the dataset's span, point outside its domain, or a
        variable missing from the dataset.
    NetworkError
        THREDDS unreachable or its answer malformed.
    """
    variables = VARIABLES if variables is None else variables
    info = dataset_info(dataset_url, source)
    missing = [v for v in variables.values() if v not in info.vertical_axis]
    if missing:
        raise InputError(f"the dataset has no {', '.join(missing)}", source=dataset_url,
                         field="var")
    if member is not None:
        off = [v for v in variables.values()
               if not any(abs(member - x) < 1e-9 for x in info.ensemble.get(v, ("", ()))[1])]
        if off:
            raise InputError(f"ensemble member {member:g} is not on the Ensemble axis of {off[0]}",
                             source=f"{dataset_url}/dataset.xml", field=off[0])
    if info.time_begin and info.time_end and not info.time_begin <= time <= info.time_end:
        raise InputError(
            f"forecast time {time:%Y-%m-%dT%H:%MZ} is outside the model run(s) available "
            f"({info.time_begin:%Y-%m-%dT%H:%MZ} to {info.time_end:%Y-%m-%dT%H:%MZ}); "
            "choose a time inside that window", source=dataset_url, field="time")
    lat_d, lon_d = math.degrees(latitude), math.degrees(longitude)
    if info.latlon_box:
        w, e, s, n = info.latlon_box
        lon_w = lon_d if w <= lon_d <= e else lon_d + 360.0 if w <= lon_d + 360.0 <= e else lon_d
        if not (s <= lat_d <= n and w <= lon_w <= e):
            raise InputError(f"site {lat_d:.3f}, {lon_d:.3f} deg is outside the model domain "
                             f"(lat {s:g}..{n:g}, lon {w:g}..{e:g})", source=dataset_url,
                             field="site")
    groups: dict[str, list[str]] = {}
    for key, var in variables.items():
        groups.setdefault(info.vertical_axis[var], []).append(key)
    merged: dict[float, dict] = {}
    meta = {}
    for axis, keys in groups.items():
        params = {"var": [variables[k] for k in keys], "latitude": f"{lat_d:.4f}",
                  "longitude": f"{lon_d:.4f}", "time": time.strftime("%Y-%m-%dT%H:%M:%SZ"),
                  "accept": "csv"}
        if member is not None:
            params["ensCoord"] = f"{member:g}"
        table = net.fetch(source, dataset_url, params=params,
                          parse=lambda b: _checked_csv(b, dataset_url, [variables[k] for k in keys],
                                                       member)).data
        p = _pressure_column(table, axis, dataset_url)
        for k in keys:
            for pi, val in zip(p, table[variables[k]][1]):
                merged.setdefault(round(float(pi), 3), {})[k] = val
        if not meta:   # older servers: date, lat, lon; TDS 5: time, latitude, longitude
            when = table.get("date") or table.get("time") or ("", [""])
            meta = {"date": when[1][0] if len(when[1]) else "",
                    "lat": _first(table, ("lat", "latitude"), lat_d),
                    "lon": _first(table, ("lon", "longitude"), lon_d)}
    levels = sorted(pk for pk, d in merged.items() if len(d) == len(variables))
    if len(levels) < 2:
        raise InputError("fewer than two pressure levels with all four variables",
                         source=dataset_url)
    out = {k: np.array([merged[pk][k] for pk in levels]) for k in variables}
    out["pressure"] = np.array(levels, dtype=float)
    lat_r = math.radians(meta["lat"])
    lon_r = math.radians((meta["lon"] + 180.0) % 360.0 - 180.0)
    grid = info.projection.get("grid_mapping_name", "")
    if grid == "lambert_conformal_conic":
        out["u"], out["v"] = rotate_grid_winds(out["u"], out["v"], lon_r, info.projection)
    elif grid not in ("", "latitude_longitude"):
        raise InputError(f"winds on a {grid!r} grid cannot be rotated to east/north",
                         source=dataset_url)
    out.update(valid_time=parse_iso(meta["date"]) if meta["date"] else time,
               run_time=info.run_time, latitude=lat_r, longitude=lon_r)
    return out


def _first(table, names, default):
    for name in names:
        if name in table and len(table[name][1]) and np.isfinite(table[name][1][0]):
            return float(table[name][1][0])
    return default


#: dataset URL -> DatasetInfo inside a :func:`reuse_dataset_info` block (None outside one)
_DATASET_MEMO: ContextVar[dict | None] = ContextVar("ncss_dataset_memo", default=None)


@contextmanager
def reuse_dataset_info():
    """Inside the block each dataset's ``dataset.xml`` is fetched once.

    A launch window asks the same collection for every hour (and, for an ensemble, every
    member): 12 hours x 31 GEFS members fetched it 372 times.  The description changes only
    when a new model run is published, so one copy serves a command's run.  A nested block
    shares the outer block's copies."""
    if _DATASET_MEMO.get() is not None:
        yield
        return
    token = _DATASET_MEMO.set({})
    try:
        yield
    finally:
        _DATASET_MEMO.reset(token)


def dataset_info(dataset_url: str, source: str = "THREDDS NCSS") -> DatasetInfo:
    """The dataset's ``dataset.xml`` description (fetched through the cache; once per
    :func:`reuse_dataset_info` block)."""
    memo = _DATASET_MEMO.get()
    if memo is not None and dataset_url in memo:
        return memo[dataset_url]
    info = net.fetch(source, f"{dataset_url}/dataset.xml",
                     parse=lambda b: parse_dataset_xml(b, f"{dataset_url}/dataset.xml")).data
    if memo is not None:
        memo[dataset_url] = info
    return info


def _checked_csv(content: bytes, source: str, names, member: float | None = None) -> dict:
    table = parse_point_csv(content, source)
    for name in names:
        if name not in table:
            raise InputError(f"column {name!r} missing from the response", source=source, field=name)
    if member is not None and "ensMember" in table:
        return _member_rows(table, member, source)
    return table


def _member_rows(table: dict, member: float, source: str) -> dict:
    """The rows of one member of a TDS 4 answer that lists every member (``ensMember`` column)."""
    keep = np.isclose(table["ensMember"][1], member)
    if not keep.any():
        have = sorted({float(v) for v in table["ensMember"][1]})
        raise InputError(f"ensemble member {member:g} not in the response's ensMember column (members {have})",
                         source=source, field="ensMember")
    return {name: (unit, [v for v, k in zip(vals, keep) if k] if isinstance(vals, list) else vals[keep])
            for name, (unit, vals) in table.items()}
