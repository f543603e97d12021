"""FrictionComponent / FrictionDrag: build-up, table error, symbolic drift, validation."""
import warnings

import casadi as ca
import numpy as np
import pytest

from ironbark_opt.aero.friction import FrictionComponent, FrictionDrag
from ironbark_opt.aero.friction_flatplate import cf_flat_plate, form_factor_body, form_factor_fin
from ironbark_opt.errors import InputError, OutOfRangeWarning

S_REF = np.pi * 0.0635 ** 2


@pytest.fixture(scope="module")
def calisto_like():
    comps = [FrictionComponent.body("body", 2.6, 0.127, roughness=20e-6),
             FrictionComponent.fins("fins", 4 * 2 * 0.0099, 0.09, 0.004, roughness=20e-6)]
    return FrictionDrag(comps, S_REF)


def test_components_and_form_factors():
    body = FrictionComponent.body("body", 2.0, 0.1)
    assert body.wetted_area == pytest.approx(np.pi * 0.1 * 2.0)
    assert body.form_factor == pytest.approx(form_factor_body(20.0))
    fins = FrictionComponent.fins("fins", 0.05, 0.1, 0.005)
    assert fins.length == 0.1 and fins.form_factor == pytest.approx(form_factor_fin(0.05))


@pytest.mark.parametrize("kwargs, field", [
    (dict(wetted_area=0.0, length=1.0), "wetted_area"),
    (dict(wetted_area=1.0, length=-1.0), "length"),
    (dict(wetted_area=1.0, length=1.0, form_factor=0.9), "form_factor"),
    (dict(wetted_area=1.0, length=1.0, roughness=-1e-6), "roughness"),
    (dict(wetted_area=1.0, length=1.0, roughness=2.0), "roughness"),
    (dict(wetted_area="1", length=1.0), "wetted_area"),
])
def test_component_validation(kwargs, field):
    with pytest.raises(InputError) as err:
        FrictionComponent("c", **kwargs)
    assert err.value.field == field


def test_drag_validation():
    c = FrictionComponent("c", 1.0, 1.0)
    with pytest.raises(InputError, match="FrictionComponent"):
        FrictionDrag([], 1.0)
    with pytest.raises(InputError):
        FrictionDrag([c], 0.0)
    with pytest.raises(InputError):
        FrictionDrag([c], 1.0, reynolds_per_m_range=(1e6, 1e3))


def test_exact_is_the_component_sum(calisto_like):
    m, rpm = 0.7, 1.2e7
    expected = sum(cf_flat_plate(m, rpm * c.length, c.length, c.roughness) * c.form_factor
                   * c.wetted_area / S_REF for c in calisto_like.components)
    assert calisto_like.CA_exact(m, rpm) == pytest.approx(expected, rel=1e-14)


def test_table_error_against_exact(calisto_like):
    """The tabulated CA (used in the RK4 step) vs the formulas: documented < 0.75 %."""
    rng = np.random.default_rng(7)
    mach = rng.uniform(0, 5, 20000)
    rpm = 10 ** rng.uniform(3, 9, 20000)
    err = np.abs(calisto_like.CA(mach, rpm) / calisto_like.CA_exact(mach, rpm) - 1)
    flight = rpm > 1e6
    print(f"friction table vs exact: max {err.max():.2%}, 99th pct {np.percentile(err, 99):.3%}, "
          f"max for Re/m > 1e6 {err[flight].max():.2%}")
    assert err.max() < 0.0075
    assert np.percentile(err, 99) < 0.0025


def test_symbolic_and_numeric_agree(calisto_like):
    rng = np.random.default_rng(8)
    mach = rng.uniform(0, 5, 100)
    rpm = 10 ** rng.uniform(2, 9, 100)
    numeric = calisto_like.CA(mach, rpm)
    for sym in (ca.SX, ca.MX):
        m, r = sym.sym("m"), sym.sym("r")
        for name, expr in (("table", calisto_like.CA(m, r)), ("exact", calisto_like.CA_exact(m, r))):
            f = ca.Function(name, [m, r], [expr]).map(mach.size)
            ref = numeric if name == "table" else calisto_like.CA_exact(mach, rpm)
            err = np.max(np.abs(np.array(f(mach, rpm)).ravel() / ref - 1))
            print(f"{name} {sym.__name__}: max relative drift {err:.1e}")
            assert err < 1e-10


def test_low_reynolds_is_held_silently_high_mach_warns(calisto_like):
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        assert calisto_like.CA(0.0, 0.0) == pytest.approx(calisto_like.CA(0.0, 1e3))
    with pytest.warns(OutOfRangeWarning, match="mach"):
        calisto_like.CA(6.0, 1e7)


def test_temperature_effect_is_small(calisto_like):
    """The table is built at 288 K; the edge temperature changes CA little (documented)."""
    m = np.linspace(0.1, 3.0, 30)
    smooth = FrictionDrag([FrictionComponent.body("b", 2.6, 0.127)], S_REF)
    for fd in (calisto_like, smooth):
        d = np.abs(fd.CA_exact(m, 2e7, 220.0) / fd.CA_exact(m, 2e7, 288.15) - 1)
        print(f"220 K vs 288 K: max {d.max():.2%}")
        assert d.max() < 0.0075


def test_magnitude_against_openrocket_style_estimate(calisto_like):
    """Independent order-of-magnitude check: OpenRocket eq. 3.78/3.85 style turbulent estimate
    Cf = 1/(1.5 ln Re - 5.6)^2 with its (1 - 0.1 M^2) correction, on the same areas and
    form factors, at a smooth-surface condition; agree within 10 %."""
    smooth = FrictionDrag([FrictionComponent.body("b", 2.6, 0.127),
                           FrictionComponent.fins("f", 0.0792, 0.09, 0.004)], S_REF)
    m, rpm = 0.5, 1.1e7
    est = 0.0
    for c in smooth.components:
        re = rpm * c.length
        est += (1 - 0.1 * m ** 2) / (1.5 * np.log(re) - 5.6) ** 2 * c.form_factor * c.wetted_area / S_REF
    ours = smooth.CA_exact(m, rpm)
    print(f"CA_friction {ours:.4f} vs OpenRocket-style {est:.4f}: {ours / est - 1:+.1%}")
    assert ours == pytest.approx(est, rel=0.10)
