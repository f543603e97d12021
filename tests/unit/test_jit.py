"""C compilation of the trajectory Functions: same numbers, cached on disk."""
from pathlib import Path

import numpy as np
import pytest

from ironbark_opt.dynamics.integrator import compile_function, compiler_available
from ironbark_opt.dynamics.model import FlightModel
from ironbark_opt.vehicle import load_setup

ROOT = Path(__file__).resolve().parents[2]


@pytest.mark.skipif(not compiler_available(), reason="no C compiler on this machine")
def test_compiled_flight_equals_vm_and_is_cached(tmp_path, monkeypatch):
    monkeypatch.setenv("IRONBARK_CACHE_DIR", str(tmp_path))
    setup = load_setup(ROOT / "examples/calisto/calisto.toml")
    p = setup.nominal_parameters()
    vm = FlightModel(setup).run(p)
    jit = FlightModel(setup, jit=True).run(p)
    libs = sorted((tmp_path / "jit").glob("*.so"))
    assert len(libs) == 4                                   # rail, boost, coast trajectories; apogee event
    print(f"apogee VM {vm['x_apogee'][2]:.9f} m, compiled {jit['x_apogee'][2]:.9f} m")
    assert jit["x_apogee"][2] == pytest.approx(vm["x_apogee"][2], abs=1e-6)
    assert jit["t_apogee"] == pytest.approx(vm["t_apogee"], abs=1e-9)
    mtimes = [lib.stat().st_mtime_ns for lib in libs]
    FlightModel(setup, jit=True)                            # second build: loads, does not compile
    assert [lib.stat().st_mtime_ns for lib in sorted((tmp_path / "jit").glob("*.so"))] == mtimes


def test_without_compiler_the_vm_is_used(monkeypatch):
    import casadi as ca
    monkeypatch.setenv("CC", "")
    monkeypatch.setattr("shutil.which", lambda name: None)
    x = ca.SX.sym("x")
    f = ca.Function("sq", [x], [x * x])
    assert compile_function(f) is f
    assert float(f(3.0)) == 9.0
