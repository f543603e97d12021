"""Wall time of a 1,000-sample Monte Carlo on the bundled Calisto example.

Prints: the wall time of ``montecarlo(setup, dispersions.toml, 1000)`` (C-compiled
trajectory Functions when a compiler exists, else the VM; ``--vm`` measures the
VM too), and — when the optional peer ``rocketpy`` is installed — the same
dispersions flown with RocketPy's ``Flight`` for a reduced number of samples
(default 20), **extrapolated** linearly to 1,000 samples, and the ratio.

RocketPy samples rebuild Environment, SolidMotor and Rocket per sample (as
RocketPy's own Monte Carlo does) and fly to apogee.  The peer disperses the
parameters it can express directly: dry mass, dry CG, dry inertia, thrust
and burn time (``reshape_thrust_curve``), drag (scaled drag curves), wind,
launch angle and heading; normal-force scale and temperature offset are not
dispersed on the peer side (they do not change its cost).

Run: ``python benchmarks/bench_montecarlo.py [--samples N] [--peer-samples N] [--vm] [--descent]``.
Goal: 1,000 samples under 10 s on a 2-core machine.
"""
from __future__ import annotations

import argparse
import math
import sys
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from ironbark_opt import params  # noqa: E402
from ironbark_opt.analysis.distributions import load_spec  # noqa: E402
from ironbark_opt.analysis.montecarlo import montecarlo  # noqa: E402
from ironbark_opt.dynamics.integrator import compiler_available  # noqa: E402
from ironbark_opt.flight import flight_model  # noqa: E402
from ironbark_opt.vehicle import load_setup  # noqa: E402

CALISTO = ROOT / "examples" / "calisto"
EXAMPLE = CALISTO / "calisto.toml"
SPEC = CALISTO / "dispersions.toml"


def ours(setup, spec, samples: int, jit: bool, descent: bool) -> tuple[float, float, object]:
    """(model build [s], Monte Carlo wall time [s], Dispersion)."""
    t0 = time.perf_counter()
    model = flight_model(setup, jit=jit)
    montecarlo(setup, spec, 2, progress=False, model=model, descent=descent)   # warm-up: mapped Functions
    build = time.perf_counter() - t0
    t0 = time.perf_counter()
    disp = montecarlo(setup, spec, samples, progress=False, model=model, descent=descent)
    return build, time.perf_counter() - t0, disp


def peer_time(setup, spec, samples: int):
    """Seconds per RocketPy sample (rebuild + Flight to apogee), or None."""
    try:
        from rocketpy import Environment, Flight, Function, Rocket, SolidMotor
    except ImportError:
        return None, None
    P = spec.sample(samples, setup.nominal_parameters(), np.random.default_rng(spec.seed))
    col = {name: P[params.index(name)] for name in params.NAMES}
    impulse, burn = float(setup.motor.total_impulse), float(setup.motor.burn_time)
    drag_off = np.loadtxt(CALISTO / "powerOffDragCurve.csv", delimiter=",")
    drag_on = np.loadtxt(CALISTO / "powerOnDragCurve.csv", delimiter=",")
    apogees = []
    t0 = time.perf_counter()
    for i in range(samples):
        env = Environment(latitude=32.990254, longitude=-106.974998, elevation=1400)
        env.set_atmospheric_model(type="custom_atmosphere", wind_u=float(col["wind_east"][i]),
                                  wind_v=float(col["wind_north"][i]))
        motor = SolidMotor(thrust_source=str(CALISTO / "Cesaroni_M1670.eng"), dry_mass=1.815,
                           dry_inertia=(0.125, 0.125, 0.002), nozzle_radius=0.033, grain_number=5,
                           grain_density=1815, grain_outer_radius=0.033, grain_initial_inner_radius=0.015,
                           grain_initial_height=0.120, grain_separation=0.005,
                           grains_center_of_mass_position=0.397, center_of_dry_mass_position=0.317,
                           nozzle_position=0, burn_time=burn, throat_radius=0.011,
                           reshape_thrust_curve=(burn * col["burn_time_scale"][i], impulse * col["thrust_scale"][i]),
                           coordinate_system_orientation="nozzle_to_combustion_chamber")
        k_i, k_d = col["dry_inertia_scale"][i], col["drag_scale"][i]
        rocket = Rocket(radius=0.0635, mass=14.426 + col["dry_mass_offset"][i],
                        inertia=(6.321 * k_i, 6.321 * k_i, 0.034 * k_i),
                        power_off_drag=Function(np.column_stack([drag_off[:, 0], k_d * drag_off[:, 1]])),
                        power_on_drag=Function(np.column_stack([drag_on[:, 0], k_d * drag_on[:, 1]])),
                        center_of_mass_without_motor=-col["dry_cg_offset"][i],   # tail_to_nose axis
                        coordinate_system_orientation="tail_to_nose")
        rocket.add_motor(motor, position=-1.255)
        rocket.set_rail_buttons(upper_button_position=0.0818, lower_button_position=-0.6182)
        rocket.add_nose(length=0.55829, kind="vonKarman", position=1.278)
        rocket.add_trapezoidal_fins(n=4, root_chord=0.120, tip_chord=0.060, span=0.110, position=-1.04956,
                                    cant_angle=0.5)
        rocket.add_tail(top_radius=0.0635, bottom_radius=0.0435, length=0.060, position=-1.194656)
        flight = Flight(rocket=rocket, environment=env, rail_length=5.2,
                        inclination=math.degrees(col["inclination"][i]), heading=math.degrees(col["heading"][i]),
                        terminate_on_apogee=True)
        apogees.append(flight.apogee - 1400.0)
    return (time.perf_counter() - t0) / samples, float(np.mean(apogees))


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--samples", type=int, default=1000)
    ap.add_argument("--peer-samples", type=int, default=20)
    ap.add_argument("--vm", action="store_true", help="also time the interpreted CasADi VM")
    ap.add_argument("--descent", action="store_true", help="fly every sample to landing")
    args = ap.parse_args()
    setup = load_setup(EXAMPLE)
    spec = load_spec(SPEC)
    print(f"Monte Carlo of {setup.name}: {len(spec.parameters)} dispersed parameters, seed {spec.seed}, "
          f"{'to landing' if args.descent else 'to apogee'}")
    modes = ([True] if compiler_available() else []) + ([False] if args.vm or not compiler_available() else [])
    best = None
    for jit in modes:
        build, wall, disp = ours(setup, spec, args.samples, jit, args.descent)
        label = "compiled" if jit else "VM"
        s = disp.stats["apogee_agl_m"]
        print(f"ironbark ({label}): model build + warm-up {build:6.2f} s; {args.samples} samples in {wall:6.2f} s "
              f"({1e3 * wall / args.samples:.2f} ms/sample; goal: 1000 in < 10 s); "
              f"apogee {s['mean']:.1f} +/- {s['std']:.1f} m")
        best = wall / args.samples if best is None else min(best, wall / args.samples)
    per_sample, mean_apogee = peer_time(setup, spec, args.peer_samples)
    if per_sample is None:
        print("rocketpy: not installed (pip install -e .[bench]) - no peer ratio")
        return
    print(f"rocketpy Flight: {args.peer_samples} samples measured, {1e3 * per_sample:.0f} ms/sample "
          f"(mean apogee {mean_apogee:.1f} m); EXTRAPOLATED to {args.samples} samples: "
          f"{per_sample * args.samples:.0f} s")
    print(f"ratio rocketpy / ironbark per sample: {per_sample / best:.0f}x (peer time extrapolated)")


if __name__ == "__main__":
    main()
