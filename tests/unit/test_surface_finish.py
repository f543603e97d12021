"""Per-component surface finish: TOML ``finish``/``surface_roughness`` on a component,
OpenRocket's ``<finish>`` per component, and the friction build-up that splits the
body's wetted area by finish (Niskanen 2013 eq. 3.79-3.80, roughness-limited skin
friction per component over the rocket's length)."""
from pathlib import Path

import numpy as np
import pytest

from ironbark_opt.aero.friction import FrictionDrag
from ironbark_opt.aero.friction_flatplate import cf_roughness_limited
from ironbark_opt.aero.model import friction_components
from ironbark_opt.errors import InputError
from ironbark_opt.rocket import load_rocket_toml

ROOT = Path(__file__).resolve().parents[2]
CALISTO = ROOT / "examples" / "calisto" / "calisto.toml"
ORK = ROOT / "tests" / "data" / "ork" / "01.One-stage_OR22.02.ork"


def _calisto(tmp_path, text_edit=lambda s: s):
    src = CALISTO.read_text()
    p = tmp_path / "calisto.toml"
    p.write_text(text_edit(src))
    for f in ("Cesaroni_M1670.eng", "powerOffDragCurve.csv", "powerOnDragCurve.csv"):
        (tmp_path / f).write_bytes((CALISTO.parent / f).read_bytes())
    return p


def test_component_finish_splits_the_body_by_roughness(tmp_path):
    polished_nose = _calisto(tmp_path, lambda s: s.replace(
        'shape = "von_karman"', 'shape = "von_karman"\nfinish = "polished"', 1))
    rk = load_rocket_toml(polished_nose).rocket
    nose = rk.body_components()[0]
    assert nose.roughness == pytest.approx(2e-6)
    comps = friction_components(rk, 60e-6)
    body = {c.roughness: c.wetted_area for c in comps if c.name.startswith("body")}
    assert set(body) == {2e-6, 60e-6}
    assert body[2e-6] == pytest.approx(nose.wetted_area())
    assert sum(body.values()) == pytest.approx(sum(c.wetted_area() for c in rk.body_components()))
    # at a Reynolds number where both finishes are roughness-limited, the body's friction is
    # the area-weighted sum of eq. 3.80 over the whole length (same form factor)
    sref = rk.reference_area()
    mach, re = 0.3, 1e9
    ca_split = FrictionDrag(comps[:2], sref).CA_exact(mach, re)
    L, ff = comps[0].length, comps[0].form_factor
    expect = sum(float(cf_roughness_limited(mach, L, k)) * a for k, a in body.items()) * ff / sref
    assert float(ca_split) == pytest.approx(expect, rel=1e-9)


def test_smoother_finish_lowers_friction(tmp_path):
    base = load_rocket_toml(_calisto(tmp_path)).rocket
    smooth = load_rocket_toml(_calisto(tmp_path, lambda s: s.replace(
        'name = "body"', 'name = "body"\nsurface_roughness = 5e-6', 1))).rocket
    sref = base.reference_area()
    ca0 = FrictionDrag(friction_components(base, 60e-6), sref).CA_exact(0.5, 1e7)
    ca1 = FrictionDrag(friction_components(smooth, 60e-6), sref).CA_exact(0.5, 1e7)
    assert float(ca1) < 0.85 * float(ca0)


@pytest.mark.parametrize("edit, needle", [
    ('name = "body"\nfinish = "glossy"', "glossy"),
    ('name = "body"\nsurface_roughness = -1e-6', "surface_roughness = -1e-6"),
    ('name = "body"\nfinish = "polished"\nsurface_roughness = 1e-6', 'finish = "polished"'),
])
def test_bad_component_finish_names_the_field(tmp_path, edit, needle):
    text = CALISTO.read_text().replace('name = "body"', edit, 1)
    p = _calisto(tmp_path, lambda s: text)
    with pytest.raises(InputError) as err:
        load_rocket_toml(p)
    assert err.value.field.startswith("component[1].")
    assert err.value.line == text.splitlines().index(
        next(ln for ln in text.splitlines() if needle in ln)) + 1


def test_openrocket_finishes_are_read_per_component():
    from ironbark_opt.openrocket import read_ork
    from ironbark_opt.openrocket.build import geometry
    rk = geometry(read_ork(ORK))
    # the file's components: 1 regular paint, 5 smooth paint, 1 polished (OpenRocket's
    # ExternalComponent.Finish: 60, 20, 2 um)
    found = {c.roughness for c in rk.body_components()} | {f.roughness for f in rk.fin_sets()}
    assert found <= {60e-6, 20e-6, 2e-6} and {20e-6, 2e-6} <= found
    comps = friction_components(rk, 60e-6)
    assert {c.roughness for c in comps} == found
