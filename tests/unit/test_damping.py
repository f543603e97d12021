"""Unit tests of ironbark_opt.aero.damping: identities, closed forms of the
OpenRocket technical documentation, a direct strip summation, and
symbolic/numeric agreement."""
import math

import casadi as ca
import numpy as np
import pytest

from ironbark_opt.aero import barrowman as b
from ironbark_opt.aero import damping as dmp
from ironbark_opt.errors import InputError

R = 0.0635
D = 2 * R
AREF = math.pi * R * R
COMPS = [b.Lift(2.0, 0.279), b.Lift(6.27, 2.378), b.Lift(-1.06, 2.501)]


def test_cmq_single_surface_and_sign():
    # one surface at arm l: Cmq = -2 CN_alpha (l/d)^2
    assert dmp.pitch_damping_cmq([b.Lift(5.0, 2.0)], 1.5, D) == pytest.approx(-2 * 5.0 * (0.5 / D) ** 2)
    assert dmp.pitch_damping_cmq(COMPS, 1.4988, D) < 0


def test_cmq_parallel_axis_identity():
    # sum a_i (x_i - x)^2 = sum a_i (x_i - xbar)^2 + A (xbar - x)^2  (xbar = slope-weighted CP)
    cna, xcp = b.total(COMPS)
    at_cp = dmp.pitch_damping_cmq(COMPS, xcp, D)
    for x in (0.5, 1.4988, 2.2):
        expected = at_cp - 2 * cna * ((xcp - x) / D) ** 2
        assert dmp.pitch_damping_cmq(COMPS, x, D) == pytest.approx(expected, rel=1e-12)


def test_cmq_matches_moment_of_a_pitching_rocket():
    # independent route: each component sees alpha_i = q (x_cg - x_i)/V and pushes with
    # CN_i = CN_alpha_i alpha_i at x_i; the moment about the CG, differentiated in q_hat.
    x_cg, V, q = 1.4988, 100.0, 1e-3
    cm = sum(-c.cn_alpha * (q * (x_cg - c.x_cp) / V) * (x_cg - c.x_cp) / D for c in COMPS)
    q_hat = q * D / (2 * V)
    assert dmp.pitch_damping_cmq(COMPS, x_cg, D) == pytest.approx(cm / q_hat, rel=1e-12)


@pytest.mark.parametrize("sym", [ca.SX, ca.MX])
def test_cmq_symbolic_in_cg_and_mach(sym):
    x = sym.sym("x")
    M = sym.sym("M")
    comps = [b.nose_cone(0.55829, R, AREF, shape="von_karman"),
             b.trapezoidal_fins(4, 0.12, 0.06, 0.11, 0.06, 2.32756, R, AREF, M)]
    cmq = dmp.pitch_damping_cmq(comps, x, D)
    cna = b.total(comps)[0]
    f = ca.Function("f", [x, M], [cmq, ca.hessian(cmq, x)[0], cna])
    for xc, mach in ((1.2, 0.3), (1.5, 1.1), (1.7, 2.5)):
        num = [b.nose_cone(0.55829, R, AREF, shape="von_karman"),
               b.trapezoidal_fins(4, 0.12, 0.06, 0.11, 0.06, 2.32756, R, AREF, mach)]
        c, h, a = (float(v) for v in f(xc, mach))
        assert c == pytest.approx(dmp.pitch_damping_cmq(num, xc, D), rel=1e-12)
        # d^2 Cmq / d x_cg^2 = -4 CN_alpha_total / d^2 (from the parallel-axis form)
        assert h == pytest.approx(-4 * a / D ** 2, rel=1e-10)


def test_trapezoid_roll_integral_matches_openrocket_closed_form():
    # [N13] eq. 3.70: sum c xi^2 dxi = (Cr+Ct)/2 r^2 s + (Cr+2Ct)/3 r s^2 + (Cr+3Ct)/12 s^3
    cr, ct, s = 0.12, 0.06, 0.11
    plan = b.trapezoid_planform(cr, ct, s, 0.06)
    ref = (cr + ct) / 2 * R ** 2 * s + (cr + 2 * ct) / 3 * R * s ** 2 + (cr + 3 * ct) / 12 * s ** 3
    assert plan.roll_integral(R) == pytest.approx(ref, rel=1e-12)


def test_elliptical_roll_integral_matches_openrocket_closed_form():
    # [N13] eq. 3.71: Cr (pi/4 r^2 s + 2/3 r s^2 + pi/16 s^3)
    cr, s = 0.15, 0.09
    ref = cr * (math.pi / 4 * R ** 2 * s + 2 / 3 * R * s ** 2 + math.pi / 16 * s ** 3)
    assert b.elliptical_planform(cr, s).roll_integral(R) == pytest.approx(ref, rel=1e-12)


@pytest.mark.parametrize("mach", [0.3, 0.8, 2.0, 3.0])
def test_clp_matches_direct_strip_summation(mach):
    # independent route: sum the roll moment of 4 fins, strip by strip, at a small roll
    # rate with the strip angle p xi / V, then divide by p_hat.
    cr, ct, s, xt, n = 0.12, 0.06, 0.11, 0.06, 4
    plan = b.trapezoid_planform(cr, ct, s, xt)
    V, p = 200.0, 0.01
    beta = math.sqrt(abs(1 - mach * mach))
    slope = 2 * math.pi / beta if mach < 1 else 4 / beta
    ys = (np.arange(20000) + 0.5) * s / 20000
    xi = R + ys
    c = cr + (ct - cr) * ys / s
    moment = -n * np.sum(slope * (p * xi / V) * c * xi) * (s / 20000)   # / (q A_ref d)
    cl = moment / (AREF * D)
    expected = cl / (p * D / (2 * V))
    assert dmp.roll_damping_clp(plan, n, R, AREF, D, mach) == pytest.approx(expected, rel=1e-6)


def test_roll_forcing_and_steady_roll_rate_balance():
    plan = b.trapezoid_planform(0.12, 0.06, 0.11, 0.06)
    cant, V = math.radians(0.5), 150.0
    for mach in (0.3, 2.0):
        cld = dmp.roll_forcing_cl_delta(plan, 4, R, AREF, D, mach)
        clp = dmp.roll_damping_clp(plan, 4, R, AREF, D, mach)
        # [N13] eq. 3.66 by hand
        cna1 = b.single_fin_cn_alpha(plan, mach, AREF)
        assert cld == pytest.approx(4 * (plan.mac_y + R) * cna1 / D, rel=1e-12)
        p = dmp.steady_roll_rate(cld, clp, cant, V, D)
        assert p > 0
        assert cld * cant + clp * p * D / (2 * V) == pytest.approx(0.0, abs=1e-15)
    # subsonic equilibrium frequency, [N13] eq. 3.72 (with y_MAC + r_t, as in its eq. 3.66)
    mach = 0.3
    cld = dmp.roll_forcing_cl_delta(plan, 4, R, AREF, D, mach)
    clp = dmp.roll_damping_clp(plan, 4, R, AREF, D, mach)
    f_eq = dmp.steady_roll_rate(cld, clp, cant, V, D) / (2 * math.pi)
    beta = math.sqrt(1 - mach ** 2)
    ref = (AREF * beta * V * (plan.mac_y + R) * b.single_fin_cn_alpha(plan, mach, AREF) * cant
           / (4 * math.pi ** 2 * plan.roll_integral(R)))
    assert f_eq == pytest.approx(ref, rel=1e-12)


def test_section_slope_limits_and_continuity():
    assert dmp.section_lift_slope(0.0) == pytest.approx(2 * math.pi)
    assert dmp.section_lift_slope(0.6) == pytest.approx(2 * math.pi / 0.8)
    assert dmp.section_lift_slope(2.0) == pytest.approx(4 / math.sqrt(3))
    for edge in (b.MACH_SUBSONIC, b.MACH_SUPERSONIC):
        lo, hi = dmp.section_lift_slope(edge - 1e-8), dmp.section_lift_slope(edge + 1e-8)
        assert hi == pytest.approx(lo, rel=1e-6)


@pytest.mark.parametrize("sym", [ca.SX, ca.MX])
def test_roll_derivatives_symbolic_numeric_drift(sym):
    plan = b.trapezoid_planform(0.12, 0.06, 0.11, 0.06)
    M = sym.sym("M")
    f = ca.Function("f", [M], [dmp.roll_forcing_cl_delta(plan, 4, R, AREF, D, M),
                               dmp.roll_damping_clp(plan, 4, R, AREF, D, M)])
    machs = np.array([0.0, 0.5, 0.9, 1.0, 1.3, 1.5, 3.0])
    vec = dmp.roll_damping_clp(plan, 4, R, AREF, D, machs)
    for i, mach in enumerate(machs):
        cld, clp = (float(v) for v in f(mach))
        assert cld == pytest.approx(dmp.roll_forcing_cl_delta(plan, 4, R, AREF, D, float(mach)),
                                    rel=1e-12)
        assert clp == pytest.approx(dmp.roll_damping_clp(plan, 4, R, AREF, D, float(mach)), rel=1e-12)
        assert vec[i] == pytest.approx(clp, rel=1e-12)


@pytest.mark.parametrize("call,field", [
    (lambda: dmp.pitch_damping_cmq([], 1.0, D), "components"),
    (lambda: dmp.pitch_damping_cmq(COMPS, 1.0, 0.0), "reference_length"),
    (lambda: dmp.roll_damping_clp(b.trapezoid_planform(0.1, 0.05, 0.1, 0.0), 0, R, AREF, D),
     "count"),
    (lambda: dmp.roll_forcing_cl_delta(b.trapezoid_planform(0.1, 0.05, 0.1, 0.0), 4, -R, AREF, D),
     "body_radius"),
])
def test_bad_input(call, field):
    with pytest.raises(InputError) as err:
        call()
    assert err.value.field == field
