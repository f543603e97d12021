import os
import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")

TESTS = Path(__file__).parent
sys.path.insert(0, str(TESTS))           # tests/dynamics_standins.py etc.
DATA = TESTS / "data"


def pytest_configure(config):
    # Keep the JIT cache and any user cache inside a temp area during tests.
    import tempfile
    if "IRONBARK_CACHE_DIR" not in os.environ:
        os.environ["IRONBARK_CACHE_DIR"] = tempfile.mkdtemp(prefix="ironbark-test-cache-")
    # jit="auto" (the default) runs the VM and starts no background compilers in tests
    # (CI time); tests of the compiled path ask for it explicitly.
    os.environ.setdefault("IRONBARK_JIT", "vm")
    # Everything the tests (and the notebook kernels they start) write goes to temp dirs.
    for var, prefix in (("MPLCONFIGDIR", "mpl"), ("IPYTHONDIR", "ipython"), ("JUPYTER_RUNTIME_DIR", "jupyter")):
        if var not in os.environ:
            os.environ[var] = tempfile.mkdtemp(prefix=f"ironbark-test-{prefix}-")


import pytest  # noqa: E402


@pytest.fixture
def ork_offline(monkeypatch, tmp_path):
    """OpenRocket fixtures flown offline: motors from tests/data/ork/motors, a fresh cache."""
    monkeypatch.setenv("IRONBARK_OFFLINE", "1")
    monkeypatch.setenv("IRONBARK_CACHE_DIR", str(tmp_path))
    monkeypatch.setenv("IRONBARK_MOTOR_PATH", str(DATA / "ork" / "motors"))


@pytest.fixture
def ork_all_motors(monkeypatch, tmp_path):
    """As ork_offline, motors from tests/data/ork/motors, then tests/data/motors."""
    monkeypatch.setenv("IRONBARK_OFFLINE", "1")
    monkeypatch.setenv("IRONBARK_CACHE_DIR", str(tmp_path))
    monkeypatch.setenv("IRONBARK_MOTOR_PATH", os.pathsep.join(
        [str(DATA / "ork" / "motors"), str(DATA / "motors")]))


@pytest.fixture(scope="session")
def coarse_finner_panels():
    """A coarse Basic Finner half model's PanelSet (body 10 calibers, four fins)."""
    import numpy as np

    from panair.mesh import BodyGeometry, FinGeometry, MeshOptions, RocketGeometry, mesh_rocket
    from panair.solver import build_panels
    body = BodyGeometry(np.array([0.0, 2.84, 10.0]), np.array([0.0, 0.5, 0.5]))
    fins = (FinGeometry(4, 1.0, 1.0, 1.0, 0.0, 9.0, 0.08, roll=np.pi / 4),)
    opt = MeshOptions(n_theta=8, n_nose=4, body_spacing=2.0, n_chord=4, n_span=2)
    return build_panels(mesh_rocket(RocketGeometry(body, fins), symmetric=True, options=opt),
                        symmetric=True)
