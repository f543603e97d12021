"""From a rocket file (TOML) to a ready-to-fly :class:`FlightSetup`.

This is the one place that turns the specs a file describes (motor file and
overrides, aerodynamic inputs, launch site, recovery, ballast) into the
model objects the flight core uses.  The OpenRocket importer produces the
same :class:`~ironbark_opt.rocket.toml_io.RocketFile`, so both formats fly
through here.
"""
from __future__ import annotations

import math

import dataclasses
from pathlib import Path

from ironbark_opt.aero.model import build_aero_model
from ironbark_opt.atmosphere.base import wind_from_speed_direction
from ironbark_opt.atmosphere.isa import ISA
from ironbark_opt.dynamics.setup import DryMass, FlightSetup, Parachute
from ironbark_opt.errors import InputError

#: How the rail length is measured (``rail_exit`` launch option).
RAIL_EXIT_RULES = ("forward_button", "aft_button", "travel")


def load_motor_for(spec):
    """The motor a :class:`MotorSpec` names, with its overrides applied (with
    air-start motors: a :class:`~ironbark_opt.motors.composite.CompositeMotor`)."""
    if spec.airstart:
        from ironbark_opt.motors.composite import CompositeMotor
        first = dataclasses.replace(spec, airstart=())
        parts = [(load_motor_for(first), 0.0, spec.nozzle_x)] + \
            [(load_motor_for(s), float(t), s.nozzle_x) for s, t in spec.airstart]
        return CompositeMotor(tuple(m for m, _, _ in parts), tuple(t for _, t, _ in parts),
                              tuple(x for _, _, x in parts), spec.nozzle_x)
    if spec.kind != "solid":
        from ironbark_opt.rocket.tank_spec import tank_motor
        return tank_motor(spec)
    overrides = _solid_overrides(spec)
    motor = read_motor_file(spec, overrides)
    if "dry_inertia" in overrides:
        overrides["dry_inertia"] = tuple(overrides["dry_inertia"])
    if overrides:
        try:
            motor = dataclasses.replace(motor, **overrides)
        except TypeError as err:
            raise InputError(f"motor override not accepted: {err}", source=spec.file, field="motor.overrides") from None
    return motor


def _solid_overrides(spec) -> dict:
    """``[motor.overrides]`` of a solid motor as motor fields (grains as
    :class:`~ironbark_opt.motors.grains.Grains`, their propellant mass)."""
    from ironbark_opt.motors.grains import Grains
    overrides = dict(spec.overrides)
    if "grains" in overrides and isinstance(overrides["grains"], dict):
        overrides["grains"] = Grains(**overrides["grains"])
    if "grains" in overrides and "propellant_mass" not in overrides:
        # The file's header mass describes the catalogue motor; the user's
        # grain geometry is the better number for their propellant load.
        overrides["propellant_mass"] = overrides["grains"].mass
    return overrides


def read_motor_file(spec, overrides: dict | None = None):
    """The thrust-curve file of ``spec`` as written (its own header numbers); a file
    without them (RocketPy-style headerless ``.eng``, a time/thrust CSV) takes the
    header's numbers from ``[motor.overrides]`` (``MOTOR_HEADER_KEYS``)."""
    from ironbark_opt.motors import load_motor
    from ironbark_opt.rocket.specs import MOTOR_HEADER_KEYS
    ov = _solid_overrides(spec) if overrides is None else overrides
    header = {k: ov[k] for k in MOTOR_HEADER_KEYS if k in ov}
    first = None
    attempts = [{}] + ([header] if header else [])   # the file's own header first
    for kwargs in attempts:
        try:
            return load_motor(spec.file, spec.designation, **kwargs)
        except InputError as err:
            if err.field != "header" and err.field not in MOTOR_HEADER_KEYS:
                raise                    # not a missing header number
            first = err
    raise InputError(f"{first.message}; in a rocket file give them in [motor.overrides] "
                     "(dry_mass, propellant_mass [kg] or grains; diameter, length [m])",
                     source=first.source, line=first.line, field=first.field) from None


def load_aero_table(aero_spec, rocket):
    """The AeroTable an :class:`AeroSpec` names: a table file, drag curves, or
    (neither given) the empirical pressure-drag estimate from the geometry."""
    from ironbark_opt.aero.importers import from_cd_mach_csv
    from ironbark_opt.aero.table import AeroTable

    if aero_spec.table is not None:
        return AeroTable.load(aero_spec.table)
    if aero_spec.drag_power_off is not None:
        return from_cd_mach_csv(aero_spec.drag_power_off, aero_spec.drag_power_on,
                                reference_area=rocket.reference_area(),
                                reference_length=2 * rocket.reference_radius(),
                                duplicates=aero_spec.drag_duplicates)
    # No aerodynamic input: the empirical pressure/wave-drag estimate from the
    # geometry (friction and base drag are added by the aero model); build a
    # panel-method table with 'ironbark aero build' for the better model.
    from ironbark_opt.aero.empirical_drag import pressure_drag_table
    return pressure_drag_table(rocket)


def rail_exit_offset(rocket, nozzle_x: float, rule: str) -> float:
    """Distance [m] subtracted from the rail length to get the travel to rail exit.

    ``forward_button``: the rocket is free when its forward rail button passes
    the rail's top end, the nozzle starting at the rail's foot (RocketPy's
    rule, its ``effective_1rl``); ``aft_button``: when the aft button leaves
    (guided as long as any button is on the rail); ``travel``: after travelling
    the full rail length (OpenRocket's launch-rod length).
    """
    if rule not in RAIL_EXIT_RULES:
        raise InputError(f"rail_exit must be one of {', '.join(RAIL_EXIT_RULES)}, got {rule!r}",
                         field="rail_exit")
    if rule == "travel":
        return 0.0
    guides = rocket.rail_guides()
    if guides is None:
        return 0.0
    fwd, aft = min(guides), max(guides)
    return abs(nozzle_x - (fwd if rule == "forward_button" else aft))


def jet_area_of(motor) -> tuple[float, str]:
    """Area of the base the exhaust fills while the motor burns [m^2], and where it
    came from: the motor's nozzle exit area when known, else the motor's
    cross-section, OpenRocket's rule ("subtracting the area of the thrusting
    motors from the base reference area", Niskanen 2013, sec. 3.4.5)."""
    if motor.nozzle_exit_area:
        return float(motor.nozzle_exit_area), "nozzle exit area"
    d = float(getattr(motor, "diameter", 0.0) or 0.0)
    if d > 0:
        return math.pi * d * d / 4.0, ("motor cross-section (nozzle exit area not given; "
                                       "OpenRocket's rule, Niskanen 2013 sec. 3.4.5)")
    return 0.0, "none (no nozzle exit area or motor diameter)"


def setup_from_file(rf, *, rail_exit: str = "forward_button", atmosphere=None,
                    pressure_correction: bool = True, atmosphere_file=None,
                    atmosphere_time=None) -> FlightSetup:
    """Assemble a :class:`FlightSetup` from a loaded :class:`RocketFile`.

    Parameters
    ----------
    rf : RocketFile
    rail_exit : str
        See :func:`rail_exit_offset`.
    atmosphere : Atmosphere, optional
        Replaces the file's standard atmosphere (e.g. a forecast profile).
    atmosphere_file, atmosphere_time : path-like, str, optional
        An atmosphere file (and ISO 8601 UTC time) read at the file's site,
        replacing ``[launch] atmosphere`` (see :mod:`ironbark_opt.atmosphere.files`).
    pressure_correction : bool
        Apply the ambient-pressure thrust correction when the motor's nozzle
        exit area is known.
    """
    if rf.stages:
        raise InputError("a rocket file with [[stage]] tables flies through load_setup (a staged setup)",
                         source=rf.source, field="stage")
    motor = load_motor_for(rf.motor)
    # the exhaust fills the nozzle exit whether or not the thrust is corrected for altitude
    jet, jet_source = jet_area_of(motor)
    if not pressure_correction and motor.nozzle_exit_area is not None:
        motor = dataclasses.replace(motor, nozzle_exit_area=None)
    rocket = rf.dry_rocket(motor)
    from ironbark_opt.plausibility import check_rocket_file
    file_motor = motor.curve if rf.motor.kind != "solid" else read_motor_file(rf.motor)
    check_rocket_file(rf, rocket, motor, file_motor)
    table = load_aero_table(rf.aero, rocket)
    aero = build_aero_model(rocket, table=table, surface_roughness=rf.aero.surface_roughness,
                            re_transition=rf.aero.re_transition, jet_area=jet,
                            jet_area_source=jet_source)
    launch = rf.launch
    if atmosphere_file is None and launch.atmosphere_file is not None:
        atmosphere_file, atmosphere_time = launch.atmosphere_file, launch.atmosphere_time
    if atmosphere is None and atmosphere_file is not None:
        from ironbark_opt.atmosphere.files import load_atmosphere_file
        atmosphere = load_atmosphere_file(atmosphere_file, time=atmosphere_time,
                                          latitude=launch.latitude, longitude=launch.longitude,
                                          ground_elevation=launch.site_elevation)
    if atmosphere is None:
        we, wn = wind_from_speed_direction(launch.wind_speed, launch.wind_from)
        atmosphere = ISA.from_site(launch.site_elevation, launch.site_temperature, launch.site_pressure,
                                   wind_east=we, wind_north=wn)
    ballast = rf.ballast
    nominal = {
        "rail_length": launch.rail_length,
        "inclination": launch.inclination,
        "heading": launch.heading,
        "ballast_mass": ballast.mass,
        "ballast_x": ballast.x if ballast.x is not None else float(rocket.dry_mass_properties().cg_x),
    }
    brakes = None
    if getattr(rf, "airbrakes", None) is not None:
        from ironbark_opt.rocket.airbrake_spec import airbrake_schedule
        brakes = airbrake_schedule(rf.airbrakes)
        nominal.update(brakes.nominal())
    chutes, delay = recovery_of(rf, motor)
    return FlightSetup(motor=motor, nozzle_x=rf.motor.nozzle_x, dry=DryMass.from_properties(rocket.dry_mass_properties()),
                       aero=aero, atmosphere=atmosphere, site_elevation=launch.site_elevation,
                       latitude=launch.latitude, longitude=launch.longitude,
                       rail_exit_offset=rail_exit_offset(rocket, rf.motor.nozzle_x, rail_exit),
                       nominal=nominal, parachutes=chutes, name=rocket.name,
                       ballast_mass_max=ballast.mass_max,
                       ballast_x_range=None if ballast.x_min is None else (ballast.x_min, ballast.x_max),
                       source=str(rf.source), airbrakes=brakes, body_length=float(rocket.length()),
                       gravity=_gravity_model(launch.gravity), ejection_delay=delay)


def recovery_of(rf, motor) -> tuple:
    """(Parachutes, ejection delay [s after burnout] or None) of a rocket file.

    ``deploy = "ejection"`` opens at the motor's ejection charge: the delay is
    ``[motor] ejection_delay`` (an ``.ork`` configuration's delay), else the
    motor file's delay when it offers exactly one.  A plugged motor (an
    ``.ork`` delay ``P``) has no charge: those chutes open at apogee, with a
    warning."""
    import warnings
    at_ejection = [r.name for r in rf.recovery if r.deploy == "ejection"]
    delay = rf.motor.ejection_delay
    if at_ejection and delay is None:
        offered = [d for d in getattr(motor, "delays", ()) if math.isfinite(d)]
        if len(offered) != 1:
            what = (f"offers the delays {', '.join(f'{d:g}' for d in offered)} s" if offered
                    else "gives no ejection delay")
            raise InputError(f"recovery '{at_ejection[0]}' deploys at ejection but the motor {what}: "
                             f"set [motor] ejection_delay [s after burnout]", source=rf.source,
                             field="motor.ejection_delay")
        delay = offered[0]
    if at_ejection and math.isinf(delay):
        warnings.warn(f"{', '.join(at_ejection)}: the motor is plugged (no ejection charge); "
                      f"deployed at apogee instead", UserWarning, stacklevel=3)
        at_ejection, delay = [], None
    chutes = tuple(Parachute(r.name, r.cd_area, float(r.deploy) if not isinstance(r.deploy, str) else None,
                             r.lag, at_ejection=r.deploy == "ejection" and delay is not None)
                   for r in rf.recovery)
    return chutes, (delay if at_ejection else None)


def _gravity_model(value):
    """``[launch] gravity`` [m/s^2] as a model (None: WGS-84 normal gravity)."""
    if value is None:
        return None
    from ironbark_opt.atmosphere.gravity import ConstantGravity
    return ConstantGravity(value)


def load_setup(path, *, config: str | None = None, table=None, **kwargs) -> FlightSetup:
    """Read a rocket file (``.toml`` or OpenRocket ``.ork``) and assemble its
    :class:`FlightSetup`.

    Parameters
    ----------
    path : path-like
    config : str, optional
        Motor configuration of an OpenRocket file (default: its selected one).
    table : path-like or sequence of them, optional
        An AeroTable (e.g. from ``ironbark aero build``) replacing the file's
        aerodynamic input (table, drag curves or the empirical estimate); for a
        serial two-stage .ork or ``[[stage]]`` TOML, the table of each flight
        configuration (the stack's and the sustainer's, any order: each names its
        configuration, :func:`ironbark_opt.openrocket.stage_tables.tables_by_configuration`).
    kwargs
        As in :func:`setup_from_file`.
    """
    tables = table_paths(table)
    table = tables[0] if tables else None
    if Path(path).suffix.lower() == ".ork":
        from ironbark_opt.openrocket import read_ork
        doc = read_ork(_existing(path))
        if doc.rocket.pods and table is not None:     # the stack's table names the core's and booster's
            from ironbark_opt.openrocket.parallel import flight_tables, parallel_setup
            return parallel_setup(doc, config, tables=flight_tables(table, doc), **kwargs)

        from ironbark_opt.openrocket.staging import flies_as_one
        if (len(doc.rocket.stages) > 1 and not flies_as_one(doc, doc.config(config))) or doc.rocket.pods:
            from ironbark_opt.openrocket.parallel import parallel_setup
            from ironbark_opt.openrocket.staging import staged_setup
            if table is not None:            # serial stages: one table per flight configuration
                from ironbark_opt.openrocket.stage_tables import tables_by_configuration
                kwargs = {**kwargs, "tables": tables_by_configuration(doc, tables)}
            return (parallel_setup if doc.rocket.pods else staged_setup)(doc, config, **kwargs)
    rf = load_rocket_file(path, config=config)
    if rf.stages:
        from ironbark_opt.staged_vehicle import stage_configurations_from_toml, staged_setup_from_toml
        if table is not None:         # the stack's replaces [[stage]]'s data, the sustainer's [aero]'s
            from ironbark_opt.openrocket.stage_tables import tables_by_configuration
            found = tables_by_configuration(path, tables, stage_configurations_from_toml(rf))
            rf = dataclasses.replace(
                rf, aero=dataclasses.replace(rf.aero, table=found["sustainer"], drag_power_off=None,
                                             drag_power_on=None),
                stages=tuple(dataclasses.replace(st, aero={"table": found["stack"]}) for st in rf.stages))
        return staged_setup_from_toml(rf, **kwargs)
    if len(tables) > 1:
        raise InputError(f"{len(tables)} tables given: a single-stage rocket flies one", source=path,
                         field="table")
    if table is not None:
        rf = dataclasses.replace(rf, aero=dataclasses.replace(
            rf.aero, table=table, drag_power_off=None, drag_power_on=None))
    return setup_from_file(rf, **kwargs)


def table_paths(table) -> tuple:
    """``table`` (None, one path or a sequence: the CLI's repeatable ``--table``) as
    a tuple of Paths whose ``.csv`` exists."""
    if table is None or isinstance(table, (str, Path)):
        table = () if table is None else (table,)
    out = []
    for t in table:
        t = Path(t)
        stem = t.with_suffix("") if t.suffix.lower() in (".csv", ".json") else t
        if not Path(f"{stem}.csv").exists():
            raise InputError("aerodynamic table not found (expected the .csv written by "
                             "'ironbark aero build')", source=t, field="table")
        out.append(t)
    return tuple(out)


def load_rocket_geometry(path):
    """``(Rocket, AeroSpec)`` of a rocket file (``.toml`` or ``.ork``) without
    resolving its motor: what an aerodynamic table is built from.

    Parameters
    ----------
    path : path-like
    """
    path = _existing(path)
    if path.suffix.lower() == ".ork":
        from ironbark_opt.openrocket.build import load_ork_geometry
        from ironbark_opt.rocket.specs import AeroSpec
        return load_ork_geometry(path), AeroSpec()
    rf = load_rocket_file(path)                 # a TOML file resolves no motor on loading
    return rf.rocket, rf.aero


def load_stage_configurations(path):
    """The flight configurations of a serial multi-stage rocket file, each with its
    geometry (:class:`~ironbark_opt.openrocket.stage_tables.StageConfiguration`, the
    stack first), or None for a file of one stage (parallel boosters included):
    what ``ironbark aero build`` builds one table per."""
    path = _existing(path)
    if path.suffix.lower() != ".ork":
        rf = load_rocket_file(path)
        if not rf.stages:
            return None
        from ironbark_opt.staged_vehicle import stage_configurations_from_toml
        return stage_configurations_from_toml(rf)
    from ironbark_opt.openrocket import read_ork
    doc = read_ork(path)
    from ironbark_opt.openrocket.staging import flies_as_one
    if len(doc.rocket.stages) < 2 or doc.rocket.pods or flies_as_one(doc):
        return None
    from ironbark_opt.openrocket.stage_tables import configurations
    return configurations(doc)


def _existing(path) -> Path:
    path = Path(path)
    if path.is_dir():
        raise InputError("is a directory, expected a rocket file (.toml or .ork)", source=path)
    if not path.exists():
        raise InputError("file not found", source=path)
    return path


def load_rocket_file(path, *, config: str | None = None):
    """A rocket file (``.toml``, or OpenRocket ``.ork`` by its suffix) as a
    :class:`~ironbark_opt.rocket.toml_io.RocketFile`.

    Parameters
    ----------
    path : path-like
    config : str, optional
        Motor configuration of an OpenRocket file (default: its selected one).
    """
    path = _existing(path)
    if path.suffix.lower() == ".ork":
        from ironbark_opt.openrocket import load_ork
        rf = load_ork(path, config=config)
    else:
        if config is not None:
            raise InputError("--config applies to OpenRocket files only", source=path, field="config")
        from ironbark_opt.rocket.toml_io import load_rocket_toml
        rf = load_rocket_toml(path)
    return rf
