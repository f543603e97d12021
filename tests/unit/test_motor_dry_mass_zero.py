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


def test_eng_header_with_total_equal_to_propellant_reads_as_dry_mass_zero(tmp_path):
    """A RASP header whose total mass equals its propellant mass is a dry mass of 0 (a
    RocketPy case with dry mass 1e-11 kg written with 6 decimals: juno3's
    '8.169384 8.169384' was refused, exit 2); a total below the propellant stays refused."""
    from ironbark_opt.motors.rasp import read_eng
    curve = "0 0\n0.1 2000\n2 2000\n2.1 0\n"
    (tmp_path / "eq.eng").write_text("M1 75 500 P 8.169384 8.169384 X\n" + curve)
    (m,) = read_eng(tmp_path / "eq.eng")
    assert m.dry_mass == 0.0 and m.propellant_mass == pytest.approx(8.169384, abs=1e-12)
    # the impulse the curve gives: trapezoids 0.1*2000/2 + 1.9*2000 + 0.1*2000/2 = 4000 N s
    assert m.total_impulse == pytest.approx(4000.0, rel=1e-9)
    (tmp_path / "lt.eng").write_text("M1 75 500 P 8.169384 8.169383 X\n" + curve)
    with pytest.raises(InputError, match="at least the propellant mass") as err:
        read_eng(tmp_path / "lt.eng")
    assert err.value.line == 1 and err.value.field == "total_kg"
