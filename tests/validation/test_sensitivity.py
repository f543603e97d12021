"""Exact (AD) sensitivities against finite differences and re-solving.

Sources of truth:
- central finite differences of the same CasADi apogee Function (the
  issue's criterion: relative error <= 1e-4);
- central finite differences of the numeric ``FlightModel.run`` path
  (``simulate``'s apogee, which the differentiated Function reproduces to
  the bit: relative error <= 1e-4), and the ballast NLP's formulation
  (coast grid ending at apogee) against its own differences;
- the optimal-ballast sensitivity against re-solving the ballast after a
  small perturbation, central difference (relative error <= 1e-4), both
  for the one-variable root ``ballast`` solves and for the NLP.

The full sweeps over every parameter are marked slow; the default run checks
a representative subset (mass, aerodynamics, launch geometry).
"""
import dataclasses
from pathlib import Path

import numpy as np
import pytest

from ironbark_opt import params
from ironbark_opt.analysis.sensitivity import (OUTPUTS, Sensitivities, apogee_function, jacobian_function,
                                              natural_step, sensitivities)
from ironbark_opt.atmosphere.isa import ISA
from ironbark_opt.errors import InputError
from ironbark_opt.flight import flight_model
from ironbark_opt.optimise.ballast import solve_ballast
from ironbark_opt.vehicle import load_setup

EXAMPLE = Path(__file__).resolve().parents[2] / "examples/calisto/calisto.toml"
# Wind and some ballast at the point, so wind/heading/ballast-position derivatives are not trivially 0.
POINT = {"wind_east": 2.0, "wind_north": -1.0, "ballast_mass": 0.5}
TARGET = 3000.0  # [m AGL] reachable with about 1.6 kg of ballast
FAST = ("ballast_mass", "drag_scale", "inclination")
REST = tuple(n for n in params.NAMES if n not in FAST)


@pytest.fixture(scope="module")
def setup():
    """Calisto with a profile wind (3 m/s toward east, 2 m/s toward south),
    so that wind_scale and heading derivatives are not trivially 0."""
    base = load_setup(EXAMPLE)
    wind = ISA.from_site(base.site_elevation, wind_east=3.0, wind_north=-2.0)
    return dataclasses.replace(base, atmosphere=wind)


@pytest.fixture(scope="module")
def point(setup):
    model = flight_model(setup)
    p0 = setup.nominal_parameters(**POINT)
    y, J = (np.array(v) for v in jacobian_function(model, p0)(p0))
    return model, p0, y.ravel(), J, apogee_function(model, p0)


@pytest.fixture(scope="module")
def at_target(setup):
    return sensitivities(setup, target=TARGET)


def _fd_check(point, name):
    model, p0, y, J, fn = point
    i = params.index(name)
    h = 1e-3 * natural_step(name, p0[i])[0]
    up, down = p0.copy(), p0.copy()
    up[i] += h
    down[i] -= h
    fd = (np.array([float(v) for v in fn(up)]) - np.array([float(v) for v in fn(down)])) / (2 * h)
    ad = J[:, i]
    for k, (key, _, _) in enumerate(OUTPUTS):
        # relative 1e-4, with a floor where the derivative itself is ~0
        # (1e-9 of the output per unit parameter)
        err = abs(fd[k] - ad[k])
        print(f"{name:20s} d{key}: AD {ad[k]:+.6e}, FD {fd[k]:+.6e}, rel. error "
              f"{err / max(abs(ad[k]), 1e-300):.2e} (tolerance 1e-4)")
        assert err <= 1e-4 * abs(ad[k]) + 1e-9 * abs(y[k])


@pytest.mark.parametrize("name", FAST)
def test_ad_matches_central_differences(point, name):
    _fd_check(point, name)


@pytest.mark.slow
@pytest.mark.parametrize("name", REST)
def test_ad_matches_central_differences_all(point, name):
    _fd_check(point, name)


@pytest.mark.parametrize("name", ["drag_scale", "wind_east", "inclination", "ballast_mass"])
def test_ad_matches_differences_of_the_simulate_path(point, name):
    """The derivatives are simulate's: its apogee (to round-off) and its central
    differences (relative 1e-4, h = 0.1 % of the natural step as above).  The
    NLP's formulation (grid ending at apogee) gave 442.14 vs simulate's
    441.27 m/rad for inclination at the 3000 m ballast, -0.2 %.

    The flight is only piecewise smooth in p: RK4 stages cross the thrust
    curve's linear-interpolation knots as the rail exit moves, so the
    derivative jumps (ballast_mass here: by 0.17 m/kg, 9e-4 relative, at
    0.5025 kg); a difference that straddles such a jump (h = 0.01 kg) is off
    by 3.8e-4, so h stays below the spacing of the jumps."""
    model, p0, y, J, _ = point
    run = model.run(p0)
    assert y[0] == pytest.approx(run["x_apogee"][2], abs=1e-6)
    assert y[1] == pytest.approx(run["t_apogee"], abs=1e-9)
    i = params.index(name)
    step = natural_step(name, p0[i])[0]
    h = 1e-3 * step
    up, down = p0.copy(), p0.copy()
    up[i] += h
    down[i] -= h
    fd = (model.run(up)["x_apogee"][2] - model.run(down)["x_apogee"][2]) / (2 * h)
    err = abs(fd - J[0, i])
    print(f"{name}: d apogee AD {J[0, i]:+.6e}, FD of run() {fd:+.6e}, rel. error {err / abs(J[0, i]):.2e} "
          f"(tolerance 1e-4)")
    assert err <= 1e-4 * abs(J[0, i])


def test_nlp_formulation_matches_its_own_differences(point):
    """``flown=False`` differentiates the ballast NLP's apogee (coast grid ending at
    apogee), a different discretisation: centimetres from simulate's apogee, and
    its derivatives against its own central differences (relative 1e-4)."""
    model, p0, y, _, _ = point
    fn = apogee_function(model, p0, flown=False)
    y_nlp, J_nlp = (np.array(v) for v in jacobian_function(model, p0, flown=False)(p0))
    assert float(fn(p0)[0]) == y_nlp[0, 0]
    assert abs(y_nlp[0, 0] - y[0]) < 0.2          # centimetres apart (Calisto: 4 cm)
    i = params.index("inclination")
    h = 1e-2 * natural_step("inclination", p0[i])[0]
    up, down = p0.copy(), p0.copy()
    up[i] += h
    down[i] -= h
    fd = (float(fn(up)[0]) - float(fn(down)[0])) / (2 * h)
    assert abs(fd - J_nlp[0, i]) <= 1e-4 * abs(J_nlp[0, i])


def test_result_object(setup, at_target):
    sens = at_target
    J = sens.jacobian
    assert sens.names == params.NAMES and J.shape == (len(OUTPUTS), params.SIZE)
    i = params.index("drag_scale")
    assert sens.derivative("apogee_agl_m", "drag_scale") == J[0, i]
    # natural steps: +10 % drag on a factor of 1 is 0.1; +1 deg launch angle
    assert sens.change("apogee_agl_m", "drag_scale") == pytest.approx(0.1 * J[0, i], rel=1e-15)
    assert sens.step("inclination") == (pytest.approx(np.radians(1.0)), "+1 deg launch angle")
    text = sens.summary()
    assert "+10 % drag" in text and "+1 % thrust" in text and "+1 kg ballast" in text
    assert "\n" not in repr(sens)
    d = sens.to_dict()
    assert d["apogee_agl_m"] == sens.values["apogee_agl_m"] and d["target_agl_m"] == TARGET
    entry = d["parameters"]["drag_scale"]
    assert entry["change_per_step"]["apogee_agl_m"] == sens.change("apogee_agl_m", "drag_scale")
    assert entry["change_per_step"]["ballast_kg"] == pytest.approx(0.1 * sens.ballast["drag_scale"], rel=1e-15)
    assert d["parameters"]["ballast_mass"]["derivative"]["ballast_kg"] is None
    df = sens.to_dataframe()
    assert list(df["parameter"]) == list(params.NAMES)
    assert df.loc[i, "d_apogee_agl_m"] == J[0, i] and np.isnan(df.loc[0, "ballast_kg"])
    with pytest.raises(AttributeError):
        sens.name = "other"
    with pytest.raises(ValueError):
        sens.jacobian[0, 0] = 1.0
    with pytest.raises(InputError, match="unknown output"):
        sens.derivative("apogee", "drag_scale")
    with pytest.raises(InputError, match="unknown parameter"):
        sensitivities(setup, names=["drag"])
    with pytest.raises(InputError, match="need\\(s\\) a target"):
        sensitivities(setup, mass_max=2.0)


def test_subset_of_names(at_target):
    i = params.index("thrust_scale")
    sub = Sensitivities(name="x", names=("thrust_scale",), point=at_target.point, values=at_target.values,
                        jacobian=np.array(at_target.jacobian[:, [i]]))
    assert sub.change("apogee_agl_m", "thrust_scale") == at_target.change("apogee_agl_m", "thrust_scale")
    assert list(sub.to_dataframe()["parameter"]) == ["thrust_scale"]
    with pytest.raises(InputError, match="not differentiated"):
        sub.derivative("apogee_agl_m", "ballast_mass")


def _resolve_check(setup, at_target, name, rel=1e-4, **options):
    """Central difference of the re-solved ballast with h = 1 % of the natural step.
    Its errors: truncation ~1e-6 relative (the apogee's differences above), and
    the re-solve's own tolerance, |apogee - target| <= ROOT_TOL_M = 1e-6 m, i.e.
    1e-6 / |dz/dm| ~ 5e-9 kg per solve, at most 3e-5 relative here (the smallest
    ballast change per h, 1.5e-4 kg for 0.01 m/s of wind): within 1e-4."""
    step = natural_step(name, at_target.point[name])[0]
    h = 0.01 * step
    base = at_target.point[name]
    m_up = solve_ballast(setup, TARGET, parameters={name: base + h}, **options).ballast
    m_down = solve_ballast(setup, TARGET, parameters={name: base - h}, **options).ballast
    fd = (m_up - m_down) / (2 * h)
    ad = at_target.ballast[name]
    print(f"dm*/d{name}: implicit {ad:+.6e}, re-solved {fd:+.6e} kg per unit, rel. error "
          f"{abs(fd - ad) / abs(ad):.2e} (tolerance {rel:g})")
    assert abs(fd - ad) <= rel * abs(ad)


def test_optimal_ballast_sensitivity_matches_resolving(setup, at_target):
    # the point is `ballast`'s own answer, and the apogee there simulate's
    sol = solve_ballast(setup, TARGET)
    assert at_target.point["ballast_mass"] == sol.ballast
    assert at_target.values["apogee_agl_m"] == sol.values["resimulated_apogee_agl_m"]
    assert at_target.values["apogee_agl_m"] == pytest.approx(TARGET, abs=1e-6)
    assert at_target.ballast["ballast_mass"] is None
    # extra dry mass is replaced kilogram for kilogram (same CG: exact identity)
    assert at_target.ballast["dry_mass_offset"] == pytest.approx(-1.0, rel=1e-9)
    _resolve_check(setup, at_target, "drag_scale")
    assert "ballast*" in at_target.summary()


@pytest.mark.slow
@pytest.mark.parametrize("name", ["thrust_scale", "inclination", "wind_east", "temperature_offset"])
def test_optimal_ballast_sensitivity_matches_resolving_all(setup, at_target, name):
    _resolve_check(setup, at_target, name)


@pytest.mark.slow
def test_nlp_ballast_sensitivity_matches_resolving_the_nlp(setup):
    """With the NLP (method="ipopt", as with flight constraints) the point and the
    derivatives are the NLP's formulation, consistent with re-solving the NLP."""
    sens = sensitivities(setup, target=TARGET, names=["inclination", "wind_east"], method="ipopt")
    for name in ("inclination", "wind_east"):
        _resolve_check(setup, sens, name, method="ipopt")


def test_unreachable_target_has_no_ballast_sensitivities(setup):
    sens = sensitivities(setup, target=5000.0, names=["drag_scale"])
    assert sens.ballast is None
    assert "no ballast sensitivities" in sens.note
