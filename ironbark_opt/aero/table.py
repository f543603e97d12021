"""Aerodynamic coefficient tables (`AeroTable`) and the spline behind them.

`AeroTable` holds coefficients on a (Mach, total angle of attack[, Reynolds
number]) grid, reads and writes the self-describing CSV + JSON pair of
DESIGN.md sec. 3, and evaluates each coefficient through a `GridSpline`.

`GridSpline` is the bridge between tabulated data and the symbolic model:
numbers go to SciPy, CasADi ``SX``/``MX``/``DM`` go to
``casadi.interpolant(..., 'bspline', ...)``, and both evaluate *the same*
spline.  CasADi's ``bspline`` interpolant fits an interpolating
tensor-product B-spline with not-a-knot end conditions; here SciPy builds the
same spline by 1-D ``make_interp_spline`` passes along each axis and evaluates
it as an ``NdBSpline`` (agreement measured at ~1e-14, see
``tests/unit/test_aero_table.py``).

Degree per axis: cubic where the axis has >= 4 points, linear where it has 2
or 3 (CasADi's cubic bspline needs 4 points).  An axis with a single point is
dropped: the data are constant along it (no clamping warning on that axis).

Out of range: a CasADi bspline returns 0 outside its grid, so every input is
clamped to the grid (``fmin``/``fmax``) before the call; the numeric path clamps
too and warns with `OutOfRangeWarning` naming the table and the axis.
"""
from __future__ import annotations

import csv
import json
import math
import warnings
from collections.abc import Mapping, Sequence
from pathlib import Path

import casadi as ca
import numpy as np

from ironbark_opt import _math
from ironbark_opt.errors import InputError, OutOfRangeWarning


def spline_degree(n_points: int) -> int:
    """Spline degree used on an axis with ``n_points`` points [-]: 3 if >= 4, else 1."""
    return 3 if n_points >= 4 else 1


class GridSpline:
    """An interpolating spline through ``values`` on the grid ``axes``.

    Parameters
    ----------
    axes : sequence of 1-D arrays [axis unit]
        One to three strictly increasing grid axes.
    values : ndarray, shape (len(axes[0]), len(axes[1]), ...) [value unit]
        Data at the grid points.
    name : str
        Used in warnings and in the CasADi function name.
    axis_names : sequence of str
        Names of the axes for warnings (e.g. ``("mach", "alpha")``).
    """

    def __init__(self, axes: Sequence[np.ndarray], values: np.ndarray, *, name: str,
                 axis_names: Sequence[str]):
        axes = [np.asarray(a, dtype=float).ravel() for a in axes]
        values = np.asarray(values, dtype=float)
        if not 1 <= len(axes) <= 3 or len(axis_names) != len(axes):
            raise InputError(f"GridSpline '{name}' supports 1 to 3 named axes, got {len(axes)}",
                             field=name)
        if values.shape != tuple(len(a) for a in axes):
            raise InputError(f"values of '{name}' have shape {values.shape}, expected "
                             f"{tuple(len(a) for a in axes)} (one value per grid point)", field=name)
        for a, an in zip(axes, axis_names):
            if a.size == 0 or not np.all(np.isfinite(a)) or np.any(np.diff(a) <= 0):
                raise InputError(f"axis '{an}' of '{name}' must be finite and strictly increasing",
                                 field=an)
        if not np.all(np.isfinite(values)):
            raise InputError(f"'{name}' contains NaN or infinite values", field=name)
        self.name = name
        self.axes = tuple(axes)
        self.axis_names = tuple(axis_names)
        self.values = values
        # axes with more than one point are "active"; the others are dropped
        self._active = tuple(i for i, a in enumerate(axes) if a.size > 1)
        squeezed = values.reshape([a.size for a in axes if a.size > 1] or [1])
        self._degrees = tuple(spline_degree(axes[i].size) for i in self._active)
        self._constant = None if self._active else float(squeezed.ravel()[0])
        self._numeric = None     # the SciPy spline, fitted on the first numeric evaluation
        self._casadi = None

    def __getstate__(self):
        # the fitted splines are caches, rebuilt on first use: a pickle (the flight-model
        # cache key, a worker's copy) depends on the data only, not on what was evaluated
        return {**self.__dict__, "_numeric": None, "_casadi": None}

    # ------------------------------------------------------------------ numeric
    def _scipy_spline(self):
        """The SciPy ``NdBSpline`` (fitted once, on first use: SciPy's interpolate
        module costs ~0.7 s to import and a symbolic-only caller never needs it)."""
        if self._numeric is None:
            from scipy.interpolate import NdBSpline, make_interp_spline
            squeezed = self.values.reshape([self.axes[i].size for i in self._active])
            # tensor-product interpolation: one not-a-knot 1-D pass per axis
            coef, knots = squeezed, []
            for d, i in enumerate(self._active):
                sp = make_interp_spline(self.axes[i], coef, k=self._degrees[d], axis=d)
                knots.append(sp.t)
                coef = np.moveaxis(sp.c, 0, d)
            self._numeric = NdBSpline(tuple(knots), coef, self._degrees, extrapolate=False)
        return self._numeric

    def evaluate(self, *coords, warn: bool = True):
        """Numeric value at ``coords`` (one per axis) with clamping. Numeric-only.

        Parameters
        ----------
        *coords : float or ndarray [axis units]
            Broadcast together.
        warn : bool
            Warn with `OutOfRangeWarning` when an input is clamped.

        Returns
        -------
        float or ndarray [value unit]
        """
        if len(coords) != len(self.axes):
            raise InputError(f"'{self.name}' takes {len(self.axes)} coordinates "
                             f"({', '.join(self.axis_names)}), got {len(coords)}", field=self.name)
        arrays = np.broadcast_arrays(*[np.asarray(c, dtype=float) for c in coords])
        scalar = arrays[0].ndim == 0
        clamped = []
        for i, (a, axis, an) in enumerate(zip(arrays, self.axes, self.axis_names)):
            lo, hi = axis[0], axis[-1]
            if warn and i in self._active and (np.any(a < lo) or np.any(a > hi)):
                bad = a[(a < lo) | (a > hi)].ravel()[0]
                warnings.warn(f"'{self.name}': {an} = {bad:g} outside the grid "
                              f"[{lo:g}, {hi:g}]; clamped", OutOfRangeWarning, stacklevel=3)
            if np.any(np.isnan(a)):
                raise InputError(f"'{self.name}': {an} is NaN", field=an)
            clamped.append(np.clip(a, lo, hi))
        if not self._active:
            out = np.full(arrays[0].shape, self._constant)
        else:
            points = np.stack([clamped[i].ravel() for i in self._active], axis=-1)
            out = self._scipy_spline()(points).reshape(arrays[0].shape)
        return float(out) if scalar else out

    # ----------------------------------------------------------------- symbolic
    def casadi_interpolant(self) -> ca.Function:
        """The CasADi bspline interpolant over the active axes (built once, cached).

        Its single input stacks the active coordinates; it returns 0 outside the
        grid, so callers must clamp (`symbolic` does).
        """
        if self._casadi is None:
            if not self._active:
                raise InputError(f"'{self.name}' is constant; it has no interpolant", field=self.name)
            grid = [self.axes[i] for i in self._active]
            vals = self.values.reshape([g.size for g in grid]).ravel(order="F")
            self._casadi = ca.interpolant(f"{_safe_name(self.name)}_bspline", "bspline", grid,
                                          vals, {"degree": list(self._degrees)})
        return self._casadi

    def mach_only_cubic(self) -> bool:
        """True when the spline varies along its first axis (Mach) alone, cubic there."""
        return self._active == (0,) and self._degrees == (3,)

    def symbolic(self, *coords):
        """Symbolic-safe evaluation: CasADi input -> clamped CasADi B-spline
        expression; numeric input -> `evaluate` (the same spline, with warnings).

        Parameters
        ----------
        *coords : float, ndarray or casadi SX/MX/DM [axis units]
            One per axis; CasADi inputs are scalars or column vectors of one length.
        """
        if len(coords) != len(self.axes):
            raise InputError(f"'{self.name}' takes {len(self.axes)} coordinates, got {len(coords)}",
                             field=self.name)
        if not _math.is_symbolic(*coords):
            return self.evaluate(*coords)
        if not self._active:
            return self._constant + 0 * coords[0]
        active = []
        for i in self._active:
            c = coords[i]
            lo, hi = float(self.axes[i][0]), float(self.axes[i][-1])
            active.append(_math.clip(c, lo, hi))
        n = max(_numel(c) for c in active)
        f = self.casadi_interpolant()
        if n == 1:
            return f(ca.vertcat(*active))
        rows = []
        for c in active:
            if _numel(c) == 1:
                c = c * ca.DM.ones(n, 1) if _math.is_symbolic(c) else ca.DM.ones(n, 1) * float(c)
            if isinstance(c, np.ndarray):
                c = ca.DM(c.reshape(-1, 1))
            rows.append(ca.reshape(c, 1, n))
        return f.map(n)(ca.vertcat(*rows)).T

    def casadi_function(self) -> ca.Function:
        """A CasADi Function ``(coord_1, ..., coord_k) -> value`` with clamping built in."""
        syms = [ca.SX.sym(n) for n in self.axis_names]
        return ca.Function(_safe_name(self.name), syms, [self.symbolic(*syms)],
                           list(self.axis_names), [_safe_name(self.name)])


def _numel(x) -> int:
    if isinstance(x, (ca.SX, ca.MX, ca.DM)):
        return x.numel()
    return int(np.size(x))


def _safe_name(name: str) -> str:
    s = "".join(ch if ch.isalnum() else "_" for ch in name)
    return s if s and s[0].isalpha() else f"f_{s}"


# --------------------------------------------------------------------------- AeroTable
FORMAT_NAME = "ironbark-aerotable"
FORMAT_VERSION = 1
INCLUDES_ALLOWED = ("pressure", "friction", "base", "crossflow")
#: Largest |coefficient| a table may hold [-]: a body at 90 deg with l/d 30 has CN ~ 50 and
#: Cm ~ 1e3, pitch damping of long rockets reaches ~1e4; a singular panel solution gave 6e9
COEFFICIENT_MAX = 1e6
FRAME_CONVENTION = (
    "body axes, aeroballistic: alpha = total angle of attack; CA axial force positive "
    "rearward (toward the base); CN normal force positive toward the crossflow side; "
    "Cm pitching moment about moment_reference_x, positive nose-up; coefficients on "
    "q * reference_area (moments also on reference_length)")
_RESERVED = ("format", "format_version", "coefficients", "reference_area_m2",
             "reference_length_m", "moment_reference_x_m", "includes", "axes", "frame", "units")


class AeroTable:
    """Aerodynamic coefficients on a (Mach, total angle of attack[, Reynolds]) grid.

    Parameters
    ----------
    mach : 1-D array [-]
        Strictly increasing Mach numbers.
    alpha : 1-D array [rad]
        Strictly increasing total angles of attack (aeroballistic).  A single
        value makes every coefficient independent of alpha (Cd-vs-Mach curves).
    coefficients : dict[str, ndarray (n_mach, n_alpha[, n_reynolds])] [-]
        E.g. ``CA`` (axial, positive rearward), ``CA_power_on``, ``CN``, ``Cm``
        (about ``moment_reference_x``, positive nose-up), optional ``CY``, ``Cn``, ``Cl``.
    reference_area : float [m^2]
    reference_length : float [m]
    moment_reference_x : float [m aft of the nose tip]
    includes : tuple of str
        Which parts the table contains: any of ``pressure``, ``friction``, ``base``
        (drag parts in ``CA``) and ``crossflow`` (the body's viscous cross-flow
        lift in ``CN`` and ``Cm``).
    metadata : dict, optional
        Free-form, JSON-serialisable description (generator, version,
        geometry_hash, transonic_bridge, source, ...).
    reynolds : 1-D array, optional [-]
        Optional third axis: strictly increasing, positive Reynolds numbers based on
        ``reference_length``; interpolated in log10(Re).
    source : str, optional
        The file the table came from (for messages).

    Coefficients are interpolated by cubic B-splines (linear on axes with
    fewer than 4 points), the same spline in SciPy (`evaluate`) and CasADi
    (`symbolic`); inputs outside the grid are clamped with a warning.
    """

    def __init__(self, mach, alpha, coefficients: Mapping[str, np.ndarray], *,
                 reference_area: float, reference_length: float, moment_reference_x: float,
                 includes: Sequence[str] = ("pressure",), metadata: Mapping | None = None,
                 reynolds=None, source: str | None = None):
        self.source = None if source is None else str(source)
        self.mach = _axis(mach, "mach", self.source)
        self.alpha = _axis(alpha, "alpha", self.source)
        self.reynolds = None if reynolds is None else _axis(reynolds, "reynolds", self.source)
        if self.reynolds is not None and self.reynolds[0] <= 0:
            raise InputError("Reynolds numbers must be > 0", source=self.source, field="reynolds")
        if not coefficients:
            raise InputError("an AeroTable needs at least one coefficient", source=self.source,
                             field="coefficients")
        for key, val in (("reference_area", reference_area), ("reference_length", reference_length)):
            if not (isinstance(val, (int, float, np.number)) and math.isfinite(val) and val > 0):
                raise InputError(f"expected a positive number, got {val!r}", source=self.source,
                                 field=key)
        if not (isinstance(moment_reference_x, (int, float, np.number))
                and math.isfinite(moment_reference_x)):
            raise InputError(f"expected a finite number [m], got {moment_reference_x!r}",
                             source=self.source, field="moment_reference_x")
        includes = (includes,) if isinstance(includes, str) else tuple(includes)
        bad = [i for i in includes if i not in INCLUDES_ALLOWED]
        if bad:
            raise InputError(f"unknown part(s) {bad}; expected any of {INCLUDES_ALLOWED}",
                             source=self.source, field="includes")
        metadata = dict(metadata or {})
        clash = [k for k in metadata if k in _RESERVED]
        if clash:
            raise InputError(f"metadata keys {clash} are reserved for the table itself",
                             source=self.source, field="metadata")
        self.reference_area = float(reference_area)
        self.reference_length = float(reference_length)
        self.moment_reference_x = float(moment_reference_x)
        self.includes = includes
        self._metadata = metadata
        self._splines: dict[str, GridSpline] = {}
        axes, names = [self.mach, self.alpha], ["mach", "alpha"]
        if self.reynolds is not None:
            axes.append(np.log10(self.reynolds))
            names.append("log10_reynolds")
        shape = tuple(a.size for a in axes)
        for cname, values in coefficients.items():
            if not (isinstance(cname, str) and cname.isidentifier()):
                raise InputError(f"coefficient name {cname!r} must be an identifier",
                                 source=self.source, field="coefficients")
            arr = np.asarray(values, dtype=float)
            if arr.shape != shape and arr.size == math.prod(shape):
                arr = arr.reshape(shape)
            if arr.shape != shape:
                raise InputError(f"coefficient '{cname}' has shape {arr.shape}, expected {shape} "
                                 f"({', '.join('n_' + n for n in names)})", source=self.source,
                                 field=cname)
            if not np.all(np.isfinite(arr)):
                raise InputError(f"coefficient '{cname}' has NaN or infinite values",
                                 source=self.source, field=cname)
            if np.max(np.abs(arr)) > COEFFICIENT_MAX:
                k = np.unravel_index(int(np.argmax(np.abs(arr))), arr.shape)
                where = ", ".join(f"{n} {float(a[i]):.4g}" for n, a, i in zip(names, axes, k))
                raise InputError(f"coefficient '{cname}' reaches {arr[k]:.3g} ({where}): not an "
                                 f"aerodynamic coefficient (|value| <= {COEFFICIENT_MAX:g}); "
                                 "the table is broken, rebuild it", source=self.source, field=cname)
            self._splines[cname] = GridSpline(axes, arr, name=cname, axis_names=names)

    # ---------------------------------------------------------------- queries
    @property
    def coefficient_names(self) -> tuple[str, ...]:
        """Names of the tabulated coefficients."""
        return tuple(self._splines)

    @property
    def mach_range(self) -> tuple[float, float]:
        """(min, max) of the Mach grid [-]."""
        return float(self.mach[0]), float(self.mach[-1])

    @property
    def alpha_range(self) -> tuple[float, float]:
        """(min, max) of the total-angle-of-attack grid [rad]."""
        return float(self.alpha[0]), float(self.alpha[-1])

    @property
    def reynolds_range(self) -> tuple[float, float] | None:
        """(min, max) of the Reynolds grid [-], or None without a Reynolds axis."""
        return None if self.reynolds is None else (float(self.reynolds[0]), float(self.reynolds[-1]))

    @property
    def metadata(self) -> dict:
        """A copy of the free-form metadata."""
        return json.loads(json.dumps(self._metadata))

    def has(self, name: str) -> bool:
        """True if coefficient ``name`` is tabulated."""
        return name in self._splines

    def values(self, name: str) -> np.ndarray:
        """A copy of the tabulated values of ``name``, shape (n_mach, n_alpha[, n_re]) [-]."""
        return self._spline(name).values.copy()

    def __repr__(self) -> str:
        re = "" if self.reynolds is None else (f", Re {self.reynolds[0]:.3g}.."
                                               f"{self.reynolds[-1]:.3g} ({self.reynolds.size})")
        return (f"AeroTable({', '.join(self.coefficient_names)}; mach {self.mach_range[0]:g}.."
                f"{self.mach_range[1]:g} ({self.mach.size}), alpha_deg "
                f"{math.degrees(self.alpha_range[0]):g}..{math.degrees(self.alpha_range[1]):g} "
                f"({self.alpha.size}){re}; Sref {self.reference_area:g} m^2)")

    def _spline(self, name: str) -> GridSpline:
        try:
            return self._splines[name]
        except KeyError:
            raise InputError(f"no coefficient '{name}' in this table; it has "
                             f"{list(self._splines)}", source=self.source, field=name) from None

    def _coords(self, mach, alpha, reynolds):
        if self.reynolds is None:
            return (mach, alpha)
        if reynolds is None:
            raise InputError("this table has a Reynolds axis: pass reynolds", source=self.source,
                             field="reynolds")
        return (mach, alpha, _math.log10(_math.fmax(reynolds, 1e-300)))

    # ------------------------------------------------------------- evaluation
    def evaluate(self, name: str, mach, alpha, reynolds=None):
        """Coefficient ``name`` at (mach, alpha[, reynolds]); numeric-only (SciPy).

        Parameters
        ----------
        name : str
        mach : float or ndarray [-]
        alpha : float or ndarray [rad]
            Total angle of attack; broadcast with ``mach``.
        reynolds : float or ndarray, optional [-]
            Required if the table has a Reynolds axis, ignored otherwise.

        Inputs outside the grid are clamped and warn with `OutOfRangeWarning`.
        """
        return self._spline(name).evaluate(*self._coords(mach, alpha, reynolds))

    def symbolic(self, name: str, mach, alpha, reynolds=None):
        """Coefficient ``name`` at (mach, alpha[, reynolds]); symbolic-safe.

        CasADi inputs give a CasADi B-spline expression with the inputs clamped
        to the grid (no warning possible); numbers give `evaluate`.

        Parameters
        ----------
        mach : float, ndarray or casadi SX/MX/DM [-]
        alpha : float, ndarray or casadi SX/MX/DM [rad]
        reynolds : float, ndarray or casadi SX/MX/DM, optional [-]
            Required if the table has a Reynolds axis, ignored otherwise.
        """
        return self._spline(name).symbolic(*self._coords(mach, alpha, reynolds))

    def casadi_function(self, name: str) -> ca.Function:
        """CasADi Function ``(mach [-], alpha [rad][, reynolds [-]]) -> name``, clamped."""
        args = [ca.SX.sym("mach"), ca.SX.sym("alpha")]
        if self.reynolds is not None:
            args.append(ca.SX.sym("reynolds"))
        return ca.Function(_safe_name(name), args, [self.symbolic(name, *args)],
                           [str(a) for a in args], [_safe_name(name)])

    # -------------------------------------------------------------------- I/O
    def _axis_columns(self) -> list[tuple[str, np.ndarray]]:
        cols = [("mach", self.mach), ("alpha_deg", np.degrees(self.alpha))]
        if self.reynolds is not None:
            cols.append(("reynolds", self.reynolds))
        return cols

    def to_json_dict(self) -> dict:
        """The JSON metadata document written by `save`."""
        axes = {n: {"unit": "deg" if n == "alpha_deg" else "-", "min": float(v[0]),
                    "max": float(v[-1]), "n": int(v.size)} for n, v in self._axis_columns()}
        doc = {
            "format": FORMAT_NAME, "format_version": FORMAT_VERSION,
            "coefficients": list(self.coefficient_names),
            "reference_area_m2": self.reference_area,
            "reference_length_m": self.reference_length,
            "moment_reference_x_m": self.moment_reference_x,
            "includes": list(self.includes),
            "axes": axes,
            "frame": FRAME_CONVENTION,
            "units": {**{n: a["unit"] for n, a in axes.items()},
                      **{c: "-" for c in self.coefficient_names}},
        }
        doc.update(self._metadata)
        doc.setdefault("transonic_bridge", False)
        doc.setdefault("generator", "ironbark_opt")
        if doc["generator"] == "ironbark_opt":
            from ironbark_opt import __version__
            doc.setdefault("generator_version", __version__)
        return doc

    def save(self, path) -> tuple[Path, Path]:
        """Write ``<stem>.csv`` (long format) and ``<stem>.json``; numeric-only.

        Returns the two paths written.
        """
        import os
        stem = _stem(path)
        # append (not with_suffix): a stem with dots, "01.One-stage_OR22.02", keeps its whole name
        csv_path, json_path = Path(f"{stem}.csv"), Path(f"{stem}.json")
        axis_cols = self._axis_columns()
        names = self.coefficient_names
        grids = np.meshgrid(*[v for _, v in axis_cols], indexing="ij")
        tmp_csv, tmp_json = Path(f"{csv_path}.tmp{os.getpid()}"), Path(f"{json_path}.tmp{os.getpid()}")
        try:                # temporary files + os.replace: never a partial table
            with open(tmp_csv, "w", newline="") as fh:
                w = csv.writer(fh)
                w.writerow([n for n, _ in axis_cols] + list(names))
                for idx in np.ndindex(*grids[0].shape):
                    w.writerow([repr(float(g[idx])) for g in grids]
                               + [repr(float(self._splines[c].values[idx])) for c in names])
            with open(tmp_json, "w") as fh:
                json.dump(self.to_json_dict(), fh, indent=2)
                fh.write("\n")
            os.replace(tmp_csv, csv_path)
            os.replace(tmp_json, json_path)
        finally:
            for tmp in (tmp_csv, tmp_json):
                if tmp.exists():
                    tmp.unlink()
        return csv_path, json_path

    @classmethod
    def load(cls, path) -> "AeroTable":
        """Read ``<stem>.csv`` + ``<stem>.json`` (``path`` may name either or the stem).

        Numeric-only.  Raises `InputError` naming the file, line and column when
        the metadata is incomplete, a value is not a number, or the grid is not
        sorted (mach, then alpha_deg[, then reynolds], increasing) and complete.
        """
        stem = _stem(path)
        csv_path, json_path = Path(f"{stem}.csv"), Path(f"{stem}.json")
        meta = _read_json(json_path)
        axes, coeffs = _read_grid_csv(csv_path)
        listed = meta.get("coefficients")
        if listed is not None and sorted(listed) != sorted(coeffs):
            raise InputError(f"the JSON lists coefficients {listed} but the CSV has columns "
                             f"{list(coeffs)}", source=json_path, field="coefficients")
        extra = {k: v for k, v in meta.items() if k not in _RESERVED}
        return cls(axes["mach"], np.radians(axes["alpha_deg"]), coeffs,
                   reference_area=_meta_number(meta, "reference_area_m2", json_path),
                   reference_length=_meta_number(meta, "reference_length_m", json_path),
                   moment_reference_x=_meta_number(meta, "moment_reference_x_m", json_path),
                   includes=tuple(meta.get("includes", ("pressure",))), metadata=extra,
                   reynolds=axes.get("reynolds"), source=str(csv_path))


def _axis(values, name: str, source) -> np.ndarray:
    arr = np.atleast_1d(np.asarray(values, dtype=float))
    if arr.ndim != 1 or arr.size == 0:
        raise InputError(f"'{name}' must be a non-empty 1-D array", source=source, field=name)
    if not np.all(np.isfinite(arr)) or np.any(np.diff(arr) <= 0):
        raise InputError(f"'{name}' must be finite and strictly increasing", source=source,
                         field=name)
    return arr


def _stem(path) -> Path:
    p = Path(path)
    return p.with_suffix("") if p.suffix.lower() in (".csv", ".json") else p


def _read_json(path: Path) -> dict:
    if not path.exists():
        raise InputError("metadata file not found: an AeroTable is a CSV plus a JSON file of the "
                         "same name (reference area, length, moment reference point)", source=path)
    try:
        with open(path) as fh:
            doc = json.load(fh)
    except json.JSONDecodeError as err:
        raise InputError(f"not valid JSON: {err.msg}", source=path, line=err.lineno) from None
    if not isinstance(doc, dict):
        raise InputError("expected a JSON object at the top level", source=path)
    if doc.get("format", FORMAT_NAME) != FORMAT_NAME:
        raise InputError(f"format is {doc['format']!r}, expected {FORMAT_NAME!r}", source=path,
                         field="format")
    return doc


def _meta_number(meta: dict, key: str, path: Path) -> float:
    if key not in meta:
        raise InputError("missing (a number, SI unit as in the key's suffix)", source=path, field=key)
    val = meta[key]
    if isinstance(val, bool) or not isinstance(val, (int, float)):
        raise InputError(f"expected a number, got {val!r}", source=path, field=key)
    return float(val)


def _read_grid_csv(path: Path):
    """Read a long-format grid CSV -> ({axis: values}, {name: array on the grid})."""
    if not path.exists():
        raise InputError("table file not found", source=path)
    rows: list[tuple[int, list[str]]] = []
    header = None
    with open(path, newline="") as fh:
        for lineno, rec in enumerate(csv.reader(fh), start=1):
            if not rec or not "".join(rec).strip() or rec[0].lstrip().startswith("#"):
                continue
            if header is None:
                header, header_line = [h.strip() for h in rec], lineno
            else:
                rows.append((lineno, rec))
    if header is None:
        raise InputError("empty file: expected a header 'mach,alpha_deg,<coefficients>'", source=path)
    for col in ("mach", "alpha_deg"):
        if col not in header:
            raise InputError(f"missing column '{col}' in header {header}", source=path,
                             line=header_line, field=col)
    if len(set(header)) != len(header):
        raise InputError(f"duplicate column names in header {header}", source=path, line=header_line)
    axis_names = [a for a in ("mach", "alpha_deg", "reynolds") if a in header]
    names = [h for h in header if h not in axis_names]
    if not names or not rows:
        raise InputError("no coefficient columns or no data rows", source=path, line=header_line)
    data = np.empty((len(rows), len(header)))
    for r, (lineno, rec) in enumerate(rows):
        if len(rec) != len(header):
            raise InputError(f"{len(rec)} values, expected {len(header)} ({', '.join(header)})",
                             source=path, line=lineno)
        for c, (txt, col) in enumerate(zip(rec, header)):
            try:
                data[r, c] = float(txt)
            except ValueError:
                raise InputError(f"{txt.strip()!r} is not a number", source=path, line=lineno,
                                 field=col) from None
            if not math.isfinite(data[r, c]):
                raise InputError(f"{txt.strip()!r} is not finite", source=path, line=lineno,
                                 field=col)
    idx = [header.index(a) for a in axis_names]
    keys = [tuple(row) for row in data[:, idx]]
    for r in range(1, len(rows)):
        if keys[r] <= keys[r - 1]:
            what = "repeats" if keys[r] == keys[r - 1] else "comes after"
            col = next(a for a, x, y in zip(axis_names, keys[r], keys[r - 1]) if x != y) \
                if keys[r] != keys[r - 1] else axis_names[-1]
            raise InputError(f"grid point {_point(axis_names, keys[r])} {what} "
                             f"{_point(axis_names, keys[r - 1])}: rows must be sorted by "
                             f"{', then '.join(axis_names)}, each point once", source=path,
                             line=rows[r][0], field=col)
    axes = {a: np.unique(data[:, i]) for a, i in zip(axis_names, idx)}
    shape = tuple(v.size for v in axes.values())
    if len(rows) != math.prod(shape):
        have = set(keys)
        missing = next(p for p in np.ndindex(*shape)
                       if tuple(axes[a][k] for a, k in zip(axis_names, p)) not in have)
        point = tuple(axes[a][k] for a, k in zip(axis_names, missing))
        raise InputError(f"incomplete grid: no row for {_point(axis_names, point)} ({len(rows)} "
                         f"rows for a {' x '.join(map(str, shape))} grid)", source=path)
    return axes, {n: data[:, header.index(n)].reshape(shape) for n in names}


def _point(names, values) -> str:
    return ", ".join(f"{n} {v:g}" for n, v in zip(names, values))
