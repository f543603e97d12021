"""The panel solvers' faster linear algebra against the plain double-precision
solve it replaced: the causal (sparse) LU of the supersonic influence matrix,
the single-precision LU refined to double of the subsonic one (LAPACK DSGESV
scheme), and the vectorised inverse Prandtl-Meyer function against Brent's
method."""
import numpy as np
import pytest
import scipy.linalg
from scipy.optimize import brentq

from ironbark_opt.errors import SolverError
from panair.solver import make_solver, subsonic, supersonic
from panair.solver.nose_correction import G, _pm, _pm_inverse


def _captured(monkeypatch, module, cls):
    """Build through ``module.cls`` and keep a copy of the matrix it was given."""
    seen = []
    orig = getattr(module, cls)

    def make(A, *args):
        seen.append(np.array(A, copy=True))
        return orig(A, *args)
    monkeypatch.setattr(module, cls, make)
    return seen


def test_causal_lu_solves_the_supersonic_matrix_as_a_dense_lu(coarse_finner_panels, monkeypatch):
    seen = _captured(monkeypatch, supersonic, "CausalLU")
    make_solver(coarse_finner_panels, 2.5, sref=np.pi / 4, lref=1.0, xref=5.0)
    A = seen[0]
    assert (A == 0).mean() > 0.3                    # causality: most pairs are out of the cone
    rng = np.random.default_rng(1)
    b = rng.standard_normal((len(A), 3))
    for x in (np.arange(len(A), dtype=float), rng.permutation(len(A)).astype(float)):
        lu = supersonic.CausalLU(A, x)               # any order solves the same system
        ref = scipy.linalg.solve(A, b)
        np.testing.assert_allclose(lu.solve(b), ref, rtol=0, atol=1e-11 * np.abs(ref).max())
        np.testing.assert_allclose(lu.solve(b[:, 0]), ref[:, 0], rtol=0,
                                   atol=1e-11 * np.abs(ref).max())


def test_causal_lu_reports_a_singular_matrix():
    A = np.tril(np.ones((5, 5)))
    A[3] = A[2]                                      # duplicated row (duplicated panel)
    with pytest.raises(SolverError, match="singular"):
        supersonic.CausalLU(A, np.arange(5.0))


def test_refined_lu_reaches_the_double_precision_solution(coarse_finner_panels, monkeypatch):
    seen = _captured(monkeypatch, subsonic, "RefinedLU")
    make_solver(coarse_finner_panels, 0.5, sref=np.pi / 4, lref=1.0, xref=5.0)
    A = seen[0]
    b = np.random.default_rng(2).standard_normal((len(A), 4))
    lu = subsonic.RefinedLU(A.copy())
    assert lu._lu64 is None                          # single precision + refinement used
    ref = scipy.linalg.lu_solve(scipy.linalg.lu_factor(A), b)
    np.testing.assert_allclose(lu.solve(b), ref, rtol=0, atol=1e-13 * np.abs(ref).max())


def test_refined_lu_falls_back_to_double_where_single_precision_cannot_judge():
    rng = np.random.default_rng(3)
    n = 60
    u, _ = np.linalg.qr(rng.standard_normal((n, n)))
    v, _ = np.linalg.qr(rng.standard_normal((n, n)))
    A = u @ np.diag(np.logspace(0, -11, n)) @ v.T     # condition 1e11 >> 1 / eps_single
    x = rng.standard_normal(n)
    b = A @ x
    lu = subsonic.RefinedLU(A.copy())
    got = lu.solve(b)
    assert lu._lu64 is not None                       # refined in double
    ref = scipy.linalg.lu_solve(scipy.linalg.lu_factor(A), b)
    np.testing.assert_allclose(got, ref, rtol=0, atol=1e-12 * np.abs(ref).max())


@pytest.mark.parametrize("mach", [1.2, 2.0, 3.5])
def test_inverse_prandtl_meyer_against_brent(mach):
    nu_max = 0.5 * np.pi * (np.sqrt((G + 1) / (G - 1)) - 1)
    nu = _pm(mach) + np.linspace(1e-6, 0.999 * nu_max - _pm(mach), 300)
    nu = nu[nu < _pm(1e3)]
    ref = np.array([brentq(lambda m, v=v: _pm(m) - v, mach, 1e3, xtol=1e-14) for v in nu])
    got = _pm_inverse(nu, mach, 1e3)
    np.testing.assert_allclose(got, ref, rtol=1e-12)
    np.testing.assert_allclose(_pm(got), nu, rtol=0, atol=1e-14)
