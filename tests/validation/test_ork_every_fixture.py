"""Every OpenRocket fixture (tests/data/ork) flies every stored simulation's
configuration within 10 % of the apogee OpenRocket stored for it (issue #14).

Flown as ``simulate`` does: the .ork's geometry, mass build-up, motor files
(tests/data/ork/motors), launch conditions of that simulation, OpenRocket's
launch-rod travel for the rail exit, the empirical aerodynamics, the motor's
ejection delay (a "too short delay" simulation deploys on the way up, as
OpenRocket's stored events show: marked in the printout).  Every case prints
its numbers.  One kind of case is skipped, with its reason:

- A simulation without a motor configuration (``configid`` empty, OpenRocket
  1.1.3 files whose simulations kept no motor) has nothing to fly: skipped,
  the reason asserted from the file.

Slow (about 6 minutes: 28 flights, each compiled); run with
``pytest -m slow tests/validation/test_ork_every_fixture.py -s``.
"""
from pathlib import Path

import pytest

from ironbark_opt.openrocket import read_ork

DATA = Path(__file__).parents[1] / "data" / "ork"
EARLY = "OpenRocket deploys before apogee (motor ejection delay)"


def _early_deployment(sim) -> bool:
    ev = sim.events()
    apogee = [t for t, k, _ in ev if k == "apogee"]
    deploy = [t for t, k, _ in ev if k == "recoverydevicedeployment"]
    return bool(apogee and deploy and min(deploy) < min(apogee))


def _cases():
    out = []
    for path in sorted(DATA.glob("*.ork")):
        doc = read_ork(path)
        for i, sim in enumerate(doc.simulations):
            marks = []
            if not sim.config_id:
                marks.append(pytest.mark.skip(reason="the simulation names no motor configuration "
                                                     "(empty configid): nothing to fly"))
            out.append(pytest.param(path.name, i, marks=marks, id=f"{path.stem}-{i + 1}"))
    return out


pytestmark = pytest.mark.usefixtures("ork_offline")     # tests/conftest.py


@pytest.mark.slow
@pytest.mark.filterwarnings("ignore::UserWarning")
@pytest.mark.parametrize("name, index", _cases())
def test_stored_simulation_apogee(name, index):
    from ironbark_opt.flight import simulate
    from ironbark_opt.vehicle import load_setup

    path = DATA / name
    sim = read_ork(path).simulations[index]
    flight = simulate(load_setup(path, config=sim.config_id, rail_exit="travel"))
    stored = sim.summary["apogee_m"]
    err = flight.apogee_agl / stored - 1
    early = _early_deployment(sim)
    print(f"{name} / {sim.name}: {flight.apogee_agl:.1f} m, OpenRocket {stored:.1f} m ({100 * err:+.2f} %)"
          + (f"  [{EARLY}]" if early else ""))
    assert abs(err) < 0.10
