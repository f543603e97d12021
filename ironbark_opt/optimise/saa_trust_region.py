"""Minimise a sample-average objective of per-sample quantities with exact gradients.

The objective is ``F(w) = mean_i phi(a_i(w))`` over fixed samples, ``phi``
known in closed form (the smoothed terms of
:mod:`~ironbark_opt.optimise.robust_objective`), ``a_i(w)`` expensive (a
flight per sample) but smooth and nearly linear in the one or two variables
``w``, with exact values and gradients from one evaluation.  Rather than
letting IPOPT call the flights at every iterate and line-search trial, each
flight enters through a local model built from its exact value and gradient
at the current point and a curvature learnt from the gradients along the
steps (symmetric rank-one update, Conn, Gould & Toint, Math. Prog. 50, 1991;
for one variable the secant of the derivative):

    a_i(w_c + s) ~ a_i + g_i . s + s' H_i s / 2,

and IPOPT solves the smooth model problem (exact Hessian, no flights) inside
a trust region (Conn, Gould & Toint, *Trust-Region Methods*, SIAM 2000,
alg. 6.1.1 with the ratio test on the exact objective).  Limits ``q_j(w) >=
b_j`` (the nominal flight's rail-exit speed and margin) are modelled the
same way.  At a model step shorter than ``xtol`` the model's first-order
conditions hold at a point where the model has the exact values and
gradients: those of the true SAA problem.  On the example rockets 2 to 4
evaluations of the flights (a step tolerance of 1e-4 kg).  Each model problem
is an ordinary smooth NLP of the variables alone: IPOPT with the exact Hessian.

Numeric-only.
"""
from __future__ import annotations

from dataclasses import dataclass

import casadi as ca
import numpy as np

from ironbark_opt.errors import SolverError


@dataclass
class Evaluation:
    """The exact quantities at one point: per-sample values ``a`` (N,), gradients ``g`` (k, N),
    limit quantities ``q`` (m,) and their gradients ``dq`` (m, k)."""
    w: np.ndarray
    a: np.ndarray
    g: np.ndarray
    q: np.ndarray
    dq: np.ndarray
    f: float


def _sr1(H, s, y):
    """Symmetric rank-one update of the k x k matrices ``H`` (n, k, k) along ``s`` (k,) with
    gradient changes ``y`` (n, k); skipped where the denominator is negligible."""
    r = y - H @ s
    den = r @ s
    ok = np.abs(den) > 1e-8 * np.linalg.norm(s) * np.maximum(np.linalg.norm(r, axis=1), 1e-300)
    H = H.copy()
    H[ok] += np.einsum("ni,nj->nij", r[ok], r[ok]) / den[ok, None, None]
    return H


class _ModelProblem:
    """IPOPT on ``mean(terms(model apogees))`` with modelled limits, built once per shape."""

    def __init__(self, terms, n: int, k: int, m: int, ipopt_options=None):
        s = ca.SX.sym("s", k)
        a, g, H = ca.SX.sym("a", n), ca.SX.sym("g", k, n), ca.SX.sym("H", k * k, n)
        q, dq, Hq = ca.SX.sym("q", m), ca.SX.sym("dq", m, k), ca.SX.sym("Hq", k * k, m)

        def model(val, grad, hess, count):
            quad = ca.vertcat(*[ca.dot(s, ca.reshape(hess[:, i], k, k) @ s) for i in range(count)])
            return val + (grad.T @ s if count else ca.SX(0, 1)) + 0.5 * quad
        am = model(a, g, H, n)
        qm = q + dq @ s + 0.5 * ca.vertcat(*[ca.dot(s, ca.reshape(Hq[:, j], k, k) @ s) for j in range(m)]) \
            if m else ca.SX(0, 1)
        par = ca.vertcat(a, ca.vec(g), ca.vec(H), q, ca.vec(dq), ca.vec(Hq))
        self.objective = ca.Function("saa_model", [s, par], [ca.sum1(terms(am)) / n])
        opts = {"ipopt.print_level": 0, "print_time": False, "ipopt.sb": "yes", "ipopt.tol": 1e-12,
                "ipopt.max_iter": 200}
        opts.update({(key if key.startswith("ipopt.") else f"ipopt.{key}"): v
                     for key, v in dict(ipopt_options or {}).items()})
        self.solver = ca.nlpsol("robust_ballast", "ipopt", {"x": s, "p": par, "f": self.objective(s, par),
                                                             "g": qm}, opts)
        self.iterations = 0

    @staticmethod
    def parameters(e: Evaluation, H, Hq):
        # column-major, as ca.vec stacks the SX parameters (H_i symmetric: either order)
        return np.concatenate([e.a, e.g.ravel(order="F"), H.ravel(), e.q, e.dq.ravel(order="F"), Hq.ravel()])

    def solve(self, e: Evaluation, H, Hq, lower, upper, limits):
        par = self.parameters(e, H, Hq)
        sol = self.solver(x0=np.zeros(e.w.size), p=par, lbx=lower - e.w, ubx=upper - e.w,
                          lbg=limits, ubg=np.full(len(limits), np.inf))
        stats = self.solver.stats()
        self.iterations += int(stats.get("iter_count", 0))
        if not stats["success"] and stats["return_status"] not in ("Solved_To_Acceptable_Level",):
            raise SolverError(f"robust ballast: IPOPT did not solve the model problem ({stats['return_status']})")
        return np.array(sol["x"]).ravel(), float(sol["f"])


def minimise(evaluate, terms, w0, lower, upper, limits=(), *, xtol: float = 1e-6,
             max_evaluations: int = 30, ipopt_options=None):
    """Trust-region minimisation of ``mean(terms(a(w)))`` subject to ``q(w) >= limits``.

    Parameters
    ----------
    evaluate : callable ``w -> (a (N,), g (k, N), q (m,), dq (m, k))``
        The exact per-sample values and gradients (and the limit quantities).
    terms : callable
        Per-sample terms of the objective, symbolic-safe (NumPy array or CasADi SX).
    w0, lower, upper : arrays (k,)
        Start (feasible) and bounds.
    limits : sequence (m,)
        Lower limits of ``q``.
    xtol : float
        A model step shorter than this (in every variable) ends the search.

    Returns
    -------
    (w, evaluations: list of :class:`Evaluation` in the order made, IPOPT iterations)
    """
    lower, upper = np.asarray(lower, float), np.asarray(upper, float)
    limits = np.asarray(limits, dtype=float)

    def exact(w):
        a, g, q, dq = evaluate(w)
        return Evaluation(np.asarray(w, float), a, g, q, dq, float(np.mean(terms(a))))
    cur = exact(np.asarray(w0, dtype=float))
    done = [cur]
    n, k, m = cur.a.size, cur.w.size, limits.size
    H, Hq = np.zeros((n, k, k)), np.zeros((m, k, k))
    problem = _ModelProblem(terms, n, k, m, ipopt_options)
    radius = upper - lower
    while len(done) < max_evaluations:
        box_lo, box_hi = np.maximum(lower, cur.w - radius), np.minimum(upper, cur.w + radius)
        s, f_model = problem.solve(cur, H, Hq, box_lo, box_hi, limits)
        if np.all(np.abs(s) <= xtol):
            break
        trial = exact(np.clip(cur.w + s, lower, upper))
        done.append(trial)
        step = trial.w - cur.w
        H = _sr1(H, step, (trial.g - cur.g).T)
        if m:
            Hq = _sr1(Hq, step, trial.dq - cur.dq)
        predicted, actual = cur.f - f_model, cur.f - trial.f
        feasible = np.all(trial.q >= limits - 1e-6 * np.maximum(1.0, np.abs(limits)))
        if feasible and actual > 0 and actual >= 0.1 * predicted:
            if actual >= 0.75 * predicted and np.any(np.abs(step) >= 0.9 * radius):
                radius = 2.0 * radius
            cur = trial
        else:
            radius = np.minimum(radius, 0.5 * np.abs(step).max())
    else:
        raise SolverError(f"robust ballast: no convergence in {max_evaluations} evaluations of the samples")
    return cur, done, problem.iterations
