"""Monte Carlo on a local Dask cluster: bit-identical to the local executor,
and exactly-once results when a worker dies mid-run.

Source of truth: the local executor (this process, ``FlightModel.run_batch``)
for the same seed; every comparison is exact (``==`` on float64).  The
cluster is a ``LocalCluster`` of 2 worker processes with 1 thread each on
127.0.0.1, dashboard off: nothing leaves the machine.
"""
from __future__ import annotations

import os
import signal
import threading
import time
from pathlib import Path

import numpy as np
import pandas as pd
import pytest
from click.testing import CliRunner

distributed = pytest.importorskip("distributed")
pytest.importorskip("pyarrow")

from ironbark_opt.analysis.distributions import load_spec  # noqa: E402
from ironbark_opt.analysis.montecarlo import montecarlo  # noqa: E402
from ironbark_opt.cli import main  # noqa: E402
from ironbark_opt.errors import InputError  # noqa: E402
from ironbark_opt.executors import DaskExecutor, get_executor  # noqa: E402
from ironbark_opt.flight import flight_model  # noqa: E402
from ironbark_opt.vehicle import load_setup  # noqa: E402

ROOT = Path(__file__).resolve().parents[2]
EXAMPLE = ROOT / "examples/calisto/calisto.toml"
SPEC = ROOT / "examples/calisto/dispersions.toml"


@pytest.fixture(scope="module")
def cluster():
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True, host="127.0.0.1",
                                  dashboard_address=None, worker_dashboard_address=None) as cl:
        yield cl


@pytest.fixture(scope="module")
def client(cluster):
    with distributed.Client(cluster, set_as_default=False) as c:
        yield c


@pytest.fixture(scope="module")
def setup():
    return load_setup(EXAMPLE)


@pytest.fixture(scope="module")
def local_result(setup):
    """Reference: 12 samples flown in this process."""
    return montecarlo(setup, load_spec(SPEC), 12, seed=7, chunk=5, progress=False, model=flight_model(setup))


def _assert_identical(a, b):
    da, db = a.to_dataframe(), b.to_dataframe()
    assert list(da.columns) == list(db.columns)
    for col in da.columns:
        diff = np.max(np.abs(da[col].to_numpy() - db[col].to_numpy()))
        assert np.array_equal(da[col].to_numpy(), db[col].to_numpy()), f"{col}: max difference {diff!r}"
    print(f"{len(da)} samples x {len(da.columns)} columns identical (tolerance: bit for bit)")


def test_dask_equals_local_bit_for_bit(client, setup, local_result, tmp_path):
    ex = DaskExecutor(client, in_flight=2)
    disp = montecarlo(setup, load_spec(SPEC), 12, seed=7, chunk=4, executor=ex, progress=False)
    _assert_identical(local_result, disp)
    # one model per worker process, however many chunks it ran
    built = client.run(lambda: __import__("ironbark_opt.executors", fromlist=["x"]).models_built())
    print(f"models built per worker: {built}")
    assert all(n == 1 for n in built.values())
    # streamed to Parquet: one file per chunk, same numbers read back
    streamed = montecarlo(setup, load_spec(SPEC), 12, seed=7, chunk=4, executor=ex, progress=False,
                          output=tmp_path / "run")
    _assert_identical(local_result, streamed)
    assert sorted(p.name for p in (tmp_path / "run").glob("chunk-*.parquet")) == [
        f"chunk-{i:06d}.parquet" for i in range(3)]


def test_cli_with_dask_address_and_errors(cluster, local_result, tmp_path):
    address = "dask://" + cluster.scheduler_address.split("://")[1]
    with get_executor(address) as ex:
        assert ex.name == address
    csv = tmp_path / "mc.csv"
    res = CliRunner().invoke(main, ["montecarlo", str(EXAMPLE), "--spec", str(SPEC), "--samples", "12", "--seed",
                                    "7", "--chunk", "6", "--executor", address, "--results-dir",
                                    str(tmp_path / "run"), "--no-progress", "--csv", str(csv), "--json"])
    assert res.exit_code == 0, res.output
    table = pd.read_csv(csv)
    ref = local_result.to_dataframe()
    for col in ("apogee_agl_m", "apogee_east_m", "rail_exit_speed_mps"):   # CSV round-trips float64 exactly
        assert np.array_equal(table[col].to_numpy(), ref[col].to_numpy()), col
    assert len(list((tmp_path / "run").glob("chunk-*.parquet"))) == 2
    with pytest.raises(InputError, match="executor"):
        get_executor("dask://")
    with pytest.raises(InputError, match="no Dask scheduler answers"):
        get_executor("dask://127.0.0.1:1")


@pytest.mark.slow
def test_killed_worker_every_sample_exactly_once(client, setup, tmp_path):
    spec = load_spec(SPEC)
    n, chunk = 48, 4
    reference = montecarlo(setup, spec, n, seed=3, chunk=chunk, progress=False, model=flight_model(setup))
    out = tmp_path / "run"
    pids_before = client.run(os.getpid)
    result: dict = {}

    def run():
        try:
            result["disp"] = montecarlo(setup, spec, n, seed=3, chunk=chunk, executor=DaskExecutor(client),
                                        progress=False, output=out)
        except Exception as err:          # reported by the assertion below
            result["error"] = err

    thread = threading.Thread(target=run)
    thread.start()
    deadline = time.monotonic() + 120
    while not list(out.glob("chunk-*.parquet")) and time.monotonic() < deadline:
        time.sleep(0.05)
    victim = sorted(pids_before.values())[0]
    done_at_kill = len(list(out.glob("chunk-*.parquet")))
    os.kill(victim, signal.SIGKILL)           # a worker dies mid-run, chunks in flight on it are lost
    thread.join(timeout=300)
    assert "error" not in result, result.get("error")
    print(f"killed worker pid {victim} after {done_at_kill} of {n // chunk} chunks")
    assert done_at_kill < n // chunk
    disp = result["disp"]
    samples = disp.to_dataframe()["sample"].to_numpy()
    assert np.array_equal(np.sort(samples), np.arange(n)) and len(samples) == n
    assert len(list(out.glob("chunk-*.parquet"))) == n // chunk and not list(out.glob("*.tmp"))
    _assert_identical(reference, disp)
    assert victim not in client.run(os.getpid).values()


@pytest.mark.slow
def test_motor_choice_on_dask_equals_in_process(client, setup, tmp_path):
    from ironbark_opt.optimise.motor_choice import Candidate, choose_motor

    bad = tmp_path / "broken.eng"
    bad.write_text("this is not a RASP file\n")
    motors = [str(ROOT / "examples/calisto/Cesaroni_M1670.eng"), str(ROOT / "tests/data/motors/AeroTech_M1305M.eng"),
              Candidate("broken", str(bad))]
    # An executor solves each candidate on its own model; in this process that is the
    # "local" executor (the same per-motor solve a worker runs): bit for bit.
    here = choose_motor(setup, motors, "2500m", executor="local")
    there = choose_motor(setup, motors, "2500m", executor=DaskExecutor(client))
    print(here.summary())
    assert [s.motor for s in here.solutions] == [s.motor for s in there.solutions] == ["M1670-BS", "M1305M"]
    for a, b in zip(here.solutions, there.solutions):
        assert {k: v for k, v in a.values.items() if k != "solve_time_s"} == \
            {k: v for k, v in b.values.items() if k != "solve_time_s"}
    assert [f[0] for f in here.failures] == [f[0] for f in there.failures] == ["broken"]
    # The default in-process ranking (processes=1) solves tabulated motors in one motor-slot
    # NLP (motor data and RK4 grids in p, optimise/motor_choice._solve_slotted): another
    # operation sequence, equal to the per-motor solves within the tolerances of
    # tests/validation/test_motor_choice_slot.py (not to the bit: ~1e-15 relative)
    slotted = choose_motor(setup, motors, "2500m", processes=1)
    assert [s.motor for s in slotted.solutions] == [s.motor for s in there.solutions]
    for a, b in zip(slotted.solutions, there.solutions):
        assert abs(a.ballast - b.ballast) < 1e-6                            # kg
        for k in ("apogee_agl_m", "resimulated_apogee_agl_m", "rail_exit_speed_mps", "launch_mass_kg"):
            assert a.values[k] == pytest.approx(b.values[k], rel=1e-9, abs=1e-9), k
