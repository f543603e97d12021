"""Serial two-stage rockets from rocket files: the one assembly of a
:class:`~ironbark_opt.dynamics.staged.StagedSetup` that the OpenRocket
importer (:mod:`ironbark_opt.openrocket.staging`) and the TOML ``[[stage]]``
table (:func:`staged_setup_from_toml`) share (numeric-only).

The three vehicles are ordinary :class:`~ironbark_opt.rocket.toml_io.RocketFile`
objects flown through :func:`~ironbark_opt.vehicle.setup_from_file`:

- the stack: both stages' geometry, dry mass and aerodynamics, the booster's
  motor lit at launch and the sustainer's carried unlit
  (:class:`~ironbark_opt.motors.composite.UnlitMotor`), no recovery;
- the sustainer alone, its motor lit at separation
  (:class:`~ironbark_opt.motors.composite.DelayedMotor`, booster burnout +
  delay), its recovery;
- the booster alone in its own frame (x from its front end), its spent motor
  aboard, its recovery, tumbling (:func:`ironbark_opt.aero.tumble.tumble_cd_area`)
  when statically unstable.
"""
from __future__ import annotations

import dataclasses
from pathlib import Path

from ironbark_opt.errors import InputError


def assemble_two_stage(stack_rf, sustainer_rf, booster_rf, *, delay: float, booster_x: float,
                       name: str, booster_name: str = "booster", sustainer_name: str = "sustainer",
                       **setup_kwargs):
    """The StagedSetup of three RocketFiles (see the module docstring).

    Parameters
    ----------
    stack_rf : RocketFile
        Both stages; its ``motor`` is the booster's (nozzle in the stack's frame).
    sustainer_rf : RocketFile
        The upper stage alone (same nose-tip origin as the stack).
    booster_rf : RocketFile
        The lower stage alone, positions from its own front end.
    delay : float [s]
        Separation and sustainer ignition after the booster's burnout.
    booster_x : float [m]
        The booster's front end aft of the stack's nose tip.
    """
    from ironbark_opt.aero.tumble import tumble_cd_area
    from ironbark_opt.dynamics.staged import StagedSetup
    from ironbark_opt.motors.composite import CompositeMotor, DelayedMotor, UnlitMotor
    from ironbark_opt.vehicle import load_motor_for, setup_from_file

    spec_b, spec_s = stack_rf.motor, sustainer_rf.motor
    stack = setup_from_file(stack_rf, **setup_kwargs)
    sustainer = setup_from_file(sustainer_rf, **setup_kwargs)
    booster_motor, sustainer_motor = load_motor_for(spec_b), load_motor_for(spec_s)
    stack_motor = CompositeMotor((booster_motor, UnlitMotor(sustainer_motor)), (0.0, 0.0),
                                 (spec_b.nozzle_x, spec_s.nozzle_x), spec_b.nozzle_x)
    sus_motor = DelayedMotor(sustainer_motor, booster_motor.burn_time + delay)
    # Ballast sits in the sustainer (same nose-tip origin as the stack): nominal at its dry CG.
    nominal = {**stack.nominal, "ballast_x": sustainer.nominal["ballast_x"]}
    stack = dataclasses.replace(stack, motor=stack_motor, name=f"{name} (stack)", nominal=nominal)
    sustainer = dataclasses.replace(sustainer, motor=sus_motor, name=name)
    booster = setup_from_file(booster_rf, **setup_kwargs)
    booster = dataclasses.replace(booster, name=f"{name} ({booster_name})")
    return StagedSetup(stack, sustainer, float(delay), booster_name, sustainer_name, booster=booster,
                       booster_x=float(booster_x),
                       booster_tumble_cd_area=tumble_cd_area(booster_rf.dry_rocket(booster_motor)))


def _shifted(comp, dx: float):
    """A Rocket component moved ``dx`` [m] aft."""
    if hasattr(comp, "x_fore"):
        return dataclasses.replace(comp, x_fore=comp.x_fore + dx, x_aft=comp.x_aft + dx)
    return dataclasses.replace(comp, x=comp.x + dx)


def stacked_rocket(upper, lower, name: str):
    """The Rocket of ``upper`` with ``lower`` (its own frame) behind it: components
    end to end, dry masses combined; one rail guide (the upper stage's if it has one)."""
    from ironbark_opt.rocket.hardware import LaunchLug, RailButtons
    from ironbark_opt.rocket.mass import MassProperties, combine_properties
    from ironbark_opt.rocket.rocket import Rocket

    x0 = float(upper.length())
    guide = (RailButtons, LaunchLug)
    has_guide = any(isinstance(c, guide) for c in upper.components)
    comps = list(upper.components) + [_shifted(c, x0) for c in lower.components
                                      if not (has_guide and isinstance(c, guide))]
    lo = lower.dry_mass_properties()
    mass = combine_properties([upper.dry_mass_properties(), MassProperties(lo.mass, lo.cg_x + x0, lo.inertia)])
    return Rocket(name, comps, mass_override=mass), x0


def stage_configurations_from_toml(rf):
    """The stack and the sustainer of a rocket TOML with one ``[[stage]]`` table
    (:func:`staged_setup_from_toml`'s geometry; StageConfiguration objects)."""
    from ironbark_opt.openrocket.stage_tables import StageConfiguration

    st, brf = _lower_stage(rf)
    upper = rf.rocket.name
    stack, _ = stacked_rocket(rf.rocket, brf.rocket, upper)
    return [StageConfiguration("stack", (upper, st.name or brf.rocket.name), stack),
            StageConfiguration("sustainer", (upper,), rf.rocket)]


def _lower_stage(rf):
    """``(StageSpec, RocketFile)`` of the one ``[[stage]]`` of a rocket TOML (InputError
    for more than one: two-stage rockets only so far)."""
    from ironbark_opt.rocket.toml_io import load_rocket_toml

    if len(rf.stages) != 1:
        raise InputError(f"{len(rf.stages)} [[stage]] tables: two-stage rockets (one [[stage]]) are "
                         "supported so far", source=rf.source, field="stage")
    return rf.stages[0], load_rocket_toml(rf.stages[0].file)


def staged_setup_from_toml(rf, **setup_kwargs):
    """The StagedSetup of a rocket TOML with a ``[[stage]]`` table (the file itself
    describes the sustainer; the stage's own rocket file the booster, in its own
    frame; see docs/rocket-toml.md)."""
    from ironbark_opt.vehicle import load_motor_for

    st, brf = _lower_stage(rf)
    if brf.stages:
        raise InputError("a [[stage]]'s rocket file cannot have stages of its own", source=st.file,
                         field="stage")
    for what, bad in (("[[airstart]]", brf.motor.airstart or rf.motor.airstart),
                      ("[airbrakes]", brf.airbrakes is not None or rf.airbrakes is not None)):
        if bad:
            raise InputError(f"{what} on a staged rocket is not supported yet", source=rf.source, field="stage")
    upper = rf.dry_rocket(load_motor_for(rf.motor))
    lower = brf.dry_rocket(load_motor_for(brf.motor))
    stack_rocket, x0 = stacked_rocket(upper, lower, f"{rf.rocket.name} (stack)")
    if st.aero is None:
        if rf.aero.table is not None or rf.aero.drag_power_off is not None:
            raise InputError("the sustainer has its own aerodynamic data: give the stack's too ([[stage]] "
                             "table or drag_power_off), or neither to fly the empirical estimate",
                             source=rf.source, field="stage")
        aero = rf.aero                       # the empirical estimate of the stack's geometry
    else:
        aero = dataclasses.replace(rf.aero, **{"table": None, "drag_power_off": None, "drag_power_on": None,
                                               **st.aero})
    stack_rf = dataclasses.replace(rf, rocket=stack_rocket, wet_mass_override=None, recovery=(), stages=(),
                                   aero=aero,
                                   motor=dataclasses.replace(brf.motor, nozzle_x=brf.motor.nozzle_x + x0))
    sus_rf = dataclasses.replace(rf, rocket=upper, wet_mass_override=None, stages=())
    booster_rf = dataclasses.replace(brf, rocket=lower, wet_mass_override=None, launch=rf.launch)
    return assemble_two_stage(stack_rf, sus_rf, booster_rf, delay=st.separation_delay, booster_x=x0,
                              name=rf.rocket.name, booster_name=st.name or brf.rocket.name,
                              sustainer_name=rf.rocket.name, **setup_kwargs)


@dataclasses.dataclass(frozen=True)
class StageSpec:
    """One ``[[stage]]`` table: a lower stage below the file's rocket.

    Parameters
    ----------
    file : Path
        Its own rocket TOML (components from its front end, ``[motor]`` lit at
        launch, ``[[recovery]]``).
    separation_delay : float [s]
        Separation and ignition of the stage above after this stage's burnout.
    name : str
    aero : dict or None
        The stack's aerodynamic data files (``table``, ``drag_power_off``,
        ``drag_power_on`` -> Path); None: the empirical estimate of the stack's
        geometry (the file's ``[aero]`` then gives no data either).
    """

    file: Path
    separation_delay: float = 0.0
    name: str = ""
    aero: object = None
