"""The thin-wing model's leading-edge diaphragms (``supersonic.THIN_WING``,
:func:`panair.solver.supersonic_diaphragm.diaphragm_sheets`) on a fin whose root follows
a boattail: the diaphragm must lie ahead of the leading edge.

Over a boattail the fin mesh's chordwise lines follow the body (the root on its surface,
:func:`panair.mesh._fin_networks`), so the trailing edge's spanwise stations in the fin's
mid-plane are not the leading edge's.  Before session 18 the diaphragm took every mid-plane
station as a leading-edge station, with the leading edge there the station's foremost
corner: at a trailing-edge-only station that was the trailing edge, and the diaphragm
ran from the Mach line over the whole chord, inside the fin (a random student rocket,
4 parallelogram fins partly over its boattail, Mach 1.6: 377 diaphragm cells instead of
13, non-physical pressure on 27 % of the area; refused at Mach 1.2 ... 2.3, i.e. local
inclination).  Now the leading edge is the mid-plane corners of forward-facing panels.
"""
import numpy as np
import pytest

from panair.mesh import BodyGeometry, FinGeometry, MeshOptions, RocketGeometry, mesh_rocket
from panair.solver import build_panels, make_solver
from panair.solver.supersonic_diaphragm import diaphragm_sheets

ROOT, SPAN, SWEEP, X_ROOT, R = 0.3, 0.06, 0.09, 0.45, 0.05


def _panels(mach):
    # cylinder to x = 0.7, boattail to r = 0.04 at 0.9: the aft 0.05 m of the root chord
    # and the swept trailing edge (out to 0.84 m at the tip) lie over the boattail
    body = BodyGeometry(np.array([0.0, 0.25, 0.7, 0.9]), np.array([0.0, R, R, 0.04]))
    fins = (FinGeometry(2, ROOT, ROOT, SPAN, SWEEP, X_ROOT, 0.003, roll=np.pi / 2,
                        section="double_wedge"),)
    opt = MeshOptions(n_theta=16, n_nose=4, body_spacing=4.0).for_mach(mach)
    return build_panels(mesh_rocket(RocketGeometry(body, fins), symmetric=True, options=opt),
                        symmetric=True)


@pytest.mark.parametrize("mach", [1.3, 1.6])
def test_diaphragm_lies_ahead_of_the_leading_edge(mach):
    p = _panels(mach)
    fins = np.unique(p.network[p.wake_upper[~p.wake_at_base]])
    d = diaphragm_sheets(p, np.ones(p.n, bool), fins, np.sqrt(mach**2 - 1.0))
    assert d is not None
    c = d.corners
    span_pos = np.linalg.norm(c[..., 1:], axis=-1) - R          # from the cylinder's surface
    x_le = X_ROOT + SWEEP / SPAN * span_pos                      # the planform's leading edge
    assert np.all(c[..., 0] <= x_le + 1e-6), float((c[..., 0] - x_le).max())
    # before the fix: cells out to the trailing edge (x up to ~0.84 m)
    assert float(c[..., 0].max()) <= X_ROOT + SWEEP + 1e-6


def test_thin_wing_solves_fins_over_a_boattail(monkeypatch):
    """The solve the misplaced diaphragm broke: physical pressures, lift of the order of
    the default model's (the thin-wing model has less: tip diaphragms)."""
    from panair.solver import supersonic
    p = _panels(1.6)
    sref = np.pi * R**2
    cn = {}
    for flag in (False, True):
        monkeypatch.setattr(supersonic, "THIN_WING", flag)
        s = make_solver(p, 1.6, sref=sref, lref=2 * R, xref=0.0)
        res = s.solve(np.radians([0.0, 2.0]))                 # raises on non-physical Cp
        cn[flag] = (res[1].CN - res[0].CN) / np.radians(2.0)
    assert 0.5 * cn[False] < cn[True] < 1.05 * cn[False], cn
