"""Motor file readers: .eng, .rse, thrust CSV, load_motor; quirks and bad files."""
from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from ironbark_opt.errors import InputError
from ironbark_opt.motors import (SolidMotor, load_motor, read_eng, read_rse, read_thrust_csv,
                                 write_eng)

DATA = Path(__file__).resolve().parents[1] / "data" / "motors"
G0 = 9.80665

# fixtures rejected without extra data, and the keyword arguments that load them
NEEDS_DATA = {
    "Cesaroni_M1101.eng": dict(propellant_mass=3.0, dry_mass=2.5, diameter=0.075, length=0.757),
    "uwinrockets_Cesaroni_N3301.eng": dict(diameter=0.098, length=1.2),
    "uwinrockets_Cesaroni_N4100.eng": dict(diameter=0.098, length=1.2),
    "uwinrockets_Cesaroni_N5800.eng": dict(diameter=0.098, length=1.2),
}
ALL = sorted(p.name for p in DATA.iterdir() if p.suffix in (".eng", ".rse"))


def write(tmp_path, name, text, encoding="utf-8"):
    p = tmp_path / name
    p.write_bytes(text.encode(encoding))
    return p


# ------------------------------------------------------- every fixture
@pytest.mark.parametrize("name", ALL)
def test_every_fixture_loads_or_is_rejected_clearly(name):
    reader = read_eng if name.endswith(".eng") else read_rse
    if name in NEEDS_DATA:
        with pytest.raises(InputError) as exc:
            reader(DATA / name)
        msg = str(exc.value)
        print(msg)
        assert name in msg and exc.value.line == 1 and "length=..." in msg
        motors = reader(DATA / name, **NEEDS_DATA[name])
    else:
        motors = reader(DATA / name)
    assert motors and all(isinstance(m, SolidMotor) for m in motors)
    for m in motors:
        assert m.total_impulse > 0 and m.burn_time > 0 and m.dry_mass > 0
        assert m.source.endswith(name) and m.designation
        assert 50 < m.specific_impulse < 300      # plausible solid motors (C6 black powder ~61 s)


SHARED_MOTORS = Path(__file__).resolve().parents[3] / "shared" / "fixtures" / "motors"


@pytest.mark.skipif(not SHARED_MOTORS.is_dir(), reason="../shared is not beside this checkout")
def test_fixture_count_matches_shared_folder():
    """Every motor file of ../shared/fixtures/motors is copied into tests/data/motors."""
    assert {p.name for p in SHARED_MOTORS.glob("*.*") if p.suffix in (".eng", ".rse")} == set(ALL)


# ------------------------------------------------------- .eng quirks
def test_header_fields_units_and_delays():
    m = load_motor(DATA / "Cesaroni_M1670.eng")
    assert (m.designation, m.manufacturer) == ("M1670-BS", "CTI")
    assert m.diameter == pytest.approx(0.075) and m.length == pytest.approx(0.757)
    assert m.propellant_mass_initial == 3.101 and m.total_mass == pytest.approx(5.231)
    assert m.delays == (0.0,) and not m.plugged
    p = load_motor(DATA / "Cesaroni_2772L640-P.eng")
    assert p.delays == (math.inf,) and p.plugged
    assert load_motor(DATA / "AeroTech_L2200G.eng").delays == (0, 6, 10, 14, 18)


def test_multi_motor_file_placeholder_delays_and_selection():
    path = DATA / "RASAero_Motors_excerpt.eng"
    motors = read_eng(path)
    assert [m.designation for m in motors] == ["D9W", "D13W", "D15T"]
    assert [m.manufacturer for m in motors] == ["AT", "AT", "AT"]   # trailing space dropped
    assert motors[0].delays == (4.0, 7.0)
    assert load_motor(path, "d13w").designation == "D13W"
    assert load_motor(path, "D15").designation == "D15T"          # common name
    with pytest.raises(InputError, match="D9W, D13W, D15T"):
        load_motor(path)
    with pytest.raises(InputError, match="available: D9W, D13W, D15T"):
        load_motor(path, "M1670")
    assert load_motor(DATA / "Cesaroni_M1670.eng", "m1670").designation == "M1670-BS"


def test_placeholder_delay_1000_dropped(tmp_path):
    p = write(tmp_path, "x.eng", "X1 24 70 1000 0.01 0.03 AT\n0.1 10\n1 0\n")
    assert read_eng(p)[0].delays == ()


def test_byte_order_mark_headerless_file():
    m = load_motor(DATA / "Cesaroni_M1101.eng", **NEEDS_DATA["Cesaroni_M1101.eng"])
    assert m.designation == "M1101"
    assert float(np.asarray(m.time)[0]) == 0.0 and float(np.asarray(m.thrust)[0]) == 0.0
    assert m.thrust(0.05) == pytest.approx(1436.62)


def test_comment_after_data_and_last_line_comment():
    m = load_motor(DATA / "Cesaroni_M1670_shifted.eng")
    assert m.burn_time == 4.0 and np.asarray(m.thrust)[-1] == 0.0
    assert m.thrust(0.155) == pytest.approx(100.0)


def test_latin1_file(tmp_path):
    p = write(tmp_path, "l.eng", "; Moteur d\u00e9j\u00e0 test\u00e9\nX2 24 70 5 0.01 0.03 M\u00fcller\n0.1 10\n1 0\n",
              encoding="latin-1")
    assert read_eng(p)[0].manufacturer == "M\u00fcller"


def test_three_number_header_decision(tmp_path):
    """uwinrockets header = (Isp [s], propellant [kg], total [kg]), checked against the curve."""
    m = load_motor(DATA / "uwinrockets_Cesaroni_N3301.eng", diameter=0.098, length=1.2)
    assert m.designation == "N3301" and m.impulse_class == "N"
    assert m.propellant_mass_initial == 10.919 and m.dry_mass == pytest.approx(16.525 - 10.919)
    isp = m.total_impulse / (10.919 * G0)
    print(f"N3301: header Isp 185 s, from the curve {isp:.1f} s ({(isp / 185 - 1) * 100:+.1f} %)")
    assert abs(isp / 185 - 1) < 0.10
    bad = write(tmp_path, "odd.eng", "300 10.919 16.525\n0.1 4000\n5 0\n")
    with pytest.raises(InputError, match="does not fit the curve") as exc:
        read_eng(bad, diameter=0.098, length=1.2)
    assert exc.value.line == 1


def test_missing_overrides_for_thrust_table_formats_are_listed():
    with pytest.raises(InputError, match="pass propellant_mass=..., dry_mass=..., length=..."):
        read_eng(DATA / "Cesaroni_M1101.eng", diameter=0.075)


# ------------------------------------------------------- bad .eng files
BAD_ENG = {
    "truncated_header_only": ("; c\nM1 75 757 0 3.1 5.2 CTI\n", 2, "no thrust rows"),
    "truncated_row": ("M1 75 757 0 3.1 5.2 CTI\n0.1 100\n0.5 200\n0.9\n", 4, "truncated row"),
    "non_numeric_value": ("M1 75 757 0 3.1 5.2 CTI\n0.1 100\n0.5 abc\n1 0\n", 3, "'abc'"),
    "non_numeric_row": ("M1 75 757 0 3.1 5.2 CTI\n0.1 100\nfoo bar\n1 0\n", 3, "neither a data row"),
    "decreasing_time": ("M1 75 757 0 3.1 5.2 CTI\n0.1 100\n0.5 200\n0.3 150\n1 0\n", 4,
                        "time decreases"),
    "missing_header_fields": ("M1 75 757 0\n0.1 100\n1 0\n", 1, "missing: propellant_kg"),
    "bad_header_number": ("M1 75 long 0 3.1 5.2 CTI\n0.1 100\n1 0\n", 1, "'long'"),
    "total_below_propellant": ("M1 75 757 0 3.1 2.0 CTI\n0.1 100\n1 0\n", 1, "at least the propellant"),
    "bad_delay": ("M1 75 757 4-x 3.1 5.2 CTI\n0.1 100\n1 0\n", 1, "'x'"),
    "negative_thrust": ("M1 75 757 0 3.1 5.2 CTI\n0.1 -100\n1 0\n", 2, "negative thrust"),
    "all_zero": ("M1 75 757 0 3.1 5.2 CTI\n0.1 0\n1 0\n", 1, "zero total impulse"),
}


@pytest.mark.parametrize("case", sorted(BAD_ENG))
def test_bad_eng_files_name_file_and_line(tmp_path, case):
    text, line, fragment = BAD_ENG[case]
    p = write(tmp_path, f"{case}.eng", text)
    with pytest.raises(InputError) as exc:
        read_eng(p)
    print(exc.value)
    assert exc.value.source == str(p) and exc.value.line == line
    assert fragment in str(exc.value) and f"{case}.eng:{line}" in str(exc.value)


def test_empty_and_missing_files(tmp_path):
    with pytest.raises(InputError, match="no motor in file"):
        read_eng(write(tmp_path, "e.eng", "; only a comment\n\n"))
    with pytest.raises(InputError, match="not found"):
        load_motor(tmp_path / "nope.eng")
    with pytest.raises(InputError, match="unknown motor file type"):
        load_motor(write(tmp_path, "m.xyz", "1 2\n"))


def test_write_eng_round_trip(tmp_path):
    m = load_motor(DATA / "AeroTech_K828FJ.eng")
    p = tmp_path / "copy.eng"
    write_eng(m, p)
    m2 = load_motor(p)
    assert m2.designation == m.designation and m2.delays == m.delays
    assert m2.total_impulse == pytest.approx(m.total_impulse, rel=1e-6)
    assert m2.total_mass == pytest.approx(m.total_mass) and m2.length == pytest.approx(m.length)


# ------------------------------------------------------- .rse
def test_rse_example_and_eng_rse_agree():
    e18 = load_motor(DATA / "rse_motor_example_file.rse")
    assert (e18.designation, e18.manufacturer) == ("E18", "Aerotech")
    assert e18.propellant_mass_initial == pytest.approx(0.0207)
    assert e18.total_mass == pytest.approx(0.057) and e18.delays == (4.0, 8.0)
    assert e18.total_impulse == pytest.approx(39.78, rel=2e-3)       # file's Itot
    for code in ("K185W", "K550W"):
        eng = load_motor(DATA / f"tc_api_decoded_AeroTech_{code}.eng")
        rse = load_motor(DATA / f"tc_api_decoded_AeroTech_{code}.rse")
        err = abs(eng.total_impulse / rse.total_impulse - 1)
        print(f"{code}: .eng I = {eng.total_impulse:.1f}, .rse I = {rse.total_impulse:.1f} N s "
              f"({err * 100:.2f} %)")
        assert err < 0.025       # two different ThrustCurve.org data sets of one motor
    k185 = load_motor(DATA / "tc_api_decoded_AeroTech_K185W.rse")
    assert k185.total_impulse == pytest.approx(1378.58, rel=1e-4)
    assert k185.propellant_mass_initial == pytest.approx(0.827008)


RSE = """<engine-database><engine-list>
<engine code="T1" mfg="Test" dia="29." len="100." delays="P" propWt="{prop}" initWt="{init}"
 exitDia="{exit}" auto-calc-mass="{acm}" auto-calc-cg="{acg}" Itot="10">
<data>
<eng-data t="0" f="0" m="{m0}" cg="{cg0}"/>
<eng-data t="0.5" f="20" m="{m1}" cg="45"/>
<eng-data t="1.0" f="0" m="{m2}" cg="{cg2}"/>
</data></engine>
<engine code="T2" mfg="Test" dia="29." len="100." delays="4,6" propWt="10" initWt="30">
<data><eng-data t="0.5" f="20" m="10"/><eng-data t="1.0" f="0" m="0"/></data></engine>
</engine-list></engine-database>
"""


def rse(tmp_path, **kw):
    v = dict(prop="10", init="30", exit="0", acm="1", acg="1", m0="10", m1="5", m2="0",
             cg0="50", cg2="50")
    v.update(kw)
    return write(tmp_path, "t.rse", RSE.format(**v))


def test_rse_mass_column_propellant_or_total(tmp_path):
    motors = read_rse(rse(tmp_path))                        # m[0] = propWt: propellant
    assert [m.designation for m in motors] == ["T1", "T2"]
    assert motors[0].propellant_mass_initial == pytest.approx(0.010)
    assert motors[0].dry_mass == pytest.approx(0.020) and motors[0].plugged
    assert motors[1].delays == (4.0, 6.0)
    tot = read_rse(rse(tmp_path, acm="0", m0="30", m1="25", m2="18"))[0]   # m[0] = initWt
    assert tot.propellant_mass_initial == pytest.approx(0.012)
    assert tot.dry_mass == pytest.approx(0.018)
    with pytest.raises(InputError, match="neither propWt") as exc:
        read_rse(rse(tmp_path, m0="17"))
    assert exc.value.line == 5 and exc.value.field == "m"


def test_rse_cg_column_and_exit_area(tmp_path):
    m = read_rse(rse(tmp_path, acg="0", cg0="40", cg2="55", exit="20"))[0]
    # cg in mm from the forward end: dry 100 - 55 = 45 mm, loaded 60 mm from the nozzle
    assert m.dry_cg == pytest.approx(0.045)
    assert m.cg(0.0) == pytest.approx(0.060) and m.cg(2.0) == pytest.approx(0.045)
    assert m.nozzle_exit_area == pytest.approx(math.pi * 0.01 ** 2)


def test_rse_errors_name_line(tmp_path):
    p = write(tmp_path, "bad.rse", "<engine-database>\n<engine-list>\n<engine code='X'\n")
    with pytest.raises(InputError, match="not well-formed") as exc:
        read_rse(p)
    assert exc.value.line is not None
    p = write(tmp_path, "bad2.rse", RSE.replace('t="0.5" f="20" m="{m1}"', 't="1.5" f="20" m="{m1}"')
              .format(prop=10, init=30, exit=0, acm=1, acg=1, m0=10, m1=5, m2=0, cg0=50, cg2=50))
    with pytest.raises(InputError, match="time decreases") as exc:
        read_rse(p)
    assert exc.value.line == 7
    p = write(tmp_path, "bad3.rse", RSE.replace(' dia="29."', "", 1)
              .format(prop=10, init=30, exit=0, acm=1, acg=1, m0=10, m1=5, m2=0, cg0=50, cg2=50))
    with pytest.raises(InputError, match="missing attribute 'dia'") as exc:
        read_rse(p)
    assert exc.value.line == 2
    with pytest.raises(InputError, match="no <engine>"):
        read_rse(write(tmp_path, "empty.rse", "<engine-database/>"))


# ------------------------------------------------------- thrust CSV
MASS = dict(propellant_mass=0.5, dry_mass=0.7, diameter=0.038, length=0.3)


@pytest.mark.parametrize("text, scale_t, scale_f", [
    ("time_s,thrust_N\n0,0\n0.1,100\n1.0,80\n1.2,0\n", 1.0, 1.0),
    ("# bench test\nTime (s); Thrust [N]\n0;0\n0.1;100\n1.0;80\n1.2;0\n", 1.0, 1.0),
    ("t_ms\tthrust_lbf\n0\t0\n100\t100\n1000\t80\n1200\t0\n", 1e-3, 4.4482216152605),
    ("0 0\n0.1 100\n1.0 80\n1.2 0\n", 1.0, 1.0),
    ("pressure_psi,thrust,time\n1,0,0\n2,100,0.1\n3,80,1.0\n4,0,1.2\n", 1.0, 1.0),
])
def test_thrust_csv_formats(tmp_path, text, scale_t, scale_f):
    m = read_thrust_csv(write(tmp_path, "bench_K100.csv", text), **MASS)
    ref = np.trapezoid(np.array([0, 100, 80, 0]) * scale_f, np.array([0, 0.1, 1.0, 1.2]))
    assert m.total_impulse == pytest.approx(ref, rel=1e-12)
    assert m.designation == "K100" and m.propellant_mass_initial == 0.5


def test_thrust_csv_errors(tmp_path):
    p = write(tmp_path, "a.csv", "time_s,thrust_N\n0,0\n0.1,1x0\n1,0\n")
    with pytest.raises(InputError, match="'1x0'") as exc:
        read_thrust_csv(p, **MASS)
    assert exc.value.line == 3 and exc.value.field == "thrust"
    p = write(tmp_path, "b.csv", "seconds_since,kilonewtons\n0,0\n1,0\n")
    with pytest.raises(InputError, match="no time column") as exc:
        read_thrust_csv(p, **MASS)
    assert exc.value.line == 1
    p = write(tmp_path, "c.csv", "time_s,thrust_N\n0,0\n0.5,10\n0.4,10\n1,0\n")
    with pytest.raises(InputError, match="time decreases") as exc:
        read_thrust_csv(p, **MASS)
    assert exc.value.line == 4
    p = write(tmp_path, "d.csv", "time_s,thrust_N\n0,0\n0.5,10\n1,0\n")
    with pytest.raises(InputError, match="dry_mass, diameter"):
        read_thrust_csv(p, propellant_mass=0.1, length=0.3)
    with pytest.raises(InputError, match="no thrust data"):
        read_thrust_csv(write(tmp_path, "e.csv", "time_s,thrust_N\n"), **MASS)
    with pytest.raises(InputError, match="unknown motor field"):
        read_thrust_csv(p, **MASS, dry_masss=1.0)
    assert load_motor(p, **MASS).total_impulse == pytest.approx(5.0)
