"""AeroTable / GridSpline: exactness, SciPy-CasADi agreement, clamping, files, errors."""
import json
import warnings

import casadi as ca
import numpy as np
import pytest

from ironbark_opt.aero.table import AeroTable, GridSpline
from ironbark_opt.errors import InputError, OutOfRangeWarning

MACH = np.array([0.0, 0.3, 0.6, 0.8, 0.95, 1.05, 1.2, 1.6, 2.0, 3.0])
ALPHA = np.radians([0.0, 2.0, 4.0, 8.0, 12.0, 20.0, 30.0])


def _smooth(m, a):
    return 0.3 + 0.2 * np.sin(2 * m) * np.cos(a) + m * a ** 2 + np.exp(-m) * a


def _table(mach=MACH, alpha=ALPHA, **kw):
    mm, aa = np.meshgrid(mach, alpha, indexing="ij")
    coeffs = {"CA": _smooth(mm, aa), "CN": 12 * aa * (1 + 0.1 * mm), "Cm": -30 * aa}
    args = dict(reference_area=0.0127, reference_length=0.127, moment_reference_x=1.3,
                includes=("pressure",), metadata={"generator": "test", "transonic_bridge": True})
    args.update(kw)
    return AeroTable(mach, alpha, coeffs, **args)


def test_interpolates_grid_points_exactly():
    t = _table()
    mm, aa = np.meshgrid(MACH, ALPHA, indexing="ij")
    np.testing.assert_allclose(t.evaluate("CA", mm, aa), _smooth(mm, aa), rtol=0, atol=1e-13)


def test_cubic_spline_reproduces_a_cubic_polynomial():
    # not-a-knot cubic interpolation is exact for cubic data (independent check of the degree)
    mach = np.array([0.0, 0.4, 0.7, 1.1, 1.5, 2.5])
    alpha = np.radians([0.0, 3.0, 7.0, 15.0, 25.0])
    mm, aa = np.meshgrid(mach, alpha, indexing="ij")
    f = lambda m, a: 1 + m - 2 * m ** 3 + 0.5 * a ** 3 * m ** 2 - a  # noqa: E731
    t = AeroTable(mach, alpha, {"CA": f(mm, aa)}, reference_area=1.0, reference_length=1.0,
                  moment_reference_x=0.0)
    rng = np.random.default_rng(1)
    m, a = rng.uniform(0, 2.5, 300), rng.uniform(0, alpha[-1], 300)
    np.testing.assert_allclose(t.evaluate("CA", m, a), f(m, a), atol=1e-12)


@pytest.mark.parametrize("n_alpha", [7, 3, 2, 1])
def test_scipy_and_casadi_agree_float_sx_mx(n_alpha):
    """Drift test: numeric (SciPy) and symbolic (CasADi SX and MX) give the same numbers."""
    alpha = ALPHA[:n_alpha]
    t = _table(alpha=alpha)
    rng = np.random.default_rng(0)
    m = rng.uniform(0, 3, 200)
    a = rng.uniform(0, alpha[-1], 200)
    numeric = t.evaluate("CA", m, a)
    for sym in (ca.SX, ca.MX):
        ms, as_ = sym.sym("m"), sym.sym("a")
        f = ca.Function("f", [ms, as_], [t.symbolic("CA", ms, as_)])
        symbolic = np.array(f.map(m.size)(m, a)).ravel()
        err = np.max(np.abs(symbolic - numeric))
        print(f"n_alpha={n_alpha} {sym.__name__}: max |casadi - scipy| = {err:.2e}")
        assert err < 1e-10
    assert np.max(np.abs(np.array(t.casadi_function("CA")(m, a)).ravel() - numeric)) < 1e-10


def test_symbolic_vector_input_and_dm():
    t = _table()
    x = ca.SX.sym("x", 3)
    f = ca.Function("f", [x], [t.symbolic("CN", x, 0.1)])
    got = np.array(f([0.2, 1.0, 2.5])).ravel()
    np.testing.assert_allclose(got, t.evaluate("CN", [0.2, 1.0, 2.5], 0.1), atol=1e-12)
    assert float(t.symbolic("CN", ca.DM(0.5), ca.DM(0.1))) == pytest.approx(t.evaluate("CN", 0.5, 0.1))


def test_numeric_clamps_and_warns():
    t = _table()
    with pytest.warns(OutOfRangeWarning, match="mach = 4"):
        v = t.evaluate("CA", 4.0, 0.1)
    assert v == pytest.approx(t.evaluate("CA", 3.0, 0.1), abs=1e-14)
    with pytest.warns(OutOfRangeWarning, match="alpha"):
        t.evaluate("CA", 1.0, np.radians(45))
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        t.evaluate("CA", 3.0, ALPHA[-1])  # the grid edge is inside


def test_symbolic_clamps_instead_of_returning_zero():
    t = _table()
    m, a = ca.SX.sym("m"), ca.SX.sym("a")
    f = ca.Function("f", [m, a], [t.symbolic("CA", m, a)])
    edge = t.evaluate("CA", 3.0, ALPHA[-1])
    assert float(f(10.0, 1.5)) == pytest.approx(edge, abs=1e-12)
    assert float(f(-1.0, -0.2)) == pytest.approx(t.evaluate("CA", 0.0, 0.0), abs=1e-12)


def test_single_alpha_is_independent_of_alpha():
    t = AeroTable(MACH, [0.0], {"CA": 0.4 + 0.1 * MACH}, reference_area=1.0, reference_length=1.0,
                  moment_reference_x=0.0)
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # alpha is not an axis of this table: no warning
        assert t.evaluate("CA", 0.5, 0.0) == pytest.approx(t.evaluate("CA", 0.5, 0.3))
        assert t.evaluate("CA", 0.5, 0.3) == pytest.approx(0.45, abs=1e-12)
    a = ca.SX.sym("a")
    assert float(ca.Function("f", [a], [t.symbolic("CA", 0.5 + 0 * a, a)])(0.7)) == pytest.approx(0.45)


def test_constant_table():
    t = AeroTable([0.5], [0.0], {"CA": [[0.42]]}, reference_area=1.0, reference_length=1.0,
                  moment_reference_x=0.0)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        assert t.evaluate("CA", 1.0, 0.3) == 0.42
    m = ca.SX.sym("m")
    assert float(ca.Function("f", [m], [t.symbolic("CA", m, 0.0)])(0.5)) == 0.42


def test_queries_and_repr():
    t = _table()
    assert t.coefficient_names == ("CA", "CN", "Cm")
    assert t.has("CN") and not t.has("CY")
    assert t.mach_range == (0.0, 3.0)
    assert t.alpha_range == pytest.approx((0.0, np.radians(30)))
    assert "CA, CN, Cm" in repr(t)
    with pytest.raises(InputError, match="no coefficient 'CY'"):
        t.evaluate("CY", 0.5, 0.0)


def test_save_load_round_trip(tmp_path):
    t = _table(includes=("pressure", "base"))
    csv_path, json_path = t.save(tmp_path / "rocket")
    assert csv_path.name == "rocket.csv" and json_path.name == "rocket.json"
    doc = json.loads(json_path.read_text())
    assert doc["reference_area_m2"] == 0.0127 and doc["moment_reference_x_m"] == 1.3
    assert doc["axes"]["alpha_deg"]["max"] == pytest.approx(30.0)
    assert doc["transonic_bridge"] is True and doc["generator"] == "test"
    header = csv_path.read_text().splitlines()[0]
    assert header == "mach,alpha_deg,CA,CN,Cm"
    back = AeroTable.load(json_path)
    assert back.includes == ("pressure", "base")
    assert back.metadata == {"generator": "test", "transonic_bridge": True}
    for name in t.coefficient_names:
        np.testing.assert_array_equal(back.values(name), t.values(name))
    np.testing.assert_allclose(back.alpha, t.alpha, rtol=1e-15)


def _write(tmp_path, csv_text, meta=None):
    (tmp_path / "t.csv").write_text(csv_text)
    if meta is not False:
        m = {"reference_area_m2": 1.0, "reference_length_m": 1.0, "moment_reference_x_m": 0.0}
        m.update(meta or {})
        (tmp_path / "t.json").write_text(json.dumps(m))
    return tmp_path / "t.csv"


GOOD = "mach,alpha_deg,CA,CN\n0.1,0,0.5,0\n0.1,5,0.52,0.3\n0.5,0,0.55,0\n0.5,5,0.57,0.35\n"


def test_load_minimal_files(tmp_path):
    t = AeroTable.load(_write(tmp_path, "# comment\n" + GOOD))
    assert t.evaluate("CN", 0.5, np.radians(5)) == pytest.approx(0.35)


@pytest.mark.parametrize("text, line, match", [
    ("mach,CA\n0.1,0.5\n", 1, "missing column 'alpha_deg'"),
    (GOOD.replace("0.52", "abc"), 3, "'abc' is not a number"),
    (GOOD.replace("0.5,0,0.55,0", "0.5,0,0.55"), 4, "3 values, expected 4"),
    ("mach,alpha_deg,CA\n0.5,0,1\n0.1,0,1\n", 3, "comes after"),
    ("mach,alpha_deg,CA\n0.1,0,1\n0.1,0,1\n", 3, "repeats"),
    ("mach,alpha_deg,CA\n0.1,5,1\n0.1,0,1\n", 3, "sorted by mach, then alpha_deg"),
])
def test_load_errors_name_line(tmp_path, text, line, match):
    with pytest.raises(InputError, match=match) as err:
        AeroTable.load(_write(tmp_path, text))
    assert err.value.line == line and err.value.source.endswith("t.csv")


def test_load_incomplete_grid(tmp_path):
    text = "mach,alpha_deg,CA\n0.1,0,1\n0.1,5,1\n0.5,0,1\n"
    with pytest.raises(InputError, match="no row for mach 0.5, alpha_deg 5"):
        AeroTable.load(_write(tmp_path, text))


def test_load_metadata_errors(tmp_path):
    with pytest.raises(InputError, match="metadata file not found"):
        AeroTable.load(_write(tmp_path, GOOD, meta=False))
    (tmp_path / "t.json").write_text('{"reference_area_m2": 1.0}')
    with pytest.raises(InputError) as err:
        AeroTable.load(tmp_path / "t.csv")
    assert err.value.field == "reference_length_m"
    with pytest.raises(InputError, match="lists coefficients"):
        AeroTable.load(_write(tmp_path, GOOD, meta={"coefficients": ["CA", "Cm"]}))
    (tmp_path / "t.json").write_text('{"reference_area_m2": 1.0,\n oops}')
    with pytest.raises(InputError, match="not valid JSON") as err:
        AeroTable.load(tmp_path / "t")
    assert err.value.line == 2


def test_constructor_validation():
    with pytest.raises(InputError, match="shape"):
        AeroTable(MACH, ALPHA, {"CA": np.zeros((3, 3))}, reference_area=1.0, reference_length=1.0,
                  moment_reference_x=0.0)
    with pytest.raises(InputError, match="strictly increasing"):
        AeroTable([0.5, 0.1], [0.0], {"CA": [[1], [2]]}, reference_area=1.0, reference_length=1.0,
                  moment_reference_x=0.0)
    with pytest.raises(InputError, match="unknown part"):
        _table(includes=("pressure", "wave"))
    with pytest.raises(InputError) as err:
        _table(reference_area=0.0)
    assert err.value.field == "reference_area"
    with pytest.raises(InputError, match="reserved"):
        _table(metadata={"includes": []})
    with pytest.raises(InputError, match="NaN"):
        AeroTable([0.1, 0.2], [0.0], {"CA": [[np.nan], [1.0]]}, reference_area=1.0,
                  reference_length=1.0, moment_reference_x=0.0)


def test_grid_spline_1d_matches_casadi_and_rejects_bad_input():
    x = np.linspace(0, 1, 6)
    s = GridSpline([x], x ** 2, name="sq", axis_names=("x",))
    assert s.evaluate(0.5) == pytest.approx(0.25, abs=1e-12)
    xs = ca.MX.sym("x")
    assert float(ca.Function("f", [xs], [s.symbolic(xs)])(0.37)) == pytest.approx(0.37 ** 2, abs=1e-12)
    with pytest.raises(InputError, match="takes 1 coordinates"):
        s.evaluate(0.1, 0.2)
    with pytest.raises(InputError, match="NaN"):
        s.evaluate(np.nan)


def _re_table():
    re = np.array([1e5, 1e6, 1e7, 1e8])
    mm, aa, rr = np.meshgrid(MACH, ALPHA[:3], np.log10(re), indexing="ij")
    return AeroTable(MACH, ALPHA[:3], {"CA": _smooth(mm, aa) + 0.05 * (8 - rr) ** 2},
                     reference_area=1.0, reference_length=0.1, moment_reference_x=0.0,
                     reynolds=re), re


def test_reynolds_axis_interpolates_in_log_re():
    t, re = _re_table()
    assert t.reynolds_range == (1e5, 1e8)
    assert "Re 1e+05..1e+08" in repr(t)
    # quadratic in log10(Re) is reproduced exactly by the cubic not-a-knot spline
    got = t.evaluate("CA", 0.6, ALPHA[1], 10 ** 6.5)  # on the Mach and alpha grid
    assert got == pytest.approx(_smooth(0.6, ALPHA[1]) + 0.05 * 1.5 ** 2, abs=1e-13)
    with pytest.raises(InputError, match="pass reynolds"):
        t.evaluate("CA", 0.7, 0.0)
    with pytest.warns(OutOfRangeWarning, match="log10_reynolds"):
        t.evaluate("CA", 0.7, 0.0, 1e9)
    assert _table().evaluate("CA", 0.5, 0.1, reynolds=1e6) == _table().evaluate("CA", 0.5, 0.1)


def test_reynolds_axis_drift_and_round_trip(tmp_path):
    t, re = _re_table()
    rng = np.random.default_rng(5)
    m, a, r = rng.uniform(0, 3, 100), rng.uniform(0, ALPHA[2], 100), 10 ** rng.uniform(5, 8, 100)
    numeric = t.evaluate("CA", m, a, r)
    f = t.casadi_function("CA")
    err = np.max(np.abs(np.array(f.map(100)(m, a, r)).ravel() - numeric))
    print(f"3-D table: max |casadi - scipy| = {err:.1e}")
    assert err < 1e-10
    t.save(tmp_path / "re")
    assert (tmp_path / "re.csv").read_text().splitlines()[0] == "mach,alpha_deg,reynolds,CA"
    back = AeroTable.load(tmp_path / "re.json")
    np.testing.assert_array_equal(back.values("CA"), t.values("CA"))
    np.testing.assert_array_equal(back.reynolds, re)
    with pytest.raises(InputError, match="> 0"):
        AeroTable([0.1, 0.2], [0.0], {"CA": np.ones((2, 1, 2))}, reference_area=1.0,
                  reference_length=1.0, moment_reference_x=0.0, reynolds=[0.0, 1e6])


def test_absurd_coefficient_is_refused_naming_it():
    """A broken build once wrote CA -7.3e9 (singular panel solution): loading refuses
    any |coefficient| above COEFFICIENT_MAX, naming the coefficient and where."""
    from ironbark_opt.aero.table import COEFFICIENT_MAX
    mm, aa = np.meshgrid(MACH, ALPHA, indexing="ij")
    ca = _smooth(mm, aa)
    ca[2, 1] = -7.3e9
    with pytest.raises(InputError, match=r"coefficient 'CA' reaches -7\.3e\+09") as err:
        AeroTable(MACH, ALPHA, {"CA": ca}, reference_area=0.0127, reference_length=0.127,
                   moment_reference_x=1.3)
    assert err.value.field == "CA"
    ca[2, 1] = 0.5 * COEFFICIENT_MAX           # large but allowed
    AeroTable(MACH, ALPHA, {"CA": ca}, reference_area=0.0127, reference_length=0.127,
                   moment_reference_x=1.3)
