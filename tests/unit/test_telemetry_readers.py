"""Telemetry readers against the real logs in tests/data/telemetry.

Expected apogees are the figures of ../shared/fixtures/telemetry/README.md
for each file (the device's header/event value where the README quotes it,
else the file's maximum), asserted within the README's rounding plus the
device's altitude resolution.
"""
from __future__ import annotations

import gzip
import math

import numpy as np
import pytest

from conftest import DATA
from ironbark_opt.errors import InputError
from ironbark_opt.telemetry import FORMATS, detect_format, read_log

TEL = DATA / "telemetry"
FT = 0.3048

# file, format, README apogee [m AGL], tolerance [m], which figure ('max' or 'device'), README apogee time [s]
CASES = [
    ("nustars-2026-ft1-telemega.csv.gz", "altos", 2198.6, 0.05 + 0.01, "max", 20.41),
    ("nustars-2026-ft2-telemega.csv.gz", "altos", 2669.0, 0.05 + 0.01, "max", 24.61),
    ("issuiuc-2023-stargazer1-easymega.csv", "altos", 571.9, 0.05 + 0.01, "max", 11.72),
    ("issuiuc-2021-endurance-telemetrum.csv", "altos", 2853.9, 0.05 + 0.01, "max", 22.4),
    ("icl-apex1-pnut.pf2", "perfectflite", 9335 * FT, 1 * FT, "max", 21.15),
    ("icl-apex1-pnut.pf2", "perfectflite", 9333 * FT, 1 * FT, "device", None),
    ("issuiuc-2023-intrepid3-tf2-slcf.pf2", "perfectflite", 15373 * FT, 1 * FT, "device", None),
    ("issuiuc-2022-intrepid3-tf1-sl100.csv", "perfectflite", 2450 * FT, 1 * FT, "device", None),
    ("issuiuc-2023-sg1.2-booster-sl-datacap.txt", "perfectflite", 1530 * FT, 1 * FT, "max", 9.8),
    ("euroc21-sta-carl2-eggtimer.csv", "eggtimer", 9318 * FT, 1 * FT, "device", 21.85),
    ("euroc21-skyward-lynx-eggtimer.csv", "eggtimer", 10094 * FT, 1 * FT, "device", 23.15),
    # Anomaly fixture (failed motor, bad baro): the README quotes the TRS's own spurious
    # 976 ft at 1.0 s (the true ~170 m is not recoverable from this log).
    ("euroc21-aris-euler-eggtimer-trs.csv", "eggtimer", 976 * FT, 1 * FT, "device", 1.0),
    ("euroc21-sta-carl2-rrc3.csv", "rrc3", 2779.95, 0.01, "max", 21.9),
    ("nustars-2025-08-16-blueraven-lr.csv.gz", "blueraven", 4061.1 * FT, 0.05 * FT + 0.1 * FT, "max", 15.58),
    ("euroc23-aesir-cats-gs.csv", "cats", 3385.31, 1.0, "max", None),
]


def test_every_fixture_log_is_covered():
    logs = {p.name for p in TEL.iterdir() if p.suffix not in (".ork", ".eng") and not p.name.endswith(".stats.txt")}
    assert logs == {c[0] for c in CASES}


@pytest.mark.parametrize("name, fmt, apogee, tol, which, t_apo", CASES)
def test_reader_apogee_matches_readme(name, fmt, apogee, tol, which, t_apo):
    log = read_log(TEL / name)
    assert log.format == fmt
    got = log.apogee_agl if which == "max" else log.device_apogee_agl
    print(f"{name}: apogee ({which}) {got:.2f} m vs README {apogee:.2f} m, error {got - apogee:+.3f} m (tol {tol:.3f})")
    assert abs(got - apogee) <= tol
    if t_apo is not None:
        assert abs(log.apogee_time - t_apo) <= 0.011
    # time from launch detection, events ordered like a flight
    assert log.events["apogee"] == pytest.approx(log.apogee_time)
    if "burnout" in log.events and fmt != "eggtimer":
        assert 0 < log.events["burnout"] < log.apogee_time
    d = log.to_dict()
    assert d["apogee_agl_m"] == pytest.approx(log.apogee_agl)
    assert "apogee" in log.summary()
    df = log.to_dataframe()
    assert np.all(np.diff(df["time_s"].values) > 0)


def test_altos_columns_units_and_states():
    log = read_log(TEL / "nustars-2026-ft1-telemega.csv.gz")
    assert log.channels() == ("altitude", "vertical_speed", "acceleration")
    # README: max speed 266 m/s; the pad at 228.6 m per the .ork, the log's baro MSL - AGL here
    assert log.vertical_speed.max() == pytest.approx(266, abs=0.5)
    assert log.events["drogue"] > log.apogee_time - 1.0
    assert log.events["main"] > log.events["drogue"]
    with pytest.raises(ValueError):
        log.altitude_agl[0] = 1.0                # immutable


def test_rrc3_sorted_and_decimal_commas():
    log = read_log(TEL / "euroc21-sta-carl2-rrc3.csv")
    assert any("sorted" in n for n in log.notes)
    assert np.all(np.diff(log.time) > 0) and log.time[1] == pytest.approx(0.05)
    assert log.events["drogue"] == pytest.approx(23.8)
    assert log.events["main"] == pytest.approx(121.35)


def test_eggtimer_scaled_columns_agree_with_altitude():
    """CARL2 writes Filt_Alt/FVeloc x100: once divided, the filtered speed
    integrates to the altitude climbed (independent check of the scale)."""
    log = read_log(TEL / "euroc21-sta-carl2-eggtimer.csv")
    assert any("x100" in n for n in log.notes)
    up = (log.time >= 0) & (log.time <= log.apogee_time)
    climbed = np.trapezoid(log.vertical_speed[up], log.time[up])
    print(f"integrated FVeloc {climbed:.0f} m vs apogee {log.apogee_agl:.0f} m")
    assert climbed == pytest.approx(log.apogee_agl, rel=0.05)


def test_cats_links_deduplicated():
    log = read_log(TEL / "euroc23-aesir-cats-gs.csv")
    assert any("repeated time" in n for n in log.notes)
    assert log.gaps                                           # radio gaps are reported
    assert log.events["burnout"] < log.apogee_time < log.events["drogue"] + 1


def test_same_flight_two_devices_agree():
    """CARL2: Eggtimer (9318 ft) and RRC3 (2780 m) within 3 % of each other (two baro sensors)."""
    a = read_log(TEL / "euroc21-sta-carl2-eggtimer.csv").apogee_agl
    b = read_log(TEL / "euroc21-sta-carl2-rrc3.csv").apogee_agl
    print(f"CARL2 Eggtimer {a:.1f} m, RRC3 {b:.1f} m, difference {100 * (a - b) / b:.2f} %")
    assert abs(a - b) / b < 0.03


def test_truncated_file_names_the_line(tmp_path):
    text = gzip.decompress((TEL / "nustars-2026-ft1-telemega.csv.gz").read_bytes()).decode()
    lines = text.splitlines(keepends=True)
    cut = tmp_path / "cut.csv"
    cut.write_text("".join(lines[:1500]) + lines[1500][:40])
    with pytest.raises(InputError) as err:
        read_log(cut)
    print(err.value)
    assert err.value.line == 1501 and "truncated" in str(err.value)


def test_log_that_stops_while_climbing(tmp_path):
    lines = (TEL / "icl-apex1-pnut.pf2").read_text().splitlines(keepends=True)
    cut = tmp_path / "cut.pf2"
    cut.write_text("".join(lines[:200]))
    with pytest.raises(InputError, match="still climbing"):
        read_log(cut)


@pytest.mark.parametrize("name", ["AeroTech_L1940X.eng", "euroc23-aesir-cats-gs.stats.txt",
                                  "nustars-2026-ft1-telemega.ork"])
def test_foreign_file_is_rejected(name):
    with pytest.raises(InputError) as err:
        read_log(TEL / name)
    print(err.value)
    assert err.value.line == 1 and err.value.source.endswith(name)


def test_bad_cell_names_line_and_column(tmp_path):
    lines = (TEL / "euroc21-skyward-lynx-eggtimer.csv").read_text().splitlines()
    lines[10] = lines[10].replace(",", ",x", 1)
    bad = tmp_path / "bad.csv"
    bad.write_text("\n".join(lines))
    with pytest.raises(InputError) as err:
        read_log(bad)
    assert err.value.line == 11 and err.value.field == "Alt"


def _openrocket_export(path, g=9.80665, a=50.0, t_b=2.0):
    """OpenRocket CSV layout (units ft, ft/s, G's) of a vacuum flight: constant
    acceleration a to t_b, then ballistic; apogee = (a t_b)^2 / (2 g) + a t_b^2 / 2."""
    t = np.arange(0, 40.0, 0.05)
    v = np.where(t < t_b, a * t, a * t_b - g * (t - t_b))
    h = np.where(t < t_b, 0.5 * a * t ** 2, 0.5 * a * t_b ** 2 + a * t_b * (t - t_b) - 0.5 * g * (t - t_b) ** 2)
    acc = np.where(t < t_b, a, -g)
    keep = h >= 0
    rows = ["# Simulation 1", "# Time (s),Altitude (ft),Vertical velocity (ft/s),Vertical acceleration (G's)",
            "# Event LAUNCH occurred at t=0 seconds"]
    for ti, hi, vi, ai in zip(t[keep], h[keep], v[keep], acc[keep]):
        if abs(ti - t_b) < 1e-9:
            rows.append(f"# Event BURNOUT occurred at t={t_b} seconds")
        rows.append(f"{ti:.3f},{hi / FT:.4f},{vi / FT:.4f},{ai / g:.5f}")
    path.write_text("\n".join(rows) + "\n")
    return (a * t_b) ** 2 / (2 * g) + 0.5 * a * t_b ** 2, t_b + a * t_b / g


def test_openrocket_export_units_and_events(tmp_path):
    f = tmp_path / "or.csv"
    apogee, t_apo = _openrocket_export(f)
    log = read_log(f)
    assert log.format == "openrocket"
    print(f"OpenRocket export apogee {log.apogee_agl:.3f} m vs analytic {apogee:.3f} m")
    assert log.apogee_agl == pytest.approx(apogee, abs=0.05 * 0.05 * 9.81)   # sampling at 0.05 s
    assert log.events["burnout"] == pytest.approx(2.0)
    assert log.acceleration.max() == pytest.approx(50.0, rel=1e-4)
    assert log.events["liftoff"] == pytest.approx(0.0, abs=0.03)   # sqrt(h) fit on a constant-a boost


def test_generic_column_map(tmp_path):
    f = tmp_path / "any.txt"
    t = np.arange(-1, 30, 0.1)
    h = np.where(t > 0, 100 * t - 4.9 * t ** 2, 0) / FT + 500       # ft MSL, apogee at t = 100/9.8
    f.write_text("t_ms;alt_ft\n" + "\n".join(f"{int(round(a * 1000))};{b:.2f}".replace(".", ",")
                                              for a, b in zip(t, h)) + "\n")
    log = read_log(f, columns="time=t_ms:ms,altitude=alt_ft:ft", decimal_comma=True, altitude_is_agl=False)
    assert log.apogee_agl == pytest.approx(100 ** 2 / (4 * 4.9), abs=0.1)
    with pytest.raises(InputError, match="unknown altitude unit"):
        read_log(f, columns="time=t_ms:ms,altitude=alt_ft:furlong")
    assert detect_format(TEL / "icl-apex1-pnut.pf2") == "perfectflite" and "cats" in FORMATS


def test_noise_estimate_on_known_noise():
    """Channel noise from second differences recovers a known white-noise sigma."""
    from ironbark_opt.telemetry import build_log
    rng = np.random.default_rng(1)
    t = np.arange(0, 30, 0.01)
    h = np.where(t < 3, 30 * t ** 2, 270 + 180 * (t - 3) - 4.9 * (t - 3) ** 2)   # 60 m/s^2 boost, coast
    log = build_log("synthetic", "test", "x", t, h + rng.normal(0, 2.0, t.size))
    print(f"noise estimate {log.noise('altitude'):.3f} m vs 2.000 m")
    assert log.noise("altitude") == pytest.approx(2.0, rel=0.08)
    assert math.isclose(log.events["liftoff"], 0.0, abs_tol=0.1)


@pytest.mark.slow
def test_copies_are_byte_identical_to_shared_fixtures():
    """tests/data/telemetry holds the ../shared logs unchanged (the three > 1 MB ones gzipped)."""
    from pathlib import Path
    shared = Path(__file__).resolve().parents[3] / "shared" / "fixtures" / "telemetry"
    if not shared.exists():
        pytest.skip("shared fixtures not mounted (../shared is not beside this checkout)")
    for src in shared.glob("*/*"):
        if src.name == "README.md" or src.name == "icl-apex1-pnut.ork":
            continue
        copy = TEL / src.name
        data = copy.read_bytes() if copy.exists() else gzip.decompress((TEL / (src.name + ".gz")).read_bytes())
        assert data == src.read_bytes(), src.name
        if src.suffix in (".csv", ".pf2", ".txt") and not src.name.endswith(".stats.txt"):
            assert read_log(src).apogee_agl == pytest.approx(read_log(TEL / (copy.name if copy.exists()
                                                                             else src.name + ".gz")).apogee_agl)
