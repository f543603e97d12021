"""Transcribe 'Two stage high power rocket.ork' (its first simulation's configuration,
H148R + H148R) into rocket TOML: sustainer.toml (the upper stage, with a
[[stage]] naming booster.toml) and booster.toml (the lower stage in its own
frame).  Geometry, OpenRocket's mass build-up (as [rocket.mass_override]),
recovery and launch conditions come from the .ork through Ironbark's importer;
no aerodynamic data is given (the empirical estimate of each geometry, as the
.ork path flies).  Run from the repository root:
    IRONBARK_OFFLINE=1 IRONBARK_MOTOR_PATH=tests/data/ork/motors python tests/data/staged_toml/make_from_ork.py
"""
import dataclasses
from pathlib import Path

from ironbark_opt.openrocket import read_ork, ormass
from ironbark_opt.openrocket.build import _motor_spec, geometry, recovery
from ironbark_opt.openrocket.staging import _shifted, _stage_doc, stage_events
from ironbark_opt.rocket.specs import AeroSpec, BallastSpec
from ironbark_opt.rocket.toml_io import RocketFile
from ironbark_opt.rocket.toml_write import to_toml

HERE = Path(__file__).parent
doc = read_ork(HERE.parent / "ork" / "Two stage high power rocket.ork")
sim = doc.simulations[0]
cfg = doc.config(sim.config_id)
ev = stage_events(doc, cfg)
sus_doc = _stage_doc(doc, (0,))
sus = RocketFile(geometry(sus_doc).with_mass_override(ormass.rocket_mass(sus_doc.rocket.stages)),
                 _motor_spec(doc, *ev["sustainer"]), AeroSpec(), sim.launch, recovery(sus_doc, cfg.config_id),
                 BallastSpec(), HERE / "sustainer.toml")
stage = doc.rocket.stages[1]
b_doc = dataclasses.replace(doc, rocket=dataclasses.replace(doc.rocket, stages=[_shifted(stage, stage.x)]))
spec_b = _motor_spec(doc, *ev["booster"])
boo = RocketFile(geometry(b_doc), dataclasses.replace(spec_b, nozzle_x=spec_b.nozzle_x - stage.x), AeroSpec(),
                 sim.launch, recovery(b_doc, cfg.config_id), BallastSpec(), HERE / "booster.toml")
head = "# Transcribed from 'Two stage high power rocket.ork' by make_from_ork.py\n"
stage_table = f'\n[[stage]]\nname = "{stage.name}"\nfile = "booster.toml"\nseparation_delay = {ev["delay"]}\n'
(HERE / "sustainer.toml").write_text(head + to_toml(sus, HERE) + stage_table)
(HERE / "booster.toml").write_text(head + to_toml(boo, HERE))
