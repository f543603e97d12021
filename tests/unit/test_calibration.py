"""Calibration against a synthetic log of known drag and thrust scales, and on NUSTARS FT1.

Synthetic: the FT1 rocket (.ork) flown with drag_scale 1.08 and thrust_scale
0.96 by the model itself, sampled at 20 Hz, with white noise of 1.5 m on
altitude and 2 m/s^2 on acceleration; the fit must cover the true values
with its reported 2-sigma intervals for every seed.  The log's time zero is
its own liftoff detection (as for a real log), so the fitted time shift and
the static-port coefficient (true values 0) are fitted with the scales.
"""
from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from conftest import DATA
from ironbark_opt.errors import InputError
from ironbark_opt.flight import flight_model, simulate
from ironbark_opt.telemetry import build_log, read_log
from ironbark_opt.telemetry.calibrate import calibrate
from ironbark_opt.telemetry.calibration_file import apply_calibration, read_calibration, write_calibration
from ironbark_opt.telemetry.sampled import SampledModel
from ironbark_opt.vehicle import load_setup

TEL = DATA / "telemetry"
TRUE = {"drag_scale": 1.08, "thrust_scale": 0.96}


@pytest.fixture(scope="module")
def setup():
    return load_setup(TEL / "nustars-2026-ft1-telemega.ork")


def test_jacobian_matches_finite_differences(setup):
    model = flight_model(setup)
    sm = SampledModel(model, ["drag_scale", "thrust_scale"], 15.0, setup.nominal_parameters())
    q = np.array([1.0, 1.0])
    t = np.array([0.5, 1.5, 3.0, 9.0, 14.0])
    out = sm.at(q, t)
    for j in range(2):
        dq = np.zeros(2)
        dq[j] = 1e-6
        hi = sm.at(q + dq, t, derivatives=False)
        lo = sm.at(q - dq, t, derivatives=False)
        for c in out:
            fd = (hi[c][0] - lo[c][0]) / 2e-6
            err = np.max(np.abs(fd - out[c][1][:, j]) / (1 + np.abs(fd)))
            print(f"{c} d/d{sm.names[j]}: max relative AD-FD difference {err:.2e}")
            assert err < 1e-4


def test_synthetic_log_recovers_known_scales(setup):
    truth = dataclasses.replace(setup, nominal={**setup.nominal, **TRUE})
    sm = SampledModel(flight_model(setup), list(TRUE), 40.0, truth.nominal_parameters())
    flight = simulate(truth)
    t = np.arange(0.0, flight.apogee_time + 2.0, 0.05)
    t = t[t <= sm.t_end]
    clean = sm.at(np.array(list(TRUE.values())), t, ("altitude", "acceleration"), derivatives=False)
    for seed in range(5):
        rng = np.random.default_rng(seed)
        h = clean["altitude"][0] + rng.normal(0, 1.5, t.size)
        a = clean["acceleration"][0] + rng.normal(0, 2.0, t.size)
        log = build_log(f"synthetic-{seed}", "synthetic", "model", t, h, a=a,
                        resolution={"altitude": 0.01, "acceleration": 0.01})
        cal = calibrate(setup, log)           # defaults: also fits the time shift and the static-port term
        for name, value in TRUE.items():
            got, se = cal.values[name], cal.standard_errors[name]
            print(f"seed {seed}: {name} {got:.5f} ± {se:.5f} (true {value}), error {(got - value) / se:+.2f} sigma")
            assert abs(got - value) <= 2 * se
        assert 0.8 < cal.stats["chi2_reduced"] < 1.25      # white noise, right model: chi2/dof ~ 1


def test_ft1_calibrated_on_60_percent_predicts_apogee(setup, tmp_path):
    """NUSTARS FT1: fit up to 60 % of the time to apogee; calibrated apogee >= 3x closer."""
    log = read_log(TEL / "nustars-2026-ft1-telemega.csv.gz")
    cal = calibrate(setup, log, until_fraction=0.6)
    before = simulate(setup).apogee_agl - log.apogee_agl
    path = write_calibration(cal, tmp_path / "ft1.toml")
    after = simulate(apply_calibration(setup, path)).apogee_agl - log.apogee_agl
    print(cal.summary())
    print(f"FT1 apogee error: uncalibrated {before:+.2f} m, calibrated {after:+.2f} m "
          f"({abs(before) / abs(after):.1f}x closer)")
    assert abs(after) * 3 <= abs(before)
    assert read_calibration(path) == pytest.approx(cal.parameter_values())


def test_calibration_file_errors(tmp_path):
    bad = tmp_path / "c.toml"
    bad.write_text("[parameters]\ndrag_scal = 1.0\n")
    with pytest.raises(InputError) as err:
        read_calibration(bad)
    assert err.value.field == "parameters.drag_scal"
    bad.write_text("[parameters]\ndrag_scale = 'x'\n")
    with pytest.raises(InputError, match="finite number"):
        read_calibration(bad)
