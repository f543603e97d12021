"""Mass build-up of simple shapes against hand formulas."""
import math

import numpy as np
import pytest

from ironbark_opt.errors import InputError
from ironbark_opt.rocket import (BodyTube, InnerTube, LaunchLug, MassProperties, NoseCone, PointMass,
                                 RailButtons, Rocket, TrapezoidalFins, Transition)

RHO = 1850.0


def test_solid_cone_hand_formulas():
    L, R = 0.5, 0.1
    mp = NoseCone(shape="conical", length=L, radius=R, filled=True, density=RHO).mass_properties()
    m = RHO * math.pi * R * R * L / 3
    errs = [abs(mp.mass / m - 1), abs(mp.cg_x / (0.75 * L) - 1),
            abs(mp.I_axial / (0.3 * m * R * R) - 1),
            abs(mp.I_transverse / (3 / 20 * m * R * R + 3 / 80 * m * L * L) - 1)]
    print(f"solid cone rel. errors (m, cg, Ia, It): {['%.1e' % e for e in errs]} (tol 1e-6)")
    assert max(errs) < 1e-6


def test_tube_shell_hand_formulas():
    L, R, t, x0 = 1.2, 0.05, 0.002, 0.3
    mp = BodyTube(x=x0, length=L, radius=R, thickness=t, density=RHO).mass_properties()
    ri = R - t
    m = RHO * math.pi * (R * R - ri * ri) * L
    assert mp.mass == pytest.approx(m, rel=1e-12)
    assert mp.cg_x == pytest.approx(x0 + L / 2, rel=1e-12)
    assert mp.I_axial == pytest.approx(m * (R * R + ri * ri) / 2, rel=1e-12)
    assert mp.I_transverse == pytest.approx(m * ((R * R + ri * ri) / 4 + L * L / 12), rel=1e-9)
    assert mp.inertia[0, 1] == 0.0


def test_cone_shell_of_normal_thickness():
    # shell between r(x) and max(r(x) - a, 0), a = t sec(beta): by hand,
    # V = S t - pi a^2 L + pi a^3 L / (3 R)  (last term: the solid tip where r < a)
    L, R, t = 0.4, 0.05, 1e-3
    nose = NoseCone(shape="conical", length=L, radius=R, thickness=t, density=RHO)
    a = t * math.sqrt(1 + (R / L) ** 2)
    ref = RHO * (t * nose.wetted_area() - math.pi * a * a * L + math.pi * a ** 3 * L / (3 * R))
    mp = nose.mass_properties()
    err = abs(mp.mass / ref - 1)
    print(f"conical shell mass vs hand: rel. error {err:.2e} (tol 1e-5)")
    assert err < 1e-5
    # CG of a thin conical shell lies 2/3 of the way from the tip (to O(t/R))
    assert mp.cg_x == pytest.approx(2 * L / 3, rel=2 * t / R)


def test_component_mass_override_keeps_cg():
    tube = BodyTube(length=1.0, radius=0.05, thickness=0.002, density=RHO, mass=2.0)
    mp = tube.mass_properties()
    assert mp.mass == 2.0 and mp.cg_x == pytest.approx(0.5)
    assert mp.I_transverse == pytest.approx(2.0 * ((0.05 ** 2 + 0.048 ** 2) / 4 + 1 / 12))
    with pytest.raises(InputError, match="needs a material or density") as err:
        BodyTube(length=1.0, radius=0.05, mass=2.0)
    assert err.value.field == "mass"


def test_flat_rectangular_fins_hand_formulas():
    c, s, t, R, x0, n = 0.1, 0.08, 0.004, 0.05, 1.0, 4
    fins = TrapezoidalFins(count=n, x=x0, root_chord=c, tip_chord=c, span=s, sweep_length=0.0,
                           thickness=t, density=RHO)
    mp = fins.mass_properties(R)
    m1 = RHO * c * s * t
    i_ax = n * m1 * (R * R + R * s + s * s / 3)         # Int (R + y)^2 dm over a uniform strip
    assert mp.mass == pytest.approx(n * m1, rel=1e-12)
    assert mp.cg_x == pytest.approx(x0 + c / 2, rel=1e-12)
    assert mp.I_axial == pytest.approx(i_ax, rel=1e-5)
    assert mp.I_transverse == pytest.approx(n * m1 * c * c / 12 + i_ax / 2, rel=1e-5)


def test_fins_on_boattail_follow_the_surface():
    nose = NoseCone(shape="conical", length=0.3, radius=0.05)
    tube = BodyTube(x=0.3, length=0.6, radius=0.05)
    tail = Transition(x=0.9, length=0.1, fore_radius=0.05, aft_radius=0.03)
    kw = dict(count=3, x=0.9, root_chord=0.1, tip_chord=0.1, span=0.05, sweep_length=0.0,
              thickness=0.003, density=RHO)
    fins = TrapezoidalFins(**kw)
    rocket = Rocket("r", [nose, tube, tail, fins])
    on_tail = dict(rocket.component_mass_properties())["fins"]
    on_tube = fins.mass_properties(0.05)
    assert on_tail.mass == pytest.approx(on_tube.mass)
    # root radius drops linearly 0.05 -> 0.03: mean r = 0.04 + s/2
    m, s = on_tube.mass, 0.05
    i_ax = m * ((0.04 + s / 2) ** 2 + s * s / 12 + 0.02 ** 2 / 12)
    print(f"fins on boattail I_axial {on_tail.I_axial:.6e} vs hand {i_ax:.6e}")
    assert on_tail.I_axial == pytest.approx(i_ax, rel=1e-4)
    assert rocket.radius_at(0.95) == pytest.approx(0.04)


def test_rocket_build_up_combines_with_parallel_axis():
    L, R, Lt, t = 0.4, 0.05, 1.0, 0.002
    nose = NoseCone(shape="conical", length=L, radius=R, filled=True, density=RHO)
    tube = BodyTube(length=Lt, thickness=t, x=L, radius=R, density=RHO)
    pm = PointMass(name="avionics", mass=0.5, x=0.8, I_transverse=0.001)
    rocket = Rocket("test", [nose, tube, pm])
    m1 = RHO * math.pi * R * R * L / 3
    m2 = RHO * math.pi * (R * R - (R - t) ** 2) * Lt
    x1, x2 = 0.75 * L, L + Lt / 2
    m = m1 + m2 + 0.5
    cg = (m1 * x1 + m2 * x2 + 0.5 * 0.8) / m
    it = (3 / 20 * m1 * R * R + 3 / 80 * m1 * L * L + m1 * (x1 - cg) ** 2
          + m2 * ((R * R + (R - t) ** 2) / 4 + Lt * Lt / 12) + m2 * (x2 - cg) ** 2
          + 0.001 + 0.5 * (0.8 - cg) ** 2)
    mp = rocket.dry_mass_properties()
    print(f"rocket build-up: m {mp.mass:.6f}/{m:.6f} cg {mp.cg_x:.6f}/{cg:.6f} "
          f"It {mp.I_transverse:.6f}/{it:.6f} (rel tol 1e-6)")
    assert mp.mass == pytest.approx(m, rel=1e-6)
    assert mp.cg_x == pytest.approx(cg, rel=1e-6)
    assert mp.I_transverse == pytest.approx(it, rel=1e-6)
    override = MassProperties.axisymmetric(3.0, 0.7, 0.2, 0.01)
    assert rocket.with_mass_override(override).dry_mass_properties() is override


def test_hardware_masses():
    rb = RailButtons(x_fore=1.0, x_aft=1.6, mass_each=0.01)
    mp = rb.mass_properties()
    assert (mp.mass, mp.cg_x) == pytest.approx((0.02, 1.3))
    assert mp.I_transverse == pytest.approx(0.02 * 0.3 ** 2)
    lug = LaunchLug(x=1.0, length=0.1, outer_radius=0.005, inner_radius=0.004, density=2700.0)
    m = 2700 * math.pi * (0.005 ** 2 - 0.004 ** 2) * 0.1
    assert lug.mass_properties().mass == pytest.approx(m)
    assert lug.rail_guides == (1.0, pytest.approx(1.1))
    with pytest.raises(InputError) as err:
        RailButtons(x_fore=1.0, x_aft=0.5)
    assert err.value.field == "x_aft"


def test_massless_rocket_asks_for_density_or_override():
    rocket = Rocket("empty", [NoseCone(shape="conical", length=0.3, radius=0.05)])
    with pytest.raises(InputError, match="no mass"):
        rocket.dry_mass_properties()


def test_mass_properties_validation():
    with pytest.raises(InputError) as err:
        MassProperties(-1.0, 0.0, np.zeros((3, 3)))
    assert err.value.field == "mass"
    with pytest.raises(InputError, match="symmetric"):
        MassProperties(1.0, 0.0, [[1, 2, 0], [0, 1, 0], [0, 0, 1]])
    with pytest.raises(InputError, match="3x3"):
        MassProperties(1.0, 0.0, [1, 2, 3])
    assert MassProperties(1.0, 0.5, (2.0, 0.1)).I_axial == 0.1


def test_inner_tubes_and_bulkheads():
    ro, ri, L = 0.048, 0.046, 0.05
    tube = InnerTube(x=0.3, length=L, outer_radius=ro, inner_radius=ri, density=RHO)
    m = RHO * math.pi * (ro * ro - ri * ri) * L
    mp = tube.mass_properties()
    assert (mp.mass, mp.cg_x) == pytest.approx((m, 0.3 + L / 2))
    assert mp.I_axial == pytest.approx(m * (ro * ro + ri * ri) / 2)
    assert mp.I_transverse == pytest.approx(m * ((ro * ro + ri * ri) / 4 + L * L / 12))
    disc = InnerTube(x=1.0, length=0.006, outer_radius=ro, mass=0.05).mass_properties()
    assert disc.mass == 0.05 and disc.I_axial == pytest.approx(0.05 * ro * ro / 2)
    with pytest.raises(InputError) as err:
        InnerTube(x=0.0, length=0.01, outer_radius=0.02, inner_radius=0.03)
    assert err.value.field == "inner_radius"
