"""SolidMotor: thrust curve, impulse, scaling, mass model, symbolic/numeric drift."""
from __future__ import annotations

import dataclasses
import math
from pathlib import Path

import casadi as ca
import numpy as np
import pytest
from scipy.integrate import quad

from ironbark_opt.errors import InputError
from ironbark_opt.motors import Grains, SolidMotor, impulse_class, load_motor, read_eng, read_rse

DATA = Path(__file__).resolve().parents[1] / "data" / "motors"
G0 = 9.80665

# Calisto reference motor (../shared/reference/calisto/README.md)
CALISTO_GRAINS = Grains(count=5, density=1815.0, outer_radius=0.033, inner_radius=0.015,
                        height=0.120, separation=0.005)


def calisto():
    m = load_motor(DATA / "Cesaroni_M1670.eng")
    return dataclasses.replace(m, propellant_mass=None, grains=CALISTO_GRAINS, dry_mass=1.815,
                               dry_cg=0.317, propellant_cg=0.397, dry_inertia=(0.125, 0.002))


def file_points(motor):
    """The file's points with the RASP (0, 0) start, independent of SolidMotor."""
    t, F = np.asarray(motor.time, float), np.asarray(motor.thrust, float)
    if t[0] > 0:
        t, F = np.r_[0.0, t], np.r_[0.0, F]
    return t, F


ENG_FILES = sorted(p.name for p in DATA.glob("*.eng")
                   if not p.name.startswith(("uwinrockets", "Cesaroni_M1101")))


# ----------------------------------------------------------------- impulse
@pytest.mark.parametrize("name", ENG_FILES)
def test_total_impulse_equals_trapezoid_of_file(name):
    for m in read_eng(DATA / name):
        t, F = file_points(m)
        ref = float(np.trapezoid(F, t))
        err = abs(m.total_impulse - ref) / ref
        print(f"{name} {m.designation}: I = {m.total_impulse:.4f} N s, trapezoid {ref:.4f}, "
              f"rel err {err:.1e} (tol 1e-12)")
        assert err < 1e-12
        assert float(m.impulse(m.burn_time + 5.0)) == pytest.approx(ref, rel=1e-12)


def test_impulse_history_against_quadrature():
    """I(t) (exact piecewise quadratic) vs adaptive quadrature of np.interp (tol 1e-8 rel)."""
    m = load_motor(DATA / "AeroTech_K828FJ.eng")
    t, F = file_points(m)
    worst = 0.0
    for tq in np.linspace(0.0, m.burn_time, 37):
        ref = quad(lambda x: np.interp(x, t, F), 0.0, tq, points=t[t < tq], limit=200)[0]
        worst = max(worst, abs(m.impulse(tq) - ref))
    print(f"K828FJ impulse history: max |I - quad| = {worst:.2e} N s (tol 1e-8 * I)")
    assert worst < 1e-8 * m.total_impulse


def test_thrust_interpolates_points_and_is_zero_outside_burn():
    m = load_motor(DATA / "Cesaroni_M1670.eng")
    t, F = file_points(m)
    assert np.allclose(m.thrust(t), F, rtol=0, atol=1e-9)
    mid = (t[1:] + t[:-1]) / 2
    assert np.allclose(m.thrust(mid), (F[1:] + F[:-1]) / 2, atol=1e-9)
    for x in (-1.0, -1e-9, m.burn_time + 1e-9, m.burn_time + 1.0, 100.0):
        assert m.thrust(x) == 0.0
    assert isinstance(m.thrust(1.0), float)
    assert m.max_thrust == 2200.0
    assert m.average_thrust == pytest.approx(m.total_impulse / 3.9)


def test_jump_at_ignition_and_nonzero_last_point():
    k550 = read_rse(DATA / "tc_api_decoded_AeroTech_K550W.rse")[0]   # two rows at t = 0
    assert k550.thrust(0.0) == pytest.approx(628.15)
    assert k550.thrust(-1e-12) == 0.0
    t, F = np.asarray(k550.time), np.asarray(k550.thrust)
    assert k550.total_impulse == pytest.approx(np.trapezoid(F, t), rel=1e-12)
    l2775 = load_motor(DATA / "AeroTech_L2775ST-PS.eng")             # ends at 14.36 N
    assert l2775.thrust(l2775.burn_time) == pytest.approx(14.35612)
    assert l2775.thrust(l2775.burn_time + 1e-9) == 0.0


def test_repeated_interior_time_is_a_jump():
    m = SolidMotor([0.0, 1.0, 1.0, 2.0], [100.0, 100.0, 50.0, 0.0], propellant_mass=0.1,
                   dry_mass=0.1, diameter=0.03, length=0.2)
    ref = 100.0 + 25.0
    # the jump becomes a 1e-6 s ramp: the impulse changes by < max thrust * 1e-6 s
    print(f"impulse with a jump: {m.total_impulse:.7f} vs {ref} N s")
    assert 0 < abs(m.total_impulse - ref) <= 100.0 * 1e-6
    assert m.thrust(0.5) == 100.0 and m.thrust(1.5) == pytest.approx(25.0, abs=1e-4)


# ----------------------------------------------------------------- scaling
def test_thrust_and_time_scaling():
    m = load_motor(DATA / "AeroTech_K990DM.eng")
    k, s = 1.07, 0.9
    for tt in np.linspace(-0.1, 2.5, 27):
        assert m.thrust(tt, k, s) == pytest.approx(k / s * m.thrust(tt / s), abs=1e-9)
        assert m.propellant_mass(tt, k, s) == pytest.approx(m.propellant_mass(tt / s), abs=1e-12)
        assert m.propellant_mass(tt, k, s) == pytest.approx(m.propellant_mass(tt, 1.0, s))
    t_end = m.burn_time * s
    delivered = quad(lambda x: m.thrust(x, k, s), 0.0, t_end, limit=400,
                     points=np.asarray(m.time) * s)[0]
    print(f"scaled impulse {delivered:.4f} vs k*I {k * m.total_impulse:.4f} N s")
    assert delivered == pytest.approx(k * m.total_impulse, rel=1e-8)
    assert m.impulse(t_end, k, s) == pytest.approx(k * m.total_impulse, rel=1e-12)
    assert m.propellant_mass(t_end, k, s) == pytest.approx(0.0, abs=1e-12)
    assert m.burn_time_scaled(s) == pytest.approx(m.burn_time * s)


# -------------------------------------------------------------- mass model
def test_propellant_burned_in_proportion_to_impulse():
    m = load_motor(DATA / "AeroTech_M1939W.eng")
    assert m.mass(0.0) == pytest.approx(8.98822)
    assert m.propellant_mass(0.0) == pytest.approx(5.656)
    assert m.mass(m.burn_time + 1) == pytest.approx(8.98822 - 5.656)
    for tt in np.linspace(0, m.burn_time, 11):
        frac = m.impulse(tt) / m.total_impulse
        assert m.propellant_mass(tt) == pytest.approx(5.656 * (1 - frac), abs=1e-12)


def test_propellant_mass_matches_thrustcurve_mass_column():
    """ThrustCurve.org's .rse m column vs our impulse-proportional model (tol 0.05 g)."""
    path = DATA / "tc_api_decoded_AeroTech_K185W.rse"
    m = read_rse(path)[0]
    import re
    rows = re.findall(r'm="([\d.]+)" t="([\d.]+)"', path.read_text())
    worst = max(abs(m.propellant_mass(float(t)) * 1000 - float(mg)) for mg, t in rows)
    print(f"K185W: max |m_p - ThrustCurve m| = {worst:.4f} g (tol 0.05 g)")
    assert worst < 0.05


def test_calisto_grains_mass_cg_inertia():
    m = calisto()
    g = CALISTO_GRAINS
    print(f"Calisto propellant mass from grains {g.mass:.4f} kg (reference 2.956 kg)")
    assert g.mass == pytest.approx(2.956, abs=5e-4)
    assert m.propellant_mass_initial == pytest.approx(2.956, abs=5e-4)
    assert m.mass(0.0) == pytest.approx(1.815 + 2.956, abs=5e-4)
    cg0 = (1.815 * 0.317 + g.mass * 0.397) / (1.815 + g.mass)
    assert m.cg(0.0) == pytest.approx(cg0, abs=1e-12)
    assert m.cg(10.0) == pytest.approx(0.317, abs=1e-9)
    # independent route: each grain's inertia about the nozzle exit, then to the CG
    for tt in (0.0, 1.0, 2.5, 3.9):
        mp = m.propellant_mass(tt)
        r2 = g.outer_radius ** 2 - mp / (g.count * g.density * math.pi * g.height)
        mg = mp / g.count
        pitch = g.height + g.separation
        xs = [0.397 + (k - 2) * pitch for k in range(5)]
        I_exit = 0.125 + 1.815 * 0.317 ** 2
        I_exit += sum(mg * (3 * (g.outer_radius ** 2 + r2) + g.height ** 2) / 12 + mg * x ** 2
                      for x in xs)
        x_cg = (1.815 * 0.317 + mp * 0.397) / (1.815 + mp)
        ref_t = I_exit - (1.815 + mp) * x_cg ** 2
        ref_a = 0.002 + mp * (g.outer_radius ** 2 + r2) / 2
        it, ia = m.inertia(tt)
        print(f"t={tt}: I_t {it:.6f} vs {ref_t:.6f}, I_a {ia:.6f} vs {ref_a:.6f} kg m^2")
        assert it == pytest.approx(ref_t, rel=1e-9)
        assert ia == pytest.approx(ref_a, rel=1e-9)
    assert m.inertia(10.0) == pytest.approx((0.125, 0.002), abs=1e-12)


def test_default_cg_and_inertia_models():
    m = load_motor(DATA / "Cesaroni_M1670.eng")
    R, L, md, mp = 0.0375, 0.757, 5.231 - 3.101, 3.101
    assert m.dry_cg_value == m.propellant_cg_value == pytest.approx(L / 2)
    assert m.cg(0.0) == pytest.approx(L / 2) and m.cg(5.0) == pytest.approx(L / 2)
    assert m.dry_inertia_value == pytest.approx((md * (R ** 2 / 2 + L ** 2 / 12), md * R ** 2))
    # at ignition: hollow cylinder with bore R/2 filling the case
    it, ia = m.inertia(0.0)
    r2 = R ** 2 / 4
    assert ia == pytest.approx(md * R ** 2 + mp * (R ** 2 + r2) / 2)
    assert it == pytest.approx(md * (R ** 2 / 2 + L ** 2 / 12) + mp * (3 * (R ** 2 + r2) + L ** 2) / 12)


def test_pressure_thrust_correction():
    m = load_motor(DATA / "Cesaroni_M1670.eng")
    assert m.pressure_thrust_correction(80000.0) == 0.0
    A = math.pi * 0.033 ** 2
    m2 = dataclasses.replace(m, nozzle_exit_area=A)
    assert m2.pressure_thrust_correction(60000.0) == pytest.approx((101325.0 - 60000.0) * A)
    p = ca.SX.sym("p")
    f = ca.Function("f", [p], [m2.pressure_thrust_correction(p)])
    assert float(f(60000.0)) == pytest.approx((101325.0 - 60000.0) * A)


# -------------------------------------------------- symbolic/numeric drift
@pytest.mark.parametrize("name", ["Cesaroni_M1670.eng", "AeroTech_L2775ST-PS.eng"])
def test_symbolic_and_numeric_evaluation_agree(name):
    m = dataclasses.replace(load_motor(DATA / name), grains=CALISTO_GRAINS)
    grid = np.r_[-0.5, np.linspace(0, m.burn_time * 1.1, 53), m.burn_time, 30.0]
    k, s = 1.05, 0.97
    worst = 0.0
    for cls in (ca.SX, ca.MX):
        t, ks, ss = cls.sym("t"), cls.sym("k"), cls.sym("s")
        st = m.state(t, ks, ss)
        outs = [m.thrust(t, ks, ss), m.impulse(t, ks, ss), m.propellant_mass(t, ks, ss),
                m.mass(t, ks, ss), m.cg(t, ks, ss), *m.inertia(t, ks, ss),
                st.thrust, st.mass, st.cg, *st.inertia]
        fun = ca.Function("motor", [t, ks, ss], outs)
        arr = [m.thrust(grid, k, s), m.impulse(grid, k, s), m.propellant_mass(grid, k, s),
               m.mass(grid, k, s), m.cg(grid, k, s), *m.inertia(grid, k, s)]
        arr += [arr[0], arr[3], arr[4], arr[5], arr[6]]
        for j, tt in enumerate(grid):
            sym = [float(v) for v in fun(tt, k, s)]
            num = [m.thrust(float(tt), k, s), m.impulse(float(tt), k, s),
                   m.propellant_mass(float(tt), k, s), m.mass(float(tt), k, s),
                   m.cg(float(tt), k, s), *m.inertia(float(tt), k, s)]
            num += [num[0], num[3], num[4], num[5], num[6]]
            for a, b, c in zip(sym, num, (x[j] for x in arr)):
                worst = max(worst, abs(a - b) / (1 + abs(b)), abs(c - b) / (1 + abs(b)))
    print(f"{name}: max relative difference float/array/SX/MX = {worst:.1e} (tol 1e-10)")
    assert worst < 1e-10


def test_symbolic_vector_of_times():
    m = load_motor(DATA / "Cesaroni_M1670.eng")
    grid = np.array([-1.0, 0.3, 1.7, 3.5, 9.0])
    for cls in (ca.SX, ca.MX):
        t = cls.sym("t", 5)
        f = ca.Function("f", [t], [m.thrust(t), m.mass(t)])
        F, M = f(grid)
        assert np.allclose(F.full().ravel(), m.thrust(grid), rtol=1e-12, atol=1e-9)
        assert np.allclose(M.full().ravel(), m.mass(grid), rtol=1e-12)


def test_symbolic_thrust_has_derivative_of_the_curve():
    m = load_motor(DATA / "Cesaroni_M1670.eng")
    t = ca.SX.sym("t")
    d = ca.Function("d", [t], [ca.jacobian(m.impulse(t), t), ca.jacobian(m.thrust(t), t)])
    dI, dF = (float(v) for v in d(0.7))
    assert dI == pytest.approx(m.thrust(0.7), rel=1e-12)
    assert dF == pytest.approx((2034 - 1950) / 0.5, rel=1e-9)


# -------------------------------------------------------- object behaviour
def test_dataclass_replace_and_frozen():
    m = load_motor(DATA / "Cesaroni_M1670.eng")
    assert np.asarray(m.thrust)[0] == 100.0 and float(m.propellant_mass) == 3.101
    m2 = dataclasses.replace(m, dry_mass=1.0)
    assert m2.dry_mass == 1.0 and m2.total_impulse == m.total_impulse
    assert np.array_equal(np.asarray(m2.thrust), np.asarray(m.thrust))
    m3 = dataclasses.replace(m, thrust=2 * np.asarray(m.thrust))
    assert m3.total_impulse == pytest.approx(2 * m.total_impulse)
    with pytest.raises(dataclasses.FrozenInstanceError):
        m.dry_mass = 3.0


@pytest.mark.parametrize("kwargs, field", [
    (dict(dry_mass=-1.0), "dry_mass"),
    (dict(diameter=0.0), "diameter"),
    (dict(propellant_mass=None), "propellant_mass"),
    (dict(dry_inertia=(1.0,)), "dry_inertia"),
    (dict(grains="five"), "grains"),
])
def test_bad_constructor_arguments(kwargs, field):
    base = dict(propellant_mass=0.1, dry_mass=0.1, diameter=0.03, length=0.2)
    with pytest.raises(InputError) as exc:
        SolidMotor([0.0, 1.0, 2.0], [10.0, 10.0, 0.0], **{**base, **kwargs})
    assert exc.value.field == field


@pytest.mark.parametrize("t, F, field", [
    ([0.0, 2.0, 1.0], [1.0, 2.0, 0.0], "time"),
    ([0.0, 1.0], [1.0, 2.0, 0.0], "thrust"),
    ([0.0, 1.0], [1.0, -2.0], "thrust"),
    ([0.0, 1.0], [0.0, np.nan], "thrust"),
])
def test_bad_curves(t, F, field):
    with pytest.raises(InputError) as exc:
        SolidMotor(t, F, propellant_mass=0.1, dry_mass=0.1, diameter=0.03, length=0.2)
    assert exc.value.field == field


def test_grains_validation():
    with pytest.raises(InputError, match="inner radius"):
        Grains(1, 1800.0, 0.01, 0.02, 0.1, 0.0)
    with pytest.raises(InputError, match="whole number"):
        Grains(2.5, 1800.0, 0.03, 0.01, 0.1, 0.0)
    assert Grains(2.0, 1800.0, 0.03, 0.01, 0.1).count == 2


@pytest.mark.parametrize("impulse, letter", [
    (0.3, "1/8A"), (0.5, "1/4A"), (1.0, "1/2A"), (1.25, "1/2A"), (2.5, "A"), (2.51, "B"),
    (5.0, "B"), (40.0, "E"), (6026.35, "M"), (19189.8, "N"), (40960.0, "O")])
def test_impulse_class(impulse, letter):
    assert impulse_class(impulse) == letter


def test_summary_and_to_dict():
    m = calisto()
    d = m.to_dict()
    assert d["impulse_class"] == "M" and d["designation"] == "M1670-BS"
    assert d["total_impulse_Ns"] == pytest.approx(6026.35)
    assert d["total_mass_kg"] == pytest.approx(1.815 + CALISTO_GRAINS.mass)
    assert d["max_thrust_N"] == 2200.0 and d["delays_s"] == [0.0]
    text = m.summary()
    assert "M1670-BS" in text and "6026.4" in text and "class M" in text
    assert "M1670-BS" in repr(m)
