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
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import casadi as ca
import numpy as np

from ironbark_opt import params
from ironbark_opt.dynamics import rhs as rhs_mod
from ironbark_opt.dynamics.frames import launch_quaternion, rail_direction_l, rotation_matrix
from ironbark_opt.dynamics import ejection, model_cache
from ironbark_opt.dynamics.integrator import (cached_library, compile_function, grid_fractions, jit_mode,
                                                library_member, phase_trajectory, rk4_step)
from ironbark_opt.errors import InputError, SolverError
from ironbark_opt.roots import illinois

G0 = 9.80665  # [m/s^2] standard gravity, only for first guesses
_PHASES = np.array(["rail", "boost", "coast"])
#: |lambda| dt allowed for RK4 (its stability region reaches 2.78 on the real
#: and 2.83 on the imaginary axis); chosen by the RK4-vs-DOP853 validation.
STABLE_LAMBDA_DT = 1.5
#: Fewest coast steps whatever the stiffness (accuracy of the coast's slow part).
MIN_COAST_STEPS = 300


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


class FlightModel:
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

    def _library_key(self) -> str | None:
        return model_cache.library_key(self)

    def _compiled(self, func: ca.Function) -> ca.Function:
        """``func`` compiled as ``self.jit`` asks (the VM Function itself when it says no);
        ``"auto"``: the cached library, else the VM and :meth:`_compile_in_background`."""
        if not self.jit:
            return func
        key = self._library_key()
        if self.jit == "auto" and key is not None:
            lib = cached_library(func.name(), key)
            if lib is None:
                self._compile_in_background()
                return func
            return lib
        return compile_function(func, key=key, background=self.jit == "auto")

    def _compile_in_background(self) -> None:
        """Start (once per model and grid) the detached process that rebuilds this model from its
        setup and the model cache and compiles its libraries for the next run
        (:func:`~ironbark_opt.dynamics.model_cache.compile_detached`): this process pays
        neither the C code generation nor the compiler."""
        started = self.__dict__.setdefault("_background_started", set())
        if self._library_key() not in started:             # once per grid (set_discretisation)
            started.add(self._library_key())
            model_cache.compile_detached(self)

    def _rebuild_args(self) -> tuple:
        """Positional arguments that rebuild this model (with ``jit=``) in another process."""
        return (self.setup, self.steps)

    def _compile_libraries(self, discretisation) -> None:
        """Compile, now, every library ``jit="auto"`` looks for (the background child)."""
        self.set_discretisation(*discretisation)
        self.jit = True
        self._compile_phases()

    #: the Functions compiled into the model's one library with the ascent
    _LIBRARY = ("ascent_batch", "traj_rail", "traj_boost", "traj_coast", "apogee_event", "outputs_rail",
                "outputs_boost", "outputs_coast")

    def _compile_phases(self) -> None:
        """Compile as ``self.jit`` asks: the ascent (:mod:`~ironbark_opt.dynamics.ascent`),
        the phase trajectories, the apogee event and the phases' output rows, all in
        one library (their RK4 steps generated and compiled once), loaded from the
        cache when it has it.  Without a cache key: one library per Function."""
        self.__dict__.pop("_ascent_cache", None)
        self.__dict__.pop("_out_cache", None)
        # the mapped ascents of run_batch were built on the old grid's ascent
        for k in [k for k in self.__dict__.get("_map_cache", {}) if k[0] == "ascent_batch"]:
            del self._map_cache[k]
        self._lib = {}
        key = self._library_key()
        self._one_library = bool(self.jit) and key is not None and self._FUSED
        if not self._one_library:
            for ph in ("rail", "boost", "coast"):
                self._run[ph] = self._compiled(self.trajectory[ph])
            self._apogee_run = self._compiled(self._apogee_event)
            return
        lib = cached_library("ascent", key)
        if lib is None and self.jit == "auto":  # the VM now, the library for the next run
            self._compile_in_background()
        elif lib is None:
            vm, members = self._library_functions()
            lib = compile_function(vm, key=key, extra=lambda: [members[n] for n in self._LIBRARY])
            if lib is vm:                       # no compiler, or compiling failed
                lib = None
        if lib is None:                         # the VM (meanwhile)
            for ph in ("rail", "boost", "coast"):
                self._run[ph] = self.trajectory[ph]
            self._apogee_run = self._apogee_event
            return
        self._lib = {"ascent": lib, **{name: library_member(name, "ascent", key) for name in self._LIBRARY}}
        for ph in ("rail", "boost", "coast"):
            self._run[ph] = self._lib[f"traj_{ph}"]
        self._apogee_run = self._lib["apogee_event"]

    def _library_twin(self) -> "FlightModel":
        """This model built again with the Mach tables in piecewise-polynomial form
        (:func:`~ironbark_opt.aero.mach_splines.table_form`: the same splines to ~1e-15,
        ~1/6 of the B-splines' cost in C; the VM keeps the B-splines, whose tables are
        no per-call copy): the right-hand sides, their RK4 steps, the phase trajectories
        on this grid and the events (~0.3 s, only where a library is compiled).  What the
        compiled library holds comes from it (:meth:`_library_functions`, and the robust
        ballast's derivative Function), so compiled flights agree with each other to the
        bit, and with the VM's to ~1e-15."""
        cached = self.__dict__.get("_twin")
        if cached is not None and cached.discretisation() == self.discretisation():
            return cached
        from ironbark_opt.aero.mach_splines import table_form
        twin = object.__new__(type(self))
        keep = ("setup", "steps", "jit", "_key", "n_boost", "n_coast", "coast_grading")
        twin.__dict__.update({k: self.__dict__[k] for k in keep})
        with table_form("pp"):
            twin.rhs = {ph: rhs_mod.build(self.setup, ph) for ph in ("rail", "boost", "coast")}
        twin.step = {ph: rk4_step(f, f"step_{ph}") for ph, f in twin.rhs.items()}
        twin.trajectory, twin._run = {}, {}
        for ph, n in (("rail", self.steps.n_rail), ("boost", self.n_boost), ("coast", self.n_coast)):
            twin._set_trajectory(ph, n)
        twin._build_events()
        self.__dict__["_twin"] = twin
        return twin

    def _library_functions(self) -> tuple[ca.Function, dict]:
        """``(ascent, {name: Function})``: what the model's library compiles, from
        :meth:`_library_twin`: the ascent, the phase trajectories, the apogee event and
        the output rows."""
        twin = self._library_twin()
        vm, vm_batch = twin._ascent_vm()
        return vm, {"ascent_batch": vm_batch,
                    "traj_rail": twin.trajectory["rail"], "traj_boost": twin.trajectory["boost"],
                    "traj_coast": twin.trajectory["coast"], "apogee_event": twin._apogee_event,
                    **{f"outputs_{ph}": twin._outputs_base(ph) for ph in ("rail", "boost", "coast")}}

    def _choose_grid(self, p):
        """Fix the RK4 grid from the *nominal* flight (deterministic: the same
        for every later run, batch, chunk or worker)."""
        t_r = self.rail_exit(p)
        t_b = self.burn_time(p)
        if t_r >= t_b:
            raise InputError(f"motor burns out ({t_b:.2f} s) before rail exit ({t_r:.2f} s)", field="motor")
        x_r = np.array(self._run["rail"](self._x0(p), 0.0, t_r, p))[:, -1]
        x_b = np.array(self._run["boost"](x_r, t_r, t_b, p))[:, -1]
        vz_b = float(self.vz_l(x_b))
        if vz_b <= 0:
            raise SolverError("vertical velocity at burnout is not positive: the rocket never climbs; check the "
                              "launch mass, the motor, launch.inclination_deg and the wind")
        self._ensure_stable(x_b, t_b, t_b + vz_b / G0 + 2.0, p)

    def discretisation(self) -> tuple[int, int, float]:
        """``(n_boost, n_coast, coast_grading)``: the RK4 grid of boost and coast."""
        return int(self.n_boost), int(self.n_coast), float(self.coast_grading)

    def set_discretisation(self, n_boost: int, n_coast: int, coast_grading: float = 1.0) -> None:
        """Impose a grid (e.g. the one a client chose, on a cluster worker)."""
        if (int(n_boost), int(n_coast), float(coast_grading)) == self.discretisation():
            return
        self.n_boost, self.n_coast, self.coast_grading = int(n_boost), int(n_coast), float(coast_grading)
        self._set_trajectory("boost", self.n_boost)
        self._set_trajectory("coast", self.n_coast)
        self._compile_phases()

    @property
    def coast_fractions(self) -> np.ndarray:
        """Coast step boundaries as fractions of the coast (n_coast + 1; read-only)."""
        key = (self.n_coast, self.coast_grading)
        cached = self.__dict__.get("_coast_fractions")
        if cached is None or cached[0] != key:
            fr = grid_fractions(self.n_coast, self.coast_grading)
            fr.flags.writeable = False
            self.__dict__["_coast_fractions"] = cached = (key, fr)
        return cached[1]

    def coast_fractions_of(self, p) -> np.ndarray:
        """Coast step boundaries of the flight with parameters ``p`` (the model's
        own grid; a motor-slot model reads it from ``p``)."""
        return self.coast_fractions

    def burn_time(self, p):
        """Burnout time [s] = the motor's burn time x ``burn_time_scale`` (numbers or MX)."""
        return float(self.setup.motor.burn_time) * p[params.index("burn_time_scale")]

    def _boost_segments(self, n: int) -> list[tuple[float | None, float | None, int]]:
        """The boost grid split at the motor's ignition/burnout events (air-start),
        so no thrust jump falls inside a step: [(start, end, steps)] with start/end
        unscaled event times [s] (None = rail exit / burnout)."""
        events = tuple(getattr(self.setup.motor, "events", ()))
        burn = float(self.setup.motor.burn_time)
        if not events:
            return [(None, None, n)]
        bounds = [None, *events, None]
        lengths = np.diff([0.0, *events, burn])
        counts = [max(4, int(round(n * length / burn))) for length in lengths]
        return [(bounds[i], bounds[i + 1], counts[i]) for i in range(len(counts))]

    def _segmented_boost(self, n: int) -> ca.Function:
        """``(x0, t_rail, t_burnout, p) -> X`` over the segments of :meth:`_boost_segments`
        (event times scaled by ``burn_time_scale``); same signature as a phase trajectory."""
        x0, t0, t1 = ca.MX.sym("x0", 13), ca.MX.sym("t0"), ca.MX.sym("t1")
        p = ca.MX.sym("p", self.n_p)
        s = p[params.index("burn_time_scale")]
        x, blocks = x0, []
        for i, (a, b, k) in enumerate(self._boost_segments(n)):
            traj = phase_trajectory(self.step["boost"], k, f"traj_boost_{i}")
            X = traj(x, t0 if a is None else a * s, t1 if b is None else b * s, p)
            blocks.append(X)
            x = X[:, -1]
        return ca.Function("traj_boost", [x0, t0, t1, p], [ca.hcat(blocks)], ["x0", "t0", "t1", "p"], ["X"])

    def boost_times(self, t_r: float, t_b: float, p) -> np.ndarray:
        """Times [s] of the boost trajectory's columns (after each step)."""
        s = float(np.asarray(p, dtype=float).ravel()[params.index("burn_time_scale")])
        out = []
        for a, b, k in self._boost_segments(self.n_boost):
            lo, hi = (t_r if a is None else a * s), (t_b if b is None else b * s)
            out.append(lo + (hi - lo) * np.arange(1, k + 1) / k)
        return np.concatenate(out)

    def _set_trajectory(self, phase: str, n: int):
        grading = self.coast_grading if phase == "coast" else 1.0
        if phase == "boost" and getattr(self.setup.motor, "events", ()):
            self.trajectory[phase] = self._segmented_boost(n)
        else:
            self.trajectory[phase] = phase_trajectory(self.step[phase], n, f"traj_{phase}", grading)
        self._run[phase] = self.trajectory[phase]      # compiled (if asked) once the grid is fixed
        for key in [k for k in self.__dict__.get("_map_cache", {}) if k[0].split(":")[0] == phase]:
            del self._map_cache[key]

    def stable_step(self, f: ca.Function, x, t, p) -> float:
        """Largest step [s] for RK4 at state ``x`` (columns: the worst one counts).

        ``STABLE_LAMBDA_DT / max |eig(df/dx)|`` of the right-hand side ``f``: inside RK4's
        stability region (|lambda dt| < 2.78 on the real and imaginary axes)
        with margin for accuracy.  Roll damping, the stiffest mode of light
        rockets, is left out: the integrator advances it exactly.
        """
        cache = self.__dict__.setdefault("_jac_cache", {})
        if f.name() not in cache:
            xs, ts, ps = ca.SX.sym("x", 13), ca.SX.sym("t"), ca.SX.sym("p", self.n_p)
            out = f(xs, ts, ps)
            xdot = out[0]
            if "c_roll" in f.name_out():          # advanced exactly by the integrator
                xdot = xdot - ca.vertcat(ca.SX.zeros(10), out[2] * xs[10], ca.SX.zeros(2))
            cache[f.name()] = ca.Function(f"jac_{f.name()}", [xs, ts, ps], [ca.jacobian(xdot, xs)])
        jac = cache[f.name()]
        x = np.atleast_2d(np.asarray(x, dtype=float).T).T
        t = np.broadcast_to(np.asarray(t, dtype=float), (x.shape[1],))
        p = np.asarray(p, dtype=float)
        p = np.repeat(p[:, None], x.shape[1], axis=1) if p.ndim == 1 else p
        lam = max(np.max(np.abs(np.linalg.eigvals(np.array(jac(x[:, i], t[i], p[:, i]))))) for i in range(x.shape[1]))
        return STABLE_LAMBDA_DT / lam if lam > 0 else np.inf

    def _coast_grid(self, x_b, t_b, t_end, p):
        """(n_coast, grading) from the stiffness along the nominal coast.

        A provisional uniform coast (stable at burnout, the stiffest point) is
        flown; at ~30 states before apogee the largest eigenvalue
        ``lambda(s)`` of the RHS Jacobian is taken, and for each grading ``a``
        of :func:`~ironbark_opt.dynamics.integrator.grid_fractions` the
        smallest ``n`` with ``span g_a'(s) lambda(s) / n <= STABLE_LAMBDA_DT``
        everywhere; the cheapest (n, a) wins.  The stiffness falls with speed
        and density, so finer steps after burnout and coarser ones near
        apogee need about half the steps of a uniform grid.
        """
        span = float(t_end - t_b)
        n_uni = max(self.steps.n_coast, int(math.ceil(span / self.stable_step(self.rhs["coast"], x_b, t_b, p))))
        X = self._coast_probe(x_b, t_b, t_end, p, n_uni)
        vz = np.array(self._mapped("vz", n_uni)(X)).ravel()
        k_top = int(np.argmax(vz <= 0)) if np.any(vz <= 0) else n_uni
        idx = np.unique(np.linspace(0, max(k_top, 1), 30).astype(int))
        states = np.column_stack([x_b] + [X[:, i - 1] for i in idx[1:]])
        frac = idx / n_uni
        lam = np.array([STABLE_LAMBDA_DT / self.stable_step(self.rhs["coast"], states[:, j], t_b + span * f, p)
                        for j, f in enumerate(frac)])
        best = None
        for a in (1.0, 0.7, 0.5, 0.35, 0.25):
            slope = a + 2.0 * (1.0 - a) * frac                    # g_a'(s)
            n = int(math.ceil(np.max(span * slope * lam) / STABLE_LAMBDA_DT))
            n = max(MIN_COAST_STEPS, 25 * int(math.ceil(n / 25)))
            if best is None or n < best[0]:
                best = (n, a)
        return best

    def _coast_probe(self, x_b, t_b, t_end, p, n: int) -> np.ndarray:
        """States after each of ``n`` uniform coast steps from burnout (grid choice only)."""
        return np.array(phase_trajectory(self.step["coast"], n, "traj_coast_probe")(x_b, t_b, t_end, p))

    def _ensure_stable(self, x_b, t_b, t_end, P):
        """Refine the boost step if burnout (the stiffest point) needs it and
        choose the coast grid (:meth:`_coast_grid`); called once, at build."""
        dt_b = self.stable_step(self.rhs["boost"], x_b, t_b, P)
        if self.steps.dt_boost > dt_b:
            self.n_boost = int(math.ceil(self.n_boost * self.steps.dt_boost / dt_b))
            self._set_trajectory("boost", self.n_boost)
        self.n_coast, self.coast_grading = self._coast_grid(x_b, t_b, t_end, P)
        self._set_trajectory("coast", self.n_coast)

    # ------------------------------------------------------------------ symbolic
    def initial_state(self, p):
        """State at t = 0: at rest at the rail foot, body axis along the rail."""
        P = params.unpack(p)
        q0 = launch_quaternion(P["inclination"], P["heading"])
        return ca.vertcat(0, 0, 0, 0, 0, 0, q0, 0, 0, 0)

    def rail_residual(self, t_r, p):
        """Distance along the rail minus the distance to leave it [m] (MX)."""
        P = params.unpack(p)
        x = self.trajectory["rail"](self.initial_state(p), 0, t_r, p)[:, -1]
        travel = ca.dot(x[0:3], rail_direction_l(P["inclination"], P["heading"]))
        return travel - (P["rail_length"] - self.setup.rail_exit_offset)

    @property
    def rail_exit_root(self) -> ca.Function:
        """``(t_guess, p) -> t_r``: the rail-exit time, root of :meth:`rail_residual` by
        CasADi's Newton ``rootfinder`` (symbolic uses: sensitivities, staged rockets);
        built on first use (~20 ms and the rail trajectory's Function that a numeric
        run from the compiled library does not need)."""
        root = self.__dict__.get("_rail_exit_root")
        if root is None:
            t_r = ca.MX.sym("t_r")
            p = ca.MX.sym("p", self.n_p)
            g = ca.Function("rail_residual", [t_r, p], [self.rail_residual(t_r, p)])
            root = self.__dict__["_rail_exit_root"] = ca.rootfinder(
                "rail_exit", "newton", g, {"abstol": 1e-10, "max_iter": 50, "error_on_fail": True})
        return root

    def _build_events(self, apex: ca.Function | None = None):
        ps = ca.SX.sym("p", self.n_p)
        P = params.unpack(ps)
        self._launch = ca.Function("launch", [ps], [self.initial_state(ps),
                                                    rail_direction_l(P["inclination"], P["heading"])])
        self.__dict__.pop("_rail_exit_root", None)
        x = ca.SX.sym("x", 13)
        self.vz_l = ca.Function("vz_l", [x], [(rotation_matrix(x[6:10]) @ x[3:6])[2]])
        if apex is None:
            h = ca.SX.sym("h")
            t = ca.SX.sym("t")
            ps = ca.SX.sym("p", self.n_p)
            vz = self.vz_l(self.step["coast"](x, t, h, ps))
            apex = ca.Function("apex", [x, t, h, ps], [vz, ca.jacobian(vz, h)])
        self._apex = apex
        self._apogee_run = self._apogee_event = self._apogee_function(apex)

    def _apogee_function(self, apex: ca.Function, iterations: int = 5) -> ca.Function:
        """``(x_k, t_k, h0, dt, p) -> (h, x_apogee)``: the apogee inside a coast step.

        :meth:`refine_in_step`'s Newton iterations on the step length (the same
        operations, so the same bits) and the step to apogee, in one Function
        (one call, compiled with the model) instead of a Python loop of calls.
        """
        x, t, h0, dt = ca.MX.sym("x", 13), ca.MX.sym("t"), ca.MX.sym("h0"), ca.MX.sym("dt")
        p = ca.MX.sym("p", self.n_p)
        h = h0
        for _ in range(iterations):
            val, der = apex(x, t, h, p)
            h = ca.fmin(ca.fmax(h - val / ca.if_else(der == 0, 1.0, der), 0.0), dt)
        x_a = self.step["coast"](x, t, h, p)
        return ca.Function("apogee_event", [x, t, h0, dt, p], [h, x_a], ["x", "t", "h0", "dt", "p"], ["h", "x_a"])

    # ------------------------------------------------------------------ numeric
    def _rail_travel(self, t_r: float, p: np.ndarray, geom) -> tuple[float, np.ndarray]:
        """(travel along the rail minus the exit distance [m], states) at ``t_r`` [s]."""
        x0, e, exit_distance = geom
        X = np.array(self._run["rail"](x0, 0.0, t_r, p))
        return float(e @ X[0:3, -1]) - exit_distance, X

    def _x0(self, p):
        return np.array(self._launch(p)[0]).ravel()

    def rail_exit(self, p: np.ndarray) -> float:
        """Rail-exit time [s] for numeric ``p``.

        The root of the same residual the symbolic model's ``rootfinder``
        uses (rail phase with ``n_rail`` equal steps over ``[0, t_r]``): a
        first run brackets it and interpolates a guess from its samples,
        then secant steps (no derivative needed, so it runs on the compiled
        functions too), with a bracketing Illinois fallback.
        """
        return self._rail_exit(p)[0]

    def _rail_exit(self, p: np.ndarray) -> tuple[float, np.ndarray]:
        """(rail-exit time [s], rail-phase states at it (13 x n_rail)): see :meth:`rail_exit`;
        the states of the last residual evaluation are kept, not integrated again."""
        exit_distance = p[params.index("rail_length")] - self.setup.rail_exit_offset
        if exit_distance <= 0:
            raise InputError(f"rail length {p[params.index('rail_length')]:.3f} m is shorter than the "
                             f"distance from the nozzle to the rail guide ({self.setup.rail_exit_offset:.3f} m)",
                             field="rail_length")
        x0, e = (np.array(v).ravel() for v in self._launch(p))
        geom = (x0, e, exit_distance)
        burn = float(self.burn_time(p))
        lo, g_lo, hi = 0.0, -exit_distance, min(0.5, burn)
        while True:
            g_hi, X = self._rail_travel(hi, p, geom)
            if g_hi > 0:
                break
            if hi >= burn:
                raise InputError("the rocket does not leave the rail before motor burnout: check thrust, "
                                 "mass and rail length", field="rail_length")
            lo, g_lo, hi = hi, g_hi, min(2 * hi, burn)
        travel = np.concatenate([[g_lo], e @ X[0:3, :] - exit_distance]) if lo == 0 else None
        if travel is not None:
            k = int(np.argmax(travel > 0))
            dt = hi / (travel.size - 1)
            t_a = (k - 1) * dt + dt * (-travel[k - 1]) / (travel[k] - travel[k - 1])
            t_b = t_a * (1 + 1e-4)
            g_a, X_a = self._rail_travel(t_a, p, geom)
            for _ in range(8):                      # secant from the interpolated guess
                if abs(g_a) < 1e-10:
                    return t_a, X_a
                g_b, X_b = self._rail_travel(t_b, p, geom)
                if g_b == g_a:
                    break
                t_a, g_a, X_a, t_b = t_b, g_b, X_b, t_b - g_b * (t_b - t_a) / (g_b - g_a)
                if not lo <= t_b <= hi:
                    break
        # Illinois regula falsi fallback
        t, _, X, _, done = illinois(lambda t: self._rail_travel(t, p, geom), lo, g_lo, hi, g_hi,
                                    gtol=np.nextafter(1e-10, 0.0), xtol=np.nextafter(1e-12, 0.0))
        if not done:
            raise SolverError(f"rail-exit time did not converge (bracket {lo:.6f}..{hi:.6f} s)")
        return t, X

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

    def _ascent_runner(self):
        """The :class:`~ironbark_opt.dynamics.ascent.AscentRunner` of this model's grid
        (built on first use; compiled as ``self.jit`` asks, like the phase Functions)."""
        cache = self.__dict__.setdefault("_ascent_cache", {})
        key = self.discretisation()
        if key not in cache:
            from ironbark_opt.dynamics.ascent import AscentRunner
            cache.clear()
            func = self._lib.get("ascent")
            if func is None:
                func = self._ascent_vm()[0] if self._one_library else self._compiled(self._ascent_vm()[0])
            cache[key] = AscentRunner(func)
        return cache[key]

    def _ascent_vm(self) -> tuple[ca.Function, ca.Function]:
        """``(ascent, ascent_batch)`` of :func:`~ironbark_opt.dynamics.ascent.ascent_functions`
        in the VM, built once per grid."""
        grid, funcs = self.__dict__.get("_ascent_vm_funcs", (None, None))
        if grid != self.discretisation():
            from ironbark_opt.dynamics.ascent import ascent_functions
            funcs = ascent_functions(self)
            self.__dict__["_ascent_vm_funcs"] = (self.discretisation(), funcs)
        return funcs

    def _ascent_fused(self, p) -> dict | None:
        """The ascent from one call of the ascent Function, or None where it does not
        apply (then :meth:`_ascent_phased` flies it, and raises what it finds)."""
        from ironbark_opt.dynamics.ascent import EV, applies
        if p[params.index("rail_length")] - self.setup.rail_exit_offset <= 0:
            return None
        r = self._ascent_runner()(p)
        if r is None or not applies([r[k] for k in EV])[0]:
            return None
        k, t_b = int(r["k"]), r["t_burnout"]
        return dict(x0=r["x0"], t_r=r["t_rail"], X_rail=r["X_rail"], t_b=t_b, X_boost=r["X_boost"],
                    span=r["t_end"] - t_b, k=k, X_coast=r["X_coast"][:, :k], t_a=r["t_k"] + r["h"],
                    x_a=r["x_apogee"])

    def _ascent_phased(self, p) -> dict:
        """The ascent phase by phase from Python (rail-exit secant, boost, coast to a
        horizon, apogee refinement): the path :meth:`_ascent_fused` falls back to."""
        x0 = self._x0(p)
        t_r, X_rail = self._rail_exit(p)
        t_b = self.burn_time(p)
        if t_r >= t_b:
            raise InputError(f"motor burns out ({t_b:.2f} s) before rail exit ({t_r:.2f} s)",
                             field="motor")
        x_r = X_rail[:, -1].copy()
        X_boost = np.array(self._run["boost"](x_r, t_r, t_b, p))
        x_b = X_boost[:, -1]
        vz_b = float(self.vz_l(x_b))
        if vz_b <= 0:
            raise SolverError("vertical velocity at burnout is not positive: the rocket never climbs; check the "
                              "launch mass, the motor, launch.inclination_deg and the wind")
        # Drag only shortens the coast below the vacuum time v_z / g; the margin
        # covers gravity falling off with height.
        t_end = t_b + vz_b / G0 + 2.0
        for _ in range(3):
            X_dm = self._run["coast"](x_b, t_b, t_end, p)
            X_coast = np.array(X_dm)
            vz = np.array(self._mapped("vz", X_coast.shape[1])(X_dm)).ravel()    # no NumPy round trip
            below = np.nonzero(vz <= 0)[0]
            if below.size:
                break
            t_end = t_b + 1.5 * (t_end - t_b)
        else:
            raise SolverError("apogee not reached within the coast horizon")
        k = int(below[0])
        fr = self.coast_fractions_of(p)
        span = t_end - t_b
        dt_c = span * (fr[k + 1] - fr[k])
        x_k = x_b if k == 0 else X_coast[:, k - 1]
        t_k = t_b + span * fr[k]
        vz_k = vz_b if k == 0 else vz[k - 1]
        h0 = dt_c * vz_k / (vz_k - vz[k]) if vz_k != vz[k] else dt_c
        h, x_a = self._apogee_run(x_k, t_k, h0, dt_c, p)
        return dict(x0=x0, t_r=t_r, X_rail=X_rail, t_b=t_b, X_boost=X_boost, span=span, k=k,
                    X_coast=X_coast[:, :k], t_a=t_k + float(h), x_a=np.array(x_a).ravel())

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

    # ------------------------------------------------------------------ batches
    def _batch_function(self, phase: str) -> ca.Function:
        """The phase trajectory returning only what :meth:`run_batch` reads (fewer
        numbers to convert): rail -> (positions, final state), boost -> final state,
        coast -> (vertical velocities, the state before the first step ending at
        v_z <= 0 (the start state if it is the first; zeros if none)).

        The coast's state is picked inside the Function by a one-hot weight (the
        first column where the running count of ``v_z <= 0`` steps is 1): one
        column times 1 plus zeros is that column exactly, and 13 numbers per
        sample are converted instead of 13 x n_coast."""
        x0, t0, t1 = ca.MX.sym("x0", 13), ca.MX.sym("t0"), ca.MX.sym("t1")
        p = ca.MX.sym("p", self.n_p)
        X = self._run[phase](x0, t0, t1, p)
        if phase == "coast":
            vz = self.vz_l.map(X.size2())(X)
            below = vz <= 0
            first = below * (ca.cumsum(below, 1) == 1)                 # one-hot row (1 x n)
            x_before = ca.mtimes(X[:, :-1], first[:, 1:].T) + x0 * first[:, 0]
            return ca.Function(f"{phase}_batch", [x0, t0, t1, p], [vz, x_before])
        outs = {"rail": [X[0:3, :], X[:, -1]], "boost": [X[:, -1]]}[phase]
        return ca.Function(f"{phase}_batch", [x0, t0, t1, p], outs)

    def _mapped(self, key, n):
        cache = self.__dict__.setdefault("_map_cache", {})
        if (key, n) not in cache:
            if key.endswith(":batch"):
                cache[(key, n)] = self._batch_function(key.split(":")[0]).map(n, "thread", 2)
                return cache[(key, n)]
            base = {"launch": self._launch, "apogee": self._apogee_run, "vz": self.vz_l,
                    "step": self.step["coast"]}.get(key) or self._run[key]
            cache[(key, n)] = base.map(n, "thread", 2) if key in self._run else base.map(n)
        return cache[(key, n)]

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

    def _run_batch_fused(self, P: np.ndarray, descent: bool) -> dict:
        """:meth:`run_batch` by ``ascent_batch`` mapped over the samples (threads): the
        very Function of :meth:`run`, so a sample and its single run agree to the bit;
        the samples it does not apply to fly one by one through :meth:`run`."""
        from ironbark_opt.dynamics.ascent import EV, applies
        n = P.shape[1]
        if np.any(P[params.index("rail_length")] - self.setup.rail_exit_offset <= 0):
            raise InputError("rail length shorter than the nozzle-to-guide distance in some samples",
                             field="rail_length")
        cache = self.__dict__.setdefault("_map_cache", {})
        if ("ascent_batch", n) not in cache:
            base = self._lib.get("ascent_batch")
            if base is None:
                base = self._ascent_vm()[1] if self._one_library else self._compiled(self._ascent_vm()[1])
            cache[("ascent_batch", n)] = base.map(n, "thread", 2)
        ev, x_r, x_a = (np.array(v) for v in cache[("ascent_batch", n)](P))
        r = dict(zip(EV, ev))
        t_r, burn, t_apo = r["t_rail"], r["t_burnout"], r["t_k"] + r["h"]
        for j in np.nonzero(~applies(ev))[0]:
            one = self.run(P[:, j])
            t_r[j], burn[j], t_apo[j] = one["t_rail"], one["t_burnout"], one["t_apogee"]
            x_r[:, j], x_a[:, j] = one["x_rail"], one["x_apogee"]
        return self._batch_result(P, t_r, burn, t_apo, x_r, x_a, descent)

    def _batch_result(self, P, t_r, burn, t_apo, x_r, x_a, descent: bool) -> dict:
        """``run_batch``'s dict from the samples' events; a sample whose ejection charge
        fires before apogee (or, with ``descent``, after it) flies alone through :meth:`run`."""
        redo = {}
        t_e = ejection.ejection_time(self.setup, P)
        if t_e is not None:                   # each sample in its own ejection case
            for j in np.nonzero((t_e < t_apo) | (descent & (t_e > t_apo)))[0]:
                redo[j] = one = self.run(P[:, j], descent=descent)
                x_a[:, j], t_apo[j] = one["x_apogee"], one["t_apogee"]
        out = dict(apogee_agl=x_a[2], t_apogee=t_apo, t_rail=t_r,
                   rail_exit_speed=np.linalg.norm(x_r[3:6], axis=0), t_burnout=burn, x_apogee=x_a)
        if descent:
            out.update(self.descend(x_a, t_apo, P))
            for j, one in redo.items():
                out["t_landing"][j], out["x_landing"][:, j] = one["t_landing"], one["x_landing"]
        return out

    def _run_batch_phased(self, P: np.ndarray, descent: bool) -> dict:
        """:meth:`run_batch` phase by phase (the motor-slot model's path): the phase
        Functions mapped, the rail-exit secant and apogee refinement vectorised."""
        n = P.shape[1]
        idx = np.arange(n)
        x0, e = (np.array(v) for v in self._mapped("launch", n)(P))
        exit_distance = P[params.index("rail_length")] - self.setup.rail_exit_offset
        if np.any(exit_distance <= 0):
            raise InputError("rail length shorter than the nozzle-to-guide distance in some samples",
                             field="rail_length")
        burn = self.burn_time(P)
        rail, nr = self._mapped("rail:batch", n), self.steps.n_rail

        def travel(t):
            # mapped outputs are blocks of nr columns per sample: positions (3, n, nr), final states (13, n)
            pos, last = rail(x0, 0.0, t[None, :], P)
            pos = np.array(pos).reshape(3, n, nr)
            return np.einsum("in,inj->nj", e, pos) - exit_distance[:, None], np.array(last)

        hi = np.minimum(0.5, burn)
        for _ in range(10):
            trav, X = travel(hi)
            grow = trav[:, -1] <= 0
            if not grow.any():
                break
            if np.any(grow & (hi >= burn)):
                raise InputError("some samples do not leave the rail before motor burnout", field="rail_length")
            hi = np.where(grow, np.minimum(2 * hi, burn), hi)
        trav = np.concatenate([-exit_distance[:, None], trav], axis=1)
        k = np.argmax(trav > 0, axis=1)
        dt = hi / nr
        t_a = (k - 1 + (-trav[idx, k - 1]) / (trav[idx, k] - trav[idx, k - 1])) * dt
        t_b = t_a * (1 + 1e-4)
        g_a = travel(t_a)[0][:, -1]
        for _ in range(10):                       # secant, all samples together
            if np.all(np.abs(g_a) < 1e-10):
                break
            g_b = travel(t_b)[0][:, -1]
            done = (np.abs(g_b) < 1e-10) | (g_b == g_a)
            t_new = np.where(done, t_b, t_b - g_b * (t_b - t_a) / np.where(done, 1.0, g_b - g_a))
            t_a, g_a, t_b = t_b, g_b, t_new
        if np.any(np.abs(g_a) > 1e-6):
            raise SolverError("rail exit did not converge for some samples")
        t_r = t_a
        x_r = travel(t_r)[1]
        x_b = np.array(self._mapped("boost:batch", n)(x_r, t_r[None, :], burn[None, :], P))
        vz_b = np.array(self._mapped("vz", n)(x_b)).ravel()
        t_end = burn + vz_b / G0 + 2.0
        nc = self.n_coast
        vz, x_k = self._mapped("coast:batch", n)(x_b, burn[None, :], t_end[None, :], P)
        vz, x_k = np.array(vz).reshape(n, nc), np.array(x_k)
        below = vz <= 0
        if not np.all(below.any(axis=1)):
            raise SolverError("apogee not reached within the coast horizon for some samples")
        kc = np.argmax(below, axis=1)
        fr = self.coast_fractions_of(P[:, 0])
        span = t_end - burn
        dtc = span * (fr[kc + 1] - fr[kc])
        t_k = burn + span * fr[kc]
        vz_k = np.where(kc == 0, vz_b, vz[idx, np.maximum(kc - 1, 0)])
        vz_end = vz[idx, kc]
        h = dtc * vz_k / np.where(vz_k != vz_end, vz_k - vz_end, 1.0)
        h, x_a = self._mapped("apogee", n)(x_k, t_k[None, :], h[None, :], dtc[None, :], P)
        h, x_a = np.array(h).ravel(), np.array(x_a)
        t_apo = t_k + h
        return self._batch_result(P, t_r, burn, t_apo, x_r, x_a, descent)

    @staticmethod
    def refine_in_step(func, x_k, t_k, h, dt, P, level=0.0, iterations: int = 5):
        """Event inside a step: root ``h`` in [0, dt] of ``func(x_k, t_k, h, P)[0] = level``.

        Newton on the step length with the derivative from ``func``'s second
        output, clipped to the step, a fixed number of iterations (quadratic
        convergence from the linear guess reaches round-off in 3).  All
        columns at once (the descent's ground and deployment crossings);
        apogee uses the same iteration inside one Function
        (:meth:`_apogee_function`), shared by :meth:`run` and :meth:`run_batch`
        so their events agree to the last bit.
        """
        for _ in range(iterations):
            val, der = (np.array(v).ravel() for v in func(x_k, t_k[None, :], h[None, :], P))
            h = np.clip(h - (val - level) / np.where(der == 0, 1.0, der), 0.0, dt)
        return h

    # ------------------------------------------------------------------ descent
    def descent_stages(self) -> list[tuple[float | None, float, str]]:
        """[(trigger altitude AGL [m] or None for apogee, total Cd*S [m^2], label)].

        Chutes without a deploy altitude open at apogee; the others add their
        Cd*S when the rocket descends through their altitude (dual deploy).
        Inflation lag is neglected.  No chute: one ballistic stage (the coast
        equations continue, 6-DOF).
        """
        chutes = self.setup.parachutes
        if not chutes:
            return [(None, 0.0, "ballistic")]
        stages, cd = [], sum(c.cd_area for c in chutes if c.deploy_altitude is None)
        stages.append((None, cd, "descent"))
        for alt in sorted({c.deploy_altitude for c in chutes if c.deploy_altitude is not None}, reverse=True):
            cd += sum(c.cd_area for c in chutes if c.deploy_altitude == alt)
            stages.append((alt, cd, f"descent_{len(stages) + 1}"))
        return stages

    def _descent_functions(self, cd_area: float, label: str):
        cache = self.__dict__.setdefault("_descent_cache", {})
        key = (cd_area, label)
        if key not in cache:
            if label == "ballistic":
                f, step = self.rhs["coast"], self.step["coast"]
            elif cd_area <= 0:
                raise InputError("a parachute stage has no drag area (Cd*S = 0)", field="recovery")
            else:
                f = rhs_mod.build(self.setup, "descent", cd_area=cd_area)
                step = rk4_step(f, "step_descent")
            x, t, h = ca.SX.sym("x", 13), ca.SX.sym("t"), ca.SX.sym("h")
            ps = ca.SX.sym("p", self.n_p)
            z = step(x, t, h, ps)[2]
            cross = ca.Function("z_step", [x, t, h, ps], [z, ca.jacobian(z, h)])
            cache[key] = (f, step, phase_trajectory(step, 100, f"traj_{label}"), cross)
            self.__dict__.setdefault("_stage_rhs", {})[label] = f
        return cache[key]

    def descend(self, x_a, t_a, P, *, keep_samples: bool = False) -> dict:
        """From apogee states ``x_a`` (13, n) at ``t_a`` (n,) to the ground.

        Each stage integrates with a fixed step (``dt_descent`` under a chute,
        0.02 s ballistic) in chunks of 100 steps, all samples together, until
        every sample passes the stage's end altitude; the crossing is then
        solved inside its step by Newton on the step length (as for apogee).

        Returns
        -------
        dict: ``t_landing`` (n,) [s], ``x_landing`` (13, n); with
        ``keep_samples`` (n = 1 only) also ``t``, ``x``, ``phase`` samples.
        """
        n = x_a.shape[1]
        idx = np.arange(n)
        x_cur, t_cur = np.array(x_a, dtype=float), np.array(t_a, dtype=float)
        stages = self.descent_stages()
        ts, xs, labels = [], [], []
        for s_i, (_, cd_area, label) in enumerate(stages):
            z_end = stages[s_i + 1][0] if s_i + 1 < len(stages) else 0.0
            f, step, chunk, cross = self._descent_functions(cd_area, label)
            dt = 0.02 if label == "ballistic" else self.steps.dt_descent
            dt = min(dt, self.stable_step(f, x_cur, t_cur, P))
            chunk_n, cross_n = chunk.map(n), cross.map(n)
            done = x_cur[2] <= z_end
            x_k, t_k = x_cur.copy(), t_cur.copy()
            for _ in range(2000):
                if done.all():
                    break
                X = np.array(chunk_n(x_cur, t_cur[None, :], (t_cur + 100 * dt)[None, :], P)).reshape(13, n, 100)
                below = X[2] <= z_end
                hit = below.any(axis=1) & ~done
                k = np.argmax(below, axis=1)
                prev = np.where(k[None, :] == 0, x_cur, X[:, idx, np.maximum(k - 1, 0)])
                x_k[:, hit] = prev[:, hit]
                t_k[hit] = t_cur[hit] + k[hit] * dt
                if keep_samples:
                    m = k[0] if hit[0] else 100
                    xs.append(X[:, 0, :m])
                    ts.append(t_cur[0] + dt * np.arange(1, m + 1))
                    labels += [label] * m
                done = done | hit
                active = ~done
                x_cur[:, active] = X[:, active, -1]
                t_cur[active] = t_cur[active] + 100 * dt
            else:
                raise SolverError("descent did not reach the ground within the time limit")
            h = self.refine_in_step(cross_n, x_k, t_k, np.full(n, 0.5 * dt), dt, P, level=z_end, iterations=12)
            x_cur = np.array(step.map(n)(x_k, t_k[None, :], h[None, :], P))
            t_cur = t_k + h
            if keep_samples:
                xs.append(x_cur[:, :1].copy())    # copies: the next stage updates x_cur/t_cur in place
                ts.append(t_cur[:1].copy())
                labels.append(label)
        out = {"t_landing": t_cur, "x_landing": x_cur}
        if keep_samples:
            out.update(t=np.concatenate(ts), x=np.hstack(xs), phase=np.array(labels))
        return out

    def _descend(self, t_a, x_a, p, t, x, phase):
        """Single run: descent samples appended to the ascent's (with a free fall
        from apogee to a late ejection charge first)."""
        late = self._late_ejection(x_a, t_a, p)
        if late is not None:
            t_l, X_l = late
            t, x = np.concatenate([t, t_l]), np.hstack([x, X_l])
            phase = np.concatenate([phase, ["coast"] * t_l.size])
            t_a, x_a = float(t_l[-1]), X_l[:, -1]
        d = self.descend(x_a[:, None], np.array([t_a]), p[:, None], keep_samples=True)
        return dict(t=np.concatenate([t, d["t"]]), x=np.hstack([x, d["x"]]),
                    phase=np.concatenate([phase, d["phase"]]),
                    t_landing=float(d["t_landing"][0]), x_landing=d["x_landing"][:, 0])

    def _late_ejection(self, x_a, t_a, p):
        """(times, states) of the free fall from apogee to an ejection charge that
        fires after it, when every chute opening at apogee waits for the charge."""
        t_e = ejection.ejection_time(self.setup, p)
        waits = all(c.at_ejection for c in self.setup.parachutes if c.deploy_altitude is None)
        if t_e is None or t_e <= t_a or not waits:
            return None
        return ejection.coast_to_late_ejection(self, x_a, t_a, t_e, p)

    def outputs(self, t, x, phase, p) -> np.ndarray:
        """Derived quantities (rows of ``rhs.OUTPUT_NAMES``) at the samples;
        ``p`` one parameter vector or one column per sample."""
        y = np.zeros((len(rhs_mod.OUTPUT_NAMES), t.size))
        p = np.asarray(p, dtype=float)
        p_col = p.reshape(-1, 1) if p.ndim == 1 else None
        for ph in np.unique(phase):
            idx = np.nonzero(phase == ph)[0]
            P = p_col if p_col is not None else p[:, idx]       # one vector, or one per sample
            y[:, idx] = np.array(self._outputs_function(ph, idx.size)(x[:, idx], t[idx][None, :], P))
        return y

    def _outputs_base(self, phase: str) -> ca.Function:
        """``(x, t, p) -> y``: the output rows of ``phase``'s right-hand side at one sample."""
        f = self.rhs[phase] if phase in self.rhs else self._stage_rhs[phase]
        xs, ts, ps = ca.SX.sym("x", 13), ca.SX.sym("t"), ca.SX.sym("p", self.n_p)
        return ca.Function(f"outputs_{phase}", [xs, ts, ps], [f(xs, ts, ps)[1]])

    def _outputs_function(self, phase: str, n: int) -> ca.Function:
        """``(X (13 x n), t (1 x n), p) -> Y``: the phase's output rows mapped over n
        samples; built once per (phase, n) and kept (``simulate`` calls it on every run)."""
        cache = self.__dict__.setdefault("_out_cache", {})
        if (phase, n) not in cache:
            base = cache.get(phase)
            if base is None:
                base = self._lib.get(f"outputs_{phase}") or self._outputs_base(phase)
                if phase in self.rhs and not self._one_library:    # else: in the model's library
                    base = self._compiled(base)
                cache[phase] = base
            cache[(phase, n)] = base.map(n)
        return cache[(phase, n)]


def _refuse_controller(setup):
    """A Python air-brake controller flies only through dynamics.controlled."""
    brakes = getattr(setup, "airbrakes", None)
    if brakes is not None and not brakes.differentiable:
        raise InputError("this rocket's air brakes follow a Python controller, which only 'simulate' flies; "
                         "ballast, sensitivities and Monte Carlo need a schedule (trigger = time, altitude, "
                         "mach or vertical_speed)", source=setup.source, field="airbrakes.trigger")


def _final_state(model: FlightModel, p, T, t_rail_guess: float, t_rail=None):
    """Symbolic (MX) state at time ``T`` in the coast, through all phases; the
    rail exit by rootfinder from ``t_rail_guess``, or ``t_rail`` itself (an
    optimisation variable constrained by :meth:`FlightModel.rail_residual`)."""
    if hasattr(type(model), "final_state_symbolic"):    # staged rockets (dynamics/staged.py)
        return model.final_state_symbolic(p, T, t_rail_guess)
    t_r = model.rail_exit_root(t_rail_guess, p) if t_rail is None else t_rail
    x_r = model.trajectory["rail"](model.initial_state(p), 0, t_r, p)[:, -1]
    t_b = model.burn_time(p)
    X_b = model.trajectory["boost"](x_r, t_r, t_b, p)
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
    v_max = ca.mmax(ca.sqrt(ca.sum1(X_b[3:6, :] ** 2)))
    final = ca.Function("final_state", [p, T], [x_t, t_r, x_r, v_max], ["p", "T"],
                        ["x_T", "t_rail", "x_rail", "max_speed"])
    vz = ca.Function("vz_T", [T, p], [model.vz_l(x_t)])
    t_apo = ca.rootfinder("apogee_time", "newton", vz, {"abstol": 1e-9, "max_iter": 30, "error_on_fail": True})(t_apogee0, p)
    x_a, t_r2, x_r2, v_max2 = final(p, t_apo)
    apogee = ca.Function("apogee", [p], [x_a[2], t_apo, ca.norm_2(x_r2[3:6]), v_max2],
                         ["p"], ["apogee_agl", "t_apogee", "rail_exit_speed", "max_speed"])
    return {"final_state": final, "apogee": apogee}
