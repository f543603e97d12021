"""Flight core against closed-form solutions (no tables, no files)."""
import dataclasses

import casadi as ca
import numpy as np
import pytest

from dynamics_standins import AxialOnlyAero, ConstantMotor, UniformAir, vertical_setup
from ironbark_opt import params
from ironbark_opt.dynamics.integrator import rk4_step
from ironbark_opt.dynamics.model import apogee_functions
from ironbark_opt.dynamics.rhs import build
from ironbark_opt.dynamics.setup import DryMass
from ironbark_opt.flight import flight_model, simulate

G = 9.80665


def test_vacuum_vertical_flight_matches_rocket_equation():
    """Tsiolkovsky with gravity: v = -ve ln(1 - mdot t / m0) - g t; then v^2 / 2g."""
    motor = ConstantMotor(thrust=2000.0, burn_time=3.0, propellant_mass=3.0, dry_mass=1.0)
    flight = simulate(vertical_setup(motor, UniformAir(density=0.0), AxialOnlyAero()))
    m0, mdot, tb = 14.0, 1.0, 3.0
    ve = 2000.0 / mdot
    vb = -ve * np.log(1 - mdot * tb / m0) - G * tb
    hb = ve * ((m0 - mdot * tb) / mdot * np.log(1 - mdot * tb / m0) + tb) - G * tb ** 2 / 2
    apogee, t_apogee = hb + vb ** 2 / (2 * G), tb + vb / G
    s = flight.summary_values
    print(f"apogee {s['apogee_agl_m']:.4f} vs {apogee:.4f} m; t {s['apogee_time_s']:.5f} vs {t_apogee:.5f} s")
    assert s["apogee_agl_m"] == pytest.approx(apogee, abs=0.01)          # tolerance 1 cm
    assert s["apogee_time_s"] == pytest.approx(t_apogee, abs=1e-4)
    assert s["max_speed_mps"] == pytest.approx(vb, abs=1e-3)
    assert s["launch_mass_kg"] == pytest.approx(m0)


def test_quadratic_drag_coast_matches_closed_form():
    """Upward coast with constant k = rho S CA / 2m: h = ln(1 + k v^2/g) / 2k,
    t = atan(v sqrt(k/g)) / sqrt(g k) from the burnout state."""
    motor = ConstantMotor(thrust=3000.0, burn_time=1.0, propellant_mass=1.0, dry_mass=1.0)
    aero = AxialOnlyAero(ca0=0.6)
    setup = vertical_setup(motor, UniformAir(density=1.1), aero)
    model = flight_model(setup)
    run = model.run(setup.nominal_parameters())
    x_b = run["x_burnout"]
    v_b, h_b, m = x_b[3], x_b[2], 11.0
    k = 1.1 * aero.reference_area * 0.6 / (2 * m)
    h = h_b + np.log(1 + k * v_b ** 2 / G) / (2 * k)
    t = run["t_burnout"] + np.arctan(v_b * np.sqrt(k / G)) / np.sqrt(G * k)
    x_a = run["x_apogee"]
    print(f"coast apogee {x_a[2]:.4f} vs {h:.4f} m; t {run['t_apogee']:.5f} vs {t:.5f} s")
    assert x_a[2] == pytest.approx(h, abs=0.02)                          # tolerance 2 cm
    assert run["t_apogee"] == pytest.approx(t, abs=1e-4)


def test_torque_free_tumbling_conserves_momentum_and_energy():
    """Asymmetric body, no air, no gravity: H_L = T_LB I w and w.I.w/2 constant."""
    motor = ConstantMotor(thrust=100.0, burn_time=0.5, propellant_mass=0.1, dry_mass=0.5)
    inertia = np.array([[0.5, 0.02, 0.0], [0.02, 3.0, 0.05], [0.0, 0.05, 4.0]])
    setup = vertical_setup(motor, UniformAir(density=0.0), AxialOnlyAero(), g=0.0, inertia=inertia)
    setup = dataclasses.replace(setup, dry=DryMass(10.0, 0.8, inertia))
    f = build(setup, "coast")
    step = rk4_step(f)
    p = setup.nominal_parameters()
    x = np.zeros(13)
    x[6] = 1.0
    x[10:13] = [3.0, 0.4, -0.7]
    m, x_cg, i_tot = _mass_after_burnout(setup)

    def invariants(x):
        q = ca.DM(x[6:10])
        from ironbark_opt.dynamics.frames import rotation_matrix
        r = np.array(ca.DM(rotation_matrix(q)))
        w = x[10:13]
        return r @ (i_tot @ w), 0.5 * w @ i_tot @ w

    h0, e0 = invariants(x)
    t, dt = 1.0, 0.002
    for _ in range(5000):
        x = np.array(step(x, t, dt, p)).ravel()
        t += dt
    h1, e1 = invariants(x)
    print(f"|dH|/|H| = {np.linalg.norm(h1 - h0) / np.linalg.norm(h0):.2e}, dE/E = {abs(e1 - e0) / e0:.2e}")
    assert np.linalg.norm(h1 - h0) / np.linalg.norm(h0) < 1e-6
    assert abs(e1 - e0) / e0 < 1e-6


def _mass_after_burnout(setup):
    from ironbark_opt.dynamics.rhs import mass_properties
    P = params.unpack(ca.DM(setup.nominal_parameters()))
    m, x_cg, i_tot = mass_properties(setup, 10.0, P)
    return float(m), float(x_cg), np.array(ca.DM(i_tot))


@pytest.fixture(scope="module")
def inclined_setup():
    motor = ConstantMotor(thrust=2000.0, burn_time=3.0, propellant_mass=3.0, dry_mass=1.0)
    setup = vertical_setup(motor, UniformAir(density=1.0), AxialOnlyAero(cn_alpha=2.0, x_cp=1.2))
    return dataclasses.replace(setup, nominal={**setup.nominal, "inclination": np.deg2rad(80)})


@pytest.mark.parametrize("name", ["ballast_mass", "thrust_scale", "drag_scale", "inclination", "rail_length"])
def test_ad_gradient_of_apogee_matches_central_differences(inclined_setup, name):
    model = flight_model(inclined_setup)
    p0 = inclined_setup.nominal_parameters()
    apogee = apogee_functions(model, p0)["apogee"]
    p = ca.MX.sym("p", params.SIZE)
    grad = ca.Function("g", [p], [ca.jacobian(apogee(p)[0], p)])
    g = np.array(grad(p0)).ravel()
    i = params.index(name)
    h = 1e-3 * max(1.0, abs(p0[i]))
    pp, pm = p0.copy(), p0.copy()
    pp[i] += h
    pm[i] -= h
    fd = (float(apogee(pp)[0]) - float(apogee(pm)[0])) / (2 * h)
    print(f"d apogee / d {name}: AD {g[i]:.6f}, FD {fd:.6f}")
    # Tolerance: relative 1e-4, or the finite difference's own round-off
    # (apogee is computed to ~1e-6 m through ~550 RK4 steps, divided by 2h).
    assert g[i] == pytest.approx(fd, rel=1e-4, abs=1e-6 / h)


def test_symbolic_apogee_equals_numeric_simulation(inclined_setup):
    model = flight_model(inclined_setup)
    p0 = inclined_setup.nominal_parameters()
    z, t_a, v_rail, v_max = apogee_functions(model, p0)["apogee"](p0)
    flight = simulate(inclined_setup)
    print(f"symbolic {float(z):.4f} m vs numeric {flight.apogee_agl:.4f} m")
    assert float(z) == pytest.approx(flight.apogee_agl, abs=0.05)
    assert float(t_a) == pytest.approx(flight.apogee_time, abs=1e-3)
    assert float(v_rail) == pytest.approx(flight.summary_values["rail_exit_speed_mps"], rel=1e-9)
    assert float(v_max) == pytest.approx(flight.summary_values["max_speed_mps"], rel=1e-9)
