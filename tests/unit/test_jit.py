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


@pytest.mark.skipif(not compiler_available(), reason="no C compiler on this machine")
def test_compiled_and_vm_agree_to_1e_9_relative(tmp_path, monkeypatch):
    """Every sample of the flight (states and derived outputs), compiled vs the VM."""
    from ironbark_opt.flight import simulate
    monkeypatch.setenv("IRONBARK_CACHE_DIR", str(tmp_path))
    setup = load_setup(ROOT / "examples/calisto/calisto.toml")
    vm = simulate(setup, jit=False).to_dataframe()
    cc = simulate(setup, jit=True).to_dataframe()
    cols = [c for c in vm.columns if c != "phase"]
    a, b = vm[cols].to_numpy(), cc[cols].to_numpy()
    scale = np.maximum(np.abs(a).max(axis=0), 1e-300)            # per column
    err = float(np.max(np.abs(a - b) / scale))
    print(f"{a.shape[0]} samples x {len(cols)} columns: max relative difference {err:.2e} (tolerance 1e-9)")
    assert err < 1e-9


@pytest.mark.skipif(not compiler_available(), reason="no C compiler on this machine")
def test_auto_flies_the_vm_now_and_compiles_in_the_background(tmp_path, monkeypatch):
    import time
    monkeypatch.setenv("IRONBARK_CACHE_DIR", str(tmp_path))
    monkeypatch.setenv("IRONBARK_JIT", "auto")
    setup = load_setup(ROOT / "examples/calisto/calisto.toml")
    p = setup.nominal_parameters()
    first = FlightModel(setup, jit="auto")
    assert first._run["coast"] is first.trajectory["coast"]      # nothing cached: the VM
    ref = first.run(p)
    deadline = time.time() + 240
    while len(list((tmp_path / "jit").glob("*.so"))) < 4 and time.time() < deadline:
        time.sleep(0.5)
    second = FlightModel(setup, jit="auto")
    assert second._run["coast"] is not second.trajectory["coast"]  # the library the background built
    got = second.run(p)
    err = abs(got["x_apogee"][2] - ref["x_apogee"][2]) / ref["x_apogee"][2]
    print(f"apogee VM {ref['x_apogee'][2]:.9f} m, background-compiled {got['x_apogee'][2]:.9f} m ({err:.1e})")
    assert err < 1e-9


def test_cached_model_flies_bit_identically(tmp_path, monkeypatch):
    """The second build loads the stored Functions and grid; the flight is the same to the bit."""
    from ironbark_opt.dynamics import model_cache
    monkeypatch.setenv("IRONBARK_CACHE_DIR", str(tmp_path))
    setup = load_setup(ROOT / "examples/calisto/calisto.toml")
    built = FlightModel(setup)
    key = model_cache.model_key(setup, built.steps)
    assert model_cache.load(key) is not None
    loaded = FlightModel(setup)
    assert loaded.discretisation() == built.discretisation()
    p = setup.nominal_parameters(ballast_mass=0.3)
    a, b = built.run(p), loaded.run(p)
    assert np.array_equal(a["x"], b["x"]) and a["t_apogee"] == b["t_apogee"]
    other = load_setup(ROOT / "examples/calisto/calisto.toml", rail_exit="aft_button")
    assert model_cache.model_key(other, built.steps) != key         # another setup, another key
