"""Pressure-level netCDF files a team already has (ERA5-style) -> profile columns.

Reads both on-disk flavours ERA5 downloads come in:

- netCDF3 (classic / 64-bit offset; e.g. the older CDS ``grib_to_netcdf``
  files with packed ``int16`` variables and ``scale_factor``/``add_offset``)
  with ``scipy.io.netcdf_file`` (no extra dependency);
- netCDF4 (HDF5; the newer CDS ``cfgrib`` files) with ``h5py`` — an
  optional dependency (``pip install h5py``; the ``netcdf4`` extra), the
  lightest well-kept reader of HDF5 with binary wheels.

Variables are found by CF ``standard_name`` (``geopotential`` or
``geopotential_height``, ``air_temperature``, ``eastward_wind``,
``northward_wind``) and otherwise by ERA5 short name (``z``, ``t``, ``u``,
``v``); axes by the variable's dimension names and their units.  The
profile at the site is bilinear in latitude/longitude and linear in time
between the two bracketing records.  Numeric-only (file I/O).
"""
from __future__ import annotations

import math
import re
from datetime import datetime, timedelta, timezone
from pathlib import Path

import numpy as np

from ironbark_opt.atmosphere.levels import G0, ProfileColumns, build_columns, geometric_height
from ironbark_opt.errors import InputError

_STANDARD = {"geopotential": ("geopotential", "geopotential_height"),
             "temperature": ("air_temperature",), "u": ("eastward_wind",),
             "v": ("northward_wind",)}
_SHORT = {"geopotential": ("z", "gh", "hgt"), "temperature": ("t", "ta", "air"),
          "u": ("u", "ua", "uwnd"), "v": ("v", "va", "vwnd")}
_TIME_AXES = ("time", "valid_time")
_LEVEL_AXES = ("level", "pressure_level", "isobaricinhpa", "plev", "isobaric")


class _Var:
    """A variable read fully into memory, with its dimension names and attributes."""

    def __init__(self, name, data, dims, attrs):
        self.name, self.dims = name, tuple(dims)
        self.attrs = {k: (v.decode() if isinstance(v, bytes) else v) for k, v in attrs.items()}
        data = np.array(data)
        fill = [self.attrs.get(k) for k in ("_FillValue", "missing_value")]
        mask = np.zeros(data.shape, bool)
        for f in fill:
            if f is not None:
                f = np.asarray(f).ravel()
                if f.size and np.isfinite(f[0]):
                    mask |= data == f[0]
        data = data.astype(float)
        if "scale_factor" in self.attrs or "add_offset" in self.attrs:
            data = data * float(np.ravel(self.attrs.get("scale_factor", 1.0))[0]) \
                + float(np.ravel(self.attrs.get("add_offset", 0.0))[0])
        data[mask] = np.nan
        self.data = data

    def attr(self, key, default=""):
        v = self.attrs.get(key, default)
        if isinstance(v, np.ndarray) and v.dtype.kind in "SO":
            v = v.ravel()[0]
        return v.decode() if isinstance(v, bytes) else v


def _read_netcdf3(path: Path) -> dict[str, _Var]:
    from scipy.io import netcdf_file
    out = {}
    with netcdf_file(path, "r", mmap=False) as nc:
        for name, var in nc.variables.items():
            out[name] = _Var(name, var.data, var.dimensions, dict(var._attributes))
    return out


def _read_netcdf4(path: Path) -> dict[str, _Var]:
    try:
        import h5py
    except ModuleNotFoundError:
        raise InputError("this is a netCDF4 (HDF5) file; reading it needs h5py "
                         "(pip install h5py)", source=path) from None
    out = {}
    with h5py.File(path, "r") as h5:
        for name, ds in h5.items():
            if not isinstance(ds, h5py.Dataset) or ds.dtype.kind not in "iuf":
                continue
            dims = []
            for i, dim in enumerate(ds.dims):
                dims.append(dim[0].name.lstrip("/") if len(dim) else f"dim{i}")
            if ds.ndim == 1 and dims == ["dim0"]:
                dims = [name]
            attrs = {k: ds.attrs[k] for k in ds.attrs
                     if k not in ("DIMENSION_LIST", "REFERENCE_LIST", "CLASS", "NAME")}
            out[name] = _Var(name, ds[()], dims, attrs)
    return out


def read_variables(path: str | Path) -> dict[str, _Var]:
    """All numeric variables of a netCDF3 or netCDF4 file (format by magic bytes)."""
    path = Path(path)
    with open(path, "rb") as fh:
        magic = fh.read(8)
    try:
        if magic.startswith(b"CDF"):
            return _read_netcdf3(path)
        if magic.startswith(b"\x89HDF"):
            return _read_netcdf4(path)
    except (OSError, ValueError, TypeError) as err:
        raise InputError(f"unreadable netCDF file ({err})", source=path) from None
    raise InputError("not a netCDF file (expected netCDF3 'CDF' or netCDF4/HDF5 magic bytes)",
                     source=path)


def _find(vs: dict[str, _Var], what: str, path) -> _Var:
    for v in vs.values():
        if v.attr("standard_name") in _STANDARD[what] and len(v.dims) == 4:
            return v
    for short in _SHORT[what]:
        if short in vs and len(vs[short].dims) == 4:
            return vs[short]
    raise InputError(f"no {what} variable (looked for standard_name {_STANDARD[what]} or "
                     f"names {_SHORT[what]}; found {sorted(vs)})", source=path, field=what)


def _cf_times(var: _Var, path) -> list[datetime]:
    units = str(var.attr("units"))
    m = re.match(r"\s*(seconds|minutes|hours|days)\s+since\s+(\d{4}-\d{1,2}-\d{1,2})"
                 r"(?:[ T](\d{1,2}:\d{2}(?::\d{2}(?:\.\d*)?)?))?", units)
    if not m:
        raise InputError(f"time units {units!r} not understood (expected '<unit> since <date>')",
                         source=path, field=var.name)
    step = {"seconds": 1.0, "minutes": 60.0, "hours": 3600.0, "days": 86400.0}[m.group(1)]
    clock = (m.group(3) or "0:00:00").split(".")[0]
    clock = clock if clock.count(":") == 2 else clock + ":00"
    epoch = datetime.strptime(f"{m.group(2)} {clock}", "%Y-%m-%d %H:%M:%S").replace(
        tzinfo=timezone.utc)
    return [epoch + timedelta(seconds=float(x) * step) for x in np.ravel(var.data)]


def _level_pa(var: _Var, path) -> np.ndarray:
    units = str(var.attr("units")).strip().lower()
    scale = {"millibars": 100.0, "millibar": 100.0, "hpa": 100.0, "mb": 100.0,
             "pa": 1.0}.get(units)
    if scale is None:
        raise InputError(f"pressure-level units {units!r} not understood (hPa or Pa)",
                         source=path, field=var.name)
    return np.ravel(var.data) * scale


def _weights(axis: np.ndarray, x: float, what: str, path) -> list[tuple[int, float]]:
    """Linear-interpolation indices and weights of ``x`` on a monotonic ``axis``."""
    lo, hi = float(np.min(axis)), float(np.max(axis))
    if axis.size == 1:
        if abs(x - axis[0]) > 1e-9:
            raise InputError(f"{what} {x:g} is not in the file (it has only {axis[0]:g})",
                             source=path, field=what)
        return [(0, 1.0)]
    if not lo - 1e-9 <= x <= hi + 1e-9:
        raise InputError(f"{what} {x:g} outside the file's range [{lo:g}, {hi:g}]",
                         source=path, field=what)
    order = np.argsort(axis)
    a = axis[order]
    j = int(np.clip(np.searchsorted(a, x) - 1, 0, a.size - 2))
    w = (x - a[j]) / (a[j + 1] - a[j])
    return [(int(order[j]), 1.0 - w), (int(order[j + 1]), w)]


def describe_times(times) -> str:
    """The records' times as short text for messages (all of them, or the range)."""
    if len(times) <= 8:
        return ", ".join(f"{t:%Y-%m-%d %H:%M}Z" for t in times)
    return (f"{len(times)} times from {times[0]:%Y-%m-%d %H:%M}Z to "
            f"{times[-1]:%Y-%m-%d %H:%M}Z")


def reanalysis_times(path: str | Path) -> list[datetime]:
    """The UTC times of the records in an ERA5-style pressure-level file."""
    path = Path(path)
    vs = read_variables(path)
    dims = _find(vs, "temperature", path).dims
    for d in dims:
        if d.lower() in _TIME_AXES and d in vs:
            return _cf_times(vs[d], path)
    raise InputError(f"no time axis among {dims}", source=path, field="time")


def read_reanalysis(path: str | Path, *, latitude: float, longitude: float,
                    time: datetime | None = None, ground_elevation: float | None = None,
                    ) -> ProfileColumns:
    """The profile over one site at one time from an ERA5-style pressure-level file.

    Parameters
    ----------
    path : path-like
        netCDF3 or netCDF4 file with geopotential, temperature, u and v on
        (time, level, latitude, longitude).
    latitude, longitude : float [rad]
        Site position (longitude east positive; 0..360 grids are handled).
    time : datetime, optional
        UTC time; naive datetimes are UTC.  Default: the first record (a
        one-record file needs no time).
    ground_elevation : float [m], optional
        Site elevation; levels under the ground are cut.  Pressure-level files
        hold no terrain height, so without it every level is kept.

    Raises
    ------
    InputError
        Missing variables or axes, a time or position outside the file.
    """
    path = Path(path)
    vs = read_variables(path)
    fields = {k: _find(vs, k, path) for k in ("geopotential", "temperature", "u", "v")}
    dims = fields["temperature"].dims
    for k, v in fields.items():
        if v.dims != dims:
            raise InputError(f"{v.name} has dimensions {v.dims}, temperature {dims}",
                             source=path, field=v.name)
    roles = {}
    for i, d in enumerate(dims):
        key = d.lower()
        if key in _TIME_AXES:
            roles["time"] = i
        elif key in _LEVEL_AXES:
            roles["level"] = i
        elif key.startswith("lat"):
            roles["lat"] = i
        elif key.startswith("lon"):
            roles["lon"] = i
    if len(roles) != 4 or any(dims[i] not in vs for i in roles.values()):
        raise InputError(f"cannot identify time, level, latitude, longitude among {dims}",
                         source=path, field=fields["temperature"].name)
    times = _cf_times(vs[dims[roles["time"]]], path)
    levels = _level_pa(vs[dims[roles["level"]]], path)
    lats = np.ravel(vs[dims[roles["lat"]]].data)
    lons = np.ravel(vs[dims[roles["lon"]]].data)
    lat_deg, lon_deg = math.degrees(latitude), math.degrees(longitude)
    if lons.max() > 180.0 and lon_deg < 0.0:
        lon_deg += 360.0
    stamps = np.array([t.timestamp() for t in times])
    if time is None:
        t_req = times[0]
    else:
        t_req = time if time.tzinfo else time.replace(tzinfo=timezone.utc)
        t_req = t_req.astimezone(timezone.utc)
    try:
        wt = _weights(stamps, t_req.timestamp(), "time", path)
    except InputError:
        raise InputError(f"time {t_req:%Y-%m-%d %H:%M}Z outside the file "
                         f"(it has {describe_times(times)})", source=path, field="time") from None
    wy = _weights(lats, lat_deg, "latitude_deg", path)
    wx = _weights(lons, lon_deg, "longitude_deg", path)

    def column(v: _Var) -> np.ndarray:
        data = np.moveaxis(v.data, [roles["time"], roles["level"], roles["lat"], roles["lon"]],
                           [0, 1, 2, 3])
        out = np.zeros(data.shape[1])
        for it, a in wt:
            for iy, b in wy:
                for ix, c in wx:
                    out = out + a * b * c * data[it, :, iy, ix]
        return out

    geo = column(fields["geopotential"])
    H = geo / G0 if fields["geopotential"].attr("standard_name") != "geopotential_height" \
        and fields["geopotential"].name != "gh" else geo
    z = geometric_height(H, latitude)
    return build_columns(levels, z, column(fields["temperature"]), column(fields["u"]),
                         column(fields["v"]), source=f"reanalysis {path.name}",
                         ground_elevation=ground_elevation, valid_time=t_req,
                         latitude=latitude, longitude=longitude,
                         notes=(f"bilinear at {lat_deg:.4f}, {lon_deg:.4f} deg; "
                                f"linear in time between records",))
