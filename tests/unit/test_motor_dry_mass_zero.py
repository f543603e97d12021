"""Motor dry mass 0 (casing counted in the rocket): accepted, finite CG after
burnout, and the flight is the limit of a vanishing dry mass."""
from __future__ import annotations

import dataclasses
import math
from pathlib import Path

import pytest

from ironbark_opt.errors import InputError
from ironbark_opt.flight import simulate
from ironbark_opt.vehicle import load_setup

ASTRA = Path(__file__).resolve().parents[1] / "data" / "flights" / "astra" / "rocket.toml"


def test_dry_mass_zero_is_the_limit_of_a_tiny_dry_mass():
    setup = load_setup(ASTRA)
    motor = setup.motor
    assert motor.dry_mass == 0.0
    after = motor.burn_time + 1.0
    assert motor.mass(after) == pytest.approx(0.0, abs=1e-12)
    cg = float(motor.cg(after))
    assert math.isfinite(cg) and cg == pytest.approx(motor.propellant_cg_value)
    a0 = simulate(setup).apogee_agl
    tiny = dataclasses.replace(setup, motor=dataclasses.replace(motor, dry_mass=1e-6))
    a1 = simulate(tiny).apogee_agl
    print(f"apogee dry mass 0: {a0:.4f} m, 1e-6 kg: {a1:.4f} m, difference {a0 - a1:.2e} m")
    assert math.isfinite(a0) and abs(a0 - a1) < 1e-2


def test_negative_dry_mass_is_refused(tmp_path):
    text = ASTRA.read_text().replace("dry_mass = 0.0", "dry_mass = -1.0")
    for f in ASTRA.parent.iterdir():
        (tmp_path / f.name).write_bytes(f.read_bytes())
    (tmp_path / "rocket.toml").write_text(text)
    with pytest.raises(InputError, match=r"dry_mass.*>= 0"):
        load_setup(tmp_path / "rocket.toml")
