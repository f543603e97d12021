"""Design study: variants, geometry changes, panel aerodynamics per variant, ballast per variant.

Sources of truth: Barrowman's fin normal-force slope (Barrowman 1966,
via ``ironbark_opt.aero.barrowman.trapezoidal_fins``) for the *change* in
CN_alpha between two fin spans (the body terms cancel in the difference,
so it isolates the fins, where panel and Barrowman should agree); the
ballast solver's own re-simulation for the target.
"""
from pathlib import Path

import numpy as np
import pytest

from ironbark_opt.aero import barrowman
from ironbark_opt.analysis.design_study import (_panel_task, apply_design, design_grid, design_samples,
                                                design_study, plot_design_study)
from ironbark_opt.errors import InputError
from ironbark_opt.rocket.toml_io import load_rocket_toml
from panair.geometry_adapter import from_rocket
from panair.mesh import MeshOptions

ROOT = Path(__file__).resolve().parents[2]
CALISTO = ROOT / "examples/calisto/calisto.toml"
COARSE = MeshOptions(n_theta=16, n_nose=8, body_spacing=1.0, n_chord=8, n_span=3)


def test_grid_and_samples():
    grid = design_grid(fin_span=[0.1, 0.12], fin_root_chord=[0.1, 0.12, 0.14])
    assert len(grid) == 6 and grid[0] == {"fin_span": 0.1, "fin_root_chord": 0.1}
    a = design_samples(5, {"fin_span": (0.08, 0.14)}, seed=3)
    assert a == design_samples(5, {"fin_span": (0.08, 0.14)}, seed=3)
    assert all(0.08 <= c["fin_span"] <= 0.14 for c in a)
    with pytest.raises(InputError, match="unknown design parameter"):
        design_grid(fin_spam=[0.1])
    with pytest.raises(InputError, match="low <= high"):
        design_samples(2, {"fin_span": (0.2, 0.1)})
    with pytest.raises(InputError, match="finite numbers"):
        design_grid(fin_span=[])
    with pytest.raises(InputError, match="no design variants"):
        design_study(CALISTO, [], "2500m")
    with pytest.raises(InputError, match="same parameters"):
        design_study(CALISTO, [{"fin_span": 0.1}, {"fin_root_chord": 0.1}], "2500m")


def test_apply_design_changes_only_the_fins():
    rf = load_rocket_toml(CALISTO)
    new = apply_design(rf, {"fin_span": 0.13, "fin_tip_chord": 0.05})
    fins = new.rocket.fin_sets()[0]
    assert (fins.span, fins.tip_chord, fins.root_chord) == (0.13, 0.05, rf.rocket.fin_sets()[0].root_chord)
    assert rf.rocket.fin_sets()[0].span == 0.110                      # the original is untouched
    assert new.rocket.length() == rf.rocket.length()
    with pytest.raises(InputError, match="span"):
        apply_design(rf, {"fin_span": -0.1})


def test_panel_fin_increment_matches_barrowman():
    """On 12 fin strips: the panel increment converges from above as the strips
    narrow (n_span 3 / 6 / 12: +13.4 / +10.1 / +7.7 % against Barrowman; 24 strips and
    n_chord 16: +7.0 %) since the coarse airfoil nose's leading-edge neighbours are in
    the surface-gradient stencil; before, the leading-edge loss hid the strip-width
    error (+8.0 % on 3 strips)."""
    from dataclasses import replace
    rf = load_rocket_toml(CALISTO)
    alpha = np.radians([0.0, 2.0])
    cna = {}
    for span in (0.08, 0.14):
        rocket = apply_design(rf, {"fin_span": span}).rocket
        cn, _, _ = _panel_task(from_rocket(rocket), 0.1, alpha, rocket.reference_area(),
                               2 * rocket.reference_radius(), replace(COARSE, n_span=12))
        f = rocket.fin_sets()[0]
        bw = barrowman.trapezoidal_fins(f.count, f.root_chord, f.tip_chord, f.span, f.sweep_length, f.x,
                                        float(rocket.radius_at(f.x + 0.5 * f.root_chord)), rocket.reference_area(),
                                        mach=0.1)
        cna[span] = ((cn[1] - cn[0]) / (alpha[1] - alpha[0]), bw.cn_alpha)
    d_panel = cna[0.14][0] - cna[0.08][0]
    d_bw = cna[0.14][1] - cna[0.08][1]
    err = d_panel / d_bw - 1
    print(f"CN_alpha increment span 0.08 -> 0.14 m: panel {d_panel:.3f}, Barrowman {d_bw:.3f} /rad, "
          f"error {100 * err:+.1f} % (tolerance 10 %)")
    assert abs(err) < 0.10


@pytest.mark.slow
def test_design_study_end_to_end(tmp_path):
    import matplotlib
    matplotlib.use("Agg")
    study = design_study(CALISTO, design_grid(fin_span=[0.08, 0.14]), "2500m", mesh=COARSE,
                         mach=(0.05, 0.5, 0.9), alpha_deg=(0.0, 4.0, 10.0, 20.0), tables_dir=tmp_path / "tables")
    df = study.to_dataframe()
    print(study.summary())
    assert list(df["fin_span_m"]) == [0.08, 0.14] and df["feasible"].all()
    err = np.max(np.abs(df["apogee_agl_m"] - 2500.0))
    print(f"apogee vs target: max error {err:.2f} m (tolerance 1 m)")
    assert err < 1.0
    # bigger fins: more lift slope, more margin, more drag -> less ballast for the same target
    assert df["CN_alpha_per_rad"].is_monotonic_increasing
    assert df["static_margin_rail_exit_cal"].is_monotonic_increasing
    assert df["ballast_kg"].is_monotonic_decreasing
    assert study.best()["variant"] == 1
    from ironbark_opt.aero.table import AeroTable
    saved = AeroTable.load(df["table"].iloc[1])
    assert saved.evaluate("CN", 0.5, np.radians(4.0)) > 0 and len(saved.mach) == 3
    fig = plot_design_study(study, filename=tmp_path / "study.png")
    assert (tmp_path / "study.png").stat().st_size > 1000 and fig is not None
