"""panair.blas_threads: OpenBLAS's thread count set at run time in every OpenBLAS
library of the process (NumPy's and SciPy's), read back through OpenBLAS's own
getter; restored afterwards."""
import ctypes

import numpy as np
import pytest
import scipy.linalg  # noqa: F401  (maps SciPy's OpenBLAS)

from panair.blas_threads import _openblas_libraries, limit_blas_threads

GETTERS = ("openblas_get_num_threads", "scipy_openblas_get_num_threads64_",
           "scipy_openblas_get_num_threads")


def _counts():
    out = []
    for path in _openblas_libraries():
        lib = ctypes.CDLL(path)
        fn = next((getattr(lib, g) for g in GETTERS if hasattr(lib, g)), None)
        if fn is not None:
            fn.restype = ctypes.c_int
            out.append(fn())
    return out


def test_limit_blas_threads_sets_every_openblas():
    before = _counts()
    if not before:
        pytest.skip("no OpenBLAS library in this process")
    try:
        assert limit_blas_threads(1) == len(before)
        assert _counts() == [1] * len(before)
        a = np.random.default_rng(0).random((200, 200))
        np.testing.assert_allclose(scipy.linalg.lu_solve(scipy.linalg.lu_factor(a), a @ np.ones(200)),
                                   np.ones(200), rtol=1e-9)
    finally:
        for path, n in zip(_openblas_libraries(), before):
            lib = ctypes.CDLL(path)
            for name in ("openblas_set_num_threads", "scipy_openblas_set_num_threads64_",
                         "scipy_openblas_set_num_threads"):
                if hasattr(lib, name):
                    getattr(lib, name)(n)
                    break
    assert _counts() == before
