"""OpenRocket .ork reader: containers, tree walk, positions, units, damaged inputs."""
from __future__ import annotations

import gzip
import math
import os
import warnings
import zipfile
from functools import lru_cache
from pathlib import Path

import pytest

from ironbark_opt.errors import InputError
from ironbark_opt.openrocket import load_ork, read_ork
from ironbark_opt.openrocket.ormass import ring
from ironbark_opt.openrocket.xmlread import read_bytes

DATA = Path(__file__).parents[1] / "data" / "ork"
SIMPLE = DATA / "A simple model rocket.ork"


@lru_cache(maxsize=None)
def _xml(name: str) -> str:
    return read_bytes(DATA / name).decode("utf-8")


def _write(tmp_path, text: str, name="x.ork") -> Path:
    p = tmp_path / name
    p.write_text(text, encoding="utf-8")
    return p


def test_all_three_containers_give_the_same_rocket(tmp_path):
    xml = _xml("A simple model rocket.ork").encode()
    plain = tmp_path / "plain.ork"
    plain.write_bytes(xml)
    gz = tmp_path / "gz.ork"
    gz.write_bytes(gzip.compress(xml))
    zp = tmp_path / "zip.ork"
    with zipfile.ZipFile(zp, "w") as zf:
        zf.writestr("rocket.ork", xml)
        zf.writestr("decals/x.png", b"\x89PNG")
    masses = [read_ork(p).dry_mass_properties().mass for p in (SIMPLE, plain, gz, zp)]
    assert max(masses) - min(masses) < 1e-12


def test_old_gzip_format_1_2_reads_and_resolves_auto_radii():
    doc = read_ork(DATA / "simplerocket_v1.2_gzip.ork")
    assert doc.version == "1.2"
    rings = [c for c in doc.rocket.components() if c.kind == "centeringring"]
    # <outerradius>auto</outerradius>: body tube inner radius 0.0125 - 0.001
    assert rings[0].geo["outer_radius"] == pytest.approx(0.0115)
    # <innerradius>auto</innerradius>: the inner tube beside it, outer radius 0.0095
    assert rings[0].geo["inner_radius"] == pytest.approx(0.0095)


def test_positions_follow_openrocket_axial_methods():
    doc = read_ork(SIMPLE)
    comps = {c.name: c for c in doc.rocket.components()}
    body = comps["Body tube"]
    assert body.x == pytest.approx(0.1)                       # after the 0.1 m nose cone
    fins = comps["Trapezoidal fin set"]                      # bottom, offset 0
    assert fins.x == pytest.approx(body.x_end - fins.geo["root_chord"])
    lug = comps["Launch lug"]                                 # middle, offset 0
    assert lug.x + lug.length / 2 == pytest.approx(body.x + body.length / 2)
    chute = comps["Parachute"]                                # top, offset 0.032
    assert chute.x == pytest.approx(body.x + 0.032)


def test_ring_mass_is_analytic_annulus():
    mp = ring(1000.0, 0.02, 0.01, 0.5, 0.1)
    m = 1000.0 * math.pi * (0.02 ** 2 - 0.01 ** 2) * 0.1
    assert mp.mass == pytest.approx(m, rel=1e-12)
    assert mp.cg_x == pytest.approx(0.55)
    assert mp.I_axial == pytest.approx(m * (0.02 ** 2 + 0.01 ** 2) / 2)


def test_stored_data_columns_are_looked_up_by_name():
    # OR 22.02 and 24.12 write the columns in different orders
    old = read_ork(DATA / "01.One-stage_OR22.02.ork").simulations[0].at_launch()
    new = read_ork(SIMPLE).simulations[0].at_launch()
    assert old["mass_kg"] == pytest.approx(0.526)
    assert old["cg_x_m"] == pytest.approx(0.74)
    assert new["mass_kg"] == pytest.approx(0.065)
    assert new["motor_mass_kg"] == pytest.approx(0.016)
    df = read_ork(SIMPLE).simulations[3].data()
    assert {"time_s", "altitude_m", "vertical_velocity_mps"} <= set(df.columns)
    assert df["altitude_m"].max() == pytest.approx(316.583, abs=0.5)


def test_launch_conditions_units():
    sim = read_ork(SIMPLE).simulations[0]
    assert sim.launch.rail_length == pytest.approx(1.0)
    assert sim.launch.inclination == pytest.approx(math.pi / 2)        # rod angle 0 from vertical
    assert sim.launch.wind_from == pytest.approx(math.pi / 2)          # radians in the file
    assert sim.launch.wind_speed == pytest.approx(2.0)
    assert sim.launch.latitude == pytest.approx(math.radians(45.0))
    assert sim.summary["apogee_m"] == pytest.approx(50.59)


def test_launch_rod_angle_is_degrees_from_vertical(tmp_path):
    text = _xml("A simple model rocket.ork").replace(
        "<launchrodangle>0.0</launchrodangle>", "<launchrodangle>5.0</launchrodangle>", 1)
    sim = read_ork(_write(tmp_path, text)).simulations[0]
    assert math.degrees(sim.launch.inclination) == pytest.approx(85.0)


def test_config_selection():
    doc = read_ork(SIMPLE)
    assert doc.config().label() == "[C6-5]"                 # the file's default
    assert doc.config("da326836").label() == "[A8-3]"      # id prefix
    assert doc.config("[B4-4]").config_id.startswith("05896b5a")
    with pytest.raises(InputError, match="no single motor configuration"):
        doc.config("Z9000")


def test_truncated_zip_is_a_clear_error(tmp_path):
    data = SIMPLE.read_bytes()
    p = tmp_path / "cut.ork"
    p.write_bytes(data[: len(data) // 3])
    with pytest.raises(InputError, match="damaged zip|truncated"):
        read_ork(p)


def test_truncated_gzip_and_bad_xml(tmp_path):
    data = (DATA / "simplerocket_v1.2_gzip.ork").read_bytes()
    p = tmp_path / "cut.ork"
    p.write_bytes(data[:600])
    with pytest.raises(InputError, match="gzip"):
        read_ork(p)
    with pytest.raises(InputError, match="not well-formed"):
        read_ork(_write(tmp_path, "<openrocket version='1.10'><rocket>"))


def test_missing_required_element_names_the_path(tmp_path):
    text = _xml("A simple model rocket.ork").replace("<length>0.3</length>", "", 1)
    with pytest.raises(InputError) as err:
        read_ork(_write(tmp_path, text))
    assert err.value.field == "rocket/subcomponents/stage[1]/subcomponents/bodytube[1]/length"


def test_negative_length_names_the_path(tmp_path):
    text = _xml("A simple model rocket.ork").replace("<length>0.3</length>", "<length>-0.3</length>", 1)
    with pytest.raises(InputError, match=">= 0") as err:
        read_ork(_write(tmp_path, text))
    assert err.value.field.endswith("bodytube[1]/length")


def test_unknown_component_tag(tmp_path):
    text = _xml("A simple model rocket.ork").replace("<masscomponent>", "<warpdrive>", 1) \
        .replace("</masscomponent>", "</warpdrive>", 1)
    with pytest.raises(InputError, match="unknown component <warpdrive>") as err:
        read_ork(_write(tmp_path, text))
    assert "warpdrive[1]" in err.value.field


def test_not_a_number_and_unsupported_version(tmp_path):
    text = _xml("A simple model rocket.ork").replace("<length>0.3</length>", "<length>long</length>", 1)
    with pytest.raises(InputError, match="must be a number"):
        read_ork(_write(tmp_path, text))
    text = _xml("A simple model rocket.ork").replace('version="1.10"', 'version="9.9"', 1)
    with pytest.raises(InputError, match="version 9.9"):
        read_ork(_write(tmp_path, text))


def test_unsupported_features_name_the_component(monkeypatch, tmp_path):
    monkeypatch.setenv("IRONBARK_OFFLINE", "1")
    monkeypatch.setenv("IRONBARK_CACHE_DIR", str(tmp_path))
    # parallel boosters are read and fly (tests/validation/test_ork_parallel.py), not as one rocket file
    with pytest.raises(InputError, match="parallel boosters \\('Booster Set'\\)") as err:
        load_ork(DATA / "Parallel booster staging.ork")
    assert err.value.field.endswith("parallelstage[1]")
    with pytest.raises(InputError, match="multi-stage.*'Booster'") as err:
        load_ork(DATA / "Two stage high power rocket.ork")
    assert err.value.field == "rocket/subcomponents/stage[2]"
    # Air-start flies (tests/validation/test_ork_airstart.py); an ignition nobody lights at launch does not.
    text = _xml("Airstart timing.ork").replace("<ignitiondelay>0.0</ignitiondelay>", "<ignitiondelay>0.5</ignitiondelay>")
    assert text != _xml("Airstart timing.ork")
    with pytest.raises(InputError, match="no motor ignites at launch"):
        load_ork(_write(tmp_path, text), config="99b8d6a6")


def test_missing_motor_names_designation_and_places(monkeypatch, tmp_path):
    monkeypatch.setenv("IRONBARK_OFFLINE", "1")
    monkeypatch.setenv("IRONBARK_CACHE_DIR", str(tmp_path))
    monkeypatch.setenv("IRONBARK_MOTOR_PATH", str(tmp_path))
    with pytest.raises(InputError, match="motor Estes C6 not found") as err:
        load_ork(SIMPLE)
    assert str(tmp_path) in str(err.value)


def test_openrocket_motor_digest_is_reproduced(monkeypatch, tmp_path):
    from ironbark_opt.openrocket.digest import eng_digests
    from ironbark_opt.openrocket.motors import find_motor_file
    doc = read_ork(DATA / "Airstart timing.ork")
    entry = next(m for _, m in doc.configs[0].motors if m.designation == "K550W")
    eng = DATA / "motors" / "tc_api_decoded_AeroTech_K550W.eng"
    # the digest OpenRocket 24.12 stored in the .ork for this K550W
    assert eng_digests(eng) == {"K550W": entry.digest} == {"K550W": "822e1d4ed7924f9dea7a62b5f5ff2823"}
    monkeypatch.setenv("IRONBARK_MOTOR_PATH", str(DATA / "motors"))
    hit = find_motor_file("K550W", "AeroTech", DATA / "Airstart timing.ork", entry.digest)
    assert hit.verified is True and hit.path == eng
    # same designation and maker, other data: found, flagged and warned about
    c6 = DATA / "motors" / "WECO_C6.eng"
    with pytest.warns(UserWarning, match="differs"):
        hit = find_motor_file("C6", "WECO", DATA / "Airstart timing.ork", "0" * 32)
    assert hit.verified is False and hit.path == c6


def test_flight_data_for_overlays():
    doc = read_ork(SIMPLE)
    df = doc.flight_data("Simulation 4")
    apogee = df["altitude_m"].max()
    # the <flightdata maxaltitude> summary agrees with the stored time series
    assert apogee == pytest.approx(doc.simulation("Simulation 4").summary["apogee_m"], abs=0.5)
    assert df["time_s"].is_monotonic_increasing
    with pytest.raises(InputError, match="no simulation 'nope'"):
        doc.flight_data("nope")


def test_absolute_position_and_pods(tmp_path):
    text = _xml("A simple model rocket.ork").replace(
        '<axialoffset method="middle">0.0</axialoffset>',
        '<axialoffset method="absolute">0.25</axialoffset>', 1)
    lug = next(c for c in read_ork(_write(tmp_path, text)).rocket.components()
               if c.kind == "launchlug")
    assert lug.x == pytest.approx(0.25)
    text = _xml("A simple model rocket.ork").replace("<masscomponent>", "<podset>", 1) \
        .replace("</masscomponent>", "</podset>", 1)
    with pytest.raises(InputError, match="pods") as err:
        read_ork(_write(tmp_path, text, "pods.ork"))
    assert err.value.field.endswith("podset[1]")


def test_cluster_flies_as_one_equivalent_motor(monkeypatch, tmp_path):
    from ironbark_opt.vehicle import load_motor_for
    monkeypatch.setenv("IRONBARK_OFFLINE", "1")
    monkeypatch.setenv("IRONBARK_CACHE_DIR", str(tmp_path / "cache"))
    monkeypatch.setenv("IRONBARK_MOTOR_PATH", str(DATA / "motors"))
    text = _xml("Clustered motors.ork").replace("<manufacturer>Estes</manufacturer>",
                                                "<manufacturer>WECO</manufacturer>")
    text = text.replace("<digest>", "<!--").replace("</digest>", "-->")
    rf = load_ork(_write(tmp_path, text), config="[C6-5]")
    one = load_motor_for(type(rf.motor)(file=DATA / "motors" / "WECO_C6.eng"))
    four = load_motor_for(rf.motor)
    assert rf.motor.designation == "4xC6"
    assert four.total_impulse == pytest.approx(4 * one.total_impulse, rel=1e-9)
    assert float(four.mass(0.0)) == pytest.approx(4 * float(one.mass(0.0)), rel=1e-9)
    assert float(four.cg(0.0)) == pytest.approx(float(one.cg(0.0)), rel=1e-9)


def test_every_fixture_is_read():
    for path in sorted(DATA.glob("*.ork")):
        doc = read_ork(path)
        assert doc.length() > 0 and doc.dry_mass_properties().mass > 0
        assert doc.configs and doc.simulations


def test_custom_atmosphere_and_bad_rod(tmp_path):
    text = _xml("A simple model rocket.ork").replace(
        '<atmosphere model="isa"/>',
        '<atmosphere model="extendedisa"><basetemperature>300.0</basetemperature>'
        '<basepressure>95000.0</basepressure></atmosphere>', 1)
    launch = read_ork(_write(tmp_path, text)).simulations[0].launch
    assert (launch.site_temperature, launch.site_pressure) == (300.0, 95000.0)
    text = _xml("A simple model rocket.ork").replace(
        "<launchrodlength>1.0</launchrodlength>", "<launchrodlength>0.0</launchrodlength>", 1)
    with pytest.raises(InputError, match="must be > 0") as err:
        read_ork(_write(tmp_path, text, "rod.ork"))
    assert err.value.field == "simulations/simulation[1]/conditions/launchrodlength"


def test_wind_direction_is_where_the_wind_comes_from():
    # OpenRocket's own flight: winddirection = pi/2 with the rod launched into the wind.
    # The rocket weathercocks east on the way up and drifts west under its chute,
    # so the wind blows from the east: our wind_from = pi/2 (clockwise from north).
    doc = read_ork(SIMPLE)
    sim = doc.simulation("Simulation 4")
    df = sim.data()
    top = df["altitude_m"].idxmax()
    assert df.loc[top, "east_m"] > 10.0 and df["east_m"].iloc[-1] < -50.0
    assert sim.launch.wind_from == pytest.approx(math.pi / 2)


def test_tube_fins_fly_empirically_and_are_not_meshed(tmp_path):
    """A tube fin set (here the simple rocket's launch lug turned into one) becomes a
    TubeFins component (Ribner's ring-wing lift, open-tube drag); the panel mesh cannot
    represent it, so building a table refuses it by name."""
    from ironbark_opt.openrocket.build import geometry
    from ironbark_opt.rocket import TubeFins
    from panair.geometry_adapter import from_rocket
    text = _xml("A simple model rocket.ork").replace("<launchlug>", "<tubefinset>", 1) \
        .replace("</launchlug>", "</tubefinset>", 1)
    rocket = geometry(read_ork(_write(tmp_path, text, "tubefins.ork")))
    tubes = rocket.tube_fin_sets()
    assert len(tubes) == 1 and isinstance(tubes[0], TubeFins) and tubes[0].outer_radius == 0.0035
    with pytest.raises(InputError, match="tube fins .* cannot be meshed"):
        from_rocket(rocket)


def test_tube_fin_auto_radius_is_openrockets(tmp_path):
    """OpenRocket writes a tube fin set's outer radius as <radius>; 'auto' is the radius at
    which neighbouring tubes touch, R_body sin(pi/n) / (1 - sin(pi/n)) (TubeFinSet.
    getTouchingRadius), the body's own for n = 6.  Read before as 0 (the mass of OpenRocket's
    'Tube fin rocket' 13 % light: launch 0.0660 kg where OpenRocket's stored flight has 0.076;
    now 0.0764 kg, CG 0.4528 m against 0.453 m)."""
    text = _xml("A simple model rocket.ork").replace("<launchlug>", "<tubefinset>", 1) \
        .replace("</launchlug>", "</tubefinset>", 1).replace("<radius>0.0035</radius>", "<radius>auto</radius>", 1)
    for n, factor in ((6, 1.0), (3, math.sin(math.pi / 3) / (1 - math.sin(math.pi / 3))), (2, 1.0)):
        doc = read_ork(_write(tmp_path, text.replace("<tubefinset>", f"<tubefinset><fincount>{n}</fincount>", 1),
                              f"tubes{n}.ork"))
        tubes = next(c for c in doc.rocket.components() if c.kind == "tubefinset")
        assert tubes.geo["count"] == n
        assert tubes.geo["outer_radius"] == pytest.approx(factor * tubes.geo["parent_radius"], rel=1e-12)


_STALE_AUTO = """<?xml version='1.0' encoding='utf-8'?>
<openrocket version="1.8" creator="OpenRocket 22.02">
  <rocket><name>stale</name>
    <subcomponents>
      <stage><name>Dart</name><subcomponents>
        <nosecone><name>nose</name><length>0.2</length><thickness>filled</thickness>
          <shape>conical</shape><aftradius>auto 0.025</aftradius></nosecone>
        <bodytube><name>auto tube</name><length>0.01</length><thickness>0.001</thickness>
          <radius>auto 0.025</radius></bodytube>
        <bodytube><name>dart tube</name><length>0.3</length><thickness>0.001</thickness>
          <radius>0.02</radius></bodytube>
        <transition><name>shoulder</name><length>0.1</length><thickness>filled</thickness>
          <shape>conical</shape><foreradius>auto 0.056</foreradius><aftradius>auto 0.025</aftradius>
        </transition>
      </subcomponents></stage>
      <stage><name>Booster</name><subcomponents>
        <bodytube><name>booster auto</name><length>0.05</length><thickness>0.002</thickness>
          <radius>auto 0.025</radius></bodytube>
        <bodytube><name>booster tube</name><length>0.5</length><thickness>0.002</thickness>
          <radius>0.05</radius>
          <subcomponents>
            <centeringring><name>ring</name><position type="top">0.1</position><length>0.003</length>
              <outerradius>auto 0.03</outerradius><innerradius>0.01</innerradius></centeringring>
          </subcomponents></bodytube>
        <transition><name>boattail</name><length>0.02</length><thickness>filled</thickness>
          <shape>conical</shape><foreradius>auto 0.056</foreradius><aftradius>0.04</aftradius>
        </transition>
      </subcomponents></stage>
    </subcomponents>
  </rocket>
</openrocket>
"""


def test_auto_radius_with_a_cached_number_is_automatic(tmp_path):
    """OpenRocket 22.02+ writes an automatic radius as ``auto <number>``: its loader sets the
    number and then switches the radius to automatic (``DoubleSetter`` with the special
    string "auto"), so the radius is the neighbour's whatever the (possibly stale) number.
    Each expected value follows OpenRocket's ``BodyTube.getAutoOuterRadius`` /
    ``Transition.getAutoFore/AftRadius`` by hand; every cached number here is stale."""
    doc = read_ork(_write(tmp_path, _STALE_AUTO))
    c = {x.name: x for x in doc.rocket.components()}
    # the nose base looks aft: through the automatic tube to the 0.02 m tube
    assert c["nose"].geo["aft_radius"] == pytest.approx(0.02)
    # the automatic tube: the nose takes its radius from it, so it looks aft too
    assert c["auto tube"].geo["radius"] == pytest.approx(0.02)
    # the shoulder: the 0.02 m tube before it, and through the booster's automatic tube
    # (across the stage boundary) to the 0.05 m tube after it
    assert c["shoulder"].geo["fore_radius"] == pytest.approx(0.02)
    assert c["shoulder"].geo["aft_radius"] == pytest.approx(0.05)
    # the booster's automatic tube: the shoulder before it takes its aft radius from it,
    # so it takes the 0.05 m tube's after it
    assert c["booster auto"].geo["radius"] == pytest.approx(0.05)
    assert c["boattail"].geo["fore_radius"] == pytest.approx(0.05)
    # an automatic ring outside: the tube's inner radius, not the cached 0.03
    assert c["ring"].geo["outer_radius"] == pytest.approx(0.048)
    # reference diameter: the largest body radius (0.05), not the stale 0.056
    from ironbark_opt.openrocket.build import geometry
    assert geometry(doc).reference_radius() == pytest.approx(0.05)


def test_unverifiable_rse_motor_is_warned_about(monkeypatch, tmp_path):
    """'01.One-stage_OR22.02.ork' names a G80T with the digest of OpenRocket's 136 N s G80;
    with only tests/data/motors on the path the 100 N s AeroTech_G80T.rse (no digest can be
    computed for a .rse) was flown without a word: apogee 526 m against OpenRocket's 706 m."""
    from ironbark_opt.openrocket.motors import find_motor_file
    doc = read_ork(DATA / "01.One-stage_OR22.02.ork")
    entry = next(m for c in doc.configs for _, m in c.motors if m.designation == "G80T")
    assert entry.digest == "bc77ef06b0e4f9471985fe24e1d7fbd6"
    motors = Path(__file__).parents[1] / "data" / "motors"
    monkeypatch.setenv("IRONBARK_MOTOR_PATH", str(motors))
    monkeypatch.setenv("IRONBARK_OFFLINE", "1")
    with pytest.warns(UserWarning, match=r"cannot be checked against the motor the \.ork.*99\.72 N s"):
        hit = find_motor_file("G80T", "AeroTech", DATA / "01.One-stage_OR22.02.ork", entry.digest)
    assert hit.verified is None and hit.path == motors / "AeroTech_G80T.rse"
    rse_impulse = hit.motor.total_impulse
    # the digest-verified .eng (tests/data/ork/motors) wins, without a warning
    monkeypatch.setenv("IRONBARK_MOTOR_PATH", os.pathsep.join([str(DATA / "motors"), str(motors)]))
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        hit = find_motor_file("G80T", "AeroTech", DATA / "01.One-stage_OR22.02.ork", entry.digest)
    assert hit.verified is True and hit.path.name == "AeroTech_G80_1.eng"
    # the design's motor: 133.2 N s, a third more than the .rse's 99.7 N s
    assert hit.motor.total_impulse > 1.3 * rse_impulse


def test_cd_override_is_named_not_dropped_silently(tmp_path):
    """OpenRocket's Cd override is not flown (drag from the geometry): each overridden
    component is named in a warning (here the simple rocket's nose cone, overridden to
    Cd 0.42); a file without overrides reads without one."""
    text = _xml("A simple model rocket.ork")
    i = text.index("<nosecone>")
    text = text[:i] + text[i:].replace("</name>", "</name><overridecd>0.42</overridecd>", 1)
    with pytest.warns(UserWarning, match=r"drag coefficient override Cd = 0.42 is not applied") as rec:
        read_ork(_write(tmp_path, text, "cd.ork"))
    said = [str(w.message) for w in rec if "override Cd" in str(w.message)]
    assert len(said) == 1 and "nosecone" in said[0]
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        read_ork(SIMPLE)


def test_bad_fin_outline_names_the_files_element(tmp_path):
    """A free-form fin whose outline crosses itself (and a trapezoid of negative height)
    is refused naming the element of the file (finpoints, height), not Ironbark's own
    field name (points, span)."""
    from ironbark_opt.openrocket.build import load_ork_geometry
    xml = _xml("A simple model rocket.ork")
    start, end = xml.index("<trapezoidfinset>"), xml.index("</trapezoidfinset>")
    fin = xml[start:end]
    shape = fin[fin.index("<rootchord>"):fin.index("</height>") + len("</height>")]
    pts = "".join(f'<point x="{x}" y="{y}"/>' for x, y in ((0, 0), (0.05, 0.03), (0.0, 0.03), (0.05, 0)))
    free = (fin.replace(shape, f"<finpoints>{pts}</finpoints>").replace("<trapezoidfinset>", "<freeformfinset>")
            + "</freeformfinset>")
    text = xml[:start] + free + xml[end + len("</trapezoidfinset>"):]
    with pytest.raises(InputError, match="crosses itself") as err:
        load_ork_geometry(_write(tmp_path, text))
    assert err.value.field.endswith("freeformfinset[1]/finpoints")
    bad = xml.replace("<height>0.03</height>", "<height>0.0</height>", 1)
    with pytest.raises(InputError) as err:
        load_ork_geometry(_write(tmp_path, bad, "h.ork"))
    assert err.value.field.endswith("trapezoidfinset[1]/height"), err.value.field


def test_every_launch_lug_instance_has_its_drag(tmp_path):
    """OpenRocket's <instancecount> of a launch lug: n identical lugs, each with drag (as its
    mass already was); before, the drag was one lug's.  Two lugs 0.2 m apart drag as the
    file's one lug plus the same lug moved 0.2 m aft (each in the boundary layer at its
    station), and the rod runs from the first lug's front to the second one's aft end."""
    from ironbark_opt.aero.model import guide_drag
    from ironbark_opt.openrocket.build import load_ork_geometry
    text = _xml("01.One-stage_OR22.02.ork")
    one = _write(tmp_path, text, "one.ork")
    blk = text[text.index("<launchlug>"):text.index("</launchlug>")]
    two = _write(tmp_path, text.replace(blk, blk.replace("<instancecount>1<", "<instancecount>2<")
                                        .replace("<instanceseparation>0.06<", "<instanceseparation>0.2<")),
                 "two.ork")
    offset = "<axialoffset method=\"top\">0.13741205324727715</axialoffset>"
    moved = _write(tmp_path, text.replace(blk, blk.replace(offset, offset.replace(
        "0.13741205324727715", repr(0.13741205324727715 + 0.2)))), "moved.ork")
    r1, r2, r3 = load_ork_geometry(one), load_ork_geometry(two), load_ork_geometry(moved)
    area, mach, re = r1.reference_area(), 0.3, 7e6

    def ca(rocket):
        return sum(float(d.CA(mach, re, area)) for d in guide_drag(rocket)[0])
    assert r3.rail_guides()[0] == pytest.approx(r1.rail_guides()[0] + 0.2)
    assert ca(r1) > 0.0
    assert ca(r2) == pytest.approx(ca(r1) + ca(r3), rel=1e-12)
    x0, x1 = r1.rail_guides()
    assert r2.rail_guides() == pytest.approx((x0, x0 + 0.2 + (x1 - x0)))


def test_unknown_fin_cross_section_is_refused_not_flown_square(tmp_path):
    """A <crosssection> other than square, rounded or airfoil (e.g. a later OpenRocket's
    'triangular') was flown as a square plate without a word (01.One-stage: apogee 669 m
    rounded, 501 m as the square it became); now refused naming the fin set."""
    text = _xml("01.One-stage_OR22.02.ork")
    assert text.count("<crosssection>rounded</crosssection>") == 1
    p = _write(tmp_path, text.replace("<crosssection>rounded</crosssection>",
                                      "<crosssection>triangular</crosssection>"))
    with pytest.raises(InputError, match="'Fin set': cross-section 'triangular' is not supported; "
                                         "expected one of square, rounded, airfoil") as err:
        read_ork(p)
    assert err.value.field.endswith("trapezoidfinset[1]/crosssection")


_BUTTONS = """<railbutton><name>{name}</name><instancecount>{n}</instancecount>
<instanceseparation>0.4</instanceseparation><angleoffset method="relative">180.0</angleoffset>
<axialoffset method="top">{x}</axialoffset><position type="top">{x}</position><finish>normal</finish>
<material type="bulk" density="1420.0">Delrin</material><outerdiameter>0.0097</outerdiameter>
<innerdiameter>0.008</innerdiameter><height>0.0097</height><baseheight>0.002</baseheight>
<flangeheight>0.002</flangeheight><screwheight>0.0</screwheight></railbutton>"""


def test_single_rail_buttons_in_separate_components_ride_the_rail(tmp_path):
    """Two rail buttons added as two OpenRocket components of one button each (a common way
    to draw them) had neither rail guides nor drag (01.One-stage with its lug replaced: apogee
    702.1 m, rail exit 18.2 m/s, against 676.7 m and 12.0 m/s with the same buttons as one
    two-instance component); now they ride the rail and drag exactly as the pair does."""
    from ironbark_opt.aero.model import guide_drag
    from ironbark_opt.openrocket.build import load_ork_geometry
    text = _xml("01.One-stage_OR22.02.ork")
    lug = text[text.index("<launchlug>"):text.index("</launchlug>") + len("</launchlug>")]
    pair = _write(tmp_path, text.replace(lug, _BUTTONS.format(name="Buttons", n=2, x=0.05)), "pair.ork")
    single = _write(tmp_path, text.replace(lug, _BUTTONS.format(name="Aft", n=1, x=0.45)
                                           + _BUTTONS.format(name="Fore", n=1, x=0.05)), "single.ork")
    r2, r1 = load_ork_geometry(pair), load_ork_geometry(single)
    assert r2.rail_guides() is not None
    assert r1.rail_guides() == pytest.approx(r2.rail_guides(), abs=1e-12)
    area, mach, re = r2.reference_area(), 0.3, 7e6
    ca = [sum(float(d.CA(mach, re, area)) for d in guide_drag(r)[0]) for r in (r1, r2)]
    assert ca[1] > 0.0 and ca[0] == pytest.approx(ca[1], rel=1e-12)
