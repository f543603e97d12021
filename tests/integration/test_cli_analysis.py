"""``ironbark sensitivity`` and ``ironbark montecarlo`` end to end (CliRunner)."""
import json
from pathlib import Path

import pandas as pd
import pytest
from click.testing import CliRunner

from ironbark_opt.cli import main

ROOT = Path(__file__).resolve().parents[2]
ROCKET = str(ROOT / "examples/calisto/calisto.toml")
SPEC = str(ROOT / "examples/calisto/dispersions.toml")


@pytest.fixture(scope="module")
def runner():
    return CliRunner()


@pytest.mark.slow
def test_sensitivity_json(runner):
    res = runner.invoke(main, ["sensitivity", ROCKET, "--param", "drag_scale", "--param", "inclination", "--json"])
    assert res.exit_code == 0, res.output
    data = json.loads(res.stdout)
    assert set(data["parameters"]) == {"drag_scale", "inclination"}
    drag = data["parameters"]["drag_scale"]
    assert drag["step_label"] == "+10 % drag"
    assert drag["change_per_step"]["apogee_agl_m"] == pytest.approx(0.1 * drag["derivative"]["apogee_agl_m"])
    assert drag["change_per_step"]["apogee_agl_m"] < 0 < data["parameters"]["inclination"]["derivative"]["apogee_agl_m"]
    assert 3000 < data["apogee_agl_m"] < 3600


def test_sensitivity_summary_csv_and_plot(runner, tmp_path):
    csv, png = tmp_path / "sens.csv", tmp_path / "sens.png"
    res = runner.invoke(main, ["sensitivity", ROCKET, "--param", "ballast_mass", "--param", "drag_scale",
                               "--csv", str(csv), "--plot", str(png)])
    assert res.exit_code == 0, res.output
    assert "+1 kg ballast" in res.output and "+10 % drag" in res.output and "apogee [m]" in res.output
    table = pd.read_csv(csv)
    assert list(table["parameter"]) == ["ballast_mass", "drag_scale"]
    assert table.loc[1, "apogee_agl_m"] == pytest.approx(0.1 * table.loc[1, "d_apogee_agl_m"], rel=1e-12)
    assert table.loc[0, "apogee_agl_m"] < 0 and table.loc[1, "apogee_agl_m"] < 0
    assert png.stat().st_size > 1000


def test_sensitivity_at_a_target_is_taken_at_the_ballast_commands_answer(runner):
    """`sensitivity --target` and `ballast --target` agree: the same ballast (bit for bit)
    and the apogee there is the one `ballast` re-simulates (simulate's, which the
    derivatives differentiate)."""
    sens = runner.invoke(main, ["sensitivity", ROCKET, "--target", "3000m", "--param", "inclination", "--json"])
    ballast = runner.invoke(main, ["ballast", ROCKET, "--target", "3000m", "--json"])
    assert sens.exit_code == 0 and ballast.exit_code == 0, sens.output + ballast.output
    s, b = json.loads(sens.stdout), json.loads(ballast.stdout)
    print(f"ballast {b['ballast_kg']:.6f} kg, sensitivity's point {s['ballast_kg']:.6f} kg; apogee "
          f"{s['apogee_agl_m']:.6f} m vs re-simulated {b['resimulated_apogee_agl_m']:.6f} m")
    assert s["ballast_kg"] == b["ballast_kg"]
    assert s["apogee_agl_m"] == pytest.approx(b["resimulated_apogee_agl_m"], abs=1e-6)
    # a steeper rail (angle above horizontal): a higher apogee, more ballast to stay on the target
    assert s["parameters"]["inclination"]["change_per_step"]["ballast_kg"] > 0


def test_montecarlo_json_csv_and_plots(runner, tmp_path):
    csv, hist, ell = tmp_path / "mc.csv", tmp_path / "hist.png", tmp_path / "ellipse.png"
    args = ["montecarlo", ROCKET, "--spec", SPEC, "--samples", "5", "--chunk", "3", "--target", "3300m",
            "--band", "60", "--no-progress", "--csv", str(csv), "--histogram", str(hist), "--ellipse", str(ell),
            "--json"]
    res = runner.invoke(main, args)
    assert res.exit_code == 0, res.output
    data = json.loads(res.stdout)
    assert data["samples"] == 5 and data["seed"] == 20260704
    assert data["target_agl_m"] == pytest.approx(3300.0)
    assert 0.0 <= data["probability_in_band"] <= 1.0
    table = pd.read_csv(csv)
    assert len(table) == 5
    assert data["apogee_agl_m"]["mean"] == pytest.approx(table["apogee_agl_m"].mean(), rel=1e-12)
    assert hist.stat().st_size > 1000 and ell.stat().st_size > 1000
    # same seed from the spec: the human summary reports the same mean
    res2 = runner.invoke(main, args[:-1] + ["--seed", "20260704"])
    assert f"{data['apogee_agl_m']['mean']:.2f}" in res2.output


def test_montecarlo_errors_are_one_line(runner, tmp_path):
    bad = tmp_path / "bad.toml"
    bad.write_text('seed = 1\n\n[parameters.drag_scale]\ndistribution = "normal"\nstd = -1\n')
    res = runner.invoke(main, ["montecarlo", ROCKET, "--spec", str(bad), "--samples", "2", "--no-progress"])
    assert res.exit_code == 2
    assert f"{bad}:5: field 'parameters.drag_scale.std'" in res.stderr
    res = runner.invoke(main, ["montecarlo", ROCKET, "--spec", SPEC, "--samples", "2", "--band", "10",
                               "--no-progress"])
    assert res.exit_code == 2 and "band needs a target" in res.stderr
    res = runner.invoke(main, ["sensitivity", ROCKET, "--param", "drag"])
    assert res.exit_code == 2 and "unknown parameter 'drag'" in res.stderr
