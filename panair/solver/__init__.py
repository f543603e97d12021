"""Built-in linearised-potential panel solver.

* :mod:`.influence` — constant source / doublet panel influence (Laplace).
* :mod:`.panels` — networks -> panels, neighbours, wake (Kutta) connectivity.
* :mod:`.pressure` — surface velocity, pressure rules, force integration.
* :mod:`.subsonic` — Prandtl-Glauert Morino solver, one LU per Mach number.

* :mod:`.supersonic_influence`, :mod:`.supersonic` — source panels with the
  Mach-cone domain of dependence, Mach 1.2 ... 5, bodies without fins.

Transonic Mach numbers and supersonic configurations with fins raise
:class:`ironbark_opt.errors.SolverError` (use an external PANAIR via
:mod:`panair.a502`): never a silently wrong number.
"""
from __future__ import annotations

import numpy as np

from ironbark_opt.errors import SolverError

from .panels import PanelSet, build_panels
from .subsonic import MACH_SUBSONIC_MAX, PanelResult, SubsonicSolver
from .supersonic import MACH_SUPERSONIC_MAX, MACH_SUPERSONIC_MIN, SupersonicSolver

__all__ = ["build_panels", "PanelSet", "SubsonicSolver", "SupersonicSolver", "PanelResult",
           "solve_networks", "make_solver", "MACH_SUBSONIC_MAX", "MACH_SUPERSONIC_MIN",
           "MACH_SUPERSONIC_MAX"]


def make_solver(panels: PanelSet, mach: float, *, sref: float, lref: float, xref: float = 0.0,
                pressure_rule: str = "second-order", mirror: bool = False):
    """Factorised solver for one Mach number (numeric-only).

    Parameters
    ----------
    panels : PanelSet
    mach : float [-]
    sref : float [m^2], lref : float [m], xref : float [m]
    pressure_rule : str
    mirror : bool
        A full model that is its own mirror image in a plane through the axis solved on
        half its panels (see SubsonicSolver, SupersonicSolver; in the x-z plane flows
        without sideslip only).

    Raises
    ------
    SolverError
        Transonic Mach numbers; supersonic ones with fins (lifting surfaces);
        superinclined panels.
    """
    if MACH_SUBSONIC_MAX < mach < MACH_SUPERSONIC_MIN:
        raise SolverError(
            f"Mach {mach}: transonic; linearised potential flow has no valid solution between "
            f"Mach {MACH_SUBSONIC_MAX} and {MACH_SUPERSONIC_MIN} (tables bridge this range, "
            "see panair.bridge)")
    if mach >= MACH_SUPERSONIC_MIN:
        return SupersonicSolver(panels, mach, sref=sref, lref=lref, xref=xref,
                                pressure_rule=pressure_rule, mirror=mirror)
    return SubsonicSolver(panels, mach, sref=sref, lref=lref, xref=xref,
                          pressure_rule=pressure_rule, mirror=mirror)


def solve_networks(networks, mach: float, alpha, *, sref: float, lref: float,
                   xref: float = 0.0, symmetric: bool = False, beta=0.0,
                   pressure_rule: str = "second-order") -> list[PanelResult]:
    """Mesh networks -> pressure forces at one Mach number and several angles.

    Parameters
    ----------
    networks : sequence of panair.lawgs.Network
    mach : float [-]
    alpha : float or array [rad]
    sref : float [m^2]; lref : float [m]; xref : float [m] (aft of nose tip)
    symmetric : bool
        Half model (y >= 0) with the x-z plane as symmetry plane.
    beta : float or array [rad]
    pressure_rule : str

    Returns
    -------
    list of PanelResult (one per angle).
    """
    panels = build_panels(networks, symmetric=symmetric)
    solver = make_solver(panels, mach, sref=sref, lref=lref, xref=xref,
                         pressure_rule=pressure_rule)
    return solver.solve(np.atleast_1d(alpha), beta)
