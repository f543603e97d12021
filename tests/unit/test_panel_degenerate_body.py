"""A body the panel method cannot represent is reported, never solved into a table.

OpenRocket's example 'Base drag hack (short-wide).ork' ends its 39.4 mm tube in a flat
base and puts behind it a transition from 0.015 mm out to 39.4 mm (a trick to add base
drag to OpenRocket's own estimate).  Meshed as a body of revolution it pinches to almost
nothing; its near-zero panels made the subsonic influence matrix singular and the build
wrote a table with |Cp| up to 1e13, CA 6e9 and a CN at zero alpha (exit 0), which then
crashed the simulation.  Now (1) ``from_rocket`` refuses the pinch, naming the station,
and (2) the subsonic solver reports a singular pressure (|Cp| > CP_MAX) on any mesh that
gets that far.  (Session 21: the .ork reader recognises that example's transition as
OpenRocket's 'base drag hack' and leaves it out, tests/unit/test_ork_base_drag_hack.py;
the pinched body is rebuilt here with the transition put back.)"""
from pathlib import Path

import numpy as np
import pytest

from ironbark_opt.errors import InputError, SolverError
from ironbark_opt.rocket import BodyTube, NoseCone, Rocket, Transition
from panair.geometry_adapter import from_rocket
from panair.mesh import MeshOptions, mesh_rocket
from panair.solver import build_panels, make_solver
from panair.solver.subsonic import CP_MAX

R = 0.03937
ORK = Path(__file__).parents[1] / "data" / "ork" / "Base drag hack (short-wide).ork"


def _pinched_rocket(fore_radius):
    return Rocket("pinched", [
        NoseCone(shape="elliptical", length=0.0454, radius=R, x=0.0),
        BodyTube(length=0.1211, radius=R, x=0.0454),
        Transition(shape="conical", length=0.2475, fore_radius=fore_radius, aft_radius=R,
                   x=0.1665)])


def test_pinched_body_is_refused_naming_the_station():
    with pytest.raises(InputError, match=r"narrows to a radius of 0\.015 mm at x = 0\.1665 m"):
        from_rocket(_pinched_rocket(1.5e-5))


def test_a_real_boattail_or_a_waist_is_not_a_pinch():
    # a transition from 40 % of the radius (a steep step, but a body) meshes
    geom = from_rocket(_pinched_rocket(0.4 * R))
    assert geom.body.r.min() == 0.0 and geom.body.r.max() == pytest.approx(R)


def test_singular_subsonic_pressure_is_reported_not_returned(monkeypatch):
    # the example itself, meshed past the adapter's check (its fins over the pinch)
    import panair.geometry_adapter as adapter
    from ironbark_opt.openrocket import read_ork
    from ironbark_opt.openrocket.build import geometry
    monkeypatch.setattr(adapter, "_check_no_pinch", lambda x, r: None)
    real = geometry(read_ork(ORK))
    tube = real.body_components()[-1]
    hack = Transition(shape="conical", length=0.2475, fore_radius=1.5e-5, aft_radius=R,
                      x=tube.x_end)
    geom = from_rocket(Rocket(real.name, list(real.components) + [hack]))
    panels = build_panels(mesh_rocket(geom, symmetric=True, options=MeshOptions()), symmetric=True)
    with pytest.raises(SolverError, match="singular surface pressure") as err:
        make_solver(panels, 0.3, sref=np.pi * R ** 2, lref=2 * R, xref=0.2).solve(np.radians([0.0]))
    print(err.value, f"(CP_MAX {CP_MAX:g})")
