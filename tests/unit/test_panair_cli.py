"""`ironbark aero build` / `ironbark aero plot` on the example rocket (coarse mesh)."""
import json
from pathlib import Path

import numpy as np
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
    # friction is flown at the flight's Reynolds number (tabulated for reference only)
    assert set(meta["includes"]) == {"pressure", "base", "crossflow"}
    assert "CA_friction" in meta["coefficients"]
    assert meta["axes"]["alpha_deg"]["max"] == 90.0             # high-angle model to 90 deg
    assert not Path(str(stem) + ".solved").exists()              # per-Mach saves cleaned up
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


def test_aero_build_from_an_openrocket_file(tmp_path):
    """An .ork builds its table from the geometry alone (no motor file needed)."""
    ork = Path(__file__).parents[1] / "data" / "ork" / "A simple model rocket.ork"
    r = CliRunner().invoke(main, ["aero", "build", str(ork), "--mach", "0.3", "--alpha-deg",
                                  "0,4", "--refine", "0.5", "--workers", "1", "--out",
                                  str(tmp_path / "simple"), "--json"])
    assert r.exit_code == 0, r.output
    out = json.loads(r.output)
    meta = json.loads(Path(out["table_json"]).read_text())
    assert meta["rocket_file"].endswith(".ork") and out["panels"] > 100
    from ironbark_opt.aero.table import AeroTable
    t = AeroTable.load(out["table_csv"])
    # a stable finned rocket: CN > 0 and a nose-down moment about the nose tip at 4 deg
    assert t.values("CN")[0, 1] > 0 and t.values("Cm")[0, 1] < 0 and t.values("CA")[0, 0] > 0


def test_aero_build_rejects_a_binary_rocket_file(tmp_path):
    bad = tmp_path / "rocket.toml"
    bad.write_bytes(b"PK\x03\x04\x92\xff binary")
    r = CliRunner().invoke(main, ["aero", "build", str(bad), "--json"])
    assert r.exit_code == 2 and "not a UTF-8 text file" in r.output and "Traceback" not in r.output


def test_default_mach_grid_reaches_1_3_times_the_peak():
    """Issue 13: the default grid reaches 1.3 x the rocket's own peak Mach, at least Mach 2."""
    from panair.rocket_table import DEFAULT_MACH, default_mach_grid
    np.testing.assert_array_equal(default_mach_grid(None), DEFAULT_MACH)
    np.testing.assert_array_equal(default_mach_grid(1.5), DEFAULT_MACH)      # 1.95 <= 2
    for peak in (1.6, 1.9, 2.4, 3.1):
        g = default_mach_grid(peak)
        assert g[-1] >= 1.3 * peak and g[-2] < 1.3 * peak
        np.testing.assert_array_equal(g[:len(DEFAULT_MACH)], DEFAULT_MACH)
    # never past the supersonic solver's range (a diverged or hypersonic estimate)
    from panair.solver import MACH_SUPERSONIC_MAX
    assert default_mach_grid(1830.0)[-1] == MACH_SUPERSONIC_MAX


def test_peak_mach_estimate_is_the_files_own_flight(monkeypatch):
    """`aero build`'s peak Mach number is the max Mach of the file flown as it is (the
    independent path: `ironbark simulate --json`); a file that cannot fly gives None
    with a warning (the grid then ends at 2).  The .ork's motors are kept unresolvable
    (no IRONBARK_MOTOR_PATH), as on a fresh machine."""
    import warnings
    monkeypatch.delenv("IRONBARK_MOTOR_PATH", raising=False)

    from ironbark_opt.cli.aero import estimated_peak_mach
    r = CliRunner().invoke(main, ["simulate", str(TOML), "--json"])
    assert r.exit_code == 0, r.output
    flown = json.loads(r.output)["max_mach"]
    assert estimated_peak_mach(str(TOML)) == pytest.approx(flown, rel=1e-9)
    ork = Path(__file__).parents[1] / "data" / "ork" / "Two stage high power rocket.ork"
    if ork.exists():
        with warnings.catch_warnings(record=True) as w:
            warnings.simplefilter("always")
            assert estimated_peak_mach(str(ork)) is None
        assert any("peak Mach" in str(x.message) for x in w)


@pytest.mark.skipif(not TOML.exists(), reason="example rocket not present")
def test_aero_build_says_which_mach_numbers_use_local_inclination(tmp_path):
    """Calisto's Haack nose at Mach 4 (coarse mesh) is steeper than the Mach cone even with the
    sharpened tip: the build says so on stderr and in its JSON, not only in the table metadata."""
    r = CliRunner().invoke(main, ["aero", "build", str(TOML), "--mach", "0.6,4.0", "--alpha-deg", "0,4",
                                  "--refine", "0.5", "--workers", "1", "--out", str(tmp_path / "c"),
                                  "--no-resume", "--json"])
    assert r.exit_code == 0, r.output
    out = json.loads(r.stdout)
    assert out["mach_local_inclination"] == [4.0] and out["mach_sonic_leading_edge"] == []
    meta = json.loads(Path(out["table_json"]).read_text())
    assert meta["mach_local_inclination"] == [4.0]
    assert "no solution at Mach 4 " in r.stderr and "local-inclination" in r.stderr


def test_configurations_together_returns_in_order_and_raises_the_failure():
    """aero build's configurations on one MachPool (cli/aero._configurations_together):
    results in the configurations' order; a failing configuration's error is raised and
    the jobs still queued are cancelled."""
    import time

    from ironbark_opt.cli.aero import _configurations_together
    from ironbark_opt.errors import SolverError

    def one(conf, rk, pool):
        futs = [pool.submit(c, float, c) for c in rk]
        return conf, [f.result() for f in futs]

    assert _configurations_together(one, [("a", [1.0, 2.0]), ("b", [3.0])], 2) == \
        [("a", [1.0, 2.0]), ("b", [3.0])]
    queued = []

    def failing(conf, rk, pool):
        if conf == "bad":
            time.sleep(0.2)
            raise SolverError("Mach 1.5: no solution")
        futs = [pool.submit(1.0, time.sleep, 0.3) for _ in range(20)]
        queued.extend(futs)
        return [f.result() for f in futs]

    with pytest.raises(SolverError, match="no solution"):
        _configurations_together(failing, [("good", None), ("bad", None)], 2)
    assert sum(f.cancelled() for f in queued) >= 10
