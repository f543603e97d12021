"""Launch-day ballast: the mass (and optionally position) that hits a target apogee.

Problem (IPOPT, CasADi ``nlpsol``), variables ``w = (m_b, [x_b,] T)``:

    minimise    m_b                         (least ballast; the feasible set
                                             is a point when x_b is fixed)
    subject to  v_z(T; p(w)) = 0            (T is the apogee time)
                z(T; p(w))   = target        [m AGL]
                v_rail(p(w)) >= v_min        (optional)
                SM_rail(p(w)) >= SM_min      (optional)
                0 <= m_b <= m_max,  x_min <= x_b <= x_max

``z``, ``v_z`` come from the same phased RK4 trajectory as ``simulate``
(rail exit by rootfinder, burnout, coast to ``T``), so the optimum
re-simulates onto the target.  Before IPOPT runs, the zero- and
maximum-ballast flights bracket the target: a target outside the bracket is
reported infeasible at once with the closest achievable apogee and the
active bound — never a silent IPOPT failure.  If the flight constraints make
the target unreachable, a second solve minimises ``(z - target)^2`` under
the constraints and reports the closest feasible apogee.
"""
from __future__ import annotations

import time
from dataclasses import dataclass, field
from typing import Mapping

import casadi as ca
import numpy as np

from ironbark_opt import params
from ironbark_opt.dynamics.integrator import cached_library, compile_detached, compile_function
from ironbark_opt.dynamics.model import _final_state
from ironbark_opt.dynamics.model_cache import library_key
from ironbark_opt.dynamics.rhs import OUTPUT_NAMES
from ironbark_opt.errors import InputError
from ironbark_opt.flight import flight_model, flight_of_run
from ironbark_opt.optimise.target import parse_target
from ironbark_opt.roots import illinois

_SM = OUTPUT_NAMES.index("static_margin_cal")


@dataclass(frozen=True)
class BallastSolution:
    """Result of :func:`solve_ballast` (immutable).

    Attributes
    ----------
    values : dict
        Unit-suffixed results: ``ballast_kg``, ``ballast_x_m``,
        ``apogee_agl_m``, ``apogee_time_s``, ``target_agl_m``,
        ``rail_exit_speed_mps``, ``static_margin_rail_exit_cal``,
        ``resimulated_apogee_agl_m``, ``solve_time_s``, ...
    feasible : bool
    status : str
        What happened, in words.
    active : tuple of str
        Bounds/constraints at their limit.
    """

    name: str
    motor: str
    feasible: bool
    status: str
    active: tuple
    values: Mapping[str, float]
    parameters: Mapping[str, float] = field(repr=False, default_factory=dict)

    def __repr__(self) -> str:
        v = self.values
        state = "feasible" if self.feasible else "INFEASIBLE"
        return (f"BallastSolution({self.name!r}, {self.motor}: {v['ballast_kg']:.3f} kg at "
                f"{v['ballast_x_m']:.3f} m -> apogee {v['apogee_agl_m']:.1f} m AGL, {state})")

    @property
    def ballast(self) -> float:
        """Ballast mass [kg]."""
        return self.values["ballast_kg"]

    def to_dict(self) -> dict:
        out = {"rocket": self.name, "motor": self.motor, "feasible": self.feasible, "status": self.status,
               "active": list(self.active)}
        out.update(self.values)
        out["parameters"] = dict(self.parameters)
        return out

    def to_dataframe(self):
        import pandas as pd   # imported here: 0.4-1 s that the command line does not need

        return pd.DataFrame([{k: v for k, v in self.to_dict().items() if k not in ("parameters", "active")}])

    def summary(self) -> str:
        v = self.values
        lines = [f"Ballast for {self.name} on {self.motor}: "
                 f"{'feasible' if self.feasible else 'NOT feasible'} ({self.status})",
                 f"  target             {v['target_agl_m']:10.1f} m AGL ({v['target_agl_m'] / 0.3048:.0f} ft)",
                 f"  ballast            {v['ballast_kg']:10.3f} kg at x = {v['ballast_x_m']:.3f} m",
                 f"  apogee             {v['apogee_agl_m']:10.1f} m AGL at {v['apogee_time_s']:.2f} s "
                 f"(re-simulated {v['resimulated_apogee_agl_m']:.1f} m)",
                 f"  rail exit          {v['rail_exit_speed_mps']:10.2f} m/s, static margin "
                 f"{v['static_margin_rail_exit_cal']:.2f} cal",
                 f"  min static margin  {v['static_margin_min_cal']:10.2f} cal at "
                 f"{v['static_margin_min_time_s']:.2f} s"]
        if self.active:
            lines.append(f"  active             {', '.join(self.active)}")
        lines.append(f"  solve time         {v['solve_time_s']:10.2f} s")
        return "\n".join(lines)


def _bounds(setup, mass_max, x_range):
    m_max = mass_max if mass_max is not None else setup.ballast_mass_max
    if m_max is None:
        m_max = setup.dry.mass            # generous default: doubling the dry mass
    if m_max <= 0:
        raise InputError(f"maximum ballast must be > 0 kg, got {m_max}", field="max_ballast")
    xr = x_range if x_range is not None else setup.ballast_x_range
    return float(m_max), (None if xr is None else (float(xr[0]), float(xr[1])))


def solve_ballast(setup, target, *, free_position: bool = False, mass_max: float | None = None,
                  x_range=None, ballast_x: float | None = None, min_rail_speed: float | None = None,
                  min_margin: float | None = None, parameters: Mapping[str, float] | None = None,
                  ipopt_options: Mapping | None = None, model=None, motor_grid=None,
                  method: str = "auto") -> BallastSolution:
    """Ballast mass (and position) putting apogee on ``target``.

    Parameters
    ----------
    setup : FlightSetup
    target : str, float or Target
        e.g. ``"30000ft"``, ``"3000 m ASL"``, or a number [m AGL].
    free_position : bool
        Optimise the ballast position within the bay too.
    mass_max : float, optional [kg]
        Upper bound on ballast (default: the file's ``mass_max``, else the dry mass).
    x_range : (float, float), optional [m]
        Ballast bay aft of the nose tip (default: the file's bay).
    ballast_x : float, optional [m]
        Fixed ballast position (default: the setup's nominal position).
    min_rail_speed : float, optional [m/s]
    min_margin : float, optional [calibers]
        Minimum static margin at rail exit.
    parameters : mapping, optional
        Other parameter overrides (SI), e.g. a forecast's wind offsets.
    ipopt_options : mapping, optional
        Passed to IPOPT.
    model : SlotFlightModel, optional
        Motor choice: one model (and one NLP) for every candidate
        (:mod:`ironbark_opt.dynamics.slot_model`); ``setup.motor`` flies in its
        slot on ``motor_grid``, the RK4 grid its own model would choose.
    method : {"auto", "ipopt"}
        ``"auto"``: a fixed ballast position without flight constraints or IPOPT
        options is a root in one variable, solved on the flown apogee
        (:func:`_mass_root`); everything else, and ``"ipopt"``, solves the NLP.

    Returns
    -------
    BallastSolution
    """
    t_start = time.perf_counter()
    tgt = parse_target(target)
    target_agl = tgt.agl(setup.site_elevation)
    if target_agl <= 0:
        raise InputError(f"target {tgt.text!r} is below the launch site", field="target")
    m_max, x_bay = _bounds(setup, mass_max, x_range)
    overrides = dict(parameters or {})
    if ballast_x is not None:
        overrides["ballast_x"] = ballast_x
    if free_position and x_bay is None:
        raise InputError("a free ballast position needs a bay: give x_min and x_max ([ballast] in the file)",
                         field="ballast.x_min")
    p_nom = setup.nominal_parameters(**overrides)
    i_m, i_x = params.index("ballast_mass"), params.index("ballast_x")
    if model is None:
        model = flight_model(setup)
    else:
        p_nom = model.parameters(p_nom, setup.motor, motor_grid)
    if ballast_x is None and not free_position and x_bay is not None and not x_bay[0] <= p_nom[i_x] <= x_bay[1]:
        p_nom[i_x] = 0.5 * (x_bay[0] + x_bay[1])

    def fly(m_b, x_b=None):
        p = p_nom.copy()
        p[i_m] = m_b
        if x_b is not None:
            p[i_x] = x_b
        return model.run(p)

    lo, hi = fly(0.0), fly(m_max)
    a_lo, a_hi = lo["x_apogee"][2], hi["x_apogee"][2]
    common = dict(name=setup.name, motor=getattr(setup.motor, "designation", "motor"))
    if not a_hi <= target_agl <= a_lo:
        m_b = 0.0 if target_agl > a_lo else m_max
        run = lo if target_agl > a_lo else hi
        bound = "ballast_kg >= 0 (target above the zero-ballast apogee)" if target_agl > a_lo else \
            f"ballast_kg <= {m_max:g} (target below the apogee with the most ballast)"
        return _solution(setup, model, p_nom, m_b, p_nom[i_x], run, target_agl, False,
                         "target outside the reachable range", (bound,), t_start, common, zero_ballast_apogee=a_lo)

    # Initial guess: interpolate between the bracketing flights.
    frac = (a_lo - target_agl) / (a_lo - a_hi)
    guess = fly(frac * m_max)
    if solved_by_root(free_position=free_position, min_rail_speed=min_rail_speed, min_margin=min_margin,
                      ipopt_options=ipopt_options, method=method):
        m_opt, run, n_it = _mass_root(fly, target_agl, (0.0, lo), (m_max, hi), (frac * m_max, guess))
        return _solution(setup, model, p_nom, m_opt, p_nom[i_x], run, target_agl, True, "solved", (), t_start,
                         common, iterations=n_it, zero_ballast_apogee=a_lo)
    nlp = _nlp(model, free_position, min_rail_speed is not None, min_margin is not None, dict(ipopt_options or {}))
    n_eq = nlp["equalities"]
    lbg = [0.0] * n_eq + [float(v) for v in (min_rail_speed, min_margin) if v is not None]
    ubg = [0.0] * n_eq + [np.inf] * (len(lbg) - n_eq)
    rail = nlp["rail_variable"]
    lbw = [0.0] + ([x_bay[0]] if free_position else []) + ([0.0] if rail else []) + [guess["t_burnout"] + 1e-3]
    ubw = [m_max] + ([x_bay[1]] if free_position else []) + ([guess["t_burnout"]] if rail else []) \
        + [guess["t_apogee"] + 30.0]
    w0 = [frac * m_max] + ([p_nom[i_x]] if free_position else []) + ([guess["t_rail"]] if rail else []) \
        + [guess["t_apogee"]]
    par = np.concatenate([p_nom, [target_agl, m_max, guess["t_rail"]]])
    sol = nlp["solve"](x0=w0, p=par, lbx=lbw, ubx=ubw, lbg=lbg, ubg=ubg)
    stats = nlp["solve"].stats()
    wopt = np.array(sol["x"]).ravel()
    feasible = stats["success"]
    status = stats["return_status"]
    active: list = []
    if not feasible:
        # Constraints make the target unreachable: closest feasible apogee.
        keep = [i for i in range(len(lbg)) if i != n_eq - 1]        # all but apogee = target
        sol = nlp["closest"](x0=w0, p=par, lbx=lbw, ubx=ubw, lbg=[lbg[i] for i in keep], ubg=[ubg[i] for i in keep])
        wopt = np.array(sol["x"]).ravel()
        status = f"target not reachable under the constraints ({status}); closest feasible apogee shown"
        gv = np.array(sol["g"]).ravel()
        active = [n for n, val, lb in zip(nlp["names"], gv[n_eq - 1:], lbg[n_eq:])
                  if abs(val - lb) < 1e-4 * max(1, abs(lb))]
    m_opt = float(wopt[0])
    x_opt = float(wopt[1]) if free_position else float(p_nom[i_x])
    if m_opt <= 1e-9:
        active.append("ballast_kg >= 0")
    if m_opt >= m_max * (1 - 1e-9):
        active.append(f"ballast_kg <= {m_max:g}")
    if free_position:
        for bound, name in ((x_bay[0], "ballast_x_m >= bay start"), (x_bay[1], "ballast_x_m <= bay end")):
            if abs(x_opt - bound) < 1e-6:
                active.append(name)
    run = fly(m_opt, x_opt)
    return _solution(setup, model, p_nom, m_opt, x_opt, run, target_agl, feasible,
                     "solved" if feasible else status, tuple(active), t_start, common,
                     iterations=stats.get("iter_count"), zero_ballast_apogee=a_lo)


def solved_by_root(*, free_position: bool = False, min_rail_speed=None, min_margin=None, ipopt_options=None,
                   method: str = "auto", **_) -> bool:
    """Whether :func:`solve_ballast` with these options solves the one-variable root
    on :meth:`FlightModel.run`'s apogee (:func:`_mass_root`) rather than the NLP
    (other keywords of ``solve_ballast`` are accepted and do not matter)."""
    return method == "auto" and not free_position and min_rail_speed is None and min_margin is None \
        and not ipopt_options


#: apogee error at which the one-variable root is accepted [m] (IPOPT's constr_viol_tol)
ROOT_TOL_M = 1e-6


def _mass_root(fly, target_agl: float, lo, hi, guess):
    """(ballast [kg], its run, flights) with ``fly(m)["x_apogee"][2] = target_agl``.

    Illinois regula falsi (:func:`ironbark_opt.roots.illinois`) on the apogee of
    :meth:`FlightModel.run`, from the bracketing flights ``lo = (0, run)``,
    ``hi = (m_max, run)`` and the interpolated ``guess = (m, run)`` already flown,
    to ``|apogee - target| <= ROOT_TOL_M``: the same problem as the NLP when the
    position is fixed and nothing else constrains it (its feasible set is that
    root), solved on the very apogee ``simulate`` reports, so the answer
    re-simulates onto the target.  Apogee falls with ballast: ``lo`` is above
    the target, ``hi`` below.
    """
    def err(run):
        return float(run["x_apogee"][2]) - target_agl
    (m_a, r_a), (m_b, r_b), (m_c, r_c) = lo, hi, guess
    g_a, g_b, g_c = err(r_a), err(r_b), err(r_c)
    if abs(g_c) <= ROOT_TOL_M:
        return m_c, r_c, 1
    if g_c > 0:
        m_a, g_a = m_c, g_c
    else:
        m_b, g_b = m_c, g_c
    m, g, run, n, _ = illinois(lambda m: (err(r := fly(m)), r), m_a, g_a, m_b, g_b, gtol=ROOT_TOL_M,
                               xtol=1e-12 * max(1.0, m_b), best=True)
    if abs(g_c) < abs(g):
        return m_c, r_c, n + 1
    return m, run, n + 1


def _nlp(model, free_position: bool, rail_speed: bool, margin: bool, ipopt_options):
    """IPOPT solvers for the ballast problem, built once per model and reused.

    NLP parameters: the nominal parameter vector (``model.n_p`` long: with a
    motor slot, the motor and its grid too), the target [m AGL], the ballast
    bound [kg] (for scaling) and the rail-exit rootfinder's first guess [s], so
    a warm solve, or the next candidate motor, pays no graph building.

    The rail-exit time is a variable with the rail residual as an equality
    constraint (instead of a rootfinder inside the graph), so the NLP's
    functions and Jacobian generate C: with ``model.jit`` they are compiled
    (on-disk cache, named by the model's key; ``"auto"``: compiled in the
    background, the VM until the library exists).  Staged rockets keep the
    rootfinder (their own ``final_state_symbolic``).
    """
    key = ("ballast_nlp", free_position, rail_speed, margin, tuple(sorted(ipopt_options.items())))
    cache = model.__dict__.setdefault("_nlp_cache", {})
    if key in cache:
        return cache[key]
    rail_variable = _rail_variable(model)
    name = _nlp_name(free_position, rail_speed, margin)
    key_c = library_key(model, name) if rail_variable else None
    names = [n for n, on in (("rail_exit_speed_mps >= minimum", rail_speed),
                             ("static_margin_rail_exit_cal >= minimum", margin)) if on]
    opts = {"ipopt.print_level": 0, "print_time": False, "ipopt.sb": "yes",
            "ipopt.hessian_approximation": "limited-memory", "ipopt.tol": 1e-10,
            "ipopt.constr_viol_tol": 1e-6, "ipopt.max_iter": 100}
    opts.update({(k if k.startswith("ipopt.") else f"ipopt.{k}"): v for k, v in ipopt_options.items()})
    compiled = cached_library(name, key_c) if key_c is not None and model.jit else None
    if compiled is not None:        # no graph to build: the closest-apogee NLP builds its own if ever needed
        cache[key] = {"solve": ca.nlpsol("ballast", "ipopt", _problem(compiled, model.n_p), opts), "names": names,
                      "equalities": 3, "rail_variable": True,        # rail residual, v_z(T) = 0, z(T) = target
                      "closest": lambda **kw: _nlp_graph(model, free_position, rail_speed, margin)[1](opts)(**kw)}
        return cache[key]
    oracle, closest, n_eq = _nlp_graph(model, free_position, rail_speed, margin)
    if rail_variable and model.jit == "auto" and key_c is not None:
        # generated and compiled in a detached process: a first run costs no more than the VM
        compile_detached(oracle, key_c, "ironbark_opt.optimise.ballast:_jacobian_in_x")
    elif rail_variable and model.jit:
        oracle = compile_function(oracle, key=key_c, extra=lambda: (_jacobian_in_x(oracle),))
    cache[key] = {"solve": ca.nlpsol("ballast", "ipopt", _problem(oracle, model.n_p), opts), "names": names,
                  "equalities": n_eq,
                  "rail_variable": rail_variable, "closest": lambda **kw: closest(opts)(**kw)}
    return cache[key]


def _rail_variable(model) -> bool:
    """True when the NLP has the rail-exit time as a variable (staged rockets keep their
    own rootfinder, ``final_state_symbolic``)."""
    return not hasattr(type(model), "final_state_symbolic")


def _nlp_name(free_position: bool, rail_speed: bool, margin: bool) -> str:
    """Name of the NLP Function (and of its compiled library) for one problem shape."""
    return f"ballast_nlp_{int(free_position)}{int(rail_speed)}{int(margin)}"


def _nlp_graph(model, free_position: bool, rail_speed: bool, margin: bool):
    """(NLP Function ``(x, p) -> (f, g)``, closest-apogee solver factory ``opts -> nlpsol``,
    number of equality constraints) of :func:`_nlp`."""
    i_m, i_x = params.index("ballast_mass"), params.index("ballast_x")
    n_p = model.n_p
    par = ca.MX.sym("par", n_p + 3)
    p_sym = par[:n_p]
    target_agl, m_max, t_rail_guess = par[n_p], par[n_p + 1], par[n_p + 2]
    m_sym, x_sym, T_sym = ca.MX.sym("m_b"), ca.MX.sym("x_b"), ca.MX.sym("T")
    p_sym = ca.vertcat(p_sym[:i_m], m_sym, x_sym if free_position else p_sym[i_x], p_sym[i_x + 1:])
    rail_variable = _rail_variable(model)
    tr_sym = ca.MX.sym("t_rail")
    w = [m_sym] + ([x_sym] if free_position else []) + ([tr_sym] if rail_variable else []) + [T_sym]
    x_T, t_r, x_r, _ = _final_state(model, p_sym, T_sym, t_rail_guess, t_rail=tr_sym if rail_variable else None)
    g = ([model.rail_residual(t_r, p_sym)] if rail_variable else []) + [model.vz_l(x_T), x_T[2] - target_agl]
    n_eq = len(g)
    if rail_speed:
        g.append(ca.norm_2(x_r[3:6]))
    if margin:
        g.append(model.rhs["boost"](x_r, t_r, p_sym)[1][_SM])
    W = ca.vertcat(*w)
    oracle = ca.Function(_nlp_name(free_position, rail_speed, margin), [W, par], [m_sym / m_max, ca.vertcat(*g)], ["x", "p"], ["f", "g"])
    closest = {"x": W, "p": par, "f": ((x_T[2] - target_agl) / 100.0) ** 2, "g": ca.vertcat(*g[:n_eq - 1], *g[n_eq:])}
    return oracle, (lambda opts: ca.nlpsol("ballast_closest", "ipopt", closest, opts)), n_eq


def _problem(oracle: ca.Function, n_p: int) -> dict:
    """The NLP for ``nlpsol`` around ``oracle`` (``(x, p) -> (f, g)``, compiled or not):
    the objective ``m_b / m_max`` as its own expression, so IPOPT's objective and
    gradient cost nothing; only the constraints call ``oracle`` (and their
    Jacobian its ``jac_``).  Given the oracle itself, ``nlpsol`` computed the
    objective gradient from the oracle's whole Jacobian: every IPOPT iteration
    paid for the constraint Jacobian twice."""
    W, par = ca.MX.sym("x", oracle.sparsity_in(0)), ca.MX.sym("p", oracle.sparsity_in(1))
    return {"x": W, "p": par, "f": W[0] / par[n_p + 1], "g": oracle(W, par)[1]}


def _jacobian_in_x(oracle: ca.Function) -> ca.Function:
    """``jac_<name>``, the Jacobian of the NLP Function as ``casadi.external`` looks
    it up, with respect to the variables only: the blocks for the parameters (the
    whole parameter vector, ~1500 entries with a motor slot) are structurally
    zero, since IPOPT never differentiates with respect to parameters; computing
    them would cost a reverse sweep per output on every call.  The constraints'
    block is forward mode, one direction per variable (3-4; 124 vs 202 ms per
    call in the VM on Calisto against ``jacobian``'s choice)."""
    W, par = (ca.MX.sym(n, oracle.sparsity_in(i)) for i, n in enumerate(("x", "p")))
    f, G = oracle(W, par)
    out_f, out_g = ca.MX.sym("out_f", ca.Sparsity(*f.shape)), ca.MX.sym("out_g", ca.Sparsity(*G.shape))
    return ca.Function(f"jac_{oracle.name()}", [W, par, out_f, out_g],
                       [ca.jacobian(f, W), ca.MX(f.numel(), par.numel()), ca.jtimes(G, W, ca.DM.eye(W.numel())),
                        ca.MX(G.numel(), par.numel())],
                       ["x", "p", "out_f", "out_g"], ["jac_f_x", "jac_f_p", "jac_g_x", "jac_g_p"])


def _solution(setup, model, p_nom, m_b, x_b, run, target_agl, feasible, status, active, t_start, common,
              iterations=None, zero_ballast_apogee=None) -> BallastSolution:
    p = p_nom.copy()
    p[params.index("ballast_mass")] = m_b
    p[params.index("ballast_x")] = x_b
    flight = flight_of_run(setup, model, p, run)       # run = model.run(p): not flown again
    s = flight.summary_values
    values = {
        "ballast_kg": float(m_b), "ballast_x_m": float(x_b), "target_agl_m": float(target_agl),
        "target_asl_m": float(target_agl + setup.site_elevation),
        "apogee_agl_m": float(run["x_apogee"][2]), "apogee_time_s": float(run["t_apogee"]),
        "resimulated_apogee_agl_m": s["apogee_agl_m"],
        "apogee_error_m": s["apogee_agl_m"] - float(target_agl),
        "rail_exit_speed_mps": s["rail_exit_speed_mps"],
        "static_margin_rail_exit_cal": s["static_margin_rail_exit_cal"],
        "max_speed_mps": s["max_speed_mps"], "launch_mass_kg": s["launch_mass_kg"],
        "static_margin_min_cal": s["static_margin_min_cal"],
        "static_margin_min_time_s": s["static_margin_min_time_s"],
        "zero_ballast_apogee_agl_m": float(zero_ballast_apogee),
        "solve_time_s": time.perf_counter() - t_start,
    }
    if iterations is not None:
        values["iterations"] = int(iterations)
    return BallastSolution(feasible=bool(feasible), status=status, active=tuple(active), values=values,
                           parameters=params.to_dict(p[:params.SIZE]), **common)
