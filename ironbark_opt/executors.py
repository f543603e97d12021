"""Where chunks of independent work run: this process, local processes or a Dask cluster.

Big studies (10^5 Monte Carlo samples, motor lists, per-geometry sweeps)
are cut into **chunks** of independent tasks.  An :class:`Executor` runs a
picklable function over a list of task arguments and yields
``(index, result)`` as chunks finish:

- :class:`LocalExecutor` — this process (``processes=1``, the default: the
  chunk's CasADi ``map`` already uses threads) or a local process pool;
- :class:`DaskExecutor` — a ``dask.distributed`` cluster (the optional
  extra ``pip install ironbark-opt[dask]``), with a bounded number of
  chunks in flight so a huge run never queues everything at once.  A
  worker that dies mid-chunk loses only that chunk; the scheduler runs it
  again elsewhere.

:func:`get_executor` turns the user's spelling (``None``, ``"local"``,
``"local:4"``, ``"dask://host:8786"``, a ``distributed.Client`` or an
Executor) into one.

Results can stream to a :class:`ChunkStore`: one Parquet file per chunk,
written atomically (temporary file + ``os.replace``), plus a manifest
naming the run.  Re-running the same study into the same directory
recomputes only the chunks without a file — never duplicating or dropping
one — so a run survives a dead client as well as a dead worker.

Setups travel as a :class:`SetupPayload` (the pickled ``FlightSetup``:
forecast atmospheres and overrides included, no shared rocket files
needed); each worker process builds the compiled trajectory Functions once
per payload (:func:`worker_model`) and reuses them for every chunk.

Numeric-only.
"""
from __future__ import annotations

import abc

import hashlib
import json
import os
import pickle
import threading
import uuid
from collections import OrderedDict
from contextlib import contextmanager
from dataclasses import dataclass
from pathlib import Path
from typing import Callable, Iterator, Sequence

import numpy as np

from ironbark_opt.dynamics.integrator import jit_mode
from ironbark_opt.errors import InputError, IronbarkError

DASK_SCHEME = "dask://"
MANIFEST = "manifest.json"
STORE_FORMAT = "ironbark-chunks/1"
_INSTALL_HINT = "install the optional extra: pip install 'ironbark-opt[dask]'"


# ---------------------------------------------------------------- executors
class Executor(abc.ABC):
    """Runs ``func(*args)`` for every ``args`` in a task list (abstract).

    Attributes
    ----------
    name : str
        ``"local"``, ``"local:N"`` or ``"dask://..."`` (for reports).
    in_process : bool
        True when tasks run in this process (callers may then pass
        unpicklable objects such as an already built model).
    """

    name = "executor"
    in_process = False

    @abc.abstractmethod
    def map_unordered(self, func: Callable, tasks: Sequence[tuple], *, label: str = "task") -> Iterator:
        """Yield ``(index, func(*tasks[index]))`` as tasks finish (any order)."""

    def close(self) -> None:
        """Release what this executor started (nothing by default)."""

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()


class LocalExecutor(Executor):
    """This machine: in this process (``processes=1``) or a process pool.

    Parameters
    ----------
    processes : int
        1 runs tasks one after the other in this process (each Monte Carlo
        chunk still uses CasADi's thread map); more starts a process pool.
    """

    def __init__(self, processes: int = 1):
        if isinstance(processes, bool) or not isinstance(processes, (int, np.integer)) or processes < 1:
            raise InputError(f"processes must be a positive integer, got {processes!r}", field="executor")
        self.processes = int(processes)
        self.in_process = self.processes == 1
        self.name = "local" if self.in_process else f"local:{self.processes}"

    def __repr__(self) -> str:
        return f"LocalExecutor(processes={self.processes})"

    def map_unordered(self, func, tasks, *, label="task"):
        if self.in_process or len(tasks) <= 1:
            for i, args in enumerate(tasks):
                yield i, func(*args)
            return
        # imported here: concurrent.futures.process (multiprocessing, socket, logging) is ~15 ms
        # of start-up that the in-process path (the CLI's default) never uses
        from concurrent.futures import FIRST_COMPLETED, ProcessPoolExecutor, wait

        with ProcessPoolExecutor(max_workers=min(self.processes, len(tasks))) as pool:
            pending = {pool.submit(func, *args): i for i, args in enumerate(tasks)}
            while pending:
                done, _ = wait(pending, return_when=FIRST_COMPLETED)
                for fut in done:
                    yield pending.pop(fut), fut.result()


class DaskExecutor(Executor):
    """A ``dask.distributed`` cluster.

    Parameters
    ----------
    address : str or distributed.Client
        ``"dask://host:port"``, ``"tcp://host:port"``, ``"host:port"`` or a
        connected Client (which this executor then does not close).
    in_flight : int, optional
        Most chunks submitted at once (default: 2 per worker thread, at
        least 4): results stream back, nothing waits in a huge queue.
    retries : int
        Extra attempts for a chunk whose task raised (a lost worker is
        handled by the scheduler itself and needs none); an error that
        persists reaches the caller with its own type (InputError, ...).
    timeout : float [s]
        Time to wait when connecting to the scheduler.
    """

    in_process = False

    def __init__(self, address, *, in_flight: int | None = None, retries: int = 1, timeout: float = 30.0):
        try:
            import distributed
        except ImportError:
            raise InputError(f"a Dask executor needs dask.distributed: {_INSTALL_HINT}", field="executor") from None
        if isinstance(address, distributed.Client):
            self.client, self._owned = address, False
        else:
            addr = str(address)
            if addr.startswith(DASK_SCHEME):
                addr = addr[len(DASK_SCHEME):]
            if not addr:
                raise InputError("executor 'dask://' needs HOST:PORT of the scheduler", field="executor")
            if "://" not in addr:
                addr = "tcp://" + addr
            _check_reachable(addr, timeout)
            try:
                self.client = distributed.Client(addr, timeout=timeout, set_as_default=False)
            except (OSError, TimeoutError) as err:
                raise InputError(f"cannot connect to the Dask scheduler at {addr}: {err}; start it with "
                                 "'dask scheduler' and check host, port and firewall", field="executor") from None
            self._owned = True
        self.in_flight = in_flight
        self.retries = int(retries)
        self.name = DASK_SCHEME + str(self.client.scheduler.address).split("://")[-1]

    def __repr__(self) -> str:
        return f"DaskExecutor({self.name!r})"

    def threads(self) -> int:
        """Worker threads in the cluster right now."""
        return int(sum(self.client.nthreads().values())) or 1

    def map_unordered(self, func, tasks, *, label="task"):
        from distributed import as_completed

        run = f"ironbark-{label}-{uuid.uuid4().hex[:10]}"
        window = self.in_flight or max(4, 2 * self.threads())
        queue = iter(enumerate(tasks))
        index: dict = {}

        def submit_next():
            item = next(queue, None)
            if item is None:
                return None
            i, args = item
            fut = self.client.submit(func, *args, key=f"{run}-{i}", retries=self.retries)
            index[fut.key] = i
            return fut

        first = [f for f in (submit_next() for _ in range(window)) if f is not None]
        if not first:
            return
        done = as_completed(first, loop=self.client.loop)
        try:
            for fut in done:
                i = index.pop(fut.key)
                result = fut.result()
                fut.release()
                yield i, result
                nxt = submit_next()
                if nxt is not None:
                    done.add(nxt)
        finally:                                 # stopped early (error, interrupt): cancel the rest
            if index:
                self.client.cancel(list(done.futures))

    def close(self) -> None:
        if self._owned:
            self.client.close()


def _check_reachable(addr: str, timeout: float) -> None:
    """Fail fast (InputError) when nothing listens at a ``tcp://host:port`` address."""
    import socket
    from urllib.parse import urlsplit

    if not addr.startswith("tcp://"):
        return
    try:
        parts = urlsplit(addr)
        host, port = parts.hostname, parts.port
    except ValueError:
        host, port = None, None
    if not host or port is None:
        raise InputError(f"executor address {addr!r}: expected dask://HOST:PORT", field="executor")
    try:
        socket.create_connection((host, port), timeout=min(timeout, 5.0)).close()
    except OSError as err:
        raise InputError(f"no Dask scheduler answers at {host}:{port} ({err.strerror or err}); start one with "
                         "'dask scheduler' (see docs/cluster.md) or run with executor='local'",
                         field="executor") from None


def get_executor(spec=None) -> Executor:
    """An :class:`Executor` from its spelling.

    Parameters
    ----------
    spec : None, str, Executor or distributed.Client
        ``None`` or ``"local"`` (this process), ``"local:N"`` (N local
        processes), ``"dask://HOST:PORT"`` (a Dask scheduler), a
        ``distributed.Client`` or an Executor (returned as is).
    """
    if isinstance(spec, Executor):
        return spec
    if spec is None or spec == "local":
        return LocalExecutor()
    if isinstance(spec, str):
        if spec.startswith("local:"):
            try:
                n = int(spec[len("local:"):])
            except ValueError:
                n = 0
            if n < 1:
                raise InputError(f"executor {spec!r}: expected 'local:N' with N a positive integer",
                                 field="executor")
            return LocalExecutor(n)
        if spec.startswith(DASK_SCHEME):
            return DaskExecutor(spec)
        raise InputError(f"executor {spec!r} not understood: expected 'local', 'local:N' or "
                         "'dask://HOST:PORT'", field="executor")
    if type(spec).__name__ == "Client" and type(spec).__module__.startswith("distributed"):
        return DaskExecutor(spec)
    raise InputError(f"executor must be None, 'local', 'local:N', 'dask://HOST:PORT', a distributed.Client or "
                     f"an Executor, got {type(spec).__name__}", field="executor")


@contextmanager
def use_executor(spec=None):
    """Context manager: :func:`get_executor`, closing it afterwards only if it was made here."""
    ex = get_executor(spec)
    try:
        yield ex
    finally:
        if ex is not spec:
            ex.close()


# ---------------------------------------------------------------- setups on workers
@dataclass(frozen=True)
class SetupPayload:
    """A ``FlightSetup`` as bytes, to ship to other processes.

    Attributes
    ----------
    data : bytes
        The pickled setup.
    digest : str
        SHA-256 of ``data`` (the per-worker model cache key).
    """

    data: bytes
    digest: str

    @classmethod
    def of(cls, setup) -> "SetupPayload":
        """Pickle ``setup``; InputError if it holds something unpicklable."""
        try:
            data = pickle.dumps(setup, protocol=pickle.HIGHEST_PROTOCOL)
        except (pickle.PicklingError, TypeError, AttributeError) as err:
            raise InputError(f"the flight setup cannot be sent to other processes ({err}); run with "
                             "executor='local'", field="executor") from None
        return cls(data, hashlib.sha256(data).hexdigest())

    def load(self):
        """The setup (a fresh copy)."""
        return pickle.loads(self.data)


_MODELS: "OrderedDict[tuple, object]" = OrderedDict()
_MODELS_LOCK = threading.Lock()
_MODELS_KEEP = 4


def discretisation(model) -> tuple[int, int, float]:
    """``(n_boost, n_coast, coast_grading)`` of ``model`` (the client's, sent to workers)."""
    return model.discretisation()


def _impose_steps(model, steps: tuple) -> None:
    # The grid is fixed from the nominal flight when a model is built, so a
    # worker's own choice equals the client's; imposing it also covers a
    # client that changed its grid (``set_discretisation``).
    model.set_discretisation(*steps)


def worker_model(payload: SetupPayload, jit="auto", steps: tuple | None = None):
    """The FlightModel of ``payload``, built once per process and reused.

    Parameters
    ----------
    payload : SetupPayload
    jit : bool
    steps : (int, int, float), optional
        ``(n_boost, n_coast, coast_grading)`` imposed on the model (the client's
        :func:`discretisation`), so every worker flies the same RK4 grid.

    Keyed by the payload digest, ``jit`` and ``steps``; the last few models are kept.
    """
    key = (payload.digest, jit_mode(jit), None if steps is None else tuple(steps))
    with _MODELS_LOCK:
        model = _MODELS.get(key)
        if model is None:
            from ironbark_opt.dynamics.model import FlightModel
            model = FlightModel(payload.load(), jit=jit)
            if steps is not None:
                _impose_steps(model, key[2])
            _MODELS[key] = model
            while len(_MODELS) > _MODELS_KEEP:
                _MODELS.popitem(last=False)
        _MODELS.move_to_end(key)
        return model


def models_built() -> int:
    """Models in this process's worker cache (for tests and benchmarks)."""
    return len(_MODELS)


# ---------------------------------------------------------------- Monte Carlo chunks
def batch_columns(out: dict, start: int) -> dict:
    """:meth:`FlightModel.run_batch` output -> flat columns (``x_apogee_0..12``) with ``sample``."""
    cols = {}
    for key, value in out.items():
        value = np.asarray(value, dtype=float)
        if value.ndim == 2:
            for k in range(value.shape[0]):
                cols[f"{key}_{k}"] = value[k]
        else:
            cols[key] = value
    n = len(next(iter(cols.values())))
    return {"sample": np.arange(start, start + n, dtype=np.int64), **cols}


def columns_batch(cols: dict) -> dict:
    """Inverse of :func:`batch_columns` (the ``sample`` column is dropped)."""
    out, stacks = {}, {}
    for key, value in cols.items():
        if key == "sample":
            continue
        head, _, tail = key.rpartition("_")
        if head in ("x_apogee", "x_landing") and tail.isdigit():
            stacks.setdefault(head, {})[int(tail)] = value
        else:
            out[key] = np.asarray(value)
    for head, rows in stacks.items():
        out[head] = np.vstack([rows[k] for k in sorted(rows)])
    return out


def fly_chunk(payload: SetupPayload, steps: tuple, P: np.ndarray, start: int, descent: bool,
              jit: bool) -> dict:
    """Worker task: fly the columns of ``P`` (samples ``start...``) on the RK4 grid ``steps`` -> flat columns."""
    return batch_columns(worker_model(payload, jit, steps).run_batch(P, descent=descent), start)


# ---------------------------------------------------------------- chunk store
class ChunkStore:
    """One Parquet file per chunk plus a manifest, in ``directory``.

    Parameters
    ----------
    directory : path-like
        Created if missing.  A manifest already there must describe the
        same run (same ``run`` token and chunk bounds), else InputError:
        results of a different study are never mixed.
    run : str
        Token naming the study (e.g. a hash of setup, samples and options).
    bounds : sequence of (start, stop)
        Sample range of each chunk.
    """

    def __init__(self, directory, run: str, bounds: Sequence[tuple[int, int]]):
        import importlib.util

        if importlib.util.find_spec("pyarrow") is None:
            raise InputError(f"streaming results to Parquet needs pyarrow: {_INSTALL_HINT}", field="output")
        self.directory = Path(directory)
        self.bounds = [(int(a), int(b)) for a, b in bounds]
        self.run = str(run)
        if self.directory.exists() and not self.directory.is_dir():
            raise InputError("results path exists and is not a directory", source=self.directory)
        self.directory.mkdir(parents=True, exist_ok=True)
        manifest = {"format": STORE_FORMAT, "run": self.run, "chunks": [list(b) for b in self.bounds]}
        path = self.directory / MANIFEST
        if path.exists():
            try:
                old = json.loads(path.read_text())
            except (OSError, ValueError) as err:
                raise InputError(f"unreadable manifest ({err})", source=path) from None
            if old.get("format") != STORE_FORMAT or old.get("run") != self.run or old.get("chunks") != manifest["chunks"]:
                raise InputError("this results directory holds a different run (other setup, samples, seed or "
                                 "chunking): use a new directory or delete it", source=path, field="run")
        else:
            _atomic_write(path, json.dumps(manifest, indent=1).encode())

    def path(self, i: int) -> Path:
        """File of chunk ``i``."""
        return self.directory / f"chunk-{i:06d}.parquet"

    def done(self) -> set[int]:
        """Chunks already on disk."""
        return {i for i in range(len(self.bounds)) if self.path(i).exists()}

    def write(self, i: int, cols: dict) -> None:
        """Write chunk ``i`` atomically (a reader never sees half a file)."""
        import pyarrow as pa
        import pyarrow.parquet as pq

        table = pa.table({k: np.asarray(v) for k, v in cols.items()})
        tmp = self.path(i).with_suffix(f".{uuid.uuid4().hex[:8]}.tmp")
        pq.write_table(table, tmp)
        os.replace(tmp, self.path(i))

    def read(self, i: int) -> dict:
        """Columns of chunk ``i``, checked to hold exactly its samples."""
        import pyarrow.parquet as pq

        try:
            table = pq.read_table(self.path(i))
        except (OSError, ValueError) as err:
            raise InputError(f"unreadable chunk file ({err}); delete it to recompute it", source=self.path(i)) from None
        cols = {name: table.column(name).to_numpy() for name in table.column_names}
        a, b = self.bounds[i]
        if "sample" in cols and not np.array_equal(cols["sample"], np.arange(a, b)):
            raise InputError(f"chunk holds samples other than {a}..{b - 1}; delete it to recompute it",
                             source=self.path(i), field="sample")
        return cols


def _atomic_write(path: Path, data: bytes) -> None:
    tmp = path.with_suffix(f".{uuid.uuid4().hex[:8]}.tmp")
    tmp.write_bytes(data)
    os.replace(tmp, path)


def run_chunks(executor: Executor, func: Callable, tasks: Sequence[tuple], *, store: ChunkStore | None = None,
               on_chunk: Callable[[int, int], None] | None = None, label: str = "chunk") -> list:
    """Run every task once (skipping chunks already in ``store``); results in task order.

    Parameters
    ----------
    executor : Executor
    func : callable
        ``func(*tasks[i])`` -> a dict of equal-length columns (with a store)
        or any picklable result.
    tasks : sequence of tuple
    store : ChunkStore, optional
        Results are written there as they arrive and read back at the end.
    on_chunk : callable, optional
        ``on_chunk(index, finished_count)`` after each chunk (progress bars).
    """
    results: dict[int, object] = {}
    have = set() if store is None else store.done()
    todo = sorted(set(range(len(tasks))) - have)
    finished = 0
    for i in sorted(have):                  # already done: count them for progress bars
        finished += 1
        if on_chunk is not None:
            on_chunk(i, finished)
    try:
        for j, res in executor.map_unordered(func, [tasks[i] for i in todo], label=label):
            i = todo[j]
            if store is not None:
                store.write(i, res)
            else:
                results[i] = res
            finished += 1
            if on_chunk is not None:
                on_chunk(i, finished)
    except IronbarkError:
        raise
    except Exception as err:
        if type(err).__name__ == "KilledWorker":
            raise IronbarkError(f"a {label} killed its Dask workers repeatedly ({err}); "
                                + ("re-run into the same results directory to resume" if store else
                                   "check worker memory and logs")) from err
        raise
    if store is not None:
        return [store.read(i) for i in range(len(tasks))]
    return [results[i] for i in range(len(tasks))]


def fly_samples(setup, P: np.ndarray, *, descent: bool = False, chunk: int = 250, executor=None,
                output=None, jit="auto", model=None, on_chunk=None) -> dict:
    """Fly every column of ``P`` in chunks on ``executor`` (the Monte Carlo engine).

    Parameters
    ----------
    setup : FlightSetup
    P : ndarray (params.SIZE, n)
        Parameter samples [SI].
    descent : bool
        Fly to landing.
    chunk : int
        Samples per task; results do not depend on it.
    executor : see :func:`get_executor`
    output : path-like, optional
        Directory for the Parquet chunk store; a run interrupted there
        resumes, recomputing only the missing chunks.
    jit : bool
        Compiled trajectory Functions.
    model : FlightModel, optional
        The client's model (default: :func:`ironbark_opt.flight.flight_model`);
        chunks in this process fly it, and remote workers use its RK4 grid.
    on_chunk : callable, optional
        ``on_chunk(samples_in_chunk)`` after each chunk.

    Returns
    -------
    dict as :meth:`FlightModel.run_batch`, over all ``n`` samples, in order.
    """
    P = np.asarray(P, dtype=float)
    n = P.shape[1]
    bounds = [(a, min(a + int(chunk), n)) for a in range(0, n, int(chunk))]
    with use_executor(executor) as ex:
        from ironbark_opt.flight import flight_model

        model = model or flight_model(setup, jit=jit)
        payload = SetupPayload.of(setup) if (output is not None or not ex.in_process) else None
        store = None
        if output is not None:
            token = hashlib.sha256(payload.digest.encode() + np.ascontiguousarray(P).tobytes()
                                   + repr((bool(descent), jit_mode(jit))).encode()).hexdigest()[:32]
            store = ChunkStore(output, token, bounds)
        if ex.in_process:
            def func(P_c, a, descent_, jit_):
                return batch_columns(model.run_batch(P_c, descent=descent_), a)
            tasks = [(P[:, a:b], a, bool(descent), jit_mode(jit)) for a, b in bounds]
        else:
            steps = discretisation(model)
            func = fly_chunk
            mode = jit_mode(jit)
            if mode == "auto" and getattr(model, "_one_library", False):
                # workers fly what this process flies: its compiled library (loaded from the
                # cache, else compiled) or the VM, whose Mach tables differ from the
                # library's in the last bits (dynamics.model.FlightModel._library_twin)
                mode = bool(model._lib)
            tasks = [(payload, steps, P[:, a:b], a, bool(descent), mode) for a, b in bounds]
        cb = None if on_chunk is None else (lambda i, _k: on_chunk(bounds[i][1] - bounds[i][0]))
        parts = run_chunks(ex, func, tasks, store=store, on_chunk=cb, label="montecarlo")
    cols = {key: np.concatenate([p[key] for p in parts]) for key in parts[0]}
    if not np.array_equal(cols["sample"], np.arange(n)):
        raise IronbarkError("internal: chunk results do not cover every sample exactly once")
    return columns_batch(cols)
