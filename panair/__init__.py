"""Aerodynamic tables from geometry: panel networks, a built-in linearised
potential panel solver, PANAIR (A502) interoperability and sweeps.

Map of the package (all numeric-only):

* :mod:`panair.lawgs` — LaWGS networks (``Network``), read/write.
* :mod:`panair.mesh` — rocket geometry (body of revolution + trapezoidal
  fin sets with real sections) -> networks, half-model option;
  :mod:`panair.geometry_adapter` converts an ``ironbark_opt.rocket.Rocket``.
* :mod:`panair.solver` — the built-in solver: subsonic Morino /
  Prandtl-Glauert (source + doublet, Kutta wakes), supersonic source panels
  with the Mach-cone domain of dependence (bodies without fins).
* :mod:`panair.a502` / :mod:`panair.a502_output` — A502 deck writer,
  external-PANAIR runner, parsers of ``ffmf``, ``panair.out``, ``agps``,
  ``panair.err``.
* :mod:`panair.sweep` — Mach x alpha sweeps -> ``AeroTable`` (pressure +
  friction + base), :mod:`panair.bridge` — transonic fairing.
* :mod:`panair.vtk`, :mod:`panair.plots` — ParaView export, pictures.

Tables for the example rockets are regenerated with
``ironbark aero build examples/<rocket>/<rocket>.toml`` (writes
``tables/<rocket name>.csv`` + ``.json``).
"""
