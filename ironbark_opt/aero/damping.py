"""Pitch/yaw damping and roll forcing/damping derivatives from geometry.

Linear (small-rate) derivatives for the 6-DOF model, from the same
component build-up as :mod:`ironbark_opt.aero.barrowman`.

Nondimensional rates (the usual aeroballistic convention): pitch rate
``q_hat = q d / (2 V)`` and roll rate ``p_hat = p d / (2 V)``, with ``d`` the
reference length and ``V`` the airspeed, so the moment coefficients are

    Cm = ... + Cmq * q_hat,      Cl = Cl_delta * delta + Clp * p_hat.

Choices where the sources differ:

* Pitch damping is the *linear* derivative of the lifting components
  (each component's slope acting at its own CP sees the local angle of
  attack q (x_cg - x_cp)/V), ``Cmq = -2 sum CN_alpha_i ((x_cp_i - x_cg)/d)^2``
  — the tail term of aircraft stability texts, Cmq = -2 eta a_t V_H l_t/c
  (R. C. Nelson, "Flight Stability and Automatic Control", 2nd ed., 1998,
  ch. 4, pitch-rate derivatives), applied to every lifting component with
  its slope referenced to A_ref and its arm x_cp_i - x_cg in units of d.
  The OpenRocket damping moment ([N13]
  §3.2.3 eq. 3.57-3.59) is quadratic in the rate (cross-flow drag of the
  body and fins, ~ omega^2/V^2), has no linear part, and is not used
  here.  Cm_alpha_dot is not included.
* Roll forcing and damping: strip theory of [N13] §3.3 (eq. 3.66 and
  3.68-3.70) with the two-dimensional section slope ``2 pi / beta``
  subsonic (thin-airfoil theory with Prandtl-Glauert, [N13] eq. 3.38) and
  the linear (Ackeret) ``4 / beta`` supersonic (the linear term of the
  pressure difference across the plate; second- and third-order Busemann
  terms dropped for a derivative at p = 0), bridged across the transonic
  gap by :func:`~ironbark_opt.aero.barrowman.transonic_blend`.  No
  fin-body interference factor in roll (as [N13] eq. 3.66).

[N13] S. Niskanen, "OpenRocket technical documentation", v13.05, 2013.
"""
from __future__ import annotations

import math
from typing import Sequence

from ironbark_opt import _math as m
from ironbark_opt.aero.barrowman import (FinPlanform, Lift, _non_negative, _positive,
                                         fin_count_factor, single_fin_cn_alpha,
                                         transonic_blend)
from ironbark_opt.errors import InputError


def pitch_damping_cmq(components: Sequence[Lift], x_cg, reference_length: float):
    """Pitch (and, by symmetry, yaw) damping derivative Cmq about the CG [-/rad].

    Cmq = dCm / d(q d / 2V) = -2 sum_i CN_alpha_i ((x_cp_i - x_cg)/d)^2
    (Nelson's tail term for each component; see module notes).  Always <= 0 for
    positive slopes.  Symbolic-safe in ``x_cg`` (it moves as the motor
    burns) and in the component values (Mach-dependent fin slopes).

    Parameters
    ----------
    components : sequence of Lift
        Component slopes [1/rad] and CPs [m], e.g. from
        :mod:`~ironbark_opt.aero.barrowman`.
    x_cg : float, array or CasADi [m]
        Current CG, aft of the nose tip.
    reference_length : float [m]
        Reference length d of the coefficients.
    """
    d = _positive(reference_length, "reference_length")
    comps = list(components)
    if not comps:
        raise InputError("need at least one component", field="components")
    cmq = 0.0
    for c in comps:
        arm = (c.x_cp - x_cg) / d
        cmq = cmq - 2.0 * c.cn_alpha * arm * arm
    return cmq


def section_lift_slope(mach):
    """Two-dimensional (strip) normal-force slope of a thin section [1/rad].

    2 pi / sqrt(1 - M^2) subsonic ([N13] eq. 3.38) and 4 / sqrt(M^2 - 1)
    supersonic (Ackeret), joined C1-continuously over Mach 0.9-1.5.
    Symbolic-safe in ``mach``.

    Parameters
    ----------
    mach : float, array or CasADi [-]
    """
    def sub(M):
        b2 = 1.0 - M * M
        return 2.0 * math.pi / m.sqrt(b2), 2.0 * math.pi * M / (b2 * m.sqrt(b2))

    def sup(M):
        b2 = M * M - 1.0
        return 4.0 / m.sqrt(b2), -4.0 * M / (b2 * m.sqrt(b2))

    return transonic_blend(mach, sub, sup)


def _check_fin_set(count, body_radius, reference_area, reference_length):
    fin_count_factor(count)  # validates count
    return (int(count), _non_negative(body_radius, "body_radius"),
            _positive(reference_area, "reference_area", "m^2"),
            _positive(reference_length, "reference_length"))


def roll_forcing_cl_delta(planform: FinPlanform, count: int, body_radius: float,
                          reference_area: float, reference_length: float, mach=0.0):
    """Roll-forcing derivative Cl_delta of a canted fin set [1/rad of cant].

    Cl_delta = N (y_MAC + r_t) (CN_alpha)_1 / d  ([N13] eq. 3.66), with the
    single-fin slope of :func:`~ironbark_opt.aero.barrowman.single_fin_cn_alpha`
    (sub- and supersonic).  Positive cant gives a positive rolling moment.
    Symbolic-safe in ``mach``.

    Parameters
    ----------
    planform : FinPlanform
    count : int
        Number of fins N (all with the same cant).
    body_radius : float [m]
        Body radius r_t at the fins.
    reference_area : float [m^2]
    reference_length : float [m]
    mach : float, array or CasADi [-]
    """
    n, r, aref, d = _check_fin_set(count, body_radius, reference_area, reference_length)
    return n * (planform.mac_y + r) * single_fin_cn_alpha(planform, mach, aref) / d


def roll_damping_clp(planform: FinPlanform, count: int, body_radius: float,
                     reference_area: float, reference_length: float, mach=0.0):
    """Roll-damping derivative Clp = dCl / d(p d / 2V) of a fin set [-/rad].

    Strip theory, [N13] eq. 3.68-3.69 linearised: a strip at xi from the
    axis sees the angle p xi / V, so
    Cl = -N CN_alpha0 (p/V) int c(xi) xi^2 dxi / (A_ref d) and
    Clp = -2 N CN_alpha0 int c xi^2 dxi / (A_ref d^2), with CN_alpha0 from
    :func:`section_lift_slope`; the integral is
    :meth:`FinPlanform.roll_integral` ([N13] eq. 3.70 for trapezoids).
    Negative.  Symbolic-safe in ``mach``.

    Parameters
    ----------
    planform : FinPlanform
    count : int
    body_radius : float [m]
    reference_area : float [m^2]
    reference_length : float [m]
    mach : float, array or CasADi [-]
    """
    n, r, aref, d = _check_fin_set(count, body_radius, reference_area, reference_length)
    integral = planform.roll_integral(r)
    return -2.0 * n * section_lift_slope(mach) * integral / (aref * d * d)


def steady_roll_rate(cl_delta, clp, cant, speed, reference_length: float):
    """Roll rate at which canting and damping balance, p = -2 V Cl_delta delta / (Clp d) [rad/s].

    The linear version of [N13] §3.3.3 (equilibrium roll frequency, times
    2 pi).  Symbolic-safe.

    Parameters
    ----------
    cl_delta : float or CasADi [1/rad]
    clp : float or CasADi [-/rad]
    cant : float or CasADi [rad]
        Fin cant angle delta.
    speed : float or CasADi [m/s]
        Airspeed V.
    reference_length : float [m]
    """
    d = _positive(reference_length, "reference_length")
    return -2.0 * speed * cl_delta * cant / (clp * d)
