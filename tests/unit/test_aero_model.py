"""The assembled aero model: tabulated Barrowman sums vs the exact build-up,
symbolic vs numeric evaluation, and the moment-transfer convention."""
from pathlib import Path

import casadi as ca
import numpy as np
import pytest

from ironbark_opt.aero import barrowman, damping
from ironbark_opt.vehicle import load_setup

ROOT = Path(__file__).resolve().parents[2]


@pytest.fixture(scope="module")
def aero():
    return load_setup(ROOT / "examples/calisto/calisto.toml").aero


def test_tabulated_sums_match_component_buildup(aero):
    mach = np.linspace(0.0, 4.0, 4001)
    for exact, table in zip(aero._sums_exact(mach), aero._sums(mach)):
        exact = np.broadcast_to(exact, mach.shape)
        err = np.max(np.abs(table - exact)) / np.max(np.abs(exact))
        print(f"max tabulation error {err:.2e} of range")
        assert err < 1e-4


def test_damping_and_cp_agree_with_direct_formulas(aero):
    for mach in (0.3, 0.8, 1.2, 2.5):
        comps = aero.lift.components(mach, aero.reference_area)
        cna, x_cp = barrowman.total(comps)
        assert aero.center_of_pressure(mach, 0.0) == pytest.approx(x_cp, rel=1e-5)
        for x_cg in (1.2, 1.5):
            direct = damping.pitch_damping_cmq(comps, x_cg, aero.reference_length)
            assert aero.pitch_damping(mach, x_cg) == pytest.approx(direct, rel=1e-5)


def test_symbolic_and_numeric_coefficients_agree(aero):
    mach, alpha, re = ca.SX.sym("M"), ca.SX.sym("a"), ca.SX.sym("re")
    for power_on in (False, True):
        f = ca.Function("c", [mach, alpha, re], list(aero.coefficients(mach, alpha, re, power_on)))
        for m_, a_ in ((0.3, 0.01), (0.85, 0.1), (1.6, 0.3)):
            num = aero.coefficients(m_, a_, 5e6, power_on)
            sym = [float(v) for v in f(m_, a_, 5e6)]
            assert np.allclose(num, sym, rtol=1e-12, atol=1e-14)


def test_normal_force_is_restoring_about_a_forward_cg(aero):
    """Cm about the nose tip with CN > 0 is negative (CP aft of the tip)."""
    cn, cm = aero.normal(0.5, np.radians(0.5))     # small alpha: Galejs body lift (~alpha^2) negligible
    assert cn > 0 and cm < 0
    x_cp = aero.center_of_pressure(0.5, 0.0)
    assert -cm * aero.reference_length / cn == pytest.approx(x_cp, rel=0.02)


def test_table_cp_is_the_linear_one_without_the_crossflow_part():
    """A panel table's CN/Cm include the viscous cross-flow (sin^2 alpha, at
    the planform centroid); the static-margin CP is read from the pressure
    part: the same CP as a table without the cross-flow part."""
    from ironbark_opt.aero.table import AeroTable
    from ironbark_opt.aero.model import AeroModel
    kestrel = load_setup(ROOT / "examples/kestrel/kestrel.toml").aero
    t = kestrel.table
    assert "crossflow" in t.includes and np.any(t.values("CN_crossflow") > 0)
    parts = {k: t.values(k) for k in ("CA", "CN_pressure", "Cm_pressure")}
    bare = AeroTable(t.mach, t.alpha, {**parts, "CN": parts["CN_pressure"],
                                       "Cm": parts["Cm_pressure"]},
                     reference_area=t.reference_area, reference_length=t.reference_length,
                     moment_reference_x=t.moment_reference_x, includes=("pressure",))
    other = AeroModel(kestrel.reference_area, kestrel.reference_length,
                      kestrel.moment_reference_x, kestrel.lift, bare)
    for mach in (0.3, 0.8):
        assert kestrel.center_of_pressure(mach, 0.0) == pytest.approx(
            other.center_of_pressure(mach, 0.0), abs=1e-9)
    # and the cross-flow part does move the 0.5 deg CP forward (toward the planform centroid)
    cn, cm = kestrel.normal(0.3, np.radians(8.0))
    cn0, cm0 = other.normal(0.3, np.radians(8.0))
    assert cn > cn0 and -cm / cn < -cm0 / cn0


def test_panel_table_flight_takes_the_jet_off_the_base_while_burning():
    """A panel table's base drag is built without a jet; with the motor's nozzle
    exit area known, the burning rocket's CA loses cd_base(M) x A_jet / Sref
    (the same rule as without a table, Niskanen 2013 sec. 3.4.5)."""
    from ironbark_opt.aero.base_drag import cd_base
    from ironbark_opt.aero.model import build_aero_model
    from ironbark_opt.aero.table import AeroTable
    from ironbark_opt.vehicle import load_rocket_geometry
    rocket, _ = load_rocket_geometry(ROOT / "examples/kestrel/kestrel.toml")
    table = AeroTable.load(ROOT / "tables/Kestrel.csv")
    assert table.metadata["base_jet_area_m2"] == 0.0
    jet = 7e-4
    with_jet = build_aero_model(rocket, table=table, jet_area=jet)
    without = build_aero_model(rocket, table=table)
    for mach in (0.3, 0.8, 1.3):
        on = with_jet.axial(mach, 0.0, 1e7, power_on=True)
        off = with_jet.axial(mach, 0.0, 1e7, power_on=False)
        assert off == pytest.approx(without.axial(mach, 0.0, 1e7, power_on=True), rel=1e-12)
        assert off - on == pytest.approx(cd_base(mach, "mccoy") * jet / rocket.reference_area(),
                                         rel=1e-9)


def test_axial_parts_without_an_incidence_model_fall_as_cos_squared():
    """Friction, base drag and a drag curve of Mach alone: Jorgensen's CA(alpha) =
    CA(0) cos^2 alpha (NASA TR R-474, 1977, eq. 2); a panel table's own CA over angle
    of attack is kept, only the friction added at flight conditions is scaled.  The
    flight's SX form (alpha = atan2) is the same number, and the factor is 0 past 90 deg."""
    from ironbark_opt.aero.crossflow import axial_factor
    from ironbark_opt.aero.model import build_aero_model
    from ironbark_opt.aero.table import AeroTable
    from ironbark_opt.vehicle import load_rocket_geometry
    a = np.radians([0.0, 10.0, 45.0, 60.0, 90.0, 120.0])
    np.testing.assert_allclose(axial_factor(a), [1.0, np.cos(a[1]) ** 2, 0.5, 0.25, 0.0, 0.0],
                               atol=1e-15)
    y, x = ca.SX.sym("y"), ca.SX.sym("x")
    f = ca.Function("f", [y, x], [axial_factor(ca.atan2(y, x))])
    for yv, xv in ((0.3, 2.0), (1.0, 1.0), (2.0, -0.5)):
        assert float(f(yv, xv)) == pytest.approx(float(axial_factor(np.arctan2(yv, xv))), abs=1e-15)
    drag_curve = load_setup(ROOT / "examples/calisto/calisto.toml").aero
    assert len(drag_curve.table.alpha) == 1
    for alpha in (0.2, 0.9):
        assert drag_curve.axial(0.5, alpha, 1e7, False) == pytest.approx(
            drag_curve.axial(0.5, 0.0, 1e7, False) * np.cos(alpha) ** 2, rel=1e-12)
    rocket, _ = load_rocket_geometry(ROOT / "examples/kestrel/kestrel.toml")
    table = AeroTable.load(ROOT / "tables/Kestrel.csv")
    panel = build_aero_model(rocket, table=table)
    for alpha in (0.1, 0.6):
        friction = float(panel.friction.CA(0.5, 1e7))
        assert friction > 0.1
        assert panel.axial(0.5, alpha, 1e7, False) == pytest.approx(
            float(table.evaluate("CA", 0.5, alpha)) + friction * np.cos(alpha) ** 2, rel=1e-12)
