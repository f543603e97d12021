"""Monte Carlo: exactness at the means, reproducibility, convergence.

Sources of truth: ``simulate`` itself (all spreads zero -> every sample is
the nominal flight, bit for bit); the seed (same seed -> same samples,
whatever the chunking); and the first-order (delta-method) propagation of
the spreads through the exact AD sensitivities, which predicts the mean
(the nominal apogee, to first order) and the standard deviation
``sqrt(sum (dz/dp_i * sigma_i)^2)`` for small, independent Gaussian spreads
(e.g. Taylor, *An Introduction to Error Analysis*, 2nd ed., eq. 3.47).
"""
import math
from pathlib import Path

import numpy as np
import pytest

from ironbark_opt.analysis.distributions import load_spec, spec_from_dict
from ironbark_opt.analysis.montecarlo import ELLIPSE_CONTENT, Dispersion, error_ellipse, montecarlo
from ironbark_opt.analysis.plots import ellipse_points
from ironbark_opt.analysis.sensitivity import sensitivities
from ironbark_opt.errors import InputError
from ironbark_opt.flight import flight_model, simulate
from ironbark_opt.vehicle import load_setup

ROOT = Path(__file__).resolve().parents[2]
EXAMPLE = ROOT / "examples/calisto/calisto.toml"
EXAMPLE_SPEC = ROOT / "examples/calisto/dispersions.toml"

# Small independent Gaussian spreads: first-order propagation is accurate.
SMALL = {"parameters": {"thrust_scale": {"distribution": "normal", "std": 0.01},
                        "drag_scale": {"distribution": "normal", "std": 0.03},
                        "inclination_deg": {"distribution": "normal", "mean": 84.0, "std": 0.5}},
         "seed": 11}


@pytest.fixture(scope="module")
def setup():
    return load_setup(EXAMPLE)


@pytest.fixture(scope="module")
def model(setup):
    return flight_model(setup)


def test_all_parameters_at_their_means_reproduce_simulate_exactly(setup, model):
    spec = spec_from_dict({"parameters": {
        "thrust_scale": {"distribution": "normal", "mean": 1.01, "std": 0.0},
        "inclination_deg": {"distribution": "uniform", "low": 85.0, "high": 85.0},
        "wind_east": {"distribution": "normal", "mean": 3.0, "std": 0.0}}})
    disp = montecarlo(setup, spec, 3, descent=True, progress=False, model=model)
    means = spec.means(setup.nominal_parameters())
    flight = simulate(setup, p=means, descent=True, model=model).summary_values
    df = disp.to_dataframe()
    for key in ("apogee_agl_m", "apogee_time_s", "rail_exit_speed_mps", "apogee_east_m", "apogee_north_m"):
        print(f"{key}: Monte Carlo {df[key].iloc[0]!r}, simulate {flight[key]!r} (tolerance: exact)")
        assert np.all(df[key].to_numpy() == flight[key])
    # Landing: the batch's apogee Newton runs a fixed 8 iterations, the single
    # run's stops at |dh| < 1e-12 s, so the apogee state can differ in the last
    # bits; the landing then agrees to round-off (relative 1e-12).
    for key in ("landing_time_s", "landing_east_m", "landing_north_m"):
        err = np.max(np.abs(df[key].to_numpy() / flight[key] - 1))
        print(f"{key}: Monte Carlo {df[key].iloc[0]!r}, simulate {flight[key]!r}, rel. error {err:.1e} "
              "(tolerance 1e-12)")
        assert err <= 1e-12
    # the samples are one flight (bit for bit); their std is 0 up to the rounding of the
    # mean (x + x + x is not always exactly 3 x, so mean != x by an ulp: ~1e-13 m here)
    apogees = disp.column("apogee_agl_m")
    assert np.all(apogees == apogees[0])
    assert disp.stats["apogee_agl_m"]["std"] <= 1e-15 * apogees[0]


def test_same_seed_same_result_whatever_the_chunking(setup, model):
    spec = load_spec(EXAMPLE_SPEC)
    a = montecarlo(setup, spec, 6, progress=False, model=model)
    b = montecarlo(setup, spec, 6, chunk=4, progress=False, model=model)
    c = montecarlo(setup, spec, 6, seed=spec.seed + 1, progress=False, model=model)
    assert a.seed == spec.seed == b.seed
    assert a.to_dataframe().equals(b.to_dataframe())
    assert not np.any(a.to_dataframe()["apogee_agl_m"].to_numpy() == c.to_dataframe()["apogee_agl_m"].to_numpy())
    # a seed drawn from fresh entropy is reported and reproduces the run
    fresh = montecarlo(setup, spec_from_dict({"parameters": SMALL["parameters"]}), 2, progress=False, model=model)
    again = montecarlo(setup, spec_from_dict({"parameters": SMALL["parameters"]}), 2, seed=fresh.seed,
                       progress=False, model=model)
    assert fresh.to_dataframe().equals(again.to_dataframe())


@pytest.fixture(scope="module")
def linear(setup, model):
    """Delta-method mean and standard deviation of apogee for SMALL [m]."""
    spec = spec_from_dict(SMALL)
    sens = sensitivities(setup, names=list(spec.parameters), model=model)
    sigma = {"thrust_scale": 0.01, "drag_scale": 0.03, "inclination": math.radians(0.5)}
    std = math.sqrt(sum((sens.derivative("apogee_agl_m", n) * s) ** 2 for n, s in sigma.items()))
    return spec, sens.values["apogee_agl_m"], std


def _convergence(setup, model, linear, sizes, std_tol):
    spec, mean_ref, std_ref = linear
    for n in sizes:
        disp = montecarlo(setup, spec, n, progress=False, model=model)
        s = disp.stats["apogee_agl_m"]
        # Monte Carlo error of the mean is std/sqrt(n): allow 4 of them, plus
        # 1 m for the second-order (curvature) bias the delta method ignores.
        tol = 4 * std_ref / math.sqrt(n) + 1.0
        print(f"n = {n:5d}: mean {s['mean']:.2f} m vs {mean_ref:.2f} m, error {s['mean'] - mean_ref:+.2f} m "
              f"(tolerance {tol:.2f} m); std {s['std']:.2f} m vs first-order {std_ref:.2f} m "
              f"({100 * (s['std'] / std_ref - 1):+.1f} %, tolerance {100 * std_tol:.0f} %)")
        assert abs(s["mean"] - mean_ref) <= tol
        if n >= 64:                        # too few samples below that to test a spread
            assert s["std"] == pytest.approx(std_ref, rel=std_tol)


def test_mean_apogee_converges(setup, model, linear):
    # std of a sample std is ~ std/sqrt(2n): 40 % is > 4 of those at n = 64
    _convergence(setup, model, linear, (8, 64), std_tol=0.4)


@pytest.mark.slow
def test_mean_apogee_converges_large(setup, model, linear):
    _convergence(setup, model, linear, (256, 1024), std_tol=0.15)


def test_statistics_band_and_ellipse(setup, model):
    spec = spec_from_dict(SMALL)
    disp = montecarlo(setup, spec, 20, target="3290 m", band=40.0, progress=False, model=model)
    df = disp.to_dataframe()
    apo = df["apogee_agl_m"].to_numpy()
    s = disp.stats["apogee_agl_m"]
    assert s["mean"] == pytest.approx(apo.mean()) and s["std"] == pytest.approx(apo.std(ddof=1))
    assert s["p50"] == pytest.approx(np.median(apo))
    assert disp.extra["probability_in_band"] == np.mean(np.abs(apo - 3290.0) <= 40.0)
    assert disp.extra["probability_above_target"] == np.mean(apo >= 3290.0)
    d = disp.to_dict()
    assert d["samples"] == 20 and d["seed"] == 11 and d["band_m"] == 40.0
    assert "apogee_agl_m" in d and "thrust_scale" in df and "inclination_deg" in df
    assert df["inclination_deg"].mean() == pytest.approx(84.0, abs=0.5)
    assert "P(|apogee - target| <= 40.0 m)" in disp.summary()
    assert "\n" not in repr(disp)
    with pytest.raises(AttributeError):
        disp.samples = 3
    with pytest.raises(InputError, match="did not fly to landing"):
        disp.positions("landing")


def test_error_ellipse_of_a_known_gaussian():
    """Semi-axes = sqrt of the covariance eigenvalues; 5 % sampling tolerance
    (n = 40000); content of the k-sigma ellipse = 1 - exp(-k^2/2)."""
    rng = np.random.default_rng(3)
    a, b, az = 30.0, 10.0, math.radians(40.0)      # major axis 40 deg east of north
    u, v = a * rng.standard_normal(40000), b * rng.standard_normal(40000)
    east = u * math.sin(az) + v * math.cos(az) + 100.0
    north = u * math.cos(az) - v * math.sin(az) - 50.0
    e = error_ellipse(east, north)
    print(f"ellipse: {e}")
    assert e["semi_major_m"] == pytest.approx(a, rel=0.05)
    assert e["semi_minor_m"] == pytest.approx(b, rel=0.05)
    assert e["azimuth_deg"] == pytest.approx(40.0, abs=1.0)
    assert e["center_east_m"] == pytest.approx(100.0, abs=1.0)
    assert ELLIPSE_CONTENT[2] == pytest.approx(0.8647, abs=1e-4)
    # the drawn 2-sigma ellipse is the Mahalanobis-distance-2 contour of the scatter
    icov = np.linalg.inv(np.cov(np.vstack([east, north])))
    pe, pn = ellipse_points(e, 2.0)
    d = np.vstack([pe - east.mean(), pn - north.mean()])
    np.testing.assert_allclose(np.sqrt(np.einsum("in,ij,jn->n", d, icov, d)), 2.0, rtol=1e-9)
    d = np.vstack([east - east.mean(), north - north.mean()])
    inside = np.mean(np.einsum("in,ij,jn->n", d, icov, d) <= 4.0)
    print(f"share inside the 2-sigma ellipse: {inside:.4f} (Gaussian {ELLIPSE_CONTENT[2]:.4f}, tolerance 0.01)")
    assert inside == pytest.approx(ELLIPSE_CONTENT[2], abs=0.01)


def test_bad_arguments(setup, model):
    spec = spec_from_dict(SMALL)
    with pytest.raises(InputError, match="executor"):
        montecarlo(setup, spec, 2, executor="dask://", model=model)            # no host:port
    with pytest.raises(InputError, match="executor"):
        montecarlo(setup, spec, 2, executor="spark://cluster", model=model)    # unknown scheme
    with pytest.raises(InputError, match="samples"):
        montecarlo(setup, spec, 0, model=model)
    with pytest.raises(InputError, match="band needs a target"):
        montecarlo(setup, spec, 2, band=10.0, model=model)
    with pytest.raises(InputError, match="DispersionSpec"):
        montecarlo(setup, {"parameters": {}}, 2, model=model)
    assert isinstance(montecarlo(setup, spec, 1, executor="local", progress=False, model=model), Dispersion)


def test_diverged_samples_are_refused(setup, model, monkeypatch):
    """A sample whose integration diverged (non-finite or below-pad apogee, as the
    canted-fin roll split once produced) stops the study with a SolverError naming it,
    never into the statistics."""
    import ironbark_opt.executors as ex
    from ironbark_opt.errors import SolverError
    real = ex.fly_samples

    def broken(*args, **kwargs):
        out = dict(real(*args, **kwargs))
        apo = np.array(out["apogee_agl"], float)
        apo[1] = -69197.3
        out["apogee_agl"] = apo
        return out
    monkeypatch.setattr(ex, "fly_samples", broken)
    with pytest.raises(SolverError, match=r"1 of 3 Monte Carlo samples reached no apogee or diverged \(sample 1"):
        montecarlo(setup, spec_from_dict(SMALL), 3, progress=False, model=model)
    # an unstable rocket flown on purpose (--allow-unstable): the sample is left out, said and counted
    with pytest.warns(UserWarning, match="1 of 3 samples reached no apogee"):
        d = montecarlo(setup, spec_from_dict(SMALL), 3, progress=False, model=model, allow_failed=True)
    assert d.extra["samples_failed"] == 1
    good = [a for i, a in enumerate(d._table["apogee_agl_m"]) if i != 1]
    assert d.stats["apogee_agl_m"]["mean"] == pytest.approx(np.mean(good), rel=1e-12)
