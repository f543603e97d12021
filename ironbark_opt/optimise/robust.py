"""Robust ballast: the ballast that scores best under the day's dispersion.

``solve_ballast`` puts the *nominal* apogee on the target; under a
dispersion spec the apogee is a random variable ``a(w, xi)`` of the ballast
``w = (m_b[, x_b])`` and the dispersed parameters ``xi``.  Competitions
score the miss, so this module maximises

    P(|a(w, xi) - target| <= B)          (objective "in_band")

or minimises ``E|a(w, xi) - target|``     (objective "expected_abs_miss")

by the sample-average approximation (SAA): one fixed set of ``N`` samples
``xi_1..xi_N`` (common random numbers: every ``w`` is judged on the same
samples, so the objective is a deterministic smooth function of ``w``) and
IPOPT on the sample mean, started from the nominal solution (Shapiro,
Dentcheva & Ruszczynski, *Lectures on Stochastic Programming: Modeling and
Theory*, SIAM 2009, ch. 5, the SAA method and its consistency).  The ``N``
samples are a Latin hypercube of the spec by default: with N = 40 independent
draws the SAA's optimum moves with the draw's own location (on Calisto's
spec it picks a ballast worse than the nominal by 0.015 in P(in band) on
average, ``benchmarks/robust_sweep.py``), and stratifying each marginal
removes most of that noise for an apogee that is nearly additive in the
dispersed parameters.

The SAA optimum is then validated (Kleywegt, Shapiro & Homem-de-Mello, SIAM
J. Optim. 12(2), 2002): it and the nominal ballast fly fresh samples, and the
nominal ballast is kept unless the optimum scores better on them.

The indicator and ``|.|`` are not differentiable, so each sample's apogee is
smoothed by a Gaussian kernel of width ``h`` (kernel estimate of the CDF,
Nadaraya 1964; the same smoothing for chance constraints: Hong, Yang & Zhang,
Operations Research 59(3), 2011):

    1{|d| <= B}  ->  Phi((B - d)/h) - Phi((-B - d)/h)
    |d|          ->  E|d + h Z| = d (2 Phi(d/h) - 1) + 2 h phi(d/h)

with ``d = a - target`` and ``h`` from Silverman's rule of thumb on the
nominal-ballast sample apogees, ``h = 0.9 min(s, IQR/1.34) N^(-1/5)``
(Silverman, *Density Estimation for Statistics and Data Analysis*, 1986,
eq. 3.31): the width is tied to the sample spread and shrinks as N grows.

Exact gradients: every sample flies the model's own phase trajectories
(``FlightModel.trajectory``) with the rail-exit time ``t_r`` and the final
time ``T`` as inputs; one compiled, mapped CasADi Function returns the rail
residual ``g``, the altitude ``z(T)`` and the vertical velocity ``v_z(T)``
with their Jacobian in ``(w, t_r, T)``.  The events are the roots
``g = 0``, ``v_z = 0`` (the same equations the nominal NLP and
``apogee_functions`` impose) and the implicit-function theorem gives

    dt_r/dw = -g_w / g_tr,   dT/dw = -(vz_w + vz_tr dt_r/dw) / vz_T,
    da/dw   = z_w + z_tr dt_r/dw + z_T dT/dw.

The roots are tracked between IPOPT iterates (first-order predictor, Newton
corrector on all samples at once).

Numeric-only.
"""
from __future__ import annotations

import hashlib
import math
import time
from dataclasses import dataclass, field
from typing import Mapping

import casadi as ca
import numpy as np

from ironbark_opt import params
from ironbark_opt.errors import InputError, SolverError

OBJECTIVES = ("in_band", "expected_abs_miss")
#: how the SAA samples are drawn from the spec
DESIGNS = ("latin_hypercube", "independent")
#: the nominal parameters' flight at each ballast, reported as the nominal ballast solution reports it
_FLOWN = ("apogee_agl_m", "rail_exit_speed_mps", "static_margin_rail_exit_cal", "static_margin_min_cal")


def _phi(u):
    """Standard normal density."""
    return np.exp(-0.5 * u * u) / math.sqrt(2.0 * math.pi)


def _Phi(u):
    """Standard normal CDF."""
    from scipy.special import ndtr
    return ndtr(u)


def silverman_width(values) -> float:
    """Kernel width [unit of ``values``]: ``0.9 min(s, IQR/1.34) n^(-1/5)`` (Silverman 1986, eq. 3.31)."""
    v = np.asarray(values, dtype=float)
    q75, q25 = np.percentile(v, [75, 25])
    spread = min(float(v.std(ddof=1)), float(q75 - q25) / 1.34)
    if not spread > 0:
        spread = float(v.std(ddof=1))
    return 0.9 * spread * v.size ** -0.2


def smoothed_terms(apogee, target: float, objective: str, band: float, width: float):
    """(per-sample terms whose mean is the smoothed objective, their derivatives in the
    apogee) -- see :func:`smoothed_objective`.  Numeric-only."""
    d = np.asarray(apogee, dtype=float) - target
    h = width
    if objective == "in_band":
        hi, lo = (band - d) / h, (-band - d) / h
        return -(_Phi(hi) - _Phi(lo)), (_phi(hi) - _phi(lo)) / h
    u = d / h
    return (d * (2 * _Phi(u) - 1) + 2 * h * _phi(u)) / 100.0, (2 * _Phi(u) - 1) / 100.0


def smoothed_objective(apogee, target: float, objective: str, band: float, width: float):
    """(value, d value / d apogee_i) of the smoothed SAA objective (minimised).

    ``in_band``: minus the kernel-smoothed share of samples within ``band`` [m];
    ``expected_abs_miss``: the smoothed mean |miss| [m] divided by 100 (order 1
    for IPOPT).  Numeric-only.
    """
    terms, grad = smoothed_terms(apogee, target, objective, band, width)
    return float(np.mean(terms)), grad / terms.size


def gain_t(terms_nominal, terms_robust) -> float:
    """t statistic of the paired in-sample improvement (mean / standard error of the per-sample
    differences of the minimised terms; +inf when every sample improves equally)."""
    diff = np.asarray(terms_nominal) - np.asarray(terms_robust)
    se = diff.std(ddof=1) / math.sqrt(diff.size)
    return float(diff.mean() / se) if se > 0 else (math.inf if diff.mean() > 0 else 0.0)


def event_function(model, free_position: bool) -> ca.Function:
    """``(w, t_r, T, p) -> (r, J)``: ``r = (g_rail [m], z(T) [m AGL], v_z(T) [m/s],
    |v| at rail exit [m/s], static margin at rail exit [cal])`` of one sample with
    ballast ``w = (m_b[, x_b])`` replacing the entries of ``p``, and
    ``J = dr/d(w, t_r, T)``; the model's own phases (``_final_state`` with the
    rail-exit time as an input, as the nominal ballast NLP flies them) and the
    nominal NLP's rail-exit speed and margin, no rootfinder (so it compiles to
    C).  Symbolic construction, numeric use."""
    from ironbark_opt.dynamics.model import _final_state
    from ironbark_opt.optimise.ballast import _SM

    if hasattr(type(model), "final_state_symbolic"):
        raise InputError("robust ballast flies single-stage rockets only", field="--robust")
    k = 2 if free_position else 1
    i_m, i_x = params.index("ballast_mass"), params.index("ballast_x")
    w, t_r, T = ca.MX.sym("w", k), ca.MX.sym("t_r"), ca.MX.sym("T")
    p = ca.MX.sym("p", params.SIZE)
    pw = ca.vertcat(p[:i_m], w[0], w[1] if free_position else p[i_x], p[i_x + 1:])
    x_T, _, x_r, _ = _final_state(model, pw, T, 0.0, t_rail=t_r)
    r = ca.vertcat(model.rail_residual(t_r, pw), x_T[2], model.vz_l(x_T), ca.norm_2(x_r[3:6]),
                   model.rhs["boost"](x_r, t_r, pw)[1][_SM])
    return ca.Function("robust_events", [w, t_r, T, p], [r, ca.jacobian(r, ca.vertcat(w, t_r, T))],
                       ["w", "t_r", "T", "p"], ["r", "J"])


def _compiled_events(model, free_position: bool) -> ca.Function:
    """:func:`event_function`, C-compiled and cached on disk unless the model runs the VM
    (the VM is ~20x slower here, so ``jit="auto"`` compiles now rather than in the background)."""
    cache = model.__dict__.setdefault("_robust_cache", {})
    if free_position not in cache:
        func = event_function(model, free_position)
        if model.jit:
            from ironbark_opt.dynamics.integrator import compile_function
            key = None
            if model._key is not None:
                key = hashlib.sha256(repr((model._key, model.discretisation(), free_position,
                                           "robust_events_rail")).encode()).hexdigest()[:24]
            func = compile_function(func, key=key)
        cache[free_position] = func
    return cache[free_position]


class SampleApogees:
    """Apogees of fixed samples as a function of the ballast, with exact gradients.

    Parameters
    ----------
    model : FlightModel
    P : array (params.SIZE x N)
        The samples (ballast rows are replaced by ``w``).
    t_rail, t_apogee : arrays (N,) [s]
        Starting guesses of the events (from ``run_batch`` at the start).
    free_position : bool
    """

    def __init__(self, model, P, t_rail, t_apogee, free_position: bool):
        self.P = np.asarray(P, dtype=float)
        self.n = self.P.shape[1]
        self.k = 2 if free_position else 1
        self.func = _compiled_events(model, free_position).map(self.n, "thread", 2)
        self.w = None
        self.roots = np.vstack([t_rail, t_apogee]).astype(float)
        self.droots = None                      # (2, k, N): d(t_r, T)/dw at self.w
        self.evaluations = 0
        self._seen: dict = {}

    def __call__(self, w) -> tuple[np.ndarray, np.ndarray]:
        """(apogee [m AGL] (N,), d apogee / d w (k, N)) at ballast ``w``."""
        return self.events(w)[:2]

    def rail(self, w) -> tuple[np.ndarray, np.ndarray]:
        """(rail-exit speed [m/s] and static margin at rail exit [cal] (2, N), their
        derivatives in ``w`` (2, k, N)) at ballast ``w``."""
        return self.events(w)[2:]

    def events(self, w):
        """(apogee, d apogee/dw, rail outputs, d rail outputs/dw) at ``w``: the events solved
        by Newton's method, derivatives by the implicit-function theorem."""
        w = np.asarray(w, dtype=float).ravel()
        if w.tobytes() in self._seen:
            return self._seen[w.tobytes()]
        k = self.k
        roots = self.roots.copy()
        if self.droots is not None:                       # first-order predictor
            roots += np.einsum("akn,k->an", self.droots, w - self.w)
        for _ in range(8):
            r, J = self.func(w, roots[0][None, :], roots[1][None, :], self.P)
            self.evaluations += 1
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
        self._seen[w.tobytes()] = (z, dz_dw, rail, drail_dw)
        return self._seen[w.tobytes()]


class _Objective(ca.Callback):
    """A numeric ``w -> (value (m,), Jacobian (m, k))`` as a CasADi Function of ``w`` with its
    exact Jacobian (the smoothed SAA objective, m = 1, or the nominal flight's constraints)."""

    def __init__(self, fn, k: int, name: str = "robust_objective", opts=None, m: int = 1):
        ca.Callback.__init__(self)
        self.fn, self.k, self.m = fn, k, m
        self.construct(name, opts or {})

    def get_n_in(self):
        return 1

    def get_n_out(self):
        return 1

    def get_sparsity_in(self, i):
        return ca.Sparsity.dense(self.k, 1)

    def get_sparsity_out(self, i):
        return ca.Sparsity.dense(self.m, 1)

    def eval(self, arg):
        return [np.reshape(self.fn(np.array(arg[0]).ravel())[0], (self.m, 1))]

    def has_jacobian(self):
        return True

    def get_jacobian(self, name, inames, onames, opts):
        self._jac = _Gradient(self.fn, self.k, self.m, name, opts)
        return self._jac


class _Gradient(ca.Callback):
    def __init__(self, fn, k, m, name, opts):
        ca.Callback.__init__(self)
        self.fn, self.k, self.m = fn, k, m
        self.construct(name, opts)

    def get_n_in(self):
        return 2

    def get_n_out(self):
        return 1

    def get_sparsity_in(self, i):
        return ca.Sparsity.dense(self.k, 1) if i == 0 else ca.Sparsity.dense(self.m, 1)

    def get_sparsity_out(self, i):
        return ca.Sparsity.dense(self.m, self.k)

    def eval(self, arg):
        return [np.reshape(self.fn(np.array(arg[0]).ravel())[1], (self.m, self.k))]


@dataclass(frozen=True)
class RobustBallastSolution:
    """Result of :func:`solve_robust_ballast` (immutable).

    ``values`` holds unit-suffixed numbers: ``ballast_kg``, ``ballast_x_m`` (robust),
    ``nominal_ballast_kg``, ``nominal_ballast_x_m``, ``target_agl_m``, ``band_m``,
    ``kernel_width_m``, the in-sample (SAA) and fresh-check probabilities and
    expected misses of both ballasts with their standard errors, solve times.
    """

    name: str
    motor: str
    objective: str
    samples: int
    seed: int
    check_seed: int
    values: Mapping[str, float]
    nominal: object = field(repr=False)
    design: str = "latin_hypercube"
    kept_nominal: bool = False
    #: why the nominal ballast was kept: "t" (min_gain_t) or "selection" (fresh-sample validation)
    kept_by: str | None = None

    def __repr__(self) -> str:
        v = self.values
        return (f"RobustBallastSolution({self.name!r}: {v['ballast_kg']:.3f} kg (nominal "
                f"{v['nominal_ballast_kg']:.3f}), P(in band) {v['check_probability_in_band']:.3f} vs "
                f"{v['check_nominal_probability_in_band']:.3f})")

    @property
    def ballast(self) -> float:
        """Robust ballast mass [kg]."""
        return self.values["ballast_kg"]

    def to_dict(self) -> dict:
        out = {"rocket": self.name, "motor": self.motor, "robust": True, "objective": self.objective,
               "samples": self.samples, "design": self.design, "seed": self.seed, "check_seed": self.check_seed,
               "kept_nominal": self.kept_nominal, "kept_by": self.kept_by}
        out.update(self.values)
        out["nominal_solution"] = {k: v for k, v in self.nominal.to_dict().items() if k != "parameters"}
        return out

    def summary(self) -> str:
        v = self.values
        b = v["band_m"]
        lines = [f"Robust ballast for {self.name} on {self.motor}: objective {self.objective}, "
                 f"{self.samples} samples ({self.design.replace('_', ' ')}, seed {self.seed}), kernel width "
                 f"{v['kernel_width_m']:.1f} m",
                 f"  target             {v['target_agl_m']:10.1f} m AGL, band +/- {b:.0f} m",
                 f"  {'':18s} {'ballast [kg]':>12s} {'x [m]':>7s} {'P(in band)':>17s} {'E|miss| [m]':>16s}"]
        checked = "check_probability_in_band" in v
        src = "check_" if checked else "saa_"
        for label, pre in (("nominal", "nominal_"), ("robust", "")):
            p_in, miss = v[f"{src}{pre}probability_in_band"], v[f"{src}{pre}expected_abs_miss_m"]
            err = (f" +/- {v[f'check_{pre}probability_in_band_stderr']:.3f}",
                   f" +/- {v[f'check_{pre}expected_abs_miss_stderr_m']:.1f}") if checked else ("", "")
            lines.append(f"  {label:18s} {v[pre + 'ballast_kg']:12.3f} {v[pre + 'ballast_x_m']:7.3f} "
                         f"{p_in:9.3f}{err[0]:8s} {miss:8.1f}{err[1]:7s}")
        lines.append(f"  SAA optimum        {v['saa_optimum_ballast_kg']:.3f} kg, in-sample gain t = {v['saa_gain_t']:.2f}"
                     + (": not significant, the nominal ballast kept" if self.kept_by == "t" else ""))
        if "select_samples" in v:
            lines.append(f"  validation         SAA optimum - nominal on {v['select_samples']} fresh samples (seed "
                         f"{v['select_seed']}): P {v['select_probability_gain']:+.3f} +/- "
                         f"{v['select_probability_gain_stderr']:.3f}, E|miss| "
                         f"{v['select_expected_abs_miss_change_m']:+.1f} m: "
                         + ("not better, the nominal ballast kept" if self.kept_by == "selection" else "accepted"))
        if checked:
            lines += [f"  robust - nominal   P(in band) {v['check_probability_gain']:+.3f} +/- "
                      f"{v['check_probability_gain_stderr']:.3f}, E|miss| "
                      f"{v['check_expected_abs_miss_change_m']:+.1f} +/- "
                      f"{v['check_expected_abs_miss_change_stderr_m']:.1f} m (paired)",
                      f"  check              {v['check_samples']} fresh samples, seed {self.check_seed} "
                      f"(in-sample SAA: P {v['saa_nominal_probability_in_band']:.3f} -> "
                      f"{v['saa_probability_in_band']:.3f})"]
        else:
            lines.append(f"  (in-sample values on the {self.samples} SAA samples: no fresh check asked)")
        for label, pre in (("nominal", "nominal_"), ("robust", "")):
            lines.append(f"  {label + ' flight':18s} apogee {v[pre + 'apogee_agl_m']:.1f} m AGL, rail exit "
                         f"{v[pre + 'rail_exit_speed_mps']:.2f} m/s, margin {v[pre + 'static_margin_rail_exit_cal']:.2f}"
                         f" cal at rail exit ({v[pre + 'static_margin_min_cal']:.2f} min; nominal parameters)")
        limits = [f"{name} >= {v[key]:g} {unit}" for name, key, unit in
                  (("rail-exit speed", "min_rail_speed_mps", "m/s"), ("margin", "min_margin_cal", "cal"))
                  if key in v]
        if limits:
            lines.append(f"  limits             {', '.join(limits)} (on the nominal parameters' flight)")
        lines.append(f"  solve time         {v['solve_time_s']:10.2f} s (nominal solve {v['nominal_solve_time_s']:.2f} "
                     f"s, {v['ipopt_iterations']} IPOPT iterations, {v['sample_evaluations']} mapped evaluations)")
        return "\n".join(lines)


def _miss_stats(apogee, target, band, prefix) -> dict:
    d = np.abs(np.asarray(apogee) - target)
    inside = (d <= band).astype(float)
    n = d.size
    p = float(inside.mean())
    return {f"{prefix}probability_in_band": p,
            # binomial standard error sqrt(p (1 - p) / n); standard error of a mean s / sqrt(n)
            f"{prefix}probability_in_band_stderr": math.sqrt(p * (1 - p) / n),
            f"{prefix}expected_abs_miss_m": float(d.mean()),
            f"{prefix}expected_abs_miss_stderr_m": float(d.std(ddof=1) / math.sqrt(n))}


def check_ballasts(model, spec, p_nominal, ballasts, target_agl, band, samples, seed) -> dict:
    """Fresh Monte Carlo of several ballasts on the *same* samples (paired); numeric-only.

    ``ballasts``: {prefix: (mass [kg], x [m])}.  Returns per-prefix P(in band),
    E|miss| and their standard errors, plus the apogees (key ``apogee:PREFIX``).
    """
    P = spec.sample(int(samples), p_nominal, np.random.default_rng(seed))
    out, flown = {}, {}
    for prefix, (m, x) in ballasts.items():
        P[params.index("ballast_mass")], P[params.index("ballast_x")] = m, x
        key = (float(m), float(x))
        if key not in flown:                               # the same ballast twice flies once
            flown[key] = model.run_batch(P)["apogee_agl"]
        apo = flown[key]
        out.update(_miss_stats(apo, target_agl, band, f"check_{prefix}"))
        out[f"apogee:{prefix}"] = apo
    return out


def solve_robust_ballast(setup, target, spec, *, objective: str = "in_band", band: float = 50.0,
                         samples: int = 40, seed: int | None = None, check_samples: int = 1000,
                         design: str = "latin_hypercube", min_gain_t: float | None = None,
                         select_samples: int = 200,
                         check_seed: int | None = None, free_position: bool = False,
                         mass_max: float | None = None, x_range=None, ballast_x: float | None = None,
                         min_rail_speed: float | None = None, min_margin: float | None = None,
                         parameters: Mapping[str, float] | None = None,
                         ipopt_options: Mapping | None = None) -> RobustBallastSolution:
    """Ballast (and position) that maximise P(|apogee - target| <= band) or minimise E|miss|.

    Parameters
    ----------
    setup : FlightSetup
    target : str, float or Target
    spec : DispersionSpec or path-like
        The dispersions (``dispersions.toml``).
    objective : "in_band" or "expected_abs_miss"
    band : float [m]
        Half-width of the scoring band (reported for both objectives).
    samples : int
        SAA samples N (common random numbers: one fixed set).
    seed : int, optional
        Seed of the SAA samples (default: the spec's seed, else 0).
    check_samples : int
        Fresh samples of the independent check of both ballasts (0: no check).
    check_seed : int, optional
        Seed of the check (default: ``seed + 1``, never the SAA seed).
    select_samples : int
        Candidate validation (Kleywegt, Shapiro & Homem-de-Mello, SIAM J. Optim.
        12(2), 2002: judge SAA candidates on an independent sample): the SAA
        optimum and the nominal ballast fly these fresh samples (seed ``seed + 2``,
        neither the SAA's nor the check's); the nominal ballast is kept unless the
        SAA optimum scores better on them (paired).  With N = 40 the SAA optimum
        can be far off on a spec centred on the nominal flight (Calisto, the spec's
        seed: 1.577 -> 1.295 kg, in-sample P 0.375 -> 0.525, t = 2.3, while a
        5,000-sample sweep puts every mass below 1.36 kg at least 0.05 worse).
        0: no validation.
    min_gain_t : float or None
        If given, the SAA optimum replaces the nominal ballast only if its
        in-sample improvement of the smoothed objective is significant: the
        paired t statistic over the N samples (mean per-sample improvement over
        its standard error, always reported as ``saa_gain_t``) at least
        ``min_gain_t`` (cf. Mak, Morton & Wood, Oper. Res. Lett. 24, 1999, on
        judging an SAA solution by its sampling error).  Off by default: near a
        flat optimum (Calisto's centred spec) the 40-sample SAA optimum is mostly
        noise (t 0.2-0.3 measured) and scores slightly worse than the nominal
        ballast on fresh samples, but the near-binary in-band terms give the test
        little power: Kestrel's real gain (+0.13 in P on 5,000 fresh samples) came
        with t = 1.3-1.7, so a bar of 2 would have discarded it.
    design : "latin_hypercube" or "independent"
        How the SAA samples are drawn (the check's are always independent).  A
        Latin hypercube (:meth:`DispersionSpec.sample_lhs`) gives the SAA objective far
        less sampling noise for the same N: the apogee is nearly additive in the
        dispersed parameters (a linear fit explains 99 % of its variance on Calisto,
        ``benchmarks/robust_sweep.py``), and stratifying each marginal removes that
        part of the variance (Stein 1987); for SAA with Latin hypercube samples see
        Homem-de-Mello & Bayraksan, Surveys in OR and Management Science 19(1), 2014.
    free_position, mass_max, x_range, ballast_x, parameters
        As in :func:`~ironbark_opt.optimise.ballast.solve_ballast`.
    min_rail_speed : float, optional [m/s]
    min_margin : float, optional [calibers]
        The nominal ballast's limits, imposed on the robust ballast the same way:
        on the flight of the nominal parameters (rail-exit speed, static margin
        at rail exit), as IPOPT constraints with exact gradients.
    ipopt_options : mapping, optional

    Returns
    -------
    RobustBallastSolution
    """
    from ironbark_opt.analysis.distributions import DispersionSpec, load_spec
    from ironbark_opt.flight import flight_model, simulate
    from ironbark_opt.optimise.ballast import _bounds, solve_ballast

    if design not in DESIGNS:
        raise InputError(f"design must be one of {', '.join(DESIGNS)}, got {design!r}", field="design")
    if objective not in OBJECTIVES:
        raise InputError(f"objective must be one of {', '.join(OBJECTIVES)}, got {objective!r}", field="objective")
    if not (isinstance(band, (int, float)) and math.isfinite(band) and band > 0):
        raise InputError(f"band must be a positive number [m], got {band!r}", field="band")
    for name, value, least in (("samples", samples, 8), ("check_samples", check_samples, 0),
                               ("select_samples", select_samples, 0)):
        if isinstance(value, bool) or not isinstance(value, (int, np.integer)) or value < least:
            raise InputError(f"{name} must be an integer >= {least}, got {value!r}", field=name)
    if not isinstance(spec, DispersionSpec):
        spec = load_spec(spec)
    for name in ("ballast_mass", "ballast_x"):
        if name in spec.parameters:
            raise InputError(f"the spec disperses {name}, which robust ballast chooses", source=spec.source,
                             field=f"parameters.{name}")
    seed = int(spec.seed if seed is None and spec.seed is not None else (seed or 0))
    check_seed = seed + 1 if check_seed is None else int(check_seed)
    if check_seed == seed:
        raise InputError("the check needs fresh samples: check_seed must differ from seed", field="check_seed")
    select_seed = next(k for k in (seed + 2, seed + 3, seed + 4) if k not in (seed, check_seed))
    t_start = time.perf_counter()
    nominal = solve_ballast(setup, target, free_position=free_position, mass_max=mass_max, x_range=x_range,
                            ballast_x=ballast_x, min_rail_speed=min_rail_speed, min_margin=min_margin,
                            parameters=parameters)
    t_nominal = time.perf_counter() - t_start
    nv = nominal.values
    target_agl = nv["target_agl_m"]
    m_max, x_bay = _bounds(setup, mass_max, x_range)
    model = flight_model(setup)
    p_nom = np.array([nominal.parameters[n] for n in params.NAMES])
    draw = spec.sample_lhs if design == "latin_hypercube" else spec.sample
    P = draw(int(samples), p_nom, np.random.default_rng(seed))
    start = model.run_batch(P)
    width = silverman_width(start["apogee_agl"])
    apogees = SampleApogees(model, P, start["t_rail"], start["t_apogee"], free_position)

    def fn(w):
        z, dz = apogees(w)
        f, df = smoothed_objective(z, target_agl, objective, band, width)
        return f, dz @ df

    # the nominal flight (the nominal parameters at ballast w): the user's limits and the report
    flown = model.run_batch(p_nom[:, None])
    nominal_flight = SampleApogees(model, p_nom[:, None], flown["t_rail"], flown["t_apogee"], free_position)
    limits = [(i, float(v)) for i, v in enumerate((min_rail_speed, min_margin)) if v is not None]

    def constraints(w):
        q, dq = nominal_flight.rail(w)
        rows = [i for i, _ in limits]
        return q[rows, 0], dq[rows, :, 0]

    w0 = [nv["ballast_kg"]] + ([nv["ballast_x_m"]] if free_position else [])
    lbw = [0.0] + ([x_bay[0]] if free_position else [])
    ubw = [m_max] + ([x_bay[1]] if free_position else [])
    obj = _Objective(fn, len(w0))
    W = ca.MX.sym("w", len(w0))
    nlp = {"x": W, "f": obj(W)}
    if limits:
        con = _Objective(constraints, len(w0), "robust_limits", m=len(limits))
        nlp["g"] = con(W)
    opts = {"ipopt.print_level": 0, "print_time": False, "ipopt.sb": "yes",
            "ipopt.hessian_approximation": "limited-memory", "ipopt.tol": 1e-6, "ipopt.max_iter": 50}
    opts.update({(k if k.startswith("ipopt.") else f"ipopt.{k}"): v for k, v in dict(ipopt_options or {}).items()})
    solver = ca.nlpsol("robust_ballast", "ipopt", nlp, opts)
    bounds = dict(lbg=[v for _, v in limits], ubg=[np.inf] * len(limits)) if limits else {}
    sol = solver(x0=w0, lbx=lbw, ubx=ubw, **bounds)
    stats = solver.stats()
    w_opt = np.array(sol["x"]).ravel()
    if not stats["success"] and stats["return_status"] not in ("Solved_To_Acceptable_Level",):
        raise SolverError(f"robust ballast: IPOPT did not converge ({stats['return_status']})")
    a_nom, _ = apogees(w0)
    a_saa, _ = apogees(w_opt)
    t_gain = gain_t(smoothed_terms(a_nom, target_agl, objective, band, width)[0],
                    smoothed_terms(a_saa, target_agl, objective, band, width)[0])
    kept_by = "t" if min_gain_t is not None and not t_gain >= min_gain_t else None
    w_saa = w_opt
    x_nom, x_saa = float(nv["ballast_x_m"]), float(w_opt[1]) if free_position else float(nv["ballast_x_m"])
    selection = {}
    if kept_by is None and select_samples:
        # candidate validation: the SAA optimum against the nominal ballast on fresh samples (paired)
        sel = check_ballasts(model, spec, p_nom, {"nominal_": (w0[0], x_nom), "": (float(w_opt[0]), x_saa)},
                             target_agl, band, select_samples, select_seed)
        d_n, d_r = sel["apogee:nominal_"] - target_agl, sel["apogee:"] - target_agl
        gain_p = (np.abs(d_r) <= band).astype(float) - (np.abs(d_n) <= band)
        dmiss = np.abs(d_r) - np.abs(d_n)
        n_sel = gain_p.size
        selection = {"select_samples": int(select_samples), "select_seed": int(select_seed),
                     "select_probability_gain": float(gain_p.mean()),
                     "select_probability_gain_stderr": float(gain_p.std(ddof=1) / math.sqrt(n_sel)),
                     "select_expected_abs_miss_change_m": float(dmiss.mean()),
                     "select_expected_abs_miss_change_stderr_m": float(dmiss.std(ddof=1) / math.sqrt(n_sel))}
        better = gain_p.mean() > 0 if objective == "in_band" else dmiss.mean() < 0
        kept_by = None if better else "selection"
    kept_nominal = kept_by is not None
    if kept_nominal:
        w_opt = np.asarray(w0, dtype=float)
    solve_time = time.perf_counter() - t_start
    m_opt = float(w_opt[0])
    x_opt = float(w_opt[1]) if free_position else float(nv["ballast_x_m"])
    a_rob = a_nom if kept_nominal else a_saa
    values = {"ballast_kg": m_opt, "ballast_x_m": x_opt, "nominal_ballast_kg": nv["ballast_kg"],
              "nominal_ballast_x_m": nv["ballast_x_m"], "target_agl_m": target_agl, "band_m": float(band),
              "kernel_width_m": width, "saa_gain_t": t_gain,
              "saa_optimum_ballast_kg": float(w_saa[0]),
              "saa_optimum_ballast_x_m": float(w_saa[1]) if free_position else float(nv["ballast_x_m"]),
              "saa_smoothed_objective": smoothed_objective(a_rob, target_agl, objective, band, width)[0],
              "saa_nominal_smoothed_objective": smoothed_objective(a_nom, target_agl, objective, band, width)[0],
              "saa_probability_in_band": float(np.mean(np.abs(a_rob - target_agl) <= band)),
              "saa_nominal_probability_in_band": float(np.mean(np.abs(a_nom - target_agl) <= band)),
              "saa_expected_abs_miss_m": float(np.mean(np.abs(a_rob - target_agl))),
              "saa_nominal_expected_abs_miss_m": float(np.mean(np.abs(a_nom - target_agl))),
              "solve_time_s": solve_time, "nominal_solve_time_s": t_nominal,
              "ipopt_iterations": int(stats.get("iter_count", 0)), "sample_evaluations": apogees.evaluations,
              "check_samples": int(check_samples), **selection}
    # the nominal parameters flown at both ballasts by simulate (as the nominal solution reports them)
    p_rob = p_nom.copy()
    p_rob[params.index("ballast_mass")], p_rob[params.index("ballast_x")] = m_opt, x_opt
    flown = simulate(setup, p=p_rob, model=model).summary_values
    for key in _FLOWN:
        values[key] = float(flown[key])
        values[f"nominal_{key}"] = float(nv["resimulated_apogee_agl_m" if key == "apogee_agl_m" else key])
    for name, value in (("min_rail_speed_mps", min_rail_speed), ("min_margin_cal", min_margin)):
        if value is not None:
            values[name] = float(value)
    if check_samples:
        chk = check_ballasts(model, spec, p_nom, {"nominal_": (w0[0], nv["ballast_x_m"]), "": (m_opt, x_opt)},
                             target_agl, band, check_samples, check_seed)
        a_n, a_r = chk.pop("apogee:nominal_"), chk.pop("apogee:")
        values.update(chk)
        gain = (np.abs(a_r - target_agl) <= band).astype(float) - (np.abs(a_n - target_agl) <= band)
        dmiss = np.abs(a_r - target_agl) - np.abs(a_n - target_agl)
        n = a_r.size
        values.update(check_probability_gain=float(gain.mean()),
                      check_probability_gain_stderr=float(gain.std(ddof=1) / math.sqrt(n)) if n > 1 else 0.0,
                      check_expected_abs_miss_change_m=float(dmiss.mean()),
                      check_expected_abs_miss_change_stderr_m=float(dmiss.std(ddof=1) / math.sqrt(n)) if n > 1
                      else 0.0,
                      check_time_s=time.perf_counter() - t_start - solve_time)
    return RobustBallastSolution(name=setup.name, motor=getattr(setup.motor, "designation", "motor"),
                                 objective=objective, samples=int(samples), seed=seed, check_seed=check_seed,
                                 values=values, nominal=nominal, design=design, kept_nominal=kept_nominal,
                                 kept_by=kept_by)
