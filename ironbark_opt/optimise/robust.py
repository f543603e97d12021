"""Robust ballast: the ballast that scores best under the day's dispersion.

``solve_ballast`` puts the *nominal* apogee on the target; under a
dispersion spec the apogee is a random variable ``a(w, xi)`` of the ballast
``w = (m_b[, x_b])`` and the dispersed parameters ``xi``.  Competitions
score the miss, so this module maximises

    P(|a(w, xi) - target| <= B)          (objective "in_band")

or minimises ``E|a(w, xi) - target|``     (objective "expected_abs_miss")

by the sample-average approximation (SAA): one fixed set of ``N`` samples
``xi_1..xi_N`` (common random numbers: every ``w`` is judged on the same
samples, so the objective is a deterministic smooth function of ``w``),
minimised from the nominal solution (Shapiro, Dentcheva & Ruszczynski,
*Lectures on Stochastic Programming: Modeling and Theory*, SIAM 2009, ch. 5,
the SAA method and its consistency).  The ``N`` samples are a Latin hypercube
of the spec by default: with N = 40 independent draws the SAA's optimum moves
with the draw's own location (on Calisto's spec it picks a ballast worse than
the nominal by 0.015 in P(in band) on average, ``benchmarks/robust_sweep.py``),
and stratifying each marginal removes most of that noise for an apogee that
is nearly additive in the dispersed parameters.

The SAA optimum is then validated (Kleywegt, Shapiro & Homem-de-Mello, SIAM
J. Optim. 12(2), 2002): it and the nominal ballast fly fresh samples, and the
nominal ballast is kept unless the optimum scores better on them.

The parts:

- :mod:`~ironbark_opt.optimise.robust_objective`: the kernel-smoothed
  objective, the kernel width, the statistics;
- :mod:`~ironbark_opt.optimise.sample_apogees`: every sample's apogee and its
  exact gradient in ``w`` from one call of the model's mapped ascent Function
  and its forward derivative (:mod:`~ironbark_opt.optimise.robust_events` for
  samples that Function does not fly);
- :mod:`~ironbark_opt.optimise.saa_trust_region`: IPOPT on per-sample models
  of the apogees refreshed by exact evaluations (a trust region), so the
  flights are evaluated 2-4 times per solve (10-11 Newton evaluations of
  the phase formulation, plus the nominal column, with IPOPT on the flights);
- :mod:`~ironbark_opt.optimise.robust_check`: the fresh-sample selection and
  check;
- :mod:`~ironbark_opt.optimise.robust_solution`: the result.

Numeric-only.
"""
from __future__ import annotations

import math
import time
from typing import Mapping

import numpy as np

from ironbark_opt import params
from ironbark_opt.errors import InputError
from ironbark_opt.optimise.robust_check import check_ballasts, paired_gain, select
from ironbark_opt.optimise.robust_objective import (OBJECTIVES, gain_t, silverman_width, smoothed_objective,
                                                    smoothed_terms, symbolic_terms)
from ironbark_opt.optimise.robust_solution import RobustBallastSolution
from ironbark_opt.optimise.sample_apogees import SampleApogees

__all__ = ["OBJECTIVES", "DESIGNS", "RobustBallastSolution", "solve_robust_ballast"]

#: how the SAA samples are drawn from the spec
DESIGNS = ("latin_hypercube", "independent")
#: the nominal parameters' flight at each ballast, reported as the nominal ballast solution reports it
_FLOWN = ("apogee_agl_m", "rail_exit_speed_mps", "static_margin_rail_exit_cal", "static_margin_min_cal")
#: the SAA search ends at a model step shorter than this [kg, m]: a tenth of a gram, a tenth of a
#: millimetre (finer than ballast is weighed or placed; 0.02 m of apogee on Calisto)
XTOL = 1e-4


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
        at rail exit), modelled from their exact values and gradients (one more
        column of the mapped evaluation) as constraints of the model problems.
    ipopt_options : mapping, optional
        Passed to IPOPT on the model problems (:mod:`~ironbark_opt.optimise.saa_trust_region`).

    Returns
    -------
    RobustBallastSolution
    """
    from ironbark_opt.analysis.distributions import DispersionSpec, load_spec
    from ironbark_opt.flight import flight_model, simulate
    from ironbark_opt.optimise.ballast import _bounds, solve_ballast
    from ironbark_opt.optimise.saa_trust_region import minimise

    _check_options(objective, design, band, samples, check_samples, select_samples)
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
    limits = [(i, float(v)) for i, v in enumerate((min_rail_speed, min_margin)) if v is not None]
    rows = [i for i, _ in limits]
    t_saa = time.perf_counter()
    # the nominal parameters' flight (the user's limits) rides along as one more column
    apogees = SampleApogees(model, np.hstack([P, p_nom[:, None]]) if limits else P, free_position)
    w0 = np.array([nv["ballast_kg"]] + ([nv["ballast_x_m"]] if free_position else []))
    width = silverman_width(apogees(w0)[0][:samples])

    def evaluate(w):
        z, dz, rail, drail = apogees.events(w)
        return z[:samples], dz[:, :samples], rail[rows, -1], drail[rows, :, -1]

    def terms(a):
        return symbolic_terms(a, target_agl, objective, band, width)

    lower = np.array([0.0] + ([x_bay[0]] if free_position else []))
    upper = np.array([m_max] + ([x_bay[1]] if free_position else []))
    best, _, ipopt_iterations = minimise(evaluate, terms, w0, lower, upper, [v for _, v in limits],
                                         xtol=XTOL, ipopt_options=ipopt_options)
    w_opt = w_saa = best.w
    a_nom, a_saa = evaluate(w0)[0], best.a
    t_gain = gain_t(smoothed_terms(a_nom, target_agl, objective, band, width)[0],
                    smoothed_terms(a_saa, target_agl, objective, band, width)[0])
    kept_by = "t" if min_gain_t is not None and not t_gain >= min_gain_t else None
    x_nom = float(nv["ballast_x_m"])
    x_saa = float(w_opt[1]) if free_position else x_nom
    t_saa = time.perf_counter() - t_saa
    selection = {}
    if kept_by is None and select_samples:
        t_select = time.perf_counter()
        better, selection = select(model, spec, p_nom, (w0[0], x_nom), (float(w_opt[0]), x_saa), target_agl,
                                   band, objective, select_samples, select_seed)
        kept_by = None if better else "selection"
        selection["select_time_s"] = time.perf_counter() - t_select
    kept_nominal = kept_by is not None
    if kept_nominal:
        w_opt = w0
    solve_time = time.perf_counter() - t_start
    m_opt = float(w_opt[0])
    x_opt = float(w_opt[1]) if free_position else x_nom
    a_rob = a_nom if kept_nominal else a_saa
    values = {"ballast_kg": m_opt, "ballast_x_m": x_opt, "nominal_ballast_kg": nv["ballast_kg"],
              "nominal_ballast_x_m": nv["ballast_x_m"], "target_agl_m": target_agl, "band_m": float(band),
              "kernel_width_m": width, "saa_gain_t": t_gain,
              "saa_optimum_ballast_kg": float(w_saa[0]),
              "saa_optimum_ballast_x_m": x_saa,
              "saa_smoothed_objective": smoothed_objective(a_rob, target_agl, objective, band, width)[0],
              "saa_nominal_smoothed_objective": smoothed_objective(a_nom, target_agl, objective, band, width)[0],
              "saa_probability_in_band": float(np.mean(np.abs(a_rob - target_agl) <= band)),
              "saa_nominal_probability_in_band": float(np.mean(np.abs(a_nom - target_agl) <= band)),
              "saa_expected_abs_miss_m": float(np.mean(np.abs(a_rob - target_agl))),
              "saa_nominal_expected_abs_miss_m": float(np.mean(np.abs(a_nom - target_agl))),
              "solve_time_s": solve_time, "nominal_solve_time_s": t_nominal, "saa_time_s": t_saa,
              "ipopt_iterations": ipopt_iterations, "sample_evaluations": apogees.evaluations,
              "check_samples": int(check_samples), **selection}
    # the nominal parameters flown at both ballasts by simulate (as the nominal solution reports them)
    nominal_flown = {key: float(nv["resimulated_apogee_agl_m" if key == "apogee_agl_m" else key])
                     for key in _FLOWN}
    if kept_nominal:                # the nominal solution's own flight of this very ballast
        flown = nominal_flown
    else:
        p_rob = p_nom.copy()
        p_rob[params.index("ballast_mass")], p_rob[params.index("ballast_x")] = m_opt, x_opt
        flown = simulate(setup, p=p_rob, model=model).summary_values
    for key in _FLOWN:
        values[key] = float(flown[key])
        values[f"nominal_{key}"] = nominal_flown[key]
    for name, value in (("min_rail_speed_mps", min_rail_speed), ("min_margin_cal", min_margin)):
        if value is not None:
            values[name] = float(value)
    if check_samples:
        chk = check_ballasts(model, spec, p_nom, {"nominal_": (w0[0], x_nom), "": (m_opt, x_opt)},
                             target_agl, band, check_samples, check_seed)
        a_n, a_r = chk.pop("apogee:nominal_"), chk.pop("apogee:")
        values.update(chk)
        values.update(paired_gain(a_n, a_r, target_agl, band, "check_"))
        values["check_time_s"] = time.perf_counter() - t_start - solve_time
    return RobustBallastSolution(name=setup.name, motor=getattr(setup.motor, "designation", "motor"),
                                 objective=objective, samples=int(samples), seed=seed, check_seed=check_seed,
                                 values=values, nominal=nominal, design=design, kept_nominal=kept_nominal,
                                 kept_by=kept_by)


def _check_options(objective, design, band, samples, check_samples, select_samples) -> None:
    """InputError for an option out of its range."""
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
