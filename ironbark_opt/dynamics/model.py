"""The phased flight model: rail -> boost -> coast (-> descent).

Phase boundaries are events found exactly, never an ``if`` inside a step:

- **rail exit** ``t_r``: root of ``s(t_r) - (L_rail - offset) = 0`` where
  ``s`` is the distance travelled along the rail, the rail phase integrated
  with ``n_rail`` RK4 steps over ``[0, t_r]`` (CasADi ``rootfinder``);
- **burnout** ``t_b = burn_time * burn_time_scale`` (the thrust curve's end);
- **apogee** ``t_a``: root of the vertical velocity ``v_z(t_a) = 0``, found
  inside the RK4 step where it changes sign by Newton on the step length
  (an exact root of the same RK4 discretisation).

:class:`FlightModel` builds the CasADi Functions once per setup and runs
them numerically; the symbolic pieces (``rhs``, ``step``, ``trajectory``)
are public so sensitivities, Monte Carlo and the optimiser use the very same
expressions.

The class is assembled from mixins named for what they do: the compiled libraries
(:mod:`~ironbark_opt.dynamics.library`), the RK4 grid (:mod:`~ironbark_opt.dynamics.grid`),
events and output rows (:mod:`~ironbark_opt.dynamics.events`), the phase-by-phase
ascent (:mod:`~ironbark_opt.dynamics.phased`), batches (:mod:`~ironbark_opt.dynamics.batch`)
and the descent (:mod:`~ironbark_opt.dynamics.descent`); this module keeps the
construction, ``run``/``run_batch`` and the symbolic apogee Functions.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import casadi as ca
import numpy as np

from ironbark_opt import params
from ironbark_opt.dynamics import ejection, model_cache
from ironbark_opt.dynamics import rhs as rhs_mod
from ironbark_opt.dynamics.batch import BatchMixin
from ironbark_opt.dynamics.constants import G0
from ironbark_opt.dynamics.descent import DescentMixin
from ironbark_opt.dynamics.events import EventsMixin
from ironbark_opt.dynamics.grid import MIN_COAST_STEPS, STABLE_LAMBDA_DT, GridMixin
from ironbark_opt.dynamics.integrator import jit_mode, rk4_step
from ironbark_opt.dynamics.library import LibraryMixin
from ironbark_opt.dynamics.phased import PhasedMixin
from ironbark_opt.errors import InputError

__all__ = ["G0", "MIN_COAST_STEPS", "STABLE_LAMBDA_DT", "Steps", "initial_boost_steps", "FlightModel",
           "apogee_functions"]

_PHASES = np.array(["rail", "boost", "coast"])


@dataclass(frozen=True)
class Steps:
    """Discretisation of the phases.

    Parameters
    ----------
    n_rail : int
        RK4 steps on the rail.
    dt_boost : float [s]
        Target step during the burn (pitch oscillation near max q needs
        <= ~0.02 s for sub-metre apogee accuracy).
    n_coast : int
        Minimum RK4 steps from burnout to the end of the coast horizon
        (about the vacuum coast time).  More are used when the flight is
        stiffer: see :meth:`FlightModel.stable_step`.
    dt_descent : float [s]
        Step under parachute (and ballistic descent).
    """

    n_rail: int = 40
    dt_boost: float = 0.02
    n_coast: int = 300
    dt_descent: float = 0.1


def initial_boost_steps(motor, p, steps: Steps) -> int:
    """Boost RK4 steps before any refinement for stiffness: ``dt_boost`` over the
    nominal burn (``p``'s ``burn_time_scale``), at least 20."""
    burn = float(motor.burn_time) * float(p[params.index("burn_time_scale")])
    return max(20, int(math.ceil(burn / steps.dt_boost)))


class FlightModel(LibraryMixin, GridMixin, EventsMixin, PhasedMixin, BatchMixin, DescentMixin):
    """Compiled-once functions of one :class:`FlightSetup`.

    Parameters
    ----------
    setup : FlightSetup
    steps : Steps, optional
    jit : bool or "auto"
        Compile the trajectory Functions to C (cached on disk); falls back
        to the VM when no C compiler is available.  ``"auto"``: the compiled
        library if the cache has it, else the VM now and a background compile
        for the next run (:func:`~ironbark_opt.dynamics.integrator.jit_mode`).

    A built model (Functions and RK4 grid) is kept on disk
    (:mod:`~ironbark_opt.dynamics.model_cache`); the same setup is loaded, not rebuilt.
    """

    #: length of the parameter vector ``p`` the Functions take
    n_p = params.SIZE
    #: the Functions loaded from the model's compiled library (empty: none, see _compile_phases)
    _lib: dict = {}
    #: True when the model compiles into one library (loaded, or being compiled in the background)
    _one_library = False

    def __init__(self, setup, steps: Steps | None = None, *, jit=False):
        self.setup = setup
        self.steps = steps or Steps()
        self.jit = jit_mode(jit)
        self.trajectory, self._run = {}, {}
        self._key = model_cache.model_key(setup, self.steps)
        cached = model_cache.load(self._key)
        if cached is not None:
            self.rhs = {ph: cached[f"rhs_{ph}"] for ph in ("rail", "boost", "coast")}
            self.step = {ph: cached[f"step_{ph}"] for ph in ("rail", "boost", "coast")}
            self.n_boost, self.n_coast, self.coast_grading = cached["discretisation"]
            for ph in ("rail", "boost", "coast"):
                self.trajectory[ph] = self._run[ph] = cached[f"traj_{ph}"]
            self._build_events(cached["apex"])
        else:
            self.n_boost = initial_boost_steps(setup.motor, setup.nominal_parameters(), self.steps)
            self.rhs = {ph: rhs_mod.build(setup, ph) for ph in ("rail", "boost", "coast")}
            self.step = {ph: rk4_step(f, f"step_{ph}") for ph, f in self.rhs.items()}
            self.n_coast = None              # chosen from the nominal flight's stiffness below
            self.coast_grading = 1.0
            self._set_trajectory("rail", self.steps.n_rail)
            self._set_trajectory("boost", self.n_boost)
            self._build_events()
            self._choose_grid(setup.nominal_parameters())
            model_cache.store(self._key, {**{f"rhs_{ph}": f for ph, f in self.rhs.items()},
                                          **{f"step_{ph}": f for ph, f in self.step.items()},
                                          **{f"traj_{ph}": f for ph, f in self.trajectory.items()},
                                          "apex": self._apex, "discretisation": self.discretisation()})
        self._compile_phases()

    def run(self, p, *, descent: bool = False) -> dict:
        """Fly numerically to apogee (optionally to landing).

        Parameters
        ----------
        p : array (params.SIZE) [mixed SI]
        descent : bool
            Continue past apogee to the ground (parachutes from the setup,
            ballistic if it has none).

        Returns
        -------
        dict with ``t`` [s] (n,), ``x`` (13, n), ``phase`` (n,) labels and the
        event times ``t_rail``, ``t_burnout``, ``t_apogee`` [s] and states.
        """
        p = np.asarray(p, dtype=float).ravel()
        if p.size != self.n_p:
            raise InputError(f"parameter vector has {p.size} entries, expected {self.n_p}")
        _refuse_controller(self.setup)
        a = self._ascent_fused(p) if self._FUSED else None
        if a is None:
            a = self._ascent_phased(p)
        return self._finish(p, a, descent)

    #: fly the ascent through :mod:`~ironbark_opt.dynamics.ascent` (one Function) when it applies
    _FUSED = True

    def _ascent_fused(self, p) -> dict | None:
        """The ascent from one call of the ascent Function, or None where it does not
        apply (then :meth:`_ascent_phased` flies it, and raises what it finds)."""
        from ironbark_opt.dynamics.ascent import EV, applies
        if self.rail_exit_distance(p) <= 0:
            return None
        r = self._ascent_runner()(p)
        if r is None or not applies([r[k] for k in EV])[0]:
            return None
        k, t_b = int(r["k"]), r["t_burnout"]
        return dict(x0=r["x0"], t_r=r["t_rail"], X_rail=r["X_rail"], t_b=t_b, X_boost=r["X_boost"],
                    span=r["t_end"] - t_b, k=k, X_coast=r["X_coast"][:, :k], t_a=r["t_k"] + r["h"],
                    x_a=r["x_apogee"])

    def _finish(self, p, a: dict, descent: bool) -> dict:
        """``run``'s result from an ascent (:meth:`_ascent_fused` or :meth:`_ascent_phased`):
        samples, events, an ejection before apogee, the descent."""
        x0, t_r, X_rail, t_b, X_boost = a["x0"], a["t_r"], a["X_rail"], a["t_b"], a["X_boost"]
        k, span, t_a, x_a = a["k"], a["span"], a["t_a"], a["x_a"]
        x_r, x_b = X_rail[:, -1].copy(), X_boost[:, -1]
        fr = self.coast_fractions_of(p)
        n_r, n_b = X_rail.shape[1], X_boost.shape[1]
        t_e = ejection.ejection_time(self.setup, p)
        head_t = np.concatenate([[0.0], np.linspace(0, t_r, n_r + 1)[1:], self.boost_times(t_r, t_b, p)])
        head_x = np.hstack([x0[:, None], X_rail, X_boost])
        extra = {}
        if t_e is not None and t_e < t_a:       # the chute opens on the way up
            head_phase = ["rail"] * (n_r + 1) + ["boost"] * n_b
            t_s, X_s, ph_s, t_a2, x_a2 = ejection.fly_early(self, x_b, t_b, t_e, p, t_a)
            extra = dict(t_ejection=t_e, x_ejection=X_s[:, ph_s.index("ejected") - 1],
                         ejection_before_apogee_s=t_a - t_e, coasting_apogee_agl_m=float(x_a[2]))
            t_a, x_a = t_a2, x_a2
            t = np.concatenate([head_t, t_s])
            x = np.hstack([head_x, X_s])
            phase = np.array(head_phase + ph_s)
        else:
            t = np.concatenate([head_t, t_b + span * fr[1:k + 1], [t_a]])
            x = np.hstack([head_x, a["X_coast"][:, :k], x_a[:, None]])
            phase = np.repeat(_PHASES, (n_r + 1, n_b, k + 1))
            if t_e is not None:
                extra = dict(t_ejection=t_e)
        out = dict(t=t, x=x, phase=phase, p=p, t_rail=t_r, t_burnout=t_b, t_apogee=t_a,
                   x_rail=x_r, x_burnout=x_b, x_apogee=x_a, **extra)
        if descent:
            out.update(self._descend(t_a, x_a, p, t, x, phase))
        return out

    def run_batch(self, P: np.ndarray, *, descent: bool = False) -> dict:
        """Fly many parameter vectors at once to apogee (the Monte Carlo path).

        The ascent Function of :meth:`run` mapped over the columns of ``P``
        (``params.SIZE`` x n, threads), so each sample equals its single run to
        the bit; the motor-slot model maps the phase Functions and solves the
        events for all samples together by the same methods as in :meth:`run`.

        Returns
        -------
        dict of arrays (n,): ``apogee_agl`` [m], ``t_apogee`` [s],
        ``t_rail`` [s], ``rail_exit_speed`` [m/s], ``t_burnout`` [s], and
        ``x_apogee`` (13, n); with ``descent`` also ``t_landing`` [s] and
        ``x_landing`` (13, n).
        """
        P = np.asarray(P, dtype=float)
        if P.ndim != 2 or P.shape[0] != self.n_p:
            raise InputError(f"parameter matrix must be {self.n_p} x n, got {P.shape}")
        _refuse_controller(self.setup)
        if self._FUSED:
            return self._run_batch_fused(P, descent)
        return self._run_batch_phased(P, descent)

def _refuse_controller(setup):
    """A Python air-brake controller flies only through dynamics.controlled."""
    brakes = getattr(setup, "airbrakes", None)
    if brakes is not None and not brakes.differentiable:
        raise InputError("this rocket's air brakes follow a Python controller, which only 'simulate' flies; "
                         "ballast, sensitivities and Monte Carlo need a schedule (trigger = time, altitude, "
                         "mach or vertical_speed)", source=setup.source, field="airbrakes.trigger")


def rail_and_boost(model: FlightModel, p, t_rail_guess: float, t_rail=None):
    """Symbolic (MX) rail exit and boost of a single-stage flight: ``(t_rail, x_rail,
    t_burnout, X_boost)``; the rail exit by rootfinder from ``t_rail_guess``, or
    ``t_rail`` itself."""
    t_r = model.rail_exit_root(t_rail_guess, p) if t_rail is None else t_rail
    x_r = model.trajectory["rail"](model.initial_state(p), 0, t_r, p)[:, -1]
    t_b = model.burn_time(p)
    return t_r, x_r, t_b, model.trajectory["boost"](x_r, t_r, t_b, p)


def max_boost_speed(X_boost):
    """The largest boost-phase speed sample [m/s] (the peak is at or just before
    burnout; its derivative is that sample's)."""
    return ca.mmax(ca.sqrt(ca.sum1(X_boost[3:6, :] ** 2)))


def _final_state(model: FlightModel, p, T, t_rail_guess: float, t_rail=None):
    """Symbolic (MX) state at time ``T`` in the coast, through all phases; the
    rail exit by rootfinder from ``t_rail_guess``, or ``t_rail`` itself (an
    optimisation variable constrained by :meth:`FlightModel.rail_residual`)."""
    if hasattr(type(model), "final_state_symbolic"):    # staged rockets (dynamics/staged.py)
        return model.final_state_symbolic(p, T, t_rail_guess)
    t_r, x_r, t_b, X_b = rail_and_boost(model, p, t_rail_guess, t_rail)
    if ejection.ejection_time(model.setup, p) is not None and ejection.ejects_before_apogee(model):
        x_t = ejection.ejected_final_state(model, X_b[:, -1], t_b, p, T)
    else:
        x_t = model.trajectory["coast"](X_b[:, -1], t_b, T, p)[:, -1]
    return x_t, t_r, x_r, X_b


def apogee_functions(model: FlightModel, p_nominal) -> dict:
    """Differentiable CasADi Functions of ``p`` around a nominal flight.

    Returns a dict of MX Functions:

    - ``final_state(p, T) -> (x_T, t_rail, x_rail)``: the phased trajectory
      with the final time ``T`` [s] as an input (rail exit by rootfinder);
    - ``apogee(p) -> (z_apogee [m AGL], t_apogee [s], rail_exit_speed [m/s],
      max_speed [m/s])`` with ``t_apogee`` the root of ``v_z(T) = 0``
      (rootfinder, so AD gives the implicit-function derivatives); the
      maximum speed is the largest boost-phase sample (the peak is at or just
      before burnout; its derivative is that sample's).

    The rootfinders start from the nominal flight's event times, so they are
    valid for ``p`` in a neighbourhood of ``p_nominal`` (a dispersion or an
    optimisation, not an arbitrary different rocket).
    """
    _refuse_controller(model.setup)
    run = model.run(p_nominal)
    t_rail0, t_apogee0 = run["t_rail"], run["t_apogee"]
    p = ca.MX.sym("p", model.n_p)
    T = ca.MX.sym("T")
    x_t, t_r, x_r, X_b = _final_state(model, p, T, t_rail0)
    v_max = max_boost_speed(X_b)
    final = ca.Function("final_state", [p, T], [x_t, t_r, x_r, v_max], ["p", "T"],
                        ["x_T", "t_rail", "x_rail", "max_speed"])
    vz = ca.Function("vz_T", [T, p], [model.vz_l(x_t)])
    t_apo = ca.rootfinder("apogee_time", "newton", vz, {"abstol": 1e-9, "max_iter": 30, "error_on_fail": True})(t_apogee0, p)
    x_a, t_r2, x_r2, v_max2 = final(p, t_apo)
    apogee = ca.Function("apogee", [p], [x_a[2], t_apo, ca.norm_2(x_r2[3:6]), v_max2],
                         ["p"], ["apogee_agl", "t_apogee", "rail_exit_speed", "max_speed"])
    return {"final_state": final, "apogee": apogee}
