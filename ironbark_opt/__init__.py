"""Ironbark-Opt: apogee prediction and launch-day ballast/motor optimisation.

Public names are re-exported explicitly below (imported on first use, so
``import ironbark_opt`` and the CLI start fast).

Map of the package: ``rocket`` (geometry, mass, TOML), ``motors``,
``atmosphere``, ``aero``, ``dynamics`` (the equations of motion, once),
``flight`` (``simulate``), ``optimise`` (ballast, motor choice), ``analysis``
(sensitivities, Monte Carlo), ``openrocket`` (.ork import), ``vehicle``
(file -> ready-to-fly setup); ``panair`` (a sibling package) builds
aerodynamic tables from geometry.
"""
from importlib import import_module

from ironbark_opt.errors import InputError, IronbarkError, NetworkError, OutOfRangeWarning, SolverError

__version__ = "0.1.0"

_EXPORTS = {
    "simulate": "ironbark_opt.flight",
    "Flight": "ironbark_opt.flight",
    "load_setup": "ironbark_opt.vehicle",
    "FlightSetup": "ironbark_opt.dynamics.setup",
    "FlightModel": "ironbark_opt.dynamics.model",
    "solve_ballast": "ironbark_opt.optimise.ballast",
    "BallastSolution": "ironbark_opt.optimise.ballast",
    "choose_motor": "ironbark_opt.optimise.motor_choice",
    "MotorRanking": "ironbark_opt.optimise.motor_choice",
    "sensitivities": "ironbark_opt.analysis.sensitivity",
    "montecarlo": "ironbark_opt.analysis.montecarlo",
    "AeroTable": "ironbark_opt.aero.table",
    "ISA": "ironbark_opt.atmosphere.isa",
    "Profile": "ironbark_opt.atmosphere.profile",
    "gravity": "ironbark_opt.atmosphere.gravity",
    "Motor": "ironbark_opt.motors.base",
    "SolidMotor": "ironbark_opt.motors.solid",
    "load_motor": "ironbark_opt.motors",
    "Rocket": "ironbark_opt.rocket.rocket",
    "load_rocket_toml": "ironbark_opt.rocket.toml_io",
}

__all__ = ["InputError", "IronbarkError", "NetworkError", "OutOfRangeWarning", "SolverError", "__version__",
           *_EXPORTS]


def __getattr__(name):
    if name in _EXPORTS:
        value = getattr(import_module(_EXPORTS[name]), name)
        globals()[name] = value
        return value
    raise AttributeError(f"module 'ironbark_opt' has no attribute {name!r}")
