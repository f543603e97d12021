"""Fin-set roll angle (TOML roll_deg, the .ork fin rotation) in the panel mesh, and
fin lift-curve / airfoil-polar files in the Barrowman fin slope, each against an
analytic or independent number."""
import math
from dataclasses import replace
import warnings
from pathlib import Path

import numpy as np
import pytest

from ironbark_opt.aero import barrowman
from ironbark_opt.errors import InputError
from ironbark_opt.rocket import BodyTube, NoseCone, Rocket, TrapezoidalFins
from ironbark_opt.rocket.fin_files import read_airfoil_polar, read_lift_curve, section_slope

DATA = Path(__file__).parents[1] / "data"


def _rocket(**fin_kw):
    return Rocket("t", [NoseCone(shape="conical", length=0.3, radius=0.05), BodyTube(x=0.3, length=1.0, radius=0.05),
                        TrapezoidalFins(x=1.1, thickness=0.004, root_chord=0.2, tip_chord=0.1, span=0.1,
                                        sweep_length=0.05, **fin_kw)])


def _fin_tip_angles(rocket, fixed_roll=False):
    """Angles [deg] of the meshed fins' tips, from +y toward +z (FinSet.roll convention)."""
    from panair.geometry_adapter import from_rocket
    from panair.mesh import mesh_rocket
    out = []
    for net in mesh_rocket(from_rocket(rocket, fixed_roll=fixed_roll)):
        if net.name.startswith("fin") and net.name[3:].isdigit():
            p = net.points.reshape(-1, 3)
            tip = p[np.argmax(np.hypot(p[:, 1], p[:, 2]))]
            out.append(math.degrees(math.atan2(tip[2], tip[1])) % 360.0)
    return sorted(round(a, 3) for a in out)


@pytest.mark.parametrize("count, roll_deg, expected", [
    (4, None, [45.0, 135.0, 225.0, 315.0]),       # default: no fin in the pitch plane
    # '+' layout of 4 fins: the polar table is roll-independent for >= 3 fins, so an even
    # count is meshed as a half model with no fin in the x-z plane
    (4, 0.0, [45.0, 135.0, 225.0, 315.0]),
    # one or two fins: lift depends on roll, the polar table is flown at every roll, so
    # they are meshed at 45 deg to the pitch plane (sum sin^2 = N/2, Barrowman's roll
    # average) whatever their own roll (was: across / in the pitch plane, twice / none
    # of that lift)
    (2, None, [45.0, 225.0]),
    (2, 90.0, [45.0, 225.0]),
    (1, 0.0, [45.0]),
    (3, 30.0, [30.0, 150.0, 270.0]),
])
def test_roll_angle_places_the_meshed_fins(count, roll_deg, expected):
    roll = None if roll_deg is None else math.radians(roll_deg)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        got = _fin_tip_angles(_rocket(count=count, roll=roll))
    said = [str(w.message) for w in caught if "roll average" in str(w.message)]
    assert len(said) == (1 if count <= 2 else 0) and all("fin set" in m for m in said)
    print(count, roll_deg, got)
    assert got == pytest.approx(expected, abs=0.01)


@pytest.mark.parametrize("count, roll_deg, expected", [
    (2, None, [0.0, 180.0]),                      # default: across the pitch plane
    (2, 90.0, [90.0, 270.0]),                     # in the pitch plane
])
def test_fixed_roll_keeps_one_or_two_fins_at_their_roll(count, roll_deg, expected):
    """A model held at one roll (Allen's tunnel fin-body): the fins where the file puts them."""
    roll = None if roll_deg is None else math.radians(roll_deg)
    assert _fin_tip_angles(_rocket(count=count, roll=roll), fixed_roll=True) == pytest.approx(expected, abs=0.01)


def test_toml_roll_and_ork_rotation_are_read(tmp_path):
    from ironbark_opt.openrocket import read_ork
    from ironbark_opt.openrocket.build import geometry
    from ironbark_opt.openrocket.parallel import booster_rocket
    doc = read_ork(DATA / "ork" / "Parallel booster staging.ork")
    core = geometry(doc).fin_sets()[0]
    pod = booster_rocket(doc, doc.rocket.pods[0]).fin_sets()
    print(math.degrees(core.roll), [math.degrees(f.roll) for f in pod])
    assert math.degrees(core.roll) == pytest.approx(45.0)
    assert sorted(math.degrees(f.roll) for f in pod) == pytest.approx([-45.0, 45.0])
    from ironbark_opt.rocket.toml_io import loads_rocket_toml
    calisto = Path(__file__).parents[2] / "examples" / "calisto" / "calisto.toml"
    text = calisto.read_text().replace('type = "trapezoidal_fins"', 'type = "trapezoidal_fins"\nroll_deg = 10', 1)
    fins = loads_rocket_toml(text, calisto).rocket.fin_sets()[0]
    assert fins.roll == pytest.approx(math.radians(10.0))


def _diederich_rocketpy(a0, planform, mach, aref):
    """RocketPy's airfoil-fin slope, written from its formulation (independent of
    barrowman.single_fin_cn_alpha): clalpha2D = a0/beta, AR = 2 s^2/A_f,
    FD = 2 pi AR/(clalpha2D cos Gc), CNa1 = clalpha2D FD (A_f/A_ref) cos Gc / (2 + FD sqrt(1 + (2/FD)^2))."""
    beta = math.sqrt(1 - mach ** 2)
    cl2d = a0 / beta
    ar = 2 * planform.span ** 2 / planform.area
    fd = 2 * math.pi * ar / (cl2d * planform.cos_midchord_sweep)
    return cl2d * fd * (planform.area / aref) * planform.cos_midchord_sweep / (2 + fd * math.sqrt(1 + (2 / fd) ** 2))


def test_airfoil_polar_slope_replaces_two_pi_as_rocketpy(tmp_path):
    # a polar with CL = 0.9 * 2 pi * alpha in its linear range, stalling beyond 10 deg
    alpha = np.arange(-20.0, 20.5, 1.0)
    cl = 0.9 * 2 * np.pi * np.radians(np.clip(alpha, -10, 10))
    f = tmp_path / "polar.csv"
    f.write_text("alpha_deg,cl\n" + "\n".join(f"{a},{c}" for a, c in zip(alpha, cl)))
    a0 = read_airfoil_polar(f)
    assert a0 == pytest.approx(0.9 * 2 * np.pi, rel=1e-12)
    plan = barrowman.trapezoid_planform(0.2, 0.1, 0.1, 0.05)
    aref = math.pi * 0.05 ** 2
    c = section_slope(("polar", a0))
    for mach in (0.0, 0.3, 0.6):
        ours = barrowman.single_fin_cn_alpha(plan, mach, aref, c)
        ref = _diederich_rocketpy(a0, plan, mach, aref)
        thin = barrowman.single_fin_cn_alpha(plan, mach, aref)
        print(f"M {mach}: polar {ours:.5f}, RocketPy's formula {ref:.5f}, thin airfoil {thin:.5f}")
        assert ours == pytest.approx(ref, rel=1e-9)
        assert ours < thin                                        # a flatter section lifts less
        assert barrowman.single_fin_cn_alpha(plan, mach, aref, section_slope(("polar", 2 * np.pi))) == \
            pytest.approx(thin, rel=1e-9)                         # 2 pi: eq. 3.40 itself


def test_lift_curve_file_and_its_use_in_the_model(tmp_path):
    mach = np.linspace(0.0, 0.8, 9)
    f = tmp_path / "lift.csv"
    f.write_text("mach,cl_alpha\n" + "\n".join(f"{m},{2 * np.pi / np.sqrt(1 - m * m)}" for m in mach))
    curve = read_lift_curve(f)
    plan = barrowman.trapezoid_planform(0.2, 0.1, 0.1, 0.05)
    aref = math.pi * 0.05 ** 2
    for m in (0.1, 0.45, 0.7):             # the thin airfoil's own 2 pi / beta: eq. 3.40 (interpolation error)
        assert barrowman.single_fin_cn_alpha(plan, m, aref, section_slope(("curve", curve))) == pytest.approx(
            barrowman.single_fin_cn_alpha(plan, m, aref), rel=2e-3)
    # in a flight model: a section of 80 % slope lowers CN-alpha (fins) and moves the CP forward
    from ironbark_opt.aero.model import lift_geometry
    base = _rocket(count=4)
    half = _rocket(count=4, section_lift=("curve", (tuple(mach), tuple(0.8 * 2 * np.pi / np.sqrt(1 - mach ** 2)))))
    lg0, lg1 = lift_geometry(base), lift_geometry(half)
    c0 = sum(c.cn_alpha for c in lg0.components(0.3, base.reference_area()))
    c1 = sum(c.cn_alpha for c in lg1.components(0.3, base.reference_area()))
    f0 = lg0.components(0.3, base.reference_area())[-1].cn_alpha
    f1 = lg1.components(0.3, base.reference_area())[-1].cn_alpha
    k = plan.span ** 2 / (plan.area * plan.cos_midchord_sweep)
    beta = math.sqrt(1 - 0.09)
    expected = (1 + math.sqrt(1 + (beta * k) ** 2)) / (1 + math.sqrt(1 + (beta * k / 0.8) ** 2))
    print(f"fins CN-alpha {f0:.4f} -> {f1:.4f} (ratio {f1 / f0:.5f}, analytic {expected:.5f}); total {c0:.3f} -> {c1:.3f}")
    assert f1 / f0 == pytest.approx(expected, rel=2e-3)


@pytest.mark.parametrize("text, message", [
    ("mach,cl\n0,1\n1,2\n", "expected columns mach and cl_alpha"),
    ("mach,cl_alpha\n0.5,6\n0.2,6\n", "increase strictly"),
    ("mach,cl_alpha\n0,6\n0.5,-1\n", "must be > 0"),
    ("mach,cl_alpha\n0,6\n0.5,x\n", "row 3"),
])
def test_bad_lift_curve_files(tmp_path, text, message):
    f = tmp_path / "bad.csv"
    f.write_text(text)
    with pytest.raises(InputError, match=message):
        read_lift_curve(f)


def test_toml_lift_curve_key(tmp_path):
    from ironbark_opt.rocket.toml_io import loads_rocket_toml
    calisto = Path(__file__).parents[2] / "examples" / "calisto" / "calisto.toml"
    lift = tmp_path / "lift.csv"
    lift.write_text("mach,cl_alpha_per_deg\n0,0.1\n0.8,0.12\n")
    text = calisto.read_text().replace('type = "trapezoidal_fins"',
                                       f'type = "trapezoidal_fins"\nlift_curve = "{lift.as_posix()}"', 1)
    fins = loads_rocket_toml(text, calisto).rocket.fin_sets()[0]
    assert fins.section_lift[0] == "curve" and fins.section_lift[1][1][0] == pytest.approx(math.degrees(0.1))
    both = text.replace("lift_curve", f'airfoil_polar = "{lift.as_posix()}"\nlift_curve', 1)
    with pytest.raises(InputError, match="not both"):
        loads_rocket_toml(both, calisto)


def test_rail_button_angle_adds_its_off_axis_inertia():
    """Two 10 g buttons 0.5 m apart, standoff 10 mm on a 50 mm body, at 30 deg from +y:
    r = 0.055 m, (y, z) = r (cos 30, sin 30); about the axis point between them
    I_xx = 2 m r^2, I_yy = 2 m (0.25^2 + z^2), I_zz = 2 m (0.25^2 + y^2), I_yz = -2 m y z."""
    from ironbark_opt.rocket import RailButtons
    m, r, a = 0.01, 0.055, math.radians(30.0)
    y, z = r * math.cos(a), r * math.sin(a)
    rocket = Rocket("t", [NoseCone(shape="conical", length=0.3, radius=0.05), BodyTube(x=0.3, length=1.0, radius=0.05),
                          RailButtons(x_fore=0.5, x_aft=1.0, height=0.01, mass_each=m, angle=a)])
    (name, mp), = [(n, p) for n, p in rocket.component_mass_properties() if n == "rail buttons"]
    expected = np.array([[2 * m * r * r, 0, 0], [0, 2 * m * (0.0625 + z * z), -2 * m * y * z],
                         [0, -2 * m * y * z, 2 * m * (0.0625 + y * y)]])
    print(mp.inertia, expected)
    assert mp.mass == pytest.approx(0.02) and mp.cg_x == pytest.approx(0.75)
    np.testing.assert_allclose(mp.inertia, expected, rtol=1e-12, atol=1e-15)
    on_axis = RailButtons(x_fore=0.5, x_aft=1.0, height=0.01, mass_each=m).mass_properties()
    assert on_axis.inertia[0, 0] == 0.0 and on_axis.inertia[1, 1] == pytest.approx(2 * m * 0.0625)
    from ironbark_opt.rocket.toml_io import loads_rocket_toml
    calisto = Path(__file__).parents[2] / "examples" / "calisto" / "calisto.toml"
    text = calisto.read_text().replace('type = "rail_buttons"', 'type = "rail_buttons"\nangle_deg = 30', 1)
    assert 'angle_deg = 30' in text
    buttons = [c for c in loads_rocket_toml(text, calisto).rocket.components if isinstance(c, RailButtons)]
    assert buttons[0].angle == pytest.approx(a)


def _two_sets(roll_main_deg, roll_fwd_deg):
    """A rocket with its main 4-fin set and a second, smaller 4-fin set 1.2 root chords
    ahead (the case a feature fuzz found meshed in line whatever the file's rolls)."""
    return Rocket("t", [NoseCone(shape="conical", length=0.3, radius=0.05), BodyTube(x=0.3, length=1.0, radius=0.05),
                        TrapezoidalFins(x=1.1, thickness=0.004, root_chord=0.2, tip_chord=0.1, span=0.1,
                                        sweep_length=0.05, roll=math.radians(roll_main_deg), name="main"),
                        TrapezoidalFins(x=0.86, thickness=0.004, root_chord=0.16, tip_chord=0.08, span=0.08,
                                        sweep_length=0.04, roll=math.radians(roll_fwd_deg), name="fwd")])


def test_fin_sets_keep_their_relative_roll():
    """Two 4-fin sets the file rolls 45 deg apart are meshed 45 deg apart (the main set at
    45 deg, a half model impossible: meshed whole); the same rocket rolled as a whole
    (both +17 deg) gives the same mesh.  Reference for the numbers: a layout of 4-fold
    symmetry has an isotropic linear normal force, so the whole-model CN-alpha at any
    common roll equals the table's (bound 2 %).  And the relative roll matters: here the
    interdigitated sets have 5 % less CN-alpha than the same sets in line (21.31 / 22.54
    /rad; the in-line forward set's wake ends on the main fins, close behind it, which
    then act as one longer fin), on a fuzzed rocket with a wider gap 6.6 % more (13.21 /
    12.39 /rad); bound: more than 1 % apart."""
    from panair.geometry_adapter import from_rocket, is_symmetric
    from panair.mesh import MeshOptions, RocketGeometry, mesh_rocket
    from panair.solver import build_panels, make_solver
    inter, turned, inline = (from_rocket(_two_sets(*r)) for r in ((45, 0), (62, 17), (45, 45)))
    rolls = lambda g: [round(math.degrees(f.roll) % 360, 6) for f in g.fins]
    assert rolls(inter) == rolls(turned) == [45.0, 90.0]
    assert rolls(inline) == [45.0, 45.0] and is_symmetric(inline) and not is_symmetric(inter)
    opt = MeshOptions(n_theta=24, n_chord=8, n_span=5)

    def cn_alpha(g, extra_deg=0.0):
        g = RocketGeometry(g.body, tuple(replace(f, roll=f.roll + math.radians(extra_deg)) for f in g.fins))
        sym = is_symmetric(g)
        panels = build_panels(mesh_rocket(g, symmetric=sym, options=opt), symmetric=sym)
        return make_solver(panels, 0.3, sref=math.pi * 0.05**2, lref=0.1, xref=0.0).solve(
            np.radians([2.0]))[0].CN / math.radians(2.0)

    a, b, c = cn_alpha(inter), cn_alpha(inter, 17.0), cn_alpha(inline)
    print(f"CN-alpha interdigitated {a:.3f} /rad, rolled +17 deg {b:.3f}, in line {c:.3f}")
    assert b == pytest.approx(a, rel=0.02)
    assert abs(a / c - 1) > 0.01


def test_fin_sets_in_line_when_the_whole_model_is_too_big(monkeypatch):
    """Keeping the relative roll needs the whole-rocket model; over
    WHOLE_MODEL_MAX_PANELS panels (a fuzzed stack of four 4-fin sets: 13016, a worker
    killed at 14.7 GB) the even sets are meshed in line, a half model, with a warning
    that names them and the panel count.  Here the limit is lowered to this small rocket."""
    import panair.geometry_adapter as ga
    assert not ga.is_symmetric(ga.from_rocket(_two_sets(45, 0)))
    monkeypatch.setattr(ga, "WHOLE_MODEL_MAX_PANELS", 100)
    with pytest.warns(UserWarning, match=r"fin sets 'main', 'fwd' are meshed in line .* panels, over 100"):
        g = ga.from_rocket(_two_sets(45, 0))
    assert [round(math.degrees(f.roll), 6) for f in g.fins] == [45.0, 45.0] and ga.is_symmetric(g)
    with warnings.catch_warnings():
        warnings.simplefilter("error")                  # in line already: nothing to say
        ga.from_rocket(_two_sets(45, 45))


def test_one_fin_sets_at_their_roll_average_do_not_share_a_line():
    """Two one-fin sets side by side (OpenRocket's parallel booster: two fins 90 deg
    apart): each at a roll average angle (sum sin^2 = 1/2), but not both at 45 deg,
    which meshed one fin twice (a wake network refused)."""
    from panair.geometry_adapter import from_rocket
    rocket = _rocket(count=1, roll=0.0, name="a")
    rocket = Rocket("t", list(rocket.components) + [TrapezoidalFins(x=1.1, thickness=0.004, root_chord=0.2,
                                                              tip_chord=0.1, span=0.1, sweep_length=0.05,
                                                              count=1, roll=math.pi / 2, name="b")])
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        g = from_rocket(rocket)
    rolls = sorted(round(math.degrees(f.roll) % 360, 6) for f in g.fins)
    assert rolls == [45.0, 135.0]
    assert all(math.sin(f.roll) ** 2 == pytest.approx(0.5) for f in g.fins)
