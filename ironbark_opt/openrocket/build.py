"""From an :class:`OrkDocument` to a flyable :class:`RocketFile` (numeric-only).

What can be flown today: one axial stage per configuration; its motor
mounts ignite at launch or after a delay (air-start, flown as one
:class:`~ironbark_opt.motors.composite.CompositeMotor`); a cluster in a
mount flies as one equivalent motor (:func:`cluster_motor_file`).
Multi-stage separation and parallel boosters/pods are rejected with an
InputError naming the component.
"""
from __future__ import annotations

import dataclasses
import hashlib
import math
import warnings
from pathlib import Path

import numpy as np

from ironbark_opt.errors import InputError
from ironbark_opt.openrocket import convert
from ironbark_opt.openrocket.components import FINS
from ironbark_opt.openrocket.document import OrkDocument, nozzle_x, read_ork
from ironbark_opt.openrocket.motors import find_motor_file
from ironbark_opt.rocket.hardware import LaunchLug, RailButtons, TubeFins
from ironbark_opt.rocket.rocket import Rocket
from ironbark_opt.rocket.specs import AeroSpec, BallastSpec, LaunchSpec, MotorSpec, RecoverySpec

#: OpenRocket's default parachute drag coefficient (``Parachute.DEFAULT_CD``)
PARACHUTE_CD = 0.8
#: drag coefficient assumed for a streamer on its strip area when the file says ``auto``
STREAMER_CD = 0.6
_IGNITE_AT_LAUNCH = ("automatic", "launch", "ignition")


def _single_stage(doc: OrkDocument, what: str, instead: str,
                  pods: str = "cannot be converted to one rocket file; the flight commands (e.g. "
                              "'simulate') fly it from the .ork", config=None) -> None:
    """InputError naming the second stage of a multi-stage rocket (not for stages that
    stay together to apogee, :func:`~ironbark_opt.openrocket.staging.flies_as_one`)."""
    from ironbark_opt.openrocket.staging import flies_as_one
    if len(doc.rocket.stages) > 1 and not flies_as_one(doc, config):
        s = doc.rocket.stages[1]
        raise InputError(f"{what} not supported yet (stage '{s.name}'); remove the lower stages "
                         f"to {instead}", source=doc.path, field=s.path)
    if doc.rocket.pods:
        s = doc.rocket.pods[0]
        raise InputError(f"a rocket with parallel boosters ('{s.name}') {pods}", source=doc.path, field=s.path)


def check_flyable(doc: OrkDocument, config) -> None:
    """InputError naming the first feature of ``config`` we cannot fly yet."""
    _single_stage(doc, "multi-stage separation is", "fly the sustainer alone", config=config)
    for mount, entry in config.motors:
        if entry.ignition_event not in _IGNITE_AT_LAUNCH:
            raise InputError(f"ignition on '{entry.ignition_event}' is not supported in one stage: motor "
                             f"{entry.designation} in '{mount.name}' (configuration {config.label()}); "
                             f"give it a delay after launch instead", source=doc.path, field=mount.path)
    if config.motors and min(e.ignition_delay for _, e in config.motors) > 0.0:
        mount, entry = min(config.motors, key=lambda me: me[1].ignition_delay)
        raise InputError(f"no motor ignites at launch in configuration {config.label()} (the first, "
                         f"{entry.designation} in '{mount.name}', after {entry.ignition_delay:g} s)",
                         source=doc.path, field=mount.path)


def cluster_motor_file(path: Path, motor, count: int) -> tuple[Path, str]:
    """An .eng file of ``count`` identical motors lit together, flown as one on the axis.

    Thrust, propellant and dry mass are multiplied by ``count``; CG and length
    are those of one motor.  The tubes' radial offsets (which add
    m d^2 to the roll inertia and nothing to the pitch inertia of a symmetric
    cluster) are neglected.  Written to ``<cache>/ork-motors``; returns the
    path and the designation (``4xC6``).
    """
    from ironbark_opt import net
    from ironbark_opt.motors import write_eng
    designation = f"{count}x{motor.designation or 'motor'}".replace(" ", "_")
    maker = (motor.manufacturer or "unknown").replace(" ", "_")
    scaled = dataclasses.replace(motor, thrust=count * np.asarray(motor.thrust, dtype=float),
                                 propellant_mass=count * motor.propellant_mass_initial,
                                 dry_mass=count * motor.dry_mass, designation=designation,
                                 manufacturer=maker, source=str(path))
    key = hashlib.sha1(f"{Path(path).resolve()}:{count}:{motor.designation}".encode()).hexdigest()[:12]
    out = net.cache_dir() / "ork-motors" / f"cluster-{designation}-{key}.eng"
    out.parent.mkdir(parents=True, exist_ok=True)
    write_eng(scaled, out)
    return out, designation


def _rail_buttons(buttons: list) -> RailButtons | None:
    """The rail buttons of ``[(component, its buttons' stations [m])]``: the first and last
    button of the first component with two or more; without one, the fore-most and aft-most
    of the single buttons (OpenRocket designs often add each button as its own component).
    Every other button is in ``x_other`` (drag; each takes the riding component's size:
    OpenRocket's RailButtonCalc sizes each instance alike).  None with fewer than two."""
    riding = next(((c, xs) for c, xs in buttons
                   if c.geo["instances"][0] >= 2 and c.geo["instances"][1] > 0), None)
    if riding is not None:
        c, xs = riding
        x_fore, x_aft = xs[0], xs[-1]
        others = xs[1:-1] + [x for c2, xs2 in buttons if c2 is not c for x in xs2]
    else:
        stations = sorted(((x, i) for i, (_, xs) in enumerate(buttons) for x in xs))
        if len(stations) < 2 or not stations[-1][0] > stations[0][0]:
            return None
        (x_fore, first), x_aft = stations[0], stations[-1][0]
        c = buttons[first][0]
        others = [x for x, _ in stations[1:-1]]
    g = c.geo
    size = {}
    if g["outer_diameter"] > 0 and g["height"] > 0 and g["base_height"] + g["flange_height"] <= g["height"]:
        size = {"outer_diameter": g["outer_diameter"], "base_height": g["base_height"],
                "flange_height": g["flange_height"],
                "inner_diameter": min(g["inner_diameter"], g["outer_diameter"])}
    return RailButtons(x_fore=x_fore, x_aft=x_aft, height=g["height"], name=c.name,
                       angle=math.radians(c.element.number("angleoffset", 0.0)),
                       x_other=tuple(others), **size)


def geometry(doc: OrkDocument) -> Rocket:
    """The Rocket (geometry; mass from :meth:`OrkDocument.dry_mass_properties`).

    An OpenRocket 'base drag hack' transition (:meth:`OrkRocket.base_drag_hack`) is left
    out (warned about when the file is read): the body ends at its real base, whose drag the base-drag models
    give, and the stability is that of the real rocket."""
    hack = doc.rocket.base_drag_hack()             # warned about when read (tree.py)
    comps = [convert.body_component(c) for c in doc.rocket.body() if c is not hack]
    buttons = []                                    # (component, its buttons' stations [m])
    for c in doc.rocket.core_components():          # parallel boosters: openrocket.parallel
        if c.kind == "tubefinset":
            g = c.geo
            ro, rb = float(g["outer_radius"] or 0.0), float(g.get("parent_radius") or 0.0)
            if not (ro > 0 and rb > 0):
                raise c.element.error(f"tube fins '{c.name}' need a radius > 0 and a body tube "
                                      f"under them", "radius")
            ri = ro - min(max(g["thickness"], 1e-6 * ro), ro)
            comps.append(TubeFins(x=c.x, length=g["length"], outer_radius=ro, inner_radius=ri,
                                  count=g["count"], body_radius=rb, name=c.name))
            continue
        if c.kind in FINS:
            comps.append(convert.fin_set(c))
        elif c.kind == "railbutton":
            n, sep = c.geo["instances"]
            x0 = c.x + 0.5 * c.length
            buttons.append((c, [x0 + i * sep for i in range(n)]))
    guide = _rail_buttons(buttons)
    if guide is None:
        for c in doc.rocket.core_components():
            if c.kind == "launchlug" and c.geo["radius"] > c.geo["thickness"] >= 0:
                # OpenRocket's instances: identical lugs, fronts 'instanceseparation' apart
                n, sep = c.geo["instances"]
                guide = LaunchLug(x=c.x, length=c.geo["length"], outer_radius=c.geo["radius"],
                                  inner_radius=c.geo["radius"] - c.geo["thickness"], name=c.name,
                                  count=n, separation=sep if n > 1 else 0.0)
                break
    if guide is not None:
        comps.append(guide)
    return Rocket(doc.name, comps, mass_override=doc.dry_mass_properties())


def recovery(doc: OrkDocument, config_id: str = "") -> tuple:
    """Parachutes and streamers as RecoverySpecs for one configuration.

    Deployment at ``apogee``, at ``ejection`` (the motor's delay charge:
    burnout + the configuration's delay, :mod:`ironbark_opt.dynamics.ejection`),
    ``altitude`` at the given height on the way down (after ``deploydelay``);
    ``never`` and lower-stage events are skipped.
    """
    out = []
    for c in doc.rocket.core_components():
        if c.kind not in ("parachute", "streamer"):
            continue
        g = c.geo
        if c.kind == "parachute":
            area = math.pi * (g["diameter"] / 2) ** 2
            cd = PARACHUTE_CD if g["cd"] is None else g["cd"]
        else:
            area = g["strip_length"] * g["strip_width"]
            cd = STREAMER_CD if g["cd"] is None else g["cd"]
        if area * cd <= 0:
            continue
        event, altitude, delay = g["deploy_per_config"].get(
            config_id, (g["deploy_event"], g["deploy_altitude"], g["deploy_delay"]))
        if event not in ("apogee", "ejection", "altitude"):
            continue
        deploy = altitude if event == "altitude" else event
        out.append(RecoverySpec(c.name, cd * area, deploy, delay))
    return tuple(out)


def _aero_table_path(rocket: Rocket, doc: OrkDocument) -> Path:
    """Write the interim pressure-drag table of ``rocket`` (rebuilt on every load, a few
    ms) to ``<cache>/ork-aero`` and return its path: AeroSpec names tables by file."""
    from ironbark_opt import net
    from ironbark_opt.aero.empirical_drag import pressure_drag_table
    key = hashlib.sha1(str(doc.path.resolve()).encode()).hexdigest()[:12]
    # dots in the name ("01.One-stage_OR22.02") would read as a suffix: keep the name whole
    stem = net.cache_dir() / "ork-aero" / f"{doc.path.stem.replace(' ', '_').replace('.', '_')}-{key}"
    stem.parent.mkdir(parents=True, exist_ok=True)
    pressure_drag_table(rocket).save(stem)
    return Path(f"{stem}.json")


def rocket_file(doc: OrkDocument, config: str | None = None):
    """A :class:`~ironbark_opt.rocket.toml_io.RocketFile` for one motor configuration."""
    from ironbark_opt.rocket.toml_io import RocketFile
    cfg, sim = doc.config_and_simulation(config)
    check_flyable(doc, cfg)
    # The motor lit at launch first; others of the stage (air-start) by ignition time.
    ordered = sorted(cfg.motors, key=lambda me: me[1].ignition_delay)
    specs = [_motor_spec(doc, mount, entry) for mount, entry in ordered]
    spec = specs[0]
    if len(specs) > 1:
        spec = dataclasses.replace(spec, airstart=tuple(
            (s, float(e.ignition_delay)) for s, (_, e) in zip(specs[1:], ordered[1:])))
    rocket = geometry(doc)
    launch = sim.launch if sim is not None else LaunchSpec()
    aero = AeroSpec(table=_aero_table_path(rocket, doc))
    return RocketFile(rocket, spec, aero, launch, recovery(doc, cfg.config_id), BallastSpec(), doc.path)


def _motor_spec(doc: OrkDocument, mount, entry) -> MotorSpec:
    """The MotorSpec of one mount's motor (a cluster flies as one equivalent motor)."""
    found = find_motor_file(entry.designation, entry.manufacturer, doc.path, entry.digest)
    path, designation = found.path, found.motor.designation
    if mount.cluster_count > 1:
        path, designation = cluster_motor_file(path, found.motor, mount.cluster_count)
    # the configuration's ejection delay (None in the file: plugged, no charge)
    delay = math.inf if entry.delay is None else float(entry.delay)
    return MotorSpec(file=path, designation=designation, nozzle_x=nozzle_x(mount, entry),
                     ejection_delay=delay)


def load_ork_geometry(path) -> Rocket:
    """The rocket's geometry and mass build-up from an .ork file, without a motor
    (what an aerodynamic table needs; numeric-only).

    Raises InputError for a damaged file or an unsupported component, and for
    more than one stage (each flight configuration has its own geometry:
    :func:`ironbark_opt.openrocket.stage_tables.configurations`)."""
    doc = read_ork(path)
    _single_stage(doc, "one geometry for a multi-stage rocket is", "mesh the sustainer alone, or build "
                  "one table per flight configuration with 'ironbark aero build'",
                  "cannot be meshed for a table yet (remove the boosters to build the core's)")
    return geometry(doc)


def load_ork(path, *, config: str | None = None):
    """Read an .ork file and return the RocketFile of one motor configuration (numeric-only).

    The RocketFile flies through :func:`ironbark_opt.vehicle.setup_from_file`:
    geometry from the design, dry mass properties from OpenRocket's component
    rules, the configuration's motor file, launch conditions from the first
    simulation of that configuration, parachutes/streamers, and the interim
    empirical pressure-drag table (:mod:`ironbark_opt.aero.empirical_drag`).

    Parameters
    ----------
    path : path-like
    config : str, optional
        Configuration id (or its first characters), name, label such as
        ``[C6-5]`` or a motor designation; default the file's selected one.

    Raises
    ------
    InputError
        Damaged file (naming the element path), unsupported feature (naming the
        component), unknown configuration, or motor not found (naming it and
        the places searched).
    """
    return rocket_file(read_ork(path), config)
