"""Base drag: Niskanen eq. 3.94 and the McCoy (MC DRAG) supersonic base pressure away
from M = 1, smooth blend, vacuum limit, power-on area, validation, drift."""
import casadi as ca
import numpy as np
import pytest

from ironbark_opt.aero.base_drag import (BaseDrag, base_pressure_ratio_mccoy, cd_base,
                                         cd_base_supersonic_mccoy)
from ironbark_opt.errors import InputError


def _niskanen(m):
    return np.where(m < 1, 0.12 + 0.13 * m ** 2, 0.25 / np.maximum(m, 1e-9))


def _mccoy(m, afterbody_calibers=10.0):
    """Independent evaluation: Cp_b = (p_b/p - 1) / (gamma/2 M^2), MC DRAG ratio for M > 1
    with its boundary-layer relief factor 1 + 0.09 M^2 (1 - exp(-L/d))."""
    m = np.asarray(m, float)
    ms = np.maximum(m, 1.0)
    relief = 1.0 + 0.09 * ms ** 2 * (1.0 - np.exp(-afterbody_calibers))
    ratio = relief / (1.0 + 0.2477 * ms ** 2 + 0.0345 * ms ** 4)
    return np.where(m < 1, 0.12 + 0.13 * m ** 2, -(ratio - 1.0) / (0.7 * ms ** 2))


def test_niskanen_matches_eq_3_94_away_from_mach_one():
    m = np.concatenate([np.linspace(0, 0.9, 50), np.linspace(1.1, 5, 50)])
    np.testing.assert_allclose(cd_base(m), _niskanen(m), rtol=1e-14)
    np.testing.assert_allclose(cd_base(m, "niskanen"), _niskanen(m), rtol=1e-14)
    assert cd_base(0.0) == pytest.approx(0.12)
    assert cd_base(2.0) == pytest.approx(0.125)


def test_mccoy_matches_mc_drag_away_from_mach_one():
    m = np.concatenate([np.linspace(0, 0.9, 50), np.linspace(1.1, 5, 50)])
    np.testing.assert_allclose(cd_base(m, "mccoy"), _mccoy(m), rtol=1e-13)
    # hand values at M = 2: denominator 1 + 0.9908 + 0.552 = 2.5428; relief 1 + 0.36 (1 - e^-L)
    assert base_pressure_ratio_mccoy(2.0, 50.0) == pytest.approx(1.36 / 2.5428, rel=1e-12)
    assert cd_base(2.0, "mccoy", 50.0) == pytest.approx((1 - 1.36 / 2.5428) / 2.8, rel=1e-12)
    short = 1 + 0.36 * (1 - np.exp(-1.0))                # a 1-caliber afterbody: less relief
    assert base_pressure_ratio_mccoy(2.0, 1.0) == pytest.approx(short / 2.5428, rel=1e-12)


def test_mccoy_below_vacuum_limit_and_decreasing():
    m = np.linspace(1.1, 8.0, 300)
    cd = cd_base_supersonic_mccoy(m)
    vacuum = 2.0 / (1.4 * m ** 2)                 # p_b = 0: the largest possible base drag
    assert np.all(cd > 0) and np.all(cd < vacuum)
    assert np.all(np.diff(cd) < 0)
    frac = cd / vacuum
    print(f"\nMC DRAG base drag / vacuum limit: {frac[0]:.2f} at M 1.1 .. {frac[-1]:.2f} at M 8")


@pytest.mark.parametrize("model", ["niskanen", "mccoy"])
def test_blend_is_continuous_and_close(model):
    ref = _niskanen if model == "niskanen" else _mccoy
    m = np.linspace(0.5, 1.5, 20001)
    cd = cd_base(m, model)
    outside = np.abs(m - 1) >= 0.1
    np.testing.assert_allclose(cd[outside], ref(m[outside]), rtol=1e-13)
    assert np.max(np.abs(np.diff(cd))) < 1e-4           # no jump (step 5e-5 in Mach)
    d1 = np.diff(cd) / np.diff(m)
    assert np.max(np.abs(np.diff(d1))) < 0.01          # no kink
    inside = ~outside                                  # between the two branches' values
    assert np.all(cd[inside] >= 0.2) and np.all(cd[inside] <= 0.32)


def test_power_on_removes_jet_area():
    b = BaseDrag(base_area=0.01, reference_area=0.0127, jet_area=0.004)
    assert b.model == "mccoy"
    assert b.CA_power_off(0.5) == pytest.approx(cd_base(0.5, "mccoy") * 0.01 / 0.0127)
    assert b.CA_power_on(2.5) == pytest.approx(cd_base(2.5, "mccoy") * 0.006 / 0.0127)
    full = BaseDrag(0.004, 0.0127, jet_area=0.005)  # exhaust covers the whole base
    assert full.CA_power_on(2.0) == 0.0
    assert "BaseDrag" in repr(b) and "mccoy" in repr(b)
    nis = BaseDrag(0.01, 0.0127, model="niskanen")
    assert nis.CA_power_off(2.0) == pytest.approx(0.125 * 0.01 / 0.0127)


@pytest.mark.parametrize("args, kwargs, field", [
    ((-1.0, 1.0), {}, "base_area"), ((1.0, 0.0), {}, "reference_area"),
    ((1.0, 1.0, float("nan")), {}, "jet_area"), ((1.0, 1.0), {"model": "hoerner"}, "base_drag.model")])
def test_validation(args, kwargs, field):
    with pytest.raises(InputError) as err:
        BaseDrag(*args, **kwargs)
    assert err.value.field == field


def test_unknown_model_in_cd_base():
    with pytest.raises(InputError, match="unknown base-drag model"):
        cd_base(1.5, "vacuum")


@pytest.mark.parametrize("model", ["niskanen", "mccoy"])
def test_drift_float_sx_mx(model):
    b = BaseDrag(0.01, 0.0127, 0.003, model=model)
    mach = np.linspace(0, 4, 81)
    for sym in (ca.SX, ca.MX):
        m = sym.sym("m")
        f = ca.Function("f", [m], [ca.vertcat(b.CA_power_off(m), b.CA_power_on(m))])
        got = np.array(f.map(mach.size)(mach))
        np.testing.assert_allclose(got[0], b.CA_power_off(mach), rtol=1e-13)
        np.testing.assert_allclose(got[1], b.CA_power_on(mach), rtol=1e-13)


def test_fin_trailing_edges_take_eq_3_94_on_their_frontal_area():
    """Blunt fin trailing edges: Niskanen eq. 3.94 whatever the body's model, motor on or off."""
    b = BaseDrag(0.01, 0.0127, jet_area=0.004, fin_trailing_edge_area=0.0022)
    bare = BaseDrag(0.01, 0.0127, jet_area=0.004)
    for m in (0.3, 0.9, 1.5, 3.0):
        fin = float(_niskanen(m)) * 0.0022 / 0.0127
        assert b.CA_fin_trailing_edges(m) == pytest.approx(fin, rel=1e-12)
        assert b.CA_power_off(m) - bare.CA_power_off(m) == pytest.approx(fin, rel=1e-12)
        assert b.CA_power_on(m) - bare.CA_power_on(m) == pytest.approx(fin, rel=1e-12)
    assert bare.CA_fin_trailing_edges(2.0) == 0.0 and "fin trailing edges 0.0022" in repr(b)
    with pytest.raises(InputError):
        BaseDrag(0.01, 0.0127, fin_trailing_edge_area=-1.0)
