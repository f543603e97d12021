"""``ironbark motor search`` / ``ironbark motor get`` against the loopback tc_server."""
from __future__ import annotations

import json
import os
from pathlib import Path

import pytest
from click.testing import CliRunner

from ironbark_opt.cli import main

TC = Path(__file__).resolve().parents[1] / "data" / "thrustcurve"
API = "/api/v1"


def test_search_json(tc_server):
    tc_server.route(f"{API}/search.json", TC / "search-GET-manufacturer.json")
    res = CliRunner().invoke(main, ["motor", "search", "--manufacturer", "Estes", "--json"])
    assert res.exit_code == 0, res.output
    out = json.loads(res.output)
    assert out["count"] == 20
    first = out["motors"][0]
    assert first["designation"] == "1/4A3" and first["total_impulse_Ns"] == 0.59
    assert first["burn_time_s"] == 0.25 and first["diameter_mm"] == pytest.approx(13.0)


def test_search_human_and_empty(tc_server):
    tc_server.route(f"{API}/search.json", TC / "search-GET-empty.json")
    res = CliRunner().invoke(main, ["motor", "search", "--class", "Z", "--diameter-mm", "54"])
    assert res.exit_code == 0 and "no motors match" in res.output
    assert tc_server.requests[-1]["query"]["diameter"] == ["54"]


def test_get_writes_file_and_summary(tc_server, tmp_path):
    tc_server.route(f"{API}/search.json", TC / "search-GET-designation-K550W.json")
    tc_server.route(f"{API}/download.json", TC / "download-POST-motorId.json")
    res = CliRunner().invoke(main, ["motor", "get", "K550W", "-o", str(tmp_path), "--json"])
    assert res.exit_code == 0, res.output
    out = json.loads(res.output)
    assert out["format"] == "RASP" and out["data_source"] == "cert"
    assert out["total_impulse_Ns"] == pytest.approx(1594.46)
    assert Path(out["file"]).read_text().startswith("; AeroTech K550W")
    # human form
    res = CliRunner().invoke(main, ["motor", "get", "K550W", "-o", str(tmp_path)])
    assert "AeroTech K550W (K, 54 x 410 mm, reload)" in res.output
    assert "wrote" in res.output


def test_get_plot(tc_server, tmp_path):
    pytest.importorskip("ironbark_opt.motors.rasp")
    tc_server.route(f"{API}/search.json", TC / "search-GET-designation-K550W.json")
    tc_server.route(f"{API}/download.json", TC / "download-POST-motorId.json")
    res = CliRunner().invoke(main, ["motor", "get", "K550W", "-o", str(tmp_path), "--plot"])
    assert res.exit_code == 0, res.output
    assert (tmp_path / "AeroTech_K550W.png").stat().st_size > 1000


def test_errors_exit_codes(tc_server):
    tc_server.route(f"{API}/search.json", TC / "search-GET-empty.json")
    res = CliRunner().invoke(main, ["motor", "get", "Z9999"])
    assert res.exit_code == 2 and "error:" in res.output and "no motor called" in res.output
    tc_server.routes.clear()
    res = CliRunner().invoke(main, ["motor", "search", "--manufacturer", "Estes"])
    assert res.exit_code == 3 and "HTTP 404" in res.output


def test_offline_flag_restores_environment(tc_server):
    res = CliRunner().invoke(main, ["motor", "search", "--manufacturer", "X", "--offline"])
    assert res.exit_code == 3 and "offline mode" in res.output
    assert "IRONBARK_OFFLINE" not in os.environ
