"""Launch-guide drag (ironbark_opt.aero.protuberance) against hand calculations, the
.ork buttons parsed into the model, the TOML fields and their errors."""
import math
import shutil
import warnings
from pathlib import Path

import casadi as ca
import numpy as np
import pytest
from scipy.integrate import quad

from ironbark_opt.aero.friction import FrictionComponent, FrictionDrag
from ironbark_opt.aero.protuberance import (GP_CD, GP_MACH, PIN_CD, LaunchLugDrag, RailButtonDrag,
                                            boundary_layer_thickness, churchill_friction_factor,
                                            cylinder_cd)
from ironbark_opt.errors import InputError
from ironbark_opt.rocket import RailButtons, load_rocket_toml

ROOT = Path(__file__).resolve().parents[2]
CALISTO = ROOT / "examples" / "calisto" / "calisto.toml"
FT1 = ROOT / "tests" / "data" / "telemetry" / "nustars-2026-ft1-telemega.ork"
SREF = math.pi * 0.05 ** 2


def test_cylinder_cd_is_the_figure_linear_between_points_and_symbolic_alike():
    """At Gowen & Perkins' points the curve is their value; between, the chord; held outside."""
    for mach, cd in zip(GP_MACH, GP_CD):
        assert float(cylinder_cd(mach)) == pytest.approx(cd, abs=1e-12)
    assert float(cylinder_cd(0.85)) == pytest.approx(1.60 + (2.10 - 1.60) * 0.15 / 0.3, abs=1e-12)
    assert float(cylinder_cd(5.0)) == pytest.approx(1.33, abs=1e-12)
    m = ca.SX.sym("m")
    f = ca.Function("f", [m], [cylinder_cd(m)])
    for x in (0.05, 0.45, 0.99, 1.3, 2.4, 4.0):
        assert float(f(x)) == pytest.approx(float(cylinder_cd(x)), rel=1e-14)


def test_button_outside_the_boundary_layer():
    """Hand calculation: x = 0.5 m, Re = 1e7 /m -> Re_x = 5e6, delta = 0.37 * 0.5 / 5e6^0.2
    = 8.4604 mm; a plain 10 mm x 20 mm cylinder (h > delta) sees
    int q/q dy = h - (2/9) delta (1/7-power layer below delta, free stream above)."""
    delta = 0.37 * 0.5 / (5e6 ** 0.2)
    assert delta == pytest.approx(8.4604e-3, rel=1e-4)
    assert float(boundary_layer_thickness(0.5, 1e7)) == pytest.approx(delta, rel=1e-12)
    d, h = 0.010, 0.020
    b = RailButtonDrag((0.5,), d, d, h)
    for mach in (0.3, 0.8, 1.0, 1.6):
        ratio = 1.0 - 2.0 * delta / (9.0 * h)                  # q_mean / q
        m_loc = mach * math.sqrt(ratio)
        cd = PIN_CD / 1.20 * float(np.interp(m_loc, GP_MACH, GP_CD))
        expected = cd * d * h * ratio / SREF
        assert float(b.CA(mach, 1e7, SREF)) == pytest.approx(expected, rel=1e-12), mach
    # delta -> 0 (Re_x huge): the pin's free-stream coefficient on the frontal area
    thin = RailButtonDrag((1e-4,), d, d, h)
    assert float(thin.CA(1.0, 1e9, SREF)) == pytest.approx(0.80 / 1.20 * 2.10 * d * h / SREF, rel=2e-3)


def test_button_inside_the_boundary_layer_against_quadrature():
    """A button lower than delta: the analytic 1/7-power integral of q over its frontal
    width (base and flange at the outer diameter, the notch at the inner one) against
    numerical quadrature of (y/delta)^(2/7) w(y)."""
    od, idia, h, base, flange = 0.0097, 0.008, 0.0097, 0.002, 0.002
    b = RailButtonDrag((1.5,), od, idia, h, base, flange)
    re = 2e7
    delta = 0.37 * 1.5 / (re * 1.5) ** 0.2
    assert h < delta

    def w(y):
        return idia if base < y < h - flange else od
    pts = [base, h - flange]
    integral = quad(lambda y: w(y) * (y / delta) ** (2.0 / 7.0), 0.0, h, points=pts, epsabs=1e-14)[0]
    assert float(b.q_weighted_area(delta)) == pytest.approx(integral, rel=1e-8)
    area = od * h - (od - idia) * (h - base - flange)
    assert b.frontal_area() == pytest.approx(area, rel=1e-14)
    mach = 0.8
    m_loc = mach * math.sqrt(integral / area)
    expected = PIN_CD / 1.20 * float(np.interp(m_loc, GP_MACH, GP_CD)) * integral / SREF
    assert float(b.CA(mach, re, SREF)) == pytest.approx(expected, rel=1e-7)
    # symbolic = numeric
    M, R = ca.SX.sym("M"), ca.SX.sym("R")
    f = ca.Function("f", [M, R], [b.CA(M, R, SREF)])
    assert float(f(mach, re)) == pytest.approx(float(b.CA(mach, re, SREF)), rel=1e-13)


def _colebrook(re, rel):
    """Colebrook-White by fixed-point iteration (independent of Churchill's fit)."""
    f = 0.02
    for _ in range(200):
        f = (-2.0 * math.log10(rel / 3.7 + 2.51 / (re * math.sqrt(f)))) ** -2
    return f


def test_churchill_friction_factor_against_poiseuille_and_colebrook():
    for re in (100.0, 500.0, 1500.0):
        assert float(churchill_friction_factor(re, 0.0)) == pytest.approx(64.0 / re, rel=0.01)
    for re, rel in ((1e4, 0.0), (1e5, 0.0), (1e5, 0.01), (1e6, 0.001)):
        assert float(churchill_friction_factor(re, rel)) == pytest.approx(_colebrook(re, rel), rel=0.03)


def test_launch_lug_tube():
    """Outside the boundary layer (station 0.1 mm, Re 1e9 /m: delta 0.5 um): front annulus
    0.85 q_stag/q + base drag (0.12 + 0.13 M^2 subsonic), bore f (l/d) on pi r_i^2
    (Colebrook), outer flat-plate friction; hand calculation at Mach 0.3.  Inside it
    (station 0.3 m, Re 2e6 /m): all of it times the 1/7-power mean q over the height 2 r_o."""
    from ironbark_opt.aero.friction_flatplate import cf_flat_plate
    ro, ri, length, k = 0.0035, 0.0025, 0.035, 60e-6
    mach, re = 0.3, 1e9
    lug = LaunchLugDrag(1e-4, length, ro, ri, roughness=k)
    annulus = math.pi * (ro ** 2 - ri ** 2)
    q = 1 + 0.09 / 4 + 0.0081 / 40
    f = _colebrook(re * 2 * ri, k / (2 * ri))
    cf = float(cf_flat_plate(mach, re * length, length, k))
    free = ((0.85 * q + 0.12 + 0.13 * 0.09) * annulus + f * (length / (2 * ri)) * math.pi * ri ** 2
            + cf * 2 * math.pi * ro * length) / SREF
    assert float(lug.CA(mach, re, SREF)) == pytest.approx(free, rel=0.01)
    deep = LaunchLugDrag(0.3, length, ro, ri, roughness=k)
    delta = 0.37 * 0.3 / (2e6 * 0.3) ** 0.2
    ratio = 7.0 / 9.0 * (2 * ro / delta) ** (2.0 / 7.0)
    assert float(deep.q_ratio(2e6)) == pytest.approx(ratio, rel=1e-12)
    speed = math.sqrt(ratio)                                        # local Mach, Re inside
    ml, rl = mach * speed, 2e6 * speed
    ql = 1 + ml ** 2 / 4 + ml ** 4 / 40
    inside = ratio * ((0.85 * ql + 0.12 + 0.13 * ml ** 2) * annulus
                      + _colebrook(rl * 2 * ri, k / (2 * ri)) * (length / (2 * ri)) * math.pi * ri ** 2
                      + float(cf_flat_plate(ml, rl * length, length, k)) * 2 * math.pi * ro * length) / SREF
    assert float(deep.CA(mach, 2e6, SREF)) == pytest.approx(inside, rel=0.01)
    M, R = ca.SX.sym("M"), ca.SX.sym("R")
    fn = ca.Function("f", [M, R], [deep.CA(M, R, SREF)])
    assert float(fn(mach, 2e6)) == pytest.approx(float(deep.CA(mach, 2e6, SREF)), rel=1e-12)


def test_friction_table_carries_the_guides():
    """FrictionDrag(protuberances=...) adds the guides to its sum; the tabulated CA
    matches the formulas (the button curve's kinks smoothed by the cubic spline)."""
    comps = [FrictionComponent.body("body", 2.5, 0.1)]
    b = RailButtonDrag((1.2, 1.8), 0.0097, 0.008, 0.0097, 0.002, 0.002)
    plain, guided = FrictionDrag(comps, SREF), FrictionDrag(comps, SREF, protuberances=[b])
    worst = 0.0
    for mach in np.linspace(0.05, 3.0, 60):
        for re in (3e6, 1e7, 3e7):
            exact = float(guided.CA_exact(mach, re)) - float(plain.CA_exact(mach, re))
            assert exact == pytest.approx(float(b.CA(mach, re, SREF)), rel=1e-12)
            tab = float(guided.CA(mach, re)) - float(plain.CA(mach, re))
            worst = max(worst, abs(tab / exact - 1))
    print(f"guides through the friction table: worst {100 * worst:.2f} % of their CA")
    assert worst < 0.02


def test_ork_buttons_parsed_into_the_model():
    """NUSTARS FT1: two buttons in one component (the rail guides) and a third in another;
    the file's size: outer 0.49 in, inner 0.29 in, height 0.56 in, base and flange 3/16 in."""
    from ironbark_opt.aero.model import guide_drag
    from ironbark_opt.openrocket import read_ork
    from ironbark_opt.openrocket.build import geometry
    rk = geometry(read_ork(FT1))
    rb = next(c for c in rk.components if isinstance(c, RailButtons))
    assert (rb.outer_diameter, rb.inner_diameter, rb.height) == pytest.approx((0.012446, 0.007366, 0.014224))
    assert (rb.base_height, rb.flange_height) == pytest.approx((0.0047625, 0.0047625))
    assert rb.x_aft - rb.x_fore == pytest.approx(0.2286)
    assert len(rb.x_other) == 1
    drags, assumed = guide_drag(rk)
    assert assumed == () and len(drags[0].x) == 3
    print("FT1 buttons CA at Mach 0.3/0.6/0.9/1.2, Re 1.8e7 /m:",
          [round(float(drags[0].CA(mc, 1.8e7, rk.reference_area())), 5) for mc in (0.3, 0.6, 0.9, 1.2)])


def _calisto(tmp_path, extra: str):
    for name in ("Cesaroni_M1670.eng", "powerOffDragCurve.csv", "powerOnDragCurve.csv"):
        shutil.copy(CALISTO.parent / name, tmp_path / name)
    text = CALISTO.read_text().replace("x_aft = 1.8962", "x_aft = 1.8962\n" + extra, 1)
    p = tmp_path / "calisto.toml"
    p.write_text(text)
    return p


@pytest.mark.parametrize("extra, field", [
    ("outer_diameter = -0.01\nheight = 0.01", "outer_diameter"),
    ("outer_diameter = 0.01", "height"),
    ("outer_diameter = 0.01\nheight = 0.01\ninner_diameter = 0.02", "inner_diameter"),
    ("outer_diameter = 0.01\nheight = 0.01\nbase_height = 0.006\nflange_height = 0.006", "flange_height"),
    ("inner_diameter = 0.008", "outer_diameter"),
    ("x_other = 1.5", "x_other"),
    ("x_other = [-1.0]", "x_other"),
    ('outer_diameter = "big"\nheight = 0.01', "outer_diameter"),
])
def test_bad_button_values_rejected(tmp_path, extra, field):
    with pytest.raises(InputError) as err:
        load_rocket_toml(_calisto(tmp_path, extra))
    print(err.value)
    assert field in str(err.value.field)


def test_button_fields_round_trip_and_assumed_size_warns(tmp_path):
    from ironbark_opt.aero.model import build_aero_model
    from ironbark_opt.aero.empirical_drag import pressure_drag_table
    from ironbark_opt.rocket import dump_rocket_toml
    f1 = load_rocket_toml(_calisto(tmp_path, "outer_diameter = 0.0125\nheight = 0.0142\ninner_diameter = 0.0074\n"
                                             "base_height = 0.0048\nflange_height = 0.0048\nx_other = [1.5]"))
    f2 = load_rocket_toml(dump_rocket_toml(f1, tmp_path / "copy.toml"))
    assert f2.rocket.components == f1.rocket.components
    rb = next(c for c in f2.rocket.components if isinstance(c, RailButtons))
    assert rb.x_other == (1.5,) and rb.outer_diameter == 0.0125
    table = pressure_drag_table(f2.rocket)            # friction not included: guides added
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        model = build_aero_model(f2.rocket, table=table)
    assert len(model.friction.protuberances) == 1
    bare = load_rocket_toml(CALISTO).rocket                # no size: OpenRocket's default, said so
    with pytest.warns(UserWarning, match="default button"):
        model = build_aero_model(bare, table=pressure_drag_table(bare))
    assert model.friction.protuberances[0].outer_diameter == 0.0097
    assert build_aero_model(bare, table=pressure_drag_table(bare), guides=False).friction.protuberances == ()


def test_ork_buttons_round_trip_through_the_toml_writer(tmp_path):
    """FT1's buttons (own size, a third button) written into Calisto's file and read back."""
    import dataclasses

    from ironbark_opt.openrocket import read_ork
    from ironbark_opt.openrocket.build import geometry
    from ironbark_opt.rocket import Rocket, dump_rocket_toml
    rb = next(c for c in geometry(read_ork(FT1)).components if isinstance(c, RailButtons))
    # moved 1 m forward onto Calisto's 2.53 m body (FT1's aft button is at 2.66 m)
    rb = dataclasses.replace(rb, x_fore=rb.x_fore - 1.0, x_aft=rb.x_aft - 1.0,
                             x_other=tuple(x - 1.0 for x in rb.x_other))
    f1 = load_rocket_toml(_calisto(tmp_path, ""))
    r1 = f1.rocket
    comps = [c for c in r1.components if not isinstance(c, RailButtons)] + [rb]
    f1 = dataclasses.replace(f1, rocket=Rocket(r1.name, comps, mass_override=r1.mass_override))
    f2 = load_rocket_toml(dump_rocket_toml(f1, tmp_path / "copy.toml"))
    assert next(c for c in f2.rocket.components if isinstance(c, RailButtons)) == rb
