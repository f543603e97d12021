"""Profile shapes of nose cones and transitions, r(x) for 0 <= x <= L.

All formulas from G. A. Crowell Sr., *The Descriptive Geometry of Nose
Cones* (1996), the usual reference of OpenRocket and RockSim; the equation
names below follow his sections.  Each function takes ``x`` [m] measured
from the pointed end, the shape ``length`` [m] and base ``radius`` [m] and
is numeric (NumPy) only.
"""
from __future__ import annotations

import numpy as np

from ironbark_opt.errors import InputError

#: shape name -> (canonical shape, fixed parameter or None)
SHAPES = {
    "conical": ("conical", None),
    "tangent_ogive": ("tangent_ogive", None),
    "ogive": ("tangent_ogive", None),
    "secant_ogive": ("secant_ogive", None),
    "elliptical": ("elliptical", None),
    "parabolic": ("parabolic", None),
    "power": ("power", None),
    "haack": ("haack", None),
    "von_karman": ("haack", 0.0),
    "ld_haack": ("haack", 0.0),
    "lv_haack": ("haack", 1.0 / 3.0),
}

#: default and allowed range of ``shape_parameter`` per canonical shape
PARAMETER_RANGE = {
    "parabolic": (1.0, 0.0, 1.0),   # K: 1 = full parabola, 0 = cone
    "power": (0.5, 1e-6, 1.0),      # n: 1 = cone, 0.5 = "1/2 power"
    "haack": (0.0, 0.0, 2.0 / 3.0),  # C: 0 = von Karman, 1/3 = LV-Haack
}


def canonical_shape(shape: str, shape_parameter, ogive_radius, length, radius):
    """Validate a shape name and its parameter; return ``(shape, parameter)``.

    ``parameter`` is K (parabolic), n (power), C (Haack), the ogive radius
    [m] (secant ogive) or None.
    """
    key = str(shape).strip().lower().replace(" ", "_").replace("-", "_")
    if key not in SHAPES:
        raise InputError(f"unknown shape '{shape}'; expected one of {', '.join(SHAPES)}",
                         field="shape")
    name, fixed = SHAPES[key]
    if fixed is not None:
        if shape_parameter is not None and abs(shape_parameter - fixed) > 1e-12:
            raise InputError(f"shape '{key}' fixes shape_parameter = {fixed:.6g}",
                             field="shape_parameter")
        return name, fixed
    if name == "secant_ogive":
        if ogive_radius is None:
            raise InputError("a secant ogive needs ogive_radius [m]", field="ogive_radius")
        half_chord = 0.5 * np.hypot(length, radius)
        if not ogive_radius > half_chord:
            raise InputError(f"ogive_radius must exceed half the tip-to-base chord "
                             f"({half_chord:.6g} m), got {ogive_radius}", field="ogive_radius")
        return name, float(ogive_radius)
    if name in PARAMETER_RANGE:
        default, lo, hi = PARAMETER_RANGE[name]
        p = default if shape_parameter is None else float(shape_parameter)
        if not lo <= p <= hi:
            raise InputError(f"shape_parameter of a {name} shape must be in [{lo:g}, {hi:g}], "
                             f"got {p}", field="shape_parameter")
        return name, p
    if shape_parameter is not None:
        raise InputError(f"shape '{key}' takes no shape_parameter", field="shape_parameter")
    return name, None


def shape_radius(shape: str, parameter, x, length: float, radius: float):
    """Radius [m] of a canonical shape at ``x`` [m] from its pointed end (numeric-only)."""
    xi = np.clip(np.asarray(x, dtype=float) / length, 0.0, 1.0)
    L, R = length, radius
    if shape == "conical":
        return R * xi
    if shape == "tangent_ogive":
        # Crowell, "Tangent ogive": rho = (R^2 + L^2) / (2 R)
        rho = (R * R + L * L) / (2.0 * R)
        # the tip is 0 exactly (rounding left -1e-16 there, which the panel mesh refused)
        return np.maximum(np.sqrt(np.maximum(rho * rho - (L - xi * L) ** 2, 0.0)) + R - rho, 0.0)
    if shape == "secant_ogive":
        # Crowell, "Secant ogive": alpha = atan(R/L) - acos(sqrt(L^2+R^2) / (2 rho))
        rho = parameter
        alpha = np.arctan2(R, L) - np.arccos(np.hypot(L, R) / (2.0 * rho))
        return np.maximum(np.sqrt(np.maximum(rho * rho - (rho * np.cos(alpha) - xi * L) ** 2, 0.0))
                          + rho * np.sin(alpha), 0.0)
    if shape == "elliptical":
        # Crowell, "Elliptical": y = R sqrt(1 - (1 - x/L)^2)
        return R * np.sqrt(np.maximum(1.0 - (1.0 - xi) ** 2, 0.0))
    if shape == "parabolic":
        # Crowell, "Parabolic series": y = R (2 x/L - K (x/L)^2) / (2 - K)
        K = parameter
        return R * (2.0 * xi - K * xi * xi) / (2.0 - K)
    if shape == "power":
        # Crowell, "Power series": y = R (x/L)^n
        return R * xi ** parameter
    if shape == "haack":
        # Crowell, "Haack series": theta = acos(1 - 2x/L),
        # y = R/sqrt(pi) sqrt(theta - sin(2 theta)/2 + C sin^3 theta)
        theta = np.arccos(1.0 - 2.0 * xi)
        inner = theta - 0.5 * np.sin(2.0 * theta) + parameter * np.sin(theta) ** 3
        return R / np.sqrt(np.pi) * np.sqrt(np.maximum(inner, 0.0))
    raise InputError(f"unknown canonical shape '{shape}'", field="shape")
