"""Supersonic source potential at and near a sonic panel edge (an edge along a
Mach line, a = e_p^2 - e_q^2 = 0 in scaled coordinates) and where an edge's
line passes through the field point's projection (delta = 0, where the old
closed form divided 0/0), against an independent reference: for a panel in the
plane Z = 0 the integral over X of 1 / sqrt((X0 - X)^2 - rho^2) is
acosh((X0 - X)/rho) in closed form (rho^2 = (Y0 - Y)^2 + Z0^2), and the
remaining integral over Y is done by adaptive quadrature (scipy.integrate.quad,
1e-11 relative) with break points at the corners and at Y0.  Also the identity
behind the removed log branch: (D + H^2)/a = -(delta/a)^2 <= 0 on every edge."""
import math

import numpy as np
import pytest
from scipy.integrate import quad

from panair.solver.influence import planar_corners
from panair.solver.supersonic_influence import _edge_term, _prepare, source_potential


def _reference(poly, P):
    """-1/(2 pi) Integral over the polygon (X, Y) in Z = 0 and inside the upstream
    Mach cone of P of dX dY / sqrt((X0-X)^2 - (Y0-Y)^2 - Z0^2)."""
    X0, Y0, Z0 = P
    xs, ys = poly[:, 0], poly[:, 1]

    def x_range(y):
        cut = []
        for k in range(len(poly)):
            (x1, y1), (x2, y2) = poly[k, :2], poly[(k + 1) % len(poly), :2]
            if min(y1, y2) <= y <= max(y1, y2) and y1 != y2:
                cut.append(x1 + (x2 - x1) * (y - y1) / (y2 - y1))
        return min(cut), max(cut)

    def inner(y):
        rho = math.hypot(Y0 - y, Z0)
        lo, hi = x_range(y)
        hi = min(hi, X0 - rho)
        if hi <= lo:
            return 0.0
        if rho == 0.0:
            return math.log((X0 - lo) / (X0 - hi)) if X0 > hi else 0.0
        return math.acosh((X0 - lo) / rho) - math.acosh(max((X0 - hi) / rho, 1.0))

    brk = sorted({*ys, min(max(Y0, ys.min()), ys.max())})
    total = 0.0
    for y1, y2 in zip(brk[:-1], brk[1:]):
        if y2 > y1:
            total += quad(inner, y1, y2, epsabs=1e-13, epsrel=1e-11, limit=400)[0]
    return -total / (2 * math.pi)


def _panel(eps):
    """Quad in Z = 0 with the edge (1, 0) -> (1.5, 0.5 + eps): sonic for eps = 0."""
    return np.array([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.5, 0.5 + eps, 0.0], [0.2, 0.6, 0.0]])


#: field points: the Mach cone crossing the sonic edge, on the edge's line
#: X - Y = 1 (delta = 0 for the sonic edge), in the panel plane, above the edge
POINTS = [[2.5, 0.2, 0.3], [2.0, 1.0, 0.1], [2.0, 1.0, 0.0], [2.2, 0.3, 0.0], [1.9, 0.45, 0.05],
          [3.0, -0.2, 0.7], [1.6, 0.52, 0.02]]


@pytest.mark.parametrize("eps", [0.0, 1e-13, -1e-13, 1e-9, -1e-9, 1e-6, -1e-6, 1e-3])
def test_potential_at_and_near_a_sonic_edge_vs_quadrature(eps):
    poly = _panel(eps)
    flat, _, nrm, _ = planar_corners(poly[None])
    pts = np.array(POINTS)
    ref = np.array([_reference(poly, p) for p in pts])
    for backend in ("compiled", "numpy"):
        ours = source_potential(pts, flat, nrm, backend=backend)[:, 0]
        print(f"eps {eps:g} {backend}: max rel err {np.max(np.abs(ours / ref - 1)):.2e}")
        np.testing.assert_allclose(ours, ref, rtol=1e-8)


def test_potential_is_continuous_through_the_sonic_edge_and_delta_zero():
    """Perturbing the sonic edge by +-1e-9, or the field point off the edge's line
    (delta = 0 -> +-1e-9), moves the potential by O(1e-9) off the panel plane (no
    jump, no 0/0); a point in the plane on the edge's line sits on the Mach line
    of the edge itself, where the exact potential moves like sqrt(shift) (the
    quadrature reference agrees with the shifted values to 1e-8 there too)."""
    pts = np.array(POINTS)
    off = pts[:, 2] > 0
    flat0, _, nrm0, _ = planar_corners(_panel(0.0)[None])
    base = source_potential(pts, flat0, nrm0)[:, 0]
    assert np.all(np.isfinite(base))
    for eps in (1e-9, -1e-9):
        flat, _, nrm, _ = planar_corners(_panel(eps)[None])
        moved = source_potential(pts, flat, nrm)[:, 0]
        np.testing.assert_allclose(moved[off], base[off], atol=1e-8)
        shifted = pts + np.array([0.0, eps, 0.0])
        moved = source_potential(shifted, flat0, nrm0)[:, 0]
        np.testing.assert_allclose(moved[off], base[off], atol=1e-8)
        assert np.all(np.abs(moved - base) < 10 * math.sqrt(abs(eps)))
        ref = np.array([_reference(_panel(0.0), p) for p in shifted])
        np.testing.assert_allclose(moved, ref, rtol=1e-8)


#: (a, delta): sonic (a = 0), near-sonic and ordinary edges; delta = 0 and +-tiny
#: where an interval with R > 0 exists (for a <= 0 it needs delta^2 > |a| H2 and,
#: near a = 0, delta > H2 / 2.4: near-sonic edges have no part inside the cone
#: close to the edge line)
EDGES = [(0.0, 0.2), (0.0, 0.5), (1e-12, 0.2), (-1e-12, 0.2), (1e-8, 0.3), (-1e-8, 0.3),
         (1e-4, 0.2), (-1e-4, 0.2), (0.3, 0.0), (0.3, 1e-10), (0.3, -1e-7), (0.3, 0.2),
         (-0.3, 0.2), (-0.3, 0.3)]


@pytest.mark.parametrize("a,delta", EDGES)
def test_edge_term_vs_quadrature(a, delta):
    """One edge: delta * Integral sqrt(R)/(R + H2) over the part with R > 0, R built
    from a point (p, q, H) and an edge direction with e_p^2 - e_q^2 = a."""
    ep = math.sqrt((1 + a) / 2)
    eq = math.sqrt((1 - a) / 2)
    H2 = 0.04
    # point at distance delta from the edge line: (p, q) = t0 (ep, eq) + delta (eq, -ep)
    p = -0.8 * ep + delta * eq
    q = -0.8 * eq - delta * ep
    b, c = 2 * (p * ep - q * eq), p * p - q * q - H2
    R = lambda t: a * t * t + b * t + c                       # noqa: E731
    ts = np.linspace(0.0, 2.0, 200001)
    inside = ts[(R(ts) > 0) & (p + ep * ts > 0)]
    assert len(inside) > 1000                                 # a part of the edge is inside
    # the ends: roots of R or the edge ends
    roots = np.roots([a, b, c]) if a != 0 else np.array([-c / b])
    roots = np.sort(roots[np.isreal(roots)].real)
    ta = max([r for r in roots if r <= inside[0] + 1e-6] + [0.0])
    tb = min([r for r in roots if r >= inside[-1] - 1e-6] + [2.0])
    ref = delta * quad(lambda t: math.sqrt(max(R(t), 0.0)) / (max(R(t), 0.0) + H2), ta, tb,
                       epsabs=1e-15, epsrel=1e-12, limit=400)[0]
    s_a, s_b = math.sqrt(max(R(ta), 0.0)), math.sqrt(max(R(tb), 0.0))
    got = _edge_term(np.array(ta), np.array(tb), np.array(s_a), np.array(s_b), np.array(a),
                     np.array(b), np.array(H2), np.array(delta))
    assert got == pytest.approx(ref, rel=1e-9, abs=1e-15)


def test_log_branch_condition_never_holds():
    """(D + H2)/a = -(delta/a)^2 on every edge of random panels and points (the old
    closed form's log branch needed (D + H2)/a > 0: unreachable but for delta = 0 to
    rounding, where it divided 0/0)."""
    rng = np.random.default_rng(3)
    worst = 0.0
    for _ in range(200):
        quad4 = rng.normal(size=(4, 3)) * [1.0, 1.0, 0.2]
        flat, _, nrm, _ = planar_corners(quad4[None])
        if nrm[0, 0] ** 2 > 0.45:
            continue
        (cen, rho, q0, normal, e1, e2, g1, sg, e1x_nx, uk, tk, L, okL, ep, eq, nup, nuq,
         a_all) = _prepare(flat, nrm)
        P = rng.normal(size=3) * 2
        d = P - q0[0]
        h = d @ normal[0]
        U = sg[0] * (d @ e1[0] + 2 * e1x_nx[0] * h / g1[0])
        H2 = h * h / g1[0]
        pk, qk = U - uk[0], d @ e2[0] - tk[0]
        a = a_all[0]
        b = 2 * (pk * ep[0] - qk * eq[0])
        c = pk**2 - qk**2 - H2
        delta = pk * nup[0] + qk * nuq[0]
        lhs = (c - b**2 / (4 * a) + H2) / a
        rhs = -(delta / a) ** 2
        assert np.all(lhs <= 1e-9 * (1 + np.abs(rhs)))
        worst = max(worst, float(np.max(np.abs(lhs - rhs) / (1 + np.abs(rhs)))))
    assert worst < 1e-8


def test_field_point_above_an_edge_line_is_finite():
    """The 0/0 case itself: a point above the line of a streamwise edge, with values
    exact in binary so that D + H2 = 0 exactly (the old closed form returned NaN for
    all three points, both backends; Defiance's Mach 1.5 build fell to local
    inclination on such a pair)."""
    poly = np.array([[0, 0, 0], [1, 0, 0], [1.25, 0.5, 0], [0.0, 0.5, 0]], float)
    flat, _, nrm, _ = planar_corners(poly[None])
    pts = np.array([[2.0, 0.0, 0.5], [3.0, 0.0, 0.5], [2.0, 0.0, 0.25]])
    ref = np.array([_reference(poly, p) for p in pts])
    for backend in ("compiled", "numpy"):
        np.testing.assert_allclose(source_potential(pts, flat, nrm, backend=backend)[:, 0], ref,
                                   rtol=1e-8)


def test_sonic_fin_leading_edge_solves_linearly(monkeypatch):
    """Fins whose rounded leading edge (meshed as a wedge) is exactly sonic at Mach 1.2
    (sweep acos(1/1.2) = 33.6 deg, as Allen's fin 12 and EuRoC's Andromeda): linear
    theory's pressure there is beyond stagnation (the sonic-edge singularity), which
    the out-of-range check used to report (the whole Mach number then went to local
    inclination).  The flagged panels are exactly forward-facing fin faces, at Mach
    1.2 only; with them the case solves, is recorded ("linear-sonic-le"), CN is
    linear in alpha, and CN-alpha and the centre of pressure continue those of
    Mach 1.25 and 1.3 (linear theory's lift is continuous through the sonic-edge
    condition, e.g. the delta wing's CL_alpha = 4/B at m = 1 from both sides,
    Jones & Cohen 1960): within 3 % and 0.1 caliber."""
    from dataclasses import replace

    from ironbark_opt.errors import SolverError
    from panair.mesh import BodyGeometry, FinGeometry, MeshOptions, RocketGeometry, mesh_rocket
    from panair.solver import build_panels, make_solver
    from panair.solver import supersonic as sup
    from panair.sweep import _solve_one
    body = BodyGeometry(np.array([0.0, 0.3, 1.2]), np.array([0.0, 0.05, 0.05]))
    span = 0.1
    fins = (FinGeometry(2, 0.14, 0.07, span, span * math.tan(math.acos(1 / 1.2)), 0.95, 0.004,
                        roll=np.pi / 2, section="rounded"),)
    opt = replace(MeshOptions(supersonic_span_factor=2.0, supersonic_chord_factor=1.0,
                              n_theta=16, n_nose=10, body_spacing=0.8, n_chord=16,
                              n_span=6).for_mach(1.2), tip_mach=(1.2,))
    p = build_panels(mesh_rocket(RocketGeometry(body, fins), symmetric=True, options=opt),
                     symmetric=True)
    sref, lref = math.pi * 0.05**2, 0.1
    alphas = np.radians([0.0, 2.0, 4.0])
    s12 = make_solver(p, 1.2, sref=sref, lref=lref)
    flagged = s12._sonic_le
    fin_net = np.isin(p.network[p.integrate], [p.names.index("fin0")])
    assert flagged.sum() > 20 and np.all(fin_net[flagged]) and np.all(s12._nrm[flagged, 0] < 0)
    assert not make_solver(p, 1.3, sref=sref, lref=lref)._sonic_le.any()
    mach, coef, extra, _, how = _solve_one((p, 1.2, alphas, sref, lref, 0.0, "second-order"))
    assert how == "linear-sonic-le" and extra == []
    cn, cm = coef[:, 1], coef[:, 2]
    assert cn[2] / cn[1] == pytest.approx(2.0, rel=0.01)
    ref = []
    for m in (1.25, 1.3):
        r = make_solver(p, m, sref=sref, lref=lref).solve(alphas[1])[0]
        ref.append((r.CN, -r.Cm / r.CN))
    print(f"\nsonic LE: CN(2 deg) {cn[1]:.4f} vs Mach 1.25/1.3 {ref[0][0]:.4f}/{ref[1][0]:.4f}, "
          f"xcp {-cm[1] / cn[1]:.3f} vs {ref[0][1]:.3f}/{ref[1][1]:.3f} cal")
    assert cn[1] == pytest.approx(ref[0][0], rel=0.03)
    assert abs(-cm[1] / cn[1] - ref[0][1]) < 0.1
    # the same solution without the classification: its edge pressures are a local
    # singularity, clipped (CLIP_AREA_MAX), which takes the edge's integrable load off
    monkeypatch.setattr(sup, "_sonic_leading_edge", lambda *a: np.zeros(len(flagged), bool))
    s = make_solver(p, 1.2, sref=sref, lref=lref)
    r = s.solve(alphas[1])[0]
    print(f"unclassified, clipped: CN(2 deg) {r.CN:.4f}")
    assert s.cp_clipped and r.CN < cn[1]
    # ... and without the clipping either: reported non-physical (before session 17)
    monkeypatch.setattr(sup, "CLIP_AREA_MAX", -1.0)
    with pytest.raises(SolverError, match="non-physical surface pressure"):
        make_solver(p, 1.2, sref=sref, lref=lref).solve(alphas[1])
