"""An abrupt radius step between two body components (no transition) in the zero-lift
pressure drag a potential solution cannot have (ironbark_opt.aero.empirical_drag.
separated_pressure_ca; the panel tables' subsonic zero-lift pressure drag): a step down
is a contracting transition of length 0, fully separated (Niskanen 2013 eq. 3.88, gamma
= 0 < 1: base pressure on the annulus), a step up a flat forward face (eq. 3.87).  Until
session 22 either step had no drag (a 157 -> 133 mm step: 0 where a 36 deg reducer had
0.038 at Mach 0.35)."""
import numpy as np
import pytest

from ironbark_opt.aero.base_drag import cd_base
from ironbark_opt.aero.empirical_drag import separated_pressure_ca, stagnation_ratio
from ironbark_opt.rocket import BodyTube, NoseCone, Rocket, Transition

R1, R2 = 0.0785, 0.0667
MACH = np.array([0.3, 0.8, 1.5, 2.5])


def _rocket(middle, r_fore=R1, r_aft=R2):
    parts = [NoseCone(shape="ogive", length=0.5, radius=r_fore), BodyTube(x=0.5, length=0.8, radius=r_fore)]
    x = 1.3
    for c in middle:
        parts.append(c)
        x = c.x + c.length
    parts.append(BodyTube(x=x, length=0.7, radius=r_aft))
    return Rocket("steps", parts)


def test_step_down_is_a_fully_separated_reducer():
    step = separated_pressure_ca(_rocket([]), MACH, streamlined_edges=False)
    # the same step as a 36 deg reducer (gamma 0.69 < 1, fully separated by eq. 3.88);
    # the tube behind starts 8.6 mm later, which changes no pressure drag
    reducer = _rocket([Transition(x=1.3, length=0.0163, fore_radius=R1, aft_radius=R2)])
    ref = separated_pressure_ca(reducer, MACH, streamlined_edges=False)
    annulus = np.pi * (R1 ** 2 - R2 ** 2) / (np.pi * R1 ** 2)
    no_step = separated_pressure_ca(_rocket([], r_aft=R1), MACH, streamlined_edges=False)
    np.testing.assert_allclose(step - no_step, cd_base(MACH) * annulus, rtol=1e-12)
    np.testing.assert_allclose(step, ref, rtol=1e-12)


def test_step_up_is_a_flat_forward_face():
    up = separated_pressure_ca(_rocket([], r_fore=R2, r_aft=R1), MACH, streamlined_edges=False)
    # the same rocket flared by a long 3 deg transition: attached, no separated drag
    flare = _rocket([Transition(x=1.3, length=0.225, fore_radius=R2, aft_radius=R1)], r_fore=R2, r_aft=R1)
    smooth = separated_pressure_ca(flare, MACH, streamlined_edges=False)
    annulus = np.pi * (R1 ** 2 - R2 ** 2) / (np.pi * R1 ** 2)
    np.testing.assert_allclose(up - smooth, 0.85 * stagnation_ratio(MACH) * annulus, rtol=1e-12)


def test_joints_without_a_step_add_nothing():
    plain = Rocket("plain", [NoseCone(shape="ogive", length=0.5, radius=R1), BodyTube(x=0.5, length=1.5, radius=R1)])
    split = Rocket("split", [NoseCone(shape="ogive", length=0.5, radius=R1), BodyTube(x=0.5, length=0.8, radius=R1),
                             BodyTube(x=1.3, length=0.7, radius=R1)])
    np.testing.assert_array_equal(separated_pressure_ca(plain, MACH), separated_pressure_ca(split, MACH))
