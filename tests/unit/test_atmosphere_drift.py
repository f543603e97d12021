"""Drift: floats, NumPy arrays, CasADi SX / MX / DM give the same numbers;
derivatives are finite and match finite differences."""
from __future__ import annotations

import warnings

import casadi as ca
import numpy as np
import pytest

from ironbark_opt.atmosphere import ISA, Profile

METHODS = ("temperature", "pressure", "density", "speed_of_sound", "dynamic_viscosity")
# Altitudes across all layers and around the profile's ends (0..86 km).
H = np.array([-300.0, 0.0, 1400.0, 5000.0, 11000.0, 11019.07, 15000.0, 20063.12, 25000.0,
              32161.9, 40000.0, 47350.1, 50000.0, 51412.5, 60000.0, 71802.0, 80000.0,
              85999.0])


def _models():
    isa = ISA.from_site(1400.0, 305.0, 86200.0, wind_east=4.0, wind_north=-2.5)
    z = np.array([1400.0, 1500.0, 2200.0, 3000.0, 5000.0, 8000.0, 12000.0, 18000.0])
    prof = Profile(z, 305.0 - 0.0068 * (z - 1400.0) + 3.0 * np.exp(-((z - 2500.0) / 300.0) ** 2),
                   isa.pressure(z), 2.0 + 1e-3 * z, np.sin(z / 2000.0), source="synthetic")
    return {"isa": isa, "profile": prof}


@pytest.fixture(autouse=True)
def _quiet():
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        yield


@pytest.mark.parametrize("name", ["isa", "profile"])
def test_float_array_sx_mx_dm_agree(name):
    atm = _models()[name]
    dT = -3.5
    worst = 0.0
    for sym in (ca.SX, ca.MX):
        h, t = sym.sym("h"), sym.sym("dT")
        outs = [getattr(atm, meth)(h) if meth == "pressure" else getattr(atm, meth)(h, t)
                for meth in METHODS]
        outs += list(atm.wind_l(h))
        f = ca.Function("f", [h, t], outs)
        for hi in H:
            ref = [getattr(atm, meth)(float(hi)) if meth == "pressure"
                   else getattr(atm, meth)(float(hi), dT) for meth in METHODS]
            ref += list(atm.wind_l(float(hi)))
            got = [float(v) for v in f(hi, dT)]
            for r, g in zip(ref, got):
                assert isinstance(r, float)
                worst = max(worst, abs(g - r) / max(abs(r), 1e-12))
    # Whole arrays at once (and a 2-D array keeps its shape).
    for meth in METHODS:
        arr = getattr(atm, meth)(H)
        assert arr.shape == H.shape
        one = np.array([getattr(atm, meth)(float(hi)) for hi in H])
        np.testing.assert_allclose(arr, one, rtol=1e-15)
        assert getattr(atm, meth)(H.reshape(3, 6)).shape == (3, 6)
        dm = getattr(atm, meth)(ca.DM(H))
        np.testing.assert_allclose(np.array(dm).ravel(), arr, rtol=1e-13)
    # SX of matrix shape.
    hm = ca.SX.sym("h", 3, 6)
    fm = ca.Function("fm", [hm], [atm.pressure(hm)])
    np.testing.assert_allclose(np.array(fm(H.reshape(3, 6))), atm.pressure(H.reshape(3, 6)),
                               rtol=1e-13)
    print(f"{name}: max relative SX/MX vs NumPy difference {worst:.1e}")
    assert worst < 1e-13


@pytest.mark.parametrize("name", ["isa", "profile"])
def test_derivatives_finite_and_match_finite_differences(name):
    atm = _models()[name]
    for sym in (ca.SX, ca.MX):
        h, t = sym.sym("h"), sym.sym("dT")
        st = atm.state(h, t)
        keys = sorted(st)
        out = ca.vertcat(*[st[k] for k in keys])
        jac = ca.Function("j", [h, t], [ca.jacobian(out, ca.vertcat(h, t)), out])
        worst = 0.0
        for hi in H:
            # stay off level / layer breakpoints, where one-sided slopes differ
            hi = hi + 7.3
            J, val = (np.array(v) for v in jac(hi, 2.0))
            assert np.all(np.isfinite(J)) and np.all(np.isfinite(val))
            step = 1e-3
            fd = (np.array(jac(hi + step, 2.0)[1]) - np.array(jac(hi - step, 2.0)[1])) / (2 * step)
            scale = np.maximum(np.abs(val) / 1000.0, 1e-12)   # per-metre scale of each output
            worst = max(worst, float(np.max(np.abs(J[:, :1] - fd) / scale)))
        print(f"{name} {sym.__name__}: max |AD - FD| of d/dh relative to value/km: {worst:.1e}")
        assert worst < 1e-5


def test_state_matches_single_methods_symbolically():
    for atm in _models().values():
        h = ca.SX.sym("h")
        st = atm.state(h, 1.5)
        f = ca.Function("f", [h], [st["density"], st["speed_of_sound"], st["wind_north"]])
        for hi in (1500.0, 9000.0, 30000.0):
            d, a, wn = (float(v) for v in f(hi))
            assert d == pytest.approx(atm.density(hi, 1.5), rel=1e-14)
            assert a == pytest.approx(atm.speed_of_sound(hi, 1.5), rel=1e-14)
            assert wn == pytest.approx(atm.wind_l(hi)[1], rel=1e-14, abs=1e-15)
