"""Symbolic-safe elementary functions.

Each function here accepts floats, NumPy arrays or CasADi ``SX``/``MX``/``DM``
and dispatches to NumPy or CasADi, so a model written once with these names is
evaluated numerically and built symbolically from the same code.  Anything
else (lists, strings, ``None``) raises a clear ``TypeError`` instead of an
obscure failure deep inside CasADi.
"""
from __future__ import annotations

import casadi as ca
import numpy as np

_CASADI_TYPES = (ca.SX, ca.MX, ca.DM)
_NUMERIC_TYPES = (int, float, np.ndarray, np.number, np.bool_)


def is_symbolic(*xs) -> bool:
    """True if any argument is a CasADi ``SX``/``MX``/``DM`` object."""
    for x in xs:
        if isinstance(x, _CASADI_TYPES):
            return True
        if not isinstance(x, _NUMERIC_TYPES):
            raise TypeError(
                f"expected a number, a NumPy array or a CasADi SX/MX/DM, got {type(x).__name__}")
    return False


def _two(name_np, name_ca):
    fnp = getattr(np, name_np)
    fca = getattr(ca, name_ca)

    def f(a, b):
        return fca(a, b) if is_symbolic(a, b) else fnp(a, b)
    f.__name__ = name_ca
    f.__doc__ = f"Symbolic-safe ``{name_ca}`` (NumPy ``{name_np}``)."
    return f


def _one(name_np, name_ca):
    fnp = getattr(np, name_np)
    fca = getattr(ca, name_ca)

    def f(a):
        return fca(a) if is_symbolic(a) else fnp(a)
    f.__name__ = name_ca
    f.__doc__ = f"Symbolic-safe ``{name_ca}`` (NumPy ``{name_np}``)."
    return f


sqrt = _one("sqrt", "sqrt")
exp = _one("exp", "exp")
log = _one("log", "log")
log10 = _one("log10", "log10")
sin = _one("sin", "sin")
cos = _one("cos", "cos")
tan = _one("tan", "tan")
atan = _one("arctan", "atan")
tanh = _one("tanh", "tanh")
fabs = _one("abs", "fabs")
atan2 = _two("arctan2", "atan2")
fmax = _two("maximum", "fmax")
fmin = _two("minimum", "fmin")
power = _two("power", "power")


def sin_angle(alpha):
    """``sin(alpha)``; symbolic-safe.  For a CasADi SX ``alpha = atan2(y, x)`` (the
    flight's angle of attack) it is ``y / sqrt(x^2 + y^2)``, the same number to
    rounding without evaluating atan2 and sin (in the RK4 step the angle itself is then
    no longer needed: ~7 % of a compiled coast step)."""
    if isinstance(alpha, ca.SX) and alpha.is_scalar() and alpha.is_op(ca.OP_ATAN2):
        y, x = alpha.dep(0), alpha.dep(1)
        return y / ca.sqrt(x * x + y * y)
    return sin(alpha)


def cos_angle(alpha):
    """``cos(alpha)``; symbolic-safe, as :func:`sin_angle` (``x / sqrt(x^2 + y^2)`` for a
    CasADi SX ``alpha = atan2(y, x)``)."""
    if isinstance(alpha, ca.SX) and alpha.is_scalar() and alpha.is_op(ca.OP_ATAN2):
        y, x = alpha.dep(0), alpha.dep(1)
        return x / ca.sqrt(x * x + y * y)
    return cos(alpha)


def if_else(cond, a, b):
    """Symbolic-safe ``cond ? a : b`` (evaluates both branches)."""
    if is_symbolic(cond, a, b):
        return ca.if_else(cond, a, b)
    return np.where(cond, a, b)


def clip(x, lo, hi):
    """Symbolic-safe clamp of ``x`` to ``[lo, hi]``."""
    return fmin(fmax(x, lo), hi)


def smooth_abs(x, eps: float):
    """sqrt(x^2 + eps^2): |x| with a finite derivative at 0 [same unit as x]."""
    return sqrt(x * x + eps * eps)
