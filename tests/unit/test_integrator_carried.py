"""The carried form of the RK4 steps (``integrator.carried_trajectory``) against the
plain steps of ``integrator.rk4_step`` it regroups.

Independent method: ``rk4_step`` mapped over the same grid (``phase_trajectory``
without ``rhs``), one step after the other, each with its own closing half step
of roll damping.  The carried form does the same operations on the same operands,
only the step boundaries' air data are evaluated once, so the states must be
equal to the bit (not merely close), with a roll rate large enough that the
damping matters (Kestrel: c_roll ~ -170 1/s at burnout).
"""
from pathlib import Path

import casadi as ca
import numpy as np
import pytest

from ironbark_opt.dynamics.integrator import carried_steps, grid_fractions, phase_trajectory
from ironbark_opt.dynamics.model import FlightModel
from ironbark_opt.vehicle import load_setup

ROOT = Path(__file__).resolve().parents[2]


def _model(tmp_path, monkeypatch, example):
    monkeypatch.setenv("IRONBARK_CACHE_DIR", str(tmp_path))
    setup = load_setup(ROOT / "examples" / example)
    model = FlightModel(setup)
    p = setup.nominal_parameters()
    return model, p, model.run(p)


@pytest.mark.parametrize("example", ["calisto/calisto.toml", "kestrel/kestrel.toml"])
@pytest.mark.parametrize("phase", ["boost", "coast"])
@pytest.mark.parametrize("n, grading", [(1, 1.0), (7, 1.0), (60, 0.4)])
def test_carried_steps_equal_the_plain_steps_to_the_bit(tmp_path, monkeypatch, example, phase, n, grading):
    model, p, run = _model(tmp_path, monkeypatch, example)
    plain = phase_trajectory(model.step[phase], n, "plain", grading)
    carried = phase_trajectory(model.step[phase], n, "carried", grading, rhs=model.rhs[phase])
    x0 = np.array(run["x_rail"] if phase == "boost" else run["x_burnout"], dtype=float)
    t0 = run["t_rail"] if phase == "boost" else run["t_burnout"]
    t_end = run["t_burnout"] if phase == "boost" else run["t_apogee"]
    n_model = model.n_boost if phase == "boost" else model.n_coast
    t1 = t0 + (t_end - t0) * n / n_model                # the model's step length (a stable one)
    for roll_rate in (0.0, 25.0, -4.0):
        x0[10] = roll_rate
        a, b = np.array(plain(x0, t0, t1, p)), np.array(carried(x0, t0, t1, p))
        assert a.shape == b.shape == (13, n)
        assert np.array_equal(a, b), f"largest difference {np.max(np.abs(a - b)):.3e}"


def test_model_trajectories_fly_the_carried_form_and_agree_with_the_plain_steps(tmp_path, monkeypatch):
    """The model's own boost and coast trajectories (the ones the ascent, ``run`` and
    ``run_batch`` fly) equal the plain steps on the model's grid to the bit."""
    model, p, run = _model(tmp_path, monkeypatch, "calisto/calisto.toml")
    x_b, t_b = np.array(run["x_burnout"], dtype=float), run["t_burnout"]
    x_b[10] = 10.0
    plain = phase_trajectory(model.step["coast"], model.n_coast, "plain", model.coast_grading)
    a = np.array(plain(x_b, t_b, t_b + 20.0, p))
    b = np.array(model.trajectory["coast"](x_b, t_b, t_b + 20.0, p))
    assert np.array_equal(a, b)
    fr = grid_fractions(model.n_coast, model.coast_grading)
    assert np.all(np.diff(fr) > 0)


def test_carried_body_evaluates_the_air_data_four_times_a_step():
    """The point of the form: one ISA evaluation (one log, one exp) per step boundary
    fewer than the plain step (5 -> 4; plus the two exact damping factors)."""
    setup = load_setup(ROOT / "examples" / "calisto" / "calisto.toml")
    from ironbark_opt.dynamics import rhs as rhs_mod
    from ironbark_opt.dynamics.integrator import rk4_step
    rhs = rhs_mod.build(setup, "coast")

    def ops(f, op):
        return sum(f.instruction_id(k) == op for k in range(f.n_instructions()))
    step = rk4_step(rhs, "s")
    body, close = carried_steps(rhs, "c")
    assert ops(step, ca.OP_LOG) == 5 and ops(body, ca.OP_LOG) == 4 and ops(close, ca.OP_LOG) == 1
    # the two exact damping factors are expm1 (the roll equation's phi1 function)
    assert ops(step, ca.OP_EXP) == 5 and ops(body, ca.OP_EXP) == 4
    assert ops(step, ca.OP_EXPM1) == 2 and ops(body, ca.OP_EXPM1) == 2
