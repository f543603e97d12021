"""Sample apogees in the phase formulation: events as roots, gradients by the
implicit-function theorem (the fallback of :mod:`~ironbark_opt.optimise.sample_apogees`
for samples the model's ascent Function does not fly).

Every sample flies the model's own phase trajectories (``_final_state`` with
the rail-exit time ``t_r`` and the final time ``T`` as inputs, as the nominal
ballast NLP flies them); one mapped CasADi Function returns the rail residual
``g``, the altitude ``z(T)`` and the vertical velocity ``v_z(T)`` with their
Jacobian in ``(w, t_r, T)``.  The events are the roots ``g = 0``, ``v_z = 0``
(the equations the ballast NLP and ``apogee_functions`` impose) and the
implicit-function theorem gives

    dt_r/dw = -g_w / g_tr,   dT/dw = -(vz_w + vz_tr dt_r/dw) / vz_T,
    da/dw   = z_w + z_tr dt_r/dw + z_T dT/dw.

The roots start from ``FlightModel.run``'s events and are tracked between
ballasts (first-order predictor, Newton corrector on all samples at once).

Numeric-only.
"""
from __future__ import annotations

import casadi as ca
import numpy as np

from ironbark_opt import params
from ironbark_opt.dynamics.model_cache import library_key
from ironbark_opt.errors import SolverError
from ironbark_opt.optimise.sample_apogees import ballast_parameters


def event_function(model, free_position: bool) -> ca.Function:
    """``(w, t_r, T, p) -> (r, J)``: ``r = (g_rail [m], z(T) [m AGL], v_z(T) [m/s],
    |v| at rail exit [m/s], static margin at rail exit [cal])`` of one sample with
    ballast ``w = (m_b[, x_b])`` replacing the entries of ``p``, and
    ``J = dr/d(w, t_r, T)``.  Symbolic construction, numeric use."""
    from ironbark_opt.dynamics.model import _final_state
    from ironbark_opt.optimise.ballast import _SM

    k = 2 if free_position else 1
    w, t_r, T = ca.MX.sym("w", k), ca.MX.sym("t_r"), ca.MX.sym("T")
    p = ca.MX.sym("p", params.SIZE)
    pw = ballast_parameters(p, w, free_position)
    x_T, _, x_r, _ = _final_state(model, pw, T, 0.0, t_rail=t_r)
    r = ca.vertcat(model.rail_residual(t_r, pw), x_T[2], model.vz_l(x_T), ca.norm_2(x_r[3:6]),
                   model.rhs["boost"](x_r, t_r, pw)[1][_SM])
    return ca.Function("robust_events", [w, t_r, T, p], [r, ca.jacobian(r, ca.vertcat(w, t_r, T))],
                       ["w", "t_r", "T", "p"], ["r", "J"])


def _compiled_events(model, free_position: bool) -> ca.Function:
    """:func:`event_function`, C-compiled (cached on disk) when the model compiles."""
    cache = model.__dict__.setdefault("_robust_cache", {})
    if free_position not in cache:
        func = event_function(model, free_position)
        if model.jit:
            from ironbark_opt.dynamics.integrator import compile_function
            func = compile_function(func, key=library_key(model, free_position, "robust_events_rail"))
        cache[free_position] = func
    return cache[free_position]


class EventApogees:
    """The interface of :class:`~ironbark_opt.optimise.sample_apogees.SampleApogees` in the
    phase formulation (a few samples: the fallback)."""

    def __init__(self, model, P, free_position: bool):
        self.model = model
        self.P = np.asarray(P, dtype=float)
        self.n = self.P.shape[1]
        self.k = 2 if free_position else 1
        self.func = _compiled_events(model, free_position).map(self.n)
        self.w = None
        self.roots = None                       # (2, N): t_r, T at self.w
        self.droots = None                      # (2, k, N): d(t_r, T)/dw at self.w

    def _start(self, w):
        """The events of ``run`` at ballast ``w``: the first roots."""
        P = self.P.copy()
        P[params.index("ballast_mass")] = w[0]
        if self.k == 2:
            P[params.index("ballast_x")] = w[1]
        runs = [self.model.run(P[:, j]) for j in range(self.n)]
        return np.array([[r["t_rail"] for r in runs], [r["t_apogee"] for r in runs]])

    def events(self, w):
        """(apogee, d apogee/dw, rail outputs, d rail outputs/dw) at ``w``: the events solved
        by Newton's method, derivatives by the implicit-function theorem."""
        w = np.asarray(w, dtype=float).ravel()
        k = self.k
        if self.roots is None:
            roots = self._start(w)
        else:
            roots = self.roots + np.einsum("akn,k->an", self.droots, w - self.w)   # first-order predictor
        for _ in range(8):
            r, J = self.func(w, roots[0][None, :], roots[1][None, :], self.P)
            r = np.array(r)                                # 5 x N
            J = np.array(J).reshape(5, self.n, k + 2).transpose(0, 2, 1)   # 5 x (k+2) x N
            g_tr, vz_tr, vz_T = J[0, k], J[2, k], J[2, k + 1]
            d_tr = -r[0] / g_tr                           # Newton on the block-triangular system
            d_T = -(r[2] + vz_tr * d_tr) / vz_T
            roots = roots + np.vstack([d_tr, d_T])
            if np.all(np.abs(d_tr) < 1e-5) and np.all(np.abs(d_T) < 1e-3):
                break
        else:
            raise SolverError("robust ballast: the events of some samples did not converge")
        # Outputs at the corrected roots to first order in the last Newton step (<= 1e-5 s on the
        # rail, 1e-3 s at apogee where v_z = 0: the neglected second-order terms are < 1e-5 m).
        z = r[1] + J[1, k] * d_tr + J[1, k + 1] * d_T
        dtr_dw = -J[0, :k] / g_tr                         # implicit-function theorem
        dT_dw = -(J[2, :k] + vz_tr * dtr_dw) / vz_T
        dz_dw = J[1, :k] + J[1, k] * dtr_dw + J[1, k + 1] * dT_dw
        rail = r[3:5] + J[3:5, k] * d_tr                  # rail exit: no dependence on T
        drail_dw = J[3:5, :k] + J[3:5, k][:, None, :] * dtr_dw[None]
        self.w, self.roots, self.droots = w, roots, np.stack([dtr_dw, dT_dw])
        return z, dz_dw, rail, drail_dw
