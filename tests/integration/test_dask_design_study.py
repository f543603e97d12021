"""Design study on a local Dask cluster: panel solves split per (variant, Mach),
ballast solves per variant; the tidy table equals the in-process run exactly.

Source of truth: the same study run in this process (``executor="local"``).
Tolerance: relative 1e-9.  The panel solver's LU factorisation goes through
OpenBLAS, and Dask workers run it single-threaded (the nanny sets
``OPENBLAS_NUM_THREADS=1``) while this process may use several threads: a
different summation order changes the last bits (measured: 1e-14 relative
in CN_alpha, 3e-12 m in apogee).  The Monte Carlo path does not use BLAS
and is bit-identical (test_dask_montecarlo.py).
"""
from pathlib import Path

import numpy as np
import pytest

distributed = pytest.importorskip("distributed")

from ironbark_opt.analysis.design_study import design_grid, design_study  # noqa: E402
from ironbark_opt.executors import DaskExecutor  # noqa: E402
from panair.mesh import MeshOptions  # noqa: E402

ROOT = Path(__file__).resolve().parents[2]
CALISTO = ROOT / "examples/calisto/calisto.toml"
COARSE = MeshOptions(n_theta=16, n_nose=8, body_spacing=1.0, n_chord=8, n_span=3)


@pytest.mark.slow
def test_design_study_on_dask_equals_local():
    cases = design_grid(fin_span=[0.09, 0.13], fin_root_chord=[0.12])
    kwargs = dict(mesh=COARSE, mach=(0.05, 0.5, 0.9), alpha_deg=(0.0, 4.0, 10.0, 20.0))
    here = design_study(CALISTO, cases, "2500m", executor="local", **kwargs).to_dataframe()
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True, host="127.0.0.1",
                                  dashboard_address=None, worker_dashboard_address=None) as cluster, \
            distributed.Client(cluster, set_as_default=False) as client:
        there = design_study(CALISTO, cases, "2500m", executor=DaskExecutor(client), **kwargs).to_dataframe()
        # every (variant, Mach) panel solve and every ballast solve was a task of its own
        keys = [k for k in client.run_on_scheduler(
            lambda dask_scheduler: list(dask_scheduler.task_prefixes))]
    print(here.to_string())
    assert list(here.columns) == list(there.columns)
    assert here[["variant", "feasible", "status"]].equals(there[["variant", "feasible", "status"]])
    for col in here.columns:
        if here[col].dtype.kind == "f":
            rel = float(np.max(np.abs(there[col] - here[col]) / np.maximum(np.abs(here[col]), 1e-300)))
            print(f"{col}: max relative difference Dask vs local {rel:.1e} (tolerance 1e-9)")
            assert rel <= 1e-9, col
    assert any("panel" in k for k in keys) and any("ballast" in k for k in keys)
