"""Validation: the Calisto Pro75 M1670 motor against RocketPy 1.13.0.

Reference numbers (tests/data/motors/calisto_rocketpy_motor.json) were produced
once with RocketPy's ``SolidMotor`` from the inputs in
../shared/reference/calisto/README.md; RocketPy is not needed to run this test.
RocketPy burns propellant in proportion to impulse too, so mass and CG agree
to round-off; its grains also regress on their ends while ours keep their
length, so the inertia during the burn differs slightly (identical at
ignition and burnout).
"""
from __future__ import annotations

import dataclasses
import json
from pathlib import Path

import pytest

from ironbark_opt.motors import Grains, load_motor

DATA = Path(__file__).resolve().parents[1] / "data" / "motors"


@pytest.fixture(scope="module")
def pair():
    ref = json.loads((DATA / "calisto_rocketpy_motor.json").read_text())
    m = dataclasses.replace(
        load_motor(DATA / "Cesaroni_M1670.eng"), propellant_mass=None,
        grains=Grains(5, 1815.0, 0.033, 0.015, 0.120, 0.005), dry_mass=1.815,
        dry_cg=0.317, propellant_cg=0.397, dry_inertia=(0.125, 0.002))
    return m, ref


def test_impulse_and_propellant_mass(pair):
    m, ref = pair
    print(f"total impulse {m.total_impulse:.4f} vs RocketPy {ref['total_impulse_Ns']:.4f} N s; "
          f"propellant {m.propellant_mass_initial:.6f} vs {ref['propellant_initial_mass_kg']:.6f} kg")
    assert m.total_impulse == pytest.approx(ref["total_impulse_Ns"], rel=1e-9)
    assert m.propellant_mass_initial == pytest.approx(ref["propellant_initial_mass_kg"], rel=1e-9)


# tolerances: mass 2e-4 kg and CG 1e-5 m (RocketPy's own interpolation near
# burnout), inertia 1e-3 / 1e-4 kg m^2 (end-burning grains in RocketPy)
@pytest.mark.parametrize("quantity, tol", [
    ("total_mass_kg", 2e-4), ("center_of_mass_m", 1e-5), ("I_11_kgm2", 1e-3), ("I_33_kgm2", 1e-4)])
def test_mass_properties_history(pair, quantity, tol):
    m, ref = pair
    ours = {"total_mass_kg": m.mass, "center_of_mass_m": m.cg,
            "I_11_kgm2": lambda t: m.inertia(t)[0], "I_33_kgm2": lambda t: m.inertia(t)[1]}[quantity]
    errors = [abs(ours(t) - r) for t, r in zip(ref["t_s"], ref[quantity])]
    print(f"{quantity}: max |ours - RocketPy| = {max(errors):.2e} (tol {tol:g}); "
          f"at ignition {errors[0]:.1e}")
    assert max(errors) < tol
    assert errors[0] < 1e-12 * (1 + abs(ref[quantity][0]))    # same geometry at t = 0
