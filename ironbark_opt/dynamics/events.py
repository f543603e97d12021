"""Events and outputs of :class:`~ironbark_opt.dynamics.model.FlightModel`: the launch
state, the rail-exit residual and its rootfinder, the apogee event (Newton on the
step length inside a coast step) and the derived output rows of each phase.
"""
from __future__ import annotations

import casadi as ca
import numpy as np

from ironbark_opt import params
from ironbark_opt.dynamics import rhs as rhs_mod
from ironbark_opt.dynamics.constants import RAIL_TOL_M
from ironbark_opt.dynamics.frames import launch_quaternion, rail_direction_l, rotation_matrix


class EventsMixin:
    """Events and output rows of a :class:`~ironbark_opt.dynamics.model.FlightModel` (mixin)."""

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
        return travel - self.rail_exit_distance(p)

    def rail_exit_distance(self, p):
        """Distance [m] travelled along the rail when the rocket leaves it: the rail
        length minus the nozzle-to-guide offset (``p`` a vector, a matrix of sample
        columns, or MX)."""
        return p[params.index("rail_length")] - self.setup.rail_exit_offset

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
                "rail_exit", "newton", g, {"abstol": RAIL_TOL_M, "max_iter": 50, "error_on_fail": True})
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
