"""Air brakes: Calisto flown with and without the camoes team's brake table
(examples/calisto_airbrakes), checked against an independent estimate; the
deployment solved for a target; a Python controller; AD sensitivities."""
import dataclasses
from pathlib import Path

import casadi as ca
import numpy as np
import pytest
from scipy.integrate import solve_ivp
from scipy.interpolate import RegularGridInterpolator

from ironbark_opt import params
from ironbark_opt.aero.airbrakes import load_controller
from ironbark_opt.atmosphere.gravity import gravity
from ironbark_opt.dynamics.frames import rotation_matrix
from ironbark_opt.errors import InputError
from ironbark_opt.flight import flight_model, simulate
from ironbark_opt.optimise.airbrakes import solve_airbrakes
from ironbark_opt.vehicle import load_setup

ROOT = Path(__file__).resolve().parents[2]
EXAMPLE = ROOT / "examples" / "calisto_airbrakes"
CONTROLLERS = ROOT / "tests" / "data" / "airbrakes" / "open_at_time.py"


@pytest.fixture(scope="module")
def setup():
    return load_setup(EXAMPLE / "calisto_airbrakes.toml")


def _point_mass_apogee(setup, burnout_row, brakes: bool) -> float:
    """Independent estimate: point mass in the vertical plane from the 6-DOF
    burnout state, SciPy DOP853, drag from the raw CSV files (Calisto's
    power-off curve, linear in Mach; the brake table bilinear, its stowed
    row subtracted) and the schedule's deployment formula written out."""
    cd0 = np.loadtxt(ROOT / "examples" / "calisto" / "powerOffDragCurve.csv", delimiter=",")
    tab = np.genfromtxt(EXAMPLE / "drag_airbrakes.csv", delimiter=",", skip_header=1)
    dep_axis, mach_axis = np.unique(tab[:, 0]), np.unique(tab[:, 1])
    cd = np.zeros((dep_axis.size, mach_axis.size))
    for d, mach, c in tab:
        cd[np.searchsorted(dep_axis, d), np.searchsorted(mach_axis, mach)] = c
    brake_cd = RegularGridInterpolator((dep_axis, mach_axis), cd - cd[0:1, :])
    area, mass = np.pi * 0.0635 ** 2, float(burnout_row.mass_kg)
    atm, elev = setup.atmosphere, setup.site_elevation
    sched = setup.airbrakes

    def deployment(t):
        u = np.clip((t - sched.start) * sched.rate / (1.5 * sched.level), 0.0, 1.0)
        return sched.level * u * u * (3 - 2 * u)

    def rhs(t, y):
        _, z, vx, vz = y
        v, h = np.hypot(vx, vz), z + elev
        mach = v / float(atm.speed_of_sound(h))
        c = np.interp(mach, cd0[:, 0], cd0[:, 1])
        if brakes:
            c += brake_cd([[deployment(t), np.clip(mach, mach_axis[0], mach_axis[-1])]])[0]
        drag = 0.5 * float(atm.density(h)) * v * v * area * c
        return [vx, vz, -drag * vx / v / mass, -drag * vz / v / mass - float(gravity(h, setup.latitude))]

    apex = lambda t, y: y[3]                              # noqa: E731
    apex.terminal, apex.direction = True, -1
    r = burnout_row
    v_l = np.array(rotation_matrix(ca.DM([r.q0, r.q1, r.q2, r.q3])) @ ca.DM([r.vx_b_mps, r.vy_b_mps, r.vz_b_mps]))
    v_l = v_l.ravel()
    sol = solve_ivp(rhs, (r.time_s, 300.0), [0.0, r.altitude_agl_m, np.hypot(v_l[0], v_l[1]), v_l[2]],
                    events=apex, method="DOP853", rtol=1e-10, atol=1e-8)
    return float(sol.y_events[0][0][1])


def test_brakes_lower_apogee_by_the_independent_estimate(setup):
    on = simulate(setup)
    off = simulate(setup, parameters={"airbrake_level": 0.0})
    row = off.to_dataframe().query("phase == 'coast'").iloc[0]      # first coast sample, brakes still stowed
    pm_off, pm_on = _point_mass_apogee(setup, row, False), _point_mass_apogee(setup, row, True)
    drop, drop_pm = off.apogee_agl - on.apogee_agl, pm_off - pm_on
    print(f"apogee without brakes {off.apogee_agl:.1f} m, with {on.apogee_agl:.1f} m: drop {drop:.2f} m; "
          f"point-mass estimate {pm_off:.1f} -> {pm_on:.1f} m: drop {drop_pm:.2f} m "
          f"({100 * (drop - drop_pm) / drop_pm:+.2f} %)")
    assert drop > 100.0
    assert drop == pytest.approx(drop_pm, rel=0.02)            # tolerance 2 % of the drop
    df = on.to_dataframe()
    assert df["airbrake_deployment"][df["time_s"] < setup.airbrakes.start].max() == 0.0
    assert on.summary_values["airbrake_max_deployment"] == pytest.approx(1.0)
    assert on.summary_values["airbrake_max_rate_per_s"] <= setup.airbrakes.rate * (1 + 1e-6)


@pytest.mark.parametrize("variable, target", [("airbrake_level", 3100.0), ("airbrake_start_time", 3150.0)])
def test_solved_deployment_hits_the_target(setup, variable, target):
    sol = solve_airbrakes(setup, target, variable=variable)
    p = np.array([sol.parameters[n] for n in params.NAMES])
    again = simulate(setup, p=p).apogee_agl
    print(f"{variable} = {sol.parameters[variable]:.4f} for {target} m: re-simulated {again:.3f} m "
          f"(error {again - target:+.3f} m), {sol.values['solve_time_s']:.2f} s")
    assert sol.feasible
    assert abs(again - target) < 1.0
    if variable == "airbrake_level":
        assert 0.0 < sol.parameters[variable] < 1.0
    else:
        assert setup.airbrakes.start < sol.parameters[variable] < again


def test_unreachable_target_is_reported(setup):
    sol = solve_airbrakes(setup, 3500.0)
    print(sol.status)
    assert not sol.feasible and "reachable apogees" in sol.status
    assert sol.values["apogee_agl_m"] == pytest.approx(sol.values["apogee_without_brakes_agl_m"], abs=1e-6)


def test_sensitivity_to_the_schedule_matches_finite_differences(setup):
    from ironbark_opt.analysis.sensitivity import sensitivities

    # At a partial deployment (the table's deployment axis ends at 1, where the
    # derivative is one-sided).
    sens = sensitivities(setup, names=["airbrake_level", "airbrake_start_time"], parameters={"airbrake_level": 0.8})
    model = flight_model(setup)
    p0 = setup.nominal_parameters(airbrake_level=0.8)
    for j, (name, h) in enumerate((("airbrake_level", 0.01), ("airbrake_start_time", 0.05))):
        up, down = p0.copy(), p0.copy()
        up[params.index(name)] += h
        down[params.index(name)] -= h
        fd = (model.run(up)["x_apogee"][2] - model.run(down)["x_apogee"][2]) / (2 * h)
        ad = sens.jacobian[0, j]
        print(f"d apogee / d {name}: AD {ad:.3f}, central difference {fd:.3f} ({100 * (ad - fd) / fd:+.3f} %)")
        assert ad == pytest.approx(fd, rel=0.01)


def test_controller_flies_like_the_equivalent_schedule(setup):
    # Full deployment commanded from 5.525 s, rate-limited to 2 /s: the linear
    # ramp 5.525..6.025 s has the same mid-point as the schedule's smoothstep
    # (5.4 s + 0.375 s), so the two apogees agree to within a few metres.
    brakes = dataclasses.replace(setup.airbrakes, trigger="controller", sampling_rate=40.0,
                                 controller=load_controller(f"{CONTROLLERS}:open_late"))
    controlled = dataclasses.replace(setup, airbrakes=brakes)
    flight = simulate(controlled)
    scheduled = simulate(setup)
    df = flight.to_dataframe()
    rate = np.diff(df["airbrake_deployment"]) / np.diff(df["time_s"])
    print(f"controller apogee {flight.apogee_agl:.2f} m, schedule {scheduled.apogee_agl:.2f} m "
          f"({flight.apogee_agl - scheduled.apogee_agl:+.2f} m); max opening rate {rate.max():.3f} /s")
    assert abs(flight.apogee_agl - scheduled.apogee_agl) < 3.0
    assert df["airbrake_deployment"][df["time_s"] < 5.525 - 1e-9].max() == 0.0
    assert df["airbrake_deployment"].max() == pytest.approx(1.0)
    # Ballast, sensitivities and Monte Carlo refuse a controller (not differentiable).
    with pytest.raises(InputError, match="Python controller"):
        flight_model(controlled).run_batch(np.repeat(controlled.nominal_parameters()[:, None], 2, axis=1))
    with pytest.raises(InputError, match="controller"):
        solve_airbrakes(controlled, 3100.0)
    broken = dataclasses.replace(setup, airbrakes=dataclasses.replace(
        brakes, controller=load_controller(f"{CONTROLLERS}:broken")))
    with pytest.raises(InputError, match="controller raised KeyError"):
        simulate(broken)


def test_controller_opening_rate_is_per_sample(setup):
    """At 10 Hz the coast is flown in two RK4 sub-steps per sample, so the output holds
    each deployment for two rows: the reported opening rate is the per-sample change x 10 Hz
    (the 2 /s limit), not that change over the 0.05 s row spacing (was 4 /s, and 20 /s on
    camoes's 0 -> 1 step at 10 /s)."""
    brakes = dataclasses.replace(setup.airbrakes, trigger="controller", sampling_rate=10.0,
                                 controller=load_controller(f"{CONTROLLERS}:open_late"))
    flight = simulate(dataclasses.replace(setup, airbrakes=brakes))
    df = flight.to_dataframe()
    coast = df[df["phase"] == "coast"]
    spacing = float(np.median(np.diff(coast["time_s"])))
    steps = np.diff(df["airbrake_deployment"])
    reported = flight.summary_values["airbrake_max_rate_per_s"]
    print(f"row spacing {spacing:.4f} s, largest per-sample change {steps.max():.4f}, reported "
          f"rate {reported:.4f} /s (limit {brakes.rate:g} /s)")
    assert spacing < 0.1 - 1e-9                      # sub-sampled: the case that was wrong
    assert steps.max() == pytest.approx(brakes.rate / 10.0, rel=1e-9)
    assert reported == pytest.approx(brakes.rate, rel=1e-9)


def test_batch_flies_each_schedule_like_a_single_run(setup):
    """Monte Carlo's path (run_batch) on dispersed schedules equals one run per sample."""
    model = flight_model(setup)
    P = np.repeat(setup.nominal_parameters()[:, None], 3, axis=1)
    P[params.index("airbrake_start_time")] = [5.0, 6.5, 9.0]
    P[params.index("airbrake_level")] = [1.0, 0.6, 0.3]
    batch = model.run_batch(P)["apogee_agl"]
    single = [model.run(P[:, i])["x_apogee"][2] for i in range(3)]
    print(f"batch {np.round(batch, 3)}, single {np.round(single, 3)}")
    assert np.allclose(batch, single, atol=1e-6)
    assert batch[0] < batch[1] < batch[2]
