"""``ironbark window``: 12 forecast hours served by a loopback THREDDS, no network.

The hourly NCSS responses are CONSTRUCTED (not recorded): each is the
constructed RAP point CSV of tests/data/weather (recorded NCSS header format,
the RAP dataset's 37 levels at Spaceport America, U.S. Standard Atmosphere
1976 temperature and heights, grid-relative winds of a 12 m/s westerly) with
its date set to the hour and both wind columns multiplied by
``f_k = 0.25 + 0.0625 k`` (k = 0..11).  The grid rotation is linear, so hour
k's earth-relative wind is a westerly of ``12 f_k`` = 3.0 ... 11.25 m/s at every
level: the wind at rail exit is known exactly, and so is the go/no-go column
of a rail-wind limit.  The dataset description is the recorded RAP
``dataset.xml`` (runs 2024-12-11T19Z .. 12T16Z).
"""
from __future__ import annotations

import json
import math
from datetime import datetime, timedelta, timezone
from pathlib import Path

import pytest
from click.testing import CliRunner

from conftest import scaled_point_csv
from ironbark_opt.cli import main

ROOT = Path(__file__).resolve().parents[2]
W = ROOT / "tests" / "data" / "weather"
CALISTO = str(ROOT / "examples" / "calisto" / "calisto.toml")
SPEC = str(ROOT / "examples" / "calisto" / "dispersions.toml")
RAP = "/ncss/grid/grib/NCEP/RAP/CONUS_13km/Best"
T0 = datetime(2024, 12, 11, 20, tzinfo=timezone.utc)
HOURS = 12
WIND_0, WIND_STEP = 12.0 * 0.25, 12.0 * 0.0625       # [m/s] westerly of hour 0, increase per hour
MAX_RAIL_WIND = 8.0                                  # [m/s]: hours 0..6 go (3.0..7.5), 7..11 no-go


def _hour_csv(k: int) -> bytes:
    return scaled_point_csv(W / "ncss_rap_point_csv_constructed.csv",
                            (T0 + timedelta(hours=k)).strftime("%Y-%m-%dT%H:%M:%SZ"), 0.25 + 0.0625 * k, (6, 7))


@pytest.fixture
def thredds(loopback, net_env, monkeypatch):
    monkeypatch.setenv("IRONBARK_THREDDS_URL", loopback.url)
    monkeypatch.setenv("IRONBARK_FORECAST_SOURCES", "thredds")
    loopback.route(RAP + "/dataset.xml", W / "ncss_RAP_CONUS_13km_20241211_1900_dataset.xml")
    bodies = {(T0 + timedelta(hours=k)).strftime("%Y-%m-%dT%H:%M:%SZ"): _hour_csv(k) for k in range(HOURS)}
    loopback.route(RAP, by_query=("time", bodies))
    return loopback


def _window(*extra, hours=HOURS, first=0):
    return ["window", CALISTO, "--forecast", "rap", "--site", "spaceport_america",
            "--from", (T0 + timedelta(hours=first)).strftime("%Y-%m-%dT%H:%MZ"), "--hours", str(hours), *extra]


def test_window_twelve_hours_table_plot_json(thredds, tmp_path, monkeypatch):
    plot = tmp_path / "window.png"
    card = tmp_path / "card.png"
    res = CliRunner().invoke(main, _window("--target", "3000m", "--spec", SPEC, "--samples", "8",
                                           "--max-rail-wind", str(MAX_RAIL_WIND), "--min-margin", "1.0",
                                           "--plot", str(plot), "--card", str(card), "--json"))
    assert res.exit_code == 0, res.output
    data = json.loads(res.output)
    hours = data["hours"]
    assert len(hours) == HOURS and all("error" not in h for h in hours)
    for k, h in enumerate(hours):
        assert h["valid_time_utc"] == (T0 + timedelta(hours=k)).strftime("%Y-%m-%dT%H:%M:%SZ")
        # the constructed profile's wind is the same westerly at every level (4-digit CSV values)
        assert h["rail_exit_wind_mps"] == pytest.approx(WIND_0 + WIND_STEP * k, rel=1e-3)
        assert h["go"] == (WIND_0 + WIND_STEP * k <= MAX_RAIL_WIND), (k, h["no_go_reasons"])
        # each hour's ballast re-flies onto the target (same model, so to the metre)
        assert h["apogee_agl_m"] == pytest.approx(3000.0, abs=1.0)
        assert 0.0 <= h["probability_in_band"] <= 1.0
        assert h["apogee_p05_agl_m"] < h["apogee_agl_m"] + 50 and h["apogee_p95_agl_m"] > h["apogee_agl_m"] - 50
        assert h["landing_distance_m"] > 0
        for key in h:   # the JSON contract: unit-suffixed keys (or dimensionless by nature)
            assert key.endswith(("_m", "_s", "_kg", "_mps", "_cal", "_Pa", "_utc", "_h")) or key in {
                "max_mach", "go", "no_go_reasons", "atmosphere", "probability_in_band",
                "probability_in_band_stderr", "monte_carlo_samples", "monte_carlo_seed", "ballast_feasible",
                "landing_ellipse"}, key
        assert h["landing_ellipse"]["semi_major_m"] >= h["landing_ellipse"]["semi_minor_m"] > 0
    # a stronger westerly drifts the rocket further: more ballast needed as the wind rises
    # (weathercocking into the wind costs apogee), and the apogee drifts further downwind
    assert hours[-1]["ballast_kg"] < hours[0]["ballast_kg"]
    assert plot.stat().st_size > 20_000 and plot.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    # the flight card of the first go hour prints that hour's numbers (the same flight,
    # ballast and Monte Carlo samples, flown again from the cached forecast)
    assert card.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    fc = data["flight_card"]
    first_go = next(h for h in hours if h["go"])
    assert fc["time_utc"] == first_go["time_utc"]
    for key in ("apogee_agl_m", "ballast_kg", "ballast_x_m", "rail_exit_speed_mps", "static_margin_rail_exit_cal",
                "static_margin_min_cal", "max_mach", "probability_in_band", "landing_distance_m"):
        assert fc[key] == pytest.approx(first_go[key], rel=1e-9, abs=1e-9), key
    assert fc["target_agl_m"] == pytest.approx(3000.0)
    assert any(f"{fc['apogee_agl_m']:.1f}" in line for line in fc["lines"])
    # second run: offline, from the cache (no new request reaches the server)
    n_requests = len(thredds.requests)
    monkeypatch.setenv("IRONBARK_OFFLINE", "1")
    res2 = CliRunner().invoke(main, _window("--json"))
    assert res2.exit_code == 0, res2.output
    assert len(thredds.requests) == n_requests
    again = json.loads(res2.output)["hours"]
    assert [h["rail_exit_wind_mps"] for h in again] == pytest.approx([h["rail_exit_wind_mps"] for h in hours])


def test_window_table_and_hours_outside_the_forecast(thredds):
    # hours 5..13: the last two have no recorded response (the server answers 400): listed, not fatal
    res = CliRunner().invoke(main, _window("--max-rail-wind", str(MAX_RAIL_WIND), hours=9, first=5))
    assert res.exit_code == 0, res.output
    lines = res.stdout.splitlines()
    assert "Launch window for Calisto" in lines[0]
    rows = [ln for ln in lines if ln.startswith("  2024-12-1")]
    assert len(rows) == 9
    # hours 5, 6: 6.75 and 7.5 m/s at rail exit (go); 7..11: 8.25 ... 11.25 m/s (no-go)
    assert sum("NO-GO: wind at rail exit" in r for r in rows) == 5 and sum(r.endswith("  GO") for r in rows) == 2
    assert sum("no forecast" in r for r in rows) == 2


def test_window_bad_input_is_one_line():
    res = CliRunner().invoke(main, ["window", CALISTO, "--forecast", "rap", "--site", "spaceport_america",
                                    "--from", "tomorrow"])
    assert res.exit_code == 2 and "error:" in res.output and "Traceback" not in res.output
    res = CliRunner().invoke(main, ["window", CALISTO, "--forecast", "rap", "--site", "spaceport_america",
                                    "--from", "2024-12-11T20:00Z", "--hours", "0"])
    assert res.exit_code == 2 and "--hours" in res.output
