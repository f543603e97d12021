"""Descent of :class:`~ironbark_opt.dynamics.model.FlightModel`: parachute stages (dual
deploy), fixed-step RK4 chunks for all samples together, the ground and deployment
crossings refined inside their step, and a late ejection charge after apogee.
"""
from __future__ import annotations

import casadi as ca
import numpy as np

from ironbark_opt.dynamics import ejection
from ironbark_opt.dynamics import rhs as rhs_mod
from ironbark_opt.dynamics.integrator import phase_trajectory, rk4_step
from ironbark_opt.errors import InputError, SolverError


class DescentMixin:
    """Descent under parachutes of a :class:`~ironbark_opt.dynamics.model.FlightModel` (mixin)."""

    def descent_stages(self) -> list[tuple[float | None, float, str]]:
        """[(trigger altitude AGL [m] or None for apogee, total Cd*S [m^2], label)].

        Chutes without a deploy altitude open at apogee; the others add their
        Cd*S when the rocket descends through their altitude (dual deploy).
        Inflation lag is neglected.  No chute: one ballistic stage (the coast
        equations continue, 6-DOF); no chute at apogee (a single main at an
        altitude): ballistic down to the first deploy altitude.
        """
        chutes = self.setup.parachutes
        if not chutes:
            return [(None, 0.0, "ballistic")]
        stages, cd = [], sum(c.cd_area for c in chutes if c.deploy_altitude is None)
        stages.append((None, cd, "descent") if cd > 0 else (None, 0.0, "ballistic"))
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
