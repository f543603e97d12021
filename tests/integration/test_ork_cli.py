"""``ironbark ork info`` and ``ironbark simulate FILE.ork`` end to end (no network)."""
from __future__ import annotations

import json
import re
from pathlib import Path

import pytest
from click.testing import CliRunner

from ironbark_opt.cli import main
from ironbark_opt.openrocket.xmlread import read_bytes

DATA = Path(__file__).parents[1] / "data" / "ork"


@pytest.fixture
def env(monkeypatch, tmp_path):
    monkeypatch.setenv("IRONBARK_OFFLINE", "1")
    monkeypatch.setenv("IRONBARK_CACHE_DIR", str(tmp_path / "cache"))
    monkeypatch.setenv("IRONBARK_MOTOR_PATH", str(DATA / "motors"))
    return tmp_path


def _weco_rocket(tmp_path) -> Path:
    """'A simple model rocket' with its Estes C6 swapped for the WECO C6 we have a file for
    (a test of the plumbing, not of the flight: the two C6 motors differ)."""
    xml = read_bytes(DATA / "A simple model rocket.ork").replace(
        b"<manufacturer>Estes</manufacturer>", b"<manufacturer>WECO</manufacturer>")
    xml = re.sub(rb"<digest>[0-9a-f]*</digest>", b"", xml)     # as if re-picked by hand
    path = tmp_path / "weco.ork"
    path.write_bytes(xml)                      # plain-XML container
    return path


def test_info_json_contract(env):
    res = CliRunner().invoke(main, ["ork", "info", str(DATA / "Two stage high power rocket.ork"),
                                    "--json"])
    assert res.exit_code == 0, res.output
    info = json.loads(res.output)
    assert info["length_m"] == pytest.approx(2.0511, abs=1e-3)
    assert info["dry_mass_kg"] == pytest.approx(1.956, rel=0.01)   # OR: 2.574 - 0.618 kg
    assert "launch_mass_kg" in info and "launch_cg_m" in info
    designations = [[m["designation"] for m in c["motors"]] for c in info["configurations"]]
    assert designations == [["H148R", "H148R"], ["I59WN", "I357T"]]


def test_info_launch_mass_with_motor_file(env):
    path = _weco_rocket(env)
    res = CliRunner().invoke(main, ["ork", "info", str(path), "--json", "--config", "[C6-5]"])
    assert res.exit_code == 0, res.output
    info = json.loads(res.output)
    # dry build-up + WECO C6 (0.022 kg total in its .eng header)
    assert info["launch_mass_kg"] == pytest.approx(info["dry_mass_kg"] + 0.022, rel=1e-6)
    assert info["dry_cg_m"] < info["launch_cg_m"] < info["length_m"]


def test_info_human_and_errors(env, tmp_path):
    res = CliRunner().invoke(main, ["ork", "info", str(DATA / "simplerocket_v1.2_gzip.ork")])
    assert res.exit_code == 0, res.output
    assert "Nose cone" in res.output and "[A8-3]" in res.output
    bad = tmp_path / "bad.ork"
    bad.write_bytes(b"PK\x03\x04 truncated")
    res = CliRunner().invoke(main, ["ork", "info", str(bad)])
    assert res.exit_code == 2
    assert "damaged zip" in res.output


@pytest.mark.slow
def test_simulate_ork(env):
    path = _weco_rocket(env)
    res = CliRunner().invoke(main, ["simulate", str(path), "--config", "[C6-5]", "--json"])
    assert res.exit_code == 0, res.output
    out = json.loads(res.stdout)      # warnings (early ejection) go to stderr
    # OpenRocket stored 316.6 m for the Estes C6-5; a different C6, so only a sanity band
    assert 200.0 < out["apogee_agl_m"] < 400.0


def test_info_reports_digest_verification(env):
    res = CliRunner().invoke(main, ["ork", "info", str(DATA / "Airstart timing.ork"), "--json",
                                    "--config", "99b8d6a6"])
    assert res.exit_code == 0, res.output
    motors = {m["designation"]: m for m in json.loads(res.output)["selected_motors"]}
    assert motors["K550W"]["digest_verified"] is True
    assert motors["I211W"]["file"].endswith("AeroTech_I211W.eng")      # the air-start motor (tests/data/ork/motors)


def test_ork_flies_its_panel_table(env):
    """.ork -> 'aero build' (geometry only) -> 'simulate --table': the panel table
    replaces the empirical estimate; the two independent drag models put the
    apogee within 3 % of each other (measured: 267.3 vs 267.1 m; before the base
    radius fix the empirical flight had no base drag: 292.5 m); a missing table is a
    clear error."""
    rocket = _weco_rocket(env)
    stem = env / "simple"
    res = CliRunner().invoke(main, ["aero", "build", str(rocket), "--mach", "0.05,0.2,0.35",
                                    "--alpha-deg", "0,4,8,16", "--refine", "0.5", "--workers", "1",
                                    "--out", str(stem), "--json"])
    assert res.exit_code == 0, res.output
    out = CliRunner().invoke(main, ["simulate", str(rocket), "--json"]).output   # [C6-5]: an early-charge warning first
    base = json.loads(out[out.index("{"):])
    res = CliRunner().invoke(main, ["simulate", str(rocket), "--table", f"{stem}.csv", "--json"])
    assert res.exit_code == 0, res.output
    panel = json.loads(res.output[res.output.index("{"):])
    print(f"\napogee: empirical {base['apogee_agl_m']:.1f} m, panel table {panel['apogee_agl_m']:.1f} m")
    assert panel["apogee_agl_m"] != base["apogee_agl_m"]
    assert panel["apogee_agl_m"] == pytest.approx(base["apogee_agl_m"], rel=0.03)
    res = CliRunner().invoke(main, ["simulate", str(rocket), "--table", str(env / "nope.csv")])
    assert res.exit_code == 2 and "aerodynamic table not found" in res.output


def test_info_shows_every_stage(env):
    """Both stages of the two-stage design, each with its dry mass, motor, ignition and
    separation settings; the stages' dry masses add up to the rocket's."""
    res = CliRunner().invoke(main, ["ork", "info", str(DATA / "Two stage high power rocket.ork"), "--json",
                                    "--config", "fadeeef3"])
    assert res.exit_code == 0, res.output
    info = json.loads(res.output)
    stages = info["stage_list"]
    assert [s["name"] for s in stages] == ["Sustainer", "Booster"]
    assert sum(s["dry_mass_kg"] for s in stages) == pytest.approx(info["dry_mass_kg"], rel=1e-12)
    assert stages[0]["motors"][0]["designation"] == "I59WN" and stages[0]["motors"][0]["ignition"] == "burnout"
    assert stages[1]["motors"][0]["designation"] == "I357T" and stages[1]["separation"] == "upperignition"
    human = CliRunner().invoke(main, ["ork", "info", str(DATA / "Two stage high power rocket.ork")]).output
    assert "stages (2):" in human and "separates on burnout + 0 s" in human


def test_simulate_two_stage_json(env):
    res = CliRunner().invoke(main, ["simulate", str(DATA / "Two stage high power rocket.ork"), "--rail-exit",
                                    "travel", "--descent", "--json"])
    assert res.exit_code == 0, res.output
    out = json.loads(res.output)
    # OpenRocket stored 675.0 m for this configuration (tolerance of the issue: 10 %)
    assert out["apogee_agl_m"] == pytest.approx(675.0, rel=0.10)
    assert out["separation_time_s"] == pytest.approx(1.535, abs=1e-3)
    assert out["booster_landing_time_s"] > out["booster_apogee_time_s"] > out["separation_time_s"]
    assert out["landing_time_s"] > out["apogee_time_s"]


def test_config_names_a_stored_simulation(monkeypatch, tmp_path):
    """``--config "Pence FT2"`` flies that stored simulation's launch conditions (the FT2 design
    keeps six simulations of one configuration at three sites): its site elevation, rail angle
    and wind, read from the file, differ from the first simulation's ("Midland"); a name
    that is neither a configuration nor a simulation is refused, listing both."""
    from ironbark_opt.openrocket import load_ork, read_ork
    tel = Path(__file__).parents[1] / "data" / "telemetry"
    monkeypatch.setenv("IRONBARK_OFFLINE", "1")
    monkeypatch.setenv("IRONBARK_CACHE_DIR", str(tmp_path / "cache"))
    monkeypatch.setenv("IRONBARK_MOTOR_PATH", str(Path(__file__).parents[1] / "data" / "thrustcurve" / "openrocket-15.03"))
    ork = tel / "nustars-2026-ft2-telemega.ork"
    doc = read_ork(ork)
    pence, midland = doc.simulation("Pence FT2").launch, doc.simulation("Midland").launch
    assert pence.site_elevation != midland.site_elevation
    rf = load_ork(ork, config="pence ft2")                    # case-insensitive, as configurations
    assert rf.launch == pence
    assert load_ork(ork).launch == midland                    # default: the configuration's first simulation
    assert rf.motor.designation == load_ork(ork).motor.designation
    res = CliRunner().invoke(main, ["simulate", str(ork), "--config", "Pence", "--json"])
    assert res.exit_code == 2
    assert "'Pence FT2'" in res.output and "M1315W" in res.output and "Traceback" not in res.output
