"""Parallel boosters (OpenRocket ``ParallelStage``) -> a flight setup (numeric-only).

A set of ``N`` identical boosters strapped around the core burns with the
core's motor from launch and separates on its own event (OpenRocket's stage
separation settings per configuration: the boosters' ``burnout`` or
``ejection`` (burnout + their motor's delay), plus the separation delay).
The sequence is fixed per configuration, so it flies as a
:class:`~ironbark_opt.dynamics.staged.StagedSetup` (``parallel=True``):

1. the stack (core + boosters): the core's dry mass plus the boosters'
   (:func:`ormass.parallel_instances`: N copies at the radial distance, their
   roll and pitch inertia by the parallel-axis theorem), the core motor and the
   N booster motors lit together (one
   :class:`~ironbark_opt.motors.composite.CompositeMotor`), the core's empirical
   aerodynamics plus the boosters' (:func:`with_boosters`), to the separation;
2. the core alone, its motor still burning, to its apogee (the answer);
3. one booster (all N follow the same path) from separation to the ground.

Without booster motors in a configuration, or with a separation event that
never fires (a plugged motor, ``never``), the boosters ride along the whole
flight: a single :class:`~ironbark_opt.dynamics.setup.FlightSetup` with their
mass and drag.

The boosters' aerodynamics are summed with the core's on the core's
reference area, each booster as a rocket of its own (OpenRocket's
BarrowmanCalculator treats every component instance the same way, Niskanen
2013 sec. 3.1): Barrowman normal force of its nose and fins (fin count x N),
skin friction of its wetted area, its nose and fin pressure drag
(:mod:`ironbark_opt.aero.empirical_drag`) and its base drag (with the motors'
jets while they burn).  Interference between booster and core is neglected,
as in OpenRocket; the boosters' fins are counted in the roll damping as if
they sat on the core's axis (roll does not enter the apogee).

With the tables of ``ironbark aero build`` (``simulate ROCKET.ork --table
STACK.csv``, :func:`flight_tables`), the stack, the core and the booster fly
their panel tables instead (:mod:`panair.parallel_table`: the same component
build-up, each booster panel-solved alone), the boosters' friction, damping
and jets added as above (:func:`with_booster_table`).
"""
from __future__ import annotations

import dataclasses
import math

import numpy as np

from ironbark_opt.errors import InputError
from ironbark_opt.openrocket import ormass
from ironbark_opt.openrocket.build import _IGNITE_AT_LAUNCH, _aero_table_path, _motor_spec, geometry, recovery
from ironbark_opt.openrocket.document import OrkDocument, nozzle_x
from ironbark_opt.rocket.specs import AeroSpec, BallastSpec, LaunchSpec, MotorSpec

#: separation events that follow the boosters' motors (OpenRocket ``StageSeparationConfiguration``)
_MOTOR_EVENTS = ("burnout", "ejection")
_NEVER = ("never",)


def separation(pod, config_id: str) -> tuple[str, float]:
    """(event, delay [s]) of the boosters' separation in a configuration."""
    table = pod.geo["separation"]
    return table.get(config_id, table[""])


def booster_document(doc: OrkDocument, pod, shift: float = 0.0) -> OrkDocument:
    """One booster of the set as a single-stage document, positions moved ``shift``
    [m] forward (``pod.x``: its own frame from its front end)."""
    def moved(c):
        return dataclasses.replace(c, x=c.x - shift, children=[moved(k) for k in c.children])

    stage = dataclasses.replace(pod, kind="stage", x=pod.x - shift, children=[moved(c) for c in pod.children])
    rocket = dataclasses.replace(doc.rocket, name=pod.name, stages=[stage], pods=[])
    return dataclasses.replace(doc, rocket=rocket)


def booster_rocket(doc: OrkDocument, pod):
    """The Rocket (geometry and dry mass) of one booster in its own frame (x from
    its front end, ``pod.x`` [m] aft of the core's nose tip)."""
    return geometry(booster_document(doc, pod, pod.x))


def _booster_lift_and_friction(aero, booster, count: int, x0: float, roughness: float):
    """(LiftGeometry, FrictionDrag) of ``aero`` with ``count`` boosters added: their
    Barrowman components (the damping sums; the normal force where no table gives
    it) and their skin friction, on the core's reference area."""
    from ironbark_opt.aero.friction import FrictionDrag
    from ironbark_opt.aero.model import LiftGeometry, friction_components, lift_geometry

    aref = aero.reference_area
    scale = count * booster.reference_area() / aref
    lg = lift_geometry(booster)
    bodies = tuple(b._replace(cn_alpha=b.cn_alpha * scale, x_cp=b.x_cp + x0, name=f"{b.name} x{count}")
                   for b in lg.bodies)
    fins = tuple(dataclasses.replace(f, count=f.count * count, x_root_le=f.x_root_le + x0) for f in lg.fins)
    plan_core, plan_b = aero.lift.planform_area, count * lg.planform_area
    lift = LiftGeometry(aero.lift.bodies + bodies, aero.lift.fins + fins, plan_core + plan_b,
                        (plan_core * aero.lift.planform_centroid_x + plan_b * (lg.planform_centroid_x + x0))
                        / (plan_core + plan_b), aero.lift.fineness_ratio)
    fr = aero.friction
    extra = tuple(dataclasses.replace(c, name=f"{booster.name} {c.name} x{count}", wetted_area=count * c.wetted_area)
                  for c in friction_components(booster, roughness))
    return lift, FrictionDrag(fr.components + extra, aref, fr.re_transition, protuberances=fr.protuberances)


def with_boosters(aero, booster, count: int, x0: float, *, roughness: float, jet_area: float = 0.0):
    """``aero`` (the core's :class:`~ironbark_opt.aero.model.AeroModel`, empirical
    table) plus ``count`` boosters of geometry ``booster`` (a Rocket in its own
    frame, its front end ``x0`` [m] aft of the core's nose tip), see the module
    docstring.

    Parameters
    ----------
    jet_area : float [m^2]
        Exit area of all the boosters' jets while they burn (0: unlit).
    """
    from ironbark_opt.aero.base_drag import BaseDrag
    from ironbark_opt.aero.empirical_drag import pressure_ca
    from ironbark_opt.aero.table import AeroTable

    aref = aero.reference_area
    scale = count * booster.reference_area() / aref
    lift, friction = _booster_lift_and_friction(aero, booster, count, x0, roughness)
    t = aero.table
    mach = t.mach
    r_base = float(booster.radius_at(booster.length()))
    base = BaseDrag(count * math.pi * r_base ** 2, aref, min(jet_area, count * math.pi * r_base ** 2))
    pressure = scale * pressure_ca(booster, mach)
    off = pressure + np.array([float(base.CA_power_off(M)) for M in mach])
    on = pressure + np.array([float(base.CA_power_on(M)) for M in mach])
    ca0 = t.values("CA")
    ca_on = t.values("CA_power_on") if t.has("CA_power_on") else ca0
    table = AeroTable(mach, t.alpha, {"CA": ca0 + off[:, None], "CA_power_on": ca_on + on[:, None]},
                      reference_area=t.reference_area, reference_length=t.reference_length,
                      moment_reference_x=t.moment_reference_x, includes=t.includes,
                      metadata={**t.metadata, "boosters": f"{count} x '{booster.name}': pressure and base drag "
                                "added (openrocket.parallel.with_boosters)"})
    return dataclasses.replace(aero, lift=lift, friction=friction, table=table)


def with_booster_table(aero, booster, count: int, x0: float, *, roughness: float, jet_area: float = 0.0):
    """``aero`` built on the stack's table from ``ironbark aero build`` (which holds
    the boosters' pressure and base drag, normal force and moment:
    :mod:`panair.parallel_table`) plus what a table leaves to the flight, for the
    boosters as for the core: their skin friction at the flight's Reynolds
    number, their fins in the damping sums, and their jets' share of their base
    taken off while the stack's motors burn (the table's base drag has no jet,
    Niskanen 2013 sec. 3.4.5; as :func:`with_boosters`)."""
    from ironbark_opt.aero.base_drag import BaseDrag

    lift, friction = _booster_lift_and_friction(aero, booster, count, x0, roughness)
    r_base = float(booster.radius_at(booster.length()))
    jet = min(jet_area, count * math.pi * r_base ** 2)
    relief = aero.jet_relief
    if jet > 0 and "base" in aero.includes:
        core_jet = relief.base_area if relief is not None else 0.0
        relief = BaseDrag(core_jet + jet, aero.reference_area,
                          model=aero.table.metadata.get("base_drag_model", "mccoy"))
    return dataclasses.replace(aero, lift=lift, friction=friction, jet_relief=relief)


def flight_tables(table, doc: OrkDocument) -> dict:
    """``{"stack", "core", "booster"}`` -> table path of a rocket with parallel
    boosters, from the stack's table ``table`` that ``ironbark aero build`` wrote
    (its metadata ``parallel_boosters`` names the other two, beside it)."""
    import json
    from pathlib import Path
    stem = Path(table)
    stem = stem.with_suffix("") if stem.suffix.lower() in (".csv", ".json") else stem
    meta_path = Path(f"{stem}.json")
    if not Path(f"{stem}.csv").exists() or not meta_path.exists():
        raise InputError("aerodynamic table not found (expected the .csv and .json written by 'ironbark aero "
                         "build')", source=table, field="table")
    try:
        info = json.loads(meta_path.read_text()).get("parallel_boosters")
    except (OSError, ValueError, AttributeError) as err:
        raise InputError(f"cannot read the table's metadata: {err}", source=meta_path, field="table") from None
    pod = single_booster_set(doc)
    if not isinstance(info, dict):
        raise InputError(f"this table has no parallel boosters; '{doc.path.name}' flies with '{pod.name}': give "
                         "the stack's table that 'ironbark aero build' wrote for it", source=meta_path,
                         field="table")
    if info.get("set") != pod.name or info.get("count") != pod.geo["instances"]:
        raise InputError(f"the table was built for {info.get('count')} x '{info.get('set')}', the rocket has "
                         f"{pod.geo['instances']} x '{pod.name}'", source=meta_path, field="parallel_boosters")
    out = {"stack": Path(f"{stem}.csv")}
    for key in ("core", "booster"):
        name = info.get(f"{key}_table")
        path = meta_path.parent / str(name)
        if not name or not path.with_suffix(".csv").exists():
            raise InputError(f"the {key}'s table {name!r} named by the stack's is not beside it",
                             source=meta_path, field=f"parallel_boosters.{key}_table")
        out[key] = path.with_suffix(".csv")
    return out


def single_booster_set(doc: OrkDocument):
    """The one set of parallel boosters on a single core stage (InputError otherwise)."""
    if len(doc.rocket.stages) > 1:
        raise InputError("parallel boosters on a rocket with serial stages are not supported yet",
                         source=doc.path, field=doc.rocket.stages[1].path)
    if len(doc.rocket.pods) > 1:
        raise InputError("more than one set of parallel boosters is not supported yet", source=doc.path,
                         field=doc.rocket.pods[1].path)
    return doc.rocket.pods[0]


def _mounts(doc: OrkDocument, cfg, pod):
    core = [(m, e) for m, e in cfg.motors if m.stage == 0]
    boost = [(m, e) for m, e in cfg.motors if m.stage == pod.stage]
    if len(core) != 1:
        raise InputError(f"configuration {cfg.label()} needs exactly one motor mount in the core with "
                         f"parallel boosters (has {len(core)})", source=doc.path, field="motorconfiguration")
    if len(boost) > 1:
        raise InputError(f"two motor mounts in the boosters '{pod.name}' are not supported yet",
                         source=doc.path, field=boost[1][0].path)
    for mount, entry in core + boost:
        if entry.ignition_event not in _IGNITE_AT_LAUNCH or entry.ignition_delay > 0:
            raise InputError(f"motor {entry.designation} in '{mount.name}' must ignite at launch with parallel "
                             f"boosters (it is '{entry.ignition_event}' + {entry.ignition_delay:g} s)",
                             source=doc.path, field=mount.path)
    return core[0], (boost[0] if boost else None)


def _booster_spec(doc, mount, entry, count: int) -> MotorSpec:
    """The N boosters' motors as one cluster motor on the axis."""
    from ironbark_opt.openrocket.build import cluster_motor_file
    from ironbark_opt.openrocket.motors import find_motor_file
    found = find_motor_file(entry.designation, entry.manufacturer, doc.path, entry.digest)
    n = count * mount.cluster_count
    path, designation = (found.path, found.motor.designation) if n == 1 else \
        cluster_motor_file(found.path, found.motor, n)
    return MotorSpec(file=path, designation=designation, nozzle_x=nozzle_x(mount, entry))


def parallel_setup(doc: OrkDocument, config: str | None = None, *, tables: dict | None = None, **setup_kwargs):
    """The flight setup of a configuration of a rocket with parallel boosters:
    a StagedSetup when they separate, else a FlightSetup carrying them.

    ``tables`` (:func:`flight_tables`): fly the stack, the core and the booster on
    the tables ``ironbark aero build`` wrote instead of the empirical estimate."""
    from ironbark_opt.aero.tumble import tumble_cd_area
    from ironbark_opt.dynamics.staged import StagedSetup
    from ironbark_opt.motors.composite import DelayedMotor
    from ironbark_opt.rocket.toml_io import RocketFile
    from ironbark_opt.vehicle import jet_area_of, load_motor_for, setup_from_file

    pod = single_booster_set(doc)
    count = pod.geo["instances"]
    cfg, sim = doc.config_and_simulation(config)
    (m_c, e_c), booster_motor = _mounts(doc, cfg, pod)
    event, delay = separation(pod, cfg.config_id)
    if event not in _MOTOR_EVENTS + _NEVER:
        raise InputError(f"booster separation on '{event}' is not supported yet (only the boosters' burnout "
                         f"or ejection + delay)", source=doc.path, field=pod.path)
    separates = booster_motor is not None and event in _MOTOR_EVENTS and not (
        event == "ejection" and booster_motor[1].delay is None)
    launch = sim.launch if sim is not None else LaunchSpec()
    spec_c = _motor_spec(doc, m_c, e_c)
    spec = spec_c
    if booster_motor is not None:
        spec_b = _booster_spec(doc, *booster_motor, count)
        spec = dataclasses.replace(spec_c, airstart=((spec_b, 0.0),))
    rocket = geometry(doc)                               # the core; mass with the boosters
    chutes = () if separates else recovery(doc, cfg.config_id)
    aero_spec = AeroSpec(table=tables["stack"] if tables else _aero_table_path(rocket, dataclasses.replace(
        doc, path=doc.path.with_name(f"{doc.path.stem}-stack{doc.path.suffix}"))))
    stack = setup_from_file(RocketFile(rocket, spec, aero_spec, launch, chutes, BallastSpec(), doc.path),
                            **setup_kwargs)
    jet = 0.0
    if booster_motor is not None:
        # each booster motor's exit (or cross-section, OpenRocket's rule) x the number of motors
        jet = jet_area_of(load_motor_for(spec_b))[0] * count * booster_motor[0].cluster_count
    add = with_booster_table if tables else with_boosters
    stack = dataclasses.replace(stack, aero=add(stack.aero, booster_rocket(doc, pod), count, pod.x,
                                                roughness=aero_spec.surface_roughness, jet_area=jet),
                                name=f"{doc.name} (with {pod.name})" if separates else doc.name)
    if not separates:
        return stack
    # the core after separation: its own dry mass, its motor still burning
    core = rocket.with_mass_override(ormass.rocket_mass(doc.rocket.stages, parallel=False))
    aero_c = AeroSpec(table=tables["core"] if tables else _aero_table_path(core, dataclasses.replace(
        doc, path=doc.path.with_name(f"{doc.path.stem}-core{doc.path.suffix}"))))
    sustainer = setup_from_file(RocketFile(core, spec_c, aero_c, launch, recovery(doc, cfg.config_id),
                                           BallastSpec(), doc.path), **setup_kwargs)
    sustainer = dataclasses.replace(sustainer, motor=DelayedMotor(sustainer.motor, 0.0), name=doc.name)
    t_burn_b = float(load_motor_for(_motor_spec(doc, *booster_motor)).burn_time)
    total_delay = float(delay) + (float(booster_motor[1].delay) if event == "ejection" else 0.0)
    if t_burn_b + total_delay >= float(sustainer.motor.burn_time):
        raise InputError(f"the boosters separate at {t_burn_b + total_delay:.3f} s, after the core's burnout "
                         f"({float(sustainer.motor.burn_time):.3f} s): not supported yet", source=doc.path,
                         field=pod.path)
    # one booster in its own frame (x from its front end), its spent motor aboard
    one = booster_rocket(doc, pod)
    spec_one = dataclasses.replace(_motor_spec(doc, *booster_motor), nozzle_x=spec_b.nozzle_x - pod.x)
    b_doc = booster_document(doc, pod, shift=pod.x)
    aero_b = AeroSpec(table=tables["booster"] if tables else _aero_table_path(one, dataclasses.replace(
        b_doc, path=doc.path.with_name(f"{doc.path.stem}-booster{doc.path.suffix}"))))
    booster = setup_from_file(RocketFile(one, spec_one, aero_b, launch, recovery(b_doc, cfg.config_id),
                                         BallastSpec(), doc.path), **setup_kwargs)
    booster = dataclasses.replace(booster, name=f"{doc.name} ({pod.name})")
    return StagedSetup(stack, sustainer, total_delay, pod.name, doc.rocket.stages[0].name,
                       booster=booster, booster_x=pod.x, booster_burnout=t_burn_b, parallel=True,
                       booster_tumble_cd_area=tumble_cd_area(one))
