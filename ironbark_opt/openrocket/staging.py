"""Serial two-stage OpenRocket designs -> :class:`~ironbark_opt.dynamics.staged.StagedSetup`.

Supported (numeric-only reading): two axial stages; the booster's motor lit at
launch; the sustainer's motor lit at the booster's ``burnout`` + delay; the
booster separating at ``burnout`` or ``upperignition`` + the same delay
(OpenRocket's stage separation settings, per configuration).  Each stage has
its own geometry, dry mass (OpenRocket's component rules), aerodynamics (the
empirical pressure-drag estimate of its own geometry plus friction and base
drag, or the stack's and sustainer's panel tables from ``ironbark aero build``,
:mod:`ironbark_opt.openrocket.stage_tables`) and recovery.  Not yet: more than two stages, ignition/separation by
altitude or time, parallel boosters (refused with InputError).
"""
from __future__ import annotations

import dataclasses

from ironbark_opt.errors import InputError
from ironbark_opt.openrocket import ormass
from ironbark_opt.openrocket.build import (_IGNITE_AT_LAUNCH, _aero_table_path, _motor_spec, geometry,
                                           recovery)
from ironbark_opt.openrocket.document import OrkDocument
from ironbark_opt.rocket.specs import AeroSpec, BallastSpec, LaunchSpec

_UPPER_EVENTS = ("burnout",)
_SEPARATION_EVENTS = ("burnout", "upperignition")


def stage_events(doc: OrkDocument, config) -> dict:
    """Ignition and separation settings of ``config`` for a two-stage rocket.

    Returns dict: ``booster`` / ``sustainer`` (mount, MotorEntry) and
    ``delay`` [s] (sustainer ignition and separation after booster burnout).
    """
    if len(doc.rocket.stages) != 2:
        raise InputError(f"{len(doc.rocket.stages)} stages: two-stage rockets are supported so far",
                         source=doc.path, field=doc.rocket.stages[-1].path)
    by_stage = {}
    for mount, entry in config.motors:
        if mount.stage in by_stage:
            raise InputError(f"two motor mounts in stage {mount.stage} of a staged rocket are not supported yet",
                             source=doc.path, field=mount.path)
        by_stage[mount.stage] = (mount, entry)
    if set(by_stage) != {0, 1}:
        raise InputError(f"configuration {config.label()} needs a motor in each stage", source=doc.path,
                         field="motorconfiguration")
    (m_s, e_s), (m_b, e_b) = by_stage[0], by_stage[1]
    if e_b.ignition_event not in _IGNITE_AT_LAUNCH or e_b.ignition_delay > 0:
        raise InputError(f"the booster's motor must ignite at launch (it is '{e_b.ignition_event}' + "
                         f"{e_b.ignition_delay:g} s)", source=doc.path, field=m_b.path)
    if e_s.ignition_event not in _UPPER_EVENTS:
        raise InputError(f"sustainer ignition on '{e_s.ignition_event}' is not supported yet (only the "
                         f"booster's burnout + delay)", source=doc.path, field=m_s.path)
    booster = doc.rocket.stages[1]
    event, delay = _separation(booster, config.config_id)
    if event not in _SEPARATION_EVENTS:
        raise InputError(f"separation on '{event}' is not supported yet (only burnout or upper-stage "
                         f"ignition)", source=doc.path, field=booster.path)
    if abs(delay - e_s.ignition_delay) > 1e-9:
        raise InputError(f"separation {delay:g} s and sustainer ignition {e_s.ignition_delay:g} s after "
                         "burnout differ; equal delays are supported so far", source=doc.path, field=booster.path)
    return {"booster": (m_b, e_b), "sustainer": (m_s, e_s), "delay": float(delay), "separation_event": event}


#: separation events that come at or after the recovery charge: to apogee the stack is one body
_LATE_SEPARATION = ("ejection", "never")


def flies_as_one(doc: OrkDocument, config=None) -> bool:
    """True when the stages of a multi-stage design stay together up to apogee in
    ``config`` (default: in every configuration that has a motor): each lower stage
    separates on the recovery charge (``ejection``) or ``never``, or on the ignition of
    the stage above it when that stage has no motor (OpenRocket then never separates
    it).  The American Rocketry Challenge layout (a motorless payload stage above a
    booster that separates on ejection, OpenRocket's 'ARC payload rocket') is one rocket
    to apogee.  Parallel boosters never count (numeric-only)."""
    if len(doc.rocket.stages) < 2 or doc.rocket.pods:
        return False
    configs = [config] if config is not None else [c for c in doc.configs if c.motors]
    if not configs:
        return False
    for cfg in configs:
        lit = {mount.stage for mount, _ in cfg.motors}
        for i, stage in enumerate(doc.rocket.stages[1:], start=1):
            event, _ = _separation(stage, cfg.config_id)
            if event in _LATE_SEPARATION or (event == "upperignition" and i - 1 not in lit):
                continue
            return False
    return True


def _separation(stage, config_id: str) -> tuple[str, float]:
    el = stage.element
    event, delay = (el.text("separationevent") or "upperignition").lower(), el.number("separationdelay", 0.0)
    for c in el.children("separationconfiguration"):
        if c.attr("configid", "") == config_id:
            event = (c.text("separationevent") or event).lower()
            delay = c.number("separationdelay", delay)
    return event, float(delay)


def _stage_doc(doc: OrkDocument, stages) -> OrkDocument:
    """A view of ``doc`` with only ``stages`` (indices)."""
    rocket = dataclasses.replace(doc.rocket, stages=[doc.rocket.stages[i] for i in stages])
    return dataclasses.replace(doc, rocket=rocket)


def _shifted(comp, dx: float):
    """``comp`` and its subtree moved ``dx`` [m] forward (positions are absolute)."""
    return dataclasses.replace(comp, x=comp.x - dx, children=[_shifted(c, dx) for c in comp.children])


def booster_file(doc: OrkDocument, cfg, spec_b, launch):
    """The booster alone after separation (its spent motor aboard) as a RocketFile in
    its own frame: x from the booster's front end; ``x0`` [m aft of the stack's nose
    tip] returned with it."""
    from ironbark_opt.rocket.toml_io import RocketFile

    stage = doc.rocket.stages[1]
    x0 = stage.x
    sub = dataclasses.replace(doc, rocket=dataclasses.replace(doc.rocket, stages=[_shifted(stage, x0)]))
    rocket = geometry(sub)
    aero = AeroSpec(table=_aero_table_path(rocket, dataclasses.replace(
        sub, path=doc.path.with_name(f"{doc.path.stem}-booster{doc.path.suffix}"))))
    spec = dataclasses.replace(spec_b, nozzle_x=spec_b.nozzle_x - x0)
    return RocketFile(rocket, spec, aero, launch, recovery(sub, cfg.config_id), BallastSpec(), doc.path), x0


def staged_setup(doc: OrkDocument, config: str | None = None, *, tables: dict | None = None,
                 **setup_kwargs):
    """The :class:`StagedSetup` of a two-stage .ork configuration (numeric-only;
    assembled by :func:`ironbark_opt.staged_vehicle.assemble_two_stage`).

    ``tables``: the stack's and the sustainer's AeroTable paths by configuration
    (``{"stack": ..., "sustainer": ...}``, from ``ironbark aero build``;
    :func:`ironbark_opt.openrocket.stage_tables.tables_by_configuration`) replacing
    the empirical estimate of their geometry; the separated booster keeps its own."""
    from ironbark_opt.rocket.toml_io import RocketFile
    from ironbark_opt.staged_vehicle import assemble_two_stage

    cfg, sim = doc.config_and_simulation(config)
    ev = stage_events(doc, cfg)
    spec_b, spec_s = _motor_spec(doc, *ev["booster"]), _motor_spec(doc, *ev["sustainer"])
    launch = sim.launch if sim is not None else LaunchSpec()
    files = {}
    for key, stages, spec in (("stack", (0, 1), spec_b), ("sustainer", (0,), spec_s)):
        sub = _stage_doc(doc, stages)
        rocket = geometry(sub).with_mass_override(ormass.rocket_mass(sub.rocket.stages))
        chutes = tuple(r for r in recovery(_stage_doc(doc, (0,)), cfg.config_id)) if key == "sustainer" else ()
        aero = AeroSpec(table=tables[key] if tables else _aero_table_path(rocket, dataclasses.replace(
            sub, path=doc.path.with_name(f"{doc.path.stem}-{key}{doc.path.suffix}"))))
        files[key] = RocketFile(rocket, spec, aero, launch, chutes, BallastSpec(), doc.path)
    booster, x0 = booster_file(doc, cfg, spec_b, launch)
    return assemble_two_stage(files["stack"], files["sustainer"], booster, delay=ev["delay"], booster_x=x0,
                              name=doc.name, booster_name=doc.rocket.stages[1].name,
                              sustainer_name=doc.rocket.stages[0].name, **setup_kwargs)
