"""Monte Carlo throughput: this process (CasADi thread map) vs a local 2-worker Dask cluster.

Prints, for the bundled Calisto example and its ``dispersions.toml``:

- samples per second with the local executor (chunks in this process, each
  chunk's trajectory Functions mapped over 2 CasADi threads);
- samples per second on a ``LocalCluster`` (2 worker processes, 1 thread
  each, 127.0.0.1): the first run (workers build their model) and a warm
  run (models cached per worker);
- the overhead per chunk on Dask: the wall-time cost of each extra chunk,
  from two warm runs with large and small chunks
  ``(T_small - T_large) / (chunks_small - chunks_large) * workers`` (the
  workers absorb chunks in parallel), and the round trip of a trivial task.

Every Dask run is checked equal to the local one (bit for bit).

Run: ``python benchmarks/bench_dask.py [--samples N] [--chunk N] [--small-chunk N]``.
Needs the optional extra: ``pip install 'ironbark-opt[dask]'``.
"""
from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from ironbark_opt.analysis.distributions import load_spec  # noqa: E402
from ironbark_opt.analysis.montecarlo import montecarlo  # noqa: E402
from ironbark_opt.executors import DaskExecutor  # noqa: E402
from ironbark_opt.flight import flight_model  # noqa: E402
from ironbark_opt.vehicle import load_setup  # noqa: E402

EXAMPLE = ROOT / "examples" / "calisto" / "calisto.toml"
SPEC = ROOT / "examples" / "calisto" / "dispersions.toml"


def timed(fn):
    t = time.perf_counter()
    out = fn()
    return out, time.perf_counter() - t


def main(argv=None) -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--samples", type=int, default=400)
    ap.add_argument("--chunk", type=int, default=50, help="chunk of the main runs")
    ap.add_argument("--small-chunk", type=int, default=5, help="chunk of the overhead run")
    ap.add_argument("--seed", type=int, default=1)
    args = ap.parse_args(argv)
    from distributed import Client, LocalCluster

    setup = load_setup(EXAMPLE)
    spec = load_spec(SPEC)
    n = args.samples
    model = flight_model(setup)

    def run(executor, chunk):
        return montecarlo(setup, spec, n, seed=args.seed, chunk=chunk, executor=executor, progress=False,
                          model=model)

    montecarlo(setup, spec, 4, seed=args.seed, progress=False, model=model)      # build + warm the model
    local, t_local = timed(lambda: run("local", args.chunk))
    ref = local.to_dataframe()
    print(f"samples: {n}, chunk {args.chunk}")
    print(f"local (this process, 2 CasADi threads): {t_local:7.2f} s  {n / t_local:8.1f} samples/s")
    with LocalCluster(n_workers=2, threads_per_worker=1, processes=True, host="127.0.0.1",
                      dashboard_address=None, worker_dashboard_address=None) as cluster, \
            Client(cluster, set_as_default=False) as client:
        ex = DaskExecutor(client)
        rows = []
        for label, chunk in (("dask, first run (model build)", args.chunk), ("dask, warm", args.chunk),
                             ("dask, warm, small chunks", args.small_chunk)):
            disp, t = timed(lambda: run(ex, chunk))
            same = disp.to_dataframe().equals(ref)
            rows.append((chunk, t))
            print(f"{label + f' (chunk {chunk})':46s} {t:7.2f} s  {n / t:8.1f} samples/s  "
                  f"identical to local: {same}")
        (c_big, t_big), (c_small, t_small) = rows[1], rows[2]
        k_big, k_small = -(-n // c_big), -(-n // c_small)
        workers = len(client.nthreads())
        per_chunk = (t_small - t_big) / (k_small - k_big) * workers
        print(f"overhead per chunk (from chunk {c_big} vs {c_small}): {1e3 * per_chunk:7.1f} ms")
        trips = []
        for _ in range(20):
            _, t = timed(lambda: client.submit(int, 1, pure=False).result())
            trips.append(t)
        print(f"trivial task round trip (median of 20): {1e3 * float(np.median(trips)):7.1f} ms")


if __name__ == "__main__":
    main()
