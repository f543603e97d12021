"""Ironbark-Opt: apogee prediction and launch-day ballast/motor optimisation.

Public names are re-exported explicitly below.
"""
from ironbark_opt.errors import InputError, IronbarkError, NetworkError, OutOfRangeWarning, SolverError

__version__ = "0.1.0"

__all__ = [
    "InputError", "IronbarkError", "NetworkError", "OutOfRangeWarning", "SolverError",
    "__version__",
]
