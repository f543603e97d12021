"""Transonic bridge: coefficients between the last subsonic and the first
supersonic panel solution.

Linearised potential flow has no valid solution near Mach 1 (Prandtl-
Glauert diverges as 1/sqrt(1 - M^2) and the supersonic kernel as
1/sqrt(M^2 - 1)), so the table is *faired* across the gap.  Model: for
each coefficient and angle of attack, a monotone piecewise-cubic Hermite
interpolant through the solved Mach numbers on both sides (Fritsch &
Carlson, "Monotone piecewise cubic interpolation", SIAM J. Numer. Anal.
17(2), 1980; SciPy's ``PchipInterpolator``): C1-continuous, it passes
through every solved point, and it neither overshoots nor oscillates
between the two sides — the usual engineering fairing of a transonic drag
rise and normal-force peak (e.g. the USAF DATCOM fairs its transonic
region between subsonic and supersonic methods in the same spirit, Finck,
AFWAL-TR-83-3048, sec. 4.1.3).  The bridged region is named in the table
metadata so a user knows it is not a solution.

Numeric-only.
"""
from __future__ import annotations

import numpy as np
from scipy.interpolate import PchipInterpolator

from ironbark_opt.errors import InputError

__all__ = ["transonic_bridge"]


def transonic_bridge(mach_solved, values, mach_out):
    """Fair solved values across the transonic gap.

    Parameters
    ----------
    mach_solved : 1-D array [-]
        Strictly increasing Mach numbers that were solved (subsonic and
        supersonic, at least one each side of the gap, 2 points in all).
    values : ndarray (n_solved, ...) [-]
        Coefficients at those Mach numbers (any trailing shape, e.g. alpha).
    mach_out : 1-D array [-]
        Mach numbers wanted (inside [min, max] of ``mach_solved``).

    Returns
    -------
    ndarray (len(mach_out), ...) [-]
        Equal to ``values`` at solved Mach numbers.
    """
    m = np.asarray(mach_solved, float)
    v = np.asarray(values, float)
    out = np.asarray(mach_out, float)
    if m.ndim != 1 or len(m) < 2 or np.any(np.diff(m) <= 0):
        raise InputError("need >= 2 strictly increasing solved Mach numbers", field="mach")
    if v.shape[0] != len(m):
        raise InputError(f"values have {v.shape[0]} rows for {len(m)} Mach numbers", field="values")
    if out.min() < m[0] - 1e-12 or out.max() > m[-1] + 1e-12:
        raise InputError(f"bridge asked outside the solved range {m[0]}..{m[-1]}", field="mach")
    return PchipInterpolator(m, v, axis=0, extrapolate=False)(np.clip(out, m[0], m[-1]))
