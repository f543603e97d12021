"""``deploy = "ejection"`` and ``[motor] ejection_delay`` in the rocket TOML: the
chute opens at burnout + delay, before apogee (lower apogee, a warning saying
how early) or after it (a free fall first, a warning saying how late)."""
from pathlib import Path

import numpy as np
import pytest

from ironbark_opt.errors import InputError
from ironbark_opt.flight import simulate
from ironbark_opt.rocket.toml_io import loads_rocket_toml
from ironbark_opt.vehicle import setup_from_file

ROOT = Path(__file__).resolve().parents[2]
CALISTO = ROOT / "examples" / "calisto" / "calisto.toml"
CHUTE = '\n[[recovery]]\nname = "drogue"\ncd_area = 1.0\ndeploy = "ejection"\n'


def _setup(motor_extra="", recovery=CHUTE, motor_file=None):
    text = CALISTO.read_text()
    if motor_file is not None:
        text = text.replace('file = "Cesaroni_M1670.eng"', f'file = "{motor_file}"')
    text = text.replace('nozzle_x = 2.533                   # nozzle exit, m aft of the nose tip',
                        "nozzle_x = 2.533\n" + motor_extra, 1)
    return setup_from_file(loads_rocket_toml(text + recovery, CALISTO))


def test_early_charge_lowers_apogee_and_warns():
    base = simulate(_setup(recovery=""))
    with pytest.warns(UserWarning, match=r"fires \d+\.\d+ s before apogee"):
        early = simulate(_setup("ejection_delay = 8.0\n"))
    s = early.summary_values
    t_e = base.summary_values["burnout_time_s"] + 8.0
    print(f"\nCalisto: apogee {base.apogee_agl:.1f} m at {base.apogee_time:.2f} s; charge at {t_e:.2f} s -> "
          f"apogee {early.apogee_agl:.1f} m at {early.apogee_time:.2f} s")
    assert s["ejection_time_s"] == pytest.approx(t_e)
    assert s["ejection_before_apogee_s"] == pytest.approx(base.apogee_time - t_e, abs=1e-6)
    assert s["coasting_apogee_agl_m"] == pytest.approx(base.apogee_agl, abs=1e-6)
    assert t_e < early.apogee_time < base.apogee_time and early.apogee_agl < base.apogee_agl
    df = early.to_dataframe()
    ej = df[df["phase"] == "ejected"]
    assert ej["time_s"].min() > t_e and ej["time_s"].max() == pytest.approx(early.apogee_time)
    # the altitude gained after the charge is below the coasting climb's v^2 / 2g
    v_e = s["ejection_speed_mps"]
    assert 0 < early.apogee_agl - s["ejection_altitude_agl_m"] < v_e ** 2 / (2 * 9.78)


def test_late_charge_free_falls_first_and_warns():
    base = simulate(_setup(recovery=""))
    delay = base.apogee_time - base.summary_values["burnout_time_s"] + 6.0
    with pytest.warns(UserWarning, match=r"fires 6\.00 s after apogee"):
        late = simulate(_setup(f"ejection_delay = {delay}\n"), descent=True)
    assert late.apogee_agl == pytest.approx(base.apogee_agl, abs=1e-6)
    df = late.to_dataframe()
    chute = df[df["phase"] == "descent"]
    t_e = base.apogee_time + 6.0
    assert chute["time_s"].min() >= t_e - 1e-9
    # free fall from apogee: after 6 s it falls at nearly g * 6 s (drag reduces it)
    fall = df[np.isclose(df["time_s"], t_e, atol=1e-6)]
    vz = float(fall["vz_l_mps"].iloc[0])
    print(f"\nfalling at {vz:.1f} m/s when the charge fires 6 s after apogee")
    assert -6.0 * 9.8 < vz < -0.5 * 6.0 * 9.8


def test_delay_from_the_motor_file():
    """No ejection_delay: the motor file's single delay (the M1670's 0 s: at burnout)."""
    with pytest.warns(UserWarning, match="before apogee"):
        flight = simulate(_setup())
    assert flight.summary_values["ejection_delay_s"] == 0.0
    assert flight.summary_values["ejection_time_s"] == pytest.approx(flight.summary_values["burnout_time_s"])


def test_several_file_delays_need_a_choice():
    """A motor offering 0-3-5 s (WECO C6): the file must say which one was fitted."""
    c6 = (ROOT / "tests" / "data" / "ork" / "motors" / "WECO_C6.eng").as_posix()
    text = CALISTO.read_text().replace('file = "Cesaroni_M1670.eng"', f'file = "{c6}"').replace(
        'designation = "M1670"', 'designation = "C6"')
    text = text[:text.index("[motor.overrides]")] + text[text.index("[aero]"):]
    with pytest.raises(InputError) as err:
        setup_from_file(loads_rocket_toml(text + CHUTE, CALISTO))
    print(err.value)
    assert err.value.field == "motor.ejection_delay" and "0, 3, 5 s" in err.value.message


@pytest.mark.parametrize("extra, recovery, field, message", [
    ("ejection_delay = -1.0\n", CHUTE, "motor.ejection_delay", "must be >= 0"),
    ("", CHUTE.replace('"ejection"', '"burnout"'), "recovery[0].deploy", "deploy must be"),
])
def test_bad_keys(extra, recovery, field, message):
    with pytest.raises(InputError) as err:
        _setup(extra, recovery)
    e = err.value
    print(e)
    assert e.field == field and message in e.message and e.line is not None


def test_ork_delay_survives_conversion_to_toml(tmp_path, monkeypatch):
    """.ork configuration [C6-3] -> TOML: the 3 s delay and the ejection deployment are kept."""
    from ironbark_opt.openrocket import load_ork
    from ironbark_opt.rocket import dump_rocket_toml
    from ironbark_opt.rocket.toml_io import load_rocket_toml

    data = ROOT / "tests" / "data" / "ork"
    monkeypatch.setenv("IRONBARK_OFFLINE", "1")
    monkeypatch.setenv("IRONBARK_CACHE_DIR", str(tmp_path / "cache"))
    monkeypatch.setenv("IRONBARK_MOTOR_PATH", str(data / "motors"))
    rf = load_ork(data / "A simple model rocket.ork", config="[C6-3]")
    assert rf.motor.ejection_delay == 3.0 and [r.deploy for r in rf.recovery] == ["ejection"]
    back = load_rocket_toml(dump_rocket_toml(rf, tmp_path / "simple.toml"))
    assert back.motor.ejection_delay == 3.0 and [r.deploy for r in back.recovery] == ["ejection"]
