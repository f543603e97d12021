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


def _light_pair(tmp_path) -> Path:
    """A light two-stage rocket (85 mm, 2.3 kg sustainer on a 2.2 kg booster, an L640
    each): the sustainer's pitch mode at its Mach 1.4 burnout is stiffer than fixed
    0.02 s boost steps and 400 coast steps allow (a feature fuzz, session 20)."""
    motor = (DATA / "motors" / "Cesaroni_2772L640-P.eng").as_posix()
    fins = ('[[component]]\ntype = "trapezoidal_fins"\ncount = 4\nx = {x}\nthickness = 0.0038\n'
            'root_chord = 0.157\ntip_chord = 0.0785\nspan = 0.062\nsweep_length = 0.061\n')
    (tmp_path / "booster.toml").write_text(
        '[rocket]\nname = "light booster"\n[rocket.mass_override]\nmass = 2.168\ncg_x = 0.587\n'
        'I_transverse = 0.249\nI_axial = 0.002\n[[component]]\ntype = "body_tube"\nlength = 1.1744\n'
        f'radius = 0.0425\n{fins.format(x=1.0097)}[motor]\nfile = "{motor}"\nnozzle_x = 1.1744\n')
    path = tmp_path / "sustainer.toml"
    path.write_text(
        '[rocket]\nname = "light sustainer"\n[rocket.mass_override]\nmass = 2.338\ncg_x = 0.493\n'
        'I_transverse = 0.19\nI_axial = 0.0021\n[[component]]\ntype = "nose_cone"\nshape = "conical"\n'
        'length = 0.4256\nradius = 0.0425\n[[component]]\ntype = "body_tube"\nlength = 0.561\n'
        f'radius = 0.0425\n{fins.format(x=0.8255)}[[component]]\ntype = "rail_buttons"\nx_fore = 0.493\n'
        'x_aft = 0.789\nouter_diameter = 0.0124\nheight = 0.0142\n'
        f'[motor]\nfile = "{motor}"\nnozzle_x = 0.9866\n[launch]\nrail_length = 5.0\n'
        '[[stage]]\nfile = "booster.toml"\n')
    return path


@pytest.mark.filterwarnings("ignore::UserWarning")
def test_light_sustainer_grid_follows_its_stiffness(tmp_path):
    """The sustainer's boost and coast steps are chosen from the nominal flight's
    stiffness (StagedFlightModel._choose_sustainer_grid, the single-stage rule of
    dynamics/grid.py).  Before, this flight diverged in 6 coast steps (Mach 412) and was
    refused.  Reference: the same flight on 4x finer boost steps and 8x more coast steps
    (RK4's error falls 4th-order); bound 0.2 % of the apogee."""
    from ironbark_opt.dynamics.model import Steps
    from ironbark_opt.dynamics.staged import StagedFlightModel
    setup = load_setup(_light_pair(tmp_path))
    model = StagedFlightModel(setup)
    flight = simulate(setup, model=model)
    fine = simulate(setup, steps=Steps(dt_boost=0.005, n_coast=8 * model.n_scoast))
    s = flight.summary_values
    err = flight.apogee_agl / fine.apogee_agl - 1
    print(f"light two-stage: apogee {flight.apogee_agl:.2f} m (finer grid {fine.apogee_agl:.2f} m, "
          f"{100 * err:+.4f} %), max Mach {s['max_mach']:.3f}; sustainer steps boost {model.n_sboost}, "
          f"coast {model.n_scoast}")
    assert s["max_mach"] < 2.0 and model.n_scoast > 400
    assert abs(err) < 0.002
