"""Fin section lift data from files (numeric-only): a lift-curve file and an
airfoil polar, both reduced to the 2-D section lift-curve slope c(M) [1/rad]
that replaces the thin-airfoil ``2 pi / beta`` in the Diederich fin slope of
:func:`ironbark_opt.aero.barrowman.single_fin_cn_alpha` (RocketPy's method
for airfoil fins, ``Fins`` with ``airfoil=``: the polar's slope at zero
angle, Prandtl-Glauert scaled).

- ``lift_curve``: CSV with columns ``mach`` and ``cl_alpha`` [1/rad] (or
  ``cl_alpha_per_deg``): c(M) itself (compressibility included), linearly
  interpolated, held outside the file's Mach range;
- ``airfoil_polar``: CSV with ``alpha_deg`` (or ``alpha_rad``) and ``cl``:
  a0 = the least-squares slope of the points within 5 deg of the smallest
  |alpha| (at least two points), and c(M) = a0 / sqrt(1 - M^2) (Prandtl-Glauert).

Both are used in the subsonic branch (up to the transonic blend); the
supersonic fin slope (Ackeret) is unchanged.
"""
from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from ironbark_opt.errors import InputError

#: half-width of the polar's linear range fitted for the slope [deg]
POLAR_FIT_DEG = 5.0


def _columns(path: Path, field: str) -> dict:
    try:
        text = Path(path).read_text(encoding="utf-8")
    except (OSError, UnicodeDecodeError) as exc:
        raise InputError(f"cannot read the file: {exc}", source=path, field=field) from None
    rows = [ln.strip() for ln in text.splitlines() if ln.strip() and not ln.lstrip().startswith("#")]
    if len(rows) < 3:
        raise InputError("expected a header line and at least two rows", source=path, field=field)
    names = [h.strip().lower() for h in rows[0].split(",")]
    data = []
    for n, ln in enumerate(rows[1:], start=2):
        parts = ln.split(",")
        try:
            vals = [float(p) for p in parts]
        except ValueError:
            raise InputError(f"row {n}: expected numbers, got {ln!r}", source=path, field=field) from None
        if len(vals) != len(names) or not all(math.isfinite(v) for v in vals):
            raise InputError(f"row {n}: expected {len(names)} finite numbers", source=path, field=field)
        data.append(vals)
    arr = np.array(data, float)
    return {k: arr[:, i] for i, k in enumerate(names)}


def read_lift_curve(path, field: str = "lift_curve") -> tuple:
    """``(mach, cl_alpha [1/rad])`` arrays of a lift-curve file (see module docstring)."""
    cols = _columns(path, field)
    if "mach" not in cols or not ({"cl_alpha", "cl_alpha_per_deg"} & set(cols)):
        raise InputError("expected columns mach and cl_alpha [1/rad] (or cl_alpha_per_deg)", source=path,
                         field=field)
    mach = cols["mach"]
    slope = cols["cl_alpha"] if "cl_alpha" in cols else np.degrees(cols["cl_alpha_per_deg"])
    if np.any(np.diff(mach) <= 0) or mach[0] < 0:
        raise InputError("mach must start at >= 0 and increase strictly", source=path, field=field)
    if np.any(slope <= 0):
        raise InputError("cl_alpha must be > 0", source=path, field=field)
    return tuple(map(float, mach)), tuple(map(float, slope))


def read_airfoil_polar(path, field: str = "airfoil_polar") -> float:
    """The section lift-curve slope a0 [1/rad] at zero angle of an airfoil polar."""
    cols = _columns(path, field)
    if "cl" not in cols or not ({"alpha_deg", "alpha_rad"} & set(cols)):
        raise InputError("expected columns alpha_deg (or alpha_rad) and cl", source=path, field=field)
    alpha = np.radians(cols["alpha_deg"]) if "alpha_deg" in cols else cols["alpha_rad"]
    near = np.abs(alpha - alpha[np.argmin(np.abs(alpha))]) <= math.radians(POLAR_FIT_DEG)
    if near.sum() < 2 or np.ptp(alpha[near]) <= 0:
        raise InputError(f"needs at least two angles within {POLAR_FIT_DEG:g} deg of zero", source=path,
                         field=field)
    a0 = float(np.polyfit(alpha[near], cols["cl"][near], 1)[0])
    if not a0 > 0:
        raise InputError(f"the polar's lift-curve slope at zero angle is {a0:.4g} /rad; expected > 0",
                         source=path, field=field)
    return a0


def section_slope(lift) -> object:
    """c(M) [1/rad] (numeric) of a fin set's ``section_lift`` (``("curve", (mach, slope))``
    or ``("polar", a0)``), or None for the thin airfoil."""
    if lift is None:
        return None
    kind, data = lift
    if kind == "curve":
        mach, slope = (np.asarray(a, float) for a in data)
        return lambda M: np.interp(M, mach, slope)
    a0 = float(data)
    return lambda M: a0 / np.sqrt(np.maximum(1.0 - np.asarray(M, float) ** 2, 1e-6))
