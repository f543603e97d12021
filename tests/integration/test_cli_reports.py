"""Flight card, KML and file exports end to end (CliRunner, Calisto example).

The card is rendered as SVG with its text kept as text, so the test reads
back what the page says and compares every number with ``--json``.
"""
import json
import re
import shutil
import sys
import xml.etree.ElementTree as ET
from pathlib import Path

import numpy as np
import pandas as pd
import pytest
from click.testing import CliRunner

from ironbark_opt.cli import main
from ironbark_opt.openrocket.simdata import COLUMNS
from kml_check import K, coordinates, ellipse_covariances, local_from_geodetic, parse_kml

ROOT = Path(__file__).resolve().parents[2]
ROCKET = str(ROOT / "examples/calisto/calisto.toml")
SPEC = str(ROOT / "examples/calisto/dispersions.toml")
LAT, LON, ELEV = 32.990254, -106.974998, 1400.0          # examples/calisto/calisto.toml [launch]
FLOAT = re.compile(r"[-+]?\d+(?:\.\d+)?")


@pytest.fixture(scope="module")
def runner():
    return CliRunner()


def _run(runner, args):
    res = runner.invoke(main, args)
    assert res.exit_code == 0, res.output
    return res


# --------------------------------------------------------------------------- flight card
#: card label -> (flight_card keys of the numbers on that line, in order; printed decimals)
CARD_NUMBERS = {
    "ballast mass": (["ballast_kg"], 3),
    "ballast position": (["ballast_x_m"], 3),
    "apogee per 100 g": (["apogee_per_100g_m"], 1),
    "target apogee": (["target_agl_m"], 1),
    "predicted apogee": (["apogee_agl_m"], 1),
    "apogee 5-95 %": (["apogee_p05_m", "apogee_p95_m", "samples"], 1),
    "apogee drift": (["apogee_east_m", "apogee_north_m"], 1),
    "rail-exit speed": (["rail_exit_speed_mps"], 2),
    "stability margin": (["static_margin_rail_exit_cal", "static_margin_min_cal"], 2),
    "max Mach": (["max_mach"], 3),
    "max q": (["max_dynamic_pressure_kPa"], 2),
    "landing (nominal)": (["landing_east_m", "landing_north_m", "landing_distance_m"], 1),
}


def _svg_texts(path):
    root = ET.parse(path).getroot()
    return [e.text for e in root.iter("{http://www.w3.org/2000/svg}text") if e.text]


@pytest.fixture(scope="module")
def card_run(runner, tmp_path_factory):
    out = tmp_path_factory.mktemp("card")
    card = out / "card.svg"
    res = _run(runner, ["ballast", ROCKET, "--target", "3000m", "--card", str(card), "--card-spec", SPEC,
                        "--card-samples", "8", "--json"])
    return json.loads(res.stdout), card


def test_card_numbers_equal_the_json(card_run):
    data, card_path = card_run
    card = dict(data["flight_card"])
    card["max_dynamic_pressure_kPa"] = card["max_dynamic_pressure_Pa"] / 1000
    texts = _svg_texts(card_path)
    for line in card["lines"]:
        assert line in texts, f"JSON line not on the page: {line!r}"
    checked = 0
    for text in texts:
        label = next((lab for lab in CARD_NUMBERS if text.startswith(lab + " ")), None)
        if label is None:
            continue
        keys, decimals = CARD_NUMBERS[label]
        numbers = [float(v) for v in FLOAT.findall(text[len(label):])]
        values = [card[k] for k in keys]
        assert len(numbers) >= len(values), text
        for key, printed, value in zip(keys, numbers, values):
            assert printed == pytest.approx(value, abs=0.5 * 10 ** -decimals + 1e-9), f"{label}: {key}"
            checked += 1
    el = card["landing_ellipse"]
    line = next(t for t in texts if t.startswith("landing ellipse "))
    a, b, az = (float(v) for v in FLOAT.findall(line.split("sigma", 1)[1])[:3])
    assert (a, b, az) == (pytest.approx(el["semi_major_m"], abs=0.05), pytest.approx(el["semi_minor_m"], abs=0.05),
                          pytest.approx(el["azimuth_deg"], abs=0.5))
    print(f"{checked} numbers on the card equal the JSON's")
    assert checked == 18
    # the card's flight is the solution's: same ballast, same apogee
    assert card["ballast_kg"] == pytest.approx(data["ballast_kg"], abs=1e-12)
    assert card["apogee_agl_m"] == pytest.approx(data["resimulated_apogee_agl_m"], abs=1e-6)
    assert card["target_agl_m"] == pytest.approx(3000.0)
    assert card["samples"] == 8 and card["apogee_p05_m"] < card["apogee_p95_m"]


def test_card_apogee_per_100g_is_the_derivative(card_run):
    """The card's sensitivity against a central difference of two flights (+-50 g)."""
    from ironbark_opt.flight import simulate
    from ironbark_opt.vehicle import load_setup

    data, _ = card_run
    setup = load_setup(ROCKET)
    m, x = data["ballast_kg"], data["ballast_x_m"]
    up, down = (simulate(setup, parameters={"ballast_mass": m + d, "ballast_x": x}).apogee_agl for d in (0.05, -0.05))
    fd = (up - down) / 0.1 * 0.1
    got = data["flight_card"]["apogee_per_100g_m"]
    print(f"apogee per 100 g: card {got:.3f} m, central difference {fd:.3f} m")
    assert got == pytest.approx(fd, rel=0.01)


def test_card_refused_before_work(runner, tmp_path):
    res = runner.invoke(main, ["ballast", ROCKET, "--target", "3000m", "--card", str(tmp_path / "no" / "c.pdf")])
    assert res.exit_code == 2 and "--card" in res.output and "does not exist" in res.output
    res = runner.invoke(main, ["ballast", ROCKET, "--target", "3000m", "--card", str(tmp_path / "c.docx")])
    assert res.exit_code == 2 and ".pdf" in res.output
    res = runner.invoke(main, ["ballast", ROCKET, "--target", "3000m", "--card-spec", SPEC])
    assert res.exit_code == 2 and "--card-spec needs --card" in res.output
    assert list(tmp_path.iterdir()) == []


# --------------------------------------------------------------------------- simulate: KML and OpenRocket CSV
@pytest.fixture(scope="module")
def simulated(runner, tmp_path_factory):
    out = tmp_path_factory.mktemp("sim")
    kml, orcsv, csv = out / "f.kml", out / "or.csv", out / "f.csv"
    res = _run(runner, ["simulate", ROCKET, "--descent", "--kml", str(kml), "--csv", str(orcsv),
                        "--csv-format", "openrocket", "--json"])
    _run(runner, ["simulate", ROCKET, "--descent", "--csv", str(csv)])
    return json.loads(res.stdout), kml, orcsv, pd.read_csv(csv)


def test_trajectory_kml(simulated):
    data, kml, _, table = simulated
    doc = parse_kml(kml.read_text())
    lines = [pm for pm in doc.findall(K + "Placemark") if pm.find(K + "LineString") is not None]
    assert len(lines) == 1
    ls = lines[0].find(K + "LineString")
    assert ls.find(K + "altitudeMode").text == "absolute"
    xyz = coordinates(ls)
    assert len(xyz) == len(table)
    # lon, lat, alt order: the first point is the rail, altitude above sea level
    assert xyz[0] == pytest.approx([LON, LAT, ELEV], abs=1e-7)
    assert xyz[:, 2] == pytest.approx(table["altitude_asl_m"].to_numpy(), abs=0.05)
    e, n = local_from_geodetic(xyz[:, 0], xyz[:, 1], LAT, LON, table["altitude_asl_m"].to_numpy())
    err = max(np.abs(e - table["x_east_m"]).max(), np.abs(n - table["y_north_m"]).max())
    print(f"trajectory KML back to east/north: max error {err * 100:.2f} cm over {len(xyz)} points")
    assert err < 0.02
    assert xyz[-1, 2] == pytest.approx(ELEV, abs=0.05)             # landed
    names = [pm.find(K + "name").text for pm in doc.findall(K + "Placemark")]
    assert names[0] == "launch rail" and any(nm.startswith("apogee") for nm in names)


def test_openrocket_csv(simulated):
    from ironbark_opt.telemetry import read_log

    data, _, orcsv, table = simulated
    text = orcsv.read_text(encoding="utf-8").splitlines()
    assert text[0] == "# Calisto (Ironbark-Opt simulation)"
    assert text[1] == f"# {len(table)} data points written for 26 variables."
    header = text[3]
    assert header.startswith("# Time (s),Altitude (m),")
    names = [re.match(r"(.*) \((.*)\)$", c).group(1) for c in header[2:].split(",")]
    unknown = [nm for nm in names if nm not in COLUMNS]
    assert not unknown, f"not OpenRocket data types: {unknown}"
    df = pd.read_csv(orcsv, comment="#", header=None, names=header[2:].split(","))
    assert len(df) == len(table)
    assert df["Altitude (m)"].to_numpy() == pytest.approx(table["altitude_agl_m"].to_numpy(), rel=1e-9, abs=1e-6)
    assert df["Mass (kg)"].to_numpy() == pytest.approx(table["mass_kg"].to_numpy(), rel=1e-9)
    assert df["Latitude (° N)"].iloc[0] == pytest.approx(LAT, abs=1e-8)
    # on the rail: 84 deg above the horizon, heading 133 deg = 90 - 133 = -43 deg from east (OpenRocket's angles)
    assert df["Vertical orientation (zenith) (°)"].iloc[0] == pytest.approx(84.0, abs=1e-6)
    assert df["Lateral orientation (azimuth) (°)"].iloc[0] == pytest.approx(-43.0, abs=1e-6)
    # vertical acceleration (differentiated) is -g in the ballistic coast near apogee
    coast = (df["Time (s)"] > data["apogee_time_s"] - 2) & (df["Time (s)"] < data["apogee_time_s"] + 2)
    assert df.loc[coast, "Vertical acceleration (m/s²)"].mean() == pytest.approx(-9.78, abs=0.3)
    log = read_log(orcsv)                                  # Ironbark's own OpenRocket-export reader
    assert log.format == "openrocket"
    print(f"OpenRocket CSV read back: apogee {log.apogee_agl:.2f} m vs --json {data['apogee_agl_m']:.2f} m")
    assert log.apogee_agl == pytest.approx(data["apogee_agl_m"], abs=0.5)
    assert log.events["burnout"] == pytest.approx(data["burnout_time_s"], abs=1e-3)
    assert log.events["rail_exit"] == pytest.approx(data["rail_exit_time_s"], abs=1e-3)


def test_openrocket_csv_to_apogee_reads_back(runner, tmp_path):
    """A flight exported to apogee only (no --descent) ends on its highest sample with the
    vertical speed ~0: read as ending at apogee (it was refused as 'still climbing'), not
    as a truncated climb; a log cut 3 s before apogee (vertical speed ~30 m/s) still is."""
    from ironbark_opt.errors import InputError
    from ironbark_opt.telemetry import read_log
    orcsv = tmp_path / "or.csv"
    data = json.loads(_run(runner, ["simulate", ROCKET, "--csv", str(orcsv), "--csv-format", "openrocket",
                                    "--json"]).stdout)
    log = read_log(orcsv)
    print(f"apogee-only OpenRocket CSV: apogee {log.apogee_agl:.2f} m at {log.events['apogee']:.2f} s "
          f"vs --json {data['apogee_agl_m']:.2f} m at {data['apogee_time_s']:.2f} s")
    assert log.apogee_agl == pytest.approx(data["apogee_agl_m"], abs=0.05)
    assert log.events["apogee"] == pytest.approx(data["apogee_time_s"], abs=0.05)
    lines = orcsv.read_text(encoding="utf-8").splitlines(keepends=True)
    head = [ln for ln in lines if ln.startswith("#")]
    rows = [ln for ln in lines if not ln.startswith("#")]
    keep = [r for r in rows if float(r.split(",")[0]) < data["apogee_time_s"] - 3.0]
    cut = tmp_path / "cut.csv"
    cut.write_text("".join(head + keep), encoding="utf-8")
    with pytest.raises(InputError, match="still climbing"):
        read_log(cut)


def test_kml_needs_the_site_position(runner, tmp_path):
    src = ROOT / "examples/calisto"
    for f in src.iterdir():
        shutil.copy(f, tmp_path / f.name)
    toml = tmp_path / "calisto.toml"
    toml.write_text("\n".join(ln for ln in toml.read_text().splitlines() if not ln.startswith("longitude_deg")))
    res = runner.invoke(main, ["simulate", str(toml), "--kml", str(tmp_path / "f.kml")])
    assert res.exit_code == 2 and "--kml" in res.output and "latitude_deg and longitude_deg" in res.output
    assert not (tmp_path / "f.kml").exists()


# --------------------------------------------------------------------------- montecarlo: KML and samples
def test_montecarlo_kml_matches_its_covariance(runner, tmp_path):
    kml, csv, pq = tmp_path / "mc.kml", tmp_path / "s.csv", tmp_path / "s.parquet"
    res = _run(runner, ["montecarlo", ROCKET, "--spec", SPEC, "--samples", "6", "--chunk", "3", "--descent",
                        "--no-progress", "--kml", str(kml), "--samples-out", str(csv), "--json"])
    data = json.loads(res.stdout)
    samples = pd.read_csv(csv)
    assert len(samples) == 6
    cov = np.cov(samples[["landing_east_m", "landing_north_m"]].to_numpy().T)
    got = ellipse_covariances(kml.read_text(), LAT, LON, ELEV)
    for k, c in got.items():
        err = np.abs(c - cov).max() / np.abs(cov).max()
        print(f"{k:g} sigma polygon covariance vs samples: max rel. error {err:.1e}")
        assert err < 1e-5
    w = np.sqrt(np.linalg.eigvalsh(cov))
    assert data["landing_ellipse"]["semi_major_m"] == pytest.approx(w[1], rel=1e-9)
    pytest.importorskip("pyarrow")
    _run(runner, ["montecarlo", ROCKET, "--spec", SPEC, "--samples", "6", "--chunk", "3", "--descent",
                  "--no-progress", "--samples-out", str(pq)])
    pd.testing.assert_frame_equal(pd.read_parquet(pq), samples, check_exact=False, rtol=1e-12)


def test_parquet_without_pyarrow_is_refused(runner, tmp_path, monkeypatch):
    monkeypatch.setitem(sys.modules, "pyarrow", None)       # import pyarrow -> ImportError
    res = runner.invoke(main, ["montecarlo", ROCKET, "--spec", SPEC, "--samples", "2", "--no-progress",
                               "--samples-out", str(tmp_path / "s.parquet")])
    assert res.exit_code == 2 and "pyarrow" in res.output and "--samples-out" in res.output
    assert "Traceback" not in res.output and list(tmp_path.iterdir()) == []
    res = runner.invoke(main, ["montecarlo", ROCKET, "--spec", SPEC, "--samples", "2", "--no-progress",
                               "--samples-out", str(tmp_path / "s.xlsx")])
    assert res.exit_code == 2 and ".parquet" in res.output
