"""Batch evaluation of :class:`~ironbark_opt.dynamics.model.FlightModel` (``run_batch``,
the Monte Carlo path): the mapped Functions and their caches, the fused ascent mapped
over the samples, and the phase-by-phase batch of the motor-slot model with the
rail-exit secant and the apogee refinement vectorised.
"""
from __future__ import annotations

import os

import casadi as ca
import numpy as np

from ironbark_opt.dynamics import ejection
from ironbark_opt.dynamics.constants import G0, RAIL_TOL_M
from ironbark_opt.errors import InputError, SolverError


def map_threads(n: int) -> int:
    """Threads of a batch of ``n`` samples mapped by CasADi (``Function.map(n, "thread", k)``):
    twice the processors this process may run on, with at least 8 samples a thread
    (and 2 threads, as before, for fewer than 16 samples).

    CasADi's thread map gives each thread an equal share of the samples, so the batch
    ends with its slowest thread: with one thread a core, a core that another job holds
    (a shared or busy machine) leaves the batch waiting for its share while the other
    core idles.  Twice as many threads as cores lets the scheduler move the remaining
    shares to the free core.  Each sample is its own evaluation, so the results do not
    depend on the count.  Measured on the 2-core development machine under load (250
    compiled Calisto samples in one process, 10 rounds): median wall 0.29 s with 2
    threads, 0.21 s with 4, 0.20 s with 8; the same CPU time (0.08 s)."""
    try:
        cores = len(os.sched_getaffinity(0))
    except (AttributeError, OSError):
        cores = os.cpu_count() or 1
    return max(min(2, int(n)), min(2 * cores, int(n) // 8))


class BatchMixin:
    """Batch evaluation of a :class:`~ironbark_opt.dynamics.model.FlightModel` (mixin)."""

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
                cache[(key, n)] = self._batch_function(key.split(":")[0]).map(n, "thread", map_threads(n))
                return cache[(key, n)]
            base = {"launch": self._launch, "apogee": self._apogee_run, "vz": self.vz_l,
                    "step": self.step["coast"]}.get(key) or self._run[key]
            cache[(key, n)] = base.map(n, "thread", map_threads(n)) if key in self._run else base.map(n)
        return cache[(key, n)]

    def _run_batch_fused(self, P: np.ndarray, descent: bool) -> dict:
        """:meth:`run_batch` by ``ascent_batch`` mapped over the samples (threads): the
        very Function of :meth:`run`, so a sample and its single run agree to the bit;
        the samples it does not apply to fly one by one through :meth:`run`."""
        from ironbark_opt.dynamics.ascent import EV, applies
        n = P.shape[1]
        if np.any(self.rail_exit_distance(P) <= 0):
            raise InputError("rail length shorter than the nozzle-to-guide distance in some samples",
                             field="rail_length")
        cache = self.__dict__.setdefault("_map_cache", {})
        if ("ascent_batch", n) not in cache:
            base = self._lib.get("ascent_batch")
            if base is None:
                base = self._ascent_vm()[1] if self._one_library else self._compiled(self._ascent_vm()[1])
            cache[("ascent_batch", n)] = base.map(n, "thread", map_threads(n))
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
        exit_distance = self.rail_exit_distance(P)
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
            if np.all(np.abs(g_a) < RAIL_TOL_M):
                break
            g_b = travel(t_b)[0][:, -1]
            done = (np.abs(g_b) < RAIL_TOL_M) | (g_b == g_a)
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
