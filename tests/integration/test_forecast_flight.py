"""A profile from each weather source, flown through ``simulate``: finite and plausible.

The Calisto example (RocketPy's reference rocket, Cesaroni M1670) is flown
with the site elevation set to each profile's ground.  In a standard
atmosphere (``ISA.from_site``) at these grounds (113-1655 m) it reaches
3190-3520 m AGL (measured once, 3466 m at 1400 m); a real profile changes
density by a few per cent and adds wind, so the apogee must lie in
2800-4000 m AGL (the ISA band widened by ~12 %).
"""
from __future__ import annotations

import dataclasses
import math
from datetime import datetime, timezone
from pathlib import Path

import numpy as np
import pytest

from ironbark_opt.atmosphere.forecast import forecast_profile
from ironbark_opt.atmosphere.reanalysis import read_reanalysis
from ironbark_opt.atmosphere.sounding import read_sounding

flight = pytest.importorskip("ironbark_opt.flight")
vehicle = pytest.importorskip("ironbark_opt.vehicle")
toml_io = pytest.importorskip("ironbark_opt.rocket.toml_io")
ROOT = Path(__file__).resolve().parents[2]
W = ROOT / "tests" / "data" / "weather"
CALISTO = ROOT / "examples" / "calisto" / "calisto.toml"


def _rap(server):
    rap = "/ncss/grid/grib/NCEP/RAP/CONUS_13km/Best"
    server.route(rap + "/dataset.xml", W / "ncss_RAP_CONUS_13km_20241211_1900_dataset.xml")
    server.route(rap, W / "ncss_rap_point_csv_constructed.csv")
    return forecast_profile("rap", "2024-12-11T21:00Z", site="spaceport_america")


def _gfs(server):
    pytest.importorskip("eccodes")
    key = "/gfs.20170905/06/atmos/gfs.t06z.pgrb2.0p25.f006"
    server.route(key + ".idx", W / "gfs_constructed.t06z.f006.grib2.idx")
    server.route(key, W / "gfs_constructed.t06z.f006.grib2")
    return forecast_profile("gfs", datetime(2017, 9, 5, 12), sources=["archive"],
                            now=datetime(2017, 9, 5, 12, tzinfo=timezone.utc),
                            latitude=math.radians(40.0), longitude=math.radians(-105.0),
                            elevation=1655.0)


SOURCES = {
    "rap_thredds": _rap,
    "gfs_grib_archive": _gfs,
    "sounding_csv": lambda s: read_sounding(W / "uwyo_wsgi_wyoming_sounding_heights.csv"),
    "sounding_text_list": lambda s: read_sounding(W / "uwyo_cgi_TEXT_LIST_OUN_1999050400.html"),
    "era5_netcdf3": lambda s: read_reanalysis(
        W / "reanalysis" / "bella_lui_weather_data_ERA5.nc", latitude=math.radians(47.213476),
        longitude=math.radians(9.003336), time=datetime(2020, 2, 22, 13), ground_elevation=407.0),
    "era5_netcdf4": lambda s: pytest.importorskip("h5py") and read_reanalysis(
        W / "reanalysis" / "euroc_2022_all_windows.nc", latitude=math.radians(39.3897),
        longitude=math.radians(-8.288964), time=datetime(2022, 10, 13, 12),
        ground_elevation=113.0),
}


@pytest.fixture(scope="module")
def rocket_file():
    return toml_io.load_rocket_toml(CALISTO)


# The second sounding format and the netCDF3 reanalysis are variants of sources
# already flown; they run with -m slow.
SLOW = {"sounding_text_list", "era5_netcdf3"}


@pytest.mark.parametrize("name", [pytest.param(n, marks=pytest.mark.slow) if n in SLOW else n
                                  for n in SOURCES])
def test_profile_flies(name, rocket_file, loopback, net_env, monkeypatch):
    for var in ("IRONBARK_THREDDS_URL", "IRONBARK_GFS_ARCHIVE_URL"):
        monkeypatch.setenv(var, loopback.url)
    col = SOURCES[name](loopback)
    ground = float(col.altitude[0])
    rf = dataclasses.replace(rocket_file, launch=dataclasses.replace(
        rocket_file.launch, site_elevation=ground, site_temperature=None, site_pressure=None))
    f = flight.simulate(vehicle.setup_from_file(rf, atmosphere=col.to_profile()))
    s = f.summary_values
    assert all(np.isfinite(v) for v in s.values() if isinstance(v, float))
    print(f"{name}: ground {ground:.0f} m, apogee {s['apogee_agl_m']:.0f} m AGL at "
          f"{s['apogee_time_s']:.1f} s, drift {s['apogee_east_m']:.0f} m E "
          f"{s['apogee_north_m']:.0f} m N")
    assert 2800.0 < s["apogee_agl_m"] < 4000.0
    assert 15.0 < s["apogee_time_s"] < 40.0
    assert 0.6 < s["max_mach"] < 1.2
