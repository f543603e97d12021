"""Fresh-sample Monte Carlo of candidate ballasts: the validation that picks between the
SAA optimum and the nominal ballast, and the independent check of the answer.

Both fly the ballasts on the *same* fresh samples (paired: the differences have
far less variance than either estimate), with ``FlightModel.run_batch``, the
Monte Carlo's own path.  Numeric-only.
"""
from __future__ import annotations

import numpy as np

from ironbark_opt import params
from ironbark_opt.optimise.robust_objective import mean_and_stderr, miss_stats, paired_change


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
        out.update(miss_stats(apo, target_agl, band, f"check_{prefix}"))
        out[f"apogee:{prefix}"] = apo
    return out


def paired_gain(apogee_nominal, apogee_robust, target_agl, band, prefix) -> dict:
    """Robust minus nominal on the same samples: the change of P(in band) and of E|miss| [m]
    with their paired standard errors, keys ``{prefix}probability_gain[_stderr]`` and
    ``{prefix}expected_abs_miss_change[_stderr]_m``."""
    gain, dmiss = paired_change(apogee_nominal, apogee_robust, target_agl, band)
    (g, g_se), (dm, dm_se) = mean_and_stderr(gain), mean_and_stderr(dmiss)
    return {f"{prefix}probability_gain": g, f"{prefix}probability_gain_stderr": g_se,
            f"{prefix}expected_abs_miss_change_m": dm, f"{prefix}expected_abs_miss_change_stderr_m": dm_se}


def select(model, spec, p_nominal, nominal, candidate, target_agl, band, objective, samples, seed):
    """(the candidate scores better, the selection's numbers): the SAA optimum ``candidate``
    against the ``nominal`` ballast ((mass [kg], x [m]) each) on ``samples`` fresh samples
    (Kleywegt, Shapiro & Homem-de-Mello, SIAM J. Optim. 12(2), 2002: judge SAA candidates
    on an independent sample)."""
    sel = check_ballasts(model, spec, p_nominal, {"nominal_": nominal, "": candidate}, target_agl, band,
                         samples, seed)
    out = {"select_samples": int(samples), "select_seed": int(seed),
           **paired_gain(sel["apogee:nominal_"], sel["apogee:"], target_agl, band, "select_")}
    better = out["select_probability_gain"] > 0 if objective == "in_band" else \
        out["select_expected_abs_miss_change_m"] < 0
    return better, out
