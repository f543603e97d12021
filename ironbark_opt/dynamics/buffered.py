"""CasADi Functions called on NumPy arrays through a CasADi buffer (``Function.buffer``).

Used by the motor-slot model's phase Functions and by the fused ascent's runner
(:class:`~ironbark_opt.dynamics.ascent.AscentRunner`).
"""
from __future__ import annotations

import threading

import casadi as ca
import numpy as np


class Buffered:
    """A Function called on numbers through a CasADi buffer (``Function.buffer``):
    NumPy arrays in and out, no DM conversion.  A slotted ``p_ext`` has ~1600
    entries and a run calls the phase Functions ~12 times with it; converting it
    to a DM costs ~0.25 ms a call and a trajectory's result back to NumPy another
    ~0.2 ms, more than some of the calls themselves.  The same compiled (or VM)
    evaluation, so the same numbers.  Symbolic arguments, or an evaluation that
    fails, go through the Function itself (its own result or error).  Other
    attributes (``map``, ``name``, ...) are the Function's."""

    def __init__(self, func):
        self._func, self._lock = func, threading.Lock()
        self._buf, self._eval = func.buffer()
        self._args = [np.zeros(func.nnz_in(i)) for i in range(func.n_in())]
        for i, arr in enumerate(self._args):
            self._buf.set_arg(i, memoryview(arr))
        # column-major (rows x cols) = C order (cols x rows): the transpose is the matrix
        self._res = [np.zeros((func.size2_out(i), func.size1_out(i))) for i in range(func.n_out())]
        for i, arr in enumerate(self._res):
            self._buf.set_res(i, memoryview(arr))

    @staticmethod
    def applies(func) -> bool:
        """Dense inputs and outputs only (the buffers are filled as dense columns)."""
        return all(func.sparsity_in(i).is_dense() for i in range(func.n_in())) and \
            all(func.sparsity_out(i).is_dense() for i in range(func.n_out()))

    def evaluate(self, values) -> list[np.ndarray] | None:
        """The outputs (each as its matrix, a fresh array) for the inputs ``values``
        (NumPy arrays of each input's entries, or single numbers), or None when
        the evaluation fails."""
        with self._lock:                       # one buffer: one evaluation at a time
            for arr, v in zip(self._args, values):
                arr[:] = v                     # a single number fills the input, as CasADi does
            self._eval()
            if self._buf.ret() != 0:
                return None
            return [r.T.copy() for r in self._res]

    def __call__(self, *args):
        if len(args) != len(self._args) or any(isinstance(a, (ca.MX, ca.SX)) for a in args):
            return self._func(*args)
        values = [np.ravel(np.asarray(a, dtype=float), order="F") for a in args]
        if any(v.size not in (1, arr.size) for v, arr in zip(values, self._args)):
            return self._func(*args)           # CasADi's own broadcasting rules (or its error)
        out = self.evaluate(values)
        if out is None:
            return self._func(*args)
        out = [np.array(r[0, 0]) if r.size == 1 else r for r in out]   # 1 x 1: a number
        return out[0] if len(out) == 1 else tuple(out)

    def __getattr__(self, name):
        return getattr(self._func, name)


def buffered(func):
    """``func`` called through a :class:`Buffered` where it applies (dense), else ``func``."""
    return Buffered(func) if Buffered.applies(func) else func
