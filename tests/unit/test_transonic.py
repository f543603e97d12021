"""panair.transonic: critical Mach numbers and the zero-lift pressure-drag model."""
from __future__ import annotations

import numpy as np
import pytest
from scipy.optimize import brentq

from panair.mesh import FinGeometry
from panair.transonic import (LOCK_OFFSET, MACH_CR_MAX, body_critical_mach, cp_sonic,
                              fin_critical_mach, karman_tsien, nose_transonic,
                              zero_lift_pressure)


def test_sonic_pressure_coefficient_limits():
    # Cp* = 0 at Mach 1 (the local speed is the free-stream speed); at Mach 0.5 the
    # isentropic value is -2.13 (e.g. Anderson, Fundamentals of Aerodynamics, eq. 11.60)
    assert abs(cp_sonic(1.0)) < 1e-12
    assert cp_sonic(0.5) == pytest.approx(-2.13, abs=5e-3)


def test_karman_tsien_reduces_to_incompressible_and_exceeds_prandtl_glauert():
    assert karman_tsien(-0.4, 1e-6) == pytest.approx(-0.4, rel=1e-9)
    m = 0.7
    assert karman_tsien(-0.4, m) < -0.4 / np.sqrt(1 - m * m) < -0.4


def test_body_critical_mach_naca0012_example():
    # NACA 0012 at zero lift, Cp_min = -0.43 (incompressible): Prandtl-Glauert gives the
    # textbook critical Mach number 0.74 (Anderson, Fundamentals of Aerodynamics,
    # Example 11.5); Karman-Tsien, which amplifies suction more, gives a lower one.
    pg = brentq(lambda m: -0.43 / np.sqrt(1 - m * m) - cp_sonic(m), 0.3, 0.99)
    kt = body_critical_mach(-0.43)
    print(f"M_cr Prandtl-Glauert {pg:.4f}, Karman-Tsien {kt:.4f}")
    assert pg == pytest.approx(0.74, abs=0.01)
    assert pg - 0.03 < kt < pg
    assert body_critical_mach(0.1) == MACH_CR_MAX       # no suction: never critical


def test_fin_critical_mach_korn_lock():
    # unswept rectangular fin, t/c = 0.12: Korn M_dd = 0.87 - 0.12 = 0.75, M_cr = M_dd - 0.108
    fin = FinGeometry(4, 0.1, 0.1, 0.1, 0.0, 1.0, 0.012)
    assert fin_critical_mach(fin) == pytest.approx(0.75 - LOCK_OFFSET, abs=1e-9)
    assert LOCK_OFFSET == pytest.approx(0.1077, abs=1e-4)
    # sweep raises it: mid-chord sweep 45 deg, t/c 0.04 -> 0.87/cos45 - 0.04/cos^2 45 - 0.108
    swept = FinGeometry(4, 0.1, 0.1, 0.1, 0.1, 1.0, 0.004)
    expect = min(0.87 / np.cos(np.pi / 4) - 0.04 / 0.5 - LOCK_OFFSET, MACH_CR_MAX)
    assert fin_critical_mach(swept) == pytest.approx(expect, abs=1e-9)


def test_zero_lift_pressure_is_subsonic_then_monotone_rise_then_supersonic():
    sub = lambda m: 0.01 + 0.02 * np.asarray(m) ** 2
    m_sup, p_sup = np.array([1.2, 1.5, 2.0]), np.array([0.30, 0.26, 0.21])
    m = np.linspace(0.05, 2.0, 400)
    p = zero_lift_pressure(m, 0.8, sub, m_sup, p_sup)
    below = m <= 0.8
    assert np.allclose(p[below], sub(m[below]))
    rise = (m > 0.8) & (m <= 1.0)
    assert np.all(np.diff(p[rise]) >= -1e-12)                    # monotone drag rise
    assert p[np.argmin(np.abs(m - 1.0))] == pytest.approx(0.30, abs=2e-3)
    assert zero_lift_pressure([1.2, 1.5, 2.0], 0.8, sub, m_sup, p_sup) == pytest.approx(p_sup)
    # continuous slope at the critical Mach number (C1 fairing)
    h = 1e-5
    left = (sub(0.8) - sub(0.8 - h)) / h
    right = (zero_lift_pressure([0.8 + h], 0.8, sub, m_sup, p_sup)[0] - sub(0.8)) / h
    assert right == pytest.approx(left, abs=0.02)
    # Lock's fourth-power law up to M_dd = M_cr + 0.108 (on the given area ratio)
    m_dd = 0.7 + LOCK_OFFSET
    p_dd = zero_lift_pressure([m_dd], 0.7, sub, m_sup, p_sup, lock_sets=[(0.7, 2.0)])[0]
    assert p_dd == pytest.approx(sub(m_dd) + 20 * LOCK_OFFSET ** 4 * 2.0, rel=1e-9)
    with pytest.raises(ValueError):
        zero_lift_pressure([0.9], 0.8, sub, [], [])


def test_each_fin_set_rises_from_its_own_critical_mach():
    """Lock's law is a section property: with two fin sets (a thick camera pod meshed as
    fins, M_cr 0.42, and the main fins, M_cr 0.95) the rise below Mach 0.95 is the pod's
    alone, on the pod's planform, not the main fins' planform from the pod's M_cr."""
    sub = lambda m: 0.0 * np.asarray(m, float)
    m_sup, p_sup = np.array([1.2, 1.5]), np.array([0.5, 0.45])
    sets = [(0.42, 0.11), (0.95, 6.0)]
    p = zero_lift_pressure([0.6, 0.8], 0.42, sub, m_sup, p_sup, lock_sets=sets)
    # (monotone cubic between Lock points spaced LOCK_OFFSET / 4: within 1 %)
    assert p[0] == pytest.approx(20 * 0.18 ** 4 * 0.11, rel=1e-2)
    assert p[1] < 20 * 0.38 ** 4 * 0.11 * 1.05 + 1e-12          # on the Lock points' fairing
    old = zero_lift_pressure([0.6], 0.42, sub, m_sup, p_sup, lock_sets=[(0.42, 6.11)])
    assert old[0] > 20 * p[0]                                     # what one shared M_cr gave


def test_mccoy_nose_rise_zero_at_its_critical_mach_and_sonic_value():
    """McCoy's transonic head drag (MC DRAG 1981): its critical Mach number
    (1 + 0.552 tau^0.8)^-1/2 is where 0.368 tau^1.8 + 1.6 tau (M^2 - 1) / (2.4 M^2)
    vanishes (0.552 = 0.368 x 2.4 / 1.6: the two published formulas agree), the sonic
    value is 0.368 tau^1.8, held above Mach 1, on the given area ratio."""
    for tau in (0.1, 0.2, 1 / 3, 0.5):
        m_cr, rise = nose_transonic(tau, 0.8)
        assert brentq(lambda m: 0.368 * tau ** 1.8 + 1.6 * tau * (m * m - 1) / (2.4 * m * m),
                      0.5, 1.0) == pytest.approx(m_cr, abs=1e-9)
        assert rise(m_cr - 0.01) == 0.0 and rise(m_cr + 0.01) > 0.0
        assert rise(1.0) == pytest.approx(0.8 * 0.368 * tau ** 1.8, rel=1e-12)
        assert rise(1.3) == rise(1.0)
        assert np.all(np.diff(rise(np.linspace(m_cr, 1.0, 50))) > 0)
    # fineness 3: the drag rise from Mach 0.90 (NASA TR R-100 data: 0.90-0.95), 0.051 at Mach 1
    m_cr, rise = nose_transonic(1 / 3, 1.0)
    assert m_cr == pytest.approx(0.902, abs=1e-3) and rise(1.0) == pytest.approx(0.0509, abs=1e-4)


def test_ogival_nose_replaces_its_share_of_the_sonic_anchor():
    """With an ogival nose the anchor at Mach 1 is the first supersonic solution minus the
    nose's share of it plus the nose's own sonic drag; the supersonic rows are untouched
    and the rise stays monotone."""
    sub = lambda m: 0.0 * np.asarray(m, float)
    m_sup, p_sup = np.array([1.2, 1.5, 2.0]), np.array([0.30, 0.26, 0.21])
    m_cr, rise = nose_transonic(0.2, 1.0)
    share = 0.05
    m = np.linspace(0.5, 2.0, 301)
    p = zero_lift_pressure(m, m_cr, sub, m_sup, p_sup, nose=(rise, share))
    assert p[np.argmin(np.abs(m - 1.0))] == pytest.approx(0.30 - share + float(rise(1.0)), abs=1e-9)
    assert zero_lift_pressure(m_sup, m_cr, sub, m_sup, p_sup, nose=(rise, share)) == pytest.approx(p_sup)
    assert np.all(np.diff(p[(m > m_cr) & (m <= 1.2)]) >= -1e-12)
    assert np.all(p[m <= m_cr] == 0.0)
    # below Mach 1 the nose's rise is in (a rocket peaking at Mach 0.97 sees it)
    assert p[np.argmin(np.abs(m - 0.97))] >= float(rise(0.97)) - 1e-9
    without = zero_lift_pressure(m, m_cr, sub, m_sup, p_sup)
    assert without[np.argmin(np.abs(m - 1.0))] == pytest.approx(0.30, abs=1e-9)


def test_mccoy_supersonic_head_drag_vs_exact_cone():
    """McCoy's supersonic head drag with R_T / R = 1 (a cone) against the exact conical
    flow (Taylor-Maccoll, panair.solver.nose_correction.TangentCone) on the Basic
    Finner's 10 deg cone: within 10 % at Mach 1.2-4.3 (measured -9 ... +9 %)."""
    import math

    from ironbark_opt.aero.compressibility import mccoy_head_drag_supersonic
    from panair.solver.nose_correction import TangentCone
    half = math.atan(0.5 / 2.84)
    for m in (1.2, 1.5, 2.0, 3.0, 4.3):
        exact = float(TangentCone(m).cp(np.array([half]))[0])
        assert float(mccoy_head_drag_supersonic(m, 1 / 2.84, 1.0)) == pytest.approx(exact, rel=0.10)


def test_empirical_nose_drag_has_wave_drag_on_tangent_noses():
    """The empirical path's nose (ironbark_opt.aero.empirical_drag.nose_pressure_ca): a
    tangent ogive and a von Karman nose (joint angle 0) get McCoy's wave drag above his
    critical Mach number (none before session 16), continuous through the blend, and a
    cone keeps at least its joint's separated-flow drag."""
    from ironbark_opt.aero.compressibility import mccoy_head_drag_transonic
    from ironbark_opt.aero.empirical_drag import head_shape_ratio, nose_pressure_ca
    from ironbark_opt.rocket.nose import NoseCone
    a_ref = np.pi * 0.05 ** 2
    m = np.linspace(0.5, 3.0, 2001)
    for shape in ("tangent_ogive", "von_karman"):
        nose = NoseCone(shape=shape, length=0.5, radius=0.05)
        assert head_shape_ratio(nose) == 0.0
        ca = nose_pressure_ca(nose, m, a_ref)
        assert np.all(ca[m < 0.9] < 1e-6)
        assert ca[np.argmin(np.abs(m - 1.0))] == pytest.approx(float(mccoy_head_drag_transonic(1.0, 0.2)), rel=1e-9)
        assert np.all(ca[m >= 1.0] > 0.015) and np.max(np.abs(np.diff(ca))) < 2e-3
    cone = NoseCone(shape="conical", length=0.5, radius=0.05)
    assert head_shape_ratio(cone) == 1.0
    joint = 0.8 * np.sin(np.arctan(0.1)) ** 2
    assert np.all(nose_pressure_ca(cone, m[m < 0.9], a_ref) >= joint - 1e-12)


def test_nose_model_decided_on_the_nose_own_critical_mach(tmp_path, monkeypatch):
    """A grid whose only transonic point lies between the nose's critical Mach number
    (McCoy, fineness 3: 0.902) and the configuration's gets the nose's transonic drag:
    the configuration's critical Mach number is set above it (0.95) here, where before
    the nose model was decided on the configuration's alone and skipped (CA(0.93) was
    the subsonic value)."""
    import panair.transonic as transonic
    from model_toml import model_toml
    from ironbark_opt.vehicle import load_rocket_geometry
    from panair.rocket_table import rocket_table
    path = tmp_path / "nose.toml"
    path.write_text(model_toml("nose", calibre=0.1, nose_shape="von_karman", nose_calibres=3.0,
                               body_calibres=10.0, cg_x=0.6))
    rk, spec = load_rocket_geometry(path)
    monkeypatch.setattr(transonic, "body_critical_mach", lambda cp_min: 0.95)
    t = rocket_table(rk, spec, mach=np.array([0.3, 0.6, 0.93, 1.2]), alpha_deg=np.array([0.0, 2.0]),
                     workers=1)
    nose = t.metadata["nose_transonic"]
    assert nose is not None and nose["mach_critical"] == pytest.approx(0.902, abs=1e-3)
    _, rise = nose_transonic(1 / 3, 1.0)
    vals = t.values("CA_pressure")[:, 0]
    ca_p = {m: float(vals[int(np.argmin(np.abs(t.mach - m)))]) for m in (0.6, 0.93)}
    # the rise at Mach 0.93 is McCoy's (the configuration's own has not started there)
    assert ca_p[0.93] - ca_p[0.6] == pytest.approx(float(rise(0.93)), rel=0.05)
