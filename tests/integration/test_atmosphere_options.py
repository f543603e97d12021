"""``--atmosphere`` / ``[launch] atmosphere`` on every flying command: the file
flown is named in the summary and --json; bad files and times exit 2."""
from __future__ import annotations

import json
import shutil
from pathlib import Path

import pandas as pd
import pytest
from click.testing import CliRunner

from ironbark_opt.cli import main

D = Path(__file__).resolve().parents[1] / "data"
BELLA = D / "flights" / "bella_lui"
NC = D / "weather" / "reanalysis" / "bella_lui_weather_data_ERA5.nc"


def _isa_copy(tmp_path):
    """bella_lui without its [launch] atmosphere and gravity lines (flies ISA)."""
    for f in BELLA.iterdir():
        shutil.copy(f, tmp_path / f.name)
    toml = tmp_path / "rocket.toml"
    lines = [ln for ln in toml.read_text().splitlines() if not ln.startswith(("atmosphere", "gravity"))]
    toml.write_text("\n".join(lines) + "\n")
    return toml


def _run(*args):
    return CliRunner().invoke(main, [str(a) for a in args])


def test_simulate_atmosphere_option_equals_toml_key(tmp_path):
    toml = _isa_copy(tmp_path)
    isa = json.loads(_run("simulate", toml, "--json").output)
    assert isa["atmosphere"]["model"] == "ISA"
    res = _run("simulate", toml, "--atmosphere", NC, "--atmosphere-time", "2020-02-22T13:00Z", "--json")
    assert res.exit_code == 0, res.output
    opt = json.loads(res.output)
    assert opt["atmosphere"]["source"] == "reanalysis bella_lui_weather_data_ERA5.nc"
    # The TOML names the same file at the same hour (plus RocketPy's constant g).
    key = json.loads(_run("simulate", BELLA / "rocket.toml", "--json").output)
    print(f"apogee ISA {isa['apogee_agl_m']:.2f} m, --atmosphere {opt['apogee_agl_m']:.2f} m, "
          f"[launch] atmosphere + gravity {key['apogee_agl_m']:.2f} m")
    assert opt["apogee_agl_m"] != isa["apogee_agl_m"] and key["atmosphere"]["source"] == opt["atmosphere"]["source"]
    human = _run("simulate", toml, "--atmosphere", NC, "--atmosphere-time", "2020-02-22T13:00Z").output
    assert "atmosphere         Profile: reanalysis bella_lui_weather_data_ERA5.nc, valid 2020-02-22" in human


def test_weather_get_json_and_csv_fly_like_the_file(tmp_path):
    toml = _isa_copy(tmp_path)
    got = _run("weather", "get", "--model", "reanalysis", "--file", NC, "--lat", "47.213476", "--lon",
               "9.003336", "--elevation-m", "407", "--time", "2020-02-22T13:00Z", "--json",
               "--csv", tmp_path / "w.csv")
    assert got.exit_code == 0, got.output
    (tmp_path / "w.json").write_text(got.output)
    saved = _run("weather", "get", "--model", "reanalysis", "--file", NC, "--lat", "47.213476", "--lon",
                 "9.003336", "--elevation-m", "407", "--time", "2020-02-22T13:00Z", "--out", tmp_path / "o.json")
    assert saved.exit_code == 0, saved.output
    ref = json.loads(_run("simulate", toml, "--atmosphere", NC, "--atmosphere-time", "2020-02-22T13:00Z",
                          "--json").output)["apogee_agl_m"]
    for saved in ("w.json", "w.csv", "o.json"):
        res = _run("simulate", toml, "--atmosphere", tmp_path / saved, "--json")
        assert res.exit_code == 0, res.output
        apo = json.loads(res.output)["apogee_agl_m"]
        print(f"{saved}: apogee {apo:.4f} m vs netCDF {ref:.4f} m")
        assert apo == pytest.approx(ref, abs=1e-6)


@pytest.mark.parametrize("command", [["sensitivity", "--param", "ballast_mass"],
                                     ["ballast", "--target", "400m"]])
def test_other_commands_take_the_option(tmp_path, command):
    toml = _isa_copy(tmp_path)
    res = _run(command[0], toml, *command[1:], "--atmosphere", NC, "--atmosphere-time", "2020-02-22T13:00Z",
               "--json")
    assert res.exit_code == 0, res.output
    assert json.loads(res.output)["atmosphere"]["source"] == "reanalysis bella_lui_weather_data_ERA5.nc"


def test_montecarlo_takes_the_option(tmp_path):
    toml = _isa_copy(tmp_path)
    spec = tmp_path / "spec.toml"
    spec.write_text('seed = 1\n[parameters.ballast_mass]\ndistribution = "uniform"\nlow = 0.0\nhigh = 0.1\n')
    res = _run("montecarlo", toml, "--spec", spec, "--samples", 4, "--chunk", 4, "--no-progress",
               "--atmosphere", NC, "--atmosphere-time", "2020-02-22T13:00Z", "--json")
    assert res.exit_code == 0, res.output
    assert json.loads(res.output)["atmosphere"]["valid_time"].startswith("2020-02-22T13:00")


def test_bad_time_and_file_exit_2_naming_them(tmp_path):
    toml = _isa_copy(tmp_path)
    res = _run("simulate", toml, "--atmosphere", NC, "--atmosphere-time", "2021-01-01T00:00Z")
    print(res.output)
    assert res.exit_code == 2 and "bella_lui_weather_data_ERA5.nc" in res.output
    assert "2020-02-22 13:00Z" in res.output           # the times available are listed
    res = _run("simulate", toml, "--atmosphere", NC)    # five records, no time given
    assert res.exit_code == 2 and "several times" in res.output
    res = _run("simulate", toml, "--atmosphere", tmp_path / "missing.nc")
    assert res.exit_code == 2 and "missing.nc" in res.output
    text = toml.read_text().replace("[launch]\n", '[launch]\natmosphere = {file = "x.nc"}\n')
    (tmp_path / "bad.toml").write_text(text)
    res = _run("simulate", tmp_path / "bad.toml")
    assert res.exit_code == 2 and "x.nc" in res.output
    text = toml.read_text().replace("[launch]\n", f'[launch]\natmosphere = {{file = "{NC}", time = "noon"}}\n')
    (tmp_path / "bad2.toml").write_text(text)
    res = _run("simulate", tmp_path / "bad2.toml")
    print(res.output)
    assert res.exit_code == 2 and "launch.atmosphere.time" in res.output and "bad2.toml:" in res.output
