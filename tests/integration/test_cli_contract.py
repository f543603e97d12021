"""The CLI contract: every command has --json; JSON keys carry unit suffixes;
bad input is one clear line with exit status 2, never a traceback."""
import json
from pathlib import Path

import click
import pytest
from click.testing import CliRunner

from ironbark_opt.cli import main

ROOT = Path(__file__).resolve().parents[2]
EXAMPLE = str(ROOT / "examples/calisto/calisto.toml")
#: keys without a unit suffix that are dimensionless or text by nature
UNITLESS = {"max_mach", "rocket", "motor", "atmosphere", "feasible", "status", "active", "parameters", "target",
            "objective", "candidates", "failures", "iterations", "recovery_devices"}
UNIT_SUFFIXES = ("_m", "_s", "_kg", "_mps", "_mps2", "_Pa", "_cal", "_N", "_Ns", "_K", "_deg", "_rad", "_kgm2")


def _leaf_commands(group, prefix=()):
    ctx = click.Context(group)
    for name in group.list_commands(ctx):
        cmd = group.get_command(ctx, name)
        if isinstance(cmd, click.Group):
            yield from _leaf_commands(cmd, prefix + (name,))
        else:
            yield prefix + (name,), cmd


def test_every_command_has_json_option():
    missing = [" ".join(path) for path, cmd in _leaf_commands(main)
               if not any("--json" in p.opts for p in cmd.params if isinstance(p, click.Option))]
    assert not missing, f"commands without --json: {missing}"


def test_simulate_json_keys_have_units():
    res = CliRunner().invoke(main, ["simulate", EXAMPLE, "--json"])
    assert res.exit_code == 0, res.output
    data = json.loads(res.output)
    bad = [k for k in data if k not in UNITLESS and not k.endswith(UNIT_SUFFIXES)]
    assert not bad, f"keys without a unit suffix: {bad}"
    assert data["apogee_agl_m"] > 3000


def test_ballast_json_has_the_contract_keys():
    res = CliRunner().invoke(main, ["ballast", EXAMPLE, "--target", "10000ft", "--json"])
    assert res.exit_code == 0, res.output
    data = json.loads(res.output)
    for key in ("ballast_kg", "motor", "apogee_agl_m", "apogee_time_s"):
        assert key in data
    assert abs(data["apogee_agl_m"] - 3048.0) < 0.5


@pytest.mark.parametrize("args, needle", [
    (["simulate", "no_such_rocket.toml"], "file not found"),
    (["ballast", EXAMPLE, "--target", "high"], "target"),
    (["simulate", EXAMPLE, "--rail-length", "0.5"], "rail"),
])
def test_bad_input_gives_one_line_and_status_2(args, needle):
    res = CliRunner().invoke(main, args)
    assert res.exit_code == 2
    assert needle in res.output.lower()
    assert "Traceback" not in res.output


def test_bad_toml_names_file_and_line(tmp_path):
    bad = tmp_path / "bad.toml"
    bad.write_text((ROOT / "examples/calisto/calisto.toml").read_text().replace("length = 0.55829", "length = -1"))
    res = CliRunner().invoke(main, ["simulate", str(bad)])
    assert res.exit_code == 2
    assert "bad.toml:" in res.output and "length" in res.output


def test_window_and_robust_ballast_are_registered_with_json():
    commands = dict((" ".join(path), cmd) for path, cmd in _leaf_commands(main))
    assert "window" in commands
    for name, flags in (("window", {"--json", "--forecast", "--site", "--from", "--hours", "--plot", "--spec",
                                    "--max-rail-wind", "--min-margin", "--min-rail-speed"}),
                        ("ballast", {"--json", "--robust", "--spec", "--band", "--objective", "--samples",
                                     "--check-samples"})):
        opts = {o for p in commands[name].params if isinstance(p, click.Option) for o in p.opts}
        assert flags <= opts, (name, flags - opts)
