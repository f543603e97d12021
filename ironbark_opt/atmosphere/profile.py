"""A tabulated atmosphere: altitude -> T, p, wind, from any source.

Forecast readers (RAP, GFS), radiosonde soundings and other models build a
:class:`Profile` from plain arrays (SI units, geometric altitude above mean
sea level).  It is then evaluated like any ``Atmosphere``: with NumPy for
numbers and with a CasADi interpolant for symbols.

Interpolation (chosen: **linear**, not B-spline)
------------------------------------------------
Temperature and the wind components are linear in altitude between levels;
pressure is linear in ``ln p``, i.e. exponential between levels (the exact
solution of the hydrostatic equation for an isothermal slab).  Linear was
chosen over a B-spline because (1) ``ln p`` linear *is* the required
exponential law, a spline of ``ln p`` is not; (2) a spline through a
sounding with an inversion overshoots (temperatures and winds that are in
no data); (3) the CasADi ``linear`` interpolant and ``numpy.interp`` give
identical numbers, so symbolic and numeric evaluation do not drift;
(4) it is 1.5-2x cheaper.  The price: derivatives w.r.t. altitude jump at
the levels (the values are continuous).

Outside the table (never a silent 0 or a wild extrapolation)
------------------------------------------------------------
- Below the lowest level: all quantities are **clamped** to the lowest
  level's values (numeric evaluation warns with ``OutOfRangeWarning``).
- Above the highest level: an ``ISA`` matched to the top level
  (the ``ISA`` whose temperature offset and sea-level pressure make
  T and p at the top level exactly the profile's) gives
  temperature and pressure, so both are continuous at the top; the wind
  is held at the top level's value.
"""
from __future__ import annotations

import datetime as _dt
import warnings

import casadi as ca
import numpy as np

from ironbark_opt import _math as m
from ironbark_opt.atmosphere.base import (
    Atmosphere,
    wind_from_speed_direction,
)
from ironbark_opt.atmosphere.isa import ISA, Z_MAX, Z_MIN
from ironbark_opt.errors import InputError, OutOfRangeWarning

_KNOT = 1852.0 / 3600.0   # [m/s] per knot (exact, international nautical mile)

# DataFrame column names: canonical SI name first, then accepted variants with
# their conversion to SI.  Matching is case-insensitive.
_ALTITUDE_COLUMNS = {"altitude_m": 1.0}
_TEMPERATURE_COLUMNS = {"temperature_K": ("K", 0.0), "temperature_C": ("C", 273.15)}
_PRESSURE_COLUMNS = {"pressure_Pa": 1.0, "pressure_hPa": 100.0}
_WIND_SPEED_COLUMNS = {"wind_speed_mps": 1.0, "wind_speed_kt": _KNOT}
_WIND_DIRECTION_COLUMNS = ("wind_direction_deg", "wind_from_deg")


def _as_column(values, name: str, source) -> np.ndarray:
    try:
        arr = np.array(values, dtype=float)
    except (TypeError, ValueError) as exc:
        raise InputError(f"expected numbers ({exc})", source=source, field=name) from None
    if arr.ndim != 1:
        raise InputError(f"expected a 1-D sequence, got shape {arr.shape}",
                         source=source, field=name)
    bad = np.flatnonzero(~np.isfinite(arr))
    if bad.size:
        raise InputError(f"non-finite value {arr[bad[0]]!r} at level {bad[0]}",
                         source=source, field=name)
    arr.setflags(write=False)
    return arr


def _time_str(value):
    if isinstance(value, (_dt.datetime, _dt.date)):
        return value.isoformat()
    return None if value is None else str(value)


class Profile(Atmosphere):
    """Tabulated atmosphere (forecast, sounding, or any other source).

    Parameters
    ----------
    altitude : sequence of float [m]
        Geometric altitude above mean sea level of each level, strictly
        increasing, at least 2 levels, within -5 000..86 000 m.
    temperature : sequence of float [K]
        Air temperature at each level (> 100 K; kelvin, not Celsius).
    pressure : sequence of float [Pa]
        Static pressure at each level, strictly decreasing with altitude.
    wind_east, wind_north : sequence of float [m/s]
        Wind components (direction the air moves towards) at each level;
        see ``atmosphere.base`` for conversion from speed/direction-from.
    source : str
        Where the data came from (file, URL, model name); used in errors and
        ``describe()``.
    valid_time, run_time : datetime, str or None
        Time the profile is valid for / forecast model run time.
    latitude_deg, longitude_deg : float or None [deg]
        Location of the profile (metadata only).
    metadata : dict or None
        Anything else worth keeping (station id, grid point, ...).

    Attributes
    ----------
    altitude, temperature_levels, pressure_levels, wind_east_levels,
    wind_north_levels : read-only 1-D arrays [m, K, Pa, m/s, m/s]
        The levels as given (``temperature``/``pressure`` are the methods).

    Evaluation is symbolic-safe; see the module docstring for interpolation
    and the behaviour outside the table.  For CasADi the interpolant takes a
    scalar or any matrix of altitudes (mapped element-wise).
    """

    def __init__(self, altitude, temperature, pressure, wind_east, wind_north, *,
                 source: str, valid_time=None, run_time=None, latitude_deg=None,
                 longitude_deg=None, metadata: dict | None = None):
        cols = {name: _as_column(v, name, source) for name, v in (
            ("altitude", altitude), ("temperature", temperature), ("pressure", pressure),
            ("wind_east", wind_east), ("wind_north", wind_north))}
        n = cols["altitude"].size
        for name, arr in cols.items():
            if arr.size != n:
                raise InputError(f"has {arr.size} levels but altitude has {n}",
                                 source=source, field=name)
        if n < 2:
            raise InputError(f"need at least 2 levels, got {n}", source=source, field="altitude")
        z, t, p = cols["altitude"], cols["temperature"], cols["pressure"]
        self._check_levels(z, t, p, source)
        self.altitude = z
        self.temperature_levels = t
        self.pressure_levels = p
        self.wind_east_levels = cols["wind_east"]
        self.wind_north_levels = cols["wind_north"]
        self.source = str(source)
        self.valid_time = valid_time
        self.run_time = run_time
        self.latitude_deg = latitude_deg
        self.longitude_deg = longitude_deg
        self.metadata = dict(metadata or {})
        self._log_p = np.log(p)
        try:
            self._top = ISA._through(float(z[-1]), float(t[-1]), float(p[-1]))
        except InputError as exc:
            raise InputError(f"top level cannot be matched by an ISA ({exc.message})",
                             source=source, field=exc.field) from None
        self._interp = None

    @staticmethod
    def _check_levels(z, t, p, source):
        step = np.diff(z)
        bad = np.flatnonzero(step <= 0.0)
        if bad.size:
            i = bad[0] + 1
            raise InputError(f"altitudes must be strictly increasing: level {i} is "
                             f"{z[i]:g} m after {z[i - 1]:g} m", source=source, field="altitude")
        if z[0] < Z_MIN or z[-1] > Z_MAX:
            raise InputError(f"altitudes {z[0]:g}..{z[-1]:g} m outside -5000..86000 m "
                             "(geometric altitude above sea level, in metres)",
                             source=source, field="altitude")
        bad = np.flatnonzero(t <= 100.0)
        if bad.size:
            raise InputError(f"temperature {t[bad[0]]:g} K at level {bad[0]} is not a "
                             "plausible air temperature (expected kelvin, > 100 K)",
                             source=source, field="temperature")
        bad = np.flatnonzero(p <= 0.0)
        if bad.size:
            raise InputError(f"pressure {p[bad[0]]:g} Pa at level {bad[0]} must be positive",
                             source=source, field="pressure")
        bad = np.flatnonzero(np.diff(p) >= 0.0)
        if bad.size:
            i = bad[0] + 1
            raise InputError(f"pressure must decrease with altitude: level {i} has "
                             f"{p[i]:g} Pa >= {p[i - 1]:g} Pa below it",
                             source=source, field="pressure")

    # -- construction from other things -------------------------------------
    @classmethod
    def from_dataframe(cls, df, *, source: str | None = None, **kwargs) -> "Profile":
        """Profile from a pandas DataFrame with columns matched by name.

        Columns (case-insensitive): ``altitude_m``; ``temperature_K`` or
        ``temperature_C``; ``pressure_Pa`` or ``pressure_hPa``; wind as
        ``wind_east_mps`` + ``wind_north_mps``, or as ``wind_speed_mps`` /
        ``wind_speed_kt`` + ``wind_direction_deg`` / ``wind_from_deg``
        (meteorological direction the wind blows from, clockwise from north).
        Rows in strictly decreasing altitude (top-down soundings) are reversed.
        Other columns are ignored.  Numeric-only.

        Parameters
        ----------
        df : pandas.DataFrame
        source : str or None
            Name for errors and ``describe()``; default ``df.attrs["source"]``
            or ``"DataFrame"``.
        **kwargs
            Passed to the constructor (``valid_time``, ``run_time``, ...).
        """
        import pandas as pd

        attrs = dict(getattr(df, "attrs", {}) or {})
        if source is None:
            source = attrs.get("source") or "DataFrame"
        for key in ("valid_time", "run_time", "latitude_deg", "longitude_deg"):
            if key not in kwargs and attrs.get(key) is not None:
                kwargs[key] = attrs[key]
        lower = {}
        for col in df.columns:
            lower.setdefault(str(col).strip().lower(), col)

        def find(names):
            for name in names:
                if name.lower() in lower:
                    return name, df[lower[name.lower()]]
            return None, None

        def need(names, what):
            name, col = find(names)
            if col is None:
                raise InputError(f"no {what} column; expected one of {', '.join(names)} "
                                 f"(columns present: {', '.join(map(str, df.columns))})",
                                 source=source, field=what)
            return name, col

        def values(name, col):
            arr = pd.to_numeric(col, errors="coerce").to_numpy(dtype=float)
            bad = np.flatnonzero(~np.isfinite(arr))
            if bad.size:
                raise InputError(f"missing, non-numeric or non-finite value "
                                 f"{col.iloc[bad[0]]!r} in row {bad[0]}",
                                 source=source, field=name)
            return arr

        z = values(*need(list(_ALTITUDE_COLUMNS), "altitude_m"))
        tname, tcol = need(list(_TEMPERATURE_COLUMNS), "temperature")
        t = values(tname, tcol) + _TEMPERATURE_COLUMNS[tname][1]
        pname, pcol = need(list(_PRESSURE_COLUMNS), "pressure")
        p = values(pname, pcol) * _PRESSURE_COLUMNS[pname]
        ename, ecol = find(["wind_east_mps"])
        nname, ncol = find(["wind_north_mps"])
        if ecol is not None and ncol is not None:
            east, north = values(ename, ecol), values(nname, ncol)
        else:
            sname, scol = need(list(_WIND_SPEED_COLUMNS), "wind")
            dname, dcol = need(list(_WIND_DIRECTION_COLUMNS), "wind direction")
            speed = values(sname, scol) * _WIND_SPEED_COLUMNS[sname]
            east, north = wind_from_speed_direction(speed, np.radians(values(dname, dcol)))
        if z.size >= 2 and np.all(np.diff(z) < 0.0):
            z, t, p, east, north = (a[::-1] for a in (z, t, p, east, north))
        return cls(z, t, p, east, north, source=source, **kwargs)

    @classmethod
    def from_atmosphere(cls, atm: Atmosphere, altitudes, *, source: str | None = None,
                        **kwargs) -> "Profile":
        """Sample another atmosphere at the given altitudes [m]; numeric-only.

        Parameters
        ----------
        atm : Atmosphere
        altitudes : sequence of float [m]
            Geometric altitudes, strictly increasing.
        source : str or None
            Default: "<atm source> sampled at N levels".
        """
        z = _as_column(altitudes, "altitudes", source)
        desc = atm.describe()
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", OutOfRangeWarning)
            t_model, p = atm._thermo(z)
            east, north = atm.wind_l(z)
        if source is None:
            source = f"{desc.get('source', type(atm).__name__)} sampled at {z.size} levels"
        for key in ("valid_time", "run_time"):
            kwargs.setdefault(key, desc.get(key))
        return cls(z, t_model, p, east, north, source=source, **kwargs)

    def to_dataframe(self):
        """The levels as a DataFrame (columns ``altitude_m``, ``temperature_K``,
        ``pressure_Pa``, ``wind_east_mps``, ``wind_north_mps``; ``attrs`` =
        ``describe()``); numeric-only.  ``from_dataframe`` reads it back."""
        import pandas as pd

        df = pd.DataFrame({
            "altitude_m": np.array(self.altitude),
            "temperature_K": np.array(self.temperature_levels),
            "pressure_Pa": np.array(self.pressure_levels),
            "wind_east_mps": np.array(self.wind_east_levels),
            "wind_north_mps": np.array(self.wind_north_levels),
        })
        df.attrs.update(self.describe())
        return df

    # -- evaluation ----------------------------------------------------------
    def _interpolant(self) -> ca.Function:
        """One CasADi linear interpolant h -> [T, ln p, east, north] (built once)."""
        if self._interp is None:
            table = np.column_stack([self.temperature_levels, self._log_p,
                                     self.wind_east_levels, self.wind_north_levels])
            # casadi.interpolant: for m outputs the values are ordered with the
            # output index fastest, i.e. row-major (levels x outputs).
            self._interp = ca.interpolant("profile", "linear", [np.array(self.altitude)],
                                          table.ravel(order="C"))
        return self._interp

    def _lookup(self, h):
        """(T [K], ln p [-], east [m/s], north [m/s]) at h, same kind as h."""
        z_lo, z_hi = float(self.altitude[0]), float(self.altitude[-1])
        if m.is_symbolic(h):
            hc = m.clip(h, z_lo, z_hi)
            f = self._interpolant()
            if hc.numel() == 1:
                vals = f(hc)
                rows = [vals[i] for i in range(4)]
            else:
                shape = hc.shape
                out = f.map(hc.numel())(ca.reshape(hc, 1, hc.numel()))
                rows = [ca.reshape(out[i, :], shape[0], shape[1]) for i in range(4)]
            above = h > z_hi
            _, t_isa, lnp_isa = self._top._layer_state(h)
            t = m.if_else(above, t_isa, rows[0])
            lnp = m.if_else(above, lnp_isa, rows[1])
            return t, lnp, rows[2], rows[3]
        ha = np.asarray(h, dtype=float)
        if ha.size and np.nanmin(ha) < z_lo:
            warnings.warn(f"altitude {np.nanmin(ha):g} m below the profile's lowest level "
                          f"{z_lo:g} m ({self.source}): values clamped",
                          OutOfRangeWarning, stacklevel=4)
        z = self.altitude
        t = np.interp(ha, z, self.temperature_levels)
        lnp = np.interp(ha, z, self._log_p)
        east = np.interp(ha, z, self.wind_east_levels)
        north = np.interp(ha, z, self.wind_north_levels)
        above = ha > z_hi
        if np.any(above):
            with warnings.catch_warnings():
                warnings.simplefilter("ignore", OutOfRangeWarning)
                _, t_isa, lnp_isa = self._top._layer_state(ha)
            t = np.where(above, t_isa, t)
            lnp = np.where(above, lnp_isa, lnp)
        if not isinstance(h, np.ndarray):
            return float(t), float(lnp), float(east), float(north)
        return t, lnp, east, north

    def _thermo(self, h):
        """(temperature [K] without dT, pressure [Pa]) from one lookup; symbolic-safe."""
        t, lnp, _, _ = self._lookup(h)
        return t, m.exp(lnp)

    def _temperature(self, h):
        return self._lookup(h)[0]

    def pressure(self, h):
        """Static pressure [Pa], exponential between levels; symbolic-safe.

        Parameters
        ----------
        h : float, array, SX or MX [m]
            Geometric altitude above mean sea level.
        """
        return m.exp(self._lookup(h)[1])

    def wind_l(self, h):
        """Wind (east, north) [m/s], linear between levels, held outside; symbolic-safe.

        Parameters
        ----------
        h : float, array, SX or MX [m]
        """
        _, _, east, north = self._lookup(h)
        return east, north

    def _thermo_wind(self, h):
        """(T [K] without dT, p [Pa], east, north [m/s]) from one lookup; symbolic-safe."""
        t, lnp, east, north = self._lookup(h)
        return t, m.exp(lnp), east, north

    def describe(self) -> dict:
        """Source, times, location and the altitude range as a plain dict."""
        return {
            "model": "Profile",
            "source": self.source,
            "run_time": _time_str(self.run_time),
            "valid_time": _time_str(self.valid_time),
            "latitude_deg": self.latitude_deg,
            "longitude_deg": self.longitude_deg,
            "levels": int(self.altitude.size),
            "altitude_min_m": float(self.altitude[0]),
            "altitude_max_m": float(self.altitude[-1]),
            **({"metadata": dict(self.metadata)} if self.metadata else {}),
        }

    def __repr__(self) -> str:
        return (f"Profile({self.source!r}, {self.altitude.size} levels, "
                f"{self.altitude[0]:g}..{self.altitude[-1]:g} m)")

    def __getstate__(self):
        state = dict(self.__dict__)
        state["_interp"] = None
        return state
