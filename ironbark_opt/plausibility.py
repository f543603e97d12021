"""Physical plausibility of a whole vehicle, after loading and before flying.

One place for the checks a single field's own validation cannot make because
they relate several inputs (numeric-only):

- dry mass > 0; dry CG inside the body; inertia realisable (symmetric,
  positive definite, principal moments obeying the triangle inequality
  ``I1 + I2 >= I3``: for an axisymmetric body ``I_axial <= 2 I_transverse``);
- the motor: its CG offsets inside the motor, its inertia realisable, its
  propellant mass against the motor file's own data (the specific impulse a
  solid or hybrid motor can deliver), the nozzle inside the body;
- ballast: inside its bay and the body, at most the bay's capacity;
- rail guides inside the body; launch angle and wind a launch can happen in;
- thrust-to-weight at ignition;
- static margin at launch and over the flown ascent (refused below zero unless
  ``allow_unstable``; :func:`check_ascent_stability` is the rule every command applies).

Impossible values raise :class:`~ironbark_opt.errors.InputError` naming the
field; plausible-but-unusual ones warn (``PlausibilityWarning``) naming it.

Sources of the limits: the triangle inequality of principal moments of
inertia (any rigid body; e.g. Landau & Lifshitz, Mechanics, sec. 32);
specific impulse of solid propellants 150-270 s (Sutton & Biblarz, Rocket
Propulsion Elements, 9th ed., table 12-3), so 40..350 s brackets every real
motor with margin; NFPA 1127 / Tripoli and NAR safety codes: launch within
20 deg (30 deg TRA high-power) of vertical, no launch in winds above
20 mph (8.9 m/s); stability: Barrowman (1967) static margin >= 1 caliber
rule of thumb; OpenRocket and RASAero warn below it.
"""
from __future__ import annotations

import math
import warnings

import numpy as np

from ironbark_opt.errors import InputError

G0 = 9.80665                      # [m/s^2] standard gravity
ISP_RANGE_S = (40.0, 350.0)       # [s] outside: no solid/hybrid motor delivers it (Sutton table 12-3)
MIN_INCLINATION_DEG = 30.0        # [deg] above horizontal: below it the rocket never climbs usefully
WARN_INCLINATION_DEG = 60.0       # [deg] TRA high-power code: within 30 deg of vertical
MAX_WIND_MPS = 30.0               # [m/s] hurricane-force at the pad: no launch
WARN_WIND_MPS = 8.9               # [m/s] 20 mph, the NAR/TRA wind limit
MIN_MARGIN_CAL = 1.0              # [cal] warn below (Barrowman rule of thumb)
#: [m/s] warn below: the common rule of thumb of about 50 ft/s for fin stabilisation at
#: rail exit (the Spaceport America Cup's rule is 100 ft/s, 30.5 m/s)
MIN_RAIL_EXIT_SPEED_MPS = 15.0
MAX_SITE_ELEVATION_M = 9000.0     # [m] above the highest ground on Earth (8849 m)
#: [m] a motor mass placed outside the motor is refused only when it moves the loaded
#: motor's CG by more than this (a 1 mm CG shift is 0.01 calibre on a 100 mm rocket)
NEGLIGIBLE_CG_SHIFT_M = 1e-3


class PlausibilityWarning(UserWarning):
    """A plausible but unusual value (named in the message)."""


def _warn(message: str) -> None:
    warnings.warn(message, PlausibilityWarning, stacklevel=3)


def check_inertia(inertia, *, source=None, field="inertia", names=("I_axial", "I_transverse"),
                  allow_point_mass: bool = False) -> None:
    """Realisable inertia tensor [kg m^2]: symmetric, positive definite, triangle inequality.
    ``allow_point_mass``: (0, 0) is accepted (a point mass, e.g. a motor casing counted
    in the rocket's mass)."""
    I = np.asarray(inertia, dtype=float)
    if I.shape == (2,):                       # (I_transverse, I_axial)
        it, ia = float(I[0]), float(I[1])
        if allow_point_mass and it == 0.0 and ia == 0.0:
            return
        if not (np.isfinite(it) and it > 0.0):
            raise InputError(f"{names[1]} must be > 0 kg m^2, got {it:g}", source=source, field=names[1])
        if not (np.isfinite(ia) and ia > 0.0):
            raise InputError(f"{names[0]} must be > 0 kg m^2, got {ia:g}", source=source, field=names[0])
        if ia > 2.0 * it * (1 + 1e-9):
            raise InputError(f"{names[0]} = {ia:g} kg m^2 exceeds twice {names[1]} = {it:g} kg m^2: "
                             f"no rigid body has that (triangle inequality I_axial <= 2 I_transverse)",
                             source=source, field=names[0])
        return
    if I.shape != (3, 3):
        raise InputError(f"inertia must be a 3x3 tensor, got shape {I.shape}", source=source, field=field)
    if not np.allclose(I, I.T, rtol=1e-9, atol=1e-12):
        raise InputError("inertia tensor must be symmetric", source=source, field=field)
    eig = np.linalg.eigvalsh(I)
    if eig[0] <= 0.0:
        raise InputError(f"inertia tensor is not positive definite (principal moments "
                         f"{', '.join(f'{e:.4g}' for e in eig)} kg m^2)", source=source, field=field)
    if eig[0] + eig[1] < eig[2] * (1 - 1e-9):
        raise InputError(f"inertia tensor breaks the triangle inequality: principal moments "
                         f"{eig[0]:.4g} + {eig[1]:.4g} < {eig[2]:.4g} kg m^2 (no rigid body has that)",
                         source=source, field=field)


def check_rocket_file(rf, rocket, motor, file_motor=None) -> None:
    """Checks of a loaded :class:`RocketFile` (``rocket`` built with ``motor``)."""
    src = rf.source
    length = float(rocket.length())
    dry = rocket.dry_mass_properties()
    override = getattr(rocket, "mass_override", None) is not None
    pre = "rocket.mass_override." if override else ""
    if not dry.mass > 0.0:
        raise InputError(f"dry mass of the rocket must be > 0 kg, got {dry.mass:g}", source=src,
                         field=pre + "mass")
    if not 0.0 <= dry.cg_x <= length:
        raise InputError(f"dry CG at x = {dry.cg_x:g} m is outside the body (0 to {length:.4g} m "
                         f"aft of the nose tip)", source=src, field=pre + "cg_x")
    I = np.asarray(dry.inertia, dtype=float)
    if np.allclose(I, np.diag(np.diag(I))) and np.isclose(I[1, 1], I[2, 2]):
        check_inertia((I[1, 1], I[0, 0]), source=src, field=pre + "inertia",
                      names=(pre + "I_axial", pre + "I_transverse"))
    else:
        check_inertia(I, source=src, field=pre + "inertia")
    # several motors (air-start, parallel boosters): their sum is not the first file's motor
    check_motor(motor, None if rf.motor.airstart else file_motor, rf.motor, length, source=src)
    # rail guides and point masses off the body: Rocket() (component-indexed)
    b = rf.ballast
    for name in ("x_min", "x_max", "x"):
        x = getattr(b, name)
        if x is not None and x > length:
            raise InputError(f"ballast {name} = {x:g} m is outside the body (0 to {length:.4g} m)",
                             source=src, field=f"ballast.{name}")
    check_launch(rf.launch.inclination, rf.launch.wind_speed, source=src)


def check_launch(inclination=None, wind_speed=None, *, source=None, option=None) -> None:
    """Launch angle [rad above horizontal] and surface wind [m/s] a launch can happen in."""
    if inclination is not None:
        deg = math.degrees(inclination)
        field = option or "launch.inclination_deg"
        if deg < MIN_INCLINATION_DEG:
            raise InputError(f"inclination {deg:g} deg above horizontal: the rocket would fly nearly "
                             f"flat and never climb; expected {MIN_INCLINATION_DEG:g} to 90 deg",
                             source=source, field=field)
        if deg < WARN_INCLINATION_DEG:
            _warn(f"{field}: {deg:g} deg is more than 30 deg from vertical (safety codes allow 20-30)")
    if wind_speed is not None:
        field = option or "launch.wind_speed"
        if wind_speed > MAX_WIND_MPS:
            raise InputError(f"wind speed {wind_speed:g} m/s is hurricane-force; expected 0 to "
                             f"{MAX_WIND_MPS:g} m/s (launch limit 8.9 m/s)", source=source, field=field)
        if wind_speed > WARN_WIND_MPS:
            _warn(f"{field}: {wind_speed:g} m/s is above the 20 mph (8.9 m/s) launch limit")


def check_motor(motor, file_motor, spec, body_length: float, *, source=None) -> None:
    """The motor with its overrides, against the file's own motor data."""
    fld = "motor.overrides."
    m_p = float(motor.propellant_mass_initial)
    if not m_p > 0.0:
        raise InputError(f"propellant mass must be > 0 kg, got {m_p:g}", source=source,
                         field=fld + "propellant_mass")
    isp = float(motor.total_impulse) / (m_p * G0)
    if not ISP_RANGE_S[0] <= isp <= ISP_RANGE_S[1]:
        raise InputError(f"propellant mass {m_p:.4g} kg gives a specific impulse of {isp:.0f} s for the "
                         f"motor's {motor.total_impulse:.0f} N s; real motors deliver "
                         f"{ISP_RANGE_S[0]:.0f}-{ISP_RANGE_S[1]:.0f} s (check propellant_mass / grains)",
                         source=source, field=fld + "propellant_mass")
    if file_motor is not None and file_motor.propellant_mass_initial > 0:
        ratio = m_p / float(file_motor.propellant_mass_initial)
        if not 0.7 <= ratio <= 1.3:
            _warn(f"{fld}propellant_mass: {m_p:.4g} kg differs from the motor file's "
                  f"{file_motor.propellant_mass_initial:.4g} kg by {100 * (ratio - 1):+.0f} %")
    length = getattr(motor, "length", None)
    m_dry = float(getattr(motor, "dry_mass", 0.0) or 0.0)
    for name, mass in (("dry_cg", m_dry), ("propellant_cg", m_p)):
        val = getattr(motor, name, None)
        if val is None or not length:
            continue
        lo, hi = -0.1 * length, 1.1 * length
        outside = max(lo - float(val), float(val) - hi, 0.0)
        # a mass whose misplacement moves the loaded motor's CG by less than
        # NEGLIGIBLE_CG_SHIFT_M changes no number the flight reports (a casing
        # counted in the rocket, given as 0 or 1e-6 kg, as RocketPy conversions do)
        if outside > 0.0 and mass * outside / (m_dry + m_p) > NEGLIGIBLE_CG_SHIFT_M:
            raise InputError(f"{name} = {float(val):g} m is outside the motor (0 to {length:.4g} m "
                             f"forward of the nozzle exit)", source=source, field=fld + name)
    di = getattr(motor, "dry_inertia", None)
    if di is not None:
        check_inertia(tuple(di), source=source, field=fld + "dry_inertia",
                      names=(fld + "dry_inertia (axial)", fld + "dry_inertia (transverse)"),
                      allow_point_mass=True)
    if spec is not None and spec.nozzle_x > 1.1 * body_length:
        raise InputError(f"nozzle_x = {spec.nozzle_x:g} m is aft of the body's end ({body_length:.4g} m)",
                         source=source, field="motor.nozzle_x")
    if spec is not None and length and spec.nozzle_x < float(length) - 1e-6:
        raise InputError(f"nozzle_x = {spec.nozzle_x:g} m puts the front of the {float(length):.4g} m motor "
                         f"{float(length) - spec.nozzle_x:.4g} m ahead of the nose tip (nozzle_x is the "
                         f"nozzle exit, m aft of the nose tip)", source=source, field="motor.nozzle_x")
    for i, (extra, _) in enumerate(getattr(spec, "airstart", None) or ()):
        if extra.nozzle_x > 1.1 * body_length:
            raise InputError(f"nozzle_x = {extra.nozzle_x:g} m is aft of the body's end ({body_length:.4g} m)",
                             source=source, field=f"airstart[{i}].nozzle_x")


def _launch_mass_and_cg(setup, p: dict):
    m_b, x_b = float(p.get("ballast_mass", 0.0)), float(p.get("ballast_x", setup.dry.cg_x))
    motor = setup.motor
    m_m = float(motor.mass(0.0))
    x_m = setup.nozzle_x - float(motor.cg(0.0))
    m = setup.dry.mass + m_b + m_m
    return m, (setup.dry.mass * setup.dry.cg_x + m_b * x_b + m_m * x_m) / m


def static_margin_at_launch(setup, p: dict, mach: float = 0.1) -> float:
    """Static margin [calibers] at ignition, at ``mach`` and zero angle of attack."""
    _, x_cg = _launch_mass_and_cg(setup, p)
    cp = float(setup.aero.center_of_pressure(mach, 0.0))
    return (cp - x_cg) / float(setup.aero.reference_length)


def check_flight_inputs(setup, p: dict, *, allow_unstable: bool = False, body_length=None) -> dict:
    """Checks of a setup with its parameter values ``p`` (name -> SI), before flying.

    Returns ``{"static_margin_launch_cal": ...}``.  A staged rocket is checked as
    its whole stack on the pad (:class:`ironbark_opt.dynamics.staged.StagedSetup`).
    """
    setup = getattr(setup, "stack", setup)
    src = setup.source
    m, _ = _launch_mass_and_cg(setup, p)
    weight = m * G0
    thrust = float(setup.motor.max_thrust)
    if thrust <= weight:
        raise InputError(f"the motor's peak thrust {thrust:.0f} N does not lift the launch weight "
                         f"{weight:.0f} N (launch mass {m:.3g} kg): check the rocket's mass and the motor",
                         source=src, field="mass")
    if thrust < 5.0 * weight:
        _warn(f"mass: thrust-to-weight {thrust / weight:.1f} at peak thrust is below 5 "
              f"(launch mass {m:.3g} kg)")
    margin = static_margin_at_launch(setup, p)
    if margin < 0.0 and not allow_unstable:
        raise InputError(f"unstable: static margin {margin:.2f} cal at launch (CP forward of the CG); "
                         f"move mass forward or enlarge the fins, or pass --allow-unstable",
                         source=src, field="static margin")
    if margin < MIN_MARGIN_CAL:
        _warn(f"static margin {margin:.2f} cal at launch is below {MIN_MARGIN_CAL:g} cal")
    return {"static_margin_launch_cal": margin}


#: summary keys of the stability rule (every command's JSON carries them)
MARGIN_KEYS = ("static_margin_min_cal", "static_margin_min_time_s")


def check_ascent_stability(setup, parameters=None, *, allow_unstable: bool, summary=None) -> dict:
    """The one stability rule of ``simulate``, ``ballast``, ``sensitivity`` and ``montecarlo``:
    the static margin must stay >= 0 everywhere on the flown ascent (rail to apogee) of
    the nominal flight (``parameters``: name -> SI overrides) or of the solved one (its
    ``summary``: a flight's ``summary_values`` or a solution's ``values``); else an
    InputError unless ``allow_unstable``. Flies the nominal flight when no ``summary``
    is given. Returns the :data:`MARGIN_KEYS` values.
    """
    if summary is None:
        from ironbark_opt.flight import simulate
        summary = simulate(setup, parameters=parameters).summary_values
    out = {k: float(summary[k]) for k in MARGIN_KEYS}
    check_ascent_margin(*out.values(), allow_unstable=allow_unstable,
                        source=getattr(getattr(setup, "stack", setup), "source", None))
    check_rail_exit_speed(summary.get("rail_exit_speed_mps") if hasattr(summary, "get") else None)
    return out


def check_rail_exit_speed(speed_mps) -> None:
    """Warn when the flown rail-exit speed [m/s] (None: not known) is below
    :data:`MIN_RAIL_EXIT_SPEED_MPS`: the fins have little dynamic pressure to turn the
    rocket into the wind and it weathercocks."""
    speed = math.nan if speed_mps is None else float(speed_mps)
    if speed < MIN_RAIL_EXIT_SPEED_MPS:            # False for NaN (not known)
        _warn(f"rail exit speed {speed:.1f} m/s is below {MIN_RAIL_EXIT_SPEED_MPS:g} m/s (about 50 "
              "ft/s, the common minimum for fin stabilisation; a longer rail, a lighter rocket or a motor "
              "with a higher initial thrust raise it)")


def check_ascent_margin(min_margin: float, time_s: float, *, allow_unstable: bool, source=None) -> None:
    """The minimum static margin [cal] of a flown ascent (rail exit to apogee)."""
    if min_margin < 0.0 and not allow_unstable:
        raise InputError(f"unstable: static margin falls to {min_margin:.2f} cal at t = {time_s:.2f} s "
                         f"of the ascent; pass --allow-unstable to fly it anyway", source=source,
                         field="static margin")
    if min_margin < MIN_MARGIN_CAL:
        _warn(f"static margin falls to {min_margin:.2f} cal at t = {time_s:.2f} s (below "
              f"{MIN_MARGIN_CAL:g} cal)")


def _as_option(err: InputError, option: str) -> InputError:
    return InputError(f"{err.message}", field=option)


def option_overrides(setup, *, rail_length=None, inclination_deg=None, heading_deg=None,
                     elevation_m=None, ballast_kg=None, ballast_x_m=None, max_ballast=None,
                     body_length=None) -> dict:
    """Parameter overrides (SI, radians) from CLI options, validated by the same
    rules as the file fields they replace (:class:`LaunchSpec`,
    :class:`BallastSpec`, :func:`check_launch`); errors name the option.

    Returns ``{"parameters": {...}, "site_elevation": float or None}``.
    """
    import dataclasses
    setup = getattr(setup, "stack", setup)              # a staged rocket: its stack on the pad

    from ironbark_opt.rocket.specs import BallastSpec, LaunchSpec

    out = {}
    nominal = dict(setup.nominal)
    launch_opts = (("rail_length", rail_length, "--rail-length", None),
                   ("inclination", inclination_deg, "--inclination", math.radians),
                   ("heading", heading_deg, "--heading", math.radians),
                   ("site_elevation", elevation_m, "--elevation", None))
    for name, value, option, conv in launch_opts:
        if value is None:
            continue
        try:
            val = conv(value) if conv is not None else value
            spec = LaunchSpec(**{name: val})
        except InputError as err:
            raise _as_option(err, option) from None
        out[name] = getattr(spec, name)
    if "inclination" in out:
        check_launch(out["inclination"], option="--inclination")
    if "site_elevation" in out and not -500.0 <= out["site_elevation"] <= MAX_SITE_ELEVATION_M:
        raise InputError(f"site elevation {out['site_elevation']:g} m is not on Earth's surface "
                         f"(expected -500 to {MAX_SITE_ELEVATION_M:g} m)", field="--elevation")
    bay = setup.ballast_x_range
    cap = setup.ballast_mass_max
    if max_ballast is not None:
        try:
            new_cap = BallastSpec(mass_max=max_ballast).mass_max
        except InputError as err:
            raise _as_option(err, "--max-ballast") from None
        if cap is not None and new_cap > cap:
            raise InputError(f"{new_cap:g} kg exceeds the file's [ballast] mass_max = {cap:g} kg",
                             field="--max-ballast")
        cap = new_cap
    if "rail_length" in out and out["rail_length"] <= setup.rail_exit_offset:
        raise InputError(f"rail length {out['rail_length']:g} m is shorter than the distance from the "
                         f"nozzle to the rail guide ({setup.rail_exit_offset:.3f} m): the rocket leaves "
                         f"the rail before it moves", field="--rail-length")
    if ballast_kg is not None or ballast_x_m is not None:
        mass = nominal.get("ballast_mass", 0.0) if ballast_kg is None else ballast_kg
        x = nominal.get("ballast_x") if ballast_x_m is None else ballast_x_m
        options = {"mass": "--ballast", "x": "--ballast-x", "mass_max": "--ballast",
                   "x_min": "--ballast-x", "x_max": "--ballast-x"}
        try:
            kw = dict(mass=mass, x=x, mass_max=cap)
            if bay is not None:
                kw.update(x_min=bay[0], x_max=bay[1])
            BallastSpec(**kw)
        except InputError as err:
            msg = err.message.replace("outside the bay", "outside the [ballast] bay")
            if err.field == "mass" and cap is not None:
                msg += " (the bay's capacity mass_max)"
            if ballast_kg is None and err.field == "mass":
                err.field = "x"
            raise InputError(msg, field=options.get(err.field, "--ballast")) from None
        if ballast_kg is not None:
            launch_mass = setup.dry.mass + float(setup.motor.mass(0.0))
            if ballast_kg > 5.0 * launch_mass:
                raise InputError(f"{ballast_kg:g} kg is more than five times the rocket "
                                 f"({launch_mass:.3g} kg without ballast)", field="--ballast")
        if ballast_x_m is not None and body_length is not None and not 0.0 <= ballast_x_m <= body_length:
            raise InputError(f"x = {ballast_x_m:g} m is outside the body (0 to {body_length:.4g} m "
                             f"aft of the nose tip)", field="--ballast-x")
        if ballast_kg is not None:
            out["ballast_mass"] = float(mass)
        if ballast_x_m is not None:
            out["ballast_x"] = float(x)
    elevation = out.pop("site_elevation", None)
    del dataclasses
    return {"parameters": out, "site_elevation": elevation, "mass_max": cap}
