"""Typos a student team makes in a rocket TOML file are refused by name (file, line, key),
not flown (found by a mutation fuzz of the example and fixture files)."""
import math
import shutil
from pathlib import Path

import pytest

from ironbark_opt.errors import InputError
from ironbark_opt.rocket import load_rocket_toml

ROOT = Path(__file__).resolve().parents[2]
EXAMPLES = ROOT / "examples"


def _variant(tmp_path, example, old, new):
    """``example`` (e.g. "kestrel/kestrel.toml") with ``old`` replaced, beside copies of its
    motor and data files; returns (path, text)."""
    src = EXAMPLES / example
    text = src.read_text()
    assert old in text, old
    text = text.replace(old, new, 1)
    text = text.replace('table = "../../tables/Kestrel.csv"', "")     # not needed to load
    for f in src.parent.iterdir():
        if f.suffix in (".eng", ".csv", ".py"):
            shutil.copy(f, tmp_path / f.name)
    text = text.replace('"../calisto/', '"')
    for name in ("Cesaroni_M1670.eng", "powerOffDragCurve.csv", "powerOnDragCurve.csv"):
        shutil.copy(EXAMPLES / "calisto" / name, tmp_path / name)
    path = tmp_path / src.name
    path.write_text(text)
    return path, text


def _line_of(text, needle):
    return next(i for i, line in enumerate(text.splitlines(), 1) if needle in line)


@pytest.mark.parametrize("example, old, new, field, needle", [
    # 0.5 m of bevel on a 0.26 m root chord flew (apogee 3353 -> 3390 m)
    ("kestrel/kestrel.toml", "le_bevel = 0.020", "le_bevel = 0.5", "component[2].le_bevel", "le_bevel"),
    # a motor mount wider than the airframe flew (apogee 3353 -> 1877 m)
    ("kestrel/kestrel.toml", "outer_radius = 0.0400", "outer_radius = 0.0600", "component[4].outer_radius",
     "outer_radius = 0.0600"),
    # a negative parachute diameter squared to a positive area
    ("kestrel/kestrel.toml", "diameter = 0.61", "diameter = -0.61", "recovery[0].diameter", "diameter = -0.61"),
    ("kestrel/kestrel.toml", 'name = "drogue"', "name = 1.5", "recovery[0].name", "name = 1.5"),
    # a 90 km site and a Celsius or kPa site value named 'elevation' / 'temperature_offset'
    # / 'pressure_offset' without the file
    ("calisto/calisto.toml", "site_elevation = 1400.0", "site_elevation = 90000.0", "launch.site_elevation",
     "site_elevation"),
    ("calisto/calisto.toml", "wind_speed = 0.0", "site_temperature = 25.0", "launch.site_temperature",
     "site_temperature"),
    ("calisto/calisto.toml", "wind_speed = 0.0", "site_pressure = 101.3", "launch.site_pressure",
     "site_pressure"),
    ("calisto/calisto.toml", "longitude_deg = -106.974998", "longitude_deg = -400.0", "launch.longitude_deg",
     "longitude_deg"),
    # brakes "5.4 s before ignition" flew (opened at burnout)
    ("calisto_airbrakes/calisto_airbrakes.toml", "start = 5.4", "start = -5.4", "airbrakes.start", "start = -5.4"),
    # a point mass 9 m aft of a 2.4 m rocket was refused only as 'static margin' (flown with
    # --allow-unstable); a rail button off the body was named 'x_aft' without the component
    ("kestrel/kestrel.toml", "x = 1.05", "x = 9.05", "component[6].x", "x = 9.05"),
    ("kestrel/kestrel.toml", "x_aft = 2.20", "x_aft = 9.20", "component[9].x_aft", "x_aft = 9.20"),
    # [motor.overrides] errors were reported against the .eng file under a bare key
    ("calisto/calisto.toml", "dry_inertia = [0.125, 0.002]", "dry_inertia = [0.125, inf]",
     "motor.overrides.dry_inertia", "dry_inertia"),
    ("calisto/calisto.toml", "propellant_cg = 0.397", "propellant_cg = -5.0", "motor.overrides.propellant_cg",
     "propellant_cg"),
    # tan(90 deg) swept the tip 1.8e15 m aft; -6 m of sweep put the tip ahead of the nose
    # (refused only as unstable; aero build: 'singular surface pressure', no file)
    ("calisto/calisto.toml", "sweep_length = 0.060", "sweep_angle_deg = 90.0", "component[3].sweep_angle_deg",
     "sweep_angle_deg"),
    ("calisto/calisto.toml", "sweep_length = 0.060", "sweep_length = -6.3", "component[3].x", "x = 2.32756"),
    # 100 fins of 11.2 mm (1.12 m) around Calisto's 0.40 m girth flew (3292.3 -> 3293.5 m);
    # a 0.5 m thick fin on a 0.26 m root chord was refused only as 'unstable'
    ("calisto/calisto.toml", "count = 4", "count = 100", "component[3].count", "count = 100"),
    ("kestrel/kestrel.toml", "thickness = 0.0048", "thickness = 0.5", "component[2].thickness", "thickness = 0.5"),
    # a reference radius in mm (100x the body: exit 3 'never climbs' without naming it)
    ("calisto/calisto.toml", "reference_radius = 0.0635", "reference_radius = 6.35", "rocket.reference_radius",
     "reference_radius"),
    ("calisto/calisto.toml", "reference_radius = 0.0635", "reference_radius = 0.000635", "rocket.reference_radius",
     "reference_radius"),
])
def test_typo_is_refused_by_name(tmp_path, example, old, new, field, needle):
    path, text = _variant(tmp_path, example, old, new)
    with pytest.raises(InputError) as err:
        load_rocket_toml(path)
    assert err.value.field == field
    assert err.value.line == _line_of(text, needle)
    assert err.value.source == str(path)
    print(err.value)


def test_bevels_shorter_than_the_fin_still_meet_at_a_short_tip(tmp_path):
    """0.2 + 0.02 m of bevel fits the 0.26 m root chord (the bevels meet toward the 0.09 m tip)."""
    path, _ = _variant(tmp_path, "kestrel/kestrel.toml", "le_bevel = 0.020", "le_bevel = 0.2")
    fins = load_rocket_toml(path).rocket.fin_sets()[0]
    assert fins.section.le_bevel == 0.2
    # the longer bevel removes material: the fins are thinner than with the 0.020 m bevel
    base = load_rocket_toml(EXAMPLES / "kestrel" / "kestrel.toml").rocket.fin_sets()[0]
    assert fins.volume() < base.volume()


def test_inner_tube_as_wide_as_the_body_fits(tmp_path):
    """A coupler flush with the outer radius (0.0508 m) is accepted; 1 um of tolerance."""
    path, _ = _variant(tmp_path, "kestrel/kestrel.toml", "outer_radius = 0.0400", "outer_radius = 0.0508")
    assert load_rocket_toml(path).rocket.components[4].outer_radius == 0.0508


def test_separation_delay_is_bounded(tmp_path):
    """A 1e6 s separation delay hung `simulate` (1e8 RK4 steps of stack coast)."""
    data = ROOT / "tests" / "data" / "staged_toml"
    text = (data / "sustainer.toml").read_text()
    for name in ("sustainer.toml", "booster.toml"):
        shutil.copy(data / name, tmp_path / name)
    (tmp_path / "motors").mkdir()
    text = text.replace('"../ork/motors/', f'"{ROOT}/tests/data/ork/motors/')
    bad = text.replace("separation_delay = 0.0", "separation_delay = 1e6")
    path = tmp_path / "sustainer.toml"
    path.write_text(bad)
    (tmp_path / "booster.toml").write_text((data / "booster.toml").read_text()
                                           .replace('"../ork/motors/', f'"{ROOT}/tests/data/ork/motors/'))
    with pytest.raises(InputError) as err:
        load_rocket_toml(path)
    assert err.value.field == "stage[0].separation_delay"
    assert err.value.line == _line_of(bad, "separation_delay")
    path.write_text(text.replace("separation_delay = 0.0", "separation_delay = 600.0"))
    assert load_rocket_toml(path).stages[0].separation_delay == 600.0


def test_longitude_east_of_greenwich_in_0_360_is_accepted(tmp_path):
    path, _ = _variant(tmp_path, "calisto/calisto.toml", "longitude_deg = -106.974998",
                       "longitude_deg = 253.025002")
    assert math.degrees(load_rocket_toml(path).launch.longitude) == pytest.approx(253.025002)


FIN_BLOCK = '''
[[component]]
type = "trapezoidal_fins"
name = "second fins"
count = 4
x = 2.32756
root_chord = 0.120
tip_chord = 0.060
span = 0.110
sweep_length = 0.060
thickness = 0.0112
'''


def test_duplicated_fin_set_is_refused_and_a_turned_one_accepted(tmp_path):
    """A copy-pasted fin set (same x, same default 45 deg roll) flew with twice the fin
    normal force (Calisto apogee 3292.3 -> 3290.4 m); turned by 45 deg it is 8 fins."""
    path, text = _variant(tmp_path, "calisto/calisto.toml", "[motor]\n", FIN_BLOCK + "\n[motor]\n")
    with pytest.raises(InputError) as err:
        load_rocket_toml(path)
    assert err.value.field == "component[5].x" and "roll_deg" in err.value.message
    assert err.value.line == _line_of(text, 'name = "second fins"') + 2
    path.write_text(text.replace('name = "second fins"', 'name = "second fins"\nroll_deg = 0.0'))
    fins = load_rocket_toml(path).rocket.fin_sets()
    assert [math.degrees(f.roll_angle) for f in fins] == pytest.approx([45.0, 0.0])


def test_motor_sticking_out_of_the_nose_is_refused(tmp_path):
    """nozzle_x = 0.2 m put Calisto's 0.757 m M1670 0.557 m ahead of the nose tip; it flew."""
    from ironbark_opt.vehicle import setup_from_file
    path, _ = _variant(tmp_path, "calisto/calisto.toml", "nozzle_x = 2.533", "nozzle_x = 0.2")
    with pytest.raises(InputError) as err:
        setup_from_file(load_rocket_toml(path))
    assert err.value.field == "motor.nozzle_x" and err.value.source == str(path)
    assert "0.557 m ahead of the nose tip" in err.value.message
    path, _ = _variant(tmp_path, "calisto/calisto.toml", "nozzle_x = 2.533", "nozzle_x = 0.757")
    assert setup_from_file(load_rocket_toml(path)) is not None      # flush with the tip: accepted


def test_negative_number_in_a_motor_header_is_refused_even_when_overridden(tmp_path):
    """Calisto's [motor.overrides] replace the header's masses, so a header propellant mass
    of -3.101 kg was never read: the file was accepted as well formed."""
    path, _ = _variant(tmp_path, "calisto/calisto.toml", "nozzle_x", "nozzle_x")
    eng = tmp_path / "Cesaroni_M1670.eng"
    eng.write_text(eng.read_text().replace("3.101 5.231", "-3.101 5.231"))
    from ironbark_opt.vehicle import setup_from_file
    with pytest.raises(InputError) as err:
        setup_from_file(load_rocket_toml(path))
    assert err.value.source == str(eng) and err.value.line == 1 and err.value.field == "propellant_kg"


def test_reference_diameter_for_radius_is_warned(tmp_path):
    """Twice the body radius (a diameter typed as the radius) flies, with a warning."""
    path, _ = _variant(tmp_path, "calisto/calisto.toml", "reference_radius = 0.0635", "reference_radius = 0.127")
    with pytest.warns(UserWarning, match=r"2 x the largest body radius: a diameter"):
        rocket = load_rocket_toml(path).rocket
    assert rocket.reference_radius() == 0.127
