"""A flat delta wing in supersonic flow: the built-in solver's lift against exact linear
theory.

The wing: two delta fins (pointed tips at the trailing edge, unswept trailing edge,
2 mm double-wedge section on 0.5 m root chord) on a thin body (radius 5 mm, 1 % of the
wing's span at 63.4 deg), meshed by :func:`panair.mesh.mesh_rocket`; CN-alpha of the
fin panels on the wing's planform area, against

* a supersonic leading edge (B cot Lambda > 1): CL-alpha = 4 / B (Ackeret's value,
  which the conical flow inside the apex Mach cone does not change; e.g. Jones &
  Cohen, *High Speed Wing Theory*, 1960, sec. 5; Puckett, J. Aero. Sci. 13, 1946);
* a subsonic leading edge: Stewart's exact result CL-alpha = 2 pi tan(eps) / E(k),
  k = sqrt(1 - (B tan eps)^2), eps = 90 deg - Lambda (Stewart, Quart. Appl. Math. 4,
  1946; E the complete elliptic integral of the second kind).

Supersonic leading edge: within 2 % at Mach 1.6 and 2.0 (measured -0.5 %, -0.1 %;
-15 % / -11 % before the coplanar fin partners were sided,
:func:`panair.solver.supersonic._fin_sides`), in the half model and the full model
alike.

Subsonic leading edge (63.4 deg): a documented shortfall, not agreement.  Measured
-12.6 % / -12.5 % at Mach 1.6 / 2.0 (-35 % / -30 % before), and it does not close
with the mesh (Mach 1.6, refine 0.7 / 1.0 / 1.2 / 1.4: -13.2 / -12.6 / -12.4 / -12.3 %,
linear in the panel size toward about -11 %; the supersonic edge -0.9 / -0.5 / -0.3 /
-0.2 %, toward 0): it converges to a wrong value.  The source model has nothing
ahead of a subsonic leading edge (PAN AIR's doublet sheet makes the upper and lower
flows communicate there, the "diaphragm" of Evvard, NACA Report 951, 1950), so the
upper side sees a wall off the wing and the leading-edge suction peak (28 % of the
lift within 10 % of the span from the edge in Stewart's loading 1 / sqrt(1 - t^2))
is missing.  The test bounds the error to -16 ... -9 % so that a change in either
direction is seen.
"""
import numpy as np
import pytest
from scipy.special import ellipe

from panair.mesh import BodyGeometry, FinGeometry, MeshOptions, RocketGeometry, mesh_rocket
from panair.solver import build_panels, make_solver
from panair.solver.pressure import integrate_forces

CHORD, R_BODY, THICK, X_ROOT = 0.5, 0.005, 0.002, 0.3


def exact_cl_alpha(mach, sweep_deg):
    """Flat delta wing, linear theory [1/rad] (Stewart 1946; 4/B for a supersonic edge)."""
    b = np.sqrt(mach**2 - 1.0)
    tan_eps = 1.0 / np.tan(np.radians(sweep_deg))
    m = b * tan_eps
    return 4.0 / b if m >= 1.0 else 2.0 * np.pi * tan_eps / ellipe(1.0 - m * m)


def wing_cn_alpha(mach, sweep_deg, symmetric=True, refine=1.0):
    """CN-alpha of the fin panels [1/rad] on the planform area (alpha 0 and 2 deg)."""
    span = CHORD / np.tan(np.radians(sweep_deg))
    xn = np.linspace(0.0, 0.1, 6)
    body = BodyGeometry(np.append(xn, X_ROOT + CHORD), np.append(R_BODY * xn / 0.1, R_BODY))
    fins = (FinGeometry(2, CHORD, 0.0, span, CHORD, X_ROOT, THICK, roll=np.pi / 2),)
    opt = MeshOptions(n_theta=16, n_nose=6, body_spacing=2.0, n_chord=20, n_span=8,
                      chord_clustering=0.0, refine=refine).for_mach(mach)
    p = build_panels(mesh_rocket(RocketGeometry(body, fins), symmetric=symmetric, options=opt),
                     symmetric=symmetric)
    sref = CHORD * span
    s = make_solver(p, mach, sref=sref, lref=CHORD)
    res = s.solve(np.radians([0.0, 2.0]))
    fins_id = np.unique(p.network[p.wake_upper[~p.wake_at_base]])
    on = np.isin(p.network[s._keep], fins_id) & ~s._caps
    cn = [integrate_forces(r.cp[s._keep][on], s._cen[on], s._nrm_f[on], s._area[on], sref=sref,
                           lref=CHORD, xref=0.0, symmetric=p.symmetric)["CN"] for r in res]
    return (cn[1] - cn[0]) / np.radians(2.0)


@pytest.mark.parametrize("mach", [1.6, 2.0])
@pytest.mark.parametrize("symmetric", [True, False])
def test_supersonic_leading_edge_delta_wing_matches_ackeret(mach, symmetric):
    cna, ref = wing_cn_alpha(mach, 45.0, symmetric), exact_cl_alpha(mach, 45.0)
    print(f"\ndelta 45 deg M{mach}: CN-alpha {cna:.4f} vs 4/B {ref:.4f} ({100 * (cna / ref - 1):+.2f} %)")
    assert abs(cna / ref - 1.0) < 0.02


@pytest.mark.parametrize("mach", [1.6, 2.0])
def test_subsonic_leading_edge_delta_wing_documented_shortfall(mach):
    """Not agreement: the known shortfall (module docstring), bounded both ways."""
    cna, ref = wing_cn_alpha(mach, 63.435), exact_cl_alpha(mach, 63.435)
    err = cna / ref - 1.0
    print(f"\ndelta 63.4 deg M{mach}: CN-alpha {cna:.4f} vs Stewart {ref:.4f} ({100 * err:+.2f} %)")
    assert -0.16 < err < -0.09


def test_exact_values():
    """The references themselves: Stewart's formula meets 4/B at the sonic edge, and
    its slender-wing limit is Jones's pi A / 2 (A = 4 tan eps)."""
    b = np.sqrt(1.6**2 - 1.0)
    sweep_sonic = np.degrees(np.arctan(b))            # B tan(eps) = 1
    assert exact_cl_alpha(1.6, sweep_sonic - 1e-9) == pytest.approx(4.0 / b, rel=1e-6)
    tan_eps = 1e-4
    assert exact_cl_alpha(1.6, 90.0 - np.degrees(np.arctan(tan_eps))) == pytest.approx(
        np.pi * 4.0 * tan_eps / 2.0, rel=1e-6)
