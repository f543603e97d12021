"""``[[airstart]]`` in the rocket TOML: a second motor lit in flight."""
from pathlib import Path

import numpy as np
import pytest

from ironbark_opt.errors import InputError
from ironbark_opt.flight import simulate
from ironbark_opt.motors import load_motor
from ironbark_opt.rocket.toml_io import loads_rocket_toml
from ironbark_opt.vehicle import setup_from_file

ROOT = Path(__file__).resolve().parents[2]
CALISTO = ROOT / "examples" / "calisto" / "calisto.toml"
AIRSTART = '\n[[airstart]]\nfile = "Cesaroni_M1670.eng"\nnozzle_x = 2.533\nignition_time = 5.0\n'


def test_airstart_motor_adds_its_thrust_and_mass():
    base = setup_from_file(loads_rocket_toml(CALISTO.read_text(), CALISTO))
    two = setup_from_file(loads_rocket_toml(CALISTO.read_text() + AIRSTART, CALISTO))
    extra = load_motor(CALISTO.parent / "Cesaroni_M1670.eng", "M1670")       # the file's own masses
    for t in (0.0, 2.0, 4.5, 5.5, 7.0, 9.0):
        assert float(two.motor.thrust(t)) == pytest.approx(float(base.motor.thrust(t)) + float(extra.thrust(t - 5.0)))
        assert float(two.motor.mass(t)) == pytest.approx(float(base.motor.mass(t)) + float(extra.mass(t - 5.0)))
        # CG of the two motors on the rocket axis (both nozzles at 2.533 m)
        m1, m2 = float(base.motor.mass(t)), float(extra.mass(t - 5.0))
        x = (m1 * (2.533 - float(base.motor.cg(t))) + m2 * (2.533 - float(extra.cg(t - 5.0)))) / (m1 + m2)
        assert 2.533 - float(two.motor.cg(t)) == pytest.approx(x)
    assert two.motor.events == pytest.approx((base.motor.burn_time, 5.0))
    assert two.motor.total_impulse == pytest.approx(base.motor.total_impulse + extra.total_impulse)
    f1, f2 = simulate(base), simulate(two)
    df = f2.to_dataframe()
    boundary = np.isclose(df["time_s"], 5.0).any()
    print(f"apogee {f1.apogee_agl:.1f} m -> {f2.apogee_agl:.1f} m with a second M1670 lit at 5 s; "
          f"a step boundary at the ignition: {boundary}")
    assert boundary and f2.apogee_agl > f1.apogee_agl + 1000.0


@pytest.mark.parametrize("section, message, field", [
    ('\n[[airstart]]\nfile = "Cesaroni_M1670.eng"\nnozzle_x = 2.533\n', "missing required key 'ignition_time'",
     "airstart[0].ignition_time"),
    ('\n[[airstart]]\nfile = "Cesaroni_M1670.eng"\nnozzle_x = 2.533\nignition_time = 0\n', "must be > 0 s",
     "airstart[0].ignition_time"),
    ('\n[[airstart]]\nfile = "nothere.eng"\nnozzle_x = 2.533\nignition_time = 2\n', "file not found", "airstart[0].file"),
    ('\n[[airstart]]\nfile = "Cesaroni_M1670.eng"\nnozzle_x = 2.533\nignition_time = 2\ndelay = 3\n',
     "unknown key 'delay'", "airstart[0].delay"),
])
def test_airstart_errors(section, message, field):
    text = CALISTO.read_text() + section
    with pytest.raises(InputError) as err:
        loads_rocket_toml(text, CALISTO)
    print(err.value)
    assert message in err.value.message and err.value.field == field and err.value.line is not None
