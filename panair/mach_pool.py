"""One process pool for the Mach-number jobs of several panel sweeps, the costliest
job first across all of them (numeric-only plumbing).

``ironbark aero build`` of a multi-stage rocket builds one table per flight
configuration (the stack, the sustainer).  Each sweep in its own pool ran the
configurations one after the other: the first pool's last jobs and the second
pool's start left a core idle, and each pool started its workers anew.  Here the
sweeps (one thread each, :func:`panair.sweep.sweep_pressure` with ``pool``) submit
to one pool; at most ``workers`` jobs run at a time and a free worker takes the
queued job of the largest ``cost`` (a sweep's estimate: panels squared, more for a
supersonic matrix), whichever sweep it belongs to, so the jobs left at the end are
short ones and the workers end together.  Each worker runs with one BLAS thread
(:mod:`panair.blas_threads`) and keeps the memory it frees (:func:`_keep_freed_memory`).

The worker processes are started (forked) when the pool is made, before the sweeps'
threads run, so no worker is forked while another thread of this process holds a
lock; the solver's kernels are compiled (or loaded from their cache) before
(:func:`panair.solver.kernels.warm_up`), so the workers inherit them.
"""
from __future__ import annotations

import heapq
import itertools
import threading
from concurrent.futures import CancelledError, Future, ProcessPoolExecutor
from concurrent.futures.process import BrokenProcessPool

from .blas_threads import limit_blas_threads

__all__ = ["MachPool"]


#: glibc's ``mallopt`` parameters (malloc.h)
_M_TRIM_THRESHOLD, _M_MMAP_THRESHOLD = -1, -3


def _keep_freed_memory() -> bool:
    """Let glibc's malloc serve large blocks from the heap and keep freed memory
    (``mallopt(M_MMAP_THRESHOLD, 1 GiB)``, ``mallopt(M_TRIM_THRESHOLD, 2 GiB)``; glibc
    manual, "Malloc Tunable Parameters"), so a worker's next Mach number reuses the
    pages of the last one's matrices instead of faulting fresh ones in (by default a
    block above 32 MiB is mmap'ed and given back when freed: every matrix of every
    Mach number was new memory, zeroed by the kernel page by page).  Measured (the
    two-stage fixture's stack, Mach 0.05, 0.5, 0.9, 1.2, 1.5, 2.0 solved one after the
    other in one process, machine loaded): minor page faults 1.16 M -> 0.82 M, system
    CPU 11.1 -> 4.4 s (subsonic Mach numbers after the first: 47 k faults -> 0).  The
    worker holds its largest Mach number's memory until the pool ends.  Best effort:
    without glibc nothing changes (only speed depends on it)."""
    import ctypes
    try:
        fn = ctypes.CDLL(None).mallopt
    except (OSError, AttributeError, TypeError):     # no glibc (macOS: no mallopt; Windows: no CDLL(None))
        return False
    fn.argtypes, fn.restype = [ctypes.c_int, ctypes.c_int], ctypes.c_int
    return bool(fn(_M_MMAP_THRESHOLD, 1 << 30)) and bool(fn(_M_TRIM_THRESHOLD, (1 << 31) - 1))


def _init_worker() -> None:
    limit_blas_threads(1)
    _keep_freed_memory()


def _ready() -> bool:
    return True


def _worker_died(err: BaseException) -> SolverError:
    """A worker process ended without a result (the pool is broken: every job fails).
    The usual cause is the system's out-of-memory killer on a large dense solve."""
    from ironbark_opt.errors import SolverError
    out = SolverError("a panel-solve worker process died without a result (killed by the system, most "
                      "likely out of memory: the dense panel matrices grow with the square of the panel "
                      "count); build with fewer workers (--workers 1) or a coarser mesh (--refine below 1)")
    out.__cause__ = err
    return out


class MachPool:
    """``workers`` processes and a queue ordered by cost (largest first).

    Use as a context manager; :meth:`submit` returns a Future."""

    def __init__(self, workers: int):
        from .solver.kernels import warm_up
        warm_up()                        # compiled (or loaded) here, inherited by the workers
        self.workers = int(workers)
        self._pool = ProcessPoolExecutor(max_workers=self.workers, initializer=_init_worker)
        for f in [self._pool.submit(_ready) for _ in range(self.workers)]:
            f.result()                   # every worker forked now, from this thread alone
        self._lock = threading.Lock()
        self._queue: list = []
        self._seq = itertools.count()
        self._running = 0
        self._closed = False

    def submit(self, cost: float, fn, *args) -> Future:
        """Queue ``fn(*args)`` with priority ``cost``."""
        fut: Future = Future()
        with self._lock:
            if self._closed:
                raise RuntimeError("MachPool is shut down")
            heapq.heappush(self._queue, (-float(cost), next(self._seq), fn, args, fut))
            started = self._dispatch()
        self._watch(started)
        return fut

    def _dispatch(self) -> list:
        """Start queued jobs while a worker is free (the lock held); the (process
        future, caller's future) pairs started, for :meth:`_watch` once the lock is
        released."""
        started = []
        while self._running < self.workers and self._queue:
            _, _, fn, args, fut = heapq.heappop(self._queue)
            if not fut.set_running_or_notify_cancel():
                continue                 # cancelled while queued
            try:
                inner = self._pool.submit(fn, *args)
            except BrokenProcessPool as err:     # a worker died: every queued job fails
                fut.set_exception(_worker_died(err))
                continue
            self._running += 1
            started.append((inner, fut))
        return started

    def _watch(self, started) -> None:
        """Forward each started job's outcome to its caller's future (the lock not
        held: a job already done runs the callback at once, in this thread, and
        :meth:`_finished` takes the lock)."""
        for inner, out in started:
            inner.add_done_callback(lambda f, out=out: self._finished(f, out))

    def _finished(self, inner: Future, out: Future) -> None:
        # the caller's future first: nothing below may leave it waiting
        exc = CancelledError() if inner.cancelled() else inner.exception()
        if isinstance(exc, BrokenProcessPool):
            exc = _worker_died(exc)
        if exc is not None:
            out.set_exception(exc)
        else:
            out.set_result(inner.result())
        with self._lock:
            self._running -= 1
            started = self._dispatch()
        self._watch(started)

    def cancel_queued(self) -> None:
        """Cancel the jobs not started (a sweep failed: the others are not needed).

        Each is also marked as notified (``set_running_or_notify_cancel``, the executor's
        duty in :mod:`concurrent.futures`): ``Future.cancel`` alone does not wake a
        thread already waiting in ``as_completed`` or ``wait``, so another sweep waiting
        on its queued jobs hung for good when one configuration of a build failed."""
        with self._lock:
            queued, self._queue = self._queue, []
        for *_, fut in queued:
            if fut.cancel():
                fut.set_running_or_notify_cancel()

    def shutdown(self) -> None:
        with self._lock:
            self._closed = True
        self.cancel_queued()
        self._pool.shutdown(wait=True, cancel_futures=True)

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.shutdown()
