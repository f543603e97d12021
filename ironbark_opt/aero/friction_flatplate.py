"""Flat-plate mean skin-friction coefficients and form factors.

All ``cf_*`` functions return the *mean* (length-averaged) skin-friction
coefficient ``C_F = D_friction / (q S_wet)`` of one side of a flat plate of
length L at zero pressure gradient, as a function of the edge Mach number and
the Reynolds number ``Re_L = rho_e u_e L / mu_e`` (edge = free stream here).
They are symbolic-safe (floats, NumPy arrays, CasADi SX/MX) and smooth except
for the documented kinks of the laminar/turbulent and smooth/rough switches.

Models (DESIGN.md sec. 5):

- laminar: Blasius ``1.328 / sqrt(Re)`` with Eckert's reference temperature
  for compressibility;
- turbulent: van Driest II (Kármán–Schoenherr incompressible law mapped by
  van Driest's F_c, F_Rx), solved exactly by Newton iterations written into the
  expression (no table needed, see `cf_incompressible_turbulent`);
- transitional: Prandtl–Schlichting composite ``Cf_turb - A / Re`` with A set
  from the transition Reynolds number;
- rough: Barrowman's roughness-limited value with its critical Reynolds
  number, applied where it exceeds the smooth value.

Wall temperature: adiabatic by default (recovery factor Pr^(1/3) = 0.89
turbulent, Pr^(1/2) = 0.85 laminar); a fixed wall-to-edge temperature ratio can
be given instead.  Reynolds numbers below `RE_FLOOR` are treated as `RE_FLOOR`
(the formulas do not apply there and the dynamic pressure is ~0 anyway).
"""
from __future__ import annotations

import casadi as ca
import numpy as np

from ironbark_opt import _math
from ironbark_opt.errors import InputError

GAMMA = 1.4                       #: ratio of specific heats of air [-]
PRANDTL = 0.72                    #: Prandtl number of air [-]
RECOVERY_TURBULENT = 0.89         #: turbulent recovery factor ~ Pr^(1/3) [-]
RECOVERY_LAMINAR = PRANDTL ** 0.5  #: laminar recovery factor Pr^(1/2) [-]
SUTHERLAND_S = 110.4              #: Sutherland constant of air [K] (White, Viscous Fluid Flow, Table 1-2)
T_DEFAULT = 288.15                #: default edge (static) temperature [K], ISA sea level
RE_FLOOR = 1.0e3                  #: Reynolds numbers are clamped to at least this [-]
MACH_FLOOR = 1.0e-3               #: Mach floor avoiding 0/0 in van Driest's F_c [-]
RE_TRANSITION_DEFAULT = 5.0e5     #: transition Reynolds number (Niskanen 2009, sec. 3.4.1) [-]


def smooth_step(x, x0: float, x1: float):
    """0 for x <= x0, 1 for x >= x1, quintic 6t^5 - 15t^4 + 10t^3 between [-]; symbolic-safe.

    Twice continuously differentiable, and exactly 0 / 1 outside [x0, x1], so a blend
    built with it leaves the blended formulas untouched outside the band.
    """
    t = _math.clip((x - x0) / (x1 - x0), 0.0, 1.0)
    return t * t * t * (10.0 + t * (-15.0 + 6.0 * t))


def _asin(x):
    return ca.asin(x) if _math.is_symbolic(x) else np.arcsin(x)


def viscosity_ratio(temperature_ratio, temperature=T_DEFAULT):
    """mu(T_e * ratio) / mu(T_e) by Sutherland's law [-]; symbolic-safe.

    Parameters
    ----------
    temperature_ratio : float or array or SX/MX [-]
        T / T_e.
    temperature : float or SX/MX [K]
        Edge static temperature T_e.
    """
    # Sutherland (1893): mu ~ T^1.5 / (T + S)
    return temperature_ratio ** 1.5 * (temperature + SUTHERLAND_S) / (
        temperature * temperature_ratio + SUTHERLAND_S)


def recovery_temperature_ratio(mach, recovery=RECOVERY_TURBULENT):
    """Adiabatic-wall (recovery) temperature over edge temperature [-]; symbolic-safe.

    T_aw / T_e = 1 + r (gamma - 1) / 2 M^2 (recovery-factor definition, e.g. White,
    Viscous Fluid Flow, ch. 7).
    """
    return 1.0 + recovery * 0.5 * (GAMMA - 1.0) * mach * mach


def cf_laminar_blasius(mach, reynolds, temperature=T_DEFAULT, wall_temperature_ratio=None):
    """Laminar mean skin friction, Blasius + Eckert reference temperature [-]; symbolic-safe.

    Parameters
    ----------
    mach : float, array or SX/MX [-]
    reynolds : float, array or SX/MX [-]
        Re_L on edge conditions; clamped to >= `RE_FLOOR`.
    temperature : float or SX/MX [K]
        Edge static temperature.
    wall_temperature_ratio : float or None [-]
        T_w / T_e; None = adiabatic wall (recovery factor Pr^0.5).
    """
    re = _math.fmax(reynolds, RE_FLOOR)
    t_r = recovery_temperature_ratio(mach, RECOVERY_LAMINAR)
    t_w = t_r if wall_temperature_ratio is None else wall_temperature_ratio
    # Eckert (1955), "Engineering relations for friction and heat transfer to surfaces
    # in high velocity flow", J. Aeronaut. Sci. 22(8): T* = Te + 0.5 (Tw - Te) + 0.22 (Tr - Te)
    t_star = 1.0 + 0.5 * (t_w - 1.0) + 0.22 * (t_r - 1.0)
    # Chapman-Rubesin parameter at T*: C* = rho* mu* / (rho_e mu_e) = mu*/mu_e / (T*/Te)
    c_star = viscosity_ratio(t_star, temperature) / t_star
    # Blasius mean skin friction C_F = 1.328 / sqrt(Re_L) (Blasius 1908; Schlichting,
    # Boundary-Layer Theory, 7th ed., ch. VII), with properties at T*: C_F = 1.328 sqrt(C*) / sqrt(Re_L)
    return 1.328 * _math.sqrt(c_star / re)


def cf_incompressible_turbulent(reynolds):
    """Kármán–Schoenherr mean turbulent skin friction [-]; symbolic-safe.

    Solves 0.242 / sqrt(C_F) = log10(Re_L C_F) (Schoenherr 1932; the incompressible
    law used with van Driest II by Hopkins & Inouye, AIAA J. 9(6), 1971) exactly:
    Newton's method on u = 1/sqrt(C_F), g(u) = 0.242 u + 2 log10 u - log10 Re = 0, started
    from the explicit Prandtl–Schlichting value 0.455 / (log10 Re)^2.58 (Schlichting,
    Boundary-Layer Theory, 7th ed., ch. XXI), five iterations written into the expression.
    g is increasing and concave, so the iterates converge monotonically; the residual is
    below 1e-13 relative for Re in [1e3, 1e12] (see tests/unit/test_friction_flatplate.py).

    Parameters
    ----------
    reynolds : float, array or SX/MX [-]
        Re_L, clamped to >= `RE_FLOOR`.
    """
    log_re = _math.log10(_math.fmax(reynolds, RE_FLOOR))
    u = 1.0 / _math.sqrt(0.455 / log_re ** 2.58)
    ln10 = float(np.log(10.0))
    for _ in range(5):
        g = 0.242 * u + 2.0 * _math.log10(u) - log_re
        u = u - g / (0.242 + 2.0 / (u * ln10))
    return 1.0 / (u * u)


def van_driest_factors(mach, temperature=T_DEFAULT, wall_temperature_ratio=None,
                       recovery=RECOVERY_TURBULENT):
    """Van Driest II transformation factors (F_c, F_Rx) [-]; symbolic-safe.

    C_F = C_F,inc(F_Rx Re_L) / F_c (Hopkins & Inouye, "An evaluation of theories for
    predicting turbulent skin friction and heat transfer on flat plates at supersonic and
    hypersonic Mach numbers", AIAA J. 9(6), 1971, van Driest II section; van Driest,
    J. Aeronaut. Sci. 23, 1956).  With m = (gamma-1)/2 M^2 and F = T_w/T_e:
    A = sqrt(r m / F), B = (1 + r m - F) / F, F_c = r m / (asin a + asin b)^2 with
    a = (2A^2 - B)/sqrt(B^2 + 4A^2), b = B/sqrt(B^2 + 4A^2); F_Rtheta = mu_e/mu_w (Sutherland),
    F_Rx = F_Rtheta / F_c.

    Parameters
    ----------
    mach : float, array or SX/MX [-]
        Clamped to >= `MACH_FLOOR` (F_c -> 1 as M -> 0).
    temperature : float or SX/MX [K]
        Edge static temperature.
    wall_temperature_ratio : float or None [-]
        T_w/T_e; None = adiabatic wall with recovery factor ``recovery``.
    """
    mach = _math.fmax(mach, MACH_FLOOR)
    m = 0.5 * (GAMMA - 1.0) * mach * mach
    f = 1.0 + recovery * m if wall_temperature_ratio is None else wall_temperature_ratio
    a2 = recovery * m / f
    b = (1.0 + recovery * m - f) / f
    den = _math.sqrt(b * b + 4.0 * a2)
    f_c = recovery * m / (_asin((2.0 * a2 - b) / den) + _asin(b / den)) ** 2
    f_rtheta = 1.0 / viscosity_ratio(f, temperature)
    return f_c, f_rtheta / f_c


def cf_turbulent_van_driest(mach, reynolds, temperature=T_DEFAULT, wall_temperature_ratio=None):
    """Turbulent mean skin friction by van Driest II [-]; symbolic-safe.

    C_F = C_F,inc(F_Rx Re_L) / F_c with the Kármán–Schoenherr law (`van_driest_factors`,
    `cf_incompressible_turbulent`).

    Parameters
    ----------
    mach : float, array or SX/MX [-]
    reynolds : float, array or SX/MX [-]
    temperature : float or SX/MX [K]
    wall_temperature_ratio : float or None [-]
        T_w/T_e; None = adiabatic.
    """
    f_c, f_rx = van_driest_factors(mach, temperature, wall_temperature_ratio)
    return cf_incompressible_turbulent(_math.fmax(reynolds, RE_FLOOR) * f_rx) / f_c


def cf_transitional(mach, reynolds, re_transition=RE_TRANSITION_DEFAULT,
                    temperature=T_DEFAULT, wall_temperature_ratio=None):
    """Mean skin friction with a laminar run up to ``re_transition`` [-]; symbolic-safe.

    Prandtl–Schlichting composite (Schlichting, Boundary-Layer Theory, 7th ed., ch. XXI:
    C_F = 0.455/(log Re)^2.58 - A/Re, A = 1700 for Re_tr = 5e5), here with the van Driest II
    turbulent law and A = Re_tr (C_F,turb(Re_tr) - C_F,lam(Re_tr)), so the composite equals
    the laminar value at Re_tr; below Re_tr the plate is laminar.  Taken as
    max(laminar, composite), which switches exactly at Re_tr.

    Parameters
    ----------
    mach, reynolds : float, array or SX/MX [-]
    re_transition : float [-]
    temperature : float or SX/MX [K]
    wall_temperature_ratio : float or None [-]
    """
    if not re_transition > 0:
        raise InputError(f"expected a positive transition Reynolds number, got {re_transition!r}",
                         field="re_transition")
    re = _math.fmax(reynolds, RE_FLOOR)
    lam = cf_laminar_blasius(mach, re, temperature, wall_temperature_ratio)
    turb = cf_turbulent_van_driest(mach, re, temperature, wall_temperature_ratio)
    a = re_transition * (cf_turbulent_van_driest(mach, re_transition, temperature,
                                                 wall_temperature_ratio)
                         - cf_laminar_blasius(mach, re_transition, temperature,
                                              wall_temperature_ratio))
    return _math.fmax(lam, turb - a / re)


def critical_reynolds_roughness(length, roughness):
    """Reynolds number above which roughness sets the friction [-]; symbolic-safe.

    Re_crit = 51 (R_s / L)^-1.039 (Barrowman 1967; Niskanen, OpenRocket technical
    documentation 2013, eq. 3.79).  ``length`` [m], ``roughness`` (equivalent sand-grain
    height R_s) [m], both > 0.
    """
    return 51.0 * (roughness / length) ** -1.039


def cf_roughness_limited(mach, length, roughness):
    """Barrowman's roughness-limited mean skin friction, compressible [-]; symbolic-safe.

    C_F = 0.032 (R_s/L)^0.2 (Niskanen 2013, eq. 3.80), corrected by (1 - 0.1 M^2) subsonic
    (eq. 3.82) and 1/(1 + 0.18 M^2) supersonic (eq. 3.84).  The two corrections differ by
    6 % at M = 1; here they are blended by `smooth_step` over 0.9 < M < 1.1 so the value is
    smooth (our choice, not Barrowman's); outside that band the formulas are exact.

    Parameters
    ----------
    mach : float, array or SX/MX [-]
    length : float [m]
    roughness : float [m]
    """
    cf = 0.032 * (roughness / length) ** 0.2
    w = smooth_step(mach, 0.9, 1.1)
    return cf * ((1.0 - w) * (1.0 - 0.1 * mach * mach) + w / (1.0 + 0.18 * mach * mach))


def cf_flat_plate(mach, reynolds, length, roughness=0.0, re_transition=RE_TRANSITION_DEFAULT,
                  temperature=T_DEFAULT, wall_temperature_ratio=None):
    """Mean skin friction of a plate of given length and roughness [-]; symbolic-safe.

    max(transitional smooth value, roughness-limited value): the rough value "should not be
    used if it would yield a value smaller than the corresponding turbulent value" (Niskanen
    2013, after eq. 3.84); against the turbulent law it takes over near Barrowman's critical
    Reynolds number (within a factor 2, tested).  Against a still partly laminar plate it can
    take over earlier: a surface that rough is taken to trip the boundary layer (our choice;
    it keeps the value continuous, unlike a switch at Re_crit).

    Parameters
    ----------
    mach, reynolds : float, array or SX/MX [-]
        ``reynolds`` is Re based on ``length``.
    length : float [m]
    roughness : float [m]
        Equivalent sand-grain roughness height; 0 = hydraulically smooth.
    re_transition : float [-]
    temperature : float or SX/MX [K]
    wall_temperature_ratio : float or None [-]
    """
    smooth = cf_transitional(mach, reynolds, re_transition, temperature, wall_temperature_ratio)
    if roughness <= 0:
        return smooth
    return _math.fmax(smooth, cf_roughness_limited(mach, length, roughness))


def form_factor_body(fineness):
    """Form factor of a streamlined body of revolution [-]; symbolic-safe.

    FF = 1 + 1.5 / f^1.5 + 7 / f^3, f = L/D (Hoerner, Fluid-Dynamic Drag, 1965, ch. 6,
    streamline bodies: friction plus pressure drag on the wetted area; also listed in
    Gudmundsson, General Aviation Aircraft Design, 2014, sec. 16.3.5).
    """
    return 1.0 + 1.5 / fineness ** 1.5 + 7.0 / fineness ** 3


def form_factor_fin(thickness_ratio):
    """Form factor of a fin section of thickness ratio t/c [-]; symbolic-safe.

    FF = 1 + 2 t/c + 60 (t/c)^4 (Hoerner, Fluid-Dynamic Drag, 1965, ch. 6, for sections
    with maximum thickness near 30 % chord; as given by Gudmundsson, General Aviation
    Aircraft Design, 2014, sec. 16.3.5, eq. 16-123).
    """
    return 1.0 + 2.0 * thickness_ratio + 60.0 * thickness_ratio ** 4
