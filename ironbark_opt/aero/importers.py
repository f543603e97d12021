"""Import external aerodynamic tables into `AeroTable`.

- `from_cd_mach_csv`: drag-coefficient-vs-Mach curves, power off and optionally power on:
  RocketPy-style two-column files without a header (``mach,cd``), and RASAero /
  OpenRocket / spreadsheet exports with a header whose columns are matched by name
  ("Mach", "CD", "CD Power-Off", "CD Power-On", "CA Power-Off", "Drag coefficient", ...).
- `from_coefficient_csv`: full coefficient tables (CFD, panel codes, wind tunnel) with
  named columns ``mach``, ``alpha_deg`` or ``alpha_rad``, and any of ``CA``, ``CN``, ``Cm``,
  ``CY``, ``Cn``, ``Cl`` (or ``CD`` + ``CL``, converted to body axes).

Real Cd-vs-Mach files are often unsorted and repeat Mach values (flight-derived or
digitised curves).  Rows are sorted by Mach; repeated Mach values with equal Cd are
merged; repeated Mach values with different Cd raise `InputError` naming both lines,
unless ``duplicates="mean"`` asks for their average.

All functions here are numeric-only (file I/O).
"""
from __future__ import annotations

import csv
import math
import io
import re
import warnings
from pathlib import Path

import numpy as np

from ironbark_opt.aero.table import AeroTable, GridSpline
from ironbark_opt.errors import InputError, OutOfRangeWarning
from ironbark_opt.validate import is_float

_DUPLICATE_POLICIES = ("error", "mean")
_POWER_OFF_NAMES = ("cdpoweroff", "capoweroff", "cdoff", "cd", "cd0", "dragcoefficient", "ca")
_POWER_ON_NAMES = ("cdpoweron", "capoweron", "cdon")
_MACH_NAMES = ("mach", "machnumber", "m")
_ALPHA_NAMES = {"alphadeg": "deg", "alpharad": "rad", "alpha": None, "aoa": None, "aoadeg": "deg"}
_COEFFICIENTS = ("CA", "CN", "Cm", "CY", "Cn", "Cl")


def _norm(name: str) -> str:
    """'CD Power-Off (-)' -> 'cdpoweroff'; 'alpha [deg]' -> 'alphadeg'."""
    name = name.replace("\u200b", "").strip().lstrip("#").strip()
    unit = re.search(r"[\(\[]\s*(deg|rad)\w*\s*[\)\]]", name, flags=re.I)
    base = re.sub(r"[\(\[].*?[\)\]]", "", name)
    base = re.sub(r"[^0-9a-z]", "", base.lower())
    return base + (unit.group(1).lower() if unit else "")


def _decoded_text(path) -> str:
    """The file's text (UTF-8, a byte-order mark dropped); a binary file or a directory
    is an InputError naming the file."""
    try:
        return path.read_bytes().decode("utf-8-sig")
    except UnicodeDecodeError as exc:
        raise InputError(f"not a UTF-8 text file (byte {exc.start}); expected a CSV of Mach and Cd",
                         source=path) from None
    except IsADirectoryError:
        raise InputError("is a directory, expected a CSV file", source=path) from None


def _read_numeric_csv(path):
    """-> (header list or None, header line, [(lineno, [float, ...])]).

    Skips blank lines and lines starting with '#', except that a '#' line directly followed
    by data and containing the same number of fields is taken as a header (OpenRocket).
    """
    path = Path(path)
    if not path.exists():
        raise InputError("file not found", source=path)
    header, header_line, rows, last_comment = None, None, [], None
    with io.StringIO(_decoded_text(path), newline="") as fh:
        for lineno, rec in enumerate(csv.reader(fh), start=1):
            rec = [f.strip() for f in rec]
            while rec and rec[-1] == "":
                rec.pop()
            if not rec:
                continue
            if rec[0].startswith("#"):
                last_comment = (lineno, rec)
                continue
            try:
                values = [float(f) for f in rec]
            except ValueError:
                if header is None and not rows and not any(is_float(f) for f in rec):
                    header, header_line = rec, lineno
                    continue
                bad = next(f for f in rec if not is_float(f))
                col = header[rec.index(bad)] if header and rec.index(bad) < len(header) else None
                raise InputError(f"{bad!r} is not a number", source=path, line=lineno,
                                 field=col) from None
            if header is None and not rows and last_comment and len(last_comment[1]) == len(rec):
                header, header_line = last_comment[1], last_comment[0]
            width = len(header) if header else (len(rows[0][1]) if rows else len(values))
            if len(values) != width:
                raise InputError(f"{len(values)} values, expected {width}", source=path, line=lineno)
            if not all(math.isfinite(v) for v in values):
                raise InputError("value is not finite", source=path, line=lineno)
            rows.append((lineno, values))
    if not rows:
        raise InputError("no numeric data rows", source=path)
    return header, header_line, rows


def _read_text_csv(path):
    """-> (header, header line, [(lineno, [str, ...])]) of a CSV that must have a header."""
    path = Path(path)
    if not path.exists():
        raise InputError("file not found", source=path)
    header, hline, rows = None, None, []
    with io.StringIO(_decoded_text(path), newline="") as fh:
        for lineno, rec in enumerate(csv.reader(fh), start=1):
            rec = [f.strip() for f in rec]
            if not any(rec) or rec[0].startswith("#"):
                continue
            if header is None:
                if all(is_float(f) for f in rec if f):
                    raise InputError("a coefficient table needs a header (mach, alpha_deg, CA, CN, "
                                     "Cm, ...)", source=path, line=lineno)
                header, hline = rec, lineno
                continue
            if len(rec) != len(header):
                raise InputError(f"{len(rec)} values, expected {len(header)} ({', '.join(header)})",
                                 source=path, line=lineno)
            rows.append((lineno, rec))
    if header is None or not rows:
        raise InputError("no header or no data rows", source=path)
    return header, hline, rows


def _numeric_column(rows, i, header, path) -> np.ndarray:
    out = np.empty(len(rows))
    for k, (lineno, rec) in enumerate(rows):
        try:
            out[k] = float(rec[i])
        except ValueError:
            raise InputError(f"{rec[i]!r} is not a number", source=path, line=lineno,
                             field=header[i]) from None
        if not math.isfinite(out[k]):
            raise InputError(f"{rec[i]!r} is not finite", source=path, line=lineno, field=header[i])
    return out


def _find_column(header, candidates, path, line, what):
    normed = [_norm(h) for h in header]
    for cand in candidates:
        if cand in normed:
            return normed.index(cand)
    raise InputError(f"no {what} column; header is {header}, expected one of "
                     f"{list(candidates)} (case, spaces and units ignored)", source=path, line=line)


def _merge_sorted(mach, values, lines, path, duplicates, field):
    """Sort by Mach; merge equal repeats; conflicting repeats -> error or mean."""
    order = np.argsort(mach, kind="stable")
    mach, values, lines = mach[order], values[order], [lines[i] for i in order]
    out_m, out_v = [], []
    i = 0
    while i < mach.size:
        j = i
        while j + 1 < mach.size and mach[j + 1] == mach[i]:
            j += 1
        group = values[i:j + 1]
        tol = 1e-12 * max(1.0, np.max(np.abs(group)))
        if np.ptp(group) > tol:
            if duplicates == "error":
                k = int(np.argmax(np.abs(group - group[0]) > tol))   # the first row that differs
                raise InputError(f"Mach {mach[i]:.10g} appears on lines {lines[i]} and "
                                 f"{lines[i + k]} with different values {group[0]:.10g} and "
                                 f"{group[k]:.10g}; to average repeated Mach values set "
                                 f"drag_duplicates = \"mean\" in the rocket file's [aero] "
                                 f"(Python: duplicates='mean')",
                                 source=path, line=lines[i + k], field=field)
        out_m.append(mach[i])
        out_v.append(float(np.mean(group)))
        i = j + 1
    return np.array(out_m), np.array(out_v)


_CD_MAX = 5.0      # [-] largest plausible whole-rocket drag coefficient


def _read_cd_curves(path, names, duplicates, want_power_on):
    """-> {'CA': (mach, cd), maybe 'CA_power_on': (mach, cd)} from one file."""
    header, hline, rows = _read_numeric_csv(path)
    data = np.array([r[1] for r in rows])
    lines = [r[0] for r in rows]
    if header is None:
        if data.shape[1] != 2:
            raise InputError(f"a file without a header must have 2 columns (mach, cd), found "
                             f"{data.shape[1]}", source=path, line=lines[0])
        im, icols = 0, {"CA": 1}
    else:
        im = _find_column(header, _MACH_NAMES, path, hline, "Mach")
        icols = {"CA": _find_column(header, names, path, hline, "drag coefficient")}
        normed = [_norm(h) for h in header]
        if want_power_on and any(n in normed for n in _POWER_ON_NAMES):
            icols["CA_power_on"] = _find_column(header, _POWER_ON_NAMES, path, hline, "power-on")
        ia = next((normed.index(n) for n in _ALPHA_NAMES if n in normed), None)
        if ia is not None:  # keep the zero-angle-of-attack rows (RASAero exports all alphas)
            keep = data[:, ia] == 0.0
            if not np.any(keep):
                raise InputError("the file has an angle-of-attack column but no rows at alpha = 0",
                                 source=path, line=hline, field=header[ia])
            data, lines = data[keep], [ln for ln, k in zip(lines, keep) if k]
    if np.any(data[:, im] < 0):
        bad = lines[int(np.argmax(data[:, im] < 0))]
        raise InputError("negative Mach number", source=path, line=bad, field="mach")
    if data.shape[0] < 2:
        raise InputError(f"a drag curve needs at least 2 rows (Mach, Cd), found {data.shape[0]}",
                         source=path, line=lines[0] if lines else None, field="mach")
    # a plain (mach, cd) table is typed in Mach order: a step back is a typo.  Files with a
    # header may be exported time series (OpenRocket: Mach rises and falls) and are sorted,
    # and so is a plain table whose Mach never rises (a descending one: hedy's coast-phase
    # power-off curve, RocketPy's docs/examples data/rockets/hedy, runs Mach 1.748 down to 0.157).
    # A step back that only repeats rows already read (same Mach, same values) is no typo
    # either: the Space Enterprise at Berkeley curve (RocketPy docs/examples
    # data/rockets/berkeley/drag.csv) is one Mach 0.01..25 curve written out three times.
    steps = np.diff(data[:, im])
    descending = header is None and not np.any(steps > 0)
    back = np.flatnonzero(steps < 0) if header is None and not descending else np.array([], int)
    if back.size:
        first = {}                                   # Mach -> its first row
        for k in range(data.shape[0]):
            first.setdefault(float(data[k, im]), k)
        top = np.maximum.accumulate(data[:, im])
        for k in range(1, data.shape[0]):
            j = first[float(data[k, im])]
            if data[k, im] < top[k - 1] and not (j < k and np.array_equal(data[k], data[j])):
                raise InputError(f"Mach must increase down the file (or decrease throughout): "
                                 f"{data[k, im]:g} follows {data[k - 1, im]:g}", source=path,
                                 line=lines[k], field="mach")
    for ic in icols.values():
        field = header[ic] if header else "cd"
        # Cd of a whole rocket: 0.2-1.5 typical (Hoerner, Fluid-Dynamic Drag); over 5 is not a rocket
        bad = np.flatnonzero((data[:, ic] < 0) | (data[:, ic] > _CD_MAX))
        if bad.size:
            i = int(bad[0])
            raise InputError(f"drag coefficient {data[i, ic]:g} is outside [0, {_CD_MAX:g}]",
                             source=path, line=lines[i], field=field)
    out = {}
    for cname, ic in icols.items():
        field = header[ic] if header else "cd"
        out[cname] = _merge_sorted(data[:, im], data[:, ic], lines, path, duplicates, field)
    return out


def _on_grid(mach, values, grid, path, name):
    """Resample a curve onto ``grid`` by its own interpolating spline; hold its end values."""
    if mach.size == grid.size and np.array_equal(mach, grid):
        return values
    if mach.size == 1:
        return np.full(grid.size, values[0])
    if grid[0] < mach[0] or grid[-1] > mach[-1]:
        warnings.warn(f"{path}: {name} covers Mach {mach[0]:g}..{mach[-1]:g} only; held constant "
                      f"outside to match the other curve's Mach range", OutOfRangeWarning,
                      stacklevel=3)
    # the same interpolating not-a-knot B-spline GridSpline uses, evaluated by CasADi
    # (no SciPy import on the simulate path; agreement with SciPy's make_interp_spline
    # measured in tests/unit/test_aero_importers.py)
    spline = GridSpline([mach], values, name=name, axis_names=["mach"]).casadi_interpolant()
    return np.asarray(spline(np.clip(grid, mach[0], mach[-1]).reshape(1, -1))).ravel()


def from_cd_mach_csv(power_off_path, power_on_path=None, *, reference_area: float,
                     reference_length: float, moment_reference_x: float = 0.0,
                     duplicates: str = "error", metadata: dict | None = None) -> AeroTable:
    """AeroTable with ``CA`` (and ``CA_power_on``) from Cd-vs-Mach files; numeric-only.

    Parameters
    ----------
    power_off_path : path
        Headerless ``mach,cd`` (RocketPy) or a CSV with named columns (RASAero,
        OpenRocket).  If it also has a power-on column (RASAero "CD Power-On") and
        ``power_on_path`` is None, that column gives ``CA_power_on``.
    power_on_path : path, optional
        The power-on curve, same formats.
    reference_area : float [m^2]
        Area the Cd values are referred to (usually the body cross-section).
    reference_length : float [m]
    moment_reference_x : float [m aft of the nose tip]
        Irrelevant for drag-only tables; stored for completeness.
    duplicates : {"error", "mean"}
        What to do with a Mach value repeated with different Cd values.
    metadata : dict, optional
        Extra metadata; ``source_files`` is added.

    The result has a single angle of attack (0): drag independent of alpha, CA = Cd.
    Both curves share one Mach grid (the union of the files' Mach values); a curve is
    resampled on it by its own spline and held constant beyond its own range (with an
    `OutOfRangeWarning`).  ``includes`` = ("pressure", "friction", "base").
    """
    if duplicates not in _DUPLICATE_POLICIES:
        raise InputError(f"expected one of {_DUPLICATE_POLICIES}, got {duplicates!r}",
                         field="duplicates")
    curves = _read_cd_curves(power_off_path, _POWER_OFF_NAMES, duplicates,
                             want_power_on=power_on_path is None)
    if power_on_path is not None:
        on = _read_cd_curves(power_on_path, _POWER_ON_NAMES + _POWER_OFF_NAMES, duplicates,
                             want_power_on=False)
        curves["CA_power_on"] = on["CA"]
    grid = np.unique(np.concatenate([m for m, _ in curves.values()]))
    coeffs = {}
    for name, (m, v) in curves.items():
        src = power_on_path if name == "CA_power_on" and power_on_path else power_off_path
        coeffs[name] = _on_grid(m, v, grid, src, name).reshape(-1, 1)
    meta = dict(metadata or {})
    meta.setdefault("generator", "ironbark_opt.aero.importers.from_cd_mach_csv")
    meta["source_files"] = [str(p) for p in (power_off_path, power_on_path) if p is not None]
    return AeroTable(grid, [0.0], coeffs, reference_area=reference_area,
                     reference_length=reference_length, moment_reference_x=moment_reference_x,
                     includes=("pressure", "friction", "base"), metadata=meta,
                     source=str(power_off_path))


def from_coefficient_csv(path, *, reference_area: float, reference_length: float,
                         moment_reference_x: float, includes=("pressure",),
                         alpha_unit: str | None = None, select: dict | None = None,
                         metadata: dict | None = None) -> AeroTable:
    """AeroTable from a full coefficient table with named columns; numeric-only.

    Parameters
    ----------
    path : path
        CSV with a header; '#' lines are comments.  Columns: ``mach``; ``alpha_deg`` or
        ``alpha_rad`` (or ``alpha`` with ``alpha_unit``); coefficients ``CA``, ``CN``, ``Cm``,
        ``CY``, ``Cn``, ``Cl`` (case matters: ``CL`` is lift, ``Cl`` roll moment; ``CM`` is
        read as ``Cm``).  Without ``CA``/``CN`` but with ``CD`` and ``CL`` (wind axes) they are
        converted: CA = CD cos a - CL sin a, CN = CL cos a + CD sin a.  Other columns are
        ignored (listed in the metadata).  Rows may come in any order; the (mach, alpha)
        grid must be complete.
    reference_area : float [m^2]
    reference_length : float [m]
    moment_reference_x : float [m aft of the nose tip]
        Point the table's Cm is about.
    includes : tuple of str
        Which drag parts the table's CA contains.
    alpha_unit : {"deg", "rad"}, optional
        Unit of a column named plain ``alpha``.
    select : dict[str, str], optional
        Keep only rows whose text in the named column equals the value
        (e.g. ``{"mesh": "fine"}``); non-numeric columns are otherwise ignored.
    """
    header, hline, rows = _read_text_csv(path)
    for col, wanted in (select or {}).items():
        if col not in header:
            raise InputError(f"select: no column '{col}' in {header}", source=path, line=hline,
                             field=col)
        rows = [r for r in rows if r[1][header.index(col)] == str(wanted)]
        if not rows:
            raise InputError(f"select: no row has {col} = {wanted!r}", source=path, field=col)
    lines = [r[0] for r in rows]
    normed = [_norm(h) for h in header]
    im = _find_column(header, _MACH_NAMES, path, hline, "Mach")
    ia = next((normed.index(n) for n in _ALPHA_NAMES if n in normed), None)
    if ia is None:
        raise InputError(f"no angle-of-attack column in {header}; expected alpha_deg or alpha_rad",
                         source=path, line=hline)
    unit = _ALPHA_NAMES[normed[ia]] or alpha_unit
    if unit not in ("deg", "rad"):
        raise InputError(f"column '{header[ia]}' does not say its unit: name it alpha_deg or "
                         f"alpha_rad, or pass alpha_unit='deg'/'rad'", source=path, line=hline,
                         field=header[ia])
    mach = _numeric_column(rows, im, header, path)
    alpha_in = _numeric_column(rows, ia, header, path)
    alpha = np.radians(alpha_in) if unit == "deg" else alpha_in
    columns = {}
    for i, h in enumerate(header):
        key = h.strip().split("(")[0].split("[")[0].strip()
        key = "Cm" if key == "CM" else key
        if key in _COEFFICIENTS + ("CD", "CL"):
            columns.setdefault(key, i)
    wanted = [k for k in _COEFFICIENTS if k in columns]
    convert = "CA" not in columns and "CD" in columns
    if convert:
        wanted += [k for k in ("CD", "CL") if k in columns]
    named = {k: _numeric_column(rows, columns[k], header, path) for k in wanted}
    used = [header[im], header[ia], *(select or {}), *(header[columns[k]] for k in wanted)]
    if convert and ("CL" in named or np.all(alpha == 0)):
        cl = named.get("CL", np.zeros_like(alpha))
        named["CA"] = named["CD"] * np.cos(alpha) - cl * np.sin(alpha)
        if "CN" not in named and "CL" in named:
            named["CN"] = cl * np.cos(alpha) + named["CD"] * np.sin(alpha)
    coeffs_flat = {k: v for k, v in named.items() if k in _COEFFICIENTS}
    if not coeffs_flat:
        raise InputError(f"no coefficient columns in {header}; expected some of "
                         f"{list(_COEFFICIENTS)} (or CD and CL)", source=path, line=hline)
    # sort rows by (mach, alpha); check the grid is complete, merge exact repeats
    order = np.lexsort((alpha, mach))
    mach_s, alpha_s = mach[order], alpha[order]
    keep = np.ones(order.size, bool)
    for k in range(1, order.size):
        if mach_s[k] == mach_s[k - 1] and alpha_s[k] == alpha_s[k - 1]:
            a, b = order[k - 1], order[k]
            if any(v[a] != v[b] for v in coeffs_flat.values()):
                raise InputError(f"grid point (mach {mach_s[k]:g}, alpha {alpha_in[b]:g}) appears "
                                 f"on lines {lines[a]} and {lines[b]} with different values",
                                 source=path, line=lines[b])
            keep[k] = False
    order = order[keep]
    mach_u, alpha_u = np.unique(mach[order]), np.unique(alpha[order])
    if order.size != mach_u.size * alpha_u.size:
        have = {(mach[i], alpha[i]) for i in order}
        m, a = next((m, a) for m in mach_u for a in alpha_u if (m, a) not in have)
        raise InputError(f"incomplete grid: no row for mach {m:g}, alpha {math.degrees(a):g} deg",
                         source=path)
    shape = (mach_u.size, alpha_u.size)
    coeffs = {k: v[order].reshape(shape) for k, v in coeffs_flat.items()}
    meta = dict(metadata or {})
    meta.setdefault("generator", "ironbark_opt.aero.importers.from_coefficient_csv")
    meta["source_files"] = [str(path)]
    meta["ignored_columns"] = [h for h in header if h not in used]
    return AeroTable(mach_u, alpha_u, coeffs, reference_area=reference_area,
                     reference_length=reference_length, moment_reference_x=moment_reference_x,
                     includes=includes, metadata=meta, source=str(path))
