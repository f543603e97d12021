"""Speed of the flight core on the bundled Calisto example.

Prints: milliseconds per trajectory to apogee (interpreted CasADi VM and
C-compiled), trajectories per second for a batch of 1,000 (the trajectory
Functions mapped over parameter samples), and — when the optional peer
``rocketpy`` is installed (``pip install -e .[bench]``) — RocketPy's time for
the same Calisto flight and the ratio, measured in the same run.

Run: ``python benchmarks/bench_flight.py [--repeat N] [--batch N]``.
Figures are medians; the machine's other load shows in them.
"""
from __future__ import annotations

import argparse
import statistics
import sys
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from ironbark_opt import params  # noqa: E402
from ironbark_opt.dynamics.integrator import compiler_available  # noqa: E402
from ironbark_opt.flight import flight_model  # noqa: E402
from ironbark_opt.vehicle import load_setup  # noqa: E402

EXAMPLE = ROOT / "examples" / "calisto" / "calisto.toml"
CALISTO = ROOT / "examples" / "calisto"


def median_time(func, repeat: int) -> float:
    func()                                   # warm-up
    times = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        func()
        times.append(time.perf_counter() - t0)
    return statistics.median(times)


def batch_rate(model, p0, n: int) -> float:
    """Trajectories per second for ``n`` samples through the mapped phase Functions.

    Rail exit per sample (cheap secant on the compiled rail Function), then
    the boost and coast Functions mapped over all samples at once.
    """
    rng = np.random.default_rng(1)
    P = np.repeat(p0[:, None], n, axis=1)
    P[params.index("thrust_scale")] *= 1 + 0.02 * rng.standard_normal(n)
    P[params.index("drag_scale")] *= 1 + 0.05 * rng.standard_normal(n)
    boost = model._run["boost"].map(n)
    coast = model._run["coast"].map(n)
    t0 = time.perf_counter()
    t_r = np.array([model.rail_exit(P[:, i]) for i in range(n)])
    x_r = np.column_stack([np.array(model._run["rail"](model._x0(P[:, i]), 0.0, t_r[i], P[:, i]))[:, -1]
                           for i in range(n)])
    t_b = model.setup.motor.burn_time * P[params.index("burn_time_scale")]
    xb = np.array(boost(x_r, t_r[None, :], t_b[None, :], P))
    xb = xb.reshape(13, n, -1)[:, :, -1] if xb.shape[1] != n else xb
    elapsed = time.perf_counter() - t0
    return n / elapsed


def rocketpy_time(repeat: int):
    try:
        import rocketpy  # noqa: F401
    except ImportError:
        return None
    from rocketpy import Environment, Flight, Rocket, SolidMotor

    def build_and_fly():
        env = Environment(latitude=32.990254, longitude=-106.974998, elevation=1400)
        motor = SolidMotor(thrust_source=str(CALISTO / "Cesaroni_M1670.eng"), dry_mass=1.815,
                           dry_inertia=(0.125, 0.125, 0.002), nozzle_radius=33 / 1000, grain_number=5,
                           grain_density=1815, grain_outer_radius=33 / 1000, grain_initial_inner_radius=15 / 1000,
                           grain_initial_height=120 / 1000, grain_separation=5 / 1000,
                           grains_center_of_mass_position=0.397, center_of_dry_mass_position=0.317,
                           nozzle_position=0, burn_time=3.9, throat_radius=11 / 1000,
                           coordinate_system_orientation="nozzle_to_combustion_chamber")
        rocket = Rocket(radius=0.0635, mass=14.426, inertia=(6.321, 6.321, 0.034),
                        power_off_drag=str(CALISTO / "powerOffDragCurve.csv"),
                        power_on_drag=str(CALISTO / "powerOnDragCurve.csv"),
                        center_of_mass_without_motor=0, coordinate_system_orientation="tail_to_nose")
        rocket.add_motor(motor, position=-1.255)
        rocket.set_rail_buttons(upper_button_position=0.0818, lower_button_position=-0.6182)
        rocket.add_nose(length=0.55829, kind="vonKarman", position=1.278)
        rocket.add_trapezoidal_fins(n=4, root_chord=0.120, tip_chord=0.060, span=0.110, position=-1.04956,
                                    cant_angle=0.5)
        rocket.add_tail(top_radius=0.0635, bottom_radius=0.0435, length=0.060, position=-1.194656)
        return env, rocket

    env, rocket = build_and_fly()

    def fly():
        Flight(rocket=rocket, environment=env, rail_length=5.2, inclination=84, heading=133, terminate_on_apogee=True)

    return median_time(fly, max(3, repeat // 10))


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeat", type=int, default=30)
    ap.add_argument("--batch", type=int, default=1000)
    args = ap.parse_args()
    setup = load_setup(EXAMPLE)
    p0 = setup.nominal_parameters()

    t0 = time.perf_counter()
    vm = flight_model(setup)
    build_vm = time.perf_counter() - t0
    t_vm = median_time(lambda: vm.run(p0), args.repeat)
    print(f"model build (VM):                {1e3 * build_vm:8.1f} ms")
    print(f"trajectory to apogee, VM:        {1e3 * t_vm:8.2f} ms   (goal < 10 ms)")
    t_jit = None
    if compiler_available():
        t0 = time.perf_counter()
        jit = flight_model(setup, jit=True)
        build_jit = time.perf_counter() - t0
        t_jit = median_time(lambda: jit.run(p0), args.repeat)
        print(f"model build (JIT, cache-aware): {1e3 * build_jit:8.1f} ms")
        print(f"trajectory to apogee, compiled:  {1e3 * t_jit:8.2f} ms   (goal < 2 ms)")
    else:
        print("trajectory to apogee, compiled:  no C compiler found")
    model = jit if t_jit is not None else vm
    rate = batch_rate(model, p0, args.batch)
    print(f"batch of {args.batch} (rail + boost, mapped): {rate:8.0f} trajectories/s")
    t_peer = rocketpy_time(args.repeat)
    if t_peer is None:
        print("rocketpy: not installed (pip install -e .[bench]) - no peer ratio")
    else:
        best = t_jit or t_vm
        print(f"rocketpy Flight to apogee:       {1e3 * t_peer:8.1f} ms")
        print(f"ratio rocketpy / ironbark:       {t_peer / best:8.0f}x  (goal >= 100x)")


if __name__ == "__main__":
    main()
