"""Analysis of a flight: exact sensitivities and Monte Carlo dispersion.

- :mod:`~ironbark_opt.analysis.sensitivity` — ``sensitivities(setup, ...)
  -> Sensitivities``: CasADi AD derivatives of apogee, apogee time, rail-exit
  and maximum speed with respect to every named parameter, and of the
  optimal ballast (parametric sensitivity of the ballast solve).
- :mod:`~ironbark_opt.analysis.distributions` — ``load_spec(path) ->
  DispersionSpec``: the ``dispersions.toml`` format (normal, uniform, from a
  file; seeded).
- :mod:`~ironbark_opt.analysis.montecarlo` — ``montecarlo(setup, spec,
  samples, ...) -> Dispersion``: the trajectory Functions mapped over
  samples; apogee/drift/landing statistics, target-band probability.
- :mod:`~ironbark_opt.analysis.plots` — histogram, landing ellipse,
  tornado chart.
"""
from ironbark_opt.analysis.distributions import DispersionSpec, load_spec, spec_from_dict
from ironbark_opt.analysis.montecarlo import Dispersion, montecarlo

__all__ = ["DispersionSpec", "Dispersion", "Sensitivities", "load_spec", "montecarlo", "sensitivities",
           "spec_from_dict"]


def __getattr__(name):
    # the sensitivity module on first use (PEP 562): a Monte Carlo run does not need it
    if name in ("Sensitivities", "sensitivities"):
        from ironbark_opt.analysis import sensitivity
        return getattr(sensitivity, name)
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
