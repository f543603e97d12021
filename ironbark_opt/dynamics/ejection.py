"""Recovery deployed by the motor's ejection charge (burnout + delay).

Model and small rockets open their parachute when the motor's delay charge
fires, ``t_e = t_burnout + delay`` (NAR/Estes motor designation ``C6-5``: 5 s
of delay after the thrust ends), not at apogee.  The flight core flies it as a
fixed sequence of phases:

- **early** (``t_e`` before the coasting apogee): coast to ``t_e``, then the
  descent equations under the ejection-deployed chutes (point mass, drag
  ``Cd S`` along the air-relative velocity, as under any parachute in
  :mod:`ironbark_opt.dynamics.rhs`) up to the apogee, the root of
  ``v_z(T) = 0`` over ``N_EJECTED`` uniform RK4 steps from ``t_e`` to ``T``;
  the same phases are the symbolic graph of ballast and sensitivities
  (:func:`ejected_final_state`), so the apogee stays differentiable;
- **late** (after apogee): a ballistic coast from apogee to ``t_e``, then the
  descent as usual (apogee unaffected).

Which case applies is decided on the nominal flight (the event sequence is
fixed per configuration, as for staging); Monte Carlo samples are flown
each in their own case.  Numeric-only except :func:`ejected_final_state`.
"""
from __future__ import annotations

import numpy as np

from ironbark_opt import params

#: RK4 steps from ejection to apogee under the chute (uniform; a few seconds).
N_EJECTED = 100

#: An ejection this long after apogee [s] is reported as late.
LATE_EJECTION_S = 2.0


def ejection_cd_area(setup) -> float:
    """Total Cd*S [m^2] of the chutes opened by the ejection charge."""
    return float(sum(c.cd_area for c in getattr(setup, "parachutes", ()) if c.at_ejection))


def ejection_time(setup, p):
    """``t_burnout * burn_time_scale + delay`` [s], or None when nothing deploys
    at ejection; symbolic-safe in ``p`` (a vector or an unpacked dict)."""
    delay = getattr(setup, "ejection_delay", None)
    if delay is None or ejection_cd_area(setup) <= 0:
        return None
    scale = p["burn_time_scale"] if isinstance(p, dict) else p[params.index("burn_time_scale")]
    return float(setup.motor.burn_time) * scale + delay


def ejected_trajectory(model):
    """``(x0, t0, T, p) -> X`` (13 x N_EJECTED) under the ejection chutes."""
    cache = model.__dict__.setdefault("_ejected", {})
    if "traj" not in cache:
        from ironbark_opt.dynamics.integrator import phase_trajectory
        _, step, _, _ = model._descent_functions(ejection_cd_area(model.setup), "ejected")
        cache["traj"] = phase_trajectory(step, N_EJECTED, "traj_ejected")
    return cache["traj"]


def apogee_under_chute(model, x_e, t_e: float, p, t_guess: float):
    """Numeric apogee after an early ejection: (T [s], X (13 x N_EJECTED)).

    Secant on ``v_z(T)`` of the same N-step trajectory the symbolic graph
    uses, bracketed in (t_e, t_hi]."""
    from scipy.optimize import brentq

    traj = ejected_trajectory(model)

    def vz(T):
        return float(model.vz_l(np.array(traj(x_e, t_e, T, p))[:, -1]))

    hi = max(t_guess, t_e + 0.5)
    for _ in range(20):
        if vz(hi) < 0:
            break
        hi = t_e + 2.0 * (hi - t_e)
    T = brentq(vz, t_e + 1e-9, hi, xtol=1e-10, rtol=1e-13)
    return T, np.array(traj(x_e, t_e, T, p))


def fly_early(model, x_b, t_b: float, t_e: float, p, t_coast_apogee: float):
    """The ascent after burnout with the chute out at ``t_e`` < apogee.

    Returns (t samples, X samples, phase labels, T_apogee, x_apogee)."""
    X_c = np.array(model._run["coast"](x_b, t_b, t_e, p))
    fr = model.coast_fractions
    t_c = t_b + (t_e - t_b) * fr[1:]
    T, X_e = apogee_under_chute(model, X_c[:, -1], t_e, p, t_coast_apogee)
    t_ej = t_e + (T - t_e) * np.arange(1, N_EJECTED + 1) / N_EJECTED
    phase = ["coast"] * X_c.shape[1] + ["ejected"] * N_EJECTED
    return (np.concatenate([t_c, t_ej]), np.hstack([X_c, X_e]), phase, T, X_e[:, -1])


def coast_to_late_ejection(model, x_a, t_a: float, t_e: float, p):
    """Ballistic coast from apogee to a late ejection: (t samples, X samples),
    or None when the rocket would land first (the chutes then open at apogee)."""
    X = np.array(model._run["coast"](x_a, t_a, t_e, p))
    if np.any(X[2] <= 0.0):
        return None
    return t_a + (t_e - t_a) * model.coast_fractions[1:], X


def ejected_final_state(model, x_b, t_b, p, T):
    """Symbolic (MX) state at ``T`` after an early ejection: coast to
    ``t_e = t_b + delay`` then the chute phase to ``T``."""
    t_e = t_b + model.setup.ejection_delay
    x_e = model.trajectory["coast"](x_b, t_b, t_e, p)[:, -1]
    return ejected_trajectory(model)(x_e, t_e, T, p)[:, -1]


def ejects_before_apogee(model) -> bool:
    """Whether the nominal flight's charge fires before its coasting apogee
    (fixes the phase sequence of the symbolic graph); cached on the model."""
    cache = model.__dict__.setdefault("_ejected", {})
    if "early" not in cache:
        run = model.run(model.setup.nominal_parameters())
        cache["early"] = bool(run.get("ejection_before_apogee_s", 0.0) > 0.0)
    return cache["early"]


def describe(run: dict, setup) -> dict:
    """Summary keys and a warning text (or None) for a flown run."""
    t_e = run.get("t_ejection")
    if t_e is None:
        return {}, None
    out = {"ejection_time_s": float(t_e), "ejection_delay_s": float(setup.ejection_delay)}
    early = run.get("ejection_before_apogee_s", 0.0)
    if early > 0.0:
        out.update(ejection_before_apogee_s=float(early),
                   coasting_apogee_agl_m=float(run["coasting_apogee_agl_m"]),
                   ejection_altitude_agl_m=float(run["x_ejection"][2]),
                   ejection_speed_mps=float(np.linalg.norm(run["x_ejection"][3:6])))
        lost = run["coasting_apogee_agl_m"] - float(run["x_apogee"][2])
        return out, (f"{setup.name}: the ejection charge fires {early:.2f} s before apogee "
                     f"(at {out['ejection_altitude_agl_m']:.1f} m AGL, {out['ejection_speed_mps']:.1f} m/s): "
                     f"the chute opens on the way up and the apogee is {lost:.1f} m lower than the "
                     f"coasting {out['coasting_apogee_agl_m']:.1f} m; choose a longer delay")
    late = float(t_e - run["t_apogee"])
    out["ejection_after_apogee_s"] = late
    if late > LATE_EJECTION_S:
        return out, (f"{setup.name}: the ejection charge fires {late:.2f} s after apogee "
                     f"(the rocket falls freely until then); choose a shorter delay")
    return out, None
