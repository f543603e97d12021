"""Serial stages in the rocket TOML ([[stage]]): a transcription of 'Two stage high
power rocket.ork' (tests/data/staged_toml, written by make_from_ork.py: geometry,
OpenRocket's mass build-up, motors, recovery and launch of its first simulation)
flies like the .ork itself, and its bad [[stage]] tables are refused by name."""
from pathlib import Path

import pytest

from ironbark_opt.dynamics.staged import StagedSetup
from ironbark_opt.errors import InputError
from ironbark_opt.flight import simulate
from ironbark_opt.openrocket import read_ork
from ironbark_opt.vehicle import load_setup

DATA = Path(__file__).parents[1] / "data"
ORK = DATA / "ork" / "Two stage high power rocket.ork"
TOML = DATA / "staged_toml" / "sustainer.toml"


pytestmark = pytest.mark.usefixtures("ork_offline")     # tests/conftest.py


@pytest.mark.filterwarnings("ignore::UserWarning")
def test_toml_transcription_flies_like_the_ork():
    sim = read_ork(ORK).simulations[0]
    ork = simulate(load_setup(ORK, config=sim.config_id, rail_exit="travel"))
    setup = load_setup(TOML, rail_exit="travel")
    assert isinstance(setup, StagedSetup) and setup.booster_name == "Booster"
    toml = simulate(setup)
    err = toml.apogee_agl / ork.apogee_agl - 1
    s, o = toml.summary_values, ork.summary_values
    print(f"TOML [[stage]] apogee {toml.apogee_agl:.2f} m, .ork {ork.apogee_agl:.2f} m ({100 * err:+.3f} %); "
          f"separation {s['separation_time_s']:.3f} s (.ork {o['separation_time_s']:.3f} s), booster apogee "
          f"{s['booster_apogee_agl_m']:.1f} m (.ork {o['booster_apogee_agl_m']:.1f} m), OpenRocket "
          f"{sim.summary['apogee_m']:.1f} m")
    assert abs(err) < 0.01                                           # the tolerance
    assert s["launch_mass_kg"] == pytest.approx(o["launch_mass_kg"], rel=1e-9)
    assert s["separation_time_s"] == pytest.approx(o["separation_time_s"], rel=1e-9)
    assert s["booster_apogee_agl_m"] == pytest.approx(o["booster_apogee_agl_m"], rel=0.01)


@pytest.mark.parametrize("stage, message, field", [
    ('[[stage]]\nname = "B"\n', "missing required key 'file'", "stage[0].file"),
    ('[[stage]]\nfile = "nothere.toml"\n', "file not found", "stage[0].file"),
    ('[[stage]]\nfile = "booster.toml"\nseparation_delay = -1\n', "must be >= 0 s", "stage[0].separation_delay"),
    ('[[stage]]\nfile = "booster.toml"\nignition = 3\n', "unknown key 'ignition'", "stage[0].ignition"),
    ('[[stage]]\nfile = "sustainer.toml"\n', "cannot be the file itself", "stage[0].file"),
])
def test_bad_stage_tables(tmp_path, stage, message, field):
    from ironbark_opt.rocket.toml_io import loads_rocket_toml
    text = TOML.read_text().split("[[stage]]")[0] + stage
    with pytest.raises(InputError) as err:
        loads_rocket_toml(text, TOML)
    print(err.value)
    assert message in err.value.message and err.value.field == field


def test_two_stage_tables_are_refused_until_supported(tmp_path):
    text = TOML.read_text() + '\n[[stage]]\nfile = "booster.toml"\n'
    path = TOML.parent / "sustainer.toml"
    from ironbark_opt.rocket.toml_io import loads_rocket_toml
    from ironbark_opt.staged_vehicle import staged_setup_from_toml
    rf = loads_rocket_toml(text, path)
    with pytest.raises(InputError, match="2 \\[\\[stage\\]\\] tables"):
        staged_setup_from_toml(rf)
