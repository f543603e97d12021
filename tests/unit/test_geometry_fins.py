"""Fin planforms and sections vs closed forms."""
import math

import numpy as np
import pytest
from scipy.integrate import quad

from ironbark_opt.errors import InputError
from ironbark_opt.rocket import (EllipticalFins, FinSection, FinSet, FreeformFins,
                                 TrapezoidalFins)
from ironbark_opt.rocket.fin_sections import NACA_AREA_FACTOR, NACA_CENTROID

CR, CT, S, SWEEP, T = 0.120, 0.060, 0.110, 0.060, 0.005


def trapezoid(**kw):
    args = dict(count=4, x=2.0, root_chord=CR, tip_chord=CT, span=S, sweep_length=SWEEP,
                thickness=T)
    args.update(kw)
    return TrapezoidalFins(**args)


def test_trapezoid_area_mac_and_mac_position():
    fins = trapezoid()
    assert fins.planform_area() == pytest.approx(0.5 * (CR + CT) * S, rel=1e-12)
    mac = 2 / 3 * (CR + CT - CR * CT / (CR + CT))
    assert fins.mean_aerodynamic_chord() == pytest.approx(mac, rel=1e-12)
    # generic strip integral agrees with the closed form
    strips = FinSet.mean_aerodynamic_chord(fins)
    print(f"trapezoid MAC strips {strips:.8f} vs closed form {mac:.8f}")
    assert strips == pytest.approx(mac, rel=1e-5)
    x_mac, y_mac = fins.mac_position()
    assert x_mac == pytest.approx(SWEEP * (CR + 2 * CT) / (3 * (CR + CT)), rel=1e-5)
    assert y_mac == pytest.approx(S * (CR + 2 * CT) / (3 * (CR + CT)), rel=1e-5)
    assert fins.wetted_area() == pytest.approx(8 * fins.planform_area())
    assert fins.aspect_ratio() == pytest.approx(S * S / fins.planform_area())
    assert fins.x_end == pytest.approx(2.0 + CR)


def test_elliptical_area_and_mac():
    fins = EllipticalFins(count=3, x=1.0, root_chord=0.2, span=0.1, thickness=0.004)
    assert fins.planform_area() == pytest.approx(math.pi * 0.2 * 0.1 / 4, rel=1e-12)
    y, dy, _, c = fins._strips(400)
    strip_area = float(np.sum(c * dy))
    print(f"elliptical area strips {strip_area:.8e} vs pi a b / 4 {fins.planform_area():.8e}")
    assert strip_area == pytest.approx(fins.planform_area(), rel=1e-5)
    assert fins.mean_aerodynamic_chord() == pytest.approx(8 * 0.2 / (3 * math.pi), rel=1e-5)
    assert fins.tip_chord == 0.0
    pts = fins.planform_points(200)
    assert pts[0] == pytest.approx([0, 0]) and pts[-1] == pytest.approx([0.2, 0], abs=1e-15)


def test_freeform_matches_trapezoid_and_handles_notches():
    trap = trapezoid(density=1850.0)
    free = FreeformFins(count=4, x=2.0, thickness=T, density=1850.0,
                        points=[(0, 0), (SWEEP, S), (SWEEP + CT, S), (CR, 0)])
    assert free.planform_area() == pytest.approx(trap.planform_area(), rel=1e-12)
    assert free.mean_aerodynamic_chord() == pytest.approx(trap.mean_aerodynamic_chord(), rel=1e-5)
    assert (free.root_chord, free.tip_chord, free.span, free.sweep_length) == \
        pytest.approx((CR, CT, S, SWEEP))
    m1, m2 = trap.mass_properties(0.0635), free.mass_properties(0.0635)
    assert m2.mass == pytest.approx(m1.mass, rel=1e-9)
    assert m2.cg_x == pytest.approx(m1.cg_x, rel=1e-9)
    assert m2.inertia == pytest.approx(m1.inertia, rel=1e-9)
    # a U-shaped (non-convex) outline: two chord pieces per strip in the notch
    u = FreeformFins(count=3, x=0.0, thickness=T,
                     points=[(0, 0), (0, 0.1), (0.03, 0.1), (0.03, 0.04), (0.07, 0.04),
                             (0.07, 0.1), (0.1, 0.1), (0.1, 0)])
    y, dy, _, c = u._strips(400)
    assert u.planform_area() == pytest.approx(0.1 * 0.1 - 0.04 * 0.06, rel=1e-12)
    assert float(np.sum(c * dy)) == pytest.approx(u.planform_area(), rel=1e-9)


@pytest.mark.parametrize("points, msg", [
    ([(0, 0), (0.1, 0.1)], "at least three"),
    ([(0.01, 0), (0.05, 0.1), (0.1, 0)], "first point"),
    ([(0, 0), (0.05, 0.1), (0.1, 0.02)], "last point"),
    ([(0, 0), (0.1, 0.1), (0.1, 0.0), (0.0, 0.1), (0.05, 0)], "crosses itself"),
    ([(0, 0), (0.05, -0.1), (0.1, 0)], "y >= 0"),
])
def test_freeform_rejects_bad_outlines(points, msg):
    with pytest.raises(InputError, match=msg) as err:
        FreeformFins(count=3, x=0.0, thickness=T, points=points)
    assert err.value.field == "points"



def test_freeform_reads_rocketpys_closed_outline():
    """hedy's fins as RocketPy's notebook gives them (docs/examples/hedy_flight_sim.ipynb:
    closed, root LE -> root TE -> tip -> back, the root TE 12 mm below the root line along
    the boattail) are the polygon of our order with the root TE on the root, with a warning;
    the same outline without the dip is read without one."""
    ours = FreeformFins(count=4, x=0.0, thickness=T,
                        points=[(0, 0), (0.195, 0.108), (0.25, 0.108), (0.25, 0)])
    with pytest.warns(UserWarning, match="below the root line"):
        rocketpy = FreeformFins(count=4, x=0.0, thickness=T,
                                points=[(0, 0), (0.250, -0.012), (0.250, 0.108), (0.195, 0.108), (0, 0)])
    assert rocketpy.points == ours.points
    assert rocketpy.planform_area() == pytest.approx(0.5 * (0.25 + 0.055) * 0.108, rel=1e-12)
    flat = FreeformFins(count=4, x=0.0, thickness=T,
                        points=[(0, 0), (0.250, 0.0), (0.250, 0.108), (0.195, 0.108), (0, 0)])
    assert flat.points == ours.points
    # a dip of more than a quarter of the span is no boattail root: refused as before
    with pytest.raises(InputError, match="root trailing edge"):
        FreeformFins(count=4, x=0.0, thickness=T,
                     points=[(0, 0), (0.250, -0.03), (0.250, 0.108), (0.195, 0.108), (0, 0)])

def test_sections_area_and_centroid():
    c, t = 0.1, 0.006
    assert FinSection(kind="square").area(c, t) == pytest.approx(c * t)
    assert FinSection(kind="rounded").area(c, t) == pytest.approx(c * t - (1 - math.pi / 4) * t * t)
    diamond = FinSection(kind="double_wedge")
    assert diamond.area(c, t) == pytest.approx(c * t / 2)
    assert diamond.centroid(c, t) == pytest.approx(c / 2)
    assert diamond.leading_edge_half_angle(c, t) == pytest.approx(math.atan(t / c))
    hexa = FinSection(kind="hexagonal", le_bevel=0.02, te_bevel=0.01)
    assert hexa.area(c, t) == pytest.approx(c * t - t * 0.03 / 2)
    # centroid by decomposition into rectangle + two trapezoid-bevel triangles, independently:
    # flat part [0.02, 0.09] area 0.07 t at 0.055; LE triangle area 0.01 t at 2/3*0.02;
    # TE triangle area 0.005 t at 0.09 + 0.01/3
    ref = (0.07 * 0.055 + 0.01 * 0.02 * 2 / 3 + 0.005 * (0.09 + 0.01 / 3)) / 0.085
    assert hexa.centroid(c, t) == pytest.approx(ref, rel=1e-12)
    # bevels longer than a short chord scale down to a diamond
    assert hexa.area(0.015, t) == pytest.approx(0.015 * t / 2)


def test_naca_section_against_quadrature():
    yt = lambda x: 5 * (0.2969 * math.sqrt(x) - 0.1260 * x - 0.3516 * x ** 2
                        + 0.2843 * x ** 3 - 0.1015 * x ** 4)
    area = 2 * quad(yt, 0, 1)[0]
    centroid = 2 * quad(lambda x: x * yt(x), 0, 1)[0] / area
    print(f"NACA area factor {NACA_AREA_FACTOR:.6f} vs quad {area:.6f}; centroid "
          f"{NACA_CENTROID:.6f} vs {centroid:.6f}")
    assert NACA_AREA_FACTOR == pytest.approx(area, rel=1e-10)
    assert NACA_CENTROID == pytest.approx(centroid, rel=1e-10)
    assert FinSection(kind="airfoil").area(0.1, 0.01) == pytest.approx(area * 0.1 * 0.01)


@pytest.mark.parametrize("kwargs, field", [
    (dict(count=0), "count"),
    (dict(count=2.5), "count"),
    (dict(span=-0.1), "span"),
    (dict(thickness=0.0), "thickness"),
    (dict(cant=1.0), "cant"),
    (dict(root_chord=0.0), "root_chord"),
])
def test_bad_fin_arguments(kwargs, field):
    with pytest.raises(InputError) as err:
        trapezoid(**kwargs)
    assert err.value.field == field


def test_bad_sections():
    with pytest.raises(InputError, match="unknown fin section"):
        FinSection(kind="wavy")
    with pytest.raises(InputError, match="only apply"):
        FinSection(kind="square", le_bevel=0.01, te_bevel=0.01)
    with pytest.raises(InputError, match="both"):
        FinSection(kind="double_wedge", le_bevel=0.01)


def test_trailing_edge_base_area_by_section():
    """count x thickness x span x (1 square or LE-only bevel, 1/2 rounded, 0 sharp)."""
    full = 4 * T * S
    assert trapezoid().trailing_edge_base_area() == pytest.approx(full)          # square default
    assert trapezoid(section=FinSection(kind="rounded")).trailing_edge_base_area() == \
        pytest.approx(0.5 * full)
    assert trapezoid(section=FinSection(kind="airfoil")).trailing_edge_base_area() == 0.0
    assert trapezoid(section=FinSection(kind="double_wedge")).trailing_edge_base_area() == 0.0
    assert trapezoid(section=FinSection(kind="hexagonal", le_bevel=0.01, te_bevel=0.01)
                     ).trailing_edge_base_area() == 0.0
    assert trapezoid(section=FinSection(kind="hexagonal", le_bevel=0.01, te_bevel=0.0)
                     ).trailing_edge_base_area() == pytest.approx(full)


def test_outline_of_elliptical_and_trapezoidal_fins():
    """Leading edge and chord along the span from the planform polygon: exact for a
    trapezoid, the half ellipse's c_r sqrt(1 - f^2) centred on the root mid-chord
    (64-point polygon: within 1e-3 c_r)."""
    frac, le, chord = trapezoid().outline(20)
    np.testing.assert_allclose(chord, CR + frac * (CT - CR), atol=1e-12)
    np.testing.assert_allclose(le, frac * SWEEP, atol=1e-12)
    e = EllipticalFins(count=3, x=1.0, thickness=T, root_chord=0.2, span=0.1)
    frac, le, chord = e.outline(50)
    exact = 0.2 * np.sqrt(1 - frac**2)
    assert frac[0] == 0 and frac[-1] == 1 and chord[-1] == pytest.approx(0, abs=1e-12)
    np.testing.assert_allclose(chord, exact, atol=1e-3 * 0.2)
    np.testing.assert_allclose(le, 0.5 * (0.2 - chord), atol=1e-12)
