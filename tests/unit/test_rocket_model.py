"""Rocket assembly: body profile, reference quantities and validation."""
import math

import numpy as np
import pytest

from ironbark_opt.errors import InputError
from ironbark_opt.rocket import (BodyTube, LaunchLug, NoseCone, PointMass, RailButtons, Rocket,
                                 TrapezoidalFins, Transition)


def calisto_like(**kw):
    nose = NoseCone(shape="von_karman", length=0.55829, radius=0.0635)
    body = BodyTube(x=0.55829, length=1.914366, radius=0.0635)
    tail = Transition(x=2.472656, length=0.06, fore_radius=0.0635, aft_radius=0.0435)
    fins = TrapezoidalFins(count=4, x=2.32756, root_chord=0.12, tip_chord=0.06, span=0.11,
                           sweep_length=0.06, thickness=0.005)
    return Rocket("calisto", [nose, body, tail, fins, RailButtons(x_fore=1.1962, x_aft=1.8962)],
                  **kw)


def test_reference_quantities():
    r = calisto_like()
    assert r.length() == pytest.approx(2.532656)
    assert r.reference_radius() == pytest.approx(0.0635)
    assert r.reference_area() == pytest.approx(math.pi * 0.0635 ** 2)
    assert r.fineness() == pytest.approx(2.532656 / 0.127)
    assert calisto_like(reference_radius=0.07).reference_area() == pytest.approx(math.pi * 0.0049)
    body_area = sum(c.wetted_area() for c in r.body_components())
    assert r.wetted_area() == pytest.approx(body_area + 8 * 0.5 * 0.18 * 0.11)
    assert "calisto" in repr(r)


def test_body_profile_covers_the_body():
    r = calisto_like()
    x, rad = r.body_profile(300)
    assert x[0] == 0.0 and rad[0] == pytest.approx(0.0)
    assert x[-1] == pytest.approx(2.532656) and rad[-1] == pytest.approx(0.0435)
    assert np.all(np.diff(x) >= 0)
    assert len(x) == len(np.unique(np.round(np.column_stack([x, rad]), 12), axis=0))
    # trapezoid-rule volume of the profile vs the components' volumes
    vol = np.sum(np.pi * np.diff(x) / 3 * (rad[:-1] ** 2 + rad[:-1] * rad[1:] + rad[1:] ** 2))
    ref = sum(c.volume() for c in r.body_components())
    print(f"profile(300) volume {vol:.6e} vs components {ref:.6e}")
    assert vol == pytest.approx(ref, rel=1e-3)
    assert r.radius_at(np.array([-1.0, 1.0, 2.502656, 3.0])) == pytest.approx([0, 0.0635, 0.0535, 0])
    # the aft end itself (x_end = x + length rounds off): the base radius, not "off the body"
    # (it was 0 for Calisto's tail: flights without drag curves lost their base drag)
    assert float(r.radius_at(r.length())) == pytest.approx(0.0435)


def test_step_in_radius_appears_twice():
    nose = NoseCone(shape="conical", length=0.3, radius=0.05)
    small = BodyTube(x=0.3, length=0.5, radius=0.04)
    x, r = Rocket("step", [nose, small]).body_profile(50)
    i = int(np.argmin(np.abs(x - 0.3)))
    assert np.sum(np.isclose(x, 0.3)) == 2 and {0.05, 0.04} <= set(np.round(r[i:i + 2], 12))


@pytest.mark.parametrize("components, msg", [
    ([], "at least one body"),
    ([BodyTube(x=0.1, length=1.0, radius=0.05)], "start at the nose tip"),
    ([NoseCone(shape="conical", length=0.3, radius=0.05),
      BodyTube(x=0.35, length=1.0, radius=0.05)], "gap"),
    ([NoseCone(shape="conical", length=0.3, radius=0.05),
      BodyTube(x=0.25, length=1.0, radius=0.05)], "overlap"),
    ([NoseCone(shape="conical", length=0.3, radius=0.05), "tube"], "not a rocket component"),
    ([NoseCone(shape="conical", length=0.3, radius=0.05),
      TrapezoidalFins(x=0.5, root_chord=0.1, tip_chord=0.05, span=0.1, thickness=0.003)],
     "off the body"),
    ([NoseCone(shape="conical", length=0.3, radius=0.05), RailButtons(x_fore=0.1, x_aft=0.2),
      LaunchLug(x=0.1, length=0.05, outer_radius=0.005)], "one rail-button pair"),
])
def test_invalid_rockets(components, msg):
    with pytest.raises(InputError, match=msg):
        Rocket("bad", components)


def test_point_masses_and_rail_guides():
    r = Rocket("r", [NoseCone(shape="conical", length=0.3, radius=0.05),
                     PointMass(mass=1.0, x=0.2), LaunchLug(x=0.1, length=0.05, outer_radius=0.005)])
    assert r.rail_guides() == (0.1, pytest.approx(0.15))
    assert r.dry_mass_properties().mass == 1.0 and r.dry_mass_properties().cg_x == 0.2
    assert len(r.point_masses()) == 1
    assert Rocket("n", [NoseCone(shape="conical", length=0.3, radius=0.05)]).rail_guides() is None
