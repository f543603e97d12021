"""A rocket whose only parachute opens at an altitude (no chute at apogee, e.g. a
single main on a chute release) falls ballistically from apogee to that altitude
and lands under the chute.  Before: every descent was refused with "a parachute
stage has no drag area (Cd*S = 0)" (found by the bad-input fuzz: deploy = 1e7 m)."""
import math
from pathlib import Path

import pytest

from ironbark_opt.atmosphere.isa import ISA
from ironbark_opt.flight import simulate
from ironbark_opt.rocket.toml_io import loads_rocket_toml
from ironbark_opt.vehicle import setup_from_file

CALISTO = Path(__file__).resolve().parents[2] / "examples" / "calisto" / "calisto.toml"
MAIN = '\n[[recovery]]\nname = "main"\ncd_area = 2.0\ndeploy = 300.0\n'


def test_single_main_at_altitude_free_falls_then_lands_at_terminal_speed():
    rf = loads_rocket_toml(CALISTO.read_text() + MAIN, CALISTO)
    res = simulate(setup_from_file(rf), descent=True)
    df = res.to_dataframe()
    phases = list(dict.fromkeys(df["phase"]))
    assert phases[-2:] == ["ballistic", "descent_2"], phases
    chute = df[df["phase"] == "descent_2"]
    # opens at 300 m AGL on the way down, falling much faster than under the chute
    first, opening = chute.iloc[0], df[df["phase"] == "ballistic"].iloc[-1]
    assert opening["altitude_agl_m"] == pytest.approx(300.0, abs=0.01)
    site = rf.launch.site_elevation
    # landing speed = terminal speed of the burnt-out rocket under Cd*S = 2 m^2:
    # v = sqrt(2 m g / (rho Cd S)), m = 14.426 kg dry + 1.815 kg motor casing
    m = 14.426 + 1.815
    rho = float(ISA().density(site))
    g = 9.7964                      # WGS-84 normal gravity at 33.0 deg N, 1400 m
    v_t = math.sqrt(2 * m * g / (rho * 2.0))
    v_land = res.summary_values["landing_speed_mps"]
    print(f"\nterminal {v_t:.3f} m/s, landed at {v_land:.3f} m/s; chute opened falling at "
          f"{-first['vz_l_mps']:.1f} m/s")
    assert v_land == pytest.approx(v_t, rel=0.02)
    assert -first["vz_l_mps"] > 3 * v_t
