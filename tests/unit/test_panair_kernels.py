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
            assert getattr(rc, k) == pytest.approx(getattr(rn, k), rel=RTOL, abs=1e-14)
    assert res_c[-1].CN > 0.1                                  # a lifting solution was compared


def test_backend_argument_is_checked(finner):
    flat, cen, nrm, _ = finner.geometry(1.0)
    with pytest.raises(ValueError, match="backend"):
        influence_matrices(cen[:2], flat, nrm, backend="fortran")
