"""The power-on base relief takes the nozzle exit area when the file gives one, also
when the thrust's ambient-pressure correction is switched off (before: switching the
correction off also dropped the exit area from the base relief, which then fell back
to the motor's cross-section: 1.29 times the area for Calisto's 75 mm motor and 33 mm
nozzle exit radius).  Calisto on the empirical aerodynamics (no drag curves)."""
import math

import pytest

from ironbark_opt import load_setup
from example_variant import example_variant

EXIT_AREA = math.pi * 0.033 ** 2          # [m^2] the example's commented exit area


@pytest.fixture()
def calisto_with_exit(tmp_path):
    # the empirical aerodynamics (its own base drag; the team's curves already hold theirs)
    return example_variant(tmp_path, "calisto", [
        ("# nozzle_exit_area = 0.00342119439976", f"nozzle_exit_area = {EXIT_AREA!r}"),
        ('drag_power_off = "powerOffDragCurve.csv"\ndrag_power_on = "powerOnDragCurve.csv"\n', "")])


@pytest.mark.parametrize("correction", [True, False])
def test_relief_is_the_nozzle_exit_with_or_without_the_thrust_correction(calisto_with_exit, correction):
    setup = load_setup(calisto_with_exit, pressure_correction=correction)
    assert setup.aero.jet_area_source == "nozzle exit area"
    # the thrust correction follows the switch
    assert (setup.motor.nozzle_exit_area is not None) == correction
    base = setup.aero.base
    print(f"correction {correction}: jet area {base.jet_area:.6e} m^2 (exit {EXIT_AREA:.6e})")
    assert base.jet_area == pytest.approx(EXIT_AREA, rel=1e-12)
