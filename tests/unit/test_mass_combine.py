"""Symbolic-safe combination of mass properties, total(t) and wet/dry conversion."""
import math

import casadi as ca
import pytest

from ironbark_opt.errors import InputError
from ironbark_opt.rocket import (MassProperties, combine, combine_properties, dry_from_wet,
                                 total_mass_properties)

# Calisto (../shared/reference/calisto/README.md)
DRY = MassProperties.axisymmetric(14.426, 1.278, 6.321, 0.034)
NOZZLE_X = 2.533
MOTOR_DRY = dict(mass=1.815, cg=0.317, I=(0.125, 0.002))
GRAINS = dict(count=5, density=1815.0, ro=0.033, ri=0.015, h=0.120, cg=0.397)


def grain_mass():
    g = GRAINS
    return g["count"] * g["density"] * math.pi * (g["ro"] ** 2 - g["ri"] ** 2) * g["h"]


def test_two_half_rods_make_one_rod():
    m, L = 2.0, 1.5
    half = lambda xc: (m / 2, xc, (m / 2) * (L / 2) ** 2 / 12, 0.0)
    mass, cg, it, ia = combine([half(L / 4), half(3 * L / 4)])
    assert (mass, cg) == pytest.approx((m, L / 2))
    assert it == pytest.approx(m * L * L / 12, rel=1e-14)


def test_combine_symbolic_matches_numeric():
    mb, xb = ca.SX.sym("mb"), ca.SX.sym("xb")
    mm, xm = ca.SX.sym("mm"), ca.SX.sym("xm")
    out = total_mass_properties(DRY, mb, xb, mm, xm, 0.1 * mm, 0.01 * mm)
    f = ca.Function("total", [mb, xb, mm, xm], list(out))
    args = (0.8, 0.4, 4.771, 2.17)
    sym = [float(v) for v in f(*args)]
    num = total_mass_properties(DRY, args[0], args[1], args[2], args[3],
                                0.1 * args[2], 0.01 * args[2])
    assert sym == pytest.approx(list(num), rel=1e-14)
    # independent: moments about the nose tip
    m = 14.426 + 0.8 + 4.771
    cg = (14.426 * 1.278 + 0.8 * 0.4 + 4.771 * 2.17) / m
    i0 = (6.321 + 14.426 * 1.278 ** 2) + 0.8 * 0.4 ** 2 + (0.4771 + 4.771 * 2.17 ** 2)
    assert sym[0] == pytest.approx(m) and sym[1] == pytest.approx(cg)
    assert sym[2] == pytest.approx(i0 - m * cg * cg, rel=1e-12)
    assert sym[3] == pytest.approx(0.034 + 0.04771)
    # derivative of the CG w.r.t. ballast mass: (xb - cg) / m
    dcg = ca.Function("d", [mb, xb, mm, xm], [ca.jacobian(out[1], mb)])
    assert float(dcg(*args)) == pytest.approx((0.4 - cg) / m, rel=1e-12)


def test_calisto_launch_mass_and_wet_dry_round_trip():
    mp = grain_mass()
    print(f"Calisto propellant from grains {mp:.4f} kg (README 2.956 kg)")
    assert mp == pytest.approx(2.956, abs=5e-4)
    m_motor = MOTOR_DRY["mass"] + mp
    cg_motor = (MOTOR_DRY["mass"] * MOTOR_DRY["cg"] + mp * GRAINS["cg"]) / m_motor
    x_motor = NOZZLE_X - cg_motor
    # motor inertia about its CG: the dry part only (enough for a round trip)
    i_t = MOTOR_DRY["I"][0] + MOTOR_DRY["mass"] * (MOTOR_DRY["cg"] - cg_motor) ** 2
    i_a = MOTOR_DRY["I"][1]
    wet = total_mass_properties(DRY, 0.0, 0.0, m_motor, x_motor, i_t, i_a)
    print(f"Calisto launch mass {wet[0]:.4f} kg (README 19.197 kg), CG {wet[1]:.4f} m")
    assert wet[0] == pytest.approx(19.197, abs=1e-3)
    back = dry_from_wet(wet, m_motor, x_motor, i_t, i_a)
    assert list(back) == pytest.approx(list(DRY.as_tuple()), rel=1e-12)
    wet_mp = MassProperties.axisymmetric(*wet)
    back_mp = dry_from_wet(wet_mp, m_motor, x_motor, i_t, i_a)
    assert isinstance(back_mp, MassProperties)
    assert back_mp.inertia == pytest.approx(DRY.inertia, rel=1e-12)


def test_dry_from_wet_symbolic():
    mm = ca.SX.sym("mm")
    out = dry_from_wet((20.0, 1.5, 8.0, 0.08), mm, 2.2, 0.3, 0.004)
    f = ca.Function("dry", [mm], list(out))
    num = dry_from_wet((20.0, 1.5, 8.0, 0.08), 4.0, 2.2, 0.3, 0.004)
    assert [float(v) for v in f(4.0)] == pytest.approx(list(num), rel=1e-14)
    it = ca.MX.sym("it")                                  # only the wet inertia symbolic
    out = dry_from_wet((20.0, 1.5, it, 0.08), 4.0, 2.2, 0.3, 0.004)
    g = ca.Function("dry_it", [it], [out[2]])
    assert float(g(8.0)) == pytest.approx(num[2], rel=1e-14)


def test_full_tensor_products_of_inertia_survive_combination():
    cad = MassProperties(10.0, 1.0, [[0.05, 0.001, 0.0], [0.001, 5.0, 0.02], [0.0, 0.02, 5.1]])
    pm = MassProperties.axisymmetric(1.0, 2.0, 0.0, 0.0)
    tot = combine_properties([cad, pm])
    cg = (10 + 2) / 11
    assert tot.cg_x == pytest.approx(cg)
    assert tot.inertia[1, 2] == pytest.approx(0.02) and tot.inertia[0, 1] == pytest.approx(0.001)
    assert tot.inertia[1, 1] == pytest.approx(5.0 + 10 * (1 - cg) ** 2 + (2 - cg) ** 2)
    assert (cad + pm).mass == pytest.approx(11.0)


def test_errors():
    with pytest.raises(InputError, match="not larger"):
        dry_from_wet((3.0, 1.0, 1.0, 0.1), 4.0, 2.0, 0.1, 0.01)
    with pytest.raises(InputError, match="zero"):
        combine([(0.0, 1.0, 0.0, 0.0)])
    with pytest.raises(InputError):
        combine([(1.0, 2.0)])
    with pytest.raises(InputError, match="inertia"):
        dry_from_wet((20.0, 1.5, 0.01, 0.08), 4.0, 2.2, 0.3, 0.004)
