"""A rectangular wing in supersonic flow: the tip's lift loss of the thin-wing model
(``supersonic.THIN_WING``) against exact linear theory.

The wing: two rectangular fins (chord 0.1 m, unswept leading and trailing edges,
streamwise tips, 0.5 mm double-wedge section) on a thin body (radius 1 mm), meshed by
:func:`panair.mesh.mesh_rocket`; CN-alpha of the fin panels on their planform area
(aspect ratio A of the two fins joined), against the rectangular wing of linear
theory (Bonney, J. Aero. Sci. 14, 1947; e.g. Jones & Cohen, *High Speed Wing Theory*,
1960): CL-alpha = 4/B (1 - 1 / (2 B A)) for B A >= 1 (the tip Mach cones do not meet
on the wing); the loss against Ackeret's 4/B is the region of each tip's Mach cone,
where the upper and lower flows communicate around the side edge.

A fin face's sources act on their own side only (:func:`panair.solver.supersonic._fin_sides`),
so with nothing outboard of the tip the fin's plane is a wall there and the tip keeps
most of the two-dimensional lift.  Measured, the thin-wing model of session 12 (no
tip diaphragm): Mach 1.6 / 2.0, A = 2: +8.8 / +6.1 %; A = 1: +24.3 / +14.5 % (of
the tip loss 1/(2 B A) only a third to a half is recovered).  With the tip diaphragms
(:func:`panair.solver.supersonic_diaphragm.tip_sheets`): +2.8 / +2.4 %, A = 1 +6.8 /
+4.3 %, the half and the full model alike (Mach 2, A = 1: 1.713 both); Mach 1.6, A = 1
on meshes 0.7 ... 2 x: +8.3 ... +7.1 % (with a 1 mm section), the remainder of the
constant-strength cells beside the edge's square-root loading.
"""
import numpy as np
import pytest

from panair.mesh import BodyGeometry, FinGeometry, MeshOptions, RocketGeometry, mesh_rocket
from panair.solver import build_panels

from fin_loads import fin_panels_cn_alpha

CHORD, R_BODY, THICK, X_ROOT = 0.1, 0.001, 0.0005, 0.1


def bonney_cl_alpha(mach, aspect):
    """Rectangular wing, linear theory, B A >= 1 [1/rad] (Bonney 1947)."""
    b = np.sqrt(mach**2 - 1.0)
    assert b * aspect >= 1.0
    return 4.0 / b * (1.0 - 1.0 / (2.0 * b * aspect))


@pytest.fixture
def thin_wing(monkeypatch):
    from panair.solver import supersonic
    monkeypatch.setattr(supersonic, "THIN_WING", True)
    return supersonic


def wing_cn_alpha(mach, span, symmetric=True):
    """CN-alpha of the fin panels [1/rad] on their planform area (alpha 0 and 2 deg)."""
    body = BodyGeometry(np.array([X_ROOT - 0.05, X_ROOT - 0.03, X_ROOT + CHORD]),
                        np.array([0.0, R_BODY, R_BODY]))
    fins = (FinGeometry(2, CHORD, CHORD, span, 0.0, X_ROOT, THICK, roll=np.pi / 2),)
    opt = MeshOptions(n_theta=16, n_nose=4, body_spacing=4.0).for_mach(mach)
    p = build_panels(mesh_rocket(RocketGeometry(body, fins), symmetric=symmetric, options=opt),
                     symmetric=symmetric)
    return fin_panels_cn_alpha(p, mach, 2.0 * span * CHORD, CHORD)


@pytest.mark.parametrize("mach, span, tol", [(1.6, 0.1, 0.05), (2.0, 0.1, 0.05),
                                             (2.0, 0.05, 0.06), (1.6, 0.05, 0.09)])
def test_rectangular_wing_tip_loss(thin_wing, mach, span, tol):
    # the session-12 model (no tip diaphragm) is +8.8 / +6.1 / +14.5 / +24.3 % here
    cna, s = wing_cn_alpha(mach, span)
    ref = bonney_cl_alpha(mach, 2.0 * span / CHORD)
    assert s.tip_cells > 0
    assert abs(cna / ref - 1.0) < tol, (cna, ref)


def test_half_and_full_model_agree(thin_wing):
    half, _ = wing_cn_alpha(2.0, 0.05, symmetric=True)
    full, _ = wing_cn_alpha(2.0, 0.05, symmetric=False)
    assert abs(full / half - 1.0) < 1e-3


def test_default_model_has_no_tip_cells():
    _, s = wing_cn_alpha(2.0, 0.1)
    assert s.tip_cells == 0 and s.diaphragm_cells == 0


def test_tip_diaphragms_alone_in_the_default_model(monkeypatch):
    """supersonic.TIP_DIAPHRAGM_DEFAULT: the tip cells without THIN_WING's leading-edge
    diaphragms, the half model the full one (measured 2.5e-5 relative, Mach 2, A = 1).
    Off by default, it over-corrects with the default model's partner leak: this wing
    measured -24.4 / -17.6 % of Bonney's value at Mach 1.6 / 2.0, A = 1 (see the flag)."""
    from panair.solver import supersonic
    monkeypatch.setattr(supersonic, "TIP_DIAPHRAGM_DEFAULT", True)
    half, s = wing_cn_alpha(2.0, 0.05, symmetric=True)
    full, _ = wing_cn_alpha(2.0, 0.05, symmetric=False)
    assert s.tip_cells > 0 and s.diaphragm_cells == 0
    assert abs(full / half - 1.0) < 1e-3
