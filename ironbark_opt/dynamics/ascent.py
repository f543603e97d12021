"""The whole ascent in one CasADi Function: rail exit, boost, coast, apogee.

:meth:`FlightModel.run <ironbark_opt.dynamics.model.FlightModel.run>` used to
drive the phases from Python (18 Function calls with NumPy conversions, the
rail phase integrated once per secant iterate).  :func:`ascent_functions`
builds the same sequence as one Function of ``p`` (compiled with the model's
other libraries), so a run is one call plus NumPy bookkeeping:

- **rail exit**: a bracketing pass of the rail phase over ``[0, min(0.5 s, burnout)]``
  on a coarse grid (``n_rail // 2`` steps: it only brackets and guesses) finds the
  exit between two samples; the cubic Hermite interpolant of the travel and the
  along-rail speed there gives the first iterate, a Newton step with the speed the
  second, then secant steps whose slope is the chord corrected by half the change of
  the along-rail speed between the two iterates (exact for a travel quadratic in
  time, so the rocket's acceleration costs no iteration).  The residual and
  tolerance are ``FlightModel._rail_exit``'s (the rail phase on ``n_rail`` equal
  steps over ``[0, t_r]``, ``|s - L| < 1e-10 m``): only the iterates differ, so the
  root differs within that tolerance.  Calisto's 1000 Monte Carlo samples: ~3.9
  full rail passes per flight (+ the half-cost bracket) instead of ~4.8 (+ a full
  one).  Each further iteration is a conditional call (``Function.if_else``, a
  CasADi switch): once the residual is below the tolerance the remaining ones
  cost nothing, so the rail phase is flown only as often as needed;
- **boost** on the model's own boost trajectory (its grid, its air-start segments);
- **coast** on the model's coast grid over the horizon ``t_b + v_z,b / g0 + 2 s``,
  in chunks of :data:`COAST_CHUNK` steps; a chunk starting at ``v_z <= 0`` is
  skipped (its columns repeat the last state), so the steps past apogee
  that the former fixed horizon flew are mostly not flown;
- **apogee**: the first coast step ending at ``v_z <= 0`` is picked by a one-hot
  weight and refined by the model's own apogee event (Newton on the step
  length, :meth:`FlightModel._apogee_function`).

Every step is the same expression on the same step boundaries as the phased
path, so the results agree with it to rounding (the rail-exit time differs
within the root tolerance: ~1e-12 relative).  Flags in the output let
``run`` fall back to the phased path where this one does not apply (the rail
not left within 0.5 s, the iteration not converged, no apogee within the
horizon).
"""
from __future__ import annotations

import casadi as ca
import numpy as np

from ironbark_opt.dynamics.buffered import Buffered
from ironbark_opt.dynamics.constants import G0, RAIL_TOL_M
from ironbark_opt.dynamics.frames import rotation_matrix
from ironbark_opt.dynamics.integrator import carried_trajectory, grid_fractions, phase_trajectory

#: rail passes after the bracketing one (conditional: only the needed ones run)
RAIL_ITERATIONS = 8
#: coast steps per conditionally evaluated chunk
COAST_CHUNK = 10
#: rows of the ``ev`` output
EV = ("t_rail", "g_rail", "g_bracket", "t_burnout", "vz_burnout", "t_end", "k", "found", "t_k", "h", "rail_passes")


def _along_rail(e, x):
    """Speed [m/s] along the rail direction ``e`` (launch frame) of the state ``x``."""
    return ca.dot(e, rotation_matrix(x[6:10]) @ x[3:6])


def _rail_pass(model) -> ca.Function:
    """``(t, x0, e, d, p) -> (g, v, X)``: the rail phase over [0, t]; residual
    ``g = e . r - d`` [m] and the along-rail speed ``v`` [m/s] at its end."""
    t, d = ca.MX.sym("t"), ca.MX.sym("d")
    x0, e, p = ca.MX.sym("x0", 13), ca.MX.sym("e", 3), ca.MX.sym("p", model.n_p)
    X = model.trajectory["rail"](x0, 0, t, p)
    x = X[:, -1]
    g = ca.dot(e, x[0:3]) - d
    v = _along_rail(e, x)
    return ca.Function("rail_pass", [t, x0, e, d, p], [g, v, X])


def _secant_iteration(rail: ca.Function, nr: int) -> ca.Function:
    """One secant step as a switch: ``(go, t_a, g_a, v_a, X_a, t_b, x0, e, d, p, n) ->
    (t_a, g_a, v_a, X_a, t_b, n)``; with ``go`` false the state passes through unflown.
    The slope is the chord plus half the change of the along-rail speed ``v``
    between the iterates: the residual's slope at ``t_b`` if the travel is quadratic
    in time (what is left is the grid's own dependence on ``t_r``)."""
    t_a, g_a, v_a, t_b, n = (ca.MX.sym(s) for s in ("t_a", "g_a", "v_a", "t_b", "n"))
    X_a = ca.MX.sym("X_a", 13, nr)
    x0, e, d, p = ca.MX.sym("x0", 13), ca.MX.sym("e", 3), ca.MX.sym("d"), ca.MX.sym("p", rail.size1_in(4))
    g_b, v_b, X_b = rail(t_b, x0, e, d, p)
    same = t_b == t_a
    slope = ca.if_else(same, v_b, (g_b - g_a) / ca.if_else(same, 1.0, t_b - t_a) + 0.5 * (v_b - v_a))
    t_new = ca.if_else(slope == 0, t_b, t_b - g_b / ca.if_else(slope == 0, 1.0, slope))
    ins = [t_a, g_a, v_a, X_a, t_b, x0, e, d, p, n]
    fly = ca.Function("secant_fly", ins, [t_b, g_b, v_b, X_b, t_new, n + 1])
    keep = ca.Function("secant_keep", ins, [t_a, g_a, v_a, X_a, t_b, n])
    return ca.Function.if_else("secant", fly, keep)


def _hermite_root(s0, s1, v0, v1, u):
    """Root ``u`` in [0, 1] of the cubic Hermite interpolant of values ``s0, s1`` and
    slopes ``v0, v1`` (per unit ``u``) on [0, 1], by Newton from ``u`` (clamped)."""
    for _ in range(4):
        h = ((2 * u**3 - 3 * u**2 + 1) * s0 + (u**3 - 2 * u**2 + u) * v0
             + (3 * u**2 - 2 * u**3) * s1 + (u**3 - u**2) * v1)
        dh = (6 * u**2 - 6 * u) * (s0 - s1) + (3 * u**2 - 4 * u + 1) * v0 + (3 * u**2 - 2 * u) * v1
        u = ca.fmin(1.0, ca.fmax(0.0, u - h / ca.if_else(dh == 0, 1.0, dh)))
    return u


def _coast_chunk(model, n: int, name: str) -> ca.Function:
    """``(x0, starts, lengths, t0, span, p) -> X``: ``n`` coast steps on the given
    grid fractions, the same expression per step as ``phase_trajectory`` (in the
    carried form of :func:`~ironbark_opt.dynamics.integrator.carried_trajectory`)."""
    x0, t0, span = ca.MX.sym("x0", 13), ca.MX.sym("t0"), ca.MX.sym("span")
    st, ln, p = ca.MX.sym("starts", 1, n), ca.MX.sym("lengths", 1, n), ca.MX.sym("p", model.n_p)
    X = carried_trajectory(model.rhs["coast"], name, x0, st, ln, t0, span, p)
    ins = [x0, st, ln, t0, span, p]
    fly = ca.Function(f"{name}_fly", ins, [X])
    skip = ca.Function(f"{name}_skip", ins, [ca.repmat(x0, 1, n)])
    return ca.Function.if_else(name, fly, skip)


def _first(mask: ca.MX) -> ca.MX:
    """One-hot row: 1 at the first true column of ``mask`` (all zeros if none)."""
    return mask * (ca.cumsum(mask, 1) == 1)


def ascent_functions(model) -> tuple[ca.Function, ca.Function]:
    """``(ascent, ascent_batch)``: ``p -> (ev, x0, X_rail, X_boost, X_coast, x_apogee)``
    (see the module doc; ``ev`` holds the scalars named in :data:`EV`) and, from
    the same graph (the same operations, so the same numbers to the bit),
    ``p -> (ev, x_rail, x_apogee)``, mapped over the samples of
    ``FlightModel.run_batch`` without their trajectories."""
    nr, nc = model.steps.n_rail, model.n_coast
    p = ca.MX.sym("p", model.n_p)
    x0, e = model._launch(p)
    d = model.rail_exit_distance(p)
    burn = model.burn_time(p)
    rail = _rail_pass(model)

    # rail exit: coarse bracket, Hermite guess, Newton step with the speed, secant steps
    nb = max(1, nr // 2)
    hi = ca.fmin(0.5, burn)
    X_hi = phase_trajectory(model.step["rail"], nb, "traj_rail_bracket")(x0, 0, hi, p)
    X_hi = ca.horzcat(x0, X_hi)                                          # 13 x (nb + 1)
    trav = e.T @ X_hi[0:3, :] - d
    g_hi = trav[-1]
    first = _first(trav > 0)                                          # first sample past the exit
    prev = ca.horzcat(first[:, 1:], 0)                                # the sample before it
    s1, s0 = ca.mtimes(trav, first.T), ca.mtimes(trav, prev.T)
    dt = hi / nb
    v1, v0 = _along_rail(e, ca.mtimes(X_hi, first.T)) * dt, _along_rail(e, ca.mtimes(X_hi, prev.T)) * dt
    k = ca.mtimes(ca.DM(np.arange(nb + 1)).T, first.T)
    u = _hermite_root(s0, s1, v0, v1, -s0 / ca.if_else(s1 == s0, 1.0, s1 - s0))
    t_a = (k - 1 + u) * dt
    g_a, v_a, X_a = rail(t_a, x0, e, d, p)
    t_b = t_a - g_a / ca.if_else(v_a == 0, 1.0, v_a)
    step = _secant_iteration(rail, nr)
    n = ca.MX(2)
    for _ in range(RAIL_ITERATIONS):
        t_a, g_a, v_a, X_a, t_b, n = step(ca.fabs(g_a) >= RAIL_TOL_M, t_a, g_a, v_a, X_a, t_b, x0, e, d, p, n)
    t_r, x_r = t_a, X_a[:, -1]

    # boost on the model's own trajectory (grid and air-start segments)
    X_b = model.trajectory["boost"](x_r, t_r, burn, p)
    x_b = X_b[:, -1]
    vz_b = model.vz_l(x_b)
    t_end = burn + vz_b / G0 + 2.0
    span = t_end - burn

    # coast in chunks, each flown only while still climbing
    fr = grid_fractions(nc, model.coast_grading)
    starts, lengths = fr[:-1], np.diff(fr)
    blocks, x, chunks = [], x_b, {}
    for j in range(0, nc, COAST_CHUNK):
        m = min(COAST_CHUNK, nc - j)
        if m not in chunks:
            chunks[m] = _coast_chunk(model, m, f"coast_chunk_{m}")
        go = model.vz_l(x) > 0
        X = chunks[m](go, x, ca.DM(starts[j:j + m]).T, ca.DM(lengths[j:j + m]).T, burn, span, p)
        blocks.append(X)
        x = X[:, -1]
    X_c = ca.hcat(blocks)
    vz = model.vz_l.map(nc)(X_c)

    # apogee inside the first step ending at v_z <= 0
    hot = _first(vz <= 0)
    found = ca.sum2(hot)
    x_k = ca.mtimes(X_c[:, :-1], hot[:, 1:].T) + x_b * hot[:, 0]
    vz_k = ca.mtimes(vz[:, :-1], hot[:, 1:].T) + vz_b * hot[:, 0]
    vz_end = ca.mtimes(vz, hot.T)
    kc = ca.mtimes(ca.DM(np.arange(nc)).T, hot.T)
    f_k = ca.mtimes(ca.DM(starts).T, hot.T)
    dt_c = span * ca.mtimes(ca.DM(lengths).T, hot.T)
    t_k = burn + span * f_k
    h0 = ca.if_else(vz_k != vz_end, dt_c * vz_k / ca.if_else(vz_k != vz_end, vz_k - vz_end, 1.0), dt_c)
    h, x_a = model._apogee_event(x_k, t_k, h0, dt_c, p)
    ev = ca.vertcat(t_r, g_a, g_hi, burn, vz_b, t_end, kc, found, t_k, h, n)
    return (ca.Function("ascent", [p], [ev, x0, X_a, X_b, X_c, x_a],
                        ["p"], ["ev", "x0", "X_rail", "X_boost", "X_coast", "x_apogee"]),
            ca.Function("ascent_batch", [p], [ev, x_r, x_a], ["p"], ["ev", "x_rail", "x_apogee"]))


def applies(ev) -> np.ndarray:
    """Where the ascent Function's answer stands (``ev``: rows of :data:`EV`, one column
    per sample): the bracket held, the rail-exit residual met its tolerance, the
    rail was left before burnout, the rocket climbs at burnout, apogee is within
    the horizon.  Elsewhere the phase-by-phase path flies (and reports errors)."""
    ev = np.asarray(ev, dtype=float).reshape(len(EV), -1)
    r = dict(zip(EV, ev))
    return ((r["g_bracket"] > 0) & (np.abs(r["g_rail"]) < RAIL_TOL_M) & (r["t_rail"] < r["t_burnout"])
            & (r["vz_burnout"] > 0) & (r["found"] == 1))


class AscentRunner:
    """Calls an ascent Function through a CasADi buffer (:class:`~ironbark_opt.dynamics.buffered.Buffered`):
    NumPy arrays in and out, no DM conversions.  ``__call__(p)`` returns a dict of fresh arrays
    (None when the evaluation fails)."""

    def __init__(self, func: ca.Function):
        self.func = func
        self._buffered = Buffered(func)

    def __call__(self, p: np.ndarray) -> dict | None:
        out = self._buffered.evaluate([p])
        if out is None:
            return None
        ev, x0, X_r, X_b, X_c, x_a = out
        r = dict(zip(EV, ev[:, 0]))
        r.update(x0=x0[:, 0], X_rail=X_r, X_boost=X_b, X_coast=X_c, x_apogee=x_a[:, 0])
        return r
