"""Unit tests of ironbark_opt.aero.barrowman: closed forms against independent
integrations, Barrowman's own formulas, continuity in Mach and symbolic/numeric
agreement."""
import math

import casadi as ca
import numpy as np
import pytest
from scipy.integrate import quad

from ironbark_opt.aero import barrowman as b
from ironbark_opt.errors import InputError

R = 0.0635
AREF = math.pi * R * R


# --- independent nose profiles (Crowell / OpenRocket tech doc appendix A) ---------------

def _profile(shape, L, Rb, p=None):
    if shape == "conical":
        return lambda x: Rb * x / L
    if shape == "ogive":
        rho = (Rb * Rb + L * L) / (2 * Rb)
        return lambda x: math.sqrt(rho ** 2 - (L - x) ** 2) + Rb - rho
    if shape == "ellipsoid":
        return lambda x: Rb * math.sqrt(max(0.0, 1 - (1 - x / L) ** 2))
    if shape == "power":
        return lambda x: Rb * (x / L) ** p
    if shape == "parabolic":
        return lambda x: Rb * (2 * x / L - p * (x / L) ** 2) / (2 - p)
    if shape == "haack":
        def r(x):
            th = math.acos(1 - 2 * x / L)
            return Rb / math.sqrt(math.pi) * math.sqrt(max(0.0, th - math.sin(2 * th) / 2
                                                           + p * math.sin(th) ** 3))
        return r
    raise ValueError(shape)


@pytest.mark.parametrize("shape,p", [("conical", None), ("ogive", None), ("ellipsoid", None),
                                     ("power", 0.5), ("power", 0.75), ("parabolic", 0.5),
                                     ("parabolic", 1.0), ("haack", 0.0), ("haack", 1 / 3)])
def test_nose_volume_closed_form_matches_quadrature(shape, p):
    L, Rb = 0.5, 0.06
    r = _profile(shape, L, Rb, p)
    v_quad = quad(lambda x: math.pi * r(x) ** 2, 0, L, limit=200)[0]
    v = b.nose_volume(shape, L, Rb, p)
    assert v == pytest.approx(v_quad, rel=1e-6)


def test_named_haack_shapes_and_cone_cp():
    L, Rb = 0.4, 0.05
    assert b.nose_volume("von_karman", L, Rb) == pytest.approx(b.nose_volume("haack", L, Rb, 0.0))
    assert b.nose_volume("lv_haack", L, Rb) == pytest.approx(b.nose_volume("haack", L, Rb, 1 / 3))
    # [B66] eq. 32: cone CP at 2/3 L; slope 2 for any nose with base = reference area
    cone = b.nose_cone(L, Rb, math.pi * Rb ** 2, shape="conical", x_tip=0.1)
    assert cone.cn_alpha == pytest.approx(2.0, rel=1e-12)
    assert cone.x_cp == pytest.approx(0.1 + 2 * L / 3, rel=1e-12)
    # von Karman: V = A L/2 exactly, so x_cp = L/2
    assert b.nose_cone(L, Rb, 1.0, shape="von_karman").x_cp == pytest.approx(L / 2)


def test_transition_matches_barrowman_frustum_formula():
    # [B66] eq. 44: x = L/3 [1 + (1 - d1/d2)/(1 - (d1/d2)^2)], CN_alpha = 2 (A2 - A1)/A_ref
    for r1, r2 in [(0.0635, 0.0435), (0.03, 0.05)]:
        L, x0 = 0.06, 2.0
        t = b.transition(x0, L, r1, r2, AREF)
        q = r1 / r2
        assert t.x_cp - x0 == pytest.approx(L / 3 * (1 + (1 - q) / (1 - q * q)), rel=1e-12)
        assert t.cn_alpha == pytest.approx(2 * math.pi * (r2 ** 2 - r1 ** 2) / AREF, rel=1e-12)
    assert b.transition(1.0, 0.2, R, R, AREF).cn_alpha == 0.0


# --- planforms ----------------------------------------------------------------------------

def _trapezoid_points(cr, ct, s, xt):
    return [(0.0, 0.0), (xt, s), (xt + ct, s), (cr, 0.0)]


def test_trapezoid_closed_form_matches_strip_integration():
    cr, ct, s, xt = 0.12, 0.06, 0.11, 0.06
    a = b.trapezoid_planform(cr, ct, s, xt)
    p = b.polygon_planform(_trapezoid_points(cr, ct, s, xt), n_strips=2000)
    for f in ("span", "area", "mac_length", "mac_x_le", "mac_y", "cos_midchord_sweep",
              "chord_moment_1", "chord_moment_2"):
        assert getattr(p, f) == pytest.approx(getattr(a, f), rel=1e-5), f
    # numbers of [B66] eq. 69/70 by hand: MAC = 2/3 (0.18 - 0.0072/0.18), Ybar = s/3 * 0.24/0.18
    assert a.mac_length == pytest.approx(2 / 3 * (0.18 - 0.04), rel=1e-12)
    assert a.mac_y == pytest.approx(0.11 / 3 * 0.24 / 0.18, rel=1e-12)


def test_elliptical_closed_form_matches_strip_integration():
    cr, s = 0.15, 0.09
    e = b.elliptical_planform(cr, s)
    th = np.linspace(0, math.pi, 4001)
    # outline: leading edge x = (cr - c)/2, trailing edge x = (cr + c)/2, c = cr sin(th)
    y = s * np.cos(th - math.pi / 2)            # 0 -> s -> 0
    c = cr * np.sqrt(np.clip(1 - (y / s) ** 2, 0, 1))
    le = [((cr - ci) / 2, yi) for ci, yi in zip(c[: len(c) // 2 + 1], y[: len(y) // 2 + 1])]
    te = [((cr + ci) / 2, yi) for ci, yi in zip(c[len(c) // 2:], y[len(y) // 2:])]
    p = b.polygon_planform(le + te, n_strips=4000)
    for f in ("area", "mac_length", "mac_x_le", "mac_y", "chord_moment_1", "chord_moment_2"):
        assert getattr(p, f) == pytest.approx(getattr(e, f), rel=2e-4), f
    assert p.cos_midchord_sweep == pytest.approx(1.0, abs=1e-9)


# --- fins -------------------------------------------------------------------------------

def test_fins_at_mach_zero_equal_barrowman_eq_58_59():
    cr, ct, s, xt, d = 0.12, 0.06, 0.11, 0.06, 2 * R
    l_mid = math.hypot(s, xt + ct / 2 - cr / 2)      # length of the mid-chord line
    den = 1 + math.sqrt(1 + (2 * l_mid / (cr + ct)) ** 2)
    k = 1 + R / (s + R)                               # [B66] eq. 77
    four = b.trapezoidal_fins(4, cr, ct, s, xt, 2.0, R, AREF, 0.0)
    three = b.trapezoidal_fins(3, cr, ct, s, xt, 2.0, R, AREF, 0.0)
    assert four.cn_alpha == pytest.approx(k * 16 * (s / d) ** 2 / den, rel=1e-12)
    assert three.cn_alpha == pytest.approx(k * 12 * (s / d) ** 2 / den, rel=1e-12)
    # [B66] eq. 76a: Xbar_F = Xr/3 (Cr + 2Ct)/(Cr + Ct) + 1/6 (Cr + Ct - Cr Ct/(Cr + Ct))
    xf = xt / 3 * (cr + 2 * ct) / (cr + ct) + (cr + ct - cr * ct / (cr + ct)) / 6
    assert four.x_cp == pytest.approx(2.0 + xf, rel=1e-12)


def test_fin_count_factors_reproduce_datcom_ratios():
    # [N13] §3.2.2: six and eight fins give 1.37 and 1.62 times the four-fin slope
    plan = b.trapezoid_planform(0.1, 0.05, 0.08, 0.04)
    c4, c6, c8 = (b.fins(plan, n, 1.0, 0.05, 0.01).cn_alpha for n in (4, 6, 8))
    assert c6 / c4 == pytest.approx(1.37, abs=0.005)
    assert c8 / c4 == pytest.approx(1.62, abs=0.005)
    assert b.fin_count_factor(12) == 0.75


def test_subsonic_prandtl_glauert_limits():
    plan = b.trapezoid_planform(0.12, 0.06, 0.11, 0.06)
    # high-aspect-ratio limit of eq. 3.40 is the 2-D slope 2 pi/beta times A cos(G)/A_ref
    wide = b.trapezoid_planform(0.01, 0.01, 50.0, 0.0)   # s^2/A = 5000
    for M in (0.0, 0.5, 0.8):
        v = b.single_fin_cn_alpha(wide, M, 1.0)
        assert v == pytest.approx(2 * math.pi * wide.area / math.sqrt(1 - M * M), rel=1e-3)
    # supersonic: Ackeret 4/beta * A_fin/A_ref
    for M in (1.5, 2.0, 3.0):
        v = b.single_fin_cn_alpha(plan, M, AREF)
        assert v == pytest.approx(4 * plan.area / AREF / math.sqrt(M * M - 1), rel=1e-12)


@pytest.mark.parametrize("mach_edge", [b.MACH_SUBSONIC, b.MACH_SUPERSONIC,
                                       b.MACH_CP_SUBSONIC, b.MACH_CP_SUPERSONIC])
def test_fin_slope_and_cp_continuous_in_mach(mach_edge):
    plan = b.trapezoid_planform(0.12, 0.06, 0.11, 0.06)
    eps = 1e-7
    for f in (lambda M: b.single_fin_cn_alpha(plan, M, AREF),
              lambda M: b.fin_cp_fraction(plan.aspect_ratio, M)):
        lo, hi = f(mach_edge - eps), f(mach_edge + eps)
        assert abs(hi - lo) < 1e-5 * max(1.0, abs(lo))
        # C1: one-sided slopes agree
        h = 1e-4
        d_lo = (f(mach_edge - h) - f(mach_edge - 2 * h)) / h
        d_hi = (f(mach_edge + 2 * h) - f(mach_edge + h)) / h
        assert d_hi == pytest.approx(d_lo, abs=5e-3 * max(1.0, abs(d_lo)))


def test_fin_cp_fraction_limits():
    assert b.fin_cp_fraction(2.0, 0.3) == pytest.approx(0.25)
    M = 3.0
    x = 2.0 * math.sqrt(M * M - 1)
    assert b.fin_cp_fraction(2.0, M) == pytest.approx((x - 0.67) / (2 * x - 1), rel=1e-12)
    # low aspect ratio: A beta held at 1 -> 0.33 instead of the pole at A beta = 0.5
    assert b.fin_cp_fraction(0.2, 2.69) == pytest.approx(0.33, rel=1e-12)
    cps = [b.fin_cp_fraction(a, M) for a in (0.1, 0.5, 2.0) for M in np.linspace(0, 5, 101)]
    assert 0.25 - 1e-12 <= min(cps) and max(cps) < 0.5


# --- combination -------------------------------------------------------------------------

def _calisto_components(mach):
    nose = b.nose_cone(0.55829, R, AREF, shape="von_karman")
    fins = b.trapezoidal_fins(4, 0.12, 0.06, 0.11, 0.06, 2.32756, R, AREF, mach)
    tail = b.transition(2.472656, 0.060, R, 0.0435, AREF)
    return [nose, fins, tail]


def test_total_and_static_margin():
    comps = [b.Lift(2.0, 0.3), b.Lift(6.0, 2.3), b.Lift(-1.0, 2.5)]
    cna, xcp = b.total(comps)
    assert cna == pytest.approx(7.0)
    assert xcp == pytest.approx((0.6 + 13.8 - 2.5) / 7.0)
    assert b.static_margin(xcp, 1.5, 0.127) == pytest.approx((xcp - 1.5) / 0.127)
    # Cm_alpha about the CP vanishes; about x it is -CN_alpha (x_cp - x)/d
    assert b.pitch_moment_slope(comps, xcp, 0.127) == pytest.approx(0.0, abs=1e-12)
    assert b.pitch_moment_slope(comps, 1.0, 0.127) == pytest.approx(-cna * (xcp - 1.0) / 0.127)


@pytest.mark.parametrize("sym", [ca.SX, ca.MX])
def test_symbolic_numeric_drift(sym):
    machs = np.array([0.0, 0.3, 0.7, 0.9, 0.95, 1.0, 1.2, 1.5, 1.7, 2.0, 2.5, 4.0])
    M = sym.sym("M")
    xcg = sym.sym("xcg")
    comps = _calisto_components(M)
    cna, xcp = b.total(comps)
    sm = b.static_margin(xcp, xcg, 2 * R)
    fn = ca.Function("f", [M, xcg], [cna, xcp, sm])
    vec = b.total(_calisto_components(machs))      # NumPy arrays through the same code
    for i, mach in enumerate(machs):
        cna_f, xcp_f = b.total(_calisto_components(float(mach)))
        c, x, s = (float(v) for v in fn(mach, 1.4988))
        assert c == pytest.approx(cna_f, rel=1e-12, abs=1e-12)
        assert x == pytest.approx(xcp_f, rel=1e-12)
        assert s == pytest.approx((xcp_f - 1.4988) / (2 * R), rel=1e-10)
        assert vec[0][i] == pytest.approx(cna_f, rel=1e-12)
    # derivative w.r.t. Mach exists and is finite everywhere (no NaN from the unused branch)
    jac = ca.Function("j", [M, xcg], [ca.jacobian(cna, M)])
    assert all(np.isfinite(float(jac(mm, 1.5))) for mm in machs)


def test_body_lift_constant_k_symbolic_and_numeric():
    """Galejs' constant-K form (the ``k`` option), [N13] eq. 3.26."""
    a = ca.SX.sym("a")
    cn, x = b.body_lift(a, 0.3, 1.2, AREF, k=b.BODY_LIFT_K)
    f = ca.Function("f", [a], [cn])
    for al in (0.0, 0.1, 0.5, 1.5):
        ref = 1.1 * 0.3 / AREF * math.sin(al) ** 2
        assert float(f(al)) == pytest.approx(ref, rel=1e-12, abs=1e-15)
        assert b.body_lift(al, 0.3, 1.2, AREF, k=1.1)[0] == pytest.approx(ref, rel=1e-12, abs=1e-15)
    assert x == 1.2
    with pytest.raises(InputError, match="fineness"):
        b.body_lift(0.1, 0.3, 1.2, AREF)


# --- bad input ---------------------------------------------------------------------------

@pytest.mark.parametrize("call,field", [
    (lambda: b.trapezoid_planform(-0.1, 0.05, 0.1, 0.0), "root_chord"),
    (lambda: b.trapezoid_planform(0.1, 0.05, 0.0, 0.0), "span"),
    (lambda: b.trapezoid_planform(0.1, "x", 0.1, 0.0), "tip_chord"),
    (lambda: b.nose_cone(0.5, 0.05, 0.0), "reference_area"),
    (lambda: b.nose_cone(0.5, 0.05, 1.0, shape="banana"), "shape"),
    (lambda: b.nose_volume("power", 0.5, 0.05), "parameter"),
    (lambda: b.nose_volume("haack", 0.5, 0.05, 0.9), "parameter"),
    (lambda: b.nose_cone(0.5, 0.05, 1.0, volume=1.0), "volume"),
    (lambda: b.fin_count_factor(0), "count"),
    (lambda: b.fin_count_factor(2.5), "count"),
    (lambda: b.polygon_planform([(0, 0), (1, 0)]), "points"),
    (lambda: b.polygon_planform([(0, 0), (1, -1), (2, 0)]), "points"),
    (lambda: b.polygon_planform([(0, 0), (1, 0), (2, 0)]), "points"),
    (lambda: b.total([]), "components"),
    (lambda: b.total([b.Lift(1.0, 1.0), b.Lift(-1.0, 2.0)]), "components"),
    (lambda: b.static_margin(1.0, 0.5, float("nan")), "reference_length"),
])
def test_bad_input_raises_input_error_naming_field(call, field):
    with pytest.raises(InputError) as err:
        call()
    assert err.value.field == field


def test_body_tube_adds_no_linear_lift():
    comps = _calisto_components(0.5)
    tube = b.body_tube(0.55829, 1.9, R)
    assert tube.cn_alpha == 0.0 and tube.x_cp == pytest.approx(0.55829 + 0.95)
    assert b.total(comps + [tube]) == pytest.approx(b.total(comps), rel=1e-15)
