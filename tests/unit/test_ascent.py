"""The one-Function ascent (dynamics/ascent.py) against the phase-by-phase path it replaced.

Independent method: ``FlightModel._ascent_phased`` (the rail-exit secant from
Python, each phase one call, the coast flown to its whole horizon).  Both fly
the same RK4 steps; the rail-exit root differs within its 1e-10 m tolerance,
so every sample and event must agree to 1e-9 relative (found: ~1e-14).
"""
from pathlib import Path

import numpy as np
import pytest

from ironbark_opt import params
from ironbark_opt.dynamics.model import FlightModel
from ironbark_opt.vehicle import load_setup

ROOT = Path(__file__).resolve().parents[2]


def _both(model, p):
    fused = model._ascent_fused(p)
    assert fused is not None, "the ascent Function should apply to this flight"
    return model._finish(p, fused, False), model._finish(p, model._ascent_phased(p), False)


def _worst(a, b) -> float:
    assert a["phase"].tolist() == b["phase"].tolist()
    # each state relative to its range; floor 1e-6 (Kestrel's roll rate is round-off, ~1e-16 rad/s)
    scale = np.maximum(np.abs(b["x"]).max(axis=1, keepdims=True), 1e-6)
    worst = float(np.max(np.abs(a["x"] - b["x"]) / scale))
    worst = max(worst, float(np.max(np.abs(a["t"] - b["t"]))) / b["t"][-1])
    for key in ("t_rail", "t_burnout", "t_apogee"):
        worst = max(worst, abs(a[key] - b[key]) / b[key])
    return worst


@pytest.mark.parametrize("example, overrides", [
    ("calisto/calisto.toml", {}),
    ("calisto/calisto.toml", {"ballast_mass": 1.5, "drag_scale": 1.1}),
    ("calisto/calisto.toml", {"thrust_scale": 0.9, "inclination": np.radians(80.0)}),
    ("kestrel/kestrel.toml", {}),
])
def test_fused_ascent_equals_the_phased_one(tmp_path, monkeypatch, example, overrides):
    monkeypatch.setenv("IRONBARK_CACHE_DIR", str(tmp_path))
    setup = load_setup(ROOT / "examples" / example)
    model = FlightModel(setup)
    p = setup.nominal_parameters(**overrides)
    fused, phased = _both(model, p)
    worst = _worst(fused, phased)
    passes = model._ascent_runner()(p)["rail_passes"]
    print(f"{example} {overrides}: apogee {fused['x_apogee'][2]:.6f} m (phased {phased['x_apogee'][2]:.6f} m), "
          f"rail passes {passes:.0f}, worst relative difference {worst:.1e} (tolerance 1e-9)")
    assert worst < 1e-9
    assert passes <= 6                      # the phased secant flies the rail 5-6 times


def test_run_falls_back_where_the_ascent_function_does_not_apply(tmp_path, monkeypatch):
    """A 12 m rail is left after 0.5 s: the bracketing pass finds no exit, ``run``
    flies phase by phase (doubling the bracket) and gives that path's answer."""
    monkeypatch.setenv("IRONBARK_CACHE_DIR", str(tmp_path))
    setup = load_setup(ROOT / "examples/calisto/calisto.toml")
    model = FlightModel(setup)
    p = setup.nominal_parameters(rail_length=12.0)
    assert model._ascent_fused(p) is None
    run = model.run(p)
    ref = model._finish(p, model._ascent_phased(p), False)
    assert run["t_rail"] > 0.5
    assert run["x_apogee"][2] == ref["x_apogee"][2]


def test_rail_shorter_than_the_guide_distance_is_an_input_error(tmp_path, monkeypatch):
    from ironbark_opt.errors import InputError
    monkeypatch.setenv("IRONBARK_CACHE_DIR", str(tmp_path))
    setup = load_setup(ROOT / "examples/calisto/calisto.toml")
    model = FlightModel(setup)
    p = setup.nominal_parameters()
    p[params.index("rail_length")] = 0.5 * setup.rail_exit_offset
    with pytest.raises(InputError, match="rail length"):
        model.run(p)


def test_run_batch_after_a_grid_change_flies_the_new_grid(tmp_path, monkeypatch):
    """``set_discretisation`` (a cluster worker imposing the client's grid) after a
    ``run_batch``: the next batch flies the new grid, equal to ``run`` on it (the
    mapped ascent of the old grid had stayed cached under the same sample count)."""
    monkeypatch.setenv("IRONBARK_CACHE_DIR", str(tmp_path))
    setup = load_setup(ROOT / "examples/calisto/calisto.toml")
    model = FlightModel(setup, jit=False)
    P = np.column_stack([setup.nominal_parameters(), setup.nominal_parameters(ballast_mass=1.0)])
    before = model.run_batch(P)
    nb, nc, g = model.discretisation()
    model.set_discretisation(nb + 7, nc + 11, g)
    after = model.run_batch(P)
    one = model.run(P[:, 1])
    a_new, a_old = after["x_apogee"][2, 1], before["x_apogee"][2, 1]
    assert a_new == one["x_apogee"][2]
    assert a_new != a_old                    # a different grid gives a (slightly) different apogee


def test_rail_exit_matches_dop853_and_its_own_residual(tmp_path, monkeypatch):
    """The fused ascent's rail exit (coarse bracket, Hermite guess, speed-corrected
    secant) for dispersed Calisto samples against two independent answers:

    - SciPy's DOP853 (rtol 1e-11) on the same rail right-hand side with an exact
      exit event: the time and speed differ only by the RK4 error of ``n_rail``
      steps through the thrust curve's kinks (found: 2.7e-5 s and 3.8e-4 m/s, i.e.
      1.5e-5 relative; tolerance 1e-4 s and 2e-3 m/s);
    - the defining residual (rail phase on ``n_rail`` steps over ``[0, t_r]``,
      :meth:`FlightModel.rail_residual`) at the fused root: below 1e-10 m, and the
      root equals the symbolic Newton ``rootfinder``'s within 1e-10 m / speed.
    """
    import casadi as ca
    from scipy.integrate import solve_ivp
    from ironbark_opt.analysis.distributions import load_spec
    from ironbark_opt.dynamics.constants import RAIL_TOL_M
    from ironbark_opt.dynamics.frames import rail_direction_l

    monkeypatch.setenv("IRONBARK_CACHE_DIR", str(tmp_path))
    setup = load_setup(ROOT / "examples/calisto/calisto.toml")
    spec = load_spec(ROOT / "examples/calisto/dispersions.toml")
    model = FlightModel(setup)
    P = spec.sample(6, setup.nominal_parameters(), np.random.default_rng(3))
    t_sym, p_sym = ca.MX.sym("t"), ca.MX.sym("p", model.n_p)
    residual = ca.Function("g", [t_sym, p_sym], [model.rail_residual(t_sym, p_sym)])
    worst_t = worst_v = 0.0
    for p in P.T:
        r = model._ascent_runner()(p)
        t_r, x_r = r["t_rail"], r["X_rail"][:, -1]
        e = np.array(rail_direction_l(p[params.index("inclination")], p[params.index("heading")])).ravel()
        d = float(model.rail_exit_distance(p))
        v_r = float(np.linalg.norm(x_r[3:6]))

        def off_rail(t, x):
            return e @ x[:3] - d
        off_rail.terminal = True
        rhs = model.rhs["rail"]
        ref = solve_ivp(lambda t, x: np.array(rhs(x, t, p)[0]).ravel(), (0, 2), r["x0"], method="DOP853",
                        rtol=1e-11, atol=1e-11, events=off_rail)
        worst_t = max(worst_t, abs(t_r - ref.t[-1]))
        worst_v = max(worst_v, abs(v_r - np.linalg.norm(ref.y[3:6, -1])))
        assert abs(float(residual(t_r, p))) < RAIL_TOL_M
        assert abs(float(model.rail_exit_root(ref.t[-1], p)) - t_r) < 2 * RAIL_TOL_M / v_r
    print(f"rail exit vs DOP853: time {worst_t:.1e} s, speed {worst_v:.1e} m/s")
    assert worst_t < 1e-4
    assert worst_v < 2e-3
