"""Rocket TOML: the Calisto example, a build-up file and error reporting."""
import math
import shutil
from pathlib import Path

import pytest

from ironbark_opt.errors import InputError
from ironbark_opt.rocket import (FreeformFins, LaunchLug, NoseCone, Transition,
                                 load_rocket_toml, loads_rocket_toml)
from ironbark_opt.rocket.mass import MassProperties, total_mass_properties

ROOT = Path(__file__).resolve().parents[2]
CALISTO = ROOT / "examples" / "calisto" / "calisto.toml"
DATA = ROOT / "tests" / "data" / "rocket"


def test_calisto_example_reproduces_the_reference():
    f = load_rocket_toml(CALISTO)
    r = f.rocket
    dry = r.dry_mass_properties()
    assert (dry.mass, dry.cg_x, dry.I_transverse, dry.I_axial) == (14.426, 1.278, 6.321, 0.034)
    assert dry.inertia[1, 1] == dry.inertia[2, 2] == 6.321
    nose, body, tail = r.body_components()
    assert isinstance(nose, NoseCone) and nose.shape == "haack" and nose.shape_parameter == 0.0
    assert (nose.length, nose.radius) == (0.55829, 0.0635)
    assert body.x == 0.55829 and body.x_end == pytest.approx(2.472656)
    assert isinstance(tail, Transition) and (tail.fore_radius, tail.aft_radius) == (0.0635, 0.0435)
    fins = r.fin_sets()[0]
    assert (fins.count, fins.root_chord, fins.tip_chord, fins.span, fins.sweep_length) == \
        (4, 0.120, 0.060, 0.110, 0.060)
    assert fins.x == 2.32756 and fins.cant == pytest.approx(math.radians(0.5))
    assert fins.x_end == pytest.approx(2.44756)
    assert r.rail_guides() == (1.1962, 1.8962)
    assert r.reference_radius() == 0.0635
    assert r.length() == pytest.approx(2.532656)
    m = f.motor
    assert m.file.name == "Cesaroni_M1670.eng" and m.file.is_file()
    assert m.designation == "M1670" and m.nozzle_x == 2.533
    assert m.overrides["dry_mass"] == 1.815 and m.overrides["dry_inertia"] == (0.125, 0.002)
    g = m.overrides["grains"]
    assert (g["count"], g["density"], g["outer_radius"], g["inner_radius"], g["height"],
            g["separation"]) == (5, 1815.0, 0.033, 0.015, 0.120, 0.005)
    # no nozzle exit area: the RocketPy reference has no ambient-pressure thrust correction
    assert "nozzle_exit_area" not in m.overrides
    assert f.aero.drag_power_off.name == "powerOffDragCurve.csv"
    assert f.aero.drag_power_on.is_file()
    L = f.launch
    assert (L.site_elevation, L.rail_length, L.wind_speed) == (1400.0, 5.2, 0.0)
    assert math.degrees(L.inclination) == pytest.approx(84.0)
    assert math.degrees(L.heading) == pytest.approx(133.0)
    assert math.degrees(L.latitude) == pytest.approx(32.990254)
    assert math.degrees(L.longitude) == pytest.approx(-106.974998)
    # launch mass = dry rocket + motor dry mass + propellant from the grains (by hand)
    prop = g["count"] * g["density"] * math.pi * (g["outer_radius"] ** 2
                                                  - g["inner_radius"] ** 2) * g["height"]
    m0 = m.overrides["dry_mass"] + prop
    total = total_mass_properties(dry, f.ballast.mass, 0.0, m0, m.motor_cg_x(0.35), 0.1, 0.002)
    print(f"Calisto launch mass {total[0]:.4f} kg vs README 19.197 kg")
    assert total[0] == pytest.approx(19.197, abs=1e-3)


def test_buildup_file():
    f = load_rocket_toml(DATA / "buildup.toml")
    r = f.rocket
    assert r.mass_override is None
    nose, tube, tail = r.body_components()
    assert tube.radius == 0.05 and tube.x == pytest.approx(0.30)   # stacked and inherited
    assert tail.fore_radius == 0.05 and tail.x == pytest.approx(1.30)
    assert nose.density == 1850.0 and tube.density == 1780.0
    fins = r.fin_sets()[0]
    assert isinstance(fins, FreeformFins) and fins.section.kind == "double_wedge"
    assert isinstance(r.components[-1], LaunchLug)
    assert dict(r.component_mass_properties())["bulkhead"].mass == 0.05
    dry = r.dry_mass_properties()
    parts = dict(r.component_mass_properties())
    assert dry.mass == pytest.approx(sum(p.mass for p in parts.values()))
    assert 0.3 < dry.cg_x < 1.35
    assert f.aero.surface_roughness == 20e-6
    assert f.launch.wind_from == pytest.approx(1.5 * math.pi)
    assert f.launch.inclination == pytest.approx(math.radians(85))   # default
    drogue, main = f.recovery
    assert drogue.deploy == "apogee" and drogue.cd_area == 0.5
    assert main.cd_area == pytest.approx(2.2 * math.pi * 0.36) and main.deploy == 300.0
    assert f.ballast.x == pytest.approx(0.175) and f.ballast.mass == 0.0
    assert r.rail_guides() == (0.8, pytest.approx(0.9))


def _write(tmp_path, text):
    shutil.copy(DATA / "Cesaroni_M1670.eng", tmp_path / "Cesaroni_M1670.eng")
    p = tmp_path / "rocket.toml"
    p.write_text(text)
    return p


def _base():
    return (DATA / "buildup.toml").read_text()


def _line_of(text, needle):
    return next(i for i, line in enumerate(text.splitlines(), 1) if needle in line)


def test_syntax_error_names_file_and_line(tmp_path):
    text = _base().replace('name = "airframe"', 'name = "airframe')
    p = _write(tmp_path, text)
    with pytest.raises(InputError) as err:
        load_rocket_toml(p)
    assert err.value.line == _line_of(text, 'name = "airframe')
    assert str(p) in str(err.value) and "TOML syntax error" in str(err.value)


def test_unknown_key_names_line_and_lists_accepted(tmp_path):
    text = _base().replace('name = "boattail"', 'name = "boattail"\nlenght = 0.05')
    p = _write(tmp_path, text)
    with pytest.raises(InputError) as err:
        load_rocket_toml(p)
    e = err.value
    assert e.field == "component[2].lenght" and e.line == _line_of(text, "lenght")
    assert "fore_radius" in e.message and "aft_radius" in e.message
    print(e)


@pytest.mark.parametrize("old, new, field, needle", [
    ("length = 1.0", "length = -1.0", "component[1].length", "length = -1.0"),
    ('material = "carbon fiber"', 'material = "unobtainium"', "component[1].material",
     "unobtainium"),
    ("count = 3", "count = 2.5", "component[3].count", "count = 2.5"),
    ('section = "hexagonal"', 'section = "wavy"', "component[3].section", "section = "),
    ("rail_length = 3.0", "rail_length = 0.0", "launch.rail_length", "rail_length"),
    ('file = "Cesaroni_M1670.eng"', 'file = "missing.eng"', "motor.file", "missing.eng"),
    ("deploy = 300.0", 'deploy = "never"', "recovery[1].deploy", "never"),
    ("mass_max = 1.0", "mass_max = 1.0\nmass = 2.0", "ballast.mass", "mass = 2.0"),
    ('finish = "smooth_paint"', 'finish = "glossy"', "aero.finish", "glossy"),
    ("x = 0.6", 'x = "middle"', "component[4].x", "middle"),
])
def test_bad_values_name_field_and_line(tmp_path, old, new, field, needle):
    text = _base().replace(old, new)
    assert text != _base()
    with pytest.raises(InputError) as err:
        load_rocket_toml(_write(tmp_path, text))
    assert err.value.field == field
    assert err.value.line == _line_of(text, needle)


def test_structural_errors(tmp_path):
    with pytest.raises(InputError, match="missing section \\[motor\\]"):
        loads_rocket_toml('[rocket]\nname = "x"\n[[component]]\ntype = "body_tube"\n'
                          'length = 1.0\nradius = 0.05\n', tmp_path / "r.toml")
    with pytest.raises(InputError, match="unknown key 'rockets'"):
        loads_rocket_toml("[rockets]\n", tmp_path / "r.toml")
    text = _base().replace('type = "point_mass"', 'type = "pointmass"')
    with pytest.raises(InputError, match="unknown component type") as err:
        load_rocket_toml(_write(tmp_path, text))
    assert err.value.line == _line_of(text, "pointmass")
    text = _base().replace("radius = 0.05\n", "", 1)
    with pytest.raises(InputError, match="missing required key 'radius'") as err:
        load_rocket_toml(_write(tmp_path, text))
    assert err.value.field == "component[0].radius" and err.value.line == 5   # its header
    with pytest.raises(InputError, match="cannot read"):
        load_rocket_toml(tmp_path / "nope.toml")
    # a gap in the body
    text = _base().replace('name = "boattail"', 'name = "boattail"\nx = 1.5')
    with pytest.raises(InputError, match="gap") as err:
        load_rocket_toml(_write(tmp_path, text))
    assert str(tmp_path) in str(err.value)
    assert err.value.field == "component[2].x" and err.value.line == _line_of(text, "x = 1.5")
    text = _base().replace("x_max = 0.25", "x_max = 2.5")
    with pytest.raises(InputError, match="aft of the rocket") as err:
        load_rocket_toml(_write(tmp_path, text))
    assert err.value.line == _line_of(text, "x_max = 2.5")


def test_wet_mass_override_needs_the_motor(tmp_path):
    text = CALISTO.read_text().replace("I_axial = 0.034 ", "I_axial = 0.034\nincludes_motor = true")
    text = text.replace("mass = 14.426", "mass = 19.197")
    for name in ("Cesaroni_M1670.eng", "powerOffDragCurve.csv", "powerOnDragCurve.csv"):
        shutil.copy(CALISTO.parent / name, tmp_path / name)
    p = tmp_path / "wet.toml"
    p.write_text(text)
    f = load_rocket_toml(p)
    assert f.rocket.mass_override is None and f.wet_mass_override.mass == 19.197
    with pytest.raises(InputError, match="pass the motor"):
        f.dry_rocket()

    class Motor:  # the Motor contract of docs/ARCHITECTURE.md, at t = 0
        def mass(self, t):
            return 4.771

        def cg(self, t):
            return 0.36

        def inertia(self, t):
            return 0.6, 0.005

    dry = f.dry_rocket(Motor()).dry_mass_properties()
    assert dry.mass == pytest.approx(19.197 - 4.771)
    wet_again = total_mass_properties(dry, 0.0, 0.0, 4.771, 2.533 - 0.36, 0.6, 0.005)
    assert wet_again[1] == pytest.approx(1.278) and wet_again[2] == pytest.approx(6.321)


def test_inertia_tensor_override(tmp_path):
    text = CALISTO.read_text().replace(
        "I_transverse = 6.321               # kg m^2 about the CG (Ixx = Iyy in RocketPy)\n"
        "I_axial = 0.034 ", "inertia = [[0.034, 0, 0], [0, 6.321, 0.01], [0, 0.01, 6.3]] ")
    for name in ("Cesaroni_M1670.eng", "powerOffDragCurve.csv", "powerOnDragCurve.csv"):
        shutil.copy(CALISTO.parent / name, tmp_path / name)
    p = tmp_path / "cad.toml"
    p.write_text(text)
    mp = load_rocket_toml(p).rocket.dry_mass_properties()
    assert isinstance(mp, MassProperties) and mp.inertia[1, 2] == 0.01
    p.write_text(text.replace("[0, 0.01, 6.3]", "[0, 0.02, 6.3]"))
    with pytest.raises(InputError, match="symmetric") as err:
        load_rocket_toml(p)
    assert err.value.field == "rocket.mass_override.inertia"


@pytest.mark.parametrize("source", [CALISTO, DATA / "buildup.toml"])
def test_round_trip_through_to_toml(tmp_path, source):
    from ironbark_opt.rocket import dump_rocket_toml
    f1 = load_rocket_toml(source)
    p = dump_rocket_toml(f1, tmp_path / "copy.toml")
    f2 = load_rocket_toml(p)
    assert f2.rocket.components == f1.rocket.components
    assert f2.rocket.reference_radius() == f1.rocket.reference_radius()
    assert f2.rocket.dry_mass_properties().as_tuple() == \
        pytest.approx(f1.rocket.dry_mass_properties().as_tuple(), rel=1e-12)
    assert (f2.motor, f2.aero, f2.recovery, f2.ballast) == (f1.motor, f1.aero, f1.recovery,
                                                             f1.ballast)
    for key in ("rail_length", "inclination", "heading", "site_elevation", "wind_from"):
        assert getattr(f2.launch, key) == pytest.approx(getattr(f1.launch, key), rel=1e-12)


@pytest.mark.parametrize("old, new, field", [
    ("count = 5", "count = 0", "motor.overrides.grains.count"),
    ("height = 0.120", "heigth = 0.120", "motor.overrides.grains.heigth"),
    ("dry_inertia = [0.125, 0.002]", "dry_inertia = [0.125]", "motor.overrides.dry_inertia"),
    ("dry_mass = 1.815", "dry_mas = 1.815", "motor.overrides.dry_mas"),
    ("inclination_deg = 84.0", "inclination_deg = 95.0", "launch.inclination_deg"),
    ("cant_deg = 0.5", "cant_deg = 60.0", "component[3].cant_deg"),
    ("cant_deg = 0.5", "cant = 0.5", "component[3].cant"),
])
def test_calisto_variants_with_errors(tmp_path, old, new, field):
    text = CALISTO.read_text()
    assert old in text
    text = text.replace(old, new)
    for name in ("Cesaroni_M1670.eng", "powerOffDragCurve.csv", "powerOnDragCurve.csv"):
        shutil.copy(CALISTO.parent / name, tmp_path / name)
    p = tmp_path / "calisto.toml"
    p.write_text(text)
    with pytest.raises(InputError) as err:
        load_rocket_toml(p)
    assert err.value.field == field
    assert err.value.line == _line_of(text, new)
    print(err.value)


def test_calisto_launch_mass_with_the_motor_package():
    """Cross-check with the motors package (grain geometry -> propellant mass)."""
    from ironbark_opt.vehicle import load_motor_for
    f = load_rocket_toml(CALISTO)
    motor = load_motor_for(f.motor)
    dry = f.rocket.dry_mass_properties()
    i_t, i_a = motor.inertia(0.0)
    wet = total_mass_properties(dry, 0.0, 0.0, float(motor.mass(0.0)),
                                f.motor.motor_cg_x(float(motor.cg(0.0))), float(i_t), float(i_a))
    print(f"Calisto launch mass with the motor package: {wet[0]:.4f} kg (README 19.197 kg), "
          f"propellant {motor.propellant_mass_initial:.4f} kg (README 2.956 kg)")
    assert wet[0] == pytest.approx(19.197, abs=1e-3)
    assert motor.propellant_mass_initial == pytest.approx(2.956, abs=5e-4)


MOTORS = ROOT / "tests" / "data" / "motors"


def test_headerless_thrust_curve_reads_with_header_overrides(tmp_path):
    """A RocketPy-style .eng (no header line) flies from a rocket file when
    [motor.overrides] gives the header's numbers; the motor equals the one read
    with the same numbers as keyword arguments (independent path: load_motor)."""
    from ironbark_opt.motors import load_motor
    from ironbark_opt.rocket.toml_io import load_rocket_toml as load_rocket_file
    from ironbark_opt.vehicle import load_motor_for
    shutil.copy(MOTORS / "Cesaroni_M1101.eng", tmp_path / "Cesaroni_M1101.eng")
    base = _base().replace('file = "Cesaroni_M1670.eng"', 'file = "Cesaroni_M1101.eng"')
    ov = "\n[motor.overrides]\ndry_mass = 2.5\npropellant_mass = 3.0\n"
    p = tmp_path / "rocket.toml"
    p.write_text(base.replace("nozzle_x = 1.35\n", "nozzle_x = 1.35\n" + ov
                              + "diameter = 0.075\nlength = 0.757\n"))
    m = load_motor_for(load_rocket_file(p).motor)
    ref = load_motor(MOTORS / "Cesaroni_M1101.eng", propellant_mass=3.0, dry_mass=2.5,
                     diameter=0.075, length=0.757)
    assert m.total_impulse == pytest.approx(ref.total_impulse, rel=1e-12)
    assert (m.dry_mass, m.propellant_mass_initial, m.diameter, m.length) == (2.5, 3.0, 0.075, 0.757)
    # without diameter and length: the error names the file, line 1, the header and the keys
    p.write_text(base.replace("nozzle_x = 1.35\n", "nozzle_x = 1.35\n" + ov))
    with pytest.raises(InputError) as err:
        load_motor_for(load_rocket_file(p).motor)
    e = err.value
    assert e.line == 1 and e.field == "header" and e.source.endswith("Cesaroni_M1101.eng")
    assert "[motor.overrides]" in str(e) and "diameter" in str(e)


def test_thrust_table_csv_from_a_rocket_file_names_the_override_keys(tmp_path):
    """A time/thrust CSV has no motor data: from a rocket file the error points at
    [motor.overrides]; with the keys given it reads (impulse = trapezoid of the rows)."""
    from ironbark_opt.rocket.toml_io import load_rocket_toml
    from ironbark_opt.vehicle import load_motor_for
    (tmp_path / "thrust.csv").write_text("time_s,thrust_N\n0,0\n0.1,1000\n2.0,1000\n2.1,0\n")
    base = _base().replace('file = "Cesaroni_M1670.eng"', 'file = "thrust.csv"')
    p = tmp_path / "rocket.toml"
    p.write_text(base.replace("nozzle_x = 1.35\n", "nozzle_x = 1.35\n[motor.overrides]\ndry_mass = 1.0\n"))
    with pytest.raises(InputError) as err:
        load_motor_for(load_rocket_toml(p).motor)
    assert "[motor.overrides]" in str(err.value) and err.value.source.endswith("thrust.csv")
    p.write_text(base.replace("nozzle_x = 1.35\n", "nozzle_x = 1.35\n[motor.overrides]\ndry_mass = 1.0\n"
                              "propellant_mass = 1.2\ndiameter = 0.054\nlength = 0.4\n"))
    m = load_motor_for(load_rocket_toml(p).motor)
    assert m.total_impulse == pytest.approx(0.5 * 0.1 * 1000 * 2 + 1.9 * 1000, rel=1e-9)


def test_drag_duplicates_key(tmp_path):
    """A team curve with a Mach number repeated at different Cd (RocketPy's Cavour
    curve) is refused naming the TOML key, flies averaged with
    ``drag_duplicates = "mean"``, and a bad value names its line."""
    import numpy as np
    from ironbark_opt.vehicle import load_aero_table

    def load_setup(path):
        f = load_rocket_toml(path)
        return load_aero_table(f.aero, f.rocket)
    curve = ROOT / "tests" / "data" / "aero" / "cavour_power_on.csv"
    shutil.copy(curve, tmp_path / "dup.csv")
    for name in ("Cesaroni_M1670.eng",):
        shutil.copy(CALISTO.parent / name, tmp_path / name)
    text = CALISTO.read_text().replace('drag_power_off = "powerOffDragCurve.csv"',
                                       'drag_power_off = "dup.csv"')
    text = text.replace('drag_power_on = "powerOnDragCurve.csv"', 'drag_power_on = "dup.csv"')
    (tmp_path / "r.toml").write_text(text)
    with pytest.raises(InputError, match='drag_duplicates = "mean"') as err:
        load_setup(tmp_path / "r.toml")
    # lines 1-5 read Mach 0.011 at Cd 0.708, line 6 at 0.707: the first line that differs
    assert Path(err.value.source).name == "dup.csv" and err.value.line == 6
    (tmp_path / "m.toml").write_text(text.replace("[aero]\n", '[aero]\ndrag_duplicates = "mean"\n'))
    table = load_setup(tmp_path / "m.toml")
    raw = np.loadtxt(curve, delimiter=",")
    m0 = raw[0, 0]
    assert table.evaluate("CA", m0, 0.0) == pytest.approx(raw[raw[:, 0] == m0, 1].mean(), rel=1e-12)
    bad = text.replace("[aero]\n", '[aero]\ndrag_duplicates = "average"\n')
    line = bad.splitlines().index('drag_duplicates = "average"') + 1
    with pytest.raises(InputError, match='expected "error" or "mean"') as err:
        loads_rocket_toml(bad, tmp_path / "b.toml")
    assert err.value.line == line and err.value.field == "aero.drag_duplicates"


def test_clipped_transition_round_trips_through_toml(tmp_path):
    """``clipped`` (OpenRocket's clipped Haack/power/ellipsoid transition, as an .ork
    converts to) is read and written back: the boattail keeps its clip and its mass."""
    from ironbark_opt.rocket import dump_rocket_toml
    text = CALISTO.read_text()
    old = 'aft_radius = 0.0435\n'
    assert text.count(old) == 1
    for name in ("Cesaroni_M1670.eng", "powerOffDragCurve.csv", "powerOnDragCurve.csv"):
        shutil.copy(CALISTO.parent / name, tmp_path / name)
    p = tmp_path / "c.toml"
    p.write_text(text.replace(old, old + 'shape = "haack"\nclipped = true\n'))
    f1 = load_rocket_toml(p)
    tail = next(c for c in f1.rocket.components if isinstance(c, Transition))
    assert tail.clipped and tail.clip_length > 0.0
    f2 = load_rocket_toml(dump_rocket_toml(f1, tmp_path / "copy.toml"))
    assert f2.rocket.components == f1.rocket.components
    assert next(c for c in f2.rocket.components if isinstance(c, Transition)).clip_length == tail.clip_length


def test_launch_lugs_in_a_row_round_trip_with_their_mass_and_rod_length(tmp_path):
    """``count``/``separation`` of a launch lug: two aluminium lugs 0.3 m apart weigh twice
    one (rho pi (ro^2 - ri^2) L each, CGs at 0.85 and 1.15 m), ride the rod from 0.8 to
    1.2 m, and are written back by to_toml; a separation shorter than a lug is refused."""
    from ironbark_opt.rocket import dump_rocket_toml
    old = "material = \"aluminium\"\n"
    text = _base()
    assert text.count("inner_radius = 0.005\n" + old) == 1
    p = _write(tmp_path, text.replace("inner_radius = 0.005\n" + old,
                                      "inner_radius = 0.005\n" + old + "count = 2\nseparation = 0.3\n"))
    f1 = load_rocket_toml(p)
    lug = next(c for c in f1.rocket.components if isinstance(c, LaunchLug))
    from ironbark_opt.rocket import material_density
    m1 = material_density("aluminium") * math.pi * (0.006 ** 2 - 0.005 ** 2) * 0.1
    assert lug.mass_properties().mass == pytest.approx(2 * m1, rel=1e-12)
    assert lug.mass_properties().cg_x == pytest.approx(1.0, rel=1e-12)
    assert f1.rocket.rail_guides() == (0.8, pytest.approx(1.2))
    f2 = load_rocket_toml(dump_rocket_toml(f1, tmp_path / "copy.toml"))
    assert f2.rocket.components == f1.rocket.components
    p.write_text(p.read_text().replace("separation = 0.3", "separation = 0.05"))
    with pytest.raises(InputError, match="separation"):
        load_rocket_toml(p)
