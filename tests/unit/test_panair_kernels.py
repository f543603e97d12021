"""Compiled (Numba) panel-influence kernels against the vectorised NumPy reference
(panair.solver.influence / supersonic_influence, backend="numpy"), on a coarse
Basic Finner half model (body, fins, wakes), both regimes: influence matrices to
1e-12 relative, and whole solutions (forces) to 1e-12."""
import numpy as np
import pytest

pytest.importorskip("numba")

from panair.solver import kernels, make_solver  # noqa: E402
from panair.solver.influence import influence_matrices  # noqa: E402
from panair.solver.supersonic_influence import panel_frames, source_potential  # noqa: E402

RTOL = 1e-12


@pytest.fixture(scope="module")
def finner(coarse_finner_panels):
    return coarse_finner_panels


def _close(a, b):
    """Elementwise agreement to RTOL of the matrix's largest entry."""
    scale = max(np.abs(b).max(), 1e-300)
    err = np.abs(a - b).max() / scale
    print(f"max |compiled - numpy| / max |numpy| = {err:.3g}")
    assert np.all(np.isfinite(a)) and err <= RTOL


@pytest.mark.parametrize("mach", [0.0, 0.6, 0.9])
def test_laplace_kernel_matches_numpy(finner, mach):
    flat, cen, nrm, _ = finner.geometry(1.0 / np.sqrt(1.0 - mach**2))
    n = finner.n
    ref = influence_matrices(cen, flat, nrm, self_index=np.arange(n), backend="numpy")
    got = influence_matrices(cen, flat, nrm, self_index=np.arange(n), backend="compiled")
    # accumulate mode (the half model's mirror image) and the wake panels
    mirror = cen * np.array([1.0, -1.0, 1.0])
    influence_matrices(mirror, flat, nrm, out=ref, backend="numpy")
    influence_matrices(mirror, flat, nrm, out=got, backend="compiled")
    wflat, _, wnrm, _ = finner.wake_geometry(1.0 / np.sqrt(1.0 - mach**2))
    for a, b in zip(got + influence_matrices(cen, wflat, wnrm, backend="compiled"),
                    ref + influence_matrices(cen, wflat, wnrm, backend="numpy")):
        _close(a, b)


@pytest.mark.parametrize("mach", [1.2, 1.5, 2.5])
def test_supersonic_kernel_matches_numpy(finner, mach):
    B = np.sqrt(mach**2 - 1.0)
    flat, cen, nrm, area = finner.geometry(1.0 / B)
    keep = finner.integrate & (panel_frames(flat, nrm)[2] > 0.05)
    flat, cen, nrm = flat[keep], cen[keep], nrm[keep]
    for off in (0.0, 0.02):                    # on the centroids and 2 % of the size off
        pts = cen + off * np.sqrt(area[keep])[:, None] * nrm
        for p in (pts, pts * np.array([1.0, -1.0, 1.0])):
            ref = source_potential(p, flat, nrm, backend="numpy")
            got = source_potential(p, flat, nrm, backend="compiled")
            _close(got, ref)
            assert np.array_equal(got == 0.0, ref == 0.0)     # same domain of dependence


@pytest.mark.parametrize("mach", [0.5, 2.5])
def test_solver_forces_identical(finner, mach, monkeypatch):
    alphas = np.radians([0.0, 4.0, 8.0])
    res_c = make_solver(finner, mach, sref=np.pi / 4, lref=1.0, xref=5.0).solve(alphas)
    monkeypatch.setattr(kernels, "HAVE_NUMBA", False)        # the solvers' NumPy path
    assert not kernels.use_compiled("auto")
    res_n = make_solver(finner, mach, sref=np.pi / 4, lref=1.0, xref=5.0).solve(alphas)
    for rc, rn in zip(res_c, res_n):
        for k in ("CA", "CN", "Cm"):
            # abs: CN and Cm at alpha 0 are zero by symmetry, rounding noise (measured up
            # to 3e-14 apart with numpy 2.4.6 / numba 0.68.1) on forces of order 1
            assert getattr(rc, k) == pytest.approx(getattr(rn, k), rel=RTOL, abs=1e-12)
    assert res_c[-1].CN > 0.1                                  # a lifting solution was compared


def test_backend_argument_is_checked(finner):
    flat, cen, nrm, _ = finner.geometry(1.0)
    with pytest.raises(ValueError, match="backend"):
        influence_matrices(cen[:2], flat, nrm, backend="fortran")


@pytest.mark.parametrize("mach, mirror", [(1.2, True), (2.5, False)])
def test_supersonic_pair_kernel_matches_separate_calls(finner, mach, mirror):
    """The solver's one-pass kernel (both potentials, fin-separated pairs skipped,
    mirror image added, rows in any order) equals the separate NumPy-reference
    calls with the shadow mask applied, to RTOL; the NumPy fallback too."""
    from panair.solver.supersonic import _fin_shadow, _fin_sides
    from panair.solver.supersonic_influence import source_potential_pair
    B = np.sqrt(mach**2 - 1.0)
    flat, cen, nrm, area = finner.geometry(1.0 / B)
    keep = finner.integrate & (panel_frames(flat, nrm)[2] > 0.05)
    flat, cen, nrm = flat[keep], cen[keep], nrm[keep]
    p0 = cen + 0.02 * np.sqrt(area[keep])[:, None] * nrm
    p1 = p0 + 0.02 * np.sqrt(area[keep])[:, None] * nrm * np.array([-1.0, 1.0, 1.0])
    sides = _fin_sides(finner, keep, cen, nrm)
    shadow = _fin_shadow(finner, keep, cen, nrm)
    assert shadow.any()
    refs = []
    for p in (p0, p1):
        val = source_potential(p, flat, nrm, backend="numpy")
        val[shadow] = 0.0
        if mirror:
            val += source_potential(p * np.array([1.0, -1.0, 1.0]), flat, nrm, backend="numpy")
        refs.append(val)
    rows = np.argsort(-cen[:, 0])
    for backend in ("compiled", "numpy"):
        phi0, phi1, bad = source_potential_pair(p0, p1, flat, nrm, sides=sides, mirror=mirror,
                                                rows=rows, backend=backend)
        assert bad == -1
        _close(phi0, refs[0])
        _close(phi1, refs[1])


def test_supersonic_pair_kernel_stops_at_the_first_nonfinite_row(finner, monkeypatch):
    """The pass stops at the first row (in ``rows`` order) with a non-finite value.
    The closed form itself returns finite limits even for a field point at infinity
    (0, the potential's limit; checked here), so the non-finite value is injected
    through the prepared panel constants: sqrt(g1) = 0 for the most forward panel
    (the potential divides by it), which every aft row sees."""
    from panair.solver import supersonic_influence as si
    flat, cen, nrm, area = finner.geometry(1.0 / np.sqrt(1.5**2 - 1.0))
    keep = finner.integrate & (panel_frames(flat, nrm)[2] > 0.05)
    flat, cen, nrm = flat[keep], cen[keep], nrm[keep]
    p0 = cen + 0.02 * np.sqrt(area[keep])[:, None] * nrm
    p1 = p0.copy()
    aft = int(np.argmax(cen[:, 0]))
    p1[aft, 0] = np.inf                           # infinitely far downstream: potential 0
    _, phi1, bad = si.source_potential_pair(p0, p1, flat, nrm, backend="compiled")
    assert bad == -1 and np.all(phi1[aft] == 0.0)
    fore = int(np.argmin(cen[:, 0]))
    prepare = si._prepare

    def poisoned(f, n):
        out = list(prepare(f, n))
        out[7] = out[7].copy()
        out[7][fore] = 0.0                        # sg: the potential divides by it
        return tuple(out)

    monkeypatch.setattr(si, "_prepare", poisoned)
    rows = np.arange(len(p0))[::-1]
    ref = si.source_potential(p0, flat, nrm, backend="numpy")
    expect = int(rows[np.nonzero(~np.all(np.isfinite(ref), axis=1)[rows])[0][0]])
    for backend in ("compiled", "numpy"):
        _, _, bad = si.source_potential_pair(p0, p0, flat, nrm, rows=rows, backend=backend)
        assert bad == expect
    monkeypatch.setattr(si, "_prepare", prepare)
    assert si.source_potential_pair(p0, p0, flat, nrm, backend="compiled")[2] == -1


def test_dense_to_csc_is_scipys_permuted_matrix():
    from scipy.sparse import csc_matrix
    rng = np.random.default_rng(3)
    A = rng.normal(size=(60, 60))
    A[rng.random((60, 60)) < 0.6] = 0.0
    order = rng.permutation(60)
    ref = csc_matrix(A)[order][:, order].tocsc()
    ref.sort_indices()
    data, indices, indptr = kernels.dense_to_csc(A, order)
    assert np.array_equal(indptr, ref.indptr) and np.array_equal(indices, ref.indices)
    assert np.array_equal(data, ref.data)
