"""Where is the best ballast under a dispersion spec?  A brute-force answer.

For one example (default Calisto, 3000 m AGL, its ``dispersions.toml``):

1. the nominal ballast solve;
2. ``N`` fresh samples (default 5000; seed: the spec's + 1, the robust
   check's) flown at the nominal ballast: the apogee distribution (mean,
   median, spread, skewness, P(|miss| <= 50 m)) and which dispersed
   parameters carry its variance (least-squares fit of the apogee on the
   sampled parameters; each parameter's share is ``b_j^2 var(xi_j) / var(a)``);
3. the same samples flown at three ballast masses ``m0 - D, m0, m0 + D``:
   each sample's apogee is interpolated quadratically in the mass
   (the apogee is smooth in the mass; the interpolation error is checked by a
   fourth, direct run at the best mass), and P(in band) is swept over the
   mass on the common samples, with the standard error of its difference to
   the nominal (paired: the same samples);
4. the SAA the robust solver runs, repeated on random subsets of N of these
   samples (N = 40, 160, 640): the mass it picks, judged on all samples; and
   on a surrogate of the flights (linear fit + resampled residuals), the SAA
   from 40 independent draws against a 40-point Latin hypercube;
5. optionally (``--positions``) the same at other ballast positions, each
   with its own nominal mass.

Prints figures; writes ``--plot FILE`` (P(in band) against the mass, with
its 95 % band).  Run:
``python benchmarks/robust_sweep.py [calisto|kestrel] [--samples N] [--positions x1,x2] [--plot f.png]``.
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
from ironbark_opt.flight import flight_model  # noqa: E402
from ironbark_opt.optimise.ballast import solve_ballast  # noqa: E402
from ironbark_opt.vehicle import load_setup  # noqa: E402

TARGETS = {"calisto": "3000m", "kestrel": "10000ft"}
I_M, I_X = params.index("ballast_mass"), params.index("ballast_x")


def in_band(apogee, target, band):
    return (np.abs(np.asarray(apogee) - target) <= band).astype(float)


def linear_fit(apogee, P, spec):
    """Least-squares apogee = c + sum_j b_j xi_j on the dispersed parameters:
    (names, b, c, residuals, xi (samples x parameters))."""
    names = list(spec.parameters)
    X = np.vstack([P[params.index(n)] for n in names]).T
    coef, *_ = np.linalg.lstsq(np.hstack([X, np.ones((X.shape[0], 1))]), apogee, rcond=None)
    return names, coef[:-1], coef[-1], apogee - X @ coef[:-1] - coef[-1], X


def saa_design_study(a_0, slope, P, p_nom, spec, masses, m0, probs, target, band, label, repeats=300):
    """The SAA pick from N independent draws vs an N-point Latin hypercube, on a surrogate of the
    flights (the linear fit on the dispersed parameters plus a residual and a slope resampled from
    the flown samples), judged on the flown samples' P(in band) curve."""
    from ironbark_opt.optimise.robust_objective import silverman_width, smoothed_objective

    names, b, c, resid, _ = linear_fit(a_0, P, spec)
    rows = [params.index(n) for n in names]
    rng = np.random.default_rng(1)
    dms = masses - m0
    n = 40
    for design, factor in (("independent", 1), ("latin hypercube", 1), ("latin hypercube", 2),
                           ("latin hypercube", 4)):
        gains = []
        for _ in range(repeats):
            Q = (spec.sample if design == "independent" else spec.sample_lhs)(n, p_nom, rng)
            k = rng.integers(0, a_0.size, n)
            a = c + b @ Q[rows] + resid[k]
            s = slope[k]
            h = factor * silverman_width(a)
            f = [smoothed_objective(a + s * dm, target, "in_band", band, h)[0] for dm in dms]
            gains.append(probs[int(np.argmin(f))] - probs[80])
        g = np.array(gains)
        print(f"  [{label}] surrogate SAA, {n} samples by {design}, kernel {factor} x Silverman ({repeats} draws):"
              f" gain in P(in band) mean {g.mean():+.4f}, 5-95 % {np.percentile(g, 5):+.4f} .. "
              f"{np.percentile(g, 95):+.4f}")


def describe(apogee, target, band, P, spec):
    a = np.asarray(apogee)
    d = a - target
    skew = float(np.mean((a - a.mean()) ** 3) / a.std() ** 3)
    q5, q25, q50, q75, q95 = np.percentile(a, [5, 25, 50, 75, 95])
    p = in_band(a, target, band).mean()
    print(f"  apogee: mean {a.mean():.1f} m, median {q50:.1f} m (target {target:.1f}), std {a.std(ddof=1):.1f} m, "
          f"skewness {skew:+.3f}, 5/25/75/95 % {q5:.0f}/{q25:.0f}/{q75:.0f}/{q95:.0f} m")
    print(f"  P(|miss| <= {band:.0f} m) = {p:.4f} +/- {math.sqrt(p * (1 - p) / a.size):.4f}; "
          f"E|miss| {np.abs(d).mean():.1f} m")
    names, b, _, resid, X = linear_fit(a, P, spec)
    r2 = 1 - np.var(resid) / np.var(a)
    share = b ** 2 * X.var(0) / np.var(a)
    print(f"  linear fit on the dispersed parameters: R^2 {r2:.3f}; share of the apogee variance:")
    for j in np.argsort(-share):
        print(f"    {names[j]:22s} {100 * share[j]:6.1f} %   ({b[j] * X[:, j].std():+7.1f} m per std)")


def sweep(model, P, m0, x0, delta, target, band, label, cache=None):
    """Per-sample quadratic in the mass from three runs; returns (masses, P(in band), stderr of the
    paired difference to m0, apogees at m0, coefficients).  ``cache``: a folder keeping the runs."""
    import hashlib

    runs = []
    for m in (m0 - delta, m0, m0 + delta):
        Q = P.copy()
        Q[I_M], Q[I_X] = m, x0
        path = None
        if cache:
            path = Path(cache) / (hashlib.sha256(Q.tobytes()).hexdigest()[:20] + ".npy")
            if path.exists():
                runs.append(np.load(path))
                continue
        t = time.perf_counter()
        runs.append(model.run_batch(Q)["apogee_agl"])
        print(f"  [{label}] {P.shape[1]} flights at {m:.3f} kg, x {x0:.3f} m: {time.perf_counter() - t:.0f} s")
        if path is not None:
            path.parent.mkdir(parents=True, exist_ok=True)
            np.save(path, runs[-1])
    a_lo, a_0, a_hi = runs
    slope = (a_hi - a_lo) / (2 * delta)
    curv = (a_hi - 2 * a_0 + a_lo) / delta ** 2
    print(f"  [{label}] d apogee / d mass: mean {slope.mean():.1f} m/kg (sample 5-95 % "
          f"{np.percentile(slope, 5):.1f} .. {np.percentile(slope, 95):.1f})")
    masses = m0 + np.linspace(-delta, delta, 161)
    base = in_band(a_0, target, band)
    probs, errs = [], []
    for m in masses:
        dm = m - m0
        inside = in_band(a_0 + slope * dm + 0.5 * curv * dm * dm, target, band)
        probs.append(inside.mean())
        errs.append((inside - base).std(ddof=1) / math.sqrt(base.size))
    return masses, np.array(probs), np.array(errs), a_0, (slope, curv)


def saa_noise(a_0, slope, curv, masses, m0, probs, target, band, label, repeats=300):
    """What the robust solver's SAA (N samples, Silverman kernel, in-band objective) picks when its
    N samples are drawn from these ones, judged by P(in band) on all of them."""
    from ironbark_opt.optimise.robust_objective import silverman_width, smoothed_objective

    rng = np.random.default_rng(0)
    dms = masses - m0
    for n in (40, 160, 640):
        gains = []
        for _ in range(repeats):
            idx = rng.choice(a_0.size, n, replace=False)
            a, s, c = a_0[idx], slope[idx], curv[idx]
            h = silverman_width(a)
            f = [smoothed_objective(a + s * dm + 0.5 * c * dm * dm, target, "in_band", band, h)[0] for dm in dms]
            gains.append(probs[int(np.argmin(f))] - probs[80])
        g = np.array(gains)
        print(f"  [{label}] SAA with {n:4d} samples ({repeats} draws): gain in P(in band) on all samples "
              f"mean {g.mean():+.4f}, 5-95 % {np.percentile(g, 5):+.4f} .. {np.percentile(g, 95):+.4f}")


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("rocket", nargs="?", default="calisto", choices=sorted(TARGETS))
    ap.add_argument("--samples", type=int, default=5000)
    ap.add_argument("--band", type=float, default=50.0)
    ap.add_argument("--delta", type=float, default=None, help="mass step [kg] (default: 40 m of apogee)")
    ap.add_argument("--positions", default="", help="other ballast positions [m], comma-separated")
    ap.add_argument("--plot")
    ap.add_argument("--cache", help="folder keeping the flown apogees (a rerun reads them)")
    ap.add_argument("--skip-direct", action="store_true", help="no direct run at the best mass")
    args = ap.parse_args()
    setup = load_setup(ROOT / "examples" / args.rocket / f"{args.rocket}.toml")
    spec = load_spec(ROOT / "examples" / args.rocket / "dispersions.toml")
    model = flight_model(setup)
    seed = (spec.seed or 0) + 1
    print(f"{args.rocket}: target {TARGETS[args.rocket]}, {args.samples} samples, seed {seed}, band "
          f"+/- {args.band:.0f} m")
    positions = [None] + [float(x) for x in args.positions.split(",") if x]
    inside = {}                        # each position's best mass: in-band flags (the samples are common)
    curves = []
    for x in positions:
        nom = solve_ballast(setup, TARGETS[args.rocket], ballast_x=x)
        v = nom.values
        m0, x0, target = v["ballast_kg"], v["ballast_x_m"], v["target_agl_m"]
        label = f"x {x0:.3f} m"
        print(f"nominal ballast {m0:.4f} kg at {x0:.3f} m (apogee {v['apogee_agl_m']:.2f} m AGL, "
              f"static margin at rail exit {v['static_margin_rail_exit_cal']:.2f} cal)")
        p_nom = np.array([nom.parameters[n] for n in params.NAMES])
        P = spec.sample(args.samples, p_nom, np.random.default_rng(seed))
        if args.delta is None:
            Q = P[:, :1].copy()
            a1 = model.run_batch(np.hstack([Q, Q]) + np.outer(np.eye(params.SIZE)[I_M], [0.0, 0.1]))["apogee_agl"]
            delta = min(max(40.0 / abs((a1[1] - a1[0]) / 0.1), 0.01), m0 if m0 > 0.02 else 1.0)
        else:
            delta = args.delta
        if x is None:
            in_band_nominal = None
        masses, probs, errs, a_0, (slope, curv) = sweep(model, P, m0, x0, delta, target, args.band, label,
                                                        args.cache)
        describe(a_0, target, args.band, P, spec)
        if in_band_nominal is None:
            in_band_nominal = in_band(a_0, target, args.band)
        k = int(np.argmax(probs))
        print(f"  [{label}] sweep {masses[0]:.3f} .. {masses[-1]:.3f} kg: P(in band) {probs.min():.4f} .. "
              f"{probs.max():.4f}; best {masses[k]:.4f} kg (apogee shift {np.mean(slope) * (masses[k] - m0):+.1f} m):"
              f" P {probs[k]:.4f}, gain over nominal {probs[k] - probs[80]:+.4f} +/- {errs[k]:.4f} (paired "
              f"stderr; optimistic: the best of 161 points on the same samples)")
        if not args.skip_direct:
            Q = P.copy()
            Q[I_M], Q[I_X] = masses[k], x0
            direct = model.run_batch(Q)["apogee_agl"]
            dm = masses[k] - m0
            interp = a_0 + slope * dm + 0.5 * curv * dm * dm
            pd = in_band(direct, target, args.band).mean()
            print(f"  [{label}] direct run at the best mass: P {pd:.4f} (interpolation max error "
                  f"{np.max(np.abs(direct - interp)):.3f} m)")
        curves.append((label, masses, probs, errs, m0, probs[80]))
        dm = masses[k] - m0
        inside[label] = in_band(a_0 + slope * dm + 0.5 * curv * dm * dm, target, args.band), masses[k]
        saa_noise(a_0, slope, curv, masses, m0, probs, target, args.band, label)
        saa_design_study(a_0, slope, P, p_nom, spec, masses, m0, probs, target, args.band, label)
        # Out-of-sample look at the gain: pick the best mass on one half, measure it on the other.
        half = args.samples // 2
        for tr, te in ((slice(0, half), slice(half, None)), (slice(half, None), slice(0, half))):
            pin = []
            for m in masses:
                dm = m - m0
                pin.append(in_band((a_0 + slope * dm + 0.5 * curv * dm * dm)[tr], target, args.band).mean())
            kk = int(np.argmax(pin))
            dm = masses[kk] - m0
            test = in_band((a_0 + slope * dm + 0.5 * curv * dm * dm)[te], target, args.band)
            base = in_band(a_0[te], target, args.band)
            g = test - base
            print(f"  [{label}] best mass on one half {masses[kk]:.4f} kg; on the other half its gain "
                  f"{g.mean():+.4f} +/- {g.std(ddof=1) / math.sqrt(g.size):.4f}")
    if len(inside) > 1:
        labels = list(inside)
        base_label = labels[0]
        for label in labels:
            flags, m = inside[label]
            g = flags - in_band_nominal
            print(f"best mass {m:.4f} kg at {label} vs the nominal ballast at {base_label}: P {flags.mean():.4f} vs "
                  f"{in_band_nominal.mean():.4f}, gain {g.mean():+.4f} +/- {g.std(ddof=1) / math.sqrt(g.size):.4f} "
                  f"(paired, same samples)")
    if args.plot:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        fig, ax = plt.subplots(figsize=(7, 4.5))
        for label, masses, probs, errs, m0, p0 in curves:
            line, = ax.plot(masses, probs, label=f"P(in band), ballast at {label}")
            ax.fill_between(masses, p0 + (probs - p0) - 1.96 * errs, p0 + (probs - p0) + 1.96 * errs,
                            color=line.get_color(), alpha=0.2, label="95 % band of the gain over nominal")
            ax.plot([m0], [p0], "o", color=line.get_color(), label=f"nominal ballast {m0:.3f} kg")
        ax.set_xlabel("ballast mass [kg]")
        ax.set_ylabel(f"P(|apogee - target| <= {args.band:.0f} m) [-]")
        ax.set_title(f"{setup.name}: P(in band) against ballast, {args.samples} samples "
                     f"(dispersions.toml, file atmosphere)", fontsize=9)
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8)
        fig.tight_layout()
        fig.savefig(args.plot, dpi=120)
        print(f"wrote {args.plot}")


if __name__ == "__main__":
    main()
