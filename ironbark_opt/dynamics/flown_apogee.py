"""The apogee :meth:`FlightModel.run` reports, as a differentiable CasADi Function.

``run`` (and so ``simulate`` and the one-variable ``ballast`` root) flies the
coast on the model's grid over the horizon ``t_b + v_z,b / g0 + 2 s`` and
places apogee *inside* the step where ``v_z`` changes sign (Newton on the
step length).  :func:`~ironbark_opt.dynamics.model.apogee_functions` instead
stretches the coast grid to end exactly at the apogee time (the ballast
NLP's formulation).  Both are RK4 on the same number of steps, but on
different step boundaries, so their apogees differ by centimetres and their
derivatives by up to ~0.2 % (Calisto at 1.7 kg of ballast: d apogee / d
inclination 442.14 vs 441.28 m/rad).  Derivatives meant to predict what
``simulate`` and ``ballast`` will do must differentiate ``run``'s own
discretisation, which :func:`flown_apogee_function` builds:

- rail exit: the root of :meth:`FlightModel.rail_residual` (the residual
  ``run`` solves by secant), by CasADi's Newton ``rootfinder``;
- boost: the model's boost trajectory;
- coast: the model's coast trajectory over ``run``'s horizon (a function of
  ``p`` through the burnout state), to the start of the step that holds the
  nominal apogee (that step index is locally constant);
- apogee: the root ``h`` of ``v_z(step(x_k, t_k, h)) = 0`` in that step by
  ``rootfinder`` — the equation ``run``'s Newton iterations solve.

The event times are roots, so AD through the rootfinders gives the
implicit-function derivatives (Griewank & Walther, *Evaluating Derivatives*,
2nd ed., SIAM 2008, ch. 15).  Valid near ``p_nominal`` while the apogee stays
in the same coast step (a dispersion's or a finite difference's
neighbourhood, not an arbitrary other flight).
"""
from __future__ import annotations

import casadi as ca
import numpy as np

from ironbark_opt.dynamics.model import G0, _refuse_controller, max_boost_speed, rail_and_boost

#: horizon growth of ``FlightModel._ascent_phased`` when apogee lies beyond the first horizon
_HORIZON_GROWTH = (1.0, 1.5, 2.25)


def applies(model, run: dict) -> bool:
    """Whether :func:`flown_apogee_function` covers the flight ``run`` (``model.run(p)``):
    not for staged rockets (their own ``run``) nor for a flight whose ejection charge
    fires before apogee (``run`` flies that on another grid); ``apogee_functions``
    covers both."""
    return not hasattr(type(model), "final_state_symbolic") and "ejection_before_apogee_s" not in run


def flown_apogee_function(model, p_nominal) -> ca.Function | None:
    """``p -> (z_apogee [m AGL], t_apogee [s], rail_exit_speed [m/s], max_speed [m/s])``
    on :meth:`FlightModel.run`'s grid (see the module doc), the outputs of
    ``apogee_functions(model, p)["apogee"]``; an MX Function.  None where it does
    not apply (:func:`applies`).
    """
    _refuse_controller(model.setup)
    p_nominal = np.asarray(p_nominal, dtype=float)
    if hasattr(type(model), "final_state_symbolic"):
        return None
    run = model.run(p_nominal)
    if not applies(model, run):
        return None
    t_b0, t_a0 = float(run["t_burnout"]), float(run["t_apogee"])
    horizon0 = float(model.vz_l(run["x_burnout"])) / G0 + 2.0
    growth = next((c for c in _HORIZON_GROWTH if t_a0 <= t_b0 + c * horizon0), _HORIZON_GROWTH[-1])
    k = int(np.count_nonzero(run["phase"] == "coast")) - 1          # the coast step that holds apogee
    fr = model.coast_fractions_of(p_nominal)
    span0 = growth * horizon0
    h_nominal = t_a0 - (t_b0 + span0 * fr[k])

    p = ca.MX.sym("p", model.n_p)
    t_r, x_r, t_b, X_b = rail_and_boost(model, p, float(run["t_rail"]))
    x_b = X_b[:, -1]
    span = growth * (model.vz_l(x_b) / G0 + 2.0)
    x_k = x_b if k == 0 else model.trajectory["coast"](x_b, t_b, t_b + span, p)[:, k - 1]
    t_k = t_b + span * fr[k]
    h = ca.MX.sym("h")
    q = ca.MX.sym("q", model.n_p + 14)                      # (x_k, t_k, p) for the rootfinder
    vz = ca.Function("vz_in_step", [h, q], [model.vz_l(model.step["coast"](q[:13], q[13], h, q[14:]))])
    root = ca.rootfinder("apogee_in_step", "newton", vz, {"abstol": 1e-10, "max_iter": 30, "error_on_fail": True})
    h_a = root(h_nominal, ca.vertcat(x_k, t_k, p))
    x_a = model.step["coast"](x_k, t_k, h_a, p)
    v_max = max_boost_speed(X_b)
    return ca.Function("flown_apogee", [p], [x_a[2], t_k + h_a, ca.norm_2(x_r[3:6]), v_max],
                       ["p"], ["apogee_agl", "t_apogee", "rail_exit_speed", "max_speed"])
