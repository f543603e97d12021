"""``flight compare`` and ``calibrate`` on the two flights whose motors are not in the
fixtures -- NUSTARS FT2 (AeroTech M1315W, TeleMega log) and Imperial College APEX I
(Cesaroni I216, Pnut .pf2) -- with the motor coming from the loopback ThrustCurve.org
server (CONSTRUCTED responses from OpenRocket's copies of the thrust curves, see
tests/data/thrustcurve/README.md), nothing on the motor search path.

Asserted: the commands succeed and fetch the motor from the server; every number is
finite and printed (logged apogee, ours uncalibrated and calibrated); the fit on its
window (the first 60 % of the time to apogee) is at least as good as the uncalibrated
model on that window, by the residual the calibration itself states (rms of the
altitude) against the one computed independently from ``flight compare`` without it.
How close the calibrated apogee comes is printed, not asserted (issue 17 asks for 3x
on FT1 only)."""
from __future__ import annotations

import json
import math

import numpy as np
import pytest
from click.testing import CliRunner

from conftest import DATA
from ironbark_opt.cli import main

TEL = DATA / "telemetry"
TC = DATA / "thrustcurve"
API = "/api/v1"
FLIGHTS = {  # name: (.ork, log, motor, fit options)
    "FT2": ("nustars-2026-ft2-telemega.ork", "nustars-2026-ft2-telemega.csv.gz", "M1315W", []),
    # APEX logged altitude only: drag and thrust scales (and the static-port coefficient)
    # cannot be told apart from it (correlation 0.9996, the command warns), so fit drag only.
    "APEX": ("icl-apex1-pnut.ork", "icl-apex1-pnut.pf2", "I216", ["--param", "drag_scale", "--no-baro-port"]),
}


def _window_rms(ork, log, start, end, calibration=None):
    """rms [m] of simulated minus logged altitude over [start, end] of log time (flight compare)."""
    from ironbark_opt.telemetry import read_log
    from ironbark_opt.telemetry.compare import compare_flight
    from ironbark_opt.vehicle import load_setup
    setup = load_setup(ork)
    if calibration is not None:
        from ironbark_opt.telemetry.calibration_file import apply_calibration
        setup = apply_calibration(setup, calibration)
    df = compare_flight(setup, read_log(log)).to_dataframe()
    win = df[(df["time_s"] >= start) & (df["time_s"] <= end)]
    return float(np.sqrt(np.nanmean((win["sim_altitude"] - win["altitude"]) ** 2)))


@pytest.mark.parametrize("name", FLIGHTS)
def test_compare_and_calibrate_with_motor_from_thrustcurve(name, tc_server, tmp_path, monkeypatch):
    ork_name, log_name, motor, fit_options = FLIGHTS[name]
    ork, log = str(TEL / ork_name), str(TEL / log_name)
    monkeypatch.setenv("IRONBARK_MOTOR_PATH", str(tmp_path / "no-motors"))
    tc_server.route(f"{API}/search.json", TC / f"search-GET-designation-{motor}-constructed.json")
    tc_server.route(f"{API}/download.json", TC / f"download-POST-motorId-{motor}-constructed.json")
    runner = CliRunner()

    res = runner.invoke(main, ["flight", "compare", ork, log, "--json"])
    assert res.exit_code == 0, res.output
    assert f"{API}/search.json" in tc_server.paths() and f"{API}/download.json" in tc_server.paths()
    # the downloaded file is the very motor the team designed with (OpenRocket's digest in the .ork)
    from ironbark_opt.openrocket import read_ork
    from ironbark_opt.openrocket.motors import find_motor_file
    entry = next(e for _, e in read_ork(ork).config(None).motors)
    assert find_motor_file(entry.designation, entry.manufacturer, ork, entry.digest).verified is True
    before = json.loads(res.stdout)
    cal_file = tmp_path / "cal.toml"
    res = runner.invoke(main, ["calibrate", ork, log, "--until-fraction", "0.6", "-o", str(cal_file),
                               "--json", *fit_options])
    assert res.exit_code == 0, res.output
    cal = json.loads(res.stdout)
    res = runner.invoke(main, ["flight", "compare", ork, log, "--calibration", str(cal_file), "--json"])
    assert res.exit_code == 0, res.output
    after = json.loads(res.stdout)

    logged = before["logged_apogee_agl_m"]
    numbers = [logged, before["simulated_apogee_agl_m"], after["simulated_apogee_agl_m"],
               cal["calibrated_apogee_agl_m"], cal["rms_altitude_m"], cal["chi2_reduced"]]
    numbers += [p["value"] for p in cal["parameters"].values()]
    numbers += [p["standard_error"] for p in cal["parameters"].values()]
    fitted = ", ".join(f"{k} {p['value']:.4f} [{p['low_2sigma']:.4f}, {p['high_2sigma']:.4f}]"
                       for k, p in cal["parameters"].items())
    start, end = cal["window_start_s"], cal["window_end_s"]
    uncal_rms = _window_rms(ork, log, start, end)
    print(f"\n{name} ({motor} from ThrustCurve.org, constructed): logged apogee {logged:.1f} m; "
          f"ours uncalibrated {before['simulated_apogee_agl_m']:.1f} m ({before['apogee_error_m']:+.1f} m), "
          f"calibrated {after['simulated_apogee_agl_m']:.1f} m ({after['apogee_error_m']:+.1f} m)\n"
          f"  fit {start:.2f}..{end:.2f} s: {fitted}; reduced chi-square {cal['chi2_reduced']:.1f}; "
          f"rms altitude on the window {cal['rms_altitude_m']:.2f} m fitted vs {uncal_rms:.2f} m uncalibrated "
          f"(noise {cal['noise_altitude_m']:.2f} m)")
    assert all(math.isfinite(x) for x in numbers + [uncal_rms])
    assert logged == pytest.approx({"FT2": 2669.0, "APEX": 2845.3}[name], abs=0.5)   # the README's apogees
    # calibrate --calibration and calibrate's own re-flight agree (same parameters; the
    # static-port coefficient is not part of the model, so flight compare cannot see it)
    if "--no-baro-port" in fit_options:
        assert after["simulated_apogee_agl_m"] == pytest.approx(cal["calibrated_apogee_agl_m"], abs=0.5)
    assert cal["rms_altitude_m"] <= uncal_rms
