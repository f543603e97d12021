"""A supersonic Mach number linear theory refuses on its mesh is tried on a coarser and a
finer mesh before local inclination (panair.sweep._remesh_refused, REMESH_REFINE).

The refusal is simulated (a local singularity that only some panel layouts have is
expensive to reproduce on a unit-test body: tests/validation/test_random_rockets.py
seeds 37, 45, 49 have real ones); the retry's numbers are checked against an
independent sweep meshed at that refinement from the start, and a resumed sweep keeps
them and the record without solving again."""
from __future__ import annotations

import numpy as np
import pytest

from model_toml import model_panel_geometry

D = 0.1
MACH = 1.5
ALPHA = np.radians([0.0, 2.0])


@pytest.fixture(scope="module")
def geometry(tmp_path_factory):
    rk, geom, sym = model_panel_geometry(tmp_path_factory.mktemp("refine"), "von Karman 3 + 5 cal",
                                         calibre=D, nose_shape="von_karman", nose_calibres=3,
                                         body_calibres=5, cg_x=4 * D)
    return geom, sym, rk.reference_area()


def test_refused_mach_solved_on_a_coarser_mesh_and_resumed(geometry, tmp_path, monkeypatch):
    import panair.sweep as S
    from panair.mesh import MeshOptions
    geom, sym, sref = geometry
    kw = dict(sref=sref, lref=D, xref=0.0, symmetric=sym, workers=1, progress=False)
    ref, _ = S.sweep_pressure(geom, np.array([MACH]), ALPHA, options=MeshOptions(refine=0.8), **kw)
    real = S._solve_one

    def refuse_but_coarse(job):
        mesh = job[0]
        if isinstance(mesh, S._OwnMesh) and mesh.options.refine == 0.8:
            return real(job)
        panels = mesh.build() if isinstance(mesh, S._OwnMesh) else mesh
        return S._local_inclination(panels, job[1], job[2], *job[3:6])
    monkeypatch.setattr(S, "_solve_one", refuse_but_coarse)
    got, info = S.sweep_pressure(geom, np.array([MACH]), ALPHA, checkpoint_dir=tmp_path, **kw)
    print("\nrefused Mach 1.5 retried:", info["mach_remeshed_refine"], "CN(2 deg)",
          got["CN"][0, 1], "vs the refine 0.8 sweep", ref["CN"][0, 1])
    assert info["mach_local_inclination"] == []
    assert info["mach_remeshed_refine"] == {"1.5": 0.8} and MACH in info["mach_remeshed"]
    for c in ("CA", "CN", "Cm"):
        np.testing.assert_allclose(got[c], ref[c], rtol=1e-9, atol=1e-12)

    def fail(*_):
        raise AssertionError("solved again")
    monkeypatch.setattr(S, "_solve_one", fail)
    again, info2 = S.sweep_pressure(geom, np.array([MACH]), ALPHA, checkpoint_dir=tmp_path, **kw)
    assert info2["mach_remeshed_refine"] == info["mach_remeshed_refine"]
    assert info2["mach_local_inclination"] == []
    for c in ("CA", "CN", "Cm"):
        np.testing.assert_array_equal(got[c], again[c])


def test_refused_everywhere_falls_to_local_inclination(geometry, monkeypatch):
    """Where no mesh solves it, the Mach number stays on local inclination (recorded)."""
    import panair.sweep as S
    geom, sym, sref = geometry
    tried = []

    def refuse(job):
        mesh = job[0]
        tried.append(mesh.options.refine if isinstance(mesh, S._OwnMesh) else None)
        panels = mesh.build() if isinstance(mesh, S._OwnMesh) else mesh
        return S._local_inclination(panels, job[1], job[2], *job[3:6])
    monkeypatch.setattr(S, "_solve_one", refuse)
    _, info = S.sweep_pressure(geom, np.array([MACH]), ALPHA, sref=sref, lref=D, xref=0.0,
                               symmetric=sym, workers=1, progress=False)
    assert info["mach_local_inclination"] == [MACH] and info["mach_remeshed_refine"] == {}
    assert {0.8, 1.25} <= set(tried)
