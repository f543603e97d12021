"""Dispersion spec parsing and sampling (ironbark_opt.analysis.distributions)."""
import math

import numpy as np
import pytest

from ironbark_opt import params
from ironbark_opt.analysis.distributions import Empirical, Normal, Uniform, load_spec, spec_from_dict
from ironbark_opt.errors import InputError

SPEC = """\
seed = 7

[parameters.thrust_scale]
distribution = "normal"
std = 0.02

[parameters.inclination_deg]
distribution = "normal"
mean = 84.0
std = 1.0

[parameters.wind_east]
distribution = "uniform"
low = -3.0
high = 5.0

[parameters.drag_scale]
distribution = "file"
file = "drag.csv"
column = "drag_scale"
"""


def write(tmp_path, text, csv="drag_scale\n0.9\n1.0\n1.1\n"):
    (tmp_path / "drag.csv").write_text(csv)
    path = tmp_path / "dispersions.toml"
    path.write_text(text)
    return path


def test_parses_all_kinds_with_degrees_converted(tmp_path):
    spec = load_spec(write(tmp_path, SPEC))
    assert spec.seed == 7
    assert list(spec.parameters) == ["thrust_scale", "drag_scale", "wind_east", "inclination"]  # registry order
    assert spec.parameters["thrust_scale"] == Normal(std=0.02, mean=None)
    inc = spec.parameters["inclination"]
    assert inc.mean == pytest.approx(math.radians(84.0), rel=1e-15)
    assert inc.std == pytest.approx(math.radians(1.0), rel=1e-15)
    assert spec.parameters["wind_east"] == Uniform(-3.0, 5.0)
    assert isinstance(spec.parameters["drag_scale"], Empirical)
    np.testing.assert_array_equal(spec.parameters["drag_scale"].values, [0.9, 1.0, 1.1])


def test_samples_have_the_requested_moments_and_are_reproducible(tmp_path):
    """Sample moments within 5 standard errors of the analytic ones (n = 20000)."""
    spec = load_spec(write(tmp_path, SPEC))
    nominal = params.nominal_values()
    n = 20000
    P = spec.sample(n, nominal, np.random.default_rng(spec.seed))
    assert P.shape == (params.SIZE, n)
    np.testing.assert_array_equal(P, spec.sample(n, nominal, np.random.default_rng(spec.seed)))
    ts = P[params.index("thrust_scale")]
    assert abs(ts.mean() - 1.0) < 5 * 0.02 / math.sqrt(n)
    assert ts.std() == pytest.approx(0.02, rel=5 / math.sqrt(2 * n))
    we = P[params.index("wind_east")]
    assert we.min() >= -3.0 and we.max() <= 5.0
    assert abs(we.mean() - 1.0) < 5 * (8 / math.sqrt(12)) / math.sqrt(n)
    assert set(np.unique(P[params.index("drag_scale")])) == {0.9, 1.0, 1.1}
    # undispersed rows keep the nominal value exactly
    np.testing.assert_array_equal(P[params.index("rail_length")], nominal[params.index("rail_length")])
    # means(): every dispersed entry at its expected value
    m = spec.means(nominal)
    assert m[params.index("inclination")] == pytest.approx(math.radians(84))
    assert m[params.index("wind_east")] == pytest.approx(1.0)
    assert m[params.index("drag_scale")] == pytest.approx(1.0)
    assert m[params.index("thrust_scale")] == nominal[params.index("thrust_scale")]


def test_to_dict_round_trips_through_the_parser(tmp_path):
    spec = load_spec(write(tmp_path, SPEC))
    d = spec.to_dict()
    assert d["inclination_deg"] == {"distribution": "normal", "std": pytest.approx(1.0), "mean": pytest.approx(84.0)}
    assert d["drag_scale"]["distribution"] == "file" and d["drag_scale"]["count"] == 3
    del d["drag_scale"]
    again = spec_from_dict({"parameters": d})
    for name in ("thrust_scale", "wind_east"):
        assert again.parameters[name] == spec.parameters[name]
    assert again.parameters["inclination"].mean == pytest.approx(spec.parameters["inclination"].mean, rel=1e-15)


def test_zero_spread_gives_the_mean_exactly():
    spec = spec_from_dict({"parameters": {"heading_deg": {"distribution": "normal", "mean": 133.0, "std": 0.0}}})
    P = spec.sample(5, params.nominal_values(), np.random.default_rng(1))
    assert np.all(P[params.index("heading")] == math.radians(133.0))


@pytest.mark.parametrize("text, line, field, words", [
    ('[parameters.thrust_scal]\ndistribution = "normal"\nstd = 0.1\n', 1, "parameters.thrust_scal",
     "unknown parameter"),
    ('seed = 1\n\n[parameters.thrust_scale]\ndistribution = "gauss"\nstd = 0.1\n', 4,
     "parameters.thrust_scale.distribution", "must be one of"),
    ('[parameters.drag_scale]\ndistribution = "normal"\n', 1, "parameters.drag_scale.std", "missing 'std'"),
    ('[parameters.drag_scale]\ndistribution = "normal"\nstd = -0.1\n', 3, "parameters.drag_scale.std", ">= 0"),
    ('[parameters.drag_scale]\ndistribution = "normal"\nstd = "big"\n', 3, "parameters.drag_scale.std",
     "finite number"),
    ('[parameters.wind_east]\ndistribution = "uniform"\nlow = 2\nhigh = 1\n', 4, "parameters.wind_east.high",
     "must be >= low"),
    ('[parameters.wind_east]\ndistribution = "uniform"\nlow = 2\nhigh = 3\nstd = 1\n', 5,
     "parameters.wind_east.std", "unknown key"),
    ('[parameters.rail_length_deg]\ndistribution = "normal"\nstd = 1\n', 1, "parameters.rail_length_deg",
     "not an angle"),
    ('[parameters.drag_scale]\ndistribution = "file"\nfile = "drag.csv"\ncolumn = "cd"\n', 4,
     "parameters.drag_scale.column", "not in drag.csv"),
    ('[parameters.drag_scale]\ndistribution = "file"\nfile = "nope.csv"\ncolumn = "cd"\n', 3,
     "parameters.drag_scale.file", "not found"),
    ('seed = -4\n', 1, "seed", "non-negative integer"),
    ('samples = 4\n', 1, "samples", "unknown key"),
])
def test_errors_name_file_line_and_field(tmp_path, text, line, field, words):
    path = write(tmp_path, text)
    with pytest.raises(InputError) as info:
        load_spec(path)
    err = info.value
    assert err.source == str(path)
    assert err.line == line
    assert err.field == field
    assert words in str(err)


def test_both_radian_and_degree_forms_rejected(tmp_path):
    text = ('[parameters.heading]\ndistribution = "normal"\nstd = 0.01\n\n'
            '[parameters.heading_deg]\ndistribution = "normal"\nstd = 1\n')
    with pytest.raises(InputError, match="given twice") as info:
        load_spec(write(tmp_path, text))
    assert info.value.line == 5


def test_bad_toml_and_bad_sample_file_rows(tmp_path):
    with pytest.raises(InputError, match="not valid TOML") as info:
        load_spec(write(tmp_path, 'seed = 1\n[parameters.drag_scale\n'))
    assert info.value.line == 2
    path = write(tmp_path, SPEC, csv="drag_scale\n1.0\nabc\n")
    with pytest.raises(InputError, match="non-number") as info:
        load_spec(path)
    assert info.value.source == str(tmp_path / "drag.csv") and info.value.line == 3
    with pytest.raises(InputError, match="not found"):
        load_spec(tmp_path / "missing.toml")


def test_latin_hypercube_one_value_per_stratum_and_a_steadier_mean(tmp_path):
    """sample_lhs: each dispersed parameter's n values fall one in each of the n equal-probability
    strata of its own CDF (analytic: normal CDF, uniform, the file's resampling CDF); the mean of a
    linear function over 40 columns varies far less than over 40 independent draws (for an
    additive function LHS removes the marginal variance: Stein 1987), measured on 400 repeats."""
    from scipy.special import ndtr

    spec = load_spec(write(tmp_path, SPEC, csv="drag_scale\n1.1\n0.9\n1.0\n0.95\n"))
    nominal = params.nominal_values()
    n = 40
    P = spec.sample_lhs(n, nominal, np.random.default_rng(3))
    assert P.shape == (params.SIZE, n)
    strata = {"thrust_scale": ndtr((P[params.index("thrust_scale")] - 1.0) / 0.02),
              "inclination": ndtr((P[params.index("inclination")] - math.radians(84)) / math.radians(1)),
              "wind_east": (P[params.index("wind_east")] + 3.0) / 8.0}
    for name, cdf in strata.items():
        assert sorted(np.floor(cdf * n).astype(int)) == list(range(n)), name
    # the file's 4 values, each 10 times (resampling CDF: weight 1/4 each, sorted)
    values, counts = np.unique(P[params.index("drag_scale")], return_counts=True)
    assert list(values) == [0.9, 0.95, 1.0, 1.1] and list(counts) == [10] * 4
    np.testing.assert_array_equal(P[params.index("rail_length")], nominal[params.index("rail_length")])
    rng = np.random.default_rng(5)
    w = {"thrust_scale": 1000.0, "wind_east": 10.0, "inclination": 500.0}

    def f(Q):
        return sum(c * Q[params.index(k)] for k, c in w.items()).mean()

    iid = np.std([f(spec.sample(n, nominal, rng)) for _ in range(400)])
    lhs = np.std([f(spec.sample_lhs(n, nominal, rng)) for _ in range(400)])
    print(f"std of the 40-column mean: independent {iid:.4f}, latin hypercube {lhs:.4f}")
    # independent: sqrt(sum c^2 var / n) = 5.0; stratified: far smaller (measured 0.31)
    assert iid == pytest.approx(math.sqrt((1000 * 0.02) ** 2 + (10 * 8 / math.sqrt(12)) ** 2
                                          + (500 * math.radians(1)) ** 2) / math.sqrt(n), rel=0.15)
    assert lhs < 0.1 * iid
