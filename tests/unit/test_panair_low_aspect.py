"""Supersonic lift of a low-aspect-ratio fin pair, alone and on a thick body, against
exact linear theory (the Mach-box method, tests/mach_box.py; tests/unit/test_mach_box.py
checks it against Bonney's and Stewart's closed forms).

The fins: Allen's fin set 10 (NASA/TM-2001-210652; root 0.1524 m, tip 0.0762 m, span
0.0381 m, leading edge swept 63.4 deg, unswept trailing edge): exposed pair aspect ratio
A = 0.67, B A = 0.44 / 0.83 at Mach 1.2 / 1.6, subsonic leading edge, every point of the
fin inside its tip's Mach cone.  Two cases:

* the wing alone (the pair on a 1 mm body): fin panels' CN-alpha on the planform area
  against the Mach box (measured, default model: Mach 1.2 / 1.6 / 2.0 +12.3 / -13.4 /
  -15.1 %; thin-wing model +1.9 / +2.6 / +1.8 %, before its leading-edge diaphragm was
  graded, session 19, -7.1 / -3.6 / -2.4 %; session 18's Mach box, its span then whole
  boxes: -6.3 / -5.3 / -3.3 %);
* the pair on Allen's 3-inch body (r / s = 0.5): the configuration's CN-alpha minus the
  body alone's (the fins and their interference on the body, the body ahead of the fins
  unchanged by causality) against the Mach box's wing alone times the slender-body
  fin-body factor K_W(B) + K_B(W) = (1 + r/s)^2 = 2.25 (Pitts, Nielsen & Kaattari, NACA
  Report 1307, 1957; their supersonic K_B(W) tends to the slender value as B A -> 0, so
  the reference is best at Mach 1.2, B A = 0.44, approximate above).  Subsonic (Mach 0.9)
  the same difference is 4.49 /rad, slender-body theory 4.50.  Measured by part at Mach
  1.2 / 1.6 / 2.0 (session 18), fins + body beside and behind them, per rocket reference
  area: default model 7.93 / 6.87 / 6.21 /rad (+66 / +25 / +14 % of 4.79 / 5.51 / 5.47),
  the fins 4.30 / 3.98 / 3.82 against K_W(B) x wing 3.02 / 3.54 / 3.52, the body 3.63 /
  2.89 / 2.39 against K_B(W) x wing 1.66 / 1.95 / 1.94: the default source model has no
  communication around the fin's edges (the fin's plane is a wall outboard of the tip,
  :data:`panair.solver.supersonic.TIP_DIAPHRAGM`; on a thin body a coplanar partner's
  faces leak through and hide it), so the tips keep two-dimensional lift and hand it on
  to the body.  Thin-wing model (partners sided, leading-edge and tip diaphragms) 4.83 /
  5.14 / 5.37 (+1 / -7 / -2 %).  Asserted here (conical nose, the difference to the body
  alone, Mach box n = 100): default +69.5 / +21.8 / +14.2 %, thin-wing +3.2 / -8.5 / -0.7 %
  (session 19, the box's tip on a box edge and the graded diaphragm: default +68.0 / +24.1
  / +15.2 %, thin-wing +7.1 / -3.9 / +3.1 %).

The default model's excess is asserted as measured (bounded both ways, so that a change is
seen); the thin-wing model against the reference.
"""
import numpy as np
import pytest

from panair.mesh import BodyGeometry, FinGeometry, MeshOptions, RocketGeometry, mesh_rocket
from panair.solver import build_panels, make_solver

from fin_loads import fin_panels_cn_alpha
from mach_box import wing_cl_alpha

ROOT, TIP, SPAN, SWEEP, THICK = 0.1524, 0.0762, 0.0381, 0.0762, 0.0005
R_BODY = 0.0381
X_FIN = 0.59436


def _reference_wing(mach):
    """The exposed pair joined at the root, Mach box [1/rad, planform area]."""
    return wing_cl_alpha(lambda y: SWEEP / SPAN * y, lambda y: ROOT, SPAN, mach, n=100)


@pytest.fixture
def thin_wing(monkeypatch):
    from panair.solver import supersonic
    monkeypatch.setattr(supersonic, "THIN_WING", True)


def _wing_alone(mach):
    x0 = 0.1
    body = BodyGeometry(np.array([x0 - 0.05, x0 - 0.03, x0 + ROOT + 0.002]),
                        np.array([0.0, 0.001, 0.001]))
    fins = (FinGeometry(2, ROOT, TIP, SPAN, SWEEP, x0, THICK, roll=np.pi / 2),)
    opt = MeshOptions(n_theta=16, n_nose=4, body_spacing=4.0).for_mach(mach)
    p = build_panels(mesh_rocket(RocketGeometry(body, fins), symmetric=True, options=opt),
                     symmetric=True)
    return fin_panels_cn_alpha(p, mach, SPAN * (ROOT + TIP), ROOT)[0] / _reference_wing(mach) - 1.0


def _fin_share(mach):
    """CN-alpha [1/rad, body cross-section] of the configuration minus the body alone's,
    over the reference (Mach box wing x (1 + r/s)^2)."""
    body = BodyGeometry(np.array([0.0, 0.2286, 0.9144]), np.array([0.0, R_BODY, R_BODY]))
    fins = (FinGeometry(2, ROOT, TIP, SPAN, SWEEP, X_FIN, 0.00236, roll=np.pi / 2,
                        section="rounded"),)
    sref = np.pi * R_BODY**2
    cna = []
    for f in ((), fins):
        geom = RocketGeometry(body, f)
        opt = MeshOptions().for_mach(mach)
        p = build_panels(mesh_rocket(geom, symmetric=True, options=opt), symmetric=True)
        res = make_solver(p, mach, sref=sref, lref=2 * R_BODY, xref=0.0).solve(np.radians([0.0, 2.0]))
        cna.append((res[1].CN - res[0].CN) / np.radians(2.0))
    r_s = R_BODY / (R_BODY + SPAN)
    ref = _reference_wing(mach) * 2 * SPAN * (ROOT + TIP) / 2 / sref * (1 + r_s) ** 2
    return (cna[1] - cna[0]) / ref - 1.0


@pytest.mark.parametrize("mach", [1.2, 1.6, 2.0])
def test_wing_alone_thin_wing_model(thin_wing, mach):
    # measured +1.9 / +2.6 / +1.8 % (before the graded diaphragm, session 19: -7.1 / -3.6 /
    # -2.4 %); the Mach box about 2 %
    assert abs(_wing_alone(mach)) < 0.05


# slender wings alone (B A = 0.33 / 0.28 at Mach 1.2): root, tip, span, leading-edge sweep
SLENDER = {"unswept_te": (0.4593, 0.3220, 0.0981, 0.1373),
           "parallelogram": (0.4593, 0.4593, 0.0981, 0.1373)}


@pytest.mark.parametrize("name", sorted(SLENDER))
def test_slender_wing_alone_thin_wing_model(thin_wing, name):
    """Mach 1.2, subsonic leading edge, streamwise tip; the parallelogram's trailing edge
    subsonic too (its wake acts on the wing).  Measured (session 19, against the Mach box
    at n = 100, itself ~1.5 % above its n -> infinity value here): unswept trailing edge
    -20.5 -> -11.3 %, parallelogram -31.2 -> -22.4 % (wake sheets behind the swept
    trailing edge, supersonic_wake.wake_sheets) -> -12.4 % (graded leading-edge
    diaphragm).  The rest, about -10 %, moves little with refinement (refine 1 / 1.4 / 2:
    -11.3 / -11.1 / -9.7 % and -12.4 / -10.9 / -10.4 %): bounded here, not explained."""
    root, tip, span, sweep = SLENDER[name]
    mach, x0 = 1.2, 0.1
    body = BodyGeometry(np.array([x0 - 0.05, x0 - 0.03, x0 + max(root, sweep + tip) + 0.002]),
                        np.array([0.0, 0.001, 0.001]))
    fins = (FinGeometry(2, root, tip, span, sweep, x0, THICK, roll=np.pi / 2),)
    opt = MeshOptions(n_theta=16, n_nose=4, body_spacing=4.0).for_mach(mach)
    p = build_panels(mesh_rocket(RocketGeometry(body, fins), symmetric=True, options=opt),
                     symmetric=True)
    ref = wing_cl_alpha(lambda y: sweep / span * y,
                        lambda y: sweep / span * y + root + (tip - root) * y / span, span, mach, n=100)
    err = fin_panels_cn_alpha(p, mach, span * (root + tip), root)[0] / ref - 1.0
    print(f"\nslender wing {name} Mach 1.2: {100 * err:+.1f} % of the Mach box")
    assert -0.16 < err < 0.0


@pytest.mark.parametrize("mach, lo, hi", [(1.6, -0.18, -0.08), (2.0, -0.20, -0.10)])
def test_wing_alone_default_model(mach, lo, hi):
    # the partner leak on a thin body (see the module docstring): below linear theory
    assert lo < _wing_alone(mach) < hi


@pytest.mark.parametrize("mach", [1.2, 1.6])
def test_fin_body_thin_wing_model(thin_wing, mach):
    assert abs(_fin_share(mach)) < 0.12


@pytest.mark.parametrize("mach, lo, hi", [(1.2, 0.45, 0.85), (1.6, 0.12, 0.40)])
def test_fin_body_default_model_excess(mach, lo, hi):
    # no communication around the fin edges: the tips keep 2-D lift (module docstring)
    assert lo < _fin_share(mach) < hi
