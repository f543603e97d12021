"""Tube fins: Ribner's ring-wing normal force and OpenRocket's tube-fin geometry, against
closed forms."""
import math

import numpy as np
import pytest

from ironbark_opt.aero import barrowman
from ironbark_opt.aero.protuberance import LaunchLugDrag
from ironbark_opt.rocket import TubeFins


def test_ribner_ring_wing_slope():
    # Ribner 1947 eq. 5: per tube 2 A'/(1 + A') pi^2 r c, A' = 2 A / pi, A = 2 r / c
    r, c, n, sref = 0.012, 0.076, 6, math.pi * 0.0125 ** 2
    a_p = 2.0 * (2.0 * r / c) / math.pi
    expected = n * 2.0 * a_p / (1.0 + a_p) * math.pi ** 2 * r * c / sref
    lift = barrowman.tube_fins(n, 0.5, c, r, sref, mach=0.3)
    assert float(lift.cn_alpha) == pytest.approx(expected, rel=1e-12)
    assert float(lift.x_cp) == pytest.approx(0.5 + 0.25 * c, rel=1e-12)      # quarter chord, subsonic


def test_touching_tubes_wetted_and_interstice_areas():
    # six tubes of the body's radius touch each other: theta1 = 60 deg, theta2 = 30 deg;
    # wetted L (2 (pi - pi/3) r - 2 (pi/6) r) = pi L r; interstice (sqrt 3 - pi/2) r^2
    r, L = 0.0125, 0.076
    t = TubeFins(x=0.5, length=L, outer_radius=r, inner_radius=0.9 * r, count=6, body_radius=r)
    assert t.wetted_area_each() == pytest.approx(math.pi * L * r, rel=1e-12)
    assert t.interstice_area_each() == pytest.approx((math.sqrt(3.0) - math.pi / 2.0) * r * r, rel=1e-12)


def test_tube_drag_is_count_lugs_with_their_areas():
    r, L = 0.0125, 0.076
    one = LaunchLugDrag(0.5, L, r, 0.9 * r, roughness=60e-6)
    six = LaunchLugDrag(0.5, L, r, 0.9 * r, roughness=60e-6, wetted_area=2 * math.pi * r * L, count=6)
    for mach, re in ((0.1, 2e6), (0.5, 1e7)):
        assert float(six.CA(mach, re, 1e-3)) == pytest.approx(6 * float(one.CA(mach, re, 1e-3)), rel=1e-12)
    blunt = LaunchLugDrag(0.5, L, r, 0.9 * r, roughness=60e-6, extra_frontal_area=1e-4)
    assert float(blunt.CA(0.3, 5e6, 1e-3)) > float(one.CA(0.3, 5e6, 1e-3))


def test_mass_properties_of_thin_tubes():
    r, L, rho = 0.0125, 0.076, 900.0
    t = TubeFins(x=0.5, length=L, outer_radius=r, inner_radius=0.95 * r, count=6, body_radius=r,
                 density=rho)
    mp = t.mass_properties()
    m_each = rho * math.pi * (r * r - (0.95 * r) ** 2) * L
    assert mp.mass == pytest.approx(6 * m_each, rel=1e-12)
    assert mp.cg_x == pytest.approx(0.5 + 0.5 * L, rel=1e-12)
    # axial: own + offset (2 r from the axis), parallel-axis theorem
    assert mp.inertia[0, 0] == pytest.approx(6 * m_each * (0.5 * (r * r + (0.95 * r) ** 2) + 4 * r * r), rel=1e-12)
