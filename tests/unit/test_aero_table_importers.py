"""Importers: Cd-vs-Mach curves (RocketPy / RASAero / OpenRocket) and CFD coefficient tables."""
import warnings
from pathlib import Path

import numpy as np
import pytest

from ironbark_opt.aero.importers import from_cd_mach_csv, from_coefficient_csv
from ironbark_opt.errors import InputError, OutOfRangeWarning

DATA = Path(__file__).resolve().parents[1] / "data" / "aero"
REF = dict(reference_area=np.pi * 0.0635 ** 2, reference_length=0.127)


def test_calisto_headerless_power_off_and_on():
    t = from_cd_mach_csv(DATA / "calisto_power_off.csv", DATA / "calisto_power_on.csv", **REF)
    raw = np.loadtxt(DATA / "calisto_power_off.csv", delimiter=",")
    assert t.coefficient_names == ("CA", "CA_power_on")
    assert t.includes == ("pressure", "friction", "base")
    assert t.mach_range == (0.01, 2.0) and t.alpha.size == 1
    # the table reproduces every row of the file exactly
    np.testing.assert_allclose(t.evaluate("CA", raw[:, 0], 0.0), raw[:, 1], atol=1e-12)
    assert t.metadata["source_files"][1].endswith("calisto_power_on.csv")


def test_rasaero_number_format_and_single_file():
    t = from_cd_mach_csv(DATA / "valetudo_power_off.csv", **REF)
    assert t.evaluate("CA", 0.02, 0.0) == pytest.approx(1.05)  # written "01.05" in the file
    assert not t.has("CA_power_on")


def test_header_matched_by_name_and_alpha_zero_rows(tmp_path):
    p = tmp_path / "rasaero.csv"
    p.write_text("Mach,Alpha,CD,CD Power-Off,CD Power-On,CL\n"
                 "0.1,0,0.50,0.52,0.45,0\n0.1,2,0.60,0.62,0.55,0.1\n"
                 "0.5,0,0.51,0.53,0.46,0\n0.5,2,0.61,0.63,0.56,0.1\n"
                 "0.9,0,0.60,0.64,0.58,0\n0.9,2,0.70,0.74,0.68,0.1\n")
    t = from_cd_mach_csv(p, **REF)
    np.testing.assert_allclose(t.values("CA").ravel(), [0.52, 0.53, 0.64])
    np.testing.assert_allclose(t.values("CA_power_on").ravel(), [0.45, 0.46, 0.58])


def test_openrocket_comment_header(tmp_path):
    p = tmp_path / "or.csv"
    p.write_text("# Simulation 1\n# Time (s),Mach number (\u200b),Drag coefficient (\u200b)\n"
                 "0.0,0.2,0.45\n# Event LAUNCH occurred at t=0 seconds\n0.1,0.1,0.44\n0.2,0.3,0.46\n")
    t = from_cd_mach_csv(p, **REF)
    np.testing.assert_allclose(t.mach, [0.1, 0.2, 0.3])  # sorted
    np.testing.assert_allclose(t.values("CA").ravel(), [0.44, 0.45, 0.46])


def test_repeated_mach_values(tmp_path):
    p = tmp_path / "dup.csv"
    p.write_text("0.1,0.5\n0.2,0.6\n0.2,0.6\n0.3,0.7\n")
    t = from_cd_mach_csv(p, **REF)  # equal repeats are merged
    np.testing.assert_allclose(t.mach, [0.1, 0.2, 0.3])
    # lines 1-5 all read 0.708, line 6 0.707: the first row that differs is named
    with pytest.raises(InputError,
                       match="Mach 0.011 appears on lines 1 and 6 with different values 0.708 and 0.707") as err:
        from_cd_mach_csv(DATA / "cavour_power_on.csv", **REF)
    assert err.value.line == 6 and "duplicates='mean'" in str(err.value) and 'drag_duplicates = "mean"' in str(err.value)
    t = from_cd_mach_csv(DATA / "cavour_power_on.csv", duplicates="mean", **REF)
    raw = np.loadtxt(DATA / "cavour_power_on.csv", delimiter=",")
    m0 = raw[0, 0]
    assert t.evaluate("CA", m0, 0.0) == pytest.approx(raw[raw[:, 0] == m0, 1].mean())


def test_descending_headerless_curve_is_sorted_and_a_step_back_refused(tmp_path):
    # hedy's team power-off curve (RocketPy docs/examples data) runs Mach 1.748 down to 0.157:
    # read as the same curve in ascending order; a single step back stays a typo
    down, up = tmp_path / "down.csv", tmp_path / "up.csv"
    rows = [(1.748, 0.364), (1.2, 0.52), (1.2, 0.52), (0.9, 0.41), (0.157, 0.44)]
    down.write_text("".join(f"{m},{c}\n" for m, c in rows))
    up.write_text("".join(f"{m},{c}\n" for m, c in sorted(set(rows))))
    t_down, t_up = from_cd_mach_csv(down, **REF), from_cd_mach_csv(up, **REF)
    np.testing.assert_array_equal(t_down.mach, [0.157, 0.9, 1.2, 1.748])
    np.testing.assert_allclose(t_down.values("CA").ravel(), [0.44, 0.41, 0.52, 0.364], atol=1e-15)
    np.testing.assert_allclose(t_down.evaluate("CA", 1.0, 0.0), t_up.evaluate("CA", 1.0, 0.0), atol=1e-15)
    bad = tmp_path / "bad.csv"
    bad.write_text("0.1,0.5\n0.3,0.6\n0.2,0.55\n0.4,0.7\n")
    with pytest.raises(InputError, match="0.2 follows 0.3") as err:
        from_cd_mach_csv(bad, **REF)
    assert err.value.line == 3
    dup = tmp_path / "dup_down.csv"      # conflicting repeats follow drag_duplicates as before
    dup.write_text("0.9,0.41\n0.163,0.437\n0.163,0.438\n")
    with pytest.raises(InputError, match="Mach 0.163 appears on lines 2 and 3"):
        from_cd_mach_csv(dup, **REF)
    assert from_cd_mach_csv(dup, duplicates="mean", **REF).evaluate("CA", 0.163, 0.0) == pytest.approx(0.4375)


def test_a_curve_written_out_twice_reads_as_one_and_a_new_row_after_a_step_back_is_refused(tmp_path):
    # the Space Enterprise at Berkeley curve (RocketPy docs/examples data) is one Mach 0.01..25
    # curve written three times: the repeats restate rows already read, so it is that curve
    rows = "0.01,0.47\n0.5,0.45\n1.2,0.6\n25,0.1\n"
    twice, once = tmp_path / "twice.csv", tmp_path / "once.csv"
    twice.write_text(rows + rows + rows.rsplit("25,", 1)[0])
    once.write_text(rows)
    t2, t1 = from_cd_mach_csv(twice, **REF), from_cd_mach_csv(once, **REF)
    np.testing.assert_array_equal(t2.mach, [0.01, 0.5, 1.2, 25])
    np.testing.assert_array_equal(t2.values("CA"), t1.values("CA"))
    for text, line, msg in [(rows + "0.5,0.46\n", 5, "0.5 follows 25"),        # restated, other Cd
                            (rows + "0.7,0.5\n", 5, "0.7 follows 25"),         # a row not read before
                            ("0.1,0.5\n0.3,0.6\n0.2,0.55\n0.2,0.55\n", 3, "0.2 follows 0.3")]:
        bad = tmp_path / "bad.csv"
        bad.write_text(text)
        with pytest.raises(InputError, match=msg) as err:
            from_cd_mach_csv(bad, **REF)
        assert err.value.line == line


def test_repeated_mach_error_names_the_row_that_differs(tmp_path):
    # hedy's curve repeats Mach 0.158 three times, 0.439, 0.439, 0.44: the message named the two
    # equal rows ("different values 0.439 and 0.439"); it names the first one that differs
    p = tmp_path / "three.csv"
    p.write_text("0.1,0.5\n0.158,0.439\n0.158,0.439\n0.158,0.44\n")
    with pytest.raises(InputError, match="lines 2 and 4 with different values 0.439 and 0.44;") as err:
        from_cd_mach_csv(p, **REF)
    assert err.value.line == 4
    mean = from_cd_mach_csv(p, duplicates="mean", **REF)
    assert mean.evaluate("CA", 0.158, 0.0) == pytest.approx(1.318 / 3)


def test_different_mach_ranges_are_held_and_warned(tmp_path):
    off, on = tmp_path / "off.csv", tmp_path / "on.csv"
    off.write_text("0.1,0.50\n0.3,0.52\n0.5,0.55\n0.7,0.60\n0.9,0.70\n")
    on.write_text("0.2,0.40\n0.4,0.42\n0.6,0.45\n0.8,0.50\n1.0,0.62\n")
    with pytest.warns(OutOfRangeWarning, match="held constant"):
        t = from_cd_mach_csv(off, on, **REF)
    assert t.mach.size == 10
    assert t.evaluate("CA", 1.0, 0.0) == pytest.approx(0.70)
    assert t.evaluate("CA_power_on", 0.1, 0.0) == pytest.approx(0.40)
    assert t.evaluate("CA_power_on", 0.6, 0.0) == pytest.approx(0.45, abs=1e-12)


@pytest.mark.parametrize("text, line, match", [
    ("0.1,0.5\n0.2,x\n", 2, "'x' is not a number"),
    ("0.1,O.5\n0.2,0.4\n", 1, "'O.5' is not a number"),
    ("0.1,0.5,3\n0.2,0.4,3\n", 1, "2 columns"),
    ("0.1,0.5\n0.2\n", 2, "1 values, expected 2"),
    ("Speed,CD\n1,0.5\n", 1, "no Mach column"),
    ("Mach,Lift\n0.1,0.5\n", 1, "no drag coefficient column"),
    ("0.1,0.5\n-0.2,0.4\n", 2, "negative Mach"),
])
def test_cd_errors_name_file_and_line(tmp_path, text, line, match):
    p = tmp_path / "bad.csv"
    p.write_text(text)
    with pytest.raises(InputError, match=match) as err:
        from_cd_mach_csv(p, **REF)
    assert err.value.line == line and err.value.source.endswith("bad.csv")


def test_cd_missing_file_and_bad_policy(tmp_path):
    with pytest.raises(InputError, match="file not found"):
        from_cd_mach_csv(tmp_path / "nope.csv", **REF)
    with pytest.raises(InputError, match="duplicates"):
        from_cd_mach_csv(DATA / "calisto_power_off.csv", duplicates="max", **REF)


def test_panair_coefficient_table():
    t = from_coefficient_csv(DATA / "basic_finner_panair.csv", reference_area=np.pi / 4,
                             reference_length=1.0, moment_reference_x=5.0)
    assert set(t.coefficient_names) == {"CA", "CN", "Cm"}
    assert t.alpha.size == 3 and t.mach.size == 9
    raw = np.genfromtxt(DATA / "basic_finner_panair.csv", delimiter=",", names=True)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        got = t.evaluate("Cm", raw["mach"], np.radians(raw["alpha_deg"]))
    np.testing.assert_allclose(got, raw["Cm"], atol=1e-12)
    assert t.metadata["ignored_columns"] == ["CL", "CDi", "panels", "wall_s"]


def test_text_column_selection_and_blank_cells():
    kw = dict(reference_area=np.pi / 4, reference_length=1.0, moment_reference_x=0.0)
    with pytest.raises(InputError, match="'' is not a number"):
        from_coefficient_csv(DATA / "ogive_cylinder_panair.csv", **kw)
    t = from_coefficient_csv(DATA / "ogive_cylinder_panair.csv", select={"mesh": "default"}, **kw)
    assert t.evaluate("CN", 1.6, np.radians(2)) == pytest.approx(0.09268)
    assert t.evaluate("CA", 0.6, np.radians(4)) == pytest.approx(-0.00511)


def test_wind_axes_converted_to_body_axes(tmp_path):
    p = tmp_path / "cfd.csv"
    a = np.radians([0.0, 5.0, 10.0])
    rows = ["mach,alpha_rad,CD,CL,Cm"]
    for m in (0.3, 0.8):
        for ai in a:
            ca_, cn = 0.4 + m, 10 * ai  # choose body-axis values, write wind-axis ones
            cd = ca_ * np.cos(ai) + cn * np.sin(ai)
            cl = cn * np.cos(ai) - ca_ * np.sin(ai)
            rows.append(f"{m},{float(ai)!r},{float(cd)!r},{float(cl)!r},{float(-3 * ai)!r}")
    p.write_text(rows[0] + "\n" + "\n".join(reversed(rows[1:])) + "\n")  # unsorted rows
    t = from_coefficient_csv(p, reference_area=1.0, reference_length=1.0, moment_reference_x=0.5)
    np.testing.assert_allclose(t.values("CA"), [[0.7] * 3, [1.2] * 3], atol=1e-12)
    np.testing.assert_allclose(t.values("CN"), [10 * a, 10 * a], atol=1e-12)


@pytest.mark.parametrize("text, match", [
    ("mach,alpha,CA\n0.1,0,0.5\n", "does not say its unit"),
    ("mach,CA\n0.1,0.5\n", "no angle-of-attack column"),
    ("mach,alpha_deg,CX\n0.1,0,0.5\n", "no coefficient columns"),
    ("0.1,0,0.5\n", "needs a header"),
    ("mach,alpha_deg,CA\n0.1,0,0.5\n0.1,2,0.5\n0.3,0,0.6\n", "no row for mach 0.3, alpha 2"),
    ("mach,alpha_deg,CA\n0.1,0,0.5\n0.1,0,0.6\n", "lines 2 and 3 with different values"),
])
def test_coefficient_errors(tmp_path, text, match):
    p = tmp_path / "cfd.csv"
    p.write_text(text)
    with pytest.raises(InputError, match=match) as err:
        from_coefficient_csv(p, reference_area=1.0, reference_length=1.0, moment_reference_x=0.0)
    assert err.value.source.endswith("cfd.csv")


def test_plain_alpha_with_unit_argument(tmp_path):
    p = tmp_path / "cfd.csv"
    p.write_text("Mach,Alpha,CA,CN\n0.1,0,0.5,0\n0.1,4,0.5,0.4\n")
    t = from_coefficient_csv(p, reference_area=1.0, reference_length=1.0, moment_reference_x=0.0,
                             alpha_unit="deg")
    assert t.alpha_range[1] == pytest.approx(np.radians(4))


def test_resampling_spline_is_scipys_not_a_knot_spline():
    """The power-on curve is resampled onto the power-off Mach grid by CasADi's B-spline
    (no SciPy import on the simulate path); it must be the interpolating not-a-knot spline
    SciPy's make_interp_spline fits (the independent reference), to 1e-9 relative."""
    from scipy.interpolate import make_interp_spline

    from ironbark_opt.aero.importers import _on_grid
    from ironbark_opt.aero.table import spline_degree
    raw = np.loadtxt(DATA / "calisto_power_on.csv", delimiter=",")
    grid = np.loadtxt(DATA / "calisto_power_off.csv", delimiter=",")[:, 0]
    for n in (2, 3, raw.shape[0]):           # linear (2, 3 points) and cubic splines
        mach, cd = raw[:n, 0], raw[:n, 1]
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            got = _on_grid(mach, cd, grid, "power_on.csv", "cd")
        ref = make_interp_spline(mach, cd, k=spline_degree(n))(np.clip(grid, mach[0], mach[-1]))
        err = float(np.max(np.abs(got - ref) / np.abs(ref)))
        print(f"{n} points: max relative difference CasADi vs SciPy {err:.2e} (tolerance 1e-9)")
        assert err < 1e-9
