"""A motor mass placed outside the motor is refused only when it matters.

The real-flight files converted from RocketPy (../shared/reference/flights, e.g.
genesis) count the casing in the rocket and give the motor ``dry_mass = 1e-06`` kg at
a CG past the motor's end (0.895 m on a 0.37 m motor).  That file was refused (exit 2)
although the mass moves no number; a real casing at the same place must still be.
"""
import pytest

from ironbark_opt import load_setup, simulate
from ironbark_opt.errors import InputError
from example_variant import example_variant


def _calisto(tmp_path, dry_mass, dry_cg):
    return example_variant(tmp_path, "calisto", [("dry_mass = 1.815", f"dry_mass = {dry_mass}"),
                                                 ("dry_cg = 0.317", f"dry_cg = {dry_cg}")])


def test_negligible_casing_mass_outside_the_motor_flies(tmp_path):
    """1e-6 kg at 2.0 m (the motor is 0.64 m long) flies, and its apogee is the one with
    the same mass inside the motor (the moment is 1e-6 kg m: identical to 1e-9)."""
    far = simulate(load_setup(_calisto(tmp_path, 1e-6, 2.0))).summary_values["apogee_agl_m"]
    near = simulate(load_setup(_calisto(tmp_path, 1e-6, 0.317))).summary_values["apogee_agl_m"]
    print(f"apogee, 1e-6 kg casing at 2.0 m / at 0.317 m: {far:.4f} / {near:.4f} m")
    assert far == pytest.approx(near, rel=1e-9)


def test_real_casing_mass_outside_the_motor_is_refused(tmp_path):
    """Calisto's 1.815 kg casing at 2.0 m would move the loaded motor's CG by 0.45 m."""
    with pytest.raises(InputError) as err:
        load_setup(_calisto(tmp_path, 1.815, 2.0))
    assert err.value.field == "motor.overrides.dry_cg"
    assert "outside the motor" in str(err.value)
    print(err.value)
