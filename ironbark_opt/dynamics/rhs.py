"""The equations of motion, written once, symbolically (CasADi SX).

State ``x`` (13): ``r_l`` (3) CG position in L [m]; ``v_b`` (3) velocity of
the CG relative to the Earth, in body axes [m/s]; ``q`` (4) attitude
quaternion B -> L; ``w_b`` (3) body rates [rad/s].  Frames: see
:mod:`ironbark_opt.dynamics.frames`.

Free flight (Zipfel, *Modeling and Simulation of Aerospace Vehicle
Dynamics*, 2nd ed., eq. 10.5 (Newton, body coordinates) and eq. 10.29
(Euler)):

    m [dv_B/dt]^B + m [Omega^BE]^B [v_B]^B = [f_a,p]^B + m [T]^BL [g]^L
    I [dw/dt]^B = -[Omega]^B I [w]^B + [m_B]^B - dI/dt [w]^B + M_jet

Mass-rate terms kept (they change pitch motion measurably during the burn):
the ``dI/dt w`` term of the variable-inertia Euler equation and jet damping
``M_jet = dm/dt * l_ne^2 * (0, w_y, w_z)`` with ``l_ne`` the CG-to-nozzle
distance (Mandell, Caporaso & Bengen, *Topics in Advanced Model Rocketry*,
1973, ch. 10, "jet damping" C2R = mdot l_ne^2).  Dropped: the Coriolis
term of the CG moving inside the body (|dx_cg/dt| < 0.1 m/s on a typical
flight, effect below 0.1 m in apogee) and the thrust produced by the
exhaust momentum, which the motor's measured thrust curve already contains.

Air brakes (coast only): the drag-coefficient increment of a deployable
device at its smooth scheduled deployment (:mod:`ironbark_opt.aero.airbrakes`).

Rail phase: 3-DOF motion along the rail (no rotation, aerodynamics at zero
angle of attack, axial force only); the rocket cannot slide back down
(acceleration clipped at 0 while thrust < weight component).

Descent phase: point mass under a parachute (drag ``Cd*S`` along the
air-relative velocity), attitude frozen.
"""
from __future__ import annotations

import casadi as ca

from ironbark_opt import params
from ironbark_opt.atmosphere.gravity import gravity
from ironbark_opt.dynamics.frames import quaternion_rate, rotation_matrix

PHASES = ("rail", "boost", "coast", "descent")

#: Derived quantities returned next to the state derivative, in this order.
OUTPUT_NAMES = (
    "altitude_asl_m", "speed_mps", "airspeed_mps", "mach", "alpha_rad",
    "dynamic_pressure_Pa", "acceleration_mps2", "mass_kg", "cg_x_m",
    "static_margin_cal", "thrust_N", "axial_force_N", "normal_force_N",
    "reynolds_per_m", "CA", "CN", "cp_x_m", "vz_l_mps", "airbrake_deployment",
)

_EPS_V = 1e-3      # [m/s] regularises |v| and the cross-flow at zero speed


def mass_properties(setup, t, P, motor=None, motor_props=None):
    """Total mass [kg], CG [m aft of tip] and inertia (3x3, about CG) [kg m^2].

    Dry rocket (+ offsets) + ballast point mass + motor(t) (``motor``: default
    the setup's; ``motor_props``: its (propellant mass, cg, (I_t, I_a)) given
    instead); parallel-axis theorem along the body axis.  Symbolic-safe in
    ``t`` and ``P``.
    """
    motor = setup.motor if motor is None else motor
    ts = P["burn_time_scale"]
    m_d = setup.dry.mass + P["dry_mass_offset"]
    x_d = setup.dry.cg_x + P["dry_cg_offset"]
    m_b, x_b = P["ballast_mass"], P["ballast_x"]
    if motor_props is None:
        m_m = motor.mass(t, time_scale=ts)
        x_m = setup.nozzle_x - motor.cg(t, time_scale=ts)
        it_m, ia_m = motor.inertia(t, time_scale=ts)
    else:
        m_p, cg_m, (it_m, ia_m) = motor_props
        m_m, x_m = motor.dry_mass + m_p, setup.nozzle_x - cg_m
    m = m_d + m_b + m_m
    x_cg = (m_d * x_d + m_b * x_b + m_m * x_m) / m
    transfer = m_d * (x_d - x_cg) ** 2 + m_b * (x_b - x_cg) ** 2 + m_m * (x_m - x_cg) ** 2
    inertia = ca.SX(setup.dry.inertia) * P["dry_inertia_scale"]
    inertia = inertia + ca.diag(ca.vertcat(ia_m, it_m + transfer, it_m + transfer))
    return m, x_cg, inertia


def _burnt_out(motor):
    """A solid motor's (propellant mass, cg, (I_t, I_a)) after burnout, as numbers: the
    coast phase starts at burnout (phases are split there), where the mass model's
    impulse has reached the total, so the coast needs no thrust-curve look-up.  None for
    other motors and for a motor slot (its data are symbols)."""
    from ironbark_opt.motors.solid import SolidMotor

    if not isinstance(motor, SolidMotor) or not isinstance(motor.burn_time, (int, float)):
        return None
    props = motor._mass_properties_unscaled(float(motor.burn_time))
    flat = [props[0], props[1], *props[2]]
    return props if all(isinstance(v, float) for v in flat) else None


def mass_rates(setup, t, P, motor, m, inertia):
    """d(mass)/dt [kg/s] and d(inertia)/dt (3x3) [kg m^2/s] of :func:`mass_properties`'
    ``m`` and ``inertia`` at symbolic ``t``.

    Where the motor's mass properties follow one scalar with a closed-form rate
    (:meth:`~ironbark_opt.motors.base.Motor.mass_driver`: a solid motor's delivered
    impulse, whose rate is the thrust), by the chain rule through it: the thrust-curve
    look-up already made serves, no derivative of the table is evaluated (the table's
    derivative look-ups measured ~1/4 of a compiled RK4 step).  Else the histories
    are differentiated symbolically.  Both give the same rates (to rounding).
    """
    drive = motor.mass_driver(t, time_scale=P["burn_time_scale"])
    if drive is None:
        return ca.jacobian(m, t), ca.jacobian(ca.vec(inertia), t).reshape((3, 3))
    d, d_dot, props = drive
    z = ca.SX.sym("mass_driver")
    m_z, _, inertia_z = mass_properties(setup, t, P, motor, props(z))
    mdot, idot = ca.jacobian(m_z, z) * d_dot, ca.jacobian(ca.vec(inertia_z), z) * d_dot
    mdot, idot = ca.substitute([mdot, idot], [z], [d])
    return mdot, idot.reshape((3, 3))


def _aero_state(setup, x, P):
    """Air data and body-frame aerodynamic forces/moments about the CG."""
    r_l, v_b, q, w_b = x[0:3], x[3:6], x[6:10], x[10:13]
    dT = P["temperature_offset"]
    h = r_l[2] + setup.site_elevation
    t_l = rotation_matrix(q)
    air = setup.atmosphere.state(h, dT)          # one layer/table lookup for all properties
    we, wn = air["wind_east"], air["wind_north"]
    wind_l = ca.vertcat(P["wind_scale"] * we + P["wind_east"], P["wind_scale"] * wn + P["wind_north"], 0)
    v_air_b = v_b - t_l.T @ wind_l
    rho = air["density"]
    a_sound = air["speed_of_sound"]
    mu = air["dynamic_viscosity"]
    speed2 = ca.dot(v_air_b, v_air_b)
    airspeed = ca.sqrt(speed2 + _EPS_V ** 2)
    cross = ca.sqrt(v_air_b[1] ** 2 + v_air_b[2] ** 2 + _EPS_V ** 2)
    alpha = ca.atan2(cross, v_air_b[0])
    return dict(h=h, t_l=t_l, v_air_b=v_air_b, rho=rho, a=a_sound, mu=mu, airspeed=airspeed,
                cross=cross, alpha=alpha, mach=airspeed / a_sound, qbar=0.5 * rho * speed2,
                re=rho * airspeed / mu, pressure=air["pressure"], w_b=w_b, v_b=v_b, q=q)


def build(setup, phase: str, cd_area: float = 0.0, n_p: int = params.SIZE) -> ca.Function:
    """CasADi Function ``f(x, t, p) -> (xdot, y)`` for one flight phase.

    Parameters
    ----------
    setup : FlightSetup
    phase : {'rail', 'boost', 'coast', 'descent'}
        'boost' uses power-on drag and thrust; 'coast' power-off and no
        thrust (phases are split at burnout, so no switch inside a step).
    cd_area : float [m^2]
        Parachute Cd*S, for the 'descent' phase only.
    n_p : int
        Length of ``p``: ``params.SIZE``, or more when the setup's motor is a
        slot whose curve and mass data follow the parameters in ``p``
        (:mod:`ironbark_opt.motors.slot`, one NLP for many motors).

    Returns
    -------
    casadi.Function
        Inputs ``x`` (13) [mixed SI], ``t`` [s], ``p`` (params.SIZE);
        outputs ``xdot`` (13, the complete derivative), ``y``
        (len(OUTPUT_NAMES)), ``c_roll`` [1/s], the roll-damping part of
        d(dw_x/dt)/dw_x, and ``f_roll`` [rad/s^2], the roll forcing (fin cant) part
        of dw_x/dt, which the integrator treats exactly together; SX-built.
    """
    if phase not in PHASES:
        raise ValueError(f"phase must be one of {PHASES}, got {phase!r}")
    x = ca.SX.sym("x", 13)
    t = ca.SX.sym("t")
    p = ca.SX.sym("p", n_p)
    P = params.unpack(p)
    aero = setup.aero
    motor = setup.motor.bind(p) if hasattr(setup.motor, "bind") else setup.motor
    burning = phase in ("rail", "boost")

    burnt = _burnt_out(motor) if phase == "coast" else None
    m, x_cg, inertia = mass_properties(setup, t, P, motor, burnt)
    s = _aero_state(setup, x, P)
    g = setup.gravity(s["h"]) if setup.gravity is not None else gravity(s["h"], setup.latitude)
    g_l = ca.vertcat(0, 0, -g)
    g_b = s["t_l"].T @ g_l
    thrust = motor.thrust(t, thrust_scale=P["thrust_scale"], time_scale=P["burn_time_scale"]) if burning else 0
    if burning:
        thrust = thrust + motor.pressure_thrust_correction(s["pressure"])

    area, dref = aero.reference_area, aero.reference_length
    alpha = 0 if phase == "rail" else s["alpha"]
    ca_coef, cn_coef, cm_coef = aero.coefficients(s["mach"], alpha, s["re"], power_on=burning)
    ca_coef = ca_coef * P["drag_scale"]
    brakes = getattr(setup, "airbrakes", None)
    deployment = 0 * t
    if brakes is not None and phase == "coast":
        # Air brakes: their drag-coefficient increment at the scheduled (smooth)
        # deployment, referred to the rocket's reference area (aero/airbrakes.py).
        vz_up = (s["t_l"] @ s["v_b"])[2]
        deployment = brakes.deployment(t, s["h"] - setup.site_elevation, s["mach"], vz_up, P)
        area_b = brakes.drag.reference_area or aero.reference_area
        ca_coef = ca_coef + brakes.drag.evaluate(deployment, s["mach"]) * (area_b / aero.reference_area)
    cn_coef = cn_coef * P["normal_force_scale"]
    cm_coef = cm_coef * P["normal_force_scale"]
    qs = s["qbar"] * area
    axial = -qs * ca_coef
    v_air_b, w_b, v_b = s["v_air_b"], s["w_b"], s["v_b"]
    e_c = ca.vertcat(0, v_air_b[1], v_air_b[2]) / s["cross"]

    if phase == "rail":
        a_axis = ca.fmax(0, (thrust + axial) / m + g_b[0])
        vdot = ca.vertcat(a_axis, 0, 0)
        xdot = ca.vertcat(s["t_l"] @ v_b, vdot, ca.SX.zeros(4), ca.SX.zeros(3))
        normal = 0 * axial
    elif phase == "descent":
        v_l_air = s["t_l"] @ v_air_b
        drag_l = -0.5 * s["rho"] * cd_area * s["airspeed"] * v_l_air
        vdot_l = drag_l / m + g_l
        vdot = s["t_l"].T @ vdot_l          # attitude frozen: dv_b/dt = T^BL dv_l/dt
        xdot = ca.vertcat(s["t_l"] @ v_b, vdot, ca.SX.zeros(4), ca.SX.zeros(3))
        normal = 0 * axial
    else:
        normal = qs * cn_coef
        f_b = ca.vertcat(thrust + axial, 0, 0) - normal * e_c
        # Aerodynamic moment about the table's reference point, then moved to
        # the CG: M_cg = M_ref + (r_ref - r_cg) x F, with r_ref - r_cg =
        # (x_cg - x_ref) e_x in body axes (x_aft grows toward -x_b).
        m_ref = qs * dref * cm_coef * ca.vertcat(0, e_c[2], -e_c[1])
        lever = ca.vertcat(x_cg - aero.moment_reference_x, 0, 0)
        m_aero = m_ref + ca.cross(lever, -normal * e_c)
        # Damping: q S d C (w d / 2V) = rho V S d^2 C w / 4 (no division by V).
        cmq = aero.pitch_damping(s["mach"], x_cg)
        cl_forcing, clp = aero.roll_coefficients(s["mach"])
        damp = 0.25 * s["rho"] * s["airspeed"] * area * dref ** 2
        m_damp = damp * ca.vertcat(clp * w_b[0], cmq * w_b[1], cmq * w_b[2])
        m_roll = ca.vertcat(qs * dref * cl_forcing, 0, 0)
        mdot, idot = (0, ca.SX.zeros(3, 3)) if burnt is not None else mass_rates(setup, t, P, motor, m, inertia)
        l_ne = setup.nozzle_x - x_cg
        m_jet = mdot * l_ne ** 2 * ca.vertcat(0, w_b[1], w_b[2])
        moment = m_aero + m_damp + m_roll + m_jet - ca.cross(w_b, inertia @ w_b) - idot @ w_b
        wdot = ca.solve(inertia, moment)
        # d(wdot_x)/d(w_x) of the roll-damping term alone: on light rockets with
        # large fins the stiffest mode of the whole flight (time constant of a
        # few ms).  The integrator advances it exactly (see rk4_step).
        c_roll = ca.solve(inertia, ca.vertcat(damp * clp, 0, 0))[0]
        # ... and the roll forcing (fin cant) that balances it: advanced with it, so the
        # roll rate relaxes toward its equilibrium -f_roll / c_roll exactly (rk4_step)
        f_roll = ca.solve(inertia, m_roll)[0]
        vdot = f_b / m - ca.cross(w_b, v_b) + g_b
        xdot = ca.vertcat(s["t_l"] @ v_b, vdot, quaternion_rate(s["q"], w_b), wdot)

    accel_l = s["t_l"] @ (vdot + ca.cross(w_b, v_b)) if phase not in ("rail", "descent") else s["t_l"] @ vdot
    cp_x = aero.center_of_pressure(s["mach"], alpha)
    y = ca.vertcat(
        s["h"], ca.norm_2(v_b), s["airspeed"], s["mach"], alpha, s["qbar"], ca.norm_2(accel_l),
        m, x_cg, (cp_x - x_cg) / dref, thrust, axial, normal, s["re"], ca_coef, cn_coef, cp_x,
        (s["t_l"] @ v_b)[2], deployment,
    )
    # Common-subexpression elimination: the aero pieces share many terms.
    if phase in ("rail", "descent"):
        c_roll = f_roll = 0 * t                 # no rotation in these phases
    xdot, y, c_roll, f_roll = ca.cse(xdot), ca.cse(y), ca.cse(c_roll), ca.cse(f_roll)
    return ca.Function(f"rhs_{phase}", [x, t, p], [xdot, y, c_roll, f_roll], ["x", "t", "p"],
                       ["xdot", "y", "c_roll", "f_roll"])
