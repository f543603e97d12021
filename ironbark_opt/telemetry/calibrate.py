"""``calibrate(setup, log) -> Calibration``: fit model parameters to a flight log.

Weighted least squares on the log's samples from liftoff to the end of the
fit window (default: the logged apogee)::

    min_q  sum_c sum_i ((y_c(t_i - t_liftoff + dt; q) - y_c,i) / sigma_c)^2

``y_c`` are the simulated channels of :class:`~ironbark_opt.telemetry.sampled.SampledModel`
(the CasADi trajectory and its exact Jacobian), ``sigma_c`` each channel's
noise estimated from the log (:meth:`FlightLog.noise`), ``q`` the chosen
named parameters (drag_scale, thrust_scale, dry_mass_offset, ...) and
``dt`` an optional time shift of the log against the simulation (the log's
liftoff is itself an estimate).  Solved by Gauss-Newton with
Levenberg-Marquardt damping (Marquardt, J. SIAM 11(2), 1963; Nocedal &
Wright, *Numerical Optimization*, 2nd ed., 2006, sec. 10.3).

Barometric altitude of a moving rocket reads low: the static port sees
a pressure ``p + C_p q`` (position error; Gracey, *Measurement of Aircraft
Speed and Altitude*, NASA RP-1046, 1980, ch. 6), i.e. an altitude error
``-C_p q / (rho g) = -C_p V^2 / (2 g)``.  With ``fit_baro_port`` (default)
the altitude channel is modelled as ``z - C_p V_air^2 / (2 g)`` and
``baro_port_cp`` [-] is fitted with the rest (a property of the avionics
bay, not of the rocket model: it is reported but not written to the
calibration's model parameters).

Uncertainty: the covariance of the estimate is the inverse of ``J^T J``
(the weighted Jacobian at the solution), scaled by the reduced chi-square
``s^2 = RSS / (m - n)`` (Bevington & Robinson, *Data Reduction and Error
Analysis*, 3rd ed., 2003, ch. 8 and 11; as SciPy's ``curve_fit`` with
``absolute_sigma=False``), so a model that cannot fit the log to its noise
gets wider intervals.  Residuals of a misfitting model are correlated in
time, so these intervals are a lower bound; the report says so.

Default channels: the *measured* ones — barometric altitude and the
accelerometer where logged.  Logged vertical speeds are the devices'
derived estimates (Kalman, baro differences) that repeat the altitude's
information with correlated errors; ask for them with ``channels=``.
"""
from __future__ import annotations

import warnings
from dataclasses import dataclass, field
from typing import Mapping, Sequence

import numpy as np
import pandas as pd

from ironbark_opt import params
from ironbark_opt.errors import InputError, SolverError
from ironbark_opt.telemetry.flightlog import FlightLog
from ironbark_opt.telemetry.sampled import SampledModel

DEFAULT_PARAMETERS = ("drag_scale", "thrust_scale")
FITTABLE = ("drag_scale", "thrust_scale", "dry_mass_offset", "burn_time_scale", "normal_force_scale",
            "temperature_offset", "wind_east", "wind_north")
TIME_OFFSET = "time_offset"
BARO_PORT = "baro_port_cp"
NUISANCE = (TIME_OFFSET, BARO_PORT)
_UNITS = {"altitude": "m", "vertical_speed": "mps", "acceleration": "mps2"}


@dataclass(frozen=True)
class Calibration:
    """Result of :func:`calibrate` (immutable).

    Attributes
    ----------
    rocket, log : str
    values : mapping name -> float
        Fitted parameter values (SI) — the registry names plus ``time_offset``
        [s] when fitted (the log's time shift, not a model parameter).
    start : mapping name -> float
        The values the fit started from (the rocket file's nominal).
    standard_errors : mapping name -> float
    correlation : DataFrame
    channels : tuple of str
    noise : mapping channel -> float [SI]
    window_s : (float, float)
        Fit window in log time [s].
    residuals : DataFrame
        ``time_s`` (log time), ``channel``, ``residual`` [SI] (simulated - logged).
    stats : mapping
        ``samples``, ``iterations``, ``chi2_reduced``, ``rms_<channel>_<unit>``.
    """

    rocket: str
    log: str
    values: Mapping[str, float]
    start: Mapping[str, float]
    standard_errors: Mapping[str, float]
    correlation: pd.DataFrame = field(repr=False)
    channels: tuple
    noise: Mapping[str, float]
    window_s: tuple
    residuals: pd.DataFrame = field(repr=False)
    stats: Mapping[str, float]

    def __repr__(self) -> str:
        vals = ", ".join(f"{k}={v:.4g}±{self.standard_errors[k]:.2g}" for k, v in self.values.items())
        return f"Calibration({self.rocket!r} on {self.log!r}: {vals})"

    def parameter_values(self) -> dict[str, float]:
        """The fitted model parameters (without ``time_offset``), to apply to a setup."""
        return {k: float(v) for k, v in self.values.items() if k not in NUISANCE}

    def to_dict(self) -> dict:
        """Summary: ``parameters`` name -> {value, start, standard_error, low_2sigma, high_2sigma, unit},
        plus unit-suffixed fit figures."""
        units = {k: {TIME_OFFSET: "s", BARO_PORT: "-"}.get(k) or params.INFO[k].unit for k in self.values}
        par = {k: {"value": float(v), "start": float(self.start[k]), "standard_error": self.standard_errors[k],
                   "low_2sigma": float(v - 2 * self.standard_errors[k]),
                   "high_2sigma": float(v + 2 * self.standard_errors[k]), "unit": units[k]}
               for k, v in self.values.items()}
        return {"rocket": self.rocket, "log": self.log, "parameters": par,
                "correlation": {"names": list(self.correlation.columns),
                                "matrix": self.correlation.values.tolist()},
                "channels": list(self.channels),
                **{f"noise_{c}_{_UNITS[c]}": float(v) for c, v in self.noise.items()},
                "window_start_s": float(self.window_s[0]), "window_end_s": float(self.window_s[1]),
                **dict(self.stats)}

    def to_dataframe(self) -> pd.DataFrame:
        """One row per fitted parameter: value, start, standard error, 95 % interval."""
        rows = []
        for k, v in self.values.items():
            se = self.standard_errors[k]
            rows.append({"parameter": k, "value": v, "start": self.start[k], "standard_error": se,
                         "low_2sigma": v - 2 * se, "high_2sigma": v + 2 * se})
        return pd.DataFrame(rows)

    def summary(self) -> str:
        """Human-readable summary (a string)."""
        s = self.stats
        lines = [f"Calibration of {self.rocket} on {self.log}",
                 f"  window         {self.window_s[0]:.2f} .. {self.window_s[1]:.2f} s (log time), "
                 f"{s['samples']} residuals, channels {', '.join(self.channels)}",
                 f"  fit            {s['iterations']} iterations, reduced chi-square {s['chi2_reduced']:.2f}"]
        for c in self.channels:
            lines.append(f"  rms {c:<15}{s[f'rms_{c}_{_UNITS[c]}']:10.3f} {_UNITS[c]} (noise {self.noise[c]:.3f})")
        lines.append(f"  {'parameter':<18}{'start':>10}{'fitted':>12}{'std err':>10}   2-sigma interval")
        for k, v in self.values.items():
            se = self.standard_errors[k]
            lines.append(f"  {k:<18}{self.start[k]:10.4f}{v:12.4f}{se:10.4f}   [{v - 2 * se:.4f}, {v + 2 * se:.4f}]")
        names = list(self.correlation.columns)
        if len(names) > 1:
            lines.append("  correlations   " + ", ".join(
                f"{a}/{b} {self.correlation.loc[a, b]:+.2f}" for i, a in enumerate(names) for b in names[i + 1:]))
        return "\n".join(lines)


def fit_window(log: FlightLog, until: float | None = None, until_fraction: float | None = None) -> tuple:
    """(start, end) of the fit in log time [s]: liftoff to apogee, or to
    ``until`` [s] or ``until_fraction`` of the liftoff-to-apogee time."""
    t0 = log.events.get("liftoff", 0.0)
    end = log.apogee_time
    if until_fraction is not None:
        if not 0 < until_fraction <= 1:
            raise InputError(f"fraction of the time to apogee must be in (0, 1], got {until_fraction}",
                             field="until_fraction")
        end = t0 + until_fraction * (log.apogee_time - t0)
    if until is not None:
        end = min(end, float(until))
    if end <= t0 + 0.5:
        raise InputError(f"fit window {t0:.2f}..{end:.2f} s is too short", field="until")
    return t0, end


def _channels(log, channels):
    if channels is None:
        return tuple(c for c in ("altitude", "acceleration") if log.channel(c) is not None)
    out = tuple(channels)
    for c in out:
        if log.channel(c) is None:
            raise InputError(f"the log has no {c} channel (it has {', '.join(log.channels())})",
                             source=log.source, field="channels")
    return out


def _initial_shift(x, model_values, nodes, data, noise, chans, baro):
    """Start values of the time shift (and the static-port term): the residual
    is not smooth in the shift (thrust edges), so Gauss-Newton starts from
    the best shift of a scan over +-0.5 s (20 ms, then 2 ms steps), the model flown once
    at the start values and re-sampled; the static-port coefficient, linear
    in the residual, is solved in closed form at each shift."""
    i_dt = -2 if baro else -1

    def at_shift(dt):
        xt = x.copy()
        xt[i_dt] = dt
        if baro:
            xt[-1] = 0.0
        sim = model_values(xt, jac=False, nodes=nodes)
        r = np.concatenate([(sim[c][0] - data[c]) / noise[c] for c in chans])
        if baro:                                   # d r / d cp on the altitude rows only
            xt[-1] = 1.0
            r1 = np.concatenate([(model_values(xt, jac=False, nodes=nodes)[c][0] - data[c]) / noise[c]
                                 for c in chans])
            d = r1 - r
            xt[-1] = -float(r @ d) / float(d @ d) if d @ d > 0 else 0.0
            r = r + xt[-1] * d
        return float(r @ r), xt

    best = min((at_shift(dt) for dt in np.arange(-0.5, 0.5001, 0.02)), key=lambda cx: cx[0])
    centre = best[1][i_dt]
    best = min((at_shift(centre + dt) for dt in np.arange(-0.02, 0.0201, 0.002)), key=lambda cx: cx[0])
    return best[1]


def calibrate(setup, log: FlightLog, *, parameters: Sequence[str] = DEFAULT_PARAMETERS,
              fit_time_offset: bool = True, fit_baro_port: bool = True, channels: Sequence[str] | None = None, until: float | None = None,
              until_fraction: float | None = None, max_iterations: int = 30, model=None) -> Calibration:
    """Fit ``parameters`` of ``setup`` to ``log`` (see the module docstring).

    Parameters
    ----------
    setup : FlightSetup
    log : FlightLog
    parameters : names from :mod:`ironbark_opt.params` (of ``FITTABLE``)
    fit_time_offset : bool
        Also fit the log's time shift ``dt`` [s].
    fit_baro_port : bool
        Also fit the static-port pressure coefficient ``baro_port_cp`` [-].
    channels : channels to fit (default: altitude and acceleration where logged)
    until, until_fraction : end of the fit window (log time [s] / fraction of the time to apogee)
    """
    from ironbark_opt.flight import flight_model

    names = tuple(parameters)
    if not names:
        raise InputError("no parameter to fit", field="parameters")
    for n in names:
        if n not in FITTABLE:
            raise InputError(f"cannot calibrate '{n}'; choose from {', '.join(FITTABLE)}", field="parameters")
    chans = _channels(log, channels)
    t_lo, t_hi = fit_window(log, until, until_fraction)
    model = model or flight_model(setup)
    p_start = setup.nominal_parameters()
    start = {n: float(p_start[params.index(n)]) for n in names}
    sm = SampledModel(model, names, t_hi - t_lo + 1.5, p_start)
    noise = {c: log.noise(c, t_max=t_hi) for c in chans}
    sel = (log.time >= t_lo) & (log.time <= t_hi)
    data = {c: log.channel(c)[sel] for c in chans}
    t_log = log.time[sel] - t_lo
    q = np.array([start[n] for n in names])
    baro = fit_baro_port and "altitude" in chans
    extra = [TIME_OFFSET] * fit_time_offset + [BARO_PORT] * baro
    nq = len(names) + len(extra)
    rows = chans + (("baro_head",) if baro else ())

    def model_values(x, jac=True, nodes=None):
        q, dt, cp = x[:len(names)], (x[len(names)] if fit_time_offset else 0.0), (x[-1] if baro else 0.0)
        tau = np.clip(t_log + dt, 0.0, None)
        sim = sm.at(q, tau, rows, derivatives=jac, nodes=nodes)
        out = {}
        for c in chans:
            val, jq, dtau = sim[c]
            if c == "altitude" and baro:
                hv, hq, ht = sim["baro_head"]
                val = val - cp * hv
                if jac:
                    jq, dtau = jq - cp * hq, dtau - cp * ht
            cols = None
            if jac:
                cols = [jq] + ([dtau[:, None]] if fit_time_offset else [])
                if baro:
                    cols.append((-hv if c == "altitude" else np.zeros_like(val))[:, None])
                cols = np.hstack(cols)
            out[c] = (val, cols)
        return out

    def residuals(x, jac=True):
        sim = model_values(x, jac)
        r = np.concatenate([(sim[c][0] - data[c]) / noise[c] for c in chans])
        return r, (np.vstack([sim[c][1] / noise[c] for c in chans]) if jac else None)

    x = np.concatenate([q, np.zeros(len(extra))])
    try:
        if fit_time_offset:
            x = _initial_shift(x, model_values, sm.nodes(q), data, noise, chans, baro)
        r, J = residuals(x)
    except RuntimeError as err:                    # CasADi: rail-exit rootfinder / evaluation failed
        raise SolverError(f"calibration: the model could not be flown at the start values ({err})") from None
    cost = float(r @ r)
    lam = 1e-6                    # start as Gauss-Newton; damp only when a step fails
    it = 0
    dof = max(r.size - nq, 1)
    for it in range(1, max_iterations + 1):
        A, g = J.T @ J, J.T @ r
        D = np.diag(np.diag(A))
        accepted = False
        for _ in range(12):
            step = -np.linalg.solve(A + lam * D, g)
            x_new = x + step
            try:
                r_new, J_new = residuals(x_new)
            except Exception:                      # solver failure far from the start: shorter step
                lam *= 10
                continue
            c_new = float(r_new @ r_new)
            if c_new < cost:
                x, r, J, accepted = x_new, r_new, J_new, True
                cost, lam = c_new, max(lam / 10, 1e-9)
                break
            lam *= 10
        # Converged when the last step moved every unknown by < 1 % of its standard error
        # (further iterations cannot change the reported result), or no step reduces the cost.
        try:
            se_now = np.sqrt(np.diag(np.linalg.inv(J.T @ J)) * cost / dof)
        except np.linalg.LinAlgError:
            break
        if not accepted or np.all(np.abs(step) <= 0.01 * se_now):
            break
    m = r.size
    if m <= nq:
        raise InputError(f"{m} samples in the fit window for {nq} unknowns", field="until")
    try:
        cov = np.linalg.inv(J.T @ J)
    except np.linalg.LinAlgError:
        raise SolverError("the fit's Jacobian is singular: the log cannot tell these parameters apart "
                          f"({', '.join(names)}); fit fewer") from None
    chi2_red = cost / (m - nq)
    cov = cov * chi2_red
    se = np.sqrt(np.diag(cov))
    all_names = list(names) + extra
    corr = cov / np.outer(se, se)
    worst = np.max(np.abs(corr - np.eye(nq))) if nq > 1 else 0.0
    if worst > 0.999:
        warnings.warn(f"calibration: parameters correlated at {worst:.4f}: the log cannot separate them "
                      f"({', '.join(list(names) + extra)}); their values are arbitrary along that direction, "
                      "fit fewer parameters", stacklevel=2)
    values = dict(zip(all_names, map(float, x)))
    start.update({k: 0.0 for k in extra})
    sim = {c: (v[0],) for c, v in model_values(x, jac=False).items()}
    res_rows, stats = [], {"samples": int(m), "iterations": int(it), "chi2_reduced": float(chi2_red)}
    for c in chans:
        d = sim[c][0] - data[c]
        stats[f"rms_{c}_{_UNITS[c]}"] = float(np.sqrt(np.mean(d ** 2)))
        res_rows.append(pd.DataFrame({"time_s": log.time[sel], "channel": c, "residual": d}))
    return Calibration(rocket=setup.name, log=log.source, values=values, start=start,
                       standard_errors=dict(zip(all_names, map(float, se))),
                       correlation=pd.DataFrame(corr, index=all_names, columns=all_names),
                       channels=chans, noise=noise, window_s=(float(t_lo), float(t_hi)),
                       residuals=pd.concat(res_rows, ignore_index=True), stats=stats)
