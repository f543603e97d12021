"""RAP and GFS forecast profiles through THREDDS NCSS, the NOMADS filter and the
cloud archive (.idx + byte ranges), served from 127.0.0.1, with faults."""
from __future__ import annotations

import csv
import math
from datetime import datetime, timezone
from pathlib import Path

import numpy as np
import pytest

from ironbark_opt.atmosphere.forecast import forecast_profile
from ironbark_opt.atmosphere.levels import geometric_height
from ironbark_opt.errors import InputError, NetworkError

W = Path(__file__).resolve().parents[1] / "data" / "weather"
RAP = "/ncss/grid/grib/NCEP/RAP/CONUS_13km/Best"
GFS = "/ncss/grid/grib/NCEP/GFS/Global_0p25deg/Best"
GFS_KEY = "/gfs.20170905/06/atmos/gfs.t06z.pgrb2.0p25.f006"
GRIB = W / "gfs_constructed.t06z.f006.grib2"
NOW = datetime(2017, 9, 5, 12, tzinfo=timezone.utc)
BOULDER = dict(latitude=math.radians(40.0), longitude=math.radians(-105.0), elevation=1655.0)


@pytest.fixture
def server(loopback, net_env, monkeypatch):
    for var in ("IRONBARK_THREDDS_URL", "IRONBARK_NOMADS_URL", "IRONBARK_GFS_ARCHIVE_URL",
                "IRONBARK_RAP_ARCHIVE_URL"):
        monkeypatch.setenv(var, loopback.url)
    return loopback


def _rap_routes(server):
    server.route(RAP + "/dataset.xml", W / "ncss_RAP_CONUS_13km_20241211_1900_dataset.xml")
    server.route(RAP, W / "ncss_rap_point_csv_constructed.csv")


def _rap_rows():
    rows = list(csv.reader(open(W / "ncss_rap_point_csv_constructed.csv")))[1:]
    return {float(r[3]): (float(r[4]), float(r[5])) for r in rows}


def test_rap_via_thredds(server):
    _rap_routes(server)
    col = forecast_profile("rap", "2024-12-11T21:00Z", site="spaceport_america")
    assert col.run_time == datetime(2024, 12, 11, 19, tzinfo=timezone.utc)
    assert col.valid_time == datetime(2024, 12, 11, 21, tzinfo=timezone.utc)
    assert "THREDDS" in col.source
    q = server.requests[-1]["query"]
    assert set(q["var"]) == {"Geopotential_height_isobaric", "Temperature_isobaric",
                             "u-component_of_wind_isobaric", "v-component_of_wind_isobaric"}
    assert q["time"] == ["2024-12-11T21:00:00Z"] and q["accept"] == ["csv"]
    assert float(q["latitude"][0]) == pytest.approx(32.990254, abs=1e-4)
    # Cut at the ground (1400 m): the first level is the ground.
    assert col.altitude[0] == pytest.approx(1400.0)
    assert np.all(np.diff(col.altitude) > 0) and np.all(np.diff(col.pressure) < 0)
    # Every level above the ground carries the recorded numbers.
    rows = _rap_rows()
    lat = math.radians(32.99)
    for z, p, T in zip(col.altitude[1:], col.pressure[1:], col.temperature[1:]):
        H, T_file = rows[p]
        assert T == pytest.approx(T_file)
        assert z == pytest.approx(geometric_height(H, lat))
    # Grid-relative winds rotated back to the 12 m/s westerly they were built from.
    np.testing.assert_allclose(col.wind_east, 12.0, atol=2e-4)
    np.testing.assert_allclose(col.wind_north, 0.0, atol=2e-4)
    # Ground pressure (log-p interpolation) vs U.S. Standard Atmosphere 1976 at
    # 1400 m, the atmosphere the file was built from (analytic check).
    H = 1400.0 * 6356766.0 / (6356766.0 + 1400.0)
    p_isa = 101325.0 * ((288.15 - 0.0065 * H) / 288.15) ** (9.80665 / (287.05287 * 0.0065))
    err = abs(col.pressure[0] - p_isa) / p_isa
    print(f"RAP ground pressure {col.pressure[0]:.0f} Pa vs ISA {p_isa:.0f} Pa: {err:.3%}")
    assert err < 2e-3


def test_forecast_time_outside_model_run(server):
    _rap_routes(server)
    with pytest.raises(InputError, match=r"outside the model run\(s\) available "
                                         r"\(2024-12-11T19:00Z to 2024-12-12T16:00Z\)") as err:
        forecast_profile("rap", "2024-12-14T12:00Z", site="sac", sources=["thredds"])
    assert RAP in str(err.value)
    assert server.paths() == [RAP + "/dataset.xml"]     # no data request made


def test_time_beyond_newest_run_for_grib_paths(server):
    with pytest.raises(InputError, match="forecasts reach 21 h"):
        forecast_profile("rap", "2024-12-14T12:00Z", site="sac", sources=["archive"],
                         now=datetime(2024, 12, 11, 21, tzinfo=timezone.utc))


def _recorded_gfs_temperatures():
    rows = list(csv.reader(open(W / "ncss_gfs0p5_point_csv_2015-06-12T15Z_40N_105W.csv")))[1:]
    return {float(r[3]): float(r[4]) for r in rows}


def test_gfs_falls_back_from_thredds_to_archive(server):
    pytest.importorskip("eccodes")
    server.route(GFS + "/dataset.xml", W / "ncss_GFS_Global_0p5deg_20170903_1200_dataset.xml")
    # The recorded point CSV has only temperature and humidity: THREDDS fails.
    server.route(GFS, W / "ncss_gfs0p5_point_csv_2015-06-12T15Z_40N_105W.csv")
    server.route(GFS_KEY + ".idx", GRIB.with_suffix(".grib2.idx"))
    server.route(GFS_KEY, GRIB)
    col = forecast_profile("gfs", datetime(2017, 9, 5, 12), now=NOW, **BOULDER)
    assert "archive" in col.source
    assert any("Geopotential_height_isobaric" in n for n in col.notes)
    assert col.run_time == datetime(2017, 9, 5, 6, tzinfo=timezone.utc)
    assert col.valid_time == datetime(2017, 9, 5, 12, tzinfo=timezone.utc)
    ranged = [r for r in server.requests if r["path"] == GFS_KEY]
    assert ranged and all(r["headers"]["Range"].startswith("bytes=") for r in ranged)
    # RH is skipped; UGRD, VGRD of one level and HGT, TMP of the next are
    # adjacent in the file and merged: 26 levels give 27 ranges.
    assert len(ranged) == 27
    recorded = _recorded_gfs_temperatures()
    err = max(abs(T - recorded[p]) for p, T in zip(col.pressure[1:], col.temperature[1:]))
    print(f"GFS GRIB2 temperatures vs recorded NCSS CSV: max |dT| = {err:.2e} K")
    assert err < 1e-3                      # 24-bit packing
    assert col.altitude[0] == pytest.approx(1655.0)
    assert 80000.0 < col.pressure[0] < 86000.0
    assert col.altitude[-1] > 30000.0


def test_gfs_via_nomads_filter(server):
    pytest.importorskip("eccodes")
    server.route("/cgi-bin/filter_gfs_0p25.pl", GRIB)
    col = forecast_profile("gfs", datetime(2017, 9, 5, 12), now=NOW, sources=["nomads"],
                           **BOULDER)
    q = server.requests[0]["query"]
    assert q["file"] == ["gfs.t06z.pgrb2.0p25.f006"] and q["dir"] == ["/gfs.20170905/06/atmos"]
    assert q["var_TMP"] == ["on"] and float(q["toplat"][0]) == pytest.approx(40.5)
    assert "NOMADS" in col.source and col.temperature.size > 10


def test_archive_tries_older_run_when_newest_is_missing(server):
    pytest.importorskip("eccodes")
    older = "/gfs.20170905/00/atmos/gfs.t00z.pgrb2.0p25.f012"
    server.route(older + ".idx", GRIB.with_suffix(".grib2.idx"))
    server.route(older, GRIB)
    col = forecast_profile("gfs", datetime(2017, 9, 5, 12), now=NOW, sources=["archive"],
                           **BOULDER)
    assert server.paths()[0] == GFS_KEY + ".idx" and server.paths()[1] == older + ".idx"
    assert col.temperature.size > 10


def test_truncated_grib_range_is_rejected_and_not_cached(server, net_env):
    pytest.importorskip("eccodes")
    server.route(GFS_KEY + ".idx", GRIB.with_suffix(".grib2.idx"))
    server.route(GFS_KEY, GRIB.read_bytes()[:-100])   # last message cut short
    with pytest.raises(NetworkError, match="truncated"):
        forecast_profile("gfs", datetime(2017, 9, 5, 12), now=NOW, sources=["archive"],
                         **BOULDER)
    files = [p for p in net_env.rglob("*") if p.is_file()]
    assert len(files) == 27            # the idx and the 26 good ranges; not the cut one
    assert not [p for p in files if p.name.startswith(".tmp")]


def test_malformed_grib_and_idx(server):
    server.route(GFS_KEY + ".idx", b"this is not an index\n")
    with pytest.raises(NetworkError, match="not an index line"):
        forecast_profile("gfs", datetime(2017, 9, 5, 12), now=NOW, sources=["archive"],
                         **BOULDER)
    server.route("/cgi-bin/filter_gfs_0p25.pl", b"<html>no such file</html>")
    with pytest.raises(NetworkError, match="no GRIB message at byte 0"):
        forecast_profile("gfs", datetime(2017, 9, 5, 12), now=NOW, sources=["nomads"],
                         **BOULDER)


def test_every_source_down(net_env, monkeypatch, closed_port_url):
    for var in ("IRONBARK_THREDDS_URL", "IRONBARK_NOMADS_URL", "IRONBARK_GFS_ARCHIVE_URL"):
        monkeypatch.setenv(var, closed_port_url)
    monkeypatch.setenv("IRONBARK_HTTP_RETRIES", "0")
    with pytest.raises(NetworkError) as err:
        forecast_profile("gfs", datetime(2017, 9, 5, 12), now=NOW, **BOULDER)
    msg = str(err.value)
    assert "[thredds]" in msg and "[nomads]" in msg and "[archive]" in msg
    assert "connection refused" in msg


def test_offline_replays_cached_forecast(server, monkeypatch):
    _rap_routes(server)
    first = forecast_profile("rap", "2024-12-11T21:00Z", site="spaceport_america")
    n = len(server.requests)
    monkeypatch.setenv("IRONBARK_OFFLINE", "1")
    again = forecast_profile("rap", "2024-12-11T21:00Z", site="spaceport_america")
    assert len(server.requests) == n
    np.testing.assert_array_equal(first.temperature, again.temperature)


def test_source_order_from_environment(server, monkeypatch):
    monkeypatch.setenv("IRONBARK_FORECAST_SOURCES", "archive")
    with pytest.raises(NetworkError) as err:
        forecast_profile("gfs", datetime(2017, 9, 5, 12), now=NOW, **BOULDER)
    assert "[thredds]" not in str(err.value) and "[archive]" in str(err.value)
    monkeypatch.setenv("IRONBARK_FORECAST_SOURCES", "carrier-pigeon")
    with pytest.raises(InputError, match="unknown forecast source"):
        forecast_profile("gfs", datetime(2017, 9, 5, 12), now=NOW, **BOULDER)


def test_unknown_site_lists_presets(net_env):
    with pytest.raises(InputError, match="spaceport_america"):
        forecast_profile("rap", "2024-12-11T21:00Z", site="atlantis")


def test_rap_grib_lambert_grid_relative_winds(server):
    """RAP GRIB2 on a Lambert grid with grid-relative winds (as NOAA publishes
    them): the archive path decodes and rotates them back to east 5, north 8."""
    pytest.importorskip("eccodes")
    key = "/rap.20241211/rap.t19z.awp130pgrbf02.grib2"
    server.route(key + ".idx", W / "rap_constructed.t19z.awp130pgrbf02.grib2.idx")
    server.route(key, W / "rap_constructed.t19z.awp130pgrbf02.grib2")
    col = forecast_profile("rap", "2024-12-11T21:00Z", site="spaceport_america",
                           sources=["archive"],
                           now=datetime(2024, 12, 11, 21, 30, tzinfo=timezone.utc))
    assert col.run_time == datetime(2024, 12, 11, 19, tzinfo=timezone.utc)
    assert col.valid_time == datetime(2024, 12, 11, 21, tzinfo=timezone.utc)
    err = max(np.max(abs(col.wind_east - 5.0)), np.max(abs(col.wind_north - 8.0)))
    print(f"RAP Lambert wind rotation: max error {err:.1e} m/s")
    assert err < 1e-3
    assert col.altitude[0] == pytest.approx(1400.0) and col.pressure.size > 10


def test_grib_without_eccodes_says_what_to_install(server, monkeypatch):
    import sys
    monkeypatch.setitem(sys.modules, "eccodes", None)
    server.route(GFS_KEY + ".idx", GRIB.with_suffix(".grib2.idx"))
    server.route(GFS_KEY, GRIB)
    with pytest.raises(InputError, match="decoding GRIB2 needs ecCodes: pip install eccodes"):
        forecast_profile("gfs", datetime(2017, 9, 5, 12), now=NOW, sources=["archive"],
                         **BOULDER)


def test_server_ignoring_range_still_gives_the_right_messages(server, monkeypatch):
    """A mirror that answers a Range request with the whole file (HTTP 200)."""
    pytest.importorskip("eccodes")
    server.route(GFS_KEY + ".idx", GRIB.with_suffix(".grib2.idx"))
    route = server.route(GFS_KEY, GRIB)
    from ironbark_opt import net
    real = net._request

    def no_range(url, params, json_body, headers, timeout):
        headers = {k: v for k, v in headers.items() if k != "Range"}
        return real(url, params, json_body, headers, timeout)
    monkeypatch.setattr(net, "_request", no_range)
    col = forecast_profile("gfs", datetime(2017, 9, 5, 12), now=NOW, sources=["archive"],
                           **BOULDER)
    assert route.calls == 27
    recorded = _recorded_gfs_temperatures()
    assert all(abs(T - recorded[p]) < 1e-3 for p, T in zip(col.pressure[1:], col.temperature[1:]))


def test_newer_thredds_csv_header_names(server):
    """TDS 5 names the columns time/latitude/longitude and the vertical by its
    axis (``isobaric``); columns are found by name, in any order."""
    text = (W / "ncss_rap_point_csv_constructed.csv").read_text()
    lines = text.splitlines()
    header = (lines[0].replace("date,", "time,").replace("lat[", "latitude[")
              .replace("lon[", "longitude[").replace("vertCoord[", "isobaric["))
    cols = header.split(",")
    order = [0, 7, 1, 2, 5, 3, 4, 6]                 # shuffle the columns
    new = [",".join(cols[i] for i in order)]
    for line in lines[1:]:
        c = line.split(",")
        new.append(",".join(c[i] for i in order))
    server.route(RAP + "/dataset.xml", W / "ncss_RAP_CONUS_13km_20241211_1900_dataset.xml")
    server.route(RAP, "\n".join(new) + "\n")
    col = forecast_profile("rap", "2024-12-11T21:00Z", site="spaceport_america",
                           sources=["thredds"])
    np.testing.assert_allclose(col.wind_east, 12.0, atol=2e-4)
    rows = _rap_rows()
    assert all(T == pytest.approx(rows[p][1]) for p, T in zip(col.pressure[1:], col.temperature[1:]))
