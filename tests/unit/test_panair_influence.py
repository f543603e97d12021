"""Panel influence coefficients against brute-force quadrature and exact
results (solid angle of a closed surface, sphere in uniform flow)."""
import numpy as np
import pytest

from panair.lawgs import Network
from panel_quadrature import quad_samples
from panair.solver.influence import influence_matrices, planar_corners
from panair.solver.panels import build_panels
from panair.solver.subsonic import SubsonicSolver


def _quadrature(quad, p, n=600):
    """Midpoint-rule integrals of 1/r and n.(P-Q)/r^3 over a planar quad."""
    pts, jac = quad_samples(quad, n)
    R = p - pts
    r = np.linalg.norm(R, axis=-1)
    return jac, R, r


@pytest.mark.parametrize("p", [[0.3, 0.2, 0.7], [2.0, 3.0, -0.4], [2.0, 0.5, 0.0], [0.5, 0.5, -0.3]])
def test_source_and_doublet_vs_quadrature(p):
    quad = np.array([[[0, 0, 0], [0, 1, 0], [1.3, 1.1, 0], [1, 0, 0]]], float)
    flat, c, nrm, area = planar_corners(quad)
    assert area[0] == pytest.approx(1.2)
    D, S = influence_matrices(np.array([p], float), flat, nrm)
    jac, R, r = _quadrature(quad[0], np.array(p, float))
    s_ref = -(jac / r).sum() / (4 * np.pi)
    d_ref = (jac * (R @ nrm[0]) / r**3).sum() / (4 * np.pi)
    print(f"P={p}: S {S[0, 0]:.6f} vs {s_ref:.6f}, D {D[0, 0]:.6f} vs {d_ref:.6f}")
    assert S[0, 0] == pytest.approx(s_ref, rel=1e-4)
    assert D[0, 0] == pytest.approx(d_ref, rel=1e-4, abs=1e-7)


def test_doublet_jump_and_self_source():
    quad = np.array([[[0, 0, 0], [0, 1, 0], [1, 1, 0], [1, 0, 0]]], float)
    flat, c, nrm, _ = planar_corners(quad)
    above = c + 1e-7 * nrm
    below = c - 1e-7 * nrm
    D, S = influence_matrices(np.vstack([above, below, c]), flat, nrm)
    assert D[0, 0] == pytest.approx(0.5, abs=1e-6)
    assert D[1, 0] == pytest.approx(-0.5, abs=1e-6)
    # unit square, centre: Integral dS/r = 4 ln(1 + sqrt 2) (exact)
    assert S[2, 0] == pytest.approx(-4 * np.log(1 + np.sqrt(2)) / (4 * np.pi), rel=1e-12)


def _sphere(n_lat=24, n_lon=48, radius=1.0):
    th = np.linspace(0, np.pi, n_lat + 1)          # from the front (x = -R) to the back
    ph = np.linspace(0, 2 * np.pi, n_lon + 1)
    T, P = np.meshgrid(th, ph, indexing="ij")
    pts = np.stack([-radius * np.cos(T), radius * np.sin(T) * np.cos(P),
                    radius * np.sin(T) * np.sin(P)], axis=-1)
    return Network("sphere", pts.transpose(1, 0, 2))


def test_closed_surface_solid_angle():
    net = _sphere()
    ps = build_panels([net])
    flat, c, nrm, _ = ps.geometry()
    # outward normals
    assert np.all(np.einsum("nj,nj->n", c, nrm) > 0)
    D, _ = influence_matrices(np.array([[0.1, 0.2, -0.1], [3.0, 1.0, 0.5]]), flat, nrm)
    assert D[0].sum() == pytest.approx(-1.0, abs=1e-9)   # inside: -1
    assert D[1].sum() == pytest.approx(0.0, abs=1e-9)    # outside: 0


def test_sphere_incompressible_pressure():
    """Potential flow past a sphere: Cp = 1 - 9/4 sin^2(theta) (exact)."""
    ps = build_panels([_sphere()])
    sol = SubsonicSolver(ps, 0.0, sref=np.pi, lref=1.0, pressure_rule="isentropic")
    res = sol.solve(0.0)[0]
    _, c, _, _ = ps.geometry()
    theta = np.arccos(np.clip(-c[:, 0] / np.linalg.norm(c, axis=1), -1, 1))
    exact = 1 - 2.25 * np.sin(theta) ** 2
    mid = (theta > 0.3) & (theta < np.pi - 0.3)
    err = np.abs(res.cp[mid] - exact[mid]).max()
    print(f"sphere: max |Cp - exact| = {err:.4f} on {mid.sum()} panels; CA = {res.CA:.2e}")
    assert err < 0.03
    assert abs(res.CA) < 5e-3   # d'Alembert


def test_inward_normals_are_reported():
    from ironbark_opt.errors import InputError
    net = _sphere()
    flipped = Network("inv", net.points[::-1])
    with pytest.raises(InputError, match="normals point into the body"):
        build_panels([flipped])
