"""Executors and the Parquet chunk store (no cluster needed).

Sources of truth: the in-process run itself (resumed or streamed runs must
equal it bit for bit) and counting: a resumed run recomputes exactly the
chunks without a file.
"""
from pathlib import Path

import numpy as np
import pytest

pytest.importorskip("pyarrow")

from ironbark_opt.analysis.distributions import load_spec  # noqa: E402
from ironbark_opt.errors import InputError  # noqa: E402
from ironbark_opt.executors import (ChunkStore, LocalExecutor, batch_columns, columns_batch, fly_samples,  # noqa: E402
                                    get_executor, run_chunks)
from ironbark_opt.dynamics.model import FlightModel  # noqa: E402
from ironbark_opt.flight import flight_model  # noqa: E402
from ironbark_opt.vehicle import load_setup  # noqa: E402

ROOT = Path(__file__).resolve().parents[2]


class CountingExecutor(LocalExecutor):
    """In-process executor that records which tasks it ran."""

    def __init__(self):
        super().__init__(1)
        self.ran = []

    def map_unordered(self, func, tasks, *, label="task"):
        for i, res in super().map_unordered(func, tasks, label=label):
            self.ran.append(int(tasks[i][1]))        # the chunk's first sample
            yield i, res


@pytest.fixture(scope="module")
def flown():
    setup = load_setup(ROOT / "examples/calisto/calisto.toml")
    P = load_spec(ROOT / "examples/calisto/dispersions.toml").sample(6, setup.nominal_parameters(),
                                                                    np.random.default_rng(5))
    return setup, P, fly_samples(setup, P, chunk=2, model=FlightModel(setup))


def test_executor_spellings():
    assert get_executor(None).in_process and get_executor("local").name == "local"
    ex = get_executor("local:3")
    assert (ex.processes, ex.in_process, ex.name) == (3, False, "local:3")
    assert get_executor(ex) is ex
    for bad in ("local:0", "local:x", "threads", "dask://", 3.5):
        with pytest.raises(InputError, match="executor"):
            get_executor(bad)


def test_columns_round_trip():
    out = {"apogee_agl": np.array([1.0, 2.0]), "x_apogee": np.arange(26.0).reshape(13, 2)}
    cols = batch_columns(out, 10)
    assert list(cols["sample"]) == [10, 11] and "x_apogee_12" in cols
    back = columns_batch(cols)
    assert np.array_equal(back["x_apogee"], out["x_apogee"]) and np.array_equal(back["apogee_agl"], out["apogee_agl"])


def test_resume_recomputes_only_missing_chunks(flown, tmp_path):
    # every run uses a fresh model (as a new process would): its RK4 grid is
    # fixed by the nominal flight, so resumed == uninterrupted
    setup, P, reference = flown
    out = tmp_path / "run"
    first = CountingExecutor()
    streamed = fly_samples(setup, P, chunk=2, executor=first, output=out, model=FlightModel(setup))
    assert sorted(first.ran) == [0, 2, 4]              # every chunk flown on the executor
    assert len(list(out.glob("chunk-*.parquet"))) == 3
    for key in reference:
        assert np.array_equal(streamed[key], reference[key]), key        # Parquet changes no bit
    # a worker died while writing chunk 1 (only a temporary file) and chunk 2 was never written
    (out / "chunk-000001.parquet").rename(out / "chunk-000001.parquet.ab12cd34.tmp")
    (out / "chunk-000002.parquet").unlink()
    again = CountingExecutor()
    resumed = fly_samples(setup, P, chunk=2, executor=again, output=out, model=FlightModel(setup))
    print(f"resumed run recomputed chunks starting at samples {sorted(again.ran)} (expected [2, 4])")
    assert sorted(again.ran) == [2, 4]
    for key in reference:
        assert np.array_equal(resumed[key], reference[key]), key
    # a complete store is read back without flying anything on the executor
    idle = CountingExecutor()
    fly_samples(setup, P, chunk=2, executor=idle, output=out, model=flight_model(setup))
    assert idle.ran == []


def test_store_refuses_other_runs_and_bad_files(tmp_path):
    store = ChunkStore(tmp_path / "s", "run-a", [(0, 2), (2, 3)])
    store.write(0, {"sample": np.array([0, 1]), "v": np.array([1.0, 2.0])})
    with pytest.raises(InputError, match="different run") as err:
        ChunkStore(tmp_path / "s", "run-b", [(0, 2), (2, 3)])
    assert "manifest.json" in str(err.value)
    with pytest.raises(InputError, match="different run"):
        ChunkStore(tmp_path / "s", "run-a", [(0, 3)])
    store.write(1, {"sample": np.array([7]), "v": np.array([3.0])})
    with pytest.raises(InputError, match="chunk-000001.parquet"):
        store.read(1)
    store.path(1).write_bytes(b"not parquet")
    with pytest.raises(InputError, match="unreadable chunk"):
        store.read(1)
    (tmp_path / "file").write_text("x")
    with pytest.raises(InputError, match="not a directory"):
        ChunkStore(tmp_path / "file", "r", [(0, 1)])


def test_run_chunks_in_order_with_local_processes():
    res = run_chunks(LocalExecutor(2), pow, [(2, k) for k in range(5)])
    assert res == [1, 2, 4, 8, 16]


def test_cli_executor_flags_are_checked():
    from click.testing import CliRunner

    from ironbark_opt.cli import main

    rocket = str(ROOT / "examples/calisto/calisto.toml")
    res = CliRunner().invoke(main, ["ballast", rocket, "--target", "2500m", "--executor", "local:2"])
    assert res.exit_code == 2 and "--executor spreads several --motor" in res.output
    res = CliRunner().invoke(main, ["montecarlo", rocket, "--spec", str(ROOT / "examples/calisto/dispersions.toml"),
                                    "--samples", "2", "--executor", "cluster", "--no-progress"])
    assert res.exit_code == 2 and "executor 'cluster' not understood" in res.output


def test_panel_sweep_hook_runs_one_task_per_mach():
    from panair.mesh import BodyGeometry, FinGeometry, MeshOptions, RocketGeometry
    from panair.sweep import sweep_pressure

    class Recording(LocalExecutor):
        def __init__(self):
            super().__init__(1)
            self.machs = []

        def map_unordered(self, func, tasks, *, label="task"):
            self.machs += [t[0][1] for t in tasks]
            yield from super().map_unordered(func, tasks, label=label)

    body = BodyGeometry(np.array([0.0, 2.84, 10.0]) * 0.03, np.array([0.0, 0.5, 0.5]) * 0.03)
    geom = RocketGeometry(body, (FinGeometry(4, 0.03, 0.03, 0.03, 0.0, 0.27, 0.0024, roll=np.pi / 4),), "bf")
    kw = dict(sref=np.pi * 0.015 ** 2, lref=0.03, xref=0.15, progress=False,
              options=MeshOptions(n_theta=16, n_nose=8, body_spacing=1.0, n_chord=8, n_span=3))
    rec = Recording()
    a, _ = sweep_pressure(geom, [0.3, 0.7], np.radians([0.0, 3.0]), executor=rec, **kw)
    b, _ = sweep_pressure(geom, [0.3, 0.7], np.radians([0.0, 3.0]), workers=1, **kw)
    assert rec.machs == [0.3, 0.7]
    for name in ("CA", "CN", "Cm"):
        assert np.array_equal(a[name], b[name]), name
