"""``ironbark weather get`` / ``ironbark weather sites`` against the loopback server."""
from __future__ import annotations

import json
from pathlib import Path

import pandas as pd
import pytest
from click.testing import CliRunner

from ironbark_opt.cli import main

W = Path(__file__).resolve().parents[1] / "data" / "weather"
RAP = "/ncss/grid/grib/NCEP/RAP/CONUS_13km/Best"


@pytest.fixture
def server(loopback, net_env, monkeypatch):
    for var in ("IRONBARK_THREDDS_URL", "IRONBARK_UWYO_URL"):
        monkeypatch.setenv(var, loopback.url)
    loopback.route(RAP + "/dataset.xml", W / "ncss_RAP_CONUS_13km_20241211_1900_dataset.xml")
    loopback.route(RAP, W / "ncss_rap_point_csv_constructed.csv")
    return loopback


def test_weather_get_rap_json_csv_plot(server, tmp_path):
    csv_path, png = tmp_path / "p.csv", tmp_path / "p.png"
    res = CliRunner().invoke(main, ["weather", "get", "--model", "rap", "--site",
                                    "spaceport_america", "--time", "2024-12-11T21:00Z",
                                    "--json", "--csv", str(csv_path), "--plot", str(png)])
    assert res.exit_code == 0, res.output
    out = json.loads(res.output)
    assert out["run_time"] == "2024-12-11T19:00:00Z" and out["valid_time"] == "2024-12-11T21:00:00Z"
    assert out["ground_elevation_m"] == 1400.0
    lv = out["levels"]
    assert lv["altitude_m"][0] == pytest.approx(1400.0)
    assert lv["wind_speed_mps"][3] == pytest.approx(12.0, abs=1e-3)
    assert lv["wind_direction_deg"][3] == pytest.approx(270.0, abs=0.01)
    df = pd.read_csv(csv_path)
    assert list(df.columns)[:4] == ["altitude_m", "altitude_agl_m", "pressure_Pa", "temperature_K"]
    assert len(df) == len(lv["altitude_m"])
    assert png.stat().st_size > 5000


def test_weather_get_human(server):
    res = CliRunner().invoke(main, ["weather", "get", "--model", "rap", "--site", "sac",
                                    "--time", "2024-12-11T21:00:00Z", "--top-m", "3000"])
    assert res.exit_code == 0, res.output
    assert "run: 2024-12-11 19:00Z" in res.output and "agl_m" in res.output
    rows = [ln for ln in res.output.splitlines() if ln.strip()[:1].isdigit()]
    assert float(rows[-1].split()[0]) <= 3000.0


def test_weather_get_sounding_file_and_reanalysis(tmp_path):
    res = CliRunner().invoke(main, ["weather", "get", "--model", "sounding", "--file",
                                    str(W / "uwyo_wsgi_wyoming_sounding.csv"), "--json"])
    assert res.exit_code == 0, res.output
    assert json.loads(res.output)["levels"]["pressure_Pa"][0] == pytest.approx(95900.0)
    pytest.importorskip("h5py")
    res = CliRunner().invoke(main, ["weather", "get", "--model", "reanalysis", "--file",
                                    str(W / "reanalysis" / "euroc_2022_all_windows.nc"),
                                    "--site", "euroc", "--time", "2022-10-13T12:00Z", "--json"])
    assert res.exit_code == 0, res.output
    assert json.loads(res.output)["ground_elevation_m"] == 113.0


def test_weather_errors(server):
    res = CliRunner().invoke(main, ["weather", "get", "--model", "rap", "--site", "sac",
                                    "--time", "2030-01-01T00:00Z"])
    assert res.exit_code in (2, 3) and "outside the model run" in res.output
    res = CliRunner().invoke(main, ["weather", "get", "--model", "rap", "--site", "sac"])
    assert res.exit_code == 2 and "--time" in res.output


def test_weather_sites(net_env):
    res = CliRunner().invoke(main, ["weather", "sites", "--json"])
    names = [s["name"] for s in json.loads(res.output)["sites"]]
    assert "spaceport_america" in names
