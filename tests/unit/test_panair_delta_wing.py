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

The default model (documented shortfalls, bounded both ways so that a change is seen):
supersonic leading edge (45 deg) -14.6 / -11.0 % at Mach 1.6 / 2.0, subsonic (63.4 deg)
-35.2 / -30.3 %.  Two causes, both of the source model's fin sides
(:func:`panair.solver.supersonic._fin_sides`): (1) a source on the lower face of one
fin acts on the upper face of the fin opposite it and cancels most of that side's own
lifting sources (thin-wing theory: the upper half-space sees the upper-side sources of
the whole plane only); (2) nothing ahead of a subsonic leading edge, where the upper
and lower flows communicate through the wing's plane (Evvard's diaphragm, NACA Report
951, 1950): the plane acts as a wall and the leading-edge suction peak is lost.

The thin-wing model (``supersonic.THIN_WING``: coplanar partners sided and diaphragms)
removes both: supersonic leading edge within 2 % (measured -0.5 / -0.1 %, half and full
model alike; refine 0.7 / 1.0 / 1.2 / 1.4: -0.9 / -0.5 / -0.3 / -0.2 %); subsonic -9.8 /
-9.9 % on this mesh, converging like sqrt(panel size) (the edge's integrable
1 / sqrt(distance) pressure: Mach 1.6, refine 0.7 / 1.0 / 1.2 / 1.4 / 1.7: -11.4 / -9.8 /
-9.0 / -8.4 / -7.6 %), whose extrapolation from refine 1.0 and 1.4 is asserted within
3 % of Stewart (measured -0.7 %).  Without the diaphragms (partners sided only) the same
meshes converge to about -10 %.  Session 19 (diaphragm cells graded to the edge,
supersonic_diaphragm.LE_GRADED): this uniform mesh -7.3 / -5.7 % at refine 1 / 1.4
(extrapolated +2.7 %); the supersonic meshes' cosine chordwise stations -2.2 %.
THIN_WING is off by default: it raises the supersonic CN-alpha of Allen's fin pairs on a
thick body, already too high (see its docstring).
"""
import numpy as np
import pytest
from scipy.special import ellipe

from panair.mesh import BodyGeometry, FinGeometry, MeshOptions, RocketGeometry, mesh_rocket
from panair.solver import build_panels

from fin_loads import fin_panels_cn_alpha

CHORD, R_BODY, THICK, X_ROOT = 0.5, 0.005, 0.002, 0.3


def exact_cl_alpha(mach, sweep_deg):
    """Flat delta wing, linear theory [1/rad] (Stewart 1946; 4/B for a supersonic edge)."""
    b = np.sqrt(mach**2 - 1.0)
    tan_eps = 1.0 / np.tan(np.radians(sweep_deg))
    m = b * tan_eps
    return 4.0 / b if m >= 1.0 else 2.0 * np.pi * tan_eps / ellipe(1.0 - m * m)


@pytest.fixture
def thin_wing(monkeypatch):
    from panair.solver import supersonic
    monkeypatch.setattr(supersonic, "THIN_WING", True)


def wing_cn_alpha(mach, sweep_deg, symmetric=True, refine=1.0):
    """CN-alpha of the fin panels [1/rad] on the planform area (alpha 0 and 2 deg)."""
    span = CHORD / np.tan(np.radians(sweep_deg))
    xn = np.linspace(0.0, 0.1, 6)
    body = BodyGeometry(np.append(xn, X_ROOT + CHORD), np.append(R_BODY * xn / 0.1, R_BODY))
    fins = (FinGeometry(2, CHORD, 0.0, span, CHORD, X_ROOT, THICK, roll=np.pi / 2),)
    opt = MeshOptions(supersonic_span_factor=2.0, supersonic_chord_factor=1.0,
                      n_theta=16, n_nose=6, body_spacing=2.0, n_chord=20, n_span=8,
                      chord_clustering=0.0, refine=refine).for_mach(mach)
    p = build_panels(mesh_rocket(RocketGeometry(body, fins), symmetric=symmetric, options=opt),
                     symmetric=symmetric)
    return fin_panels_cn_alpha(p, mach, CHORD * span, CHORD)[0]


@pytest.mark.parametrize("mach, sweep, lo, hi", [(1.6, 45.0, -0.17, -0.12), (2.0, 45.0, -0.14, -0.08),
                                               (1.6, 63.435, -0.40, -0.30), (2.0, 63.435, -0.35, -0.25)])
def test_default_model_documented_shortfall(mach, sweep, lo, hi):
    """Not agreement: the default model's known shortfall (module docstring), bounded."""
    err = wing_cn_alpha(mach, sweep) / exact_cl_alpha(mach, sweep) - 1.0
    print(f"\ndefault model, delta {sweep} deg M{mach}: {100 * err:+.2f} % of exact")
    assert lo < err < hi


@pytest.mark.parametrize("mach", [1.6, 2.0])
@pytest.mark.parametrize("symmetric", [True, False])
def test_thin_wing_supersonic_leading_edge_matches_ackeret(thin_wing, mach, symmetric):
    cna, ref = wing_cn_alpha(mach, 45.0, symmetric), exact_cl_alpha(mach, 45.0)
    print(f"\ndelta 45 deg M{mach}: CN-alpha {cna:.4f} vs 4/B {ref:.4f} ({100 * (cna / ref - 1):+.2f} %)")
    assert abs(cna / ref - 1.0) < 0.02


def test_thin_wing_subsonic_leading_edge_converges_to_stewart(thin_wing):
    """Mach 1.6, 63.4 deg: -9.8 % on the mesh of refine 1.0; the error of an edge
    singularity 1 / sqrt(d) resolved by panels of size h falls like sqrt(h), so the
    Richardson extrapolation from refine 1.0 and 1.4 (h ratio 1.4) is compared."""
    mach, sweep = 1.6, 63.435
    ref = exact_cl_alpha(mach, sweep)
    e1, e2 = (wing_cn_alpha(mach, sweep, refine=r) / ref - 1.0 for r in (1.0, 1.4))
    g = np.sqrt(1.0 / 1.4)
    extrap = (e2 - g * e1) / (1.0 - g)
    print(f"\ndelta 63.4 deg M1.6: {100 * e1:+.2f} % (refine 1), {100 * e2:+.2f} % (1.4), "
          f"extrapolated {100 * extrap:+.2f} % of Stewart")
    assert -0.12 < e1 < -0.07 and e1 < e2 < 0.0
    assert abs(extrap) < 0.03


def test_thin_wing_subsonic_leading_edge_on_the_supersonic_mesh(thin_wing, monkeypatch):
    """The same wing with the supersonic meshes' cosine-clustered chordwise stations
    (chord_clustering 1, MeshOptions' default): the fin's leading-edge panels resolve
    the edge's 1 / sqrt(d) load and the diaphragm's cells are graded to them
    (supersonic_diaphragm.LE_GRADED).  Measured Mach 1.6, 63.4 deg: -7.9 % before the
    grading (session 19), -2.2 % with it (refine 1.4: -6.8 -> -1.3 %)."""
    import test_panair_delta_wing as me
    base = me.MeshOptions
    monkeypatch.setattr(me, "MeshOptions", lambda **kw: base(**{**kw, "chord_clustering": 1.0}))
    err = wing_cn_alpha(1.6, 63.435) / exact_cl_alpha(1.6, 63.435) - 1.0
    print(f"\ndelta 63.4 deg M1.6, cosine chordwise: {100 * err:+.2f} % of Stewart")
    assert abs(err) < 0.04


def test_exact_values():
    """The references themselves: Stewart's formula meets 4/B at the sonic edge, and
    its slender-wing limit is Jones's pi A / 2 (A = 4 tan eps)."""
    b = np.sqrt(1.6**2 - 1.0)
    sweep_sonic = np.degrees(np.arctan(b))            # B tan(eps) = 1
    assert exact_cl_alpha(1.6, sweep_sonic - 1e-9) == pytest.approx(4.0 / b, rel=1e-6)
    tan_eps = 1e-4
    assert exact_cl_alpha(1.6, 90.0 - np.degrees(np.arctan(tan_eps))) == pytest.approx(
        np.pi * 4.0 * tan_eps / 2.0, rel=1e-6)


def test_thin_wing_mirror_sides_compiled_equals_numpy(thin_wing):
    """The half model's mirror-image sides (the fourth element of ``sides``) give the
    same potentials in the compiled kernel and the NumPy reference (1e-9 relative),
    and they do separate pairs (the partner is the fin's own twin here)."""
    from panair.solver import supersonic as sup
    from panair.solver.supersonic_influence import source_potential_pair
    mach, span = 1.6, CHORD / np.tan(np.radians(63.435))
    xn = np.linspace(0.0, 0.1, 4)
    body = BodyGeometry(np.append(xn, X_ROOT + CHORD), np.append(R_BODY * xn / 0.1, R_BODY))
    fins = (FinGeometry(2, CHORD, 0.0, span, CHORD, X_ROOT, THICK, roll=np.pi / 2),)
    opt = MeshOptions(supersonic_span_factor=2.0, supersonic_chord_factor=1.0,
                      n_theta=8, n_nose=3, body_spacing=4.0, n_chord=6, n_span=2,
                      chord_clustering=0.0).for_mach(mach)
    p = build_panels(mesh_rocket(RocketGeometry(body, fins), symmetric=True, options=opt),
                     symmetric=True)
    B = np.sqrt(mach**2 - 1.0)
    flat, cen, nrm, area = p.geometry(1.0 / B)
    keep = p.integrate
    flat, cen, nrm = flat[keep], cen[keep], nrm[keep]
    p0 = cen + 0.02 * np.sqrt(area[keep])[:, None] * nrm
    p1 = p0 + 0.02 * np.sqrt(area[keep])[:, None] * nrm * np.array([-1.0, 1.0, 1.0])
    sides = sup._fin_sides(p, keep, cen, nrm)
    recv_m = sup._mirror_sides(p, keep, cen, nrm, sup._fin_index(p, keep))
    assert np.any(recv_m != 0)
    out = [source_potential_pair(p0, p1, flat, nrm, sides=sides + (recv_m,), mirror=True,
                                 backend=b) for b in ("compiled", "numpy")]
    plain = source_potential_pair(p0, p1, flat, nrm, sides=sides, mirror=True, backend="numpy")
    assert out[0][2] == out[1][2] == -1
    for k in (0, 1):
        scale = np.abs(out[1][k]).max()
        assert np.abs(out[0][k] - out[1][k]).max() <= 1e-9 * scale
    assert np.abs(plain[0] - out[1][0]).max() > 1e-6 * np.abs(plain[0]).max()
