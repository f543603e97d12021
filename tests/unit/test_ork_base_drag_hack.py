"""OpenRocket's 'base drag hack' is not hardware: the .ork reader leaves it out.

OpenRocket's example 'Base drag hack (short-wide).ork' (tests/data/ork) ends its 39.4 mm
tube in a flat base and puts behind it a conical transition from a 0.015 mm point back out
to 39.4 mm, 0.247 m long, with OpenRocket's mass, CG and Cd overrides ticked (the file's own
comment gives the recipe): a device to move OpenRocket's Barrowman centre of pressure aft
for a short rocket.  As a body of revolution it pinches to a point, which the panel mesh
refuses (tests/unit/test_panel_degenerate_body.py), so `aero build` refused the file.  Now
the reader recognises the recipe (:meth:`OrkRocket.base_drag_hack`), warns once naming the
component, and the rocket flies as built: flat base at the tube's end, fins overhanging it.
A pinch without the recipe stays in the body and is still refused by name.
"""
import math
import warnings
from pathlib import Path

import numpy as np
import pytest

from barrowman_reference import barrowman_cna_cp
from ironbark_opt.errors import InputError
from ironbark_opt.openrocket import read_ork
from ironbark_opt.openrocket.build import geometry
from ironbark_opt.rocket import Transition
from ironbark_opt.openrocket.xmlread import read_bytes
from panair.geometry_adapter import from_rocket

ORK = Path(__file__).parents[1] / "data" / "ork" / "Base drag hack (short-wide).ork"
TUBE_END_X = 0.0454269 + 0.1211385          # nose + body tube [m], from the file


def _read(path):
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        doc = read_ork(path)
    return doc, [str(w.message) for w in caught]


def test_hack_is_left_out_with_one_warning_and_the_body_ends_at_the_base():
    doc, said = _read(ORK)
    hack = [m for m in said if "base drag hack" in m]
    assert len(hack) == 1 and "'Base-Drag Hack Transition'" in hack[0] and "0.0151 mm" in hack[0]
    assert not any("override Cd" in m for m in said)      # the hack's Cd 0 is not 'computed'
    rocket = geometry(doc)
    assert not any(isinstance(c, Transition) for c in rocket.body_components())
    x, r = from_rocket(rocket).body.x, from_rocket(rocket).body.r
    # the mesh's body: the tube to its flat base, then continued under the fins that
    # overhang the base (panair.geometry_adapter._continue_past_fins), never a pinch
    assert r.max() == pytest.approx(0.03937)
    assert np.all(r[(x > 0.05) & (x <= TUBE_END_X)] == pytest.approx(0.03937))


def test_pinch_without_the_recipe_is_the_bodys_and_is_refused(tmp_path):
    text = read_bytes(ORK).decode("utf-8")
    i = text.index("<name>Base-Drag Hack Transition</name>")
    tail = text[i:]
    for tag in ("overridemass", "overridecd"):
        a, b = tail.index(f"<{tag}>"), tail.index(f"</{tag}>") + len(f"</{tag}>")
        tail = tail[:a] + tail[b:]
    path = tmp_path / "pinch.ork"
    path.write_text(text[:i] + tail, encoding="utf-8")
    doc, said = _read(path)
    assert not any("base drag hack" in m and "left out" in m for m in said)
    rocket = geometry(doc)
    assert any(isinstance(c, Transition) for c in rocket.body_components())
    with pytest.raises(InputError, match=r"narrows to a radius of 0\.0151 mm"):
        from_rocket(rocket)


def test_the_real_rocket_gets_a_sane_panel_table():
    """Independent check of the table the file now builds (subsonic): zero normal force
    at zero incidence and CN-alpha / CP against Barrowman with the body's carry-over
    (tests/barrowman_reference.py), the bounds of the random-rocket validation (20 %,
    0.6 caliber).  Measured (session 21): 7.68 vs 8.13 /rad (-5.5 %), CP +0.01 cal."""
    from ironbark_opt.vehicle import load_rocket_geometry
    from panair.rocket_table import rocket_table
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", UserWarning)
        rocket, spec = load_rocket_geometry(ORK)
    t = rocket_table(rocket, spec, mach=np.array([0.1, 0.3]), alpha_deg=np.array([0.0, 2.0, 4.0]),
                     workers=1)
    a = math.radians(2.0)
    cn, cm = float(t.evaluate("CN", 0.3, a)), float(t.evaluate("Cm", 0.3, a))
    x_cp = -cm / cn * t.reference_length + t.moment_reference_x
    cna_ref, x_ref = barrowman_cna_cp(rocket, 0.3, carryover=True)
    d = 2 * rocket.reference_radius()
    print(f"\nbase drag hack rocket, Mach 0.3: CN-alpha {cn / a:.2f} /rad (Barrowman + carry-over "
          f"{cna_ref:.2f}), CP {(x_cp - x_ref) / d:+.2f} cal")
    assert abs(float(t.evaluate("CN", 0.3, 0.0))) < 1e-9
    assert cn / math.sin(a) == pytest.approx(cna_ref, rel=0.20)
    assert abs(x_cp - x_ref) <= 0.6 * d
