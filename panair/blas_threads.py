"""One BLAS thread in each worker process of a panel sweep (numeric-only).

A sweep already runs one Mach number per core (:func:`panair.sweep.sweep_pressure`,
``workers`` processes).  NumPy's and SciPy's OpenBLAS libraries start their own
threads in every process (one per core by default) and spin while they wait, so two
workers each factorising with two threads oversubscribed this 2-core machine.
Measured (two-stage fixture's stack at Mach 0.05/0.5/0.9, six single-precision LUs of
~3300 unknowns, one process, loaded machine): 4.5 s CPU with the default threads,
2.9-3.1 s with one.

OpenBLAS's own call, ``openblas_set_num_threads`` (OpenBLAS user manual, "Setting the
number of threads at runtime"), is reached through ctypes in every OpenBLAS library
mapped into the process (NumPy's and SciPy's wheels each carry one, with prefixed
symbol names), since the environment variable ``OPENBLAS_NUM_THREADS`` is read only
when a library loads (before the workers fork).  Best effort: where no such library or
symbol is found (another BLAS, another OS) nothing changes; only speed depends on it.
"""
from __future__ import annotations

import ctypes

__all__ = ["limit_blas_threads"]

#: ``openblas_set_num_threads`` as the OpenBLAS builds in NumPy/SciPy wheels name it
_SETTERS = ("openblas_set_num_threads", "scipy_openblas_set_num_threads64_",
            "scipy_openblas_set_num_threads")


def _openblas_libraries() -> list[str]:
    try:
        with open("/proc/self/maps") as f:
            fields = [line.split() for line in f]
    except OSError:
        return []
    return sorted({x[-1] for x in fields if len(x) >= 6 and "openblas" in x[-1].lower()
                   and ".so" in x[-1]})


def limit_blas_threads(n: int = 1) -> int:
    """Set every loaded OpenBLAS library to ``n`` threads; returns how many were set."""
    done = 0
    for path in _openblas_libraries():
        try:
            lib = ctypes.CDLL(path)
        except OSError:
            continue
        for name in _SETTERS:
            fn = getattr(lib, name, None)
            if fn is not None:
                fn.argtypes, fn.restype = [ctypes.c_int], None
                fn(int(n))
                done += 1
                break
    return done
