"""U.S. Standard Atmosphere 1976 (0-86 km geometric) with site offsets.

Source: COESA, *U.S. Standard Atmosphere, 1976*, NOAA-S/T 76-1562 (also
NASA-TM-X-74335), sections 1.2-1.3.  Below 32 km it is identical to the ICAO /
ISO 2533 standard atmosphere.

The model is written in closed form, layer by layer, in geopotential
altitude ``H``:

- geopotential from geometric altitude, ``H = r0 Z / (r0 + Z)`` (eq. 18),
- molecular-scale temperature linear in ``H`` per layer,
  ``T = T_b + L_b (H - H_b)`` (eq. 23),
- pressure ``p = p_b (T_b / T)^(g0' M0 / (R* L_b))`` (eq. 33a) or, in the
  isothermal layers, ``p = p_b exp(-g0' M0 (H - H_b) / (R* T_b))`` (eq. 33b).

For speed inside a CasADi SX RK4 step the layer is *selected* rather than
every layer evaluated: with per-layer constants A, L, B, c1, c2,
``T = A + L H`` and ``ln p = B + c1 ln T + c2 H`` (eqs. 23, 33a, 33b
rearranged; ``c1 = -g0'M0/(R* L_b)`` in gradient layers, ``c2 =
-g0'M0/(R* T_b)`` in isothermal ones, else 0), each constant a sum of step
functions of ``H`` sharing seven comparisons, and one ``log``/``exp`` pair.
Measured (CasADi 3.8.2 SX VM, 2-core machine under load, 1000 evaluations
of T, p, rho, a, mu in one Function, min-median over runs): 0.4-1.1 ms
(99 instructions per evaluation), on a par with a cubic B-spline table of
T and ln p at 100 m spacing (0.4-1.4 ms, and 0.06 K error at the layer
kinks, 1.4e-6 in p), slower than a linear table (0.2-0.6 ms); compiled
(-O1) 0.16 ms.  The closed form is exact, so it is used.
In generated C the selection is ~8 % of a compiled Calisto ascent's instructions
(callgrind: 2.92e6 -> 2.67e6 per flight with the troposphere's constants alone, the
same numbers to the bit); a branch to them below 11 km (a CasADi switch, which the SX
right-hand side can only call through a never-inlined MX Function) saved 0.8 %, the
call layers costing the rest, and no time (paired runs of 2000 samples): not used.
Temperature and pressure are continuous across layer boundaries (the base
values are computed by marching the same formulas), and so is dp/dh.

Deliberate simplifications (documented, both < 0.05 %):

- Temperature is the molecular-scale temperature ``T_M``; the standard's
  kinetic temperature differs from it only between 80 and 86 km, by the
  factor M/M0 >= 0.999579 (Table 8).
- Above 86 km geometric (84 852 m geopotential) the model continues
  isothermal at 186.946 K, as the standard's kinetic temperature itself
  does from 86 to 91 km; numeric evaluation warns (``OutOfRangeWarning``)
  above 86 km and below -5 km, where the standard stops.

Site offsets: ``ISA(temperature_offset, pressure_offset)`` shifts every
layer base temperature by ``temperature_offset`` and the sea-level pressure by
``pressure_offset`` and re-integrates the hydrostatic equation, so the
offset atmosphere stays hydrostatically consistent.  (The per-call ``dT``
argument of the methods is different: it is applied at constant pressure.)
"""
from __future__ import annotations

import math
import warnings

import numpy as np

from ironbark_opt import _math as m
from ironbark_opt.atmosphere.base import M0, R_STAR, Atmosphere, constant_like
from ironbark_opt.errors import InputError, OutOfRangeWarning

# 1976 standard, Table 2 / eq. 18: effective Earth radius for geopotential [m]
# and the geopotential constant g0' [m^2/(s^2 m')].
R0_GEOPOTENTIAL = 6356766.0
G0 = 9.80665
SEA_LEVEL_TEMPERATURE = 288.15    # [K]   Table 2
SEA_LEVEL_PRESSURE = 101325.0     # [Pa]  Table 2
# g0' M0 / R*  [K/m], the hydrostatic constant of eqs. 33a/33b (R* in J/(kmol K)).
_K_HYDRO = G0 * M0 / R_STAR

# Table 4: layer base geopotential altitude H_b [m'] and molecular-scale
# temperature gradient L_b [K/m'].  The last layer (from 84 852 m' = 86 km
# geometric) is this module's isothermal extension.
_LAYER_H = (0.0, 11000.0, 20000.0, 32000.0, 47000.0, 51000.0, 71000.0, 84852.0)
_LAYER_L = (-0.0065, 0.0, 0.001, 0.0028, 0.0, -0.0028, -0.002, 0.0)

Z_MIN = -5000.0    # [m] bottom of the standard's tables
Z_MAX = 86000.0    # [m] top of the homogeneously mixed model


def geopotential_altitude(z):
    """Geopotential altitude H [m'] from geometric altitude [m]; symbolic-safe.

    H = r0 Z / (r0 + Z), U.S. Standard Atmosphere 1976 eq. 18.

    Parameters
    ----------
    z : float, array, SX or MX [m]
    """
    return R0_GEOPOTENTIAL * z / (R0_GEOPOTENTIAL + z)


def geometric_altitude(H):
    """Geometric altitude Z [m] from geopotential altitude [m']; symbolic-safe.

    Z = r0 H / (r0 - H), the inverse of 1976 standard eq. 18.

    Parameters
    ----------
    H : float, array, SX or MX [m']
    """
    return R0_GEOPOTENTIAL * H / (R0_GEOPOTENTIAL - H)


def _layer_table(temperature_offset: float, sea_level_pressure: float):
    """Base temperature [K] and ln(base pressure [Pa]) of each layer (numeric)."""
    t_b = [SEA_LEVEL_TEMPERATURE + temperature_offset]
    lnp_b = [math.log(sea_level_pressure)]
    for i in range(1, len(_LAYER_H)):
        dh = _LAYER_H[i] - _LAYER_H[i - 1]
        lapse, t0 = _LAYER_L[i - 1], t_b[-1]
        t1 = t0 + lapse * dh
        if lapse == 0.0:
            lnp = lnp_b[-1] - _K_HYDRO * dh / t0                  # eq. 33b
        else:
            lnp = lnp_b[-1] - _K_HYDRO / lapse * math.log(t1 / t0)  # eq. 33a
        t_b.append(t1)
        lnp_b.append(lnp)
    return t_b, lnp_b


def _selector(H):
    """Function v -> v[layer of H], from step functions sharing 7 comparisons; symbolic-safe."""
    steps = [H >= hb for hb in _LAYER_H[1:]]

    def select(values):
        out = values[0]
        for i in range(1, len(values)):
            jump = values[i] - values[i - 1]
            if jump != 0.0:
                out = out + jump * steps[i - 1]
        return out
    return select


class ISA(Atmosphere):
    """U.S. Standard Atmosphere 1976 with site offsets and a constant wind.

    Parameters
    ----------
    temperature_offset : float [K]
        Added to every layer base temperature; the pressure profile is
        re-integrated hydrostatically (a warm day has higher pressure aloft).
    pressure_offset : float [Pa]
        Added to the sea-level pressure 101 325 Pa; pressure at every altitude
        scales by the same factor (hydrostatics is linear in p).
    wind_east, wind_north : float [m/s]
        Constant wind (direction the air moves towards) at all altitudes.

    All evaluation methods are symbolic-safe (floats, NumPy arrays, CasADi
    SX/MX); see the module docstring for the formulas and their validity.
    """

    def __init__(self, temperature_offset: float = 0.0, pressure_offset: float = 0.0,
                 wind_east: float = 0.0, wind_north: float = 0.0):
        self._setup(temperature_offset, pressure_offset, wind_east, wind_north,
                    plausible_pressure=True)

    def _setup(self, temperature_offset, pressure_offset, wind_east, wind_north, *,
               plausible_pressure: bool):
        values = {"temperature_offset": temperature_offset, "pressure_offset": pressure_offset,
                  "wind_east": wind_east, "wind_north": wind_north}
        for name, value in values.items():
            if isinstance(value, bool) or not isinstance(value, (int, float, np.number)) \
                    or not math.isfinite(value):
                raise InputError(f"expected a finite number, got {value!r}", field=name)
        if not -100.0 <= temperature_offset <= 100.0:
            raise InputError(f"temperature offset {temperature_offset:g} K is outside +-100 K "
                             "(temperatures are in kelvin, not Celsius)",
                             field="temperature_offset")
        p0 = SEA_LEVEL_PRESSURE + pressure_offset
        lo, hi = (0.5 * SEA_LEVEL_PRESSURE, 1.5 * SEA_LEVEL_PRESSURE) if plausible_pressure \
            else (0.0, math.inf)
        if not lo < p0 <= hi:
            raise InputError(f"sea-level pressure {p0:g} Pa is implausible "
                             "(expected 50 662..151 988 Pa; pressures are in Pa, not hPa)",
                             field="pressure_offset")
        self.temperature_offset = float(temperature_offset)
        self.pressure_offset = float(pressure_offset)
        self.wind_east = float(wind_east)
        self.wind_north = float(wind_north)
        self._t_b, self._lnp_b = _layer_table(self.temperature_offset, p0)
        # Per-layer constants of T = A + L H and ln p = B + c1 ln T + c2 H, i.e.
        # T = T_b + L (H - H_b), ln p = ln p_b + c1 ln(T / T_b) + c2 (H - H_b)
        # with c1 = -g0'M0/(R* L) (eq. 33a) or c2 = -g0'M0/(R* T_b) (eq. 33b).
        self._c1 = [0.0 if L == 0.0 else -_K_HYDRO / L for L in _LAYER_L]
        self._c2 = [-_K_HYDRO / t if L == 0.0 else 0.0 for L, t in zip(_LAYER_L, self._t_b)]
        self._a = [t - L * hb for t, L, hb in zip(self._t_b, _LAYER_L, _LAYER_H)]
        self._b = [lnp - c1 * math.log(t) - c2 * hb for lnp, c1, c2, t, hb
                   in zip(self._lnp_b, self._c1, self._c2, self._t_b, _LAYER_H)]

    @classmethod
    def _through(cls, elevation: float, temperature: float, pressure: float) -> "ISA":
        """ISA with T and p exactly as given at ``elevation`` [m], no plausibility check
        on the implied sea-level pressure (used to continue a profile above its top,
        where that pressure is only a fitting constant)."""
        dtemp = float(temperature) - float(cls().temperature(float(elevation)))
        probe = cls.__new__(cls)
        probe._setup(dtemp, 0.0, 0.0, 0.0, plausible_pressure=False)
        scale = float(pressure) / float(probe.pressure(float(elevation)))
        out = cls.__new__(cls)
        out._setup(dtemp, SEA_LEVEL_PRESSURE * (scale - 1.0), 0.0, 0.0,
                   plausible_pressure=False)
        return out

    @classmethod
    def from_site(cls, elevation: float, temperature: float | None = None,
                  pressure: float | None = None, *, wind_east: float = 0.0,
                  wind_north: float = 0.0) -> "ISA":
        """ISA matched to measured conditions at the launch site.

        The temperature offset is ``temperature - T_std(elevation)`` so that
        ``T(elevation) == temperature``; then the sea-level pressure is scaled
        so that ``p(elevation) == pressure`` with that offset's hydrostatic
        profile.  A quantity given as None keeps its standard value.

        Parameters
        ----------
        elevation : float [m]
            Site geometric altitude above mean sea level.
        temperature : float or None [K]
            Measured site air temperature.
        pressure : float or None [Pa]
            Measured site station pressure (not the sea-level QNH).
        wind_east, wind_north : float [m/s]
        """
        for name, value in (("elevation", elevation), ("temperature", temperature),
                            ("pressure", pressure)):
            if value is not None and (not isinstance(value, (int, float, np.number))
                                      or not math.isfinite(value)):
                raise InputError(f"expected a finite number, got {value!r}", field=name)
        if not Z_MIN <= elevation <= Z_MAX:
            raise InputError(f"site elevation {elevation:g} m outside -5000..86000 m",
                             field="elevation")
        if temperature is not None and temperature <= 0.0:
            raise InputError(f"site temperature {temperature:g} K must be positive (kelvin)",
                             field="temperature")
        if pressure is not None and pressure <= 0.0:
            raise InputError(f"site pressure {pressure:g} Pa must be positive",
                             field="pressure")
        dtemp = 0.0
        if temperature is not None:
            dtemp = float(temperature) - float(cls().temperature(float(elevation)))
        dpress = 0.0
        if pressure is not None:
            p_model = float(cls(temperature_offset=dtemp).pressure(float(elevation)))
            dpress = SEA_LEVEL_PRESSURE * (float(pressure) / p_model - 1.0)
        return cls(dtemp, dpress, wind_east, wind_north)

    # -- evaluation ----------------------------------------------------------
    def _check_range(self, z):
        if not m.is_symbolic(z):
            za = np.asarray(z, dtype=float)
            if za.size and (np.nanmax(za) > Z_MAX or np.nanmin(za) < Z_MIN):
                warnings.warn("altitude outside the 1976 standard's -5..86 km: below, the "
                              "troposphere lapse continues; above, isothermal extension",
                              OutOfRangeWarning, stacklevel=4)

    def _layer_state(self, z):
        """(H, T, ln p) at geometric altitude z; symbolic-safe."""
        self._check_range(z)
        H = geopotential_altitude(z)
        select = _selector(H)
        T = select(self._a) + select(_LAYER_L) * H
        lnp = select(self._b) + select(self._c1) * m.log(T) + select(self._c2) * H
        return H, T, lnp

    def _thermo(self, h):
        """(temperature [K] without dT, pressure [Pa]) from one layer lookup; symbolic-safe."""
        _, T, lnp = self._layer_state(h)
        return T, m.exp(lnp)

    def _temperature(self, h):
        """Molecular-scale temperature [K] at geometric altitude h [m]; symbolic-safe."""
        self._check_range(h)
        H = geopotential_altitude(h)
        select = _selector(H)
        return select(self._a) + select(_LAYER_L) * H

    def pressure(self, h):
        """Static pressure [Pa] at geometric altitude ``h`` [m]; symbolic-safe.

        Parameters
        ----------
        h : float, array, SX or MX [m]
        """
        return m.exp(self._layer_state(h)[2])

    def wind_l(self, h):
        """Constant wind (east, north) [m/s] shaped like ``h``; symbolic-safe."""
        return constant_like(h, self.wind_east), constant_like(h, self.wind_north)

    def describe(self) -> dict:
        """Model, source and offsets as a plain dict."""
        return {
            "model": "ISA",
            "source": "U.S. Standard Atmosphere 1976 (NOAA-S/T 76-1562)",
            "run_time": None,
            "valid_time": None,
            "temperature_offset_K": self.temperature_offset,
            "pressure_offset_Pa": self.pressure_offset,
            "sea_level_pressure_Pa": SEA_LEVEL_PRESSURE + self.pressure_offset,
            "wind_east_mps": self.wind_east,
            "wind_north_mps": self.wind_north,
        }

    def __repr__(self) -> str:
        return (f"ISA(temperature_offset={self.temperature_offset:g}, "
                f"pressure_offset={self.pressure_offset:g}, wind_east={self.wind_east:g}, "
                f"wind_north={self.wind_north:g})")

    def _key(self):
        return (self.temperature_offset, self.pressure_offset, self.wind_east, self.wind_north)

    def __eq__(self, other) -> bool:
        return isinstance(other, ISA) and self._key() == other._key()

    def __hash__(self) -> int:
        return hash(self._key())
