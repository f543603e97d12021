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
        import rocketpy  # noqa: F401
    except ImportError:
        return None, None
    from rocketpy_calisto import build, fly
    P = spec.sample(samples, setup.nominal_parameters(), np.random.default_rng(spec.seed))
    col = {name: P[params.index(name)] for name in params.NAMES}
    impulse, burn = float(setup.motor.total_impulse), float(setup.motor.burn_time)
    apogees = []
    t0 = time.perf_counter()
    for i in range(samples):
        env, rocket = build(wind_east=col["wind_east"][i], wind_north=col["wind_north"][i],
                            thrust_scale=col["thrust_scale"][i], burn_time_scale=col["burn_time_scale"][i],
                            dry_mass_offset=col["dry_mass_offset"][i], dry_inertia_scale=col["dry_inertia_scale"][i],
                            drag_scale=col["drag_scale"][i], dry_cg_offset=col["dry_cg_offset"][i],
                            impulse=impulse, burn_time=burn)
        flight = fly(env, rocket, math.degrees(col["inclination"][i]), math.degrees(col["heading"][i]))
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
