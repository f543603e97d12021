"""Gravity: WGS-84 Somigliana + TR8350.2 free-air, and the 1976 standard's law."""
from __future__ import annotations

import math

import casadi as ca
import numpy as np
import pytest

from ironbark_opt.atmosphere import gravity
from ironbark_opt.atmosphere.gravity import (
    WGS84_A, WGS84_B, WGS84_E2, WGS84_M, GAMMA_EQUATOR, GAMMA_POLE, normal_gravity_ellipsoid)


def test_somigliana_equator_and_pole_tr8350():
    """NIMA TR8350.2 Table 3.4: gamma_e = 9.7803253359, gamma_p = 9.8321849378 m/s^2."""
    ge = float(gravity(0.0, 0.0))
    gp = float(gravity(0.0, math.pi / 2))
    print(f"equator error {ge - 9.7803253359:.1e}, pole error {gp - 9.8321849378:.1e} m/s^2")
    assert ge == pytest.approx(9.7803253359, abs=1e-10)
    assert gp == pytest.approx(9.8321849378, abs=1e-10)
    assert float(gravity(0.0, -math.pi / 2)) == pytest.approx(gp, abs=1e-12)


def test_somigliana_against_the_original_form():
    """Somigliana's original form (a ge cos^2 + b gp sin^2) / sqrt(a^2 cos^2 + b^2 sin^2)
    -- algebraically the same law, written independently -- to 1e-12 m/s^2."""
    lat = np.radians(np.linspace(-90.0, 90.0, 37))
    c2, s2 = np.cos(lat) ** 2, np.sin(lat) ** 2
    ref = (WGS84_A * GAMMA_EQUATOR * c2 + WGS84_B * GAMMA_POLE * s2) / np.sqrt(
        WGS84_A ** 2 * c2 + WGS84_B ** 2 * s2)
    err = np.max(np.abs(normal_gravity_ellipsoid(lat) - ref))
    print(f"Somigliana vs original form: max error {err:.1e} m/s^2")
    assert err < 1e-12


def test_45_degrees_against_grs80_value():
    """9.806199203 m/s^2 is Moritz's GRS80 normal gravity at 45 deg (IGF 1980).
    WGS-84 differs from GRS80 by ~1.4e-6 m/s^2 there; tolerance 2e-6."""
    g45 = float(gravity(0.0, math.radians(45.0)))
    print(f"45 deg: WGS-84 {g45:.10f} vs GRS80 9.806199203, diff {g45 - 9.806199203:.2e}")
    assert g45 == pytest.approx(9.806199203, abs=2e-6)


def test_free_air_gradient_by_ad():
    """d gamma / dh at 45 deg, h = 0: -2 gamma/a (1 + f + m - 2 f sin^2) (TR8350.2 eq. 4-3)
    is the textbook free-air gradient 0.3086 mGal/m = 3.086e-6 s^-2 (to 5e-9 s^-2)."""
    h = ca.SX.sym("h")
    lat = math.radians(45.0)
    dg = float(ca.Function("d", [h], [ca.jacobian(gravity(h, lat), h)])(0.0))
    print(f"free-air gradient at 45 deg: {dg:.5e} s^-2")
    assert dg == pytest.approx(-3.086e-6, abs=5e-9)


def test_spaceport_america():
    """Spaceport America (32.990254 N, 1400 m): ~9.79 m/s^2; second-order term checked
    against the first-order gradient (difference 3 h^2 gamma / a^2 = 1.4e-6)."""
    lat = math.radians(32.990254)
    g = float(gravity(1400.0, lat))
    print(f"Spaceport America: g = {g:.6f} m/s^2")
    assert g == pytest.approx(9.79, abs=0.005)
    g0 = float(normal_gravity_ellipsoid(lat))
    s2 = math.sin(lat) ** 2
    first_order = g0 * (1 - 2 / WGS84_A * (1 + 1 / 298.257223563 + WGS84_M - 2 / 298.257223563
                                             * s2) * 1400.0)
    assert g - first_order == pytest.approx(3 * g0 * 1400.0 ** 2 / WGS84_A ** 2, rel=1e-6)


def test_standard_gravity_when_latitude_unknown():
    """latitude=None: 9.80665 (r0/(r0+h))^2, r0 = 6 356 766 m (1976 standard eq. 17)."""
    assert float(gravity(0.0)) == 9.80665
    # The 1976 standard's Table I lists g = 9.7452 m/s^2 at 20 km, 9.5614 at 81.02 km.
    assert float(gravity(20000.0)) == pytest.approx(9.7452, abs=5e-5)
    assert float(gravity(81020.0)) == pytest.approx(9.5614, abs=5e-5)


def test_symbolic_and_numeric_agree():
    h = np.array([0.0, 1400.0, 30000.0])
    lat = math.radians(32.99)
    hs, ls = ca.SX.sym("h"), ca.MX.sym("lat")
    f_sx = ca.Function("f", [hs], [gravity(hs, lat)])
    f_mx = ca.Function("f", [ls], [gravity(1400.0, ls)])
    np.testing.assert_allclose(np.array(f_sx(ca.DM(h))).ravel(), gravity(h, lat), rtol=1e-15)
    assert float(f_mx(lat)) == pytest.approx(float(gravity(1400.0, lat)), rel=1e-15)
    assert gravity(h, lat).shape == (3,)
    assert isinstance(gravity(10.0), float)
    # TR8350.2 Table 3.3: e^2 = 6.69437999014e-3 (derived from f).
    assert WGS84_E2 == pytest.approx(6.69437999014e-3, abs=5e-15)
