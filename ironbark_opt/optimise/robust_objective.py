"""The smoothed sample-average objective of robust ballast, and its statistics.

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

The same terms exist twice in kind only: NumPy here (values and derivatives
for the exact evaluations) and CasADi in :func:`symbolic_terms` (the model
subproblem of :mod:`~ironbark_opt.optimise.saa_trust_region`), both written
from :func:`_terms`, which is symbolic-safe.
"""
from __future__ import annotations

import math

import numpy as np

from ironbark_opt import _math

OBJECTIVES = ("in_band", "expected_abs_miss")
#: ``expected_abs_miss`` is minimised in units of 100 m (order 1 for IPOPT)
MISS_SCALE_M = 100.0


def _Phi(u):
    """Standard normal CDF; symbolic-safe (``Phi(u) = (1 + erf(u / sqrt 2)) / 2``)."""
    if _math.is_symbolic(u):
        import casadi as ca
        return 0.5 * (1.0 + ca.erf(u / math.sqrt(2.0)))
    from scipy.special import ndtr
    return ndtr(u)


def _phi(u):
    """Standard normal density; symbolic-safe."""
    return _math.exp(-0.5 * u * u) / math.sqrt(2.0 * math.pi)


def _terms(d, objective: str, band, h):
    """Per-sample minimised terms of the miss ``d`` [m]; symbolic-safe."""
    if objective == "in_band":
        return -(_Phi((band - d) / h) - _Phi((-band - d) / h))
    u = d / h
    return (d * (2 * _Phi(u) - 1) + 2 * h * _phi(u)) / MISS_SCALE_M


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
        return _terms(d, objective, band, h), (_phi(hi) - _phi(lo)) / h
    return _terms(d, objective, band, h), (2 * _Phi(d / h) - 1) / MISS_SCALE_M


def symbolic_terms(apogee, target, objective: str, band, width):
    """The terms of :func:`smoothed_terms` as a CasADi expression of ``apogee`` (SX/MX)."""
    return _terms(apogee - target, objective, band, width)


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


def miss_stats(apogee, target, band, prefix) -> dict:
    """P(|apogee - target| <= band), E|miss| [m] and their standard errors, keys with ``prefix``."""
    d = np.abs(np.asarray(apogee) - target)
    inside = (d <= band).astype(float)
    n = d.size
    p = float(inside.mean())
    return {f"{prefix}probability_in_band": p,
            # binomial standard error sqrt(p (1 - p) / n); standard error of a mean s / sqrt(n)
            f"{prefix}probability_in_band_stderr": math.sqrt(p * (1 - p) / n),
            f"{prefix}expected_abs_miss_m": float(d.mean()),
            f"{prefix}expected_abs_miss_stderr_m": float(d.std(ddof=1) / math.sqrt(n))}


def paired_change(apogee_nominal, apogee_robust, target, band) -> tuple[np.ndarray, np.ndarray]:
    """Per-sample (change of the in-band indicator, change of |miss| [m]) from the nominal
    to the robust ballast on the same samples (paired)."""
    d_n, d_r = np.abs(np.asarray(apogee_nominal) - target), np.abs(np.asarray(apogee_robust) - target)
    return (d_r <= band).astype(float) - (d_n <= band), d_r - d_n


def mean_and_stderr(values) -> tuple[float, float]:
    """(mean, standard error of the mean; 0 for one value)."""
    v = np.asarray(values, dtype=float)
    return float(v.mean()), float(v.std(ddof=1) / math.sqrt(v.size)) if v.size > 1 else 0.0
