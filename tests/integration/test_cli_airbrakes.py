"""``ironbark ballast ROCKET --solve airbrake_level`` and ``simulate`` of a rocket with air brakes."""
import json
from pathlib import Path

import pytest
from click.testing import CliRunner

from ironbark_opt.cli import main

ROOT = Path(__file__).resolve().parents[2]
ROCKET = str(ROOT / "examples/calisto_airbrakes/calisto_airbrakes.toml")


@pytest.fixture(scope="module")
def runner():
    return CliRunner()


def test_solve_level_json_hits_target(runner, tmp_path):
    png = tmp_path / "flight.png"
    res = runner.invoke(main, ["ballast", ROCKET, "--target", "10000ft", "--solve", "airbrake_level", "--json",
                               "--plot", str(png)])
    assert res.exit_code == 0, res.output
    data = json.loads(res.stdout)
    print(f"level {data['airbrake_level']:.4f}: re-simulated {data['resimulated_apogee_agl_m']:.3f} m "
          f"for {data['target_agl_m']:.3f} m")
    assert data["feasible"] and data["solved"] == "airbrake_level"
    assert abs(data["resimulated_apogee_agl_m"] - 3048.0) < 1.0
    assert 0 < data["airbrake_level"] < 1 and png.stat().st_size > 0


def test_simulate_reports_the_brakes(runner):
    res = runner.invoke(main, ["simulate", ROCKET, "--json"])
    assert res.exit_code == 0, res.output
    data = json.loads(res.stdout)
    assert data["airbrake_max_deployment"] == pytest.approx(1.0)
    assert data["airbrake_open_time_s"] == pytest.approx(5.4, abs=0.1)


def test_errors_are_one_line(runner):
    calisto = str(ROOT / "examples/calisto/calisto.toml")
    res = runner.invoke(main, ["ballast", calisto, "--target", "3000m", "--solve", "airbrake_level"])
    assert res.exit_code == 2
    assert "no air brakes" in res.output and "Traceback" not in res.output
    res = runner.invoke(main, ["ballast", ROCKET, "--target", "3000m", "--solve", "airbrake_level",
                               "--max-ballast", "1"])
    assert res.exit_code == 2 and "takes no ballast" in res.output
