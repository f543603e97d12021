"""Apogees of fixed samples as a function of the ballast, with exact gradients.

Every sample flies the model's own ascent Function
(:func:`~ironbark_opt.dynamics.ascent.ascent_functions`, the one of
``FlightModel.run`` and ``run_batch``), so the apogees are bit for bit those a
Monte Carlo of the same samples reports.  Their derivatives in the ballast
``w = (m_b[, x_b])`` are the forward-mode directional derivatives of that
same graph, one direction per variable, computed with the values in one call
of one compiled Function mapped over the samples: the rail exit (a converged
secant iteration: its derivative is the implicit-function one to the
iteration's tolerance, Griewank & Walther, *Evaluating Derivatives*, 2nd ed.,
SIAM 2008, sec. 15.1 on derivatives of fixed-point iterations), the boost, the
coast on its grid (which stretches with the burnout speed) and the apogee
inside its step (Newton on the step length).  One evaluation per ballast;
no root tracking between evaluations.

The rail-exit speed and static margin at rail exit come out of the same
call with their derivatives (the limits of the nominal parameters' flight).

Samples the ascent Function does not apply to (the rail left after 0.5 s, no
apogee in its horizon) or whose ejection charge fires before apogee fly the
phase formulation of :mod:`~ironbark_opt.optimise.robust_events` instead.

Numeric-only.
"""
from __future__ import annotations

import casadi as ca
import numpy as np

from ironbark_opt import params
from ironbark_opt.dynamics import ejection
from ironbark_opt.dynamics.model_cache import library_key
from ironbark_opt.errors import InputError

#: rows of the ``out`` output of :func:`ascent_derivative_function`
OUTPUTS = ("apogee_agl", "rail_exit_speed", "static_margin_rail_exit")


def ballast_parameters(p, w, free_position: bool):
    """``p`` with the ballast entries replaced by ``w = (m_b[, x_b])`` (MX)."""
    i_m, i_x = params.index("ballast_mass"), params.index("ballast_x")
    return ca.vertcat(p[:i_m], w[0], w[1] if free_position else p[i_x], p[i_x + 1:])


def ascent_derivative_function(model, free_position: bool) -> ca.Function:
    """``(w, p) -> (ev, out, J)``: the ascent of ``p`` with its ballast set to ``w``
    (``ev``: the rows :data:`~ironbark_opt.dynamics.ascent.EV`), ``out`` the rows
    :data:`OUTPUTS` [m AGL, m/s, cal] and ``J = d out / d w`` by forward mode
    through the model's ascent Function.  Symbolic construction, numeric use."""
    from ironbark_opt.optimise.ballast import _SM

    if hasattr(type(model), "final_state_symbolic") or not model._FUSED:
        raise InputError("robust ballast flies single-stage rockets with one tabulated motor only",
                         field="--robust")
    k = 2 if free_position else 1
    w, p = ca.MX.sym("w", k), ca.MX.sym("p", model.n_p)
    pw = ballast_parameters(p, w, free_position)
    ev, x_r, x_a = model._ascent_vm()[1](pw)
    out = ca.vertcat(x_a[2], ca.norm_2(x_r[3:6]), model.rhs["boost"](x_r, ev[0], pw)[1][_SM])
    return ca.Function(f"robust_ascent_{k}", [w, p], [ev, out, ca.jtimes(out, w, ca.DM.eye(k))],
                       ["w", "p"], ["ev", "out", "J"])


def compiled_derivative_function(model, free_position: bool) -> ca.Function:
    """:func:`ascent_derivative_function` as ``model.jit`` asks, cached on the model: the
    compiled library when the disk cache has it; else ``jit=True`` compiles it now and
    ``"auto"`` runs the VM (a solve takes a few evaluations) and compiles it in a detached
    background process for the next solve."""
    from ironbark_opt.dynamics.integrator import cached_library, compile_detached, compile_function

    cache = model.__dict__.setdefault("_robust_cache", {})
    slot = ("ascent", free_position, model.discretisation())
    if slot not in cache:
        k = 2 if free_position else 1
        key = library_key(model, f"robust_ascent_{k}")
        func = cached_library(f"robust_ascent_{k}", key) if model.jit and key is not None else None
        if func is None:
            func = ascent_derivative_function(model, free_position)
            # compiled from the ascent the model's library holds (its Mach tables in C form),
            # so compiled apogees are the compiled Monte Carlo's to the bit
            source = model._library_twin() if model.jit and getattr(model, "_one_library", False) else model
            if model.jit == "auto" and key is not None:
                compile_detached(ascent_derivative_function(source, free_position), key)
            elif model.jit:
                func = compile_function(ascent_derivative_function(source, free_position), key=key)
        cache[slot] = func
    return cache[slot]


class SampleApogees:
    """Apogees of fixed samples as a function of the ballast, with exact gradients.

    Parameters
    ----------
    model : FlightModel
    P : array (params.SIZE x N)
        The samples (their ballast rows are replaced by ``w``).
    free_position : bool
    """

    def __init__(self, model, P, free_position: bool):
        self.model = model
        self.P = np.asarray(P, dtype=float)
        self.n = self.P.shape[1]
        self.k = 2 if free_position else 1
        self.free_position = free_position
        self.func = compiled_derivative_function(model, free_position).map(self.n, "thread", 2)
        self.evaluations = 0
        # ejection times [s] of the samples (burnout + delay: independent of the ballast)
        self._t_ejection = ejection.ejection_time(model.setup, self.P)
        self._seen: dict = {}
        self._fallback: dict = {}

    def __call__(self, w) -> tuple[np.ndarray, np.ndarray]:
        """(apogee [m AGL] (N,), d apogee / d w (k, N)) at ballast ``w``."""
        return self.events(w)[:2]

    def rail(self, w) -> tuple[np.ndarray, np.ndarray]:
        """(rail-exit speed [m/s] and static margin at rail exit [cal] (2, N), their
        derivatives in ``w`` (2, k, N)) at ballast ``w``."""
        return self.events(w)[2:]

    def events(self, w):
        """(apogee, d apogee/dw, rail outputs, d rail outputs/dw) at ``w``: one call of the
        mapped ascent and its forward derivative."""
        from ironbark_opt.dynamics.ascent import EV, applies

        w = np.asarray(w, dtype=float).ravel()
        if w.tobytes() in self._seen:
            return self._seen[w.tobytes()]
        ev, out, J = (np.array(v) for v in self.func(w, self.P))
        self.evaluations += 1
        J = J.reshape(len(OUTPUTS), self.n, self.k).transpose(0, 2, 1)          # 3 x k x N
        t_e = self._t_ejection
        t_apo = dict(zip(EV, ev))["t_k"] + dict(zip(EV, ev))["h"]
        redo = ~applies(ev) | ((t_e < t_apo) if t_e is not None else False)
        if np.any(redo):                   # the phase formulation for those samples
            cols = np.nonzero(redo)[0]
            if tuple(cols) not in self._fallback:
                from ironbark_opt.optimise.robust_events import EventApogees
                self._fallback[tuple(cols)] = EventApogees(self.model, self.P[:, cols], self.free_position)
            z, dz, rail, drail = self._fallback[tuple(cols)].events(w)
            out[:, cols] = np.vstack([z, rail])
            J[:, :, cols] = np.concatenate([dz[None], drail])
        result = (out[0], J[0], out[1:], J[1:])
        self._seen[w.tobytes()] = result
        return result
