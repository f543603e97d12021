"""The merged Mach B-spline (aero/mach_splines.py) equals the splines it replaces."""
import warnings
from pathlib import Path

import casadi as ca
import numpy as np
import pytest

from ironbark_opt.aero.mach_splines import merged_spline, spline_knots, table_form
from ironbark_opt.aero.model import LIFT_MACH_GRID
from ironbark_opt.vehicle import load_setup

ROOT = Path(__file__).resolve().parents[2]
CALISTO = ROOT / "examples" / "calisto"


def _curves():
    """Calisto's power-off and power-on drag curves and a five-output curve on the
    lift-sum grid, each as CasADi's cubic B-spline through its data."""
    grids, funcs = [LIFT_MACH_GRID], []
    g = LIFT_MACH_GRID
    values = np.vstack([np.sin(3 * g) + g ** 2, np.cos(g), np.exp(-g), np.sqrt(g), np.tanh(g - 1)])
    funcs.append(ca.interpolant("sums", "bspline", [g], values.ravel(order="F")))
    for name in ("powerOffDragCurve.csv", "powerOnDragCurve.csv"):
        data = np.loadtxt(CALISTO / name, delimiter=",")
        grids.append(data[:, 0])
        funcs.append(ca.interpolant(name[:-4], "bspline", [data[:, 0]], data[:, 1]))
    return grids, funcs


def _reference(grids, funcs, x):
    """Every curve at ``x`` clamped to its own grid (what the flight evaluated before)."""
    return np.vstack([np.array(f(np.clip(x, g[0], g[-1])[None, :])).reshape(-1, x.size)
                      for g, f in zip(grids, funcs)])


def test_knots_are_casadis_not_a_knot_knots():
    g = np.array([0.0, 0.1, 0.3, 0.4, 0.7, 1.0])
    assert np.array_equal(spline_knots(g), [0, 0, 0, 0, 0.3, 0.4, 1, 1, 1, 1])


FORMS = pytest.mark.parametrize("form", ["bspline", "pp"])


@FORMS
def test_merged_spline_equals_each_clamped_spline(form):
    grids, funcs = _curves()
    with table_form(form):
        fn, lo, hi = merged_spline("merged", grids, funcs)
    assert (lo, hi) == (min(g[0] for g in grids), max(g[-1] for g in grids))
    # dense points, every grid point, and points outside each curve's range (clamped)
    x = np.r_[np.linspace(-0.5, 7.0, 40001), np.concatenate(grids)]
    got = np.array(fn(np.clip(x, lo, hi)[None, :]))
    ref = _reference(grids, funcs, x)
    err = np.max(np.abs(got - ref) / np.abs(ref).max(axis=1, keepdims=True))
    print(f"{form}: {got.shape[0]} outputs at {x.size} Mach numbers: max relative difference {err:.2e} (tolerance 1e-12)")
    assert err < 1e-12


@FORMS
def test_merged_spline_derivative_equals_each_splines_derivative(form):
    grids, funcs = _curves()
    with table_form(form):
        fn, lo, hi = merged_spline("merged", grids, funcs)
    m = ca.SX.sym("m")
    jac = ca.Function("dmach", [m], [ca.jacobian(fn(m), m), ca.vertcat(*[ca.jacobian(f(m), m) for f in funcs])])
    x = np.linspace(0.0105, 1.9995, 20001)            # inside every grid
    a, b = (np.array(v) for v in jac.map(x.size)(x[None, :]))
    err = np.max(np.abs(a - b) / np.abs(b).max(axis=1, keepdims=True))
    print(f"{form}: d/dMach: max relative difference {err:.2e} (tolerance 1e-10)")
    assert err < 1e-10


@FORMS
def test_merged_spline_reproduces_cubic_polynomials(form):
    """A not-a-knot cubic spline through samples of a cubic is that cubic (analytic)."""
    def poly(x):
        return 0.3 - 1.2 * x + 0.7 * x ** 2 - 0.25 * x ** 3
    g1, g2 = np.linspace(0.0, 3.0, 31), np.array([0.5, 0.9, 1.3, 1.6, 2.2])
    f1 = ca.interpolant("p1", "bspline", [g1], poly(g1))
    f2 = ca.interpolant("p2", "bspline", [g2], 2 * poly(g2))
    with table_form(form):
        fn, lo, hi = merged_spline("merged", [g1, g2], [f1, f2])
    x = np.linspace(lo, hi, 3001)
    got = np.array(fn(x[None, :]))
    want = np.vstack([poly(x), 2 * poly(np.clip(x, g2[0], g2[-1]))])
    err = np.max(np.abs(got - want))
    print(f"{form}: cubic reproduced to {err:.2e} (tolerance 1e-13)")
    assert err < 1e-13


@FORMS
def test_calisto_aero_from_the_merged_spline_equals_the_table_splines(form):
    """The flight's symbolic CA and lift sums (one merged call) against the numeric
    path (the table's own splines, the lift-sum spline) at the same Mach numbers."""
    setup = load_setup(CALISTO / "calisto.toml")
    aero = setup.aero
    assert aero._merged_drag() == ("CA", "CA_power_on")
    m = ca.SX.sym("m")
    rows = []
    with table_form(form):
        for alpha in (ca.SX(0.0), 0.0):     # symbolic angle: the merged spline; a number (rail): the table's
            rows += [aero.axial(m, alpha, 1e7, False), aero.axial(m, alpha, 1e7, True)]
        sym = ca.Function("aero", [m], [ca.vertcat(*rows, *aero._sums(m))])
    mach = np.linspace(0.0, 3.0, 3001)
    got = np.array(sym.map(mach.size)(mach[None, :]))
    with warnings.catch_warnings():          # drag curves end at Mach 2: clamped (and warned)
        warnings.simplefilter("ignore")
        drag = [aero.axial(mach, 0.0, 1e7, False), aero.axial(mach, 0.0, 1e7, True)]
        want = np.vstack(drag + drag + list(aero._sums(mach)))
    err = np.max(np.abs(got - want) / np.abs(want).max(axis=1, keepdims=True))
    print(f"{form}: CA, CA_power_on and 5 lift sums: max relative difference {err:.2e} (tolerance 1e-12)")
    assert err < 1e-12
