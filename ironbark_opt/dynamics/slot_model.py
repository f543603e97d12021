"""One flight model for many motors: the motor and the RK4 grid in ``p``.

:class:`SlotFlightModel` is a :class:`~ironbark_opt.dynamics.model.FlightModel`
whose motor is a :class:`~ironbark_opt.motors.slot.MotorSlot` and whose boost
and coast grids are read from ``p`` (:func:`~ironbark_opt.dynamics.integrator.padded_grid`).
The parameter vector is

    p_ext = [p (params.SIZE) | motor data (slot.n_data) | boost grid (2 cap_b) | coast grid (2 cap_c)]

so the model (and an NLP built on it) is built once and flies every candidate
motor with *its own* grid — the grid :meth:`FlightModel._choose_grid` picks
for that motor — by changing numbers.  Steps past a motor's grid have length
0 and leave the state exactly as it is, so a candidate flies the same RK4
steps as on its own model.
"""
from __future__ import annotations

import dataclasses
import hashlib

import casadi as ca
import numpy as np

from ironbark_opt import params
from ironbark_opt.dynamics import model_cache
from ironbark_opt.dynamics import rhs as rhs_mod
from ironbark_opt.dynamics.buffered import buffered as _buffered
from ironbark_opt.dynamics.integrator import (cached_library, grid_fractions, jit_mode, padded_grid,
                                               phase_trajectory, rk4_step)
from ironbark_opt.dynamics.model import FlightModel, Steps, initial_boost_steps
from ironbark_opt.motors.slot import MotorSlot


class SlotFlightModel(FlightModel):
    """Flight model of ``setup`` with a motor slot of ``n_knots`` knots and grids
    of up to ``capacity = (boost steps, coast steps)``.

    Use :meth:`parameters` to lay out a candidate's ``p_ext``; ``run``,
    ``_final_state`` and the ballast NLP take ``p_ext``.
    """

    _FUSED = False          # grids read from p: flown phase by phase

    def __init__(self, setup, n_knots: int, capacity: tuple[int, int], steps: Steps | None = None, *, jit=False):
        self.slot = MotorSlot(n_knots, params.SIZE)
        self.cap_boost, self.cap_coast = int(capacity[0]), int(capacity[1])
        self.o_boost = params.SIZE + self.slot.n_data
        self.o_coast = self.o_boost + 2 * self.cap_boost
        self.n_p = self.o_coast + 2 * self.cap_coast
        self.setup = dataclasses.replace(setup, motor=self.slot)
        self.steps = steps or Steps()
        self.jit = jit_mode(jit)
        self.trajectory, self._run = {}, {}
        self.n_boost, self.n_coast, self.coast_grading = self.cap_boost, self.cap_coast, 1.0
        self._key = model_cache.model_key(self.setup, (self.steps, self.n_p))
        cached = model_cache.load(self._key, lazy=True)
        if cached is not None:
            # deserialised when first used: with the compiled libraries cached, a ranking
            # needs the rail trajectory, the coast step and the right-hand sides symbolically
            # (~0.15 s of Functions left on disk: the boost and coast trajectories)
            self.rhs, self.step, self.trajectory = (model_cache.PhaseView(cached, f"{kind}_")
                                                    for kind in ("rhs", "step", "traj"))
            self._build_events(cached["apex"])
        else:
            self.rhs = {ph: rhs_mod.build(self.setup, ph, n_p=self.n_p) for ph in ("rail", "boost", "coast")}
            self.step = {ph: rk4_step(f, f"step_{ph}") for ph, f in self.rhs.items()}
            self.trajectory["rail"] = phase_trajectory(self.step["rail"], self.steps.n_rail, "traj_rail")
            for ph, cap, off in (("boost", self.cap_boost, self.o_boost), ("coast", self.cap_coast, self.o_coast)):
                self.trajectory[ph] = phase_trajectory(self.step[ph], cap, f"traj_{ph}", grid_offset=off)
            self._build_events()
            model_cache.store(self._key, {**{f"rhs_{ph}": f for ph, f in self.rhs.items()},
                                          **{f"step_{ph}": f for ph, f in self.step.items()},
                                          **{f"traj_{ph}": f for ph, f in self.trajectory.items()},
                                          "apex": self._apex})
        for ph in ("rail", "boost", "coast"):
            self._run[ph] = self._cached_run(ph) or self._compiled(self.trajectory[ph])
        self._apogee_run = self._compiled(self._apogee_event)
        # a run calls these ~12 times with p_ext (~1600 numbers): no DM conversions
        for ph in ("rail", "boost", "coast"):
            self._run[ph] = _buffered(self._run[ph])
        self._apogee_run = _buffered(self._apogee_run)
        self._launch, self.vz_l = _buffered(self._launch), _buffered(self.vz_l)

    def _cached_run(self, phase: str, kind: str = "traj"):
        """The compiled trajectory (``kind="outputs"``: output rows) of ``phase`` if the
        cache has it, found by its name and key (as :meth:`_compiled` names it) without
        loading or building the symbolic Function."""
        if not self.jit or self._key is None or phase not in ("rail", "boost", "coast"):
            return None
        return cached_library(f"{kind}_{phase}", self._library_key())

    def _rebuild_args(self) -> tuple:
        return (self.setup, self.slot.n_knots, (self.cap_boost, self.cap_coast), self.steps)

    def _compile_libraries(self, discretisation) -> None:
        """Compile, now, every library ``jit="auto"`` looks for: the phase trajectories,
        the apogee event and the phases' output rows (one library each)."""
        self.jit = True
        for ph in ("rail", "boost", "coast"):
            self._compiled(self.trajectory[ph])
            self._compiled(self._outputs_base(ph))
        self._compiled(self._apogee_event)

    # ------------------------------------------------------------ layout of p_ext
    def parameters(self, p, motor, grid: tuple[int, int, float]) -> np.ndarray:
        """``p_ext`` for parameters ``p`` (params.SIZE), ``motor`` and its RK4 grid
        ``(n_boost, n_coast, coast_grading)``."""
        n_b, n_c, a = grid
        return np.concatenate([np.asarray(p, dtype=float)[:params.SIZE], self.slot.pack(motor),
                               padded_grid(n_b, self.cap_boost), padded_grid(n_c, self.cap_coast, a)])

    def grid_for(self, motor, p_nominal) -> tuple[int, int, float]:
        """The RK4 grid ``motor``'s own model would choose (``_choose_grid`` on the
        nominal parameters), flown here.  Needs ``n_boost`` to fit the slot.

        Kept on disk with the model (:mod:`~ironbark_opt.dynamics.model_cache`), as a
        motor's own model keeps its grid: keyed by this model's key, the motor's slot
        data and ``p_nominal``, so the next ranking with this motor skips the ~30
        stiffness eigenproblems and the probe flights of the choice."""
        key = None
        if self._key is not None:
            data = self.slot.pack(motor).tobytes() + np.asarray(p_nominal, dtype=float).tobytes()
            key = hashlib.sha256(repr(("grid", self._key)).encode() + data).hexdigest()[:24]
            hit = model_cache.load(key)
            if hit is not None:
                return tuple(hit["grid"])
        grid = self._choose_grid_for(motor, p_nominal)
        model_cache.store(key, {"grid": grid})
        return grid

    def _choose_grid_for(self, motor, p_nominal) -> tuple[int, int, float]:
        n0 = initial_boost_steps(motor, p_nominal, self.steps)
        if n0 >= self.cap_boost:
            raise ValueError(f"{n0} boost steps do not fit a grid of {self.cap_boost}")
        saved = self.discretisation()
        try:
            self.n_boost = n0
            self._choose_grid(self.parameters(p_nominal, motor, (n0, 1, 1.0)))
            return self.discretisation()
        finally:
            self.n_boost, self.n_coast, self.coast_grading = saved

    def fits(self, grid) -> bool:
        """True when ``grid`` leaves at least one spare step in both phases (exact end fractions)."""
        return grid[0] < self.cap_boost and grid[1] < self.cap_coast

    # ------------------------------------------------------------ FlightModel hooks
    def _coast_probe(self, x_b, t_b, t_end, p, n: int) -> np.ndarray:
        """The uniform probe of the grid choice on the slot's own (compiled) coast,
        its grid set in ``p``: the same steps, no new Function per candidate."""
        fr = grid_fractions(n)
        starts, lengths = fr[:-1], np.diff(fr)
        q, cap, o = np.array(p, dtype=float), self.cap_coast, self.o_coast
        cols, x = [], x_b
        for j in range(0, n, cap):      # longer probes in pieces: the same t0 + span * f0 and span * df
            st, ln = starts[j:j + cap], lengths[j:j + cap]
            q[o:o + cap] = np.r_[st, np.full(cap - st.size, 1.0)]
            q[o + cap:o + 2 * cap] = np.r_[ln, np.zeros(cap - st.size)]
            cols.append(np.array(self._run["coast"](x, t_b, t_end, q))[:, :st.size])
            x = cols[-1][:, -1]
        return np.hstack(cols)

    #: columns of the mapped outputs Function (see :meth:`_outputs_function`)
    OUTPUT_BLOCK = 64

    def _outputs_function(self, phase: str, n: int):
        """As :meth:`FlightModel._outputs_function`, for one parameter vector: one
        map over :data:`OUTPUT_BLOCK` columns per phase with ``p`` shared by them
        (``reduce_in``; mapped per column, the slot's ~1600 entries were copied to
        every column: 64 us a sample), called on blocks of the samples (the last
        padded with copies of its last column).  A map costs ~0.1 ms a column to
        build, more than evaluating it, and every candidate has its own sample
        counts: one small map serves them all.  Each column is the same call as
        before, so the same numbers.  A parameter matrix (one column a sample)
        takes the per-sample map."""
        per_sample = super()._outputs_function
        out_cache = self.__dict__.setdefault("_out_cache", {})
        if phase not in out_cache:
            lib = self._cached_run(phase, "outputs")   # the library, without building the symbolic Function
            if lib is not None:
                out_cache[phase] = lib
            else:
                per_sample(phase, 1)                   # builds (and compiles) the phase's base Function
        shared = self.__dict__.setdefault("_out_shared", {})
        k = self.OUTPUT_BLOCK
        if phase not in shared:
            shared[phase] = _buffered(self._out_cache[phase].map(f"outputs_{phase}_shared", "serial", k, [2], []))

        def call(X, T, P):
            P = np.asarray(P, dtype=float)
            if P.ndim == 2 and P.shape[1] > 1:
                return per_sample(phase, n)(X, T, P)
            X, T = np.asarray(X, dtype=float), np.asarray(T, dtype=float).reshape(1, -1)
            pad = -n % k
            if pad:
                X = np.hstack([X, np.repeat(X[:, -1:], pad, axis=1)])
                T = np.hstack([T, np.repeat(T[:, -1:], pad, axis=1)])
            P = P.ravel()
            return np.hstack([np.array(shared[phase](X[:, i:i + k], T[:, i:i + k], P))
                              for i in range(0, n + pad, k)])[:, :n]
        return call

    def _mapped(self, key, n):
        """The mapped Functions of :class:`FlightModel` (kept there), called through buffers."""
        cache = self.__dict__.setdefault("_map_buffered", {})
        if (key, n) not in cache:
            cache[(key, n)] = _buffered(super()._mapped(key, n))
        return cache[(key, n)]

    def _set_trajectory(self, phase: str, n: int):
        """The grids live in ``p``: nothing to rebuild (``_choose_grid`` only records ``n``)."""

    def _with_boost_grid(self, p):
        """``p`` with the boost grid of the current ``n_boost`` (:meth:`_finite_boost`)."""
        q = np.array(p, dtype=float)
        q[self.o_boost:self.o_boost + 2 * self.cap_boost] = padded_grid(self.n_boost, self.cap_boost)
        return q

    def _can_refine_boost(self, n: int) -> bool:
        return n < self.cap_boost

    def burn_time(self, p):
        return self.slot.burn_time(p) * p[params.index("burn_time_scale")]

    def _steps_in(self, p, offset: int, cap: int) -> int:
        return int(np.count_nonzero(np.asarray(p, dtype=float)[offset + cap:offset + 2 * cap]))

    def coast_fractions_of(self, p) -> np.ndarray:
        p = np.asarray(p, dtype=float)
        starts = p[self.o_coast:self.o_coast + self.cap_coast]
        n = self._steps_in(p, self.o_coast, self.cap_coast)
        return np.r_[starts[:n], starts[n]]

    def boost_times(self, t_r: float, t_b: float, p) -> np.ndarray:
        """Times of the boost columns (the padded ones at burnout)."""
        p = np.asarray(p, dtype=float)
        starts = p[self.o_boost:self.o_boost + self.cap_boost]
        lengths = p[self.o_boost + self.cap_boost:self.o_boost + 2 * self.cap_boost]
        return t_r + (t_b - t_r) * np.minimum(starts + lengths, 1.0)

    def run(self, p, *, descent: bool = False) -> dict:
        """As :meth:`FlightModel.run`, without the boost grid's padded steps."""
        out = super().run(p, descent=descent)
        n_b = self._steps_in(out["p"], self.o_boost, self.cap_boost)
        if n_b < self.cap_boost:
            first = 1 + self.steps.n_rail + n_b                 # t = 0, rail columns, real boost columns
            keep = np.r_[0:first, first + self.cap_boost - n_b:out["t"].size]
            t_b = float(self.burn_time(out["p"]))
            times = out["t"]
            times[1 + self.steps.n_rail:first] = (out["t_rail"] + (t_b - out["t_rail"])
                                                   * np.arange(1, n_b + 1) / n_b)
            for k in ("t", "x", "phase"):
                out[k] = out[k][..., keep]
        return out
