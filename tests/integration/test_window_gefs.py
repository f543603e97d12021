"""``ironbark window --forecast gefs``: every member of every hour, served by a loopback THREDDS.

No recorded GEFS response exists; the files are BUILT (tests/data/weather/make_gefs.py, README):
the dataset description in the layout of netCDF-Java's dataset.xml with an Ensemble axis of 21
members, and TDS 5 point CSVs (``alt`` vertical column) of members 0, 1, 2 whose temperature is the
recorded GFS column (+0, +2, -2 K) and whose wind is a uniform westerly of 8, 10, 6 m/s.  Hour k's
body is the member's file with its time set to the hour and both wind columns multiplied by
``f_k = 0.35 + 0.1 k``: member m's wind at rail exit is ``W_m f_k`` exactly, so every member's
go/no-go against a rail-wind limit of 8 m/s, and the number of members go per hour, is known:
member 0 go for k <= 6, member 1 for k <= 4, member 2 for k <= 9.
"""
from __future__ import annotations

import json
from datetime import datetime, timedelta, timezone
from pathlib import Path

import numpy as np
import pytest
from click.testing import CliRunner

from conftest import scaled_point_csv
from ironbark_opt.cli import main

ROOT = Path(__file__).resolve().parents[2]
W = ROOT / "tests" / "data" / "weather"
CALISTO = str(ROOT / "examples" / "calisto" / "calisto.toml")
GEFS = "/ncss/grid/grib/NCEP/GEFS/Global_1p0deg_Ensemble/members/Best"
T0 = datetime(2024, 12, 11, 18, tzinfo=timezone.utc)
HOURS, STEP = 12, 3                                  # GEFS is 3-hourly
WIND = {0: 8.0, 1: 10.0, 2: 6.0}                     # [m/s] westerly of each member's file
MAX_RAIL_WIND = 8.0


def _factor(k):
    return 0.35 + 0.1 * k


def _body(k, m):
    return scaled_point_csv(W / f"ncss_gefs_member{m}_point_csv_built.csv",
                            (T0 + timedelta(hours=STEP * k)).strftime("%Y-%m-%dT%H:%M:%SZ"), _factor(k), (7, 8))


@pytest.fixture
def thredds(loopback, net_env, monkeypatch):
    monkeypatch.setenv("IRONBARK_THREDDS_URL", loopback.url)
    monkeypatch.setenv("IRONBARK_FORECAST_SOURCES", "thredds")
    loopback.route(GEFS + "/dataset.xml", W / "ncss_GEFS_members_built_dataset.xml")
    bodies = {((T0 + timedelta(hours=STEP * k)).strftime("%Y-%m-%dT%H:%M:%SZ"), str(m)): _body(k, m)
              for k in range(HOURS) for m in WIND}
    loopback.route(GEFS, by_query=(("time", "ensCoord"), bodies))
    return loopback


def _window(*extra, hours=HOURS):
    return ["window", CALISTO, "--forecast", "gefs", "--site", "spaceport_america", "--from",
            T0.strftime("%Y-%m-%dT%H:%MZ"), "--hours", str(hours), "--step-hours", str(STEP), *extra]


def test_gefs_member_profile_is_the_built_column(thredds):
    from ironbark_opt.atmosphere.forecast import forecast_profile
    from ironbark_opt.atmosphere.levels import geometric_height
    import math

    col = forecast_profile("gefs", T0, site="spaceport_america", member=1)
    q = thredds.requests[-1]["query"]
    assert q["ensCoord"] == ["1"] and "Temperature_isobaric_ens" in q["var"]
    assert "GEFS member 1" in col.source and col.valid_time == T0
    rows = [r.split(",") for r in (W / "ncss_gefs_member1_point_csv_built.csv").read_text().splitlines()[1:]]
    file = {float(r[1]): (float(r[5]), float(r[6])) for r in rows}
    for z, p, T in zip(col.altitude[1:], col.pressure[1:], col.temperature[1:]):
        assert T == pytest.approx(file[p][1])
        assert z == pytest.approx(geometric_height(file[p][0], math.radians(33.0)))
    np.testing.assert_allclose(col.wind_east, WIND[1] * _factor(0), atol=1e-9)
    np.testing.assert_allclose(col.wind_north, 0.0, atol=1e-12)


def test_tds4_answer_with_every_member_is_filtered_to_the_one_asked(thredds):
    """TDS 4 writes all members with an ``ensMember`` column (CSVPointDataWriter): the rows of
    the member asked for are kept, in the TDS 4 header names (date/lat/lon/vertCoord)."""
    from ironbark_opt.atmosphere.forecast import forecast_profile

    rows = {m: _body(0, m).decode().splitlines() for m in (0, 1)}
    head = ('date,lat[unit="degrees_north"],lon[unit="degrees_east"],ensMember,vertCoord[unit="Pa"],'
            + rows[0][0].split(",", 5)[5])
    lines = [head]
    for r0, r1 in zip(rows[0][1:], rows[1][1:]):             # interleaved members, as TDS 4 loops
        for m, r in ((0, r0), (1, r1)):
            c = r.split(",")
            lines.append(",".join([c[0], c[3], c[4], str(m), c[1]] + c[5:]))
    thredds.route(GEFS, "\n".join(lines) + "\n")
    col = forecast_profile("gefs", T0, site="spaceport_america", member=1)
    np.testing.assert_allclose(col.wind_east, WIND[1] * _factor(0), atol=1e-9)
    file = {float(r.split(",")[1]): float(r.split(",")[6]) for r in rows[1][1:]}
    assert all(T == pytest.approx(file[p]) for p, T in zip(col.pressure[1:], col.temperature[1:]))


def test_gefs_window_members_table_plot_card(thredds, tmp_path, monkeypatch):
    plot, card = tmp_path / "window.png", tmp_path / "card.png"
    res = CliRunner().invoke(main, _window("--members", "3", "--target", "3000m", "--band", "5",
                                           "--max-rail-wind", str(MAX_RAIL_WIND), "--min-go-fraction", "0.6",
                                           "--plot", str(plot), "--card", str(card), "--json"))
    assert res.exit_code == 0, res.output
    n_first = len(thredds.requests)
    data = json.loads(res.output)
    assert data["ensemble_members"] == 3 and data["members"] == [0, 1, 2]
    hours = data["hours"]
    assert len(hours) == HOURS and all("error" not in h for h in hours)
    for k, h in enumerate(hours):
        members = h["members"]
        assert [m["member"] for m in members] == [0, 1, 2]
        wind = {m["member"]: m["rail_exit_wind_mps"] for m in members}
        for m, w in WIND.items():
            assert wind[m] == pytest.approx(w * _factor(k), rel=1e-6)
        go = [w * _factor(k) <= MAX_RAIL_WIND for w in WIND.values()]
        assert [m["go"] for m in members] == go
        assert h["members_go"] == sum(go) and h["members_flown"] == 3
        assert h["go"] == (sum(go) / 3 >= 0.6)
        # one ballast per hour, solved on the control run: the control lands on the target,
        # the others fly the same ballast
        assert {m["ballast_kg"] for m in members} == {h["ballast_kg"]}
        assert members[0]["apogee_agl_m"] == pytest.approx(3000.0, abs=1.0)
        # the hour's numbers are the members' median / 5 / 95 % (numpy, linear) and fraction in band
        apo = np.array([m["apogee_agl_m"] for m in members])
        assert h["apogee_agl_m"] == pytest.approx(np.median(apo))
        assert (h["apogee_p05_agl_m"], h["apogee_p95_agl_m"]) == pytest.approx(tuple(np.percentile(apo, [5, 95])))
        assert h["probability_in_band"] == pytest.approx(np.mean(np.abs(apo - 3000.0) <= 5.0))
        drift = [m["apogee_drift_m"] for m in members]
        assert h["apogee_drift_p95_m"] == pytest.approx(np.percentile(drift, 95))
        assert h["landing_distance_m"] == pytest.approx(np.median([m["landing_distance_m"] for m in members]))
        assert h["rail_exit_wind_p95_mps"] == pytest.approx(np.percentile(list(wind.values()), 95))
    # member spread is real: the +2 K / 10 m/s and -2 K / 6 m/s members miss the control's apogee
    spreads = [h["apogee_p95_agl_m"] - h["apogee_p05_agl_m"] for h in hours]
    print("apogee 5-95 % spread over members per hour [m]:", [round(s, 1) for s in spreads])
    assert min(spreads) > 1.0
    assert {round(h["probability_in_band"], 6) for h in hours} >= {1.0, 0.333333}   # members leave the band
    # the table: one line per hour with members go / flown
    text = CliRunner().invoke(main, _window("--members", "3", "--max-rail-wind", str(MAX_RAIL_WIND),
                                            hours=2)).stdout
    assert "3 ensemble members per hour" in text and "GO 3/3" in text
    assert plot.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n" and plot.stat().st_size > 20_000
    # the card: the control member of the first go hour, and the hour's numbers over the members
    assert card.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    fc = data["flight_card"]
    first_go = next(h for h in hours if h["go"])
    assert fc["time_utc"] == first_go["time_utc"]
    control = first_go["members"][0]
    for key in ("apogee_agl_m", "ballast_kg", "rail_exit_speed_mps", "static_margin_rail_exit_cal",
                "max_mach", "landing_distance_m"):
        assert fc[key] == pytest.approx(control[key], rel=1e-9, abs=1e-9), key
    ens = fc["ensemble"]
    for key in ("apogee_agl_m", "apogee_p05_agl_m", "apogee_p95_agl_m", "members_go", "probability_in_band"):
        assert ens[key] == pytest.approx(first_go[key]), key
    assert any(f"{ens['apogee_p95_agl_m']:.1f}" in line for line in fc["lines"])
    assert ens["landing_east_m"] == pytest.approx([m["landing_east_m"] for m in first_go["members"]])
    # the collection's description is fetched once for the whole window, not per hour and member
    # (it was 1 + 12 hours x 3 members = 37 requests)
    assert sum(r["path"].endswith("/dataset.xml") for r in thredds.requests[:n_first]) == 1
    # second run: offline, every member of the hours from the cache
    n = len(thredds.requests)
    monkeypatch.setenv("IRONBARK_OFFLINE", "1")
    res2 = CliRunner().invoke(main, _window("--members", "3", "--json", hours=2))
    assert res2.exit_code == 0, res2.output
    assert len(thredds.requests) == n
    again = json.loads(res2.output)["hours"]
    assert [m["rail_exit_wind_mps"] for m in again[1]["members"]] == pytest.approx(
        [m["rail_exit_wind_mps"] for m in hours[1]["members"]])


def test_gefs_flight_error_is_not_a_missing_forecast(thredds):
    """A flight's own error (a target below the site) stops the command as on a deterministic
    hour (exit 2, that message); it used to turn every hour into "no forecast"."""
    res = CliRunner().invoke(main, _window("--members", "2", "--target", "1000m ASL", hours=2))
    assert res.exit_code == 2, res.output
    line = res.stderr.strip().splitlines()[-1]
    assert line.startswith("error:") and "below the launch site" in line and "no forecast" not in line


def test_gefs_bad_member_count_and_deterministic_members(thredds):
    res = CliRunner().invoke(main, _window("--members", "40", hours=1))
    assert res.exit_code == 2 and "--members" in res.stderr and "Global_1p0deg_Ensemble" in res.stderr
    assert "has 21" in res.stderr and "Traceback" not in res.output
    res = CliRunner().invoke(main, ["window", CALISTO, "--forecast", "rap", "--site", "spaceport_america",
                                    "--from", "2024-12-11T20:00Z", "--members", "3"])
    assert res.exit_code == 2 and "--members" in res.stderr and "deterministic" in res.stderr


def test_gefs_dataset_without_ensemble_axis(thredds):
    xml = (W / "ncss_GEFS_members_built_dataset.xml").read_text()
    thredds.route(GEFS + "/dataset.xml", xml.replace('axisType="Ensemble"', 'axisType="GeoZ"'))
    res = CliRunner().invoke(main, _window("--members", "3", hours=1))
    assert res.exit_code == 2, res.output
    line = res.stderr.strip().splitlines()[-1]
    assert line.startswith("error:") and "ensemble axis" in line and "dataset.xml" in line
    assert "Geopotential_height_isobaric_ens" in line


def test_gefs_answer_missing_the_member_is_a_network_error(thredds):
    # a TDS 4 style answer (ensMember column) that lists only member 5: the member asked for is
    # missing, so the response is malformed for that request -> network error, exit 3
    body = _body(0, 0).decode().splitlines()
    head = body[0].replace("station,", "ensMember,")
    rows = [",".join(r.split(",")[:2] + ["5"] + r.split(",")[3:]) for r in body[1:]]
    thredds.route(GEFS, "\n".join([head] + rows) + "\n")
    res = CliRunner().invoke(main, _window("--members", "1", hours=1))
    assert res.exit_code == 3, res.output
    assert "ensMember" in res.stderr and "member 0" in res.stderr


def test_member_off_the_ensemble_axis(thredds):
    from ironbark_opt.atmosphere.forecast import forecast_profile
    from ironbark_opt.errors import InputError

    with pytest.raises(InputError, match=r"member 25 is not on the Ensemble axis") as err:
        forecast_profile("gefs", T0, site="spaceport_america", member=25)
    assert "Global_1p0deg_Ensemble/members/Best/dataset.xml" in str(err.value)
    assert "Geopotential_height_isobaric_ens" in str(err.value)
    with pytest.raises(InputError, match="ensemble: give a member"):
        forecast_profile("gefs", T0, site="spaceport_america")


def test_gefs_with_a_dispersion_spec_pools_the_members_monte_carlo(thredds):
    spec = str(ROOT / "examples" / "calisto" / "dispersions.toml")
    res = CliRunner().invoke(main, _window("--members", "2", "--target", "3000m", "--spec", spec, "--samples", "6",
                                           "--seed", "3", "--json", hours=1))
    assert res.exit_code == 0, res.output
    h = json.loads(res.output)["hours"][0]
    members = h["members"]
    assert h["monte_carlo_samples"] == 12 and all(m["monte_carlo_samples"] == 6 for m in members)
    # the same samples per member (common seed): the pooled fraction in band is the members' mean
    assert h["probability_in_band"] == pytest.approx(np.mean([m["probability_in_band"] for m in members]))
    assert h["apogee_p05_agl_m"] < h["apogee_p95_agl_m"]
    # the hour's band is the pooled flights', not the two members' nominal apogees
    nominal = np.percentile([m["apogee_agl_m"] for m in members], [5, 95])
    assert (h["apogee_p05_agl_m"], h["apogee_p95_agl_m"]) != pytest.approx(tuple(nominal))
