"""Viscous cross-flow normal force (ironbark_opt.aero.crossflow): Allen & Perkins,
NACA Report 1048, as Jorgensen, NASA TR R-474 eq. 1,
CN = eta(l/d) Cdc(M sin alpha) (A_plan/A_ref) sin^2 alpha.

Hand values below are read from the published figures (eta: l/d 10 -> 0.68, 20 ->
0.75; Cdc: M_c 0.4 -> 1.25, 1.0 -> 2.02, 2.0 -> 1.48), written out here rather than
taken from the module's table."""
import math

import casadi as ca
import numpy as np
import pytest

from ironbark_opt.aero import barrowman as b
from ironbark_opt.aero import crossflow as xf
from ironbark_opt.errors import InputError

APLAN, AREF = 0.3, 0.01


@pytest.mark.parametrize("alpha_deg,mach,fineness,eta,cdc", [
    (30.0, 0.8, 10.0, 0.68, 1.25),      # M_c = 0.4
    (30.0, 2.0, 20.0, 0.75, 2.02),      # M_c = 1.0: the transonic peak
    (90.0, 2.0, 10.0, 0.68, 1.48),      # broadside: M_c = M
    (90.0, 0.4, 20.0, 0.75, 1.25),
])
def test_hand_calculation_from_the_published_formula(alpha_deg, mach, fineness, eta, cdc):
    a = math.radians(alpha_deg)
    ref = eta * cdc * APLAN / AREF * math.sin(a) ** 2
    cn = xf.normal_force(a, mach, APLAN, AREF, fineness)
    assert cn == pytest.approx(ref, rel=1e-12)
    cn_b, x = b.body_lift(a, APLAN, 1.3, AREF, mach=mach, fineness_ratio=fineness)
    assert cn_b == pytest.approx(ref, rel=1e-12) and x == 1.3


def test_broadside_normal_force_is_eta_cdc_planform():
    """At 90 deg CN = eta Cdc(M) A_plan/A_ref for every Mach number."""
    for mach in np.linspace(0.05, 3.5, 23):
        cn = xf.normal_force(math.pi / 2, mach, APLAN, AREF, 12.0)
        assert cn == pytest.approx(0.70 * xf.cdc(mach) * APLAN / AREF, rel=1e-12)


def test_curves_bounds_and_clamping():
    assert xf.eta(0.5) == xf.eta(1.0) == pytest.approx(0.55)
    assert xf.eta(100.0) == pytest.approx(0.81)
    assert np.all(np.diff([xf.eta(f) for f in np.linspace(1, 40, 79)]) >= 0)   # monotone
    mc = np.linspace(0.0, 5.0, 501)
    c = xf.cdc(mc)
    assert xf.cdc(5.0) == xf.cdc(4.0) == pytest.approx(1.32)
    # the B-spline stays within the figure's range: subcritical 1.2 (within 0.001) ... peak 2.02
    assert c.min() > 1.199 and c.max() < 2.03
    assert abs(float(np.argmax(c)) / 100 - 1.0) < 0.1          # peak near M_c = 1
    with pytest.raises(InputError, match="fineness_ratio"):
        xf.eta(0.0)


def test_symbolic_equals_numeric_and_is_smooth():
    a, mach = ca.SX.sym("a"), ca.SX.sym("M")
    cn = xf.normal_force(a, mach, APLAN, AREF, 12.0)
    f = ca.Function("f", [a, mach], [cn, ca.gradient(cn, a), ca.gradient(cn, mach)])
    h = 1e-6
    for al in np.radians([0.0, 3.5, 20.0, 45.0, 89.0]):
        for mm in (0.1, 0.6, 0.95, 1.2, 2.5):
            v, da, dm = (float(x) for x in f(al, mm))
            assert v == pytest.approx(xf.normal_force(al, mm, APLAN, AREF, 12.0), rel=1e-12, abs=1e-15)
            num = xf.normal_force(np.array([al + h, al - h]), mm, APLAN, AREF, 12.0)
            assert da == pytest.approx((num[0] - num[1]) / (2 * h), rel=1e-5, abs=1e-7)
            num = xf.normal_force(al, np.array([mm + h, mm - h]), APLAN, AREF, 12.0)
            assert dm == pytest.approx((num[0] - num[1]) / (2 * h), rel=1e-5, abs=1e-7)
    # zero slope at alpha = 0: CN-alpha and the static margin are the linear model's
    assert float(f(0.0, 0.8)[1]) == 0.0


def test_aero_model_uses_it_and_keeps_the_constant_k_option():
    from dataclasses import replace
    from pathlib import Path
    from ironbark_opt import load_setup
    aero = load_setup(Path(__file__).parents[2] / "examples/calisto/calisto.toml").aero
    al, mach = math.radians(40.0), 0.7
    lin = float(aero._sums(mach)[0]) * math.sin(al)
    body = xf.normal_force(al, mach, aero.lift.planform_area, aero.reference_area, aero.lift.fineness_ratio)
    assert float(aero.normal(mach, al)[0]) == pytest.approx(lin + body, rel=1e-12)
    galejs = replace(aero, body_lift_k=1.1)
    k_body = 1.1 * aero.lift.planform_area / aero.reference_area * math.sin(al) ** 2
    assert float(galejs.normal(mach, al)[0]) == pytest.approx(lin + k_body, rel=1e-12)


def test_curves_against_independent_readings_of_the_same_figures():
    """eta(l/d) against an independent digitisation of [J77]'s eta figure (AeroSandbox's
    fit ``jorgensen_eta``, 1 - 23.00906/(x + 122.769) - (13.00645/(x + 24.3676))^2, values
    worked out here, not its code) to 0.01; Cdc(M_c) against Gowen & Perkins' cylinder
    points as OpenRocket 23.09 transcribed them (aero.protuberance.GP_MACH/GP_CD, the
    rail buttons' source) to 0.1 (two readings of the figures, a few percent each)."""
    from ironbark_opt.aero.protuberance import GP_CD, GP_MACH
    for x in (1.0, 2.0, 4.0, 6.0, 8.0, 10.0, 12.0, 16.0, 20.0, 24.0, 28.0, 32.0, 40.0):
        ref = 1 - 23.009059965179222 / (x + 122.76900250914575) - (13.006453125841258 / (x + 24.367562360344193)) ** 2
        assert xf.eta(x) == pytest.approx(ref, abs=0.01)
    for mach, cd in zip(GP_MACH, GP_CD):
        assert float(xf.cdc(mach)) == pytest.approx(cd, abs=0.1)
