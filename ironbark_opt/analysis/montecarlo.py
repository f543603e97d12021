"""Monte Carlo dispersion: ``montecarlo(setup, spec, samples) -> Dispersion``.

The parameter samples are drawn once from a :class:`DispersionSpec`
(seeded, so a run is reproducible), then flown in chunks through
:meth:`FlightModel.run_batch` — the very trajectory Functions of
``simulate``, mapped over the samples in threads.  The result holds every
sample and the statistics a team needs on launch day: apogee and drift
spread, landing ellipse, and the probability of an apogee within a band
around the target.

Numeric-only.
"""
from __future__ import annotations

import contextlib
import math
import time
from dataclasses import dataclass, field
from pathlib import Path
from typing import Mapping

import numpy as np

from ironbark_opt import params
from ironbark_opt.analysis.distributions import DispersionSpec, load_spec
from ironbark_opt.errors import InputError, SolverError

PERCENTILES = (5, 50, 95)
_UNIT_SUFFIX = {"kg": "_kg", "m": "_m", "m/s": "_mps", "K": "_K", "-": "", "rad": "_deg"}
#: Share of a 2-D Gaussian inside its k-sigma ellipse: 1 - exp(-k^2 / 2), the
#: chi-square CDF with 2 degrees of freedom, since the squared Mahalanobis
#: distance of a bivariate normal is chi-square(2) (Johnson & Wichern,
#: *Applied Multivariate Statistical Analysis*, 6th ed., Result 4.7).
ELLIPSE_CONTENT = {k: 1.0 - math.exp(-k * k / 2.0) for k in (1, 2, 3)}


def column_name(name: str) -> str:
    """Output column of a registry parameter: unit-suffixed, angles in degrees."""
    return name + _UNIT_SUFFIX.get(params.INFO[name].unit, "")


def column_values(name: str, values: np.ndarray) -> np.ndarray:
    """Values of parameter ``name`` [SI] in the unit of :func:`column_name`."""
    return np.degrees(values) if params.INFO[name].unit == "rad" else values


def statistics(values) -> dict:
    """mean, std (sample, ddof=1), min, p05/p50/p95, max of ``values`` [their unit]; numeric-only."""
    v = np.asarray(values, dtype=float)
    out = {"mean": float(v.mean()), "std": float(v.std(ddof=1)) if v.size > 1 else 0.0, "min": float(v.min())}
    for q, val in zip(PERCENTILES, np.percentile(v, PERCENTILES)):
        out[f"p{q:02d}"] = float(val)
    out["max"] = float(v.max())
    return out


def error_ellipse(east, north) -> dict:
    """1-sigma ellipse of scattered points (sample covariance) [m]; numeric-only.

    Returns ``center_east_m``, ``center_north_m``, ``semi_major_m``,
    ``semi_minor_m`` (square roots of the covariance eigenvalues) and
    ``azimuth_deg`` of the major axis, clockwise from north.  The k-sigma
    ellipse has k times the semi-axes and holds :data:`ELLIPSE_CONTENT`\\[k]
    of a Gaussian scatter.
    """
    xy = np.vstack([np.asarray(east, dtype=float), np.asarray(north, dtype=float)])
    cov = np.cov(xy) if xy.shape[1] > 1 else np.zeros((2, 2))
    w, V = np.linalg.eigh(cov)
    w = np.clip(w, 0.0, None)
    major = V[:, 1]
    return {"center_east_m": float(xy[0].mean()), "center_north_m": float(xy[1].mean()),
            "semi_major_m": float(math.sqrt(w[1])), "semi_minor_m": float(math.sqrt(w[0])),
            "azimuth_deg": float(math.degrees(math.atan2(major[0], major[1])) % 180.0)}


def ellipse_points(ellipse: dict, k: float, n: int = 181) -> tuple[np.ndarray, np.ndarray]:
    """(east, north) [m] on the ``k``-sigma ellipse of :func:`error_ellipse`."""
    th = np.linspace(0.0, 2 * math.pi, n)
    az = math.radians(ellipse["azimuth_deg"])
    u, v = k * ellipse["semi_major_m"] * np.cos(th), k * ellipse["semi_minor_m"] * np.sin(th)
    # major axis at azimuth az (clockwise from north), minor axis 90 deg further
    east = ellipse["center_east_m"] + u * math.sin(az) + v * math.cos(az)
    north = ellipse["center_north_m"] + u * math.cos(az) - v * math.sin(az)
    return east, north


@dataclass(frozen=True)
class Dispersion:
    """Result of :func:`montecarlo` (immutable).

    Attributes
    ----------
    name : str
        Rocket name.
    samples : int
    seed : int
        The seed actually used (pass it back to reproduce the run).
    descent : bool
        Whether samples were flown to landing.
    dispersed : tuple of str
        One description per dispersed parameter (for the summary).
    distributions : mapping
        The spec's distributions as in the spec file (``NAME_deg`` for angles).
    stats : mapping
        Output column -> :func:`statistics` dict.
    extra : mapping
        Target/band probabilities, ellipses, wall time (unit-suffixed keys).
    """

    name: str
    samples: int
    seed: int
    descent: bool
    dispersed: tuple
    distributions: Mapping[str, Mapping]
    stats: Mapping[str, Mapping[str, float]]
    extra: Mapping[str, object]
    #: per-sample columns, name -> 1-D array (pandas is imported only by `to_dataframe`)
    _table: Mapping[str, np.ndarray] = field(repr=False)

    def __repr__(self) -> str:
        a = self.stats["apogee_agl_m"]
        return (f"Dispersion({self.name!r}: {self.samples} samples, apogee {a['mean']:.1f} +/- {a['std']:.1f} m "
                f"AGL, seed {self.seed})")

    def column(self, name: str) -> np.ndarray:
        """One per-sample column (a copy), e.g. ``apogee_agl_m``."""
        return np.array(self._table[name])

    def to_dataframe(self):
        """One row per sample (a new ``pandas.DataFrame``): dispersed parameters
        (unit-suffixed, angles in degrees) and the outputs."""
        import pandas as pd
        return pd.DataFrame({k: np.array(v) for k, v in self._table.items()})

    def positions(self, which: str = "auto") -> tuple[np.ndarray, np.ndarray, str]:
        """(east [m], north [m], label) of landing points (``"landing"``),
        apogee points (``"apogee"``) or landing when flown (``"auto"``)."""
        if which == "auto":
            which = "landing" if self.descent else "apogee"
        if which not in ("landing", "apogee"):
            raise InputError(f"positions: expected 'landing' or 'apogee', got {which!r}", field="which")
        if which == "landing" and not self.descent:
            raise InputError("this Monte Carlo did not fly to landing (descent=False)", field="descent")
        t = self._table
        return np.array(t[f"{which}_east_m"]), np.array(t[f"{which}_north_m"]), which

    def to_dict(self) -> dict:
        """Statistics with unit-suffixed keys (no per-sample data)."""
        out = {"rocket": self.name, "samples": self.samples, "seed": self.seed, "descent": self.descent,
               "dispersions": {k: dict(v) for k, v in self.distributions.items()}}
        out.update({k: dict(v) for k, v in self.stats.items()})
        out.update({k: (dict(v) if isinstance(v, Mapping) else v) for k, v in self.extra.items()})
        return out

    def summary(self) -> str:
        """Human-readable summary (a string; nothing is printed)."""
        lines = [f"Monte Carlo of {self.name}: {self.samples} samples, seed {self.seed} "
                 f"({self.extra['wall_time_s']:.1f} s)",
                 f"  {'':22s} {'mean':>10s} {'std':>9s} {'p05':>10s} {'p50':>10s} {'p95':>10s}"]
        labels = {"apogee_agl_m": "apogee AGL [m]", "apogee_time_s": "apogee time [s]",
                  "rail_exit_speed_mps": "rail exit speed [m/s]", "apogee_drift_m": "apogee drift [m]",
                  "landing_distance_m": "landing distance [m]", "landing_time_s": "landing time [s]"}
        for key, label in labels.items():
            if key in self.stats:
                s = self.stats[key]
                lines.append(f"  {label:22s} {s['mean']:10.2f} {s['std']:9.2f} {s['p05']:10.2f} "
                             f"{s['p50']:10.2f} {s['p95']:10.2f}")
        e = self.extra
        if "target_agl_m" in e:
            lines.append(f"  target {e['target_agl_m']:.1f} m AGL: mean error {e['apogee_error_mean_m']:+.1f} m, "
                         f"P(apogee >= target) = {e['probability_above_target']:.3f}")
        if "band_m" in e:
            lines.append(f"  P(|apogee - target| <= {e['band_m']:.1f} m) = {e['probability_in_band']:.3f} "
                         f"+/- {e['probability_in_band_stderr']:.3f}")
        key = "landing_ellipse" if self.descent else "apogee_ellipse"
        el = e[key]
        lines.append(f"  {key.replace('_', ' ')} (1 sigma): {el['semi_major_m']:.1f} x {el['semi_minor_m']:.1f} m, "
                     f"major axis at {el['azimuth_deg']:.0f} deg from north, centre "
                     f"{el['center_east_m']:.1f} m east, {el['center_north_m']:.1f} m north")
        lines.append("  dispersed:")
        lines += [f"    {d}" for d in self.dispersed]
        return "\n".join(lines)


def _resolve_seed(seed, spec: DispersionSpec) -> int:
    if seed is None:
        seed = spec.seed
    if seed is None:
        return int(np.random.SeedSequence().entropy)
    if isinstance(seed, bool) or not isinstance(seed, (int, np.integer)) or seed < 0:
        raise InputError(f"seed must be a non-negative integer, got {seed!r}", field="seed")
    return int(seed)


def _check(samples, chunk, executor, target, band):
    for name, value in (("samples", samples), ("chunk", chunk)):
        if isinstance(value, bool) or not isinstance(value, (int, np.integer)) or value < 1:
            raise InputError(f"{name} must be a positive integer, got {value!r}", field=name)
    if band is not None:
        if target is None:
            raise InputError("a band needs a target apogee", field="band")
        if not (isinstance(band, (int, float)) and math.isfinite(band) and band > 0):
            raise InputError(f"band must be a positive number [m], got {band!r}", field="band")


@contextlib.contextmanager
def _progress_bar(total: int, show: bool):
    """A tqdm bar on stderr (``bar.update(n)``), or a no-op without importing tqdm (~30 ms)."""
    if not show:
        yield _NoBar()
        return
    from tqdm.autonotebook import tqdm   # tqdm.auto adds asyncio support (0.25 s import), unused here
    with tqdm(total=total, desc="Monte Carlo", unit="flight", leave=False) as bar:
        yield bar


class _NoBar:
    def update(self, n: int = 1) -> None:
        pass


def montecarlo(setup, spec, samples: int, *, seed: int | None = None, descent: bool = False, target=None,
               band: float | None = None, chunk: int = 250, executor=None, progress: bool = True,
               parameters: Mapping[str, float] | None = None, jit="auto", model=None,
               output=None, allow_failed: bool = False) -> Dispersion:
    """Fly ``samples`` dispersed copies of ``setup`` and collect statistics (numeric-only).

    Parameters
    ----------
    setup : FlightSetup
    spec : DispersionSpec or path-like
        Dispersions (a ``dispersions.toml`` path is read with :func:`load_spec`).
    samples : int
        Number of flights.
    seed : int, optional
        Overrides the spec's seed; with neither, fresh entropy is used and
        reported in :attr:`Dispersion.seed`.
    descent : bool
        Fly each sample to landing (parachutes from the setup).
    target : str or float, optional
        Apogee target (``"30000ft"``, ``"3000 m ASL"`` or a number [m AGL]).
    band : float, optional [m]
        Half-width of the band around ``target`` for the success probability.
    chunk : int
        Samples per :meth:`FlightModel.run_batch` call (results do not
        depend on it).
    executor : None, "local", "local:N", "dask://HOST:PORT", distributed.Client or Executor
        Where the chunks run (:func:`ironbark_opt.executors.get_executor`);
        results are bit-identical whatever the executor.
    progress : bool
        Show a progress bar (tqdm, on stderr).
    parameters : mapping, optional
        Overrides of the nominal parameters (SI) before dispersing, e.g.
        the ballast from a ballast solve.
    jit : bool
        Use C-compiled trajectory Functions (cached on disk).
    model : FlightModel, optional
        Reuse an already built model.
    output : path-like, optional
        Directory where each chunk's results stream to a Parquet file
        (needs pyarrow); re-running the same study into it resumes,
        recomputing only missing chunks.

    Returns
    -------
    Dispersion
    """
    _check(samples, chunk, executor, target, band)
    if not isinstance(spec, DispersionSpec):
        if not isinstance(spec, (str, Path)):
            raise InputError(f"spec must be a DispersionSpec or a path to a TOML file, got {type(spec).__name__}",
                             field="spec")
        spec = load_spec(spec)
    seed = _resolve_seed(seed, spec)
    target_agl = None
    if target is not None:                 # parsed first: a typo fails before any flight
        from ironbark_opt.optimise.target import parse_target
        target_agl = parse_target(target).agl(setup.site_elevation)
    t_start = time.perf_counter()
    p_nom = setup.nominal_parameters(**dict(parameters or {}))
    P = spec.sample(int(samples), p_nom, np.random.default_rng(seed))
    from ironbark_opt.executors import fly_samples
    with _progress_bar(int(samples), progress) as bar:
        out = fly_samples(setup, P, descent=descent, chunk=int(chunk), executor=executor, output=output, jit=jit,
                          model=model, on_chunk=bar.update)
    x_a = out["x_apogee"]
    apo = np.asarray(out["apogee_agl"], float)
    diverged = np.flatnonzero(~np.isfinite(apo) | (apo < 0.0))
    if diverged.size and (not allow_failed or diverged.size == apo.size):
        # as simulate refuses one (flight._check_converged)
        raise SolverError(f"{setup.name}: {diverged.size} of {int(samples)} Monte Carlo samples reached no "
                          f"apogee or diverged (sample {int(diverged[0])}: apogee {apo[diverged[0]]:.6g} m AGL); "
                          "no statistics were written. An unstable rocket (flown with --allow-unstable) "
                          "may tumble; otherwise please report it with the rocket and spec files")
    ok = np.ones(apo.size, bool)
    ok[diverged] = False
    if diverged.size:
        import warnings
        warnings.warn(f"{setup.name}: {diverged.size} of {int(samples)} samples reached no apogee (an unstable "
                      f"rocket tumbling; first: sample {int(diverged[0])}); the statistics are of the other "
                      f"{int(ok.sum())}", UserWarning, stacklevel=2)
    data = {"sample": np.arange(int(samples))}
    for name in spec.parameters:
        data[column_name(name)] = column_values(name, P[params.index(name)])
    data.update(apogee_agl_m=out["apogee_agl"], apogee_time_s=out["t_apogee"],
                rail_exit_speed_mps=out["rail_exit_speed"],
                apogee_east_m=x_a[0], apogee_north_m=x_a[1], apogee_drift_m=np.hypot(x_a[0], x_a[1]))
    if descent:
        x_l = out["x_landing"]
        data.update(landing_time_s=out["t_landing"], landing_east_m=x_l[0],
                    landing_north_m=x_l[1], landing_distance_m=np.hypot(x_l[0], x_l[1]))
    table = {k: np.asarray(v) for k, v in data.items()}
    outputs = [c for c in table if c.startswith(("apogee_", "rail_exit_", "landing_"))]
    stats = {c: statistics(table[c][ok]) for c in outputs}
    extra: dict[str, object] = {"apogee_ellipse": error_ellipse(x_a[0][ok], x_a[1][ok]),
                                "samples_failed": int(diverged.size)}
    if descent:
        extra["landing_ellipse"] = error_ellipse(table["landing_east_m"][ok], table["landing_north_m"][ok])
    if target_agl is not None:
        apo = table["apogee_agl_m"][ok]
        extra.update(target_agl_m=float(target_agl), apogee_error_mean_m=float(apo.mean() - target_agl),
                     probability_above_target=float(np.mean(apo >= target_agl)))
        if band is not None:
            prob = float(np.mean(np.abs(apo - target_agl) <= band))
            # binomial standard error of a proportion, sqrt(p (1 - p) / n)
            extra.update(band_m=float(band), probability_in_band=prob,
                         probability_in_band_stderr=math.sqrt(prob * (1 - prob) / apo.size))
    extra["wall_time_s"] = time.perf_counter() - t_start
    return Dispersion(name=setup.name, samples=int(samples), seed=seed, descent=bool(descent),
                      dispersed=tuple(spec.describe()), distributions=spec.to_dict(), stats=stats, extra=extra,
                      _table=table)
