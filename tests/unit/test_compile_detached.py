"""compile_detached: a Function saved here is generated and compiled by a detached
process (with extra Functions from a named builder) and then loads from the cache."""
import time

import casadi as ca
import numpy as np
import pytest

from ironbark_opt.dynamics.integrator import cached_library, compile_detached, compiler_available


def test_detached_compile_with_jacobian(tmp_path, monkeypatch):
    if not compiler_available():
        pytest.skip("no C compiler")
    monkeypatch.setenv("IRONBARK_CACHE_DIR", str(tmp_path))
    # slots of its own (test_compile_slots.py): other compiles on this machine cannot make it give up
    monkeypatch.setenv("XDG_RUNTIME_DIR", str(tmp_path))
    # the child waits for this process to exit, at most AFTER_PARENT_MAX_S: here, not at all
    monkeypatch.setattr("ironbark_opt.dynamics.integrator.AFTER_PARENT_MAX_S", 0.0)
    x, p = ca.MX.sym("x", 2), ca.MX.sym("p", 3)
    f = ca.Function("tiny_nlp", [x, p], [ca.sumsqr(x - p[:2]), ca.vertcat(x[0] * p[2], ca.sin(x[1]))],
                    ["x", "p"], ["f", "g"])
    compile_detached(f, "k1", "ironbark_opt.optimise.ballast:_jacobian_in_x")
    deadline = time.time() + 300
    # the library appears before the child removes its markers (it runs at the lowest
    # priority, so on a busy machine that can take a while): wait for both
    while (cached_library("tiny_nlp", "k1") is None or list((tmp_path / "jit").glob(".*"))) \
            and time.time() < deadline:
        time.sleep(0.5)
    lib = cached_library("tiny_nlp", "k1")
    assert lib is not None and lib.is_a("External")
    assert not list((tmp_path / "jit").glob(".*"))                 # markers and the saved Function removed
    w, pv = [0.3, -0.7], [1.0, 2.0, 1.5]
    for a, b in zip(f(w, pv), lib(w, pv)):
        np.testing.assert_allclose(np.array(b), np.array(a), rtol=1e-14)
    xs = ca.MX.sym("xs", 2)
    jac = [ca.Function("j", [xs], [ca.jacobian(g(xs, pv)[1], xs)])(w) for g in (f, lib)]
    np.testing.assert_allclose(np.array(jac[1]), np.array(jac[0]), rtol=1e-14)   # the library's jac_tiny_nlp
