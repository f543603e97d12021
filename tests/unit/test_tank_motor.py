"""Liquid motor from tanks (ironbark_opt/motors/tanks.py, tank_motor.py) against an
analytic tank drain: constant outflow, so the liquid mass falls linearly and its
column's CG moves linearly; a second tank drained with the thrust; ignition after
the valves open; TOML keys and their errors."""
import shutil
from pathlib import Path

import casadi as ca
import numpy as np
import pytest

from ironbark_opt.errors import InputError
from ironbark_opt.flight import simulate
from ironbark_opt.rocket.toml_io import loads_rocket_toml
from ironbark_opt.vehicle import load_motor_for, setup_from_file

ROOT = Path(__file__).resolve().parents[2]
DATA = ROOT / "tests" / "data" / "motors" / "liquid"
CALISTO = ROOT / "examples" / "calisto" / "calisto.toml"

R, L, RHO_L, RHO_G = 0.08, 0.9, 800.0, 50.0      # oxidiser tank [m, m, kg/m^3, kg/m^3]
POS_OX, POS_FUEL = 1.2, 0.5                       # tank centres fwd of the nozzle exit [m]
M_OX0, M_GAS, MDOT = 12.0, 0.2, 2.0               # kg, kg, kg/s (0 .. 5.5 s)
M_FUEL0, R_F, L_F, RHO_F = 4.0, 0.07, 0.4, 790.0
T_IG, T_BURN, THRUST = 0.5, 5.0, 2000.0          # ignition after the valves open; burn [s]; [N]
DRY, DRY_CG, DRY_I = 8.0, 0.8, (2.0, 0.05)

MOTOR = f"""[motor]
file = "thrust.csv"
nozzle_x = 2.533
kind = "liquid"
ignition_time = {T_IG}

[motor.overrides]
dry_mass = {DRY}
dry_cg = {DRY_CG}
dry_inertia = [{DRY_I[0]}, {DRY_I[1]}]

[[motor.tank]]
name = "oxidiser"
position = {POS_OX}
radius = {R}
length = {L}
liquid_density = {RHO_L}
gas_density = {RHO_G}
schedule = "mass_flow"
liquid_mass = {M_OX0}
gas_mass = {M_GAS}
file = "ox_flow.csv"

[[motor.tank]]
name = "fuel"
position = {POS_FUEL}
radius = {R_F}
length = {L_F}
liquid_density = {RHO_F}
gas_density = 1.0
schedule = "thrust"
liquid_mass = {M_FUEL0}

"""


def _rocket_text(motor_block=MOTOR):
    text = CALISTO.read_text()
    start, end = text.index("[motor]"), text.index("[aero]")
    return text[:start] + motor_block + text[end:]


@pytest.fixture()
def folder(tmp_path):
    for f in ("thrust.csv", "ox_flow.csv", "ox_level.csv"):
        shutil.copy(DATA / f, tmp_path / f)
    for f in CALISTO.parent.iterdir():
        if f.suffix in (".csv", ".eng"):
            shutil.copy(f, tmp_path / f.name)
    return tmp_path


def _rocket_file(folder, motor_block=MOTOR):
    return loads_rocket_toml(_rocket_text(motor_block), folder / "rocket.toml")


def _analytic(t):
    """Masses, CG [m fwd of nozzle] and transverse inertia about the CG of the
    motor written out: oxidiser liquid column from the aft end, gas over it,
    fuel tank drained in proportion to the (constant-thrust) impulse."""
    area = np.pi * R * R
    m_l = M_OX0 - MDOT * min(t, 5.5)
    h = m_l / (RHO_L * area)
    aft = POS_OX - L / 2
    x_l, x_g = aft + h / 2, aft + h + (L - h) / 2
    frac = np.clip((t - T_IG) / T_BURN, 0.0, 1.0)
    m_f = M_FUEL0 * (1 - frac)
    h_f = m_f / (RHO_F * np.pi * R_F ** 2)
    x_f = POS_FUEL - L_F / 2 + h_f / 2
    parts = [(DRY, DRY_CG, DRY_I[0]),
             (m_l, x_l, m_l * (3 * R * R + h * h) / 12),
             (M_GAS, x_g, M_GAS * (3 * R * R + (L - h) ** 2) / 12),
             (m_f, x_f, m_f * (3 * R_F ** 2 + h_f ** 2) / 12)]
    m = sum(p[0] for p in parts)
    x = sum(p[0] * p[1] for p in parts) / m
    i_t = sum(p[2] + p[0] * (p[1] - x) ** 2 for p in parts)
    return m, x, i_t


def test_constant_outflow_tank_against_analytic_drain(folder):
    motor = load_motor_for(_rocket_file(folder).motor)
    assert motor.kind == "liquid" and motor.ignition == pytest.approx(T_IG)
    assert motor.total_impulse == pytest.approx(THRUST * T_BURN)
    print("\n  t [s]   mass [kg] (analytic)     CG [m] (analytic)      I_t [kg m^2] (analytic)")
    for t in (0.0, 0.3, 0.5, 1.7, 3.0, 5.5, 7.0):
        m, x, i_t = _analytic(t)
        got = (float(motor.mass(t)), float(motor.cg(t)), float(motor.inertia(t)[0]))
        print(f"  {t:4.1f}  {got[0]:8.4f} ({m:8.4f})  {got[1]:8.5f} ({x:8.5f})  {got[2]:9.5f} ({i_t:9.5f})")
        assert got[0] == pytest.approx(m, rel=1e-6)
        assert got[1] == pytest.approx(x, abs=1e-6)
        assert got[2] == pytest.approx(i_t, rel=1e-5)
    # thrust only after ignition; before it the oxidiser drains on the pad
    assert float(motor.thrust(0.3)) == 0.0 and float(motor.thrust(1.0)) == pytest.approx(THRUST)
    assert float(motor.mass(0.5)) == pytest.approx(float(motor.mass(0.0)) - MDOT * 0.5)


def test_symbolic_equals_numeric_and_time_scale(folder):
    motor = load_motor_for(_rocket_file(folder).motor)
    t = ca.SX.sym("t")
    s = ca.SX.sym("s")
    st = motor.state(t, thrust_scale=1.1, time_scale=s)
    f = ca.Function("f", [t, s], [st.thrust, st.mass, st.cg, st.inertia[0], st.inertia[1]])
    for tv in (0.2, 2.0, 4.4, 6.0):
        for sv in (1.0, 1.2):
            sym = [float(v) for v in f(tv, sv)]
            num = motor.state(tv, thrust_scale=1.1, time_scale=sv)
            ref = [num.thrust, num.mass, num.cg, num.inertia[0], num.inertia[1]]
            assert sym == pytest.approx([float(v) for v in ref], rel=1e-9, abs=1e-9)
            # the propellant history depends on t / s only
            assert float(num.mass) == pytest.approx(float(motor.mass(tv / sv)))


def test_level_schedule_equals_mass_flow(folder):
    """ox_level.csv is the same drain as a liquid level: identical mass and CG."""
    block = MOTOR.replace('schedule = "mass_flow"\nliquid_mass = 12.0\ngas_mass = 0.2\nfile = "ox_flow.csv"',
                          'schedule = "level"\nfile = "ox_level.csv"')
    assert block != MOTOR
    by_level = load_motor_for(_rocket_file(folder, block).motor)
    by_flow = load_motor_for(_rocket_file(folder).motor)
    area = np.pi * R * R
    for t in (0.0, 2.0, 5.5):
        m_l = M_OX0 - MDOT * t
        tank = by_level.tanks[0]
        liquid, gas = tank.masses(t)
        assert liquid == pytest.approx(m_l, rel=1e-6)
        assert gas == pytest.approx(RHO_G * area * (L - m_l / (RHO_L * area)), rel=1e-6)
        # the level file's gas is the ullage at its density, the flow file's a fixed 0.2 kg:
        # compare the liquid's CG through a tank without gas
        _, x_lev, _ = tank.mass_properties(liquid, 0.0)
        _, x_flow, _ = by_flow.tanks[0].mass_properties(by_flow.tanks[0].masses(t)[0], 0.0)
        assert x_lev == pytest.approx(x_flow, abs=1e-6)


def test_liquid_motor_flies(folder):
    setup = setup_from_file(_rocket_file(folder))
    flight = simulate(setup)
    print(f"\nliquid test motor on Calisto: apogee {flight.apogee_agl:.1f} m, burnout "
          f"{setup.motor.burn_time:.2f} s")
    assert flight.apogee_agl > 100.0
    df = flight.to_dataframe()
    row = df.iloc[(df["time_s"] - 3.0).abs().argmin()]
    m, _, _ = _analytic(float(row["time_s"]))
    assert row["mass_kg"] == pytest.approx(setup.dry.mass + m, rel=1e-6)


@pytest.mark.parametrize("old, new, field, message", [
    ('radius = 0.08', 'radius = -0.08', "motor.tank[0].radius", "must be > 0"),
    ('liquid_mass = 12.0', 'liquid_mass = 30.0', "motor.tank[0].liquid_mass", "the tank holds"),
    ('schedule = "thrust"', 'schedule = "pressure"', "motor.tank[1].schedule", "expected one of"),
    ('kind = "liquid"', 'kind = "gas"', "motor.kind", "expected one of"),
    ('file = "ox_flow.csv"', 'file = "missing.csv"', "motor.tank[0].file", "file not found"),
    ('dry_cg = 0.8\n', '', "motor.overrides.dry_cg", "needs [motor.overrides] dry_cg"),
    ('ignition_time = 0.5', 'ignition_time = -1.0', "motor.ignition_time", "must be >= 0"),
    ('schedule = "thrust"', 'schedule = "thrust"\nflow_end = 3.0', "motor.tank[1].flow_end",
     "not used by schedule"),
])
def test_bad_tank_keys_name_file_line_field(folder, old, new, field, message):
    block = MOTOR.replace(old, new, 1)
    assert block != MOTOR
    with pytest.raises(InputError) as err:
        _rocket_file(folder, block)
    e = err.value
    print(e)
    assert e.field == field and message in e.message
    assert e.line is not None and str(e.source).endswith("rocket.toml")
    if field.endswith("radius") or field.endswith("schedule"):
        line = _rocket_text(block).splitlines()[e.line - 1]
        assert line.startswith(field.split(".")[-1])


def test_outflow_beyond_the_initial_mass_is_refused(folder):
    block = MOTOR.replace("liquid_mass = 12.0", "liquid_mass = 5.0", 1)
    with pytest.raises(InputError, match="negative mass"):
        _rocket_file(folder, block)


@pytest.mark.parametrize("schedule, header, rows", [
    # the same drain as ox_flow.csv: ullage volume V - m_l / rho_l, and liquid/gas masses
    ("ullage", "time_s,ullage_m3", [(0.0, None), (5.5, None)]),
    ("mass", "time_s,liquid_kg,gas_kg", [(0.0, (12.0, 0.2)), (5.5, (1.0, 0.2))]),
])
def test_ullage_and_mass_schedules_equal_the_flow(folder, schedule, header, rows):
    volume = np.pi * R * R * L
    lines = [header]
    for t, masses in rows:
        if schedule == "ullage":
            lines.append(f"{t},{volume - (M_OX0 - MDOT * t) / RHO_L:.10f}")
        else:
            lines.append(f"{t},{masses[0]},{masses[1]}")
    (folder / "ox_table.csv").write_text("\n".join(lines) + "\n")
    block = MOTOR.replace('schedule = "mass_flow"\nliquid_mass = 12.0\ngas_mass = 0.2\nfile = "ox_flow.csv"',
                          f'schedule = "{schedule}"\nfile = "ox_table.csv"')
    tank = load_motor_for(_rocket_file(folder, block).motor).tanks[0]
    flow = load_motor_for(_rocket_file(folder).motor).tanks[0]
    for t in (0.0, 1.3, 4.0, 5.5, 8.0):
        liquid, gas = tank.masses(t)
        # (ox_flow.csv's step to 0 at 5.5 s is a 1 us ramp: 1e-6 kg more drained)
        assert liquid == pytest.approx(flow.masses(t)[0], abs=1e-5)
        if schedule == "ullage":          # the gas fills the ullage at its density
            assert gas == pytest.approx(RHO_G * (volume - liquid / RHO_L), rel=1e-6)
        else:
            assert gas == pytest.approx(M_GAS)
            assert tank.mass_properties(liquid, gas)[1] == pytest.approx(
                flow.mass_properties(*flow.masses(t))[1], abs=1e-6)
