"""`ironbark aero build` / `ironbark aero plot` on the example rocket (coarse mesh)."""
import json
from pathlib import Path

import pytest
from click.testing import CliRunner

from ironbark_opt.cli import main

TOML = Path(__file__).parents[2] / "examples" / "calisto" / "calisto.toml"


@pytest.mark.skipif(not TOML.exists(), reason="example rocket not present")
def test_aero_build_and_plot(tmp_path):
    runner = CliRunner()
    stem = tmp_path / "cal"
    r = runner.invoke(main, ["aero", "build", str(TOML), "--mach", "0.3,0.6", "--alpha-deg",
                             "0,4", "--refine", "0.5", "--workers", "1", "--out", str(stem),
                             "--json"])
    assert r.exit_code == 0, r.output
    out = json.loads(r.output)
    assert Path(out["table_csv"]).exists() and out["panels"] > 100
    meta = json.loads(Path(out["table_json"]).read_text())
    assert set(meta["includes"]) == {"pressure", "friction", "base", "crossflow"}
    r = runner.invoke(main, ["aero", "plot", out["table_csv"], "--out", str(tmp_path / "p.png")])
    assert r.exit_code == 0, r.output
    assert (tmp_path / "p.png").stat().st_size > 10000


def test_aero_build_errors(tmp_path):
    runner = CliRunner()
    r = runner.invoke(main, ["aero", "build", str(tmp_path / "missing.toml")])
    assert r.exit_code == 2 and "error:" in r.output
    if TOML.exists():
        r = runner.invoke(main, ["aero", "build", str(TOML), "--mach", "0.5,0.3"])
        assert r.exit_code == 2 and "--mach" in r.output
