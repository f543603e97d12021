"""Two OpenRocket stages that stay together to apogee fly as one rocket.

OpenRocket's example 'Deployable payload.ork' (tests/data/ork; OpenRocket commit
8fa969d8, stored flight data stripped, every summary kept): a motorless payload stage
on a booster that separates on the recovery charge (``ejection``), the American
Rocketry Challenge layout ('ARC payload rocket.ork' is the same with an F50T).  Up to
apogee it is one body with one motor, so every flight command flies the whole stack as
a single-stage rocket and ``aero build`` writes one table; before, such files were
refused ('needs a motor in each stage').  A booster that separates on its burnout
with nothing lit above it (a boosted dart) is two bodies and stays refused.

Measured (session 15): every stored simulation within -1.6 ... +0.3 % of the apogee
OpenRocket stored (A8-3 to C6-7)."""
import re
from pathlib import Path

import pytest

from ironbark_opt.errors import InputError
from ironbark_opt.flight import simulate
from ironbark_opt.openrocket import read_ork
from ironbark_opt.openrocket.staging import flies_as_one
from ironbark_opt.openrocket.xmlread import read_bytes
from ironbark_opt.vehicle import load_setup, load_stage_configurations

DATA = Path(__file__).parents[1] / "data"
ORK = DATA / "ork" / "Deployable payload.ork"


def test_stages_that_separate_on_ejection_are_one_body():
    doc = read_ork(ORK)
    assert len(doc.rocket.stages) == 2 and flies_as_one(doc)
    assert load_stage_configurations(ORK) is None         # aero build: one table


@pytest.mark.parametrize("index", [0, 1, 3, 4])
def test_every_stored_simulation_within_five_percent(index, ork_all_motors):
    doc = read_ork(ORK)
    sim = doc.simulations[index]
    setup = load_setup(ORK, config=sim.name, rail_exit="travel")     # OpenRocket: rod travel
    flight = simulate(setup)
    stored = sim.summary["apogee_m"]
    err = flight.apogee_agl / stored - 1
    print(f"{sim.name} ({setup.motor.designation}): apogee {flight.apogee_agl:.2f} m, "
          f"OpenRocket {stored:.2f} m ({100 * err:+.2f} %)")
    assert abs(err) < 0.05


def test_separation_on_burnout_without_an_upper_motor_is_refused(ork_all_motors, tmp_path):
    text = read_bytes(ORK).decode("utf-8")
    text = re.sub(r"<separationevent>ejection</separationevent>",
                  "<separationevent>burnout</separationevent>", text)
    dart = tmp_path / "dart.ork"
    dart.write_text(text, encoding="utf-8")
    assert not flies_as_one(read_ork(dart))
    with pytest.raises(InputError, match="needs a motor in each stage"):
        load_setup(dart)
