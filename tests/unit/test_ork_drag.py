"""Interim empirical pressure drag (ironbark_opt.aero.empirical_drag) against its formulas."""
from __future__ import annotations

import numpy as np
import pytest

from ironbark_opt.aero.empirical_drag import pressure_ca, pressure_drag_table, rounded_le, stagnation_ratio
from ironbark_opt.rocket import BodyTube, NoseCone, Rocket, TrapezoidalFins
from ironbark_opt.rocket.fin_sections import FinSection


def test_stagnation_ratio_values():
    # Niskanen 2013 eq. 3.85 at M = 0.5: 1 + 0.25/4 + 0.0625/40; eq. 3.86 at M = 2
    assert stagnation_ratio(0.5) == pytest.approx(1 + 0.0625 + 0.0625 / 40)
    assert stagnation_ratio(2.0) == pytest.approx(1.84 - 0.19 + 0.166 / 16 + 0.035 / 64)
    # the two branches nearly meet at M = 1 (1.275 vs 1.281)
    assert abs(stagnation_ratio(0.999999) - stagnation_ratio(1.0)) < 0.01


def test_rounded_leading_edge_is_continuous():
    assert rounded_le(0.0) == pytest.approx(0.0)
    # the published branches meet to 1.2e-3 at M = 0.9 ((0.19)^-0.417 - 1 = 0.9988)
    assert float(rounded_le(0.9 - 1e-9)) == pytest.approx(float(rounded_le(0.9)), abs=2e-3)
    assert float(rounded_le(1.0 - 1e-9)) == pytest.approx(float(rounded_le(1.0)), abs=0.03)


def _rocket(nose_shape):
    return Rocket("t", [NoseCone(shape=nose_shape, length=0.3, radius=0.05),
                        BodyTube(x=0.3, length=1.0, radius=0.05),
                        TrapezoidalFins(count=3, x=1.1, thickness=0.004, root_chord=0.2,
                                        tip_chord=0.1, span=0.1, sweep_length=0.0,
                                        section=FinSection(kind="square"))])


def test_square_fins_and_tangent_ogive_at_low_mach():
    r = _rocket("tangent_ogive")
    frontal = 0.004 * 0.1 * 3 / r.reference_area()
    # tangent ogive: zero joint angle -> no nose pressure drag; square fins: 0.85 q_stag/q
    # on the leading edge plus base drag 0.12 + 0.13 M^2 on the trailing edge
    ca = pressure_ca(r, np.array([0.0]))[0]
    assert ca == pytest.approx((0.85 + 0.12) * frontal, rel=1e-6)


def test_cone_adds_eq_3_81_and_table_is_pressure_only():
    cone, ogive = _rocket("conical"), _rocket("tangent_ogive")
    phi = np.arctan(0.05 / 0.3)
    diff = pressure_ca(cone, np.array([0.3]))[0] - pressure_ca(ogive, np.array([0.3]))[0]
    assert diff == pytest.approx(0.8 * np.sin(phi) ** 2, rel=1e-3)
    table = pressure_drag_table(cone)
    assert table.includes == ("pressure",)
    assert float(table.evaluate("CA", 0.3, 0.0)) == pytest.approx(
        pressure_ca(cone, np.array([0.3]))[0], rel=1e-3)


def test_rounded_trailing_edge_takes_half_the_base_drag():
    """OpenRocket's fin base drag: square trailing edge the full base coefficient
    (eq. 3.94), rounded half of it, sharp (airfoil) none; leading-edge parts as before."""
    def fins_ca(kind):
        r = Rocket("t", [NoseCone(shape="tangent_ogive", length=0.3, radius=0.05),
                         BodyTube(x=0.3, length=1.0, radius=0.05),
                         TrapezoidalFins(count=3, x=1.1, thickness=0.004, root_chord=0.2,
                                         tip_chord=0.1, span=0.1, sweep_length=0.0,
                                         section=FinSection(kind=kind))])
        return pressure_ca(r, np.array([0.0]))[0], 0.004 * 0.1 * 3 / r.reference_area()
    rounded, frontal = fins_ca("rounded")
    airfoil, _ = fins_ca("airfoil")
    assert rounded - airfoil == pytest.approx(0.5 * 0.12 * frontal, rel=1e-9)
    assert airfoil == pytest.approx(0.0, abs=1e-12)      # rounded LE drag is 0 at M = 0


def test_bevelled_fins_are_not_square_at_the_leading_edge():
    """A double-wedge (bevelled) fin's sharp leading edge takes the rounded-edge formula
    (eq. 3.89, as OpenRocket's airfoils), not the square edge's 0.85 q_stag/q."""
    def fins_ca(section, m):
        r = Rocket("t", [NoseCone(shape="tangent_ogive", length=0.3, radius=0.05),
                         BodyTube(x=0.3, length=1.0, radius=0.05),
                         TrapezoidalFins(count=3, x=1.1, thickness=0.004, root_chord=0.2,
                                         tip_chord=0.1, span=0.1, sweep_length=0.0,
                                         section=section)])
        return pressure_ca(r, np.array([m]))[0], 0.004 * 0.1 * 3 / r.reference_area()
    for m in (0.3, 2.0):
        bevel, frontal = fins_ca(FinSection(kind="hexagonal", le_bevel=0.02, te_bevel=0.02), m)
        airfoil, _ = fins_ca(FinSection(kind="airfoil"), m)
        assert bevel == pytest.approx(airfoil, rel=1e-12)
        # below the critical Mach number a streamlined edge has no pressure drag
        # (d'Alembert); supersonic it carries eq. 3.89 on its frontal area
        edge = float(rounded_le(m)) * frontal if m >= 1 else 0.0
        assert bevel == pytest.approx(edge + pressure_ca(
            Rocket("n", [NoseCone(shape="tangent_ogive", length=0.3, radius=0.05),
                         BodyTube(x=0.3, length=1.0, radius=0.05)]), np.array([m]))[0], rel=1e-9)


def test_streamlined_fins_rise_by_lock_above_the_korn_critical_mach():
    """Item 8 of issue 13: no rise below M_cr (Korn - Lock offset), Lock's fourth-power law
    on the exposed planform above it, continuous into eq. 3.89 at Mach 1."""
    from ironbark_opt.aero.compressibility import LOCK_OFFSET, korn_critical_mach
    from ironbark_opt.aero.empirical_drag import streamlined_fin_ca
    fins = TrapezoidalFins(count=4, x=1.1, thickness=0.012, root_chord=0.12, tip_chord=0.06,
                           span=0.11, sweep_length=0.06, section=FinSection(kind="airfoil"))
    sref = np.pi * 0.0635 ** 2
    m_cr = korn_critical_mach(0.12, 0.06, 0.06, 0.11, 0.012)
    # Korn by hand: t/c 0.012/0.09, mid-chord sweep atan(0.03/0.11)
    c = np.cos(np.arctan(0.03 / 0.11))
    assert m_cr == pytest.approx(0.87 / c - (0.012 / 0.09) / c ** 2 - LOCK_OFFSET, rel=1e-12)
    ca = streamlined_fin_ca(fins, np.array([0.0, m_cr - 0.01, m_cr, m_cr + 0.05]), sref)
    assert np.all(ca[:3] == 0.0)
    assert ca[3] == pytest.approx(20 * 0.05 ** 4 * 4 * fins.planform_area() / sref, rel=1e-12)
    m = np.linspace(0.5, 1.0, 501)
    rise = streamlined_fin_ca(fins, m, sref)
    assert np.all(np.diff(rise) >= -1e-15)                       # monotone to Mach 1
    frontal = 4 * 0.012 * 0.11 / sref * np.cos(np.arctan2(0.06, 0.11)) ** 2
    at1 = float(streamlined_fin_ca(fins, np.array([1.0 - 1e-9]), sref)[0])
    assert at1 == pytest.approx(float(rounded_le(1.0)) * frontal, rel=1e-6)


def test_flat_front_carries_the_stagnation_pressure():
    """A body that starts with a tube (a booster after separation): the flat front adds
    0.85 q_stag/q on its full area (Niskanen 2013 eq. 3.87, Hoerner ch. 3), i.e. 0.85 at
    M = 0 and 0.85 x 1.0641 at M = 0.5 on a face of the reference area; a nose adds none."""
    tube = Rocket("booster", [BodyTube(length=1.0, radius=0.05)])
    with_nose = _rocket("tangent_ogive")
    for m, expected in ((0.0, 0.85), (0.5, 0.85 * (1 + 0.0625 + 0.0625 / 40)), (2.0, 0.85 * float(stagnation_ratio(2.0)))):
        assert pressure_ca(tube, np.array([m]))[0] == pytest.approx(expected, rel=1e-12)
    bare = Rocket("t", [BodyTube(length=1.0, radius=0.05),
                        TrapezoidalFins(count=3, x=0.8, thickness=0.004, root_chord=0.2, tip_chord=0.1, span=0.1,
                                        sweep_length=0.0, section=FinSection(kind="square"))])
    fins_only = pressure_ca(with_nose, np.array([0.3]))[0]          # tangent ogive: no nose drag
    assert pressure_ca(bare, np.array([0.3]))[0] - fins_only == pytest.approx(0.85 * float(stagnation_ratio(0.3)))
