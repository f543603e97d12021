"""Base drag: Niskanen eq. 3.94 away from M = 1, smooth blend, power-on area, drift."""
import casadi as ca
import numpy as np
import pytest

from ironbark_opt.aero.base_drag import BaseDrag, cd_base
from ironbark_opt.errors import InputError


def _piecewise(m):
    return np.where(m < 1, 0.12 + 0.13 * m ** 2, 0.25 / np.maximum(m, 1e-9))


def test_matches_eq_3_94_away_from_mach_one():
    m = np.concatenate([np.linspace(0, 0.9, 50), np.linspace(1.1, 5, 50)])
    np.testing.assert_allclose(cd_base(m), _piecewise(m), rtol=1e-14)
    assert cd_base(0.0) == pytest.approx(0.12)
    assert cd_base(2.0) == pytest.approx(0.125)


def test_blend_is_continuous_and_close():
    m = np.linspace(0.5, 1.5, 20001)
    cd = cd_base(m)
    dev = np.max(np.abs(cd / _piecewise(m) - 1))
    print(f"max deviation of the smoothed base drag from eq. 3.94: {dev:.2%}")
    assert dev < 0.02
    assert np.max(np.abs(np.diff(cd))) < 1e-4
    assert cd_base(1.0) == pytest.approx(0.25, abs=1e-12)


def test_power_on_removes_jet_area():
    b = BaseDrag(base_area=0.01, reference_area=0.0127, jet_area=0.004)
    assert b.CA_power_off(0.5) == pytest.approx(cd_base(0.5) * 0.01 / 0.0127)
    assert b.CA_power_on(0.5) == pytest.approx(cd_base(0.5) * 0.006 / 0.0127)
    full = BaseDrag(0.004, 0.0127, jet_area=0.005)  # exhaust covers the whole base
    assert full.CA_power_on(2.0) == 0.0
    assert "BaseDrag" in repr(b)


@pytest.mark.parametrize("args, field", [((-1.0, 1.0), "base_area"), ((1.0, 0.0), "reference_area"),
                                         ((1.0, 1.0, float("nan")), "jet_area")])
def test_validation(args, field):
    with pytest.raises(InputError) as err:
        BaseDrag(*args)
    assert err.value.field == field


def test_drift_float_sx_mx():
    b = BaseDrag(0.01, 0.0127, 0.003)
    mach = np.linspace(0, 4, 81)
    for sym in (ca.SX, ca.MX):
        m = sym.sym("m")
        f = ca.Function("f", [m], [ca.vertcat(b.CA_power_off(m), b.CA_power_on(m))])
        got = np.array(f.map(mach.size)(mach))
        np.testing.assert_allclose(got[0], b.CA_power_off(mach), rtol=1e-13)
        np.testing.assert_allclose(got[1], b.CA_power_on(mach), rtol=1e-13)
