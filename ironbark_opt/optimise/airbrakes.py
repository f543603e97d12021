"""The air-brake deployment that hits a target apogee.

Problem (IPOPT, CasADi ``nlpsol``), variables ``w = (v, T)`` with ``v`` one
schedule parameter, ``airbrake_level`` [-] (how far the brakes open) or
``airbrake_start_time`` [s] (when they start opening, time trigger):

    find        v, T
    subject to  v_z(T; p(v)) = 0          (T is the apogee time)
                z(T; p(v))   = target      [m AGL]
                bounds: level in [0, 1]; start in [burnout, apogee without brakes]

The deployment is a smooth function of the schedule's parameters inside the
one right-hand side (:mod:`ironbark_opt.aero.airbrakes`), so the same phased
RK4 trajectory as ``simulate`` is differentiated (no switch inside a step)
and the answer re-simulates onto the target.  Before IPOPT runs, the two
ends of the range bracket the target; a target outside is reported
infeasible with the closest reachable apogee.  Numeric-only.
"""
from __future__ import annotations

import time
from dataclasses import dataclass, field
from typing import Mapping

import casadi as ca
import numpy as np

from ironbark_opt import params
from ironbark_opt.dynamics.model import _final_state
from ironbark_opt.errors import InputError, SolverError
from ironbark_opt.flight import flight_model, simulate
from ironbark_opt.optimise.target import parse_target

VARIABLES = ("airbrake_level", "airbrake_start_time")
_KEYS = {"airbrake_level": "airbrake_level", "airbrake_start_time": "airbrake_start_time_s"}


@dataclass(frozen=True)
class AirbrakeSolution:
    """Result of :func:`solve_airbrakes` (immutable).

    Attributes
    ----------
    variable : str
        The solved parameter.
    values : dict
        ``airbrake_level``, ``airbrake_start_time_s``, ``target_agl_m``,
        ``apogee_agl_m``, ``apogee_time_s``, ``resimulated_apogee_agl_m``,
        ``apogee_error_m``, ``apogee_without_brakes_agl_m``, ``solve_time_s``.
    """

    name: str
    variable: str
    feasible: bool
    status: str
    values: Mapping[str, float]
    parameters: Mapping[str, float] = field(repr=False, default_factory=dict)

    def __repr__(self) -> str:
        v = self.values
        return (f"AirbrakeSolution({self.name!r}: level {v['airbrake_level']:.3f} from "
                f"{v['airbrake_start_time_s']:.2f} s -> apogee {v['apogee_agl_m']:.1f} m AGL, "
                f"{'feasible' if self.feasible else 'INFEASIBLE'})")

    def to_dict(self) -> dict:
        out = {"rocket": self.name, "solved": self.variable, "feasible": self.feasible, "status": self.status}
        out.update(self.values)
        out["parameters"] = dict(self.parameters)
        return out

    def summary(self) -> str:
        v = self.values
        return "\n".join([
            f"Air brakes for {self.name}: {'feasible' if self.feasible else 'NOT feasible'} ({self.status}), "
            f"solved {self.variable}",
            f"  target             {v['target_agl_m']:10.1f} m AGL ({v['target_agl_m'] / 0.3048:.0f} ft)",
            f"  deployment level   {v['airbrake_level']:10.4f} (0 stowed, 1 open)",
            f"  start time         {v['airbrake_start_time_s']:10.3f} s after ignition",
            f"  apogee             {v['apogee_agl_m']:10.1f} m AGL at {v['apogee_time_s']:.2f} s "
            f"(re-simulated {v['resimulated_apogee_agl_m']:.1f} m)",
            f"  without brakes     {v['apogee_without_brakes_agl_m']:10.1f} m AGL",
            f"  solve time         {v['solve_time_s']:10.2f} s"])


def solve_airbrakes(setup, target, *, variable: str = "airbrake_level",
                    parameters: Mapping[str, float] | None = None,
                    ipopt_options: Mapping | None = None) -> AirbrakeSolution:
    """Deployment level (or start time) of ``setup``'s air brakes that puts
    apogee on ``target``.

    Parameters
    ----------
    setup : FlightSetup
        With air brakes on a differentiable schedule (not a Python controller).
    target : str, float or Target
        e.g. ``"3000 m"``, ``"10000ft"``, or a number [m AGL].
    variable : {'airbrake_level', 'airbrake_start_time'}
        The schedule parameter solved for; the other stays at its nominal value.
    parameters : mapping, optional
        Other parameter overrides (SI).
    ipopt_options : mapping, optional

    Returns
    -------
    AirbrakeSolution
    """
    t0 = time.perf_counter()
    brakes = getattr(setup, "airbrakes", None)
    if brakes is None:
        raise InputError("the rocket has no air brakes: add an [airbrakes] section", source=setup.source,
                         field="airbrakes")
    if not brakes.differentiable:
        raise InputError("a Python controller's deployment cannot be solved for: use a schedule "
                         "(trigger = time, altitude, mach or vertical_speed)", source=setup.source,
                         field="airbrakes.trigger")
    if variable not in VARIABLES:
        raise InputError(f"can solve for {', '.join(VARIABLES)}, got {variable!r}", field="solve")
    if variable == "airbrake_start_time" and brakes.trigger != "time":
        raise InputError(f"the start time is a parameter of the time trigger only (this rocket's trigger is "
                         f"'{brakes.trigger}'); solve airbrake_level instead", source=setup.source,
                         field="airbrakes.trigger")
    tgt = parse_target(target)
    target_agl = tgt.agl(setup.site_elevation)
    model = flight_model(setup)
    p_nom = setup.nominal_parameters(**dict(parameters or {}))
    i_v = params.index(variable)
    i_l = params.index("airbrake_level")

    def fly(value):
        p = p_nom.copy()
        p[i_v] = value
        return model.run(p)

    p_off = p_nom.copy()
    p_off[i_l] = 0.0
    free = model.run(p_off)
    if variable == "airbrake_level":
        lo_v, hi_v = 0.0, 1.0                # more deployment, lower apogee
    else:
        lo_v, hi_v = float(free["t_burnout"]), float(free["t_apogee"])   # earlier start, lower apogee
    run_lo, run_hi = fly(lo_v), fly(hi_v)
    a_lo, a_hi = float(run_lo["x_apogee"][2]), float(run_hi["x_apogee"][2])
    a_min, a_max = min(a_lo, a_hi), max(a_lo, a_hi)
    common = dict(model=model, p_nom=p_nom, variable=variable, target_agl=target_agl, t0=t0,
                  free=float(free["x_apogee"][2]))
    if not a_min <= target_agl <= a_max:
        best = lo_v if abs(a_lo - target_agl) < abs(a_hi - target_agl) else hi_v
        reach = f"reachable apogees {a_min:.1f}..{a_max:.1f} m AGL"
        return _solution(setup, best, False, f"target outside the range of {variable} ({reach})", **common)
    frac = (target_agl - a_lo) / (a_hi - a_lo)
    v0 = lo_v + frac * (hi_v - lo_v)
    guess = fly(v0)
    solver = _nlp(model, variable, guess["t_rail"], dict(ipopt_options or {}))
    par = np.concatenate([p_nom, [target_agl]])
    t_guess = float(guess["t_apogee"])
    sol = solver(x0=[v0, t_guess], p=par, lbx=[lo_v, float(guess["t_burnout"]) + 1e-3],
                 ubx=[hi_v, t_guess + 30.0], lbg=[0.0, 0.0], ubg=[0.0, 0.0])
    stats = solver.stats()
    if not stats["success"]:
        raise SolverError(f"air-brake solve did not converge ({stats['return_status']})")
    return _solution(setup, float(np.array(sol["x"]).ravel()[0]), True, "solved", **common,
                     iterations=stats.get("iter_count"))


def _nlp(model, variable: str, t_rail_guess: float, ipopt_options):
    """IPOPT solver (cached on the model) with NLP parameters (p, target)."""
    key = ("airbrake_nlp", variable, tuple(sorted(ipopt_options.items())))
    cache = model.__dict__.setdefault("_nlp_cache", {})
    if key in cache:
        return cache[key]
    i_v = params.index(variable)
    par = ca.MX.sym("par", params.SIZE + 1)
    v, T = ca.MX.sym("v"), ca.MX.sym("T")
    p_sym = ca.vertcat(par[:i_v], v, par[i_v + 1: params.SIZE])
    x_T = _final_state(model, p_sym, T, t_rail_guess)[0]
    g = ca.vertcat(model.vz_l(x_T), (x_T[2] - par[params.SIZE]) / 100.0)
    opts = {"ipopt.print_level": 0, "print_time": False, "ipopt.sb": "yes",
            "ipopt.hessian_approximation": "limited-memory", "ipopt.tol": 1e-10,
            "ipopt.constr_viol_tol": 1e-6, "ipopt.max_iter": 100}
    opts.update({(k if k.startswith("ipopt.") else f"ipopt.{k}"): val for k, val in ipopt_options.items()})
    # A square system (two equations, two unknowns): zero objective.
    cache[key] = ca.nlpsol("airbrakes", "ipopt", {"x": ca.vertcat(v, T), "p": par, "f": 0 * v, "g": g}, opts)
    return cache[key]


def _solution(setup, value, feasible, status, *, model, p_nom, variable, target_agl, t0, free,
              iterations=None) -> AirbrakeSolution:
    p = p_nom.copy()
    p[params.index(variable)] = value
    flight = simulate(setup, p=p, model=model)
    s = flight.summary_values
    values = {
        "airbrake_level": float(p[params.index("airbrake_level")]),
        "airbrake_start_time_s": float(p[params.index("airbrake_start_time")]),
        "target_agl_m": float(target_agl), "target_asl_m": float(target_agl + setup.site_elevation),
        "apogee_agl_m": s["apogee_agl_m"], "apogee_time_s": s["apogee_time_s"],
        "resimulated_apogee_agl_m": s["apogee_agl_m"], "apogee_error_m": s["apogee_agl_m"] - float(target_agl),
        "apogee_without_brakes_agl_m": free, "solve_time_s": time.perf_counter() - t0,
        "static_margin_min_cal": s["static_margin_min_cal"],
        "static_margin_min_time_s": s["static_margin_min_time_s"],
    }
    if iterations is not None:
        values["iterations"] = int(iterations)
    return AirbrakeSolution(name=setup.name, variable=variable, feasible=bool(feasible), status=status,
                            values=values, parameters=params.to_dict(p))
