"""The odd-rocket corpus (tests/odd_rockets.py): deterministic per seed, every file loads
through the rocket TOML reader, and each layout has the feature it is named for."""
from __future__ import annotations

import warnings

import pytest

from odd_rockets import LAYOUTS, odd_rocket

SEEDS = range(30)


def _load(text, tmp_path, seed):
    from ironbark_opt.vehicle import load_rocket_geometry
    path = tmp_path / f"odd{seed}.toml"
    path.write_text(text)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        rocket, _ = load_rocket_geometry(path)
    return rocket


def test_deterministic_per_seed_and_seeds_differ():
    assert odd_rocket(7) == odd_rocket(7)
    assert len({odd_rocket(s) for s in SEEDS}) == len(SEEDS)
    # both kinds of step occur: seed 20 has no reducer, seed 0 has one
    assert 'type = "transition"' not in odd_rocket(20) and 'type = "transition"' in odd_rocket(0)


@pytest.mark.parametrize("seed", SEEDS)
def test_every_seed_loads_with_its_layout(seed, tmp_path):
    from ironbark_opt.rocket.body import BodyTube, Transition
    rk = _load(odd_rocket(seed), tmp_path, seed)
    layout = LAYOUTS[seed % len(LAYOUTS)]
    fins = rk.fin_sets()
    body = rk.body_components()
    radii = [c.radius for c in body if isinstance(c, BodyTube)]
    fineness = rk.length() / (2 * rk.reference_radius())
    assert len(fins) == (2 if layout == "canards" else 1)
    aft = max(fins, key=lambda f: f.x)
    if layout in ("step_down", "step_up"):
        # a reducer, or an abrupt step between the two tubes (the same ratio)
        assert len([c for c in body if isinstance(c, Transition)]) <= 1 and len(radii) == 2
        ratio = radii[1] / radii[0] if layout == "step_down" else radii[0] / radii[1]
        assert 0.64 <= ratio <= 0.86 or (layout == "step_up" and radii[0] == 0.03)
    elif layout == "shoulder":
        assert body[0].radius < rk.reference_radius() and isinstance(body[1], Transition)
        assert body[1].length <= 0.6 * 2 * rk.reference_radius() + 1e-9
    elif layout == "canards":
        fore = min(fins, key=lambda f: f.x)
        assert fore.x_end < aft.x and fore.span < aft.span
    elif layout == "many_fins":
        assert aft.count in (6, 8)
    elif layout == "two_fins":
        assert aft.count == 2
    elif layout == "fins_past_base":
        assert 0.1 * aft.root_chord < aft.x_end - rk.length() < 0.5 * aft.root_chord
    elif layout == "long_thin":
        assert 22 <= fineness <= 26
    elif layout == "short_fat":
        assert 5 <= fineness <= 7.5
    elif layout == "clipped_delta":
        assert aft.root_chord >= 2.5 * 2 * rk.reference_radius() - 1e-9 and aft.tip_chord <= 0.3 * aft.root_chord
    if layout not in ("fins_past_base",):
        assert aft.x_end <= rk.length() + 1e-9
