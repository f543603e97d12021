"""OpenRocket component mass rules (ironbark_opt.openrocket.ormass) against closed forms."""
from __future__ import annotations

import math
from pathlib import Path

import pytest

from ironbark_opt.openrocket import read_ork
from ironbark_opt.openrocket.ormass import own_mass, subtree_mass
from ironbark_opt.openrocket.xmlread import read_bytes

DATA = Path(__file__).parents[1] / "data" / "ork"
SIMPLE = DATA / "A simple model rocket.ork"


def _doc(tmp_path, replacements):
    text = read_bytes(SIMPLE).decode()
    for old, new in replacements:
        assert old in text
        text = text.replace(old, new, 1)
    p = tmp_path / "m.ork"
    p.write_text(text)
    return read_ork(p)


def _comp(doc, name):
    return next(c for c in doc.rocket.components() if c.name == name)


def test_filled_cone_with_capped_shoulder(tmp_path):
    doc = _doc(tmp_path, [("<shape>ogive</shape>", "<shape>conical</shape>"),
                          ("<thickness>0.002</thickness>\n            <shape>",
                           "<thickness>filled</thickness>\n            <shape>")])
    nose = _comp(doc, "Nose cone")
    rho, r, L = 1050.0, 0.0125, 0.1
    cone = rho * math.pi * r * r * L / 3                              # solid cone
    shoulder = rho * math.pi * (0.0115 ** 2 - 0.0095 ** 2) * 0.02     # tube 0.0115/0.002 x 0.02
    cap = rho * math.pi * 0.0095 ** 2 * 0.002                         # disc r_s - t, thickness t
    assert own_mass(nose).mass == pytest.approx(cone + shoulder + cap, rel=1e-4)
    x_cg = (cone * 0.75 * L + shoulder * (L + 0.01) + cap * (L + 0.019)) / (cone + shoulder + cap)
    assert own_mass(nose).cg_x == pytest.approx(x_cg, rel=1e-4)


def test_body_tube_fins_and_recovery_closed_forms():
    doc = read_ork(SIMPLE)
    tube = _comp(doc, "Body tube")
    assert own_mass(tube).mass == pytest.approx(680 * math.pi * (0.0125 ** 2 - 0.0115 ** 2) * 0.3)
    fins = _comp(doc, "Trapezoidal fin set")
    g = fins.geo
    area = 0.5 * (g["root_chord"] + g["tip_chord"]) * g["span"]
    # planform x thickness x rounded-section factor 0.99 x count (OpenRocket FinSet)
    assert own_mass(fins).mass == pytest.approx(680 * area * g["thickness"] * 0.99 * g["count"], rel=1e-6)
    chute = _comp(doc, "Parachute")
    c = chute.geo
    surface = chute.material.density * math.pi * (c["diameter"] / 2) ** 2
    lines = c["line_count"] * c["line_length"] * c["line_material"].density
    assert own_mass(chute).mass == pytest.approx(surface + lines, rel=1e-9)
    assert own_mass(chute).cg_x == pytest.approx(chute.x + c["packed_length"] / 2)


def test_overrides(tmp_path):
    doc = read_ork(DATA / "Base drag hack (short-wide).ork")
    hack = _comp(doc, "Base-Drag Hack Transition")         # overridemass 0
    assert subtree_mass(hack).mass == 0.0
    doc = read_ork(DATA / "01.One-stage_OR22.02.ork")
    chute = next(c for c in doc.rocket.components() if c.name.startswith("Elliptical 12-Gore Parachute [Cd 1.5 (1.9"))
    sub = subtree_mass(chute)
    assert sub.mass == pytest.approx(0.05386409389)
    assert sub.cg_x == pytest.approx(chute.x + 0.0)           # overridecg 0 -> its front
    # a subtree override replaces the component and everything inside it
    doc = _doc(tmp_path, [("<name>Inner Tube</name>",
                           "<name>Inner Tube</name><overridemass>0.01</overridemass>"
                           "<overridesubcomponentsmass>true</overridesubcomponentsmass>")])
    assert subtree_mass(_comp(doc, "Inner Tube")).mass == pytest.approx(0.01)


def test_cluster_children_are_instanced():
    doc = read_ork(DATA / "Clustered motors.ork")
    tube = _comp(doc, "Clustered Inner Tube")
    block = _comp(doc, "Engine block")
    assert tube.cluster_count == 4 and block.cluster_count == 4
    g = block.geo
    one = 680 * math.pi * (g["outer_radius"] ** 2 - (g["outer_radius"] - g["thickness"]) ** 2) * g["length"]
    assert own_mass(block).mass == pytest.approx(4 * one, rel=1e-9)


def test_fillet_area_limits():
    from ironbark_opt.openrocket.ormass import fillet_area
    # on a flat body (rb -> inf) the fillet is the square minus the quarter circle
    assert fillet_area(0.005, 10.0) == pytest.approx((1 - math.pi / 4) * 0.005 ** 2, rel=1e-3)
    # on a curved body it is smaller, and it vanishes with the radius
    assert 0 < fillet_area(0.005, 0.025) < (1 - math.pi / 4) * 0.005 ** 2
    assert fillet_area(0.0, 0.025) == 0.0


ONE_STAGE = DATA / "01.One-stage_OR22.02.ork"
_BOATTAIL = ("<thickness>0.002</thickness>\n            <shape>conical</shape>\n"
             "            <foreradius>auto 0.025</foreradius>")


def _ellipsoid_boattail(tmp_path, clipped: str | None):
    """01.One-stage's boattail (fore radius auto = the 0.025146 m tube, aft 0.01905 m) as a
    filled 0.06 m ellipsoid; ``<shapeclipped>`` as given (None: absent, as OpenRocket
    writes no such element before it knew the flag)."""
    flag = "" if clipped is None else f"\n            <shapeclipped>{clipped}</shapeclipped>"
    text = read_bytes(ONE_STAGE).decode()
    for old, new in [(_BOATTAIL, "<thickness>filled</thickness>\n            <shape>ellipsoid</shape>"
                      f"{flag}\n            <foreradius>auto 0.025</foreradius>"),
                     ("<length>0.0127</length>", "<length>0.06</length>")]:
        assert text.count(old) == 1
        text = text.replace(old, new)
    p = tmp_path / "bt.ork"
    p.write_text(text)
    return [c for c in read_ork(p).rocket.body() if c.kind == "transition"][-1]


@pytest.mark.parametrize("clipped", [None, "true"])
def test_clipped_ellipsoid_transition_is_openrockets(tmp_path, clipped):
    """OpenRocket clips an ellipsoid/power/Haack transition by default (Transition.Shape
    canClip, ``<shapeclipped>`` true): the half-ellipse of the large radius R, lengthened
    past the small end to pass through r there.  With u1 = sqrt(1 - (r/R)^2) its total
    length is L/u1 and the solid volume pi R^2 L (1 - u1^2/3) (integral of the ellipse);
    at mid-length the radius is R sqrt(1 - (u1/2)^2)."""
    comp = _ellipsoid_boattail(tmp_path, clipped)
    R, r, L, rho = 0.025146, 0.01905, 0.06, 1050.0
    u1 = math.sqrt(1 - (r / R) ** 2)
    assert own_mass(comp).mass == pytest.approx(rho * math.pi * R * R * L * (1 - u1 * u1 / 3), rel=1e-3)
    from ironbark_opt.openrocket.convert import body_component
    tr = body_component(comp)
    assert float(tr.radius_at(comp.x + L / 2)) == pytest.approx(R * math.sqrt(1 - (u1 / 2) ** 2), rel=1e-6)
    assert float(tr.radius_at(comp.x + L)) == pytest.approx(r, rel=1e-6)


def test_unclipped_ellipsoid_transition_spans_the_radius_change(tmp_path):
    """``<shapeclipped>false``: r_small + dr sqrt(1 - (1 - d/L)^2), solid volume
    pi L (r^2 + 2 r dr pi/4 + dr^2 2/3) (the ellipse's mean height pi/4, of its square 2/3)."""
    comp = _ellipsoid_boattail(tmp_path, "false")
    R, r, L, rho = 0.025146, 0.01905, 0.06, 1050.0
    dr = R - r
    vol = math.pi * L * (r * r + 2 * r * dr * math.pi / 4 + dr * dr * 2 / 3)
    assert own_mass(comp).mass == pytest.approx(rho * vol, rel=1e-3)
