"""Flight with a user's air-brake controller sampled at a fixed rate.

A controller is Python code, so this path is numeric only: the coast is
flown sample period by sample period, each period one RK4 ``mapaccum`` of
the same coast right-hand side as every other flight, with the deployment
held (zero-order hold, as an on-board computer commands a servo) at
``p[airbrake_level]`` for that period.  At each sampling instant the
controller sees the state and returns a commanded deployment; the command
is clipped to [0, 1] and rate-limited (a change of at most ``rate / f``
per sample, ``rate`` [1/s], ``f`` the sampling rate [Hz]).  Deployment
changes only at sample instants, which are step boundaries, so no switch
falls inside a step.  The brakes stay stowed while the motor burns
(:mod:`ironbark_opt.aero.airbrakes`); the controller runs from burnout.

Numeric-only.  Sensitivities, ballast and Monte Carlo need a
differentiable schedule instead (a controller is refused there).
"""
from __future__ import annotations

import math

import numpy as np

from ironbark_opt import params
from ironbark_opt.dynamics import rhs as rhs_mod
from ironbark_opt.dynamics.integrator import phase_trajectory
from ironbark_opt.errors import InputError, SolverError

_Y = {name: i for i, name in enumerate(rhs_mod.OUTPUT_NAMES)}
MAX_COAST_S = 600.0    # [s] a coast longer than this is not a rocket flight


def _state(model, x, t, p, deployment) -> dict:
    y = np.array(model.rhs["coast"](x, t, p)[1]).ravel()
    return {"time_s": float(t), "altitude_agl_m": float(x[2]), "vz_mps": float(y[_Y["vz_l_mps"]]),
            "speed_mps": float(y[_Y["speed_mps"]]), "mach": float(y[_Y["mach"]]),
            "deployment": float(deployment)}


def _where(func, exc: BaseException | None = None):
    """``(file, line)`` of a user's controller: the deepest line of its file in the
    traceback of ``exc``, else its ``def`` line; ``(None, None)`` when not Python code."""
    code = getattr(func, "__code__", None)
    if code is None:
        return None, None
    line, tb = code.co_firstlineno, None if exc is None else exc.__traceback__
    while tb is not None:
        if tb.tb_frame.f_code.co_filename == code.co_filename:
            line = tb.tb_lineno
        tb = tb.tb_next
    return code.co_filename, line


def run_controlled(model, p, *, descent: bool = False) -> dict:
    """Fly ``model`` (a FlightModel whose setup has a controller) to apogee.

    Parameters
    ----------
    model : FlightModel
    p : array (params.SIZE) [mixed SI]
    descent : bool

    Returns
    -------
    dict as :meth:`FlightModel.run`, plus ``P`` (params.SIZE x n): the
    parameter vector in force at each sample (its ``airbrake_level`` row is
    the held deployment), and ``deployment_commands`` (time [s], command).
    """
    brakes = model.setup.airbrakes
    p = np.asarray(p, dtype=float).ravel()
    i_l = params.index("airbrake_level")
    x0 = model._x0(p)
    t_r = model.rail_exit(p)
    t_b = float(model.setup.motor.burn_time) * p[params.index("burn_time_scale")]
    p_off = p.copy()
    p_off[i_l] = 0.0
    X_rail = np.array(model._run["rail"](x0, 0.0, t_r, p_off))
    X_boost = np.array(model._run["boost"](X_rail[:, -1], t_r, t_b, p_off))
    x_b = X_boost[:, -1]
    if float(model.vz_l(x_b)) <= 0:
        raise SolverError("vertical velocity at burnout is not positive: the rocket never climbs")
    period = 1.0 / float(brakes.sampling_rate)
    h_max = model.stable_step(model.rhs["coast"], x_b, t_b, p_off)
    n_sub = max(1, int(math.ceil(period / min(h_max, 0.05))))
    cache = model.__dict__.setdefault("_controlled_cache", {})
    if n_sub not in cache:
        cache[n_sub] = phase_trajectory(model.step["coast"], n_sub, f"traj_ctrl_{n_sub}")
    traj = cache[n_sub]
    max_change = float(brakes.rate) * period
    d, x, t = 0.0, x_b.copy(), t_b
    ts, xs, ds, commands = [], [], [], []
    for _ in range(int(MAX_COAST_S / period)):
        state = _state(model, x, t, p_off, d)
        try:
            cmd = float(brakes.controller(t, state))
        except Exception as exc:                     # a user's code: report where it failed
            src, line = _where(brakes.controller, exc)
            raise InputError(f"the air-brake controller raised {type(exc).__name__}: {exc} "
                             f"(at t = {t:.3f} s)", source=src, line=line,
                             field="airbrakes.controller") from None
        if not math.isfinite(cmd):
            src, line = _where(brakes.controller)
            raise InputError(f"the air-brake controller returned {cmd} at t = {t:.3f} s (expected a "
                             "deployment in [0, 1])", source=src, line=line, field="airbrakes.controller")
        commands.append((t, cmd))
        d = d + float(np.clip(min(max(cmd, 0.0), 1.0) - d, -max_change, max_change))
        p_k = p.copy()
        p_k[i_l] = d
        X = np.array(traj(x, t, t + period, p_k))
        vz = np.array(model._mapped("vz", n_sub)(X)).ravel()
        below = np.nonzero(vz <= 0)[0]
        h = period / n_sub
        if below.size:
            k = int(below[0])
            x_k = x if k == 0 else X[:, k - 1]
            vz_k = float(model.vz_l(x)) if k == 0 else vz[k - 1]
            t_k = t + k * h
            h0 = h * vz_k / (vz_k - vz[k]) if vz_k != vz[k] else h
            hh, x_a = model._apogee_run(x_k, t_k, h0, h, p_k)    # the model's own apogee root
            hh, x_a = float(hh), np.array(x_a).ravel()
            ts.extend(t + h * np.arange(1, k + 1))
            xs.append(X[:, :k])
            ds.extend([d] * k)
            ts.append(t_k + hh)
            xs.append(x_a[:, None])
            ds.append(d)
            t_a = t_k + hh
            break
        ts.extend(t + h * np.arange(1, n_sub + 1))
        xs.append(X)
        ds.extend([d] * n_sub)
        x, t = X[:, -1], t + period
    else:
        raise SolverError(f"apogee not reached within {MAX_COAST_S:.0f} s of coast")
    n_r, n_b = X_rail.shape[1], X_boost.shape[1]
    t_all = np.concatenate([[0.0], np.linspace(0, t_r, n_r + 1)[1:], model.boost_times(t_r, t_b, p),
                            np.array(ts)])
    x_all = np.hstack([x0[:, None], X_rail, X_boost] + xs)
    phase = np.array(["rail"] * (n_r + 1) + ["boost"] * n_b + ["coast"] * len(ts))
    P = np.repeat(p_off[:, None], t_all.size, axis=1)
    P[i_l, n_r + 1 + n_b:] = ds
    out = dict(t=t_all, x=x_all, phase=phase, p=p, P=P, t_rail=t_r, t_burnout=t_b, t_apogee=t_a,
               x_rail=X_rail[:, -1].copy(), x_burnout=x_b, x_apogee=x_a,
               deployment_commands=np.array(commands))
    if descent:
        d_run = model._descend(t_a, x_a, p_off, t_all, x_all, phase)
        extra = d_run["t"].size - t_all.size
        out.update(d_run)
        out["P"] = np.hstack([P, np.repeat(p_off[:, None], extra, axis=1)])
    return out
