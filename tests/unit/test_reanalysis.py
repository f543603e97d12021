"""ERA5-style pressure-level netCDF files (netCDF3 packed and netCDF4/HDF5)."""
from __future__ import annotations

import math
from datetime import datetime, timezone
from pathlib import Path

import numpy as np
import pytest
from scipy.io import netcdf_file

from ironbark_opt.atmosphere.levels import G0, R_AIR, geometric_height
from ironbark_opt.atmosphere.reanalysis import read_reanalysis
from ironbark_opt.errors import InputError

DATA = Path(__file__).resolve().parents[1] / "data" / "weather" / "reanalysis"
BELLA = DATA / "bella_lui_weather_data_ERA5.nc"        # netCDF3, int16 packed
EUROC = DATA / "euroc_2022_all_windows.nc"             # netCDF4 / HDF5
RAD = math.radians


def _raw_netcdf3(name, it, ilev, iy, ix):
    with netcdf_file(BELLA, "r", mmap=False) as nc:
        v = nc.variables[name]
        return float(v.data[it, ilev, iy, ix]) * v.scale_factor + v.add_offset


def test_netcdf3_values_at_grid_node_match_raw_decoding():
    # 47.0 N, 9.0 E is grid node (iy=4, ix=4); first record 2020-02-22 00Z.
    col = read_reanalysis(BELLA, latitude=RAD(47.0), longitude=RAD(9.0))
    assert col.valid_time == datetime(2020, 2, 22, tzinfo=timezone.utc)
    # Without a ground elevation every level is kept: 14 levels, 1000..600 hPa.
    assert col.pressure.size == 14
    np.testing.assert_allclose(col.pressure[[0, -1]], [100000.0, 60000.0])
    i850 = int(np.argmin(abs(col.pressure - 85000.0)))
    ilev = 7                                            # 850 hPa in the file's level axis
    assert col.temperature[i850] == pytest.approx(_raw_netcdf3("t", 0, ilev, 4, 4), abs=1e-9)
    assert col.wind_east[i850] == pytest.approx(_raw_netcdf3("u", 0, ilev, 4, 4), abs=1e-9)
    assert col.wind_north[i850] == pytest.approx(_raw_netcdf3("v", 0, ilev, 4, 4), abs=1e-9)
    H = _raw_netcdf3("z", 0, ilev, 4, 4) / G0
    assert col.altitude[i850] == pytest.approx(geometric_height(H, RAD(47.0)), abs=1e-6)
    assert 1000.0 < col.altitude[i850] < 1800.0         # 850 hPa is near 1.5 km


def test_bilinear_and_time_interpolation():
    # Midway between 4 nodes and between records 0 (00Z) and 1 (06Z).
    t = datetime(2020, 2, 22, 3, tzinfo=timezone.utc)
    col = read_reanalysis(BELLA, latitude=RAD(47.125), longitude=RAD(9.125), time=t)
    expect = np.mean([_raw_netcdf3("t", it, 0, iy, ix)
                      for it in (0, 1) for iy in (3, 4) for ix in (4, 5)])
    i600 = int(np.argmin(col.pressure))
    assert col.temperature[i600] == pytest.approx(expect, abs=1e-9)


def test_hypsometric_consistency_of_geopotential_and_temperature():
    """Independent check: thickness between levels from the file's geopotential vs
    the hypsometric equation (Wallace & Hobbs, Atmospheric Science, 2nd ed., eq.
    3.29) with the layer-mean temperature; moisture is ignored (virtual
    temperature within ~1 % of T), so the tolerance is 1.5 %."""
    pytest.importorskip("h5py")
    col = read_reanalysis(EUROC, latitude=RAD(39.5), longitude=RAD(-8.5),
                          time=datetime(2022, 10, 13, 12))
    assert col.source.endswith("euroc_2022_all_windows.nc")
    p, T = col.pressure, col.temperature
    H = col.altitude   # geometric; convert back to geopotential at this latitude
    lat = RAD(39.5)
    # geopotential thickness from the file vs R_d Tmean / g0 ln(p1/p2)
    Hgp = np.array([_inverse_geometric(z, lat) for z in H])
    dz_file = np.diff(Hgp)
    dz_hyps = R_AIR * 0.5 * (T[1:] + T[:-1]) / G0 * np.log(p[:-1] / p[1:])
    err = np.max(np.abs(dz_file - dz_hyps) / dz_hyps)
    print(f"hypsometric thickness vs ERA5 geopotential: max relative error {err:.3%}")
    assert err < 0.015


def _inverse_geometric(z, lat):
    lo, hi = z * 0.99, z * 1.0001 + 1.0
    for _ in range(80):
        mid = 0.5 * (lo + hi)
        if geometric_height(mid, lat) < z:
            lo = mid
        else:
            hi = mid
    return 0.5 * (lo + hi)


def test_netcdf4_cut_at_ground():
    pytest.importorskip("h5py")
    col = read_reanalysis(EUROC, latitude=RAD(39.389700), longitude=RAD(-8.288964),
                          time=datetime(2022, 10, 13, 12), ground_elevation=113.0)
    assert col.altitude[0] == pytest.approx(113.0)
    assert np.all(np.diff(col.altitude) > 0)
    assert 95000.0 < col.pressure[0] < 103000.0
    assert np.all(np.diff(col.pressure) < 0)
    assert 270.0 < col.temperature[0] < 310.0
    assert col.altitude[-1] > 40000.0


def test_time_outside_file_names_file_and_range():
    # The message lists the file's times (five here; a long file gives the range).
    with pytest.raises(InputError, match=r"outside the file \(it has 2020-02-22 00:00Z, 2020-02-22 06:00Z, "
                                         r"2020-02-22 12:00Z, 2020-02-22 13:00Z, 2020-02-22 18:00Z\)") as err:
        read_reanalysis(BELLA, latitude=RAD(47.0), longitude=RAD(9.0),
                        time=datetime(2021, 1, 1))
    assert "bella_lui" in str(err.value)


def test_position_outside_grid():
    with pytest.raises(InputError, match="latitude_deg 50 outside"):
        read_reanalysis(BELLA, latitude=RAD(50.0), longitude=RAD(9.0))


def test_not_a_netcdf_file(tmp_path):
    bad = tmp_path / "x.nc"
    bad.write_bytes(b"hello world")
    with pytest.raises(InputError, match="not a netCDF file"):
        read_reanalysis(bad, latitude=0.0, longitude=0.0)


def test_geometric_height_us_standard_atmosphere_1976():
    # U.S. Standard Atmosphere 1976, Table I: Z = 11 000 m geometric is
    # H = 10 981 m' (tabulated to the metre; eq. 18, H = r0 Z / (r0 + Z)).
    assert geometric_height(10981.0, None) == pytest.approx(11000.0, abs=0.5)
    assert geometric_height(11000.0 * 6356766.0 / (6356766.0 + 11000.0)) == \
        pytest.approx(11000.0, abs=1e-6)
    # List (1968) latitude form at 45.5425 deg, where normal gravity is
    # close to g0, agrees with the 1976 form within 0.05 % at 10 km.
    z45 = geometric_height(10000.0, RAD(45.5425))
    assert z45 == pytest.approx(geometric_height(10000.0), rel=5e-4)
    # Gravity is weaker at the equator, so a geopotential metre is longer.
    assert geometric_height(10000.0, 0.0) > geometric_height(10000.0, RAD(90.0))


def test_netcdf4_without_h5py_says_what_to_install(monkeypatch):
    import sys
    monkeypatch.setitem(sys.modules, "h5py", None)
    with pytest.raises(InputError, match=r"needs h5py \(pip install h5py\)"):
        read_reanalysis(EUROC, latitude=RAD(39.5), longitude=RAD(-8.5))
