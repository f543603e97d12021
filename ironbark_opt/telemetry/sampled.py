"""The flight model sampled at a log's times, with its exact Jacobian.

:class:`SampledModel` builds one CasADi Function of the fitted parameters
``q`` (a subset of the named vector ``p``, :mod:`ironbark_opt.params`):
the phased trajectory of :mod:`ironbark_opt.dynamics.model` (rail exit by
its ``rootfinder``, boost to burnout, coast to a fixed end time) returns
the node times and, at every RK4 node, the three loggable channels

- ``altitude`` ``z`` [m above the rail foot],
- ``vertical_speed`` ``v_z`` in the launch frame [m/s],
- ``acceleration`` as an axial accelerometer with its pad reading
  subtracted logs it (AltOS convention): ``(F_thrust + F_axial) / m - g_pad``
  [m/s^2] (the specific force along the body axis minus local gravity),

together with their Jacobians by CasADi AD (forward mode: few parameters).
The same equations :func:`ironbark_opt.flight.simulate` flies; nothing is
copied.  Samples at arbitrary times are linear interpolants between nodes
(RK4 nodes are <= 0.02 s apart in boost, where the error of the interpolant
``a dt^2 / 8`` is < 1 cm), differentiated exactly, node times included
(they move with the rail-exit time).  Numeric-only results.
"""
from __future__ import annotations

import casadi as ca
import numpy as np

from ironbark_opt import params
from ironbark_opt.atmosphere.gravity import gravity
from ironbark_opt.dynamics.rhs import OUTPUT_NAMES
from ironbark_opt.errors import InputError
from ironbark_opt.telemetry.flightlog import CHANNELS

_I = {n: OUTPUT_NAMES.index(n) for n in ("thrust_N", "axial_force_N", "mass_kg", "airspeed_mps")}
#: Node rows: the loggable channels, then ``baro_head`` = V_air^2 / (2 g) [m], the
#: altitude error per unit static-port pressure coefficient (see :mod:`calibrate`).
ROWS = CHANNELS + ("baro_head",)


class SampledModel:
    """Channels of the simulated flight at given times and their derivatives.

    Parameters
    ----------
    model : FlightModel
    names : sequence of str
        Parameters to differentiate with respect to (registry names).
    t_end : float [s]
        Last time needed (after burnout; the coast is integrated to it with
        the model's coast grid).
    p_nominal : array (params.SIZE)
        Start point (rail-exit root guess and the fixed parameters).
    """

    def __init__(self, model, names, t_end: float, p_nominal):
        self.model = model
        self.names = tuple(names)
        for n in self.names:
            params.index(n)
        p_nominal = np.asarray(p_nominal, dtype=float)
        setup = model.setup
        t_b0 = float(setup.motor.burn_time) * p_nominal[params.index("burn_time_scale")]
        self.t_end = max(float(t_end), t_b0 + 0.5)
        t_rail0 = model.rail_exit(p_nominal)
        nq = len(self.names)
        q = ca.MX.sym("q", nq)
        p0 = ca.MX.sym("p0", params.SIZE)
        E = np.zeros((params.SIZE, nq))
        for j, n in enumerate(self.names):
            E[params.index(n), j] = 1.0
        p = p0 + ca.DM(E) @ q
        P = params.unpack(p)
        t_r = model.rail_exit_root(t_rail0, p)
        x0 = model.initial_state(p)
        X_r = model.trajectory["rail"](x0, 0, t_r, p)
        t_b = float(setup.motor.burn_time) * P["burn_time_scale"]
        X_b = model.trajectory["boost"](X_r[:, -1], t_r, t_b, p)
        X_c = model.trajectory["coast"](X_b[:, -1], t_b, self.t_end, p)
        n_r, n_b, n_c = model.steps.n_rail, model.n_boost, model.n_coast
        fr = model.coast_fractions
        tn = ca.vertcat(0, t_r * np.arange(1, n_r + 1) / n_r, t_r + (t_b - t_r) * np.arange(1, n_b + 1) / n_b,
                        t_b + (self.t_end - t_b) * fr[1:])
        g_pad = float(gravity(setup.site_elevation, setup.latitude)) if setup.gravity is None \
            else float(setup.gravity(setup.site_elevation))
        blocks = []
        for ph, X, t0, nn in (("rail", ca.horzcat(x0, X_r), 0, n_r + 1), ("boost", X_b, n_r + 1, n_b),
                              ("coast", X_c, n_r + 1 + n_b, n_c)):
            tt = tn[t0:t0 + nn].T
            y = model.rhs[ph].map(nn)(X, tt, ca.repmat(p, 1, nn))[1]
            f_ax = (y[_I["thrust_N"], :] + y[_I["axial_force_N"], :]) / y[_I["mass_kg"], :] - g_pad
            vz = model.vz_l.map(nn)(X)
            head = y[_I["airspeed_mps"], :] ** 2 / (2 * g_pad)
            blocks.append(ca.vertcat(X[2, :], vz, f_ax, head))
        Y = ca.horzcat(*blocks)                              # 4 x N
        out = [tn, Y.T]
        jac = [ca.jacobian(tn, q), ca.jacobian(ca.vec(Y.T), q)]
        self._f = ca.Function("sampled", [q, p0], out + jac, ["q", "p0"], ["t", "Y", "dt_dq", "dY_dq"])
        self.p_fixed = p_nominal.copy()
        for n in self.names:
            self.p_fixed[params.index(n)] = 0.0
        self.n_nodes = int(tn.shape[0])

    def p_of(self, q) -> np.ndarray:
        """Full parameter vector for fitted values ``q`` [mixed SI]."""
        p = self.p_fixed.copy()
        for j, n in enumerate(self.names):
            p[params.index(n)] += float(q[j])
        return p

    def nodes(self, q):
        """(node times (N,), rows (N, 4), dt/dq (N, nq), dY/dq (N, 4, nq)); rows as ``ROWS``."""
        t, Y, dt, dY = (np.array(v) for v in self._f(np.asarray(q, dtype=float), self.p_fixed))
        n, nq = t.size, len(self.names)
        return t.ravel(), Y, dt.reshape(n, nq), dY.reshape(len(ROWS), n, nq).transpose(1, 0, 2)

    def at(self, q, times, channels=CHANNELS, *, derivatives: bool = True, nodes=None):
        """Rows (``ROWS``) at ``times`` [s after ignition]: dict row -> (values (m,), d/dq (m, nq), d/dt (m,)).

        Times outside ``[0, t_end]`` are an InputError (the caller trims the log).
        ``nodes``: the result of :meth:`nodes` at ``q``, to re-sample without re-flying.
        """
        t, Y, dt, dY = nodes if nodes is not None else self.nodes(q)
        times = np.asarray(times, dtype=float)
        if times.size and (times.min() < 0 or times.max() > t[-1]):
            raise InputError(f"sample times {times.min():.2f}..{times.max():.2f} s outside the simulated "
                             f"0..{t[-1]:.2f} s", field="times")
        k = np.clip(np.searchsorted(t, times, side="right") - 1, 0, t.size - 2)
        h = t[k + 1] - t[k]
        w = (times - t[k]) / h
        dw = (-dt[k] * h[:, None] - (times - t[k])[:, None] * (dt[k + 1] - dt[k])) / (h ** 2)[:, None]
        out = {}
        for c in channels:
            i = ROWS.index(c)
            y0, y1 = Y[k, i], Y[k + 1, i]
            val = (1 - w) * y0 + w * y1
            if derivatives:
                jq = (1 - w)[:, None] * dY[k, i] + w[:, None] * dY[k + 1, i] + (y1 - y0)[:, None] * dw
                out[c] = (val, jq, (y1 - y0) / h)
            else:
                out[c] = (val, None, None)
        return out
