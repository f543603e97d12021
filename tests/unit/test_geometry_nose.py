"""Nose cones and transitions: volumes and wetted areas vs closed forms and quadrature."""
import math

import numpy as np
import pytest
from scipy.integrate import quad

from ironbark_opt.errors import InputError
from ironbark_opt.rocket import BodyTube, NoseCone, Transition

L, R = 0.55, 0.0635
REL = 1e-5  # frustum sum with 2001 cosine-spaced stations


def _report(name, got, ref):
    err = abs(got - ref) / ref
    print(f"{name}: {got:.9g} vs {ref:.9g}, rel. error {err:.2e} (tol {REL:g})")
    return err


@pytest.mark.parametrize("shape, param, volume", [
    ("conical", None, math.pi * R * R * L / 3),
    ("elliptical", None, 2 / 3 * math.pi * R * R * L),                    # half spheroid
    ("power", 0.5, math.pi * R * R * L / 2),                             # pi R^2 L/(2n+1)
    ("power", 0.75, math.pi * R * R * L / 2.5),
    ("parabolic", 1.0, math.pi * R * R * L * 8 / 15),                     # (4/3 - K + K^2/5)/(2-K)^2
    ("parabolic", 0.5, math.pi * R * R * L * (4 / 3 - 0.5 + 0.05) / 1.5 ** 2),
    ("von_karman", None, math.pi * R * R * L / 2),                        # R^2 L/2 pi (1 + 3C/8)
    ("lv_haack", None, math.pi * R * R * L / 2 * (1 + 3 / 8 / 3)),
])
def test_nose_volume_closed_form(shape, param, volume):
    nose = NoseCone(shape=shape, shape_parameter=param, length=L, radius=R)
    assert _report(f"{shape}({param}) volume", nose.volume(), volume) < REL


def test_cone_and_spheroid_wetted_area():
    cone = NoseCone(shape="conical", length=L, radius=R)
    assert _report("cone area", cone.wetted_area(), math.pi * R * math.hypot(R, L)) < REL
    e = math.sqrt(1 - R * R / (L * L))
    spheroid = math.pi * R * R * (1 + L / (R * e) * math.asin(e))        # half prolate spheroid
    ell = NoseCone(shape="elliptical", length=L, radius=R)
    assert _report("ellipsoid area", ell.wetted_area(), spheroid) < 1e-4


def test_tangent_ogive_against_quadrature():
    rho = (R * R + L * L) / (2 * R)
    r = lambda x: math.sqrt(rho * rho - (L - x) ** 2) + R - rho
    dr = lambda x: (L - x) / math.sqrt(rho * rho - (L - x) ** 2)
    vol = quad(lambda x: math.pi * r(x) ** 2, 0, L, epsabs=0, epsrel=1e-12)[0]
    area = quad(lambda x: 2 * math.pi * r(x) * math.sqrt(1 + dr(x) ** 2), 0, L,
                epsabs=0, epsrel=1e-12)[0]
    nose = NoseCone(shape="tangent_ogive", length=L, radius=R)
    assert _report("ogive volume", nose.volume(), vol) < REL
    assert _report("ogive area", nose.wetted_area(), area) < REL
    assert nose.radius_at(L) == pytest.approx(R, abs=1e-12)


def test_von_karman_area_against_quadrature_in_theta():
    # x = L/2 (1 - cos t), y = R/sqrt(pi) sqrt(t - sin 2t / 2): both smooth in t
    def integrand(t):
        g = t - math.sin(2 * t) / 2
        y = R / math.sqrt(math.pi) * math.sqrt(g)
        dy = R / math.sqrt(math.pi) * (1 - math.cos(2 * t)) / (2 * math.sqrt(g))
        dx = L / 2 * math.sin(t)
        return 2 * math.pi * y * math.hypot(dx, dy)
    area = quad(integrand, 1e-12, math.pi, epsrel=1e-12)[0]
    nose = NoseCone(shape="von_karman", length=L, radius=R)
    assert _report("von Karman area", nose.wetted_area(), area) < REL


def test_secant_ogive_reduces_to_tangent_and_ends_at_radius():
    rho_t = (R * R + L * L) / (2 * R)
    sec = NoseCone(shape="secant_ogive", ogive_radius=rho_t, length=L, radius=R)
    tan = NoseCone(shape="tangent_ogive", length=L, radius=R)
    x = np.linspace(0, L, 50)
    assert np.allclose(sec.radius_at(x), tan.radius_at(x), atol=1e-12)
    big = NoseCone(shape="secant_ogive", ogive_radius=3 * rho_t, length=L, radius=R)
    assert big.radius_at(0.0) == pytest.approx(0.0, abs=1e-12)
    assert big.radius_at(L) == pytest.approx(R, abs=1e-12)
    # a larger arc radius lies between the tangent ogive and the cone
    xm = np.array([L / 2])
    assert R / 2 < big.radius_at(xm)[0] < tan.radius_at(xm)[0]
    with pytest.raises(InputError, match="ogive_radius"):
        NoseCone(shape="secant_ogive", length=L, radius=R)


def test_conical_transition_frustum_and_boattail_direction():
    r1, r2, h = 0.0635, 0.0435, 0.06
    bt = Transition(x=2.0, length=h, fore_radius=r1, aft_radius=r2)
    assert _report("frustum volume", bt.volume(),
                   math.pi * h / 3 * (r1 * r1 + r1 * r2 + r2 * r2)) < 1e-9
    assert _report("frustum area", bt.wetted_area(),
                   math.pi * (r1 + r2) * math.hypot(h, r1 - r2)) < 1e-9
    og = Transition(x=0.0, length=0.1, fore_radius=0.05, aft_radius=0.03, shape="ogive")
    x, r = og.profile(200)
    assert r[0] == pytest.approx(0.05) and r[-1] == pytest.approx(0.03)
    assert np.all(np.diff(r) <= 1e-15)                      # monotone boattail
    assert og.fineness() == pytest.approx(0.1 / 0.1)


def test_body_tube_geometry():
    tube = BodyTube(x=0.5, length=1.2, radius=0.05)
    assert tube.volume() == pytest.approx(math.pi * 0.05 ** 2 * 1.2, rel=1e-12)
    assert tube.wetted_area() == pytest.approx(2 * math.pi * 0.05 * 1.2, rel=1e-12)
    assert tube.planform_area() == pytest.approx(0.1 * 1.2, rel=1e-12)
    assert tube.radius_at(np.array([0.4, 0.5, 1.0, 1.7, 1.8])).tolist() == [0, 0.05, 0.05, 0.05, 0]


@pytest.mark.parametrize("kwargs, field", [
    (dict(shape="conical", length=-1.0, radius=R), "length"),
    (dict(shape="conical", length=L, radius=0.0), "radius"),
    (dict(shape="bullet", length=L, radius=R), "shape"),
    (dict(shape="power", shape_parameter=1.5, length=L, radius=R), "shape_parameter"),
    (dict(shape="conical", length=L, radius=R, density=1000.0), "thickness"),
    (dict(shape="conical", length=L, radius=R, thickness=0.1, density=1.0), "thickness"),
    (dict(shape="conical", length="long", radius=R), "length"),
])
def test_bad_nose_arguments_name_the_field(kwargs, field):
    with pytest.raises(InputError) as err:
        NoseCone(**kwargs)
    assert err.value.field == field


def test_transition_equal_radii_rejected():
    with pytest.raises(InputError) as err:
        Transition(length=0.1, fore_radius=0.05, aft_radius=0.05)
    assert err.value.field == "aft_radius"


def test_tangent_ogive_matches_the_panair_reference_mesh():
    """Profile vs the independently generated PANAIR mesh of ../shared/reference/panair."""
    from pathlib import Path
    data = Path(__file__).resolve().parents[1] / "data" / "rocket" / "panair_ogive_meridian.csv"
    x, r = np.loadtxt(data, delimiter=",", comments="#", skiprows=3, unpack=True)
    nose = NoseCone(shape="tangent_ogive", length=3.0, radius=0.5)
    err = float(np.max(np.abs(nose.radius_at(x) - r)))
    print(f"tangent ogive vs PANAIR mesh: max |dr| = {err:.2e} m over {len(x)} stations "
          f"(tol 1e-6 m; file has 8 digits)")
    assert len(x) == 25 and err < 1e-6


def test_tangent_ogive_radius_never_negative():
    """OpenRocket's 'Chute release' nose (L = 0.24765 m, R = 0.03175 m): the closed-form
    tangent ogive gave -1.1e-16 m at the tip by rounding, which the panel mesh refused
    ('body ... r >= 0'); the tip is 0 and every radius >= 0 (exact: r(0) = 0)."""
    from ironbark_opt.rocket.shapes import shape_radius
    for length, radius in ((0.24765, 0.03175), (0.3, 0.05), (0.1, 0.0127)):
        r = shape_radius("tangent_ogive", None, np.linspace(0.0, length, 2001), length, radius)
        assert r[0] == 0.0 and np.all(r >= 0.0)
        assert r[-1] == pytest.approx(radius, rel=1e-12)
