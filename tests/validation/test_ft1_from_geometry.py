"""NUSTARS FT1 (issue 13): the apogee from the .ork geometry alone (panel table built by
``ironbark aero build``), flown with the .ork's "Michiana - FT1" simulation conditions and
the AeroTech L1940X, against the TeleMega's logged apogee, next to the prediction
OpenRocket stored in the same file.  Goal: ours closer than OpenRocket's.

Source: tests/data/telemetry (copied from ../shared/fixtures/telemetry/altos; README there:
max height 2198.6 m AGL at t = 20.41 s).  Slow (a whole table build, about 40 s idle).
"""
import json
from pathlib import Path

import pytest
from click.testing import CliRunner

TEL = Path(__file__).parents[1] / "data" / "telemetry"
ORK = TEL / "nustars-2026-ft1-telemega.ork"
LOGGED_APOGEE_M = 2198.6


@pytest.mark.slow
def test_ft1_panel_table_beats_openrocket(tmp_path, monkeypatch):
    from ironbark_opt.cli import main
    from ironbark_opt.openrocket import read_ork
    monkeypatch.setenv("IRONBARK_CACHE_DIR", str(tmp_path / "cache"))
    monkeypatch.setenv("IRONBARK_OFFLINE", "1")
    stem = tmp_path / "ft1"
    res = CliRunner().invoke(main, ["aero", "build", str(ORK), "--out", str(stem), "--no-progress", "--json"])
    assert res.exit_code == 0, res.output
    res = CliRunner().invoke(main, ["simulate", str(ORK), "--table", f"{stem}.csv", "--json"])
    assert res.exit_code == 0, res.output
    ours = json.loads(res.output[res.output.index("{"):])["apogee_agl_m"]
    doc = read_ork(ORK)
    sim = doc.simulation_for(doc.config())
    stored = sim.summary["apogee_m"]
    e_ours, e_or = ours / LOGGED_APOGEE_M - 1, stored / LOGGED_APOGEE_M - 1
    print(f"\nFT1 ({sim.name}): logged {LOGGED_APOGEE_M:.1f} m; ours (panel table from the .ork) "
          f"{ours:.1f} m ({100 * e_ours:+.2f} %); OpenRocket stored {stored:.1f} m ({100 * e_or:+.2f} %)")
    assert abs(e_ours) < abs(e_or)
