"""Parsers for the outputs of PANAIR (A502): ``ffmf``, ``panair.out``,
``agps`` and ``panair.err``.

Formats were read from real runs (``tests/data/panair``): the force and
moment summary prints, per solution, ``sol alpha beta cl cdi cy fx fy fz``
then ``mx my mz area``; fx, fy, fz are body-axis force coefficients
(x aft, z up), my is positive nose-up about (xref, yref, zref).  Only kt=1
networks are summed (no base, no wakes) and they are pressure forces only.

All functions are numeric-only (file I/O).
"""
from __future__ import annotations

import re
from dataclasses import dataclass
from os import PathLike
from pathlib import Path

import numpy as np

from ironbark_opt.errors import InputError, SolverError

__all__ = ["ForceSummary", "read_ffmf", "read_panair_out_summary", "read_agps",
           "check_panair_err"]

_SUMMARY_FIELDS = ("alpha_deg", "beta_deg", "cl", "cdi", "cy", "fx", "fy", "fz",
                   "mx", "my", "mz", "area")


@dataclass(frozen=True)
class ForceSummary:
    """One solution of a PANAIR full-configuration force/moment summary.

    Attributes: ``solution`` (1-based), ``alpha_deg``/``beta_deg`` [deg],
    ``cl``, ``cdi``, ``cy`` (wind axes) and ``fx``, ``fy``, ``fz`` (body
    axes: x aft, z up) force coefficients [-], ``mx``, ``my``, ``mz``
    moment coefficients [-] (``my`` positive nose-up), ``area`` [length^2
    of the deck] wetted area of the summed networks.
    ``CA = fx``, ``CN = fz``, ``Cm = my`` in Ironbark's body-axis names.
    """

    solution: int
    alpha_deg: float
    beta_deg: float
    cl: float
    cdi: float
    cy: float
    fx: float
    fy: float
    fz: float
    mx: float
    my: float
    mz: float
    area: float

    @property
    def CA(self) -> float:
        """Axial force coefficient (positive aft) [-]."""
        return self.fx

    @property
    def CN(self) -> float:
        """Normal force coefficient (positive up) [-]."""
        return self.fz

    @property
    def Cm(self) -> float:
        """Pitching moment coefficient (positive nose-up) [-]."""
        return self.my


def _read_lines(path) -> list[str]:
    path = Path(path)
    try:
        return path.read_text(errors="replace").splitlines()
    except OSError as exc:
        raise InputError(f"cannot read PANAIR output: {exc.strerror}", source=path) from exc


def _floats(tokens, path, line):
    out = []
    for t in tokens:
        try:
            out.append(float(t))
        except ValueError as exc:
            # Fortran overflow prints '*****': a garbage solution, not a number.
            raise InputError(f"expected a number in the force summary, got {t!r} "
                             "(PANAIR overflow field?)", source=path, line=line) from exc
    return out


def _parse_summary(lines, start, path) -> list[ForceSummary]:
    """Parse summary rows after the header at index ``start``."""
    rows = []
    k = start
    # skip to the dashed line under the header
    while k < len(lines) and not lines[k].strip().startswith("------"):
        k += 1
    k += 1
    while k < len(lines):
        s = lines[k].split()
        if not s:
            k += 1
            continue
        if s[0].startswith("*") or not re.fullmatch(r"\d+", s[0]):
            break
        if len(s) != 9:
            raise InputError(f"force summary row must have 9 fields, got {len(s)}",
                             source=path, line=k + 1)
        first = _floats(s[1:], path, k + 1)
        k += 1
        while k < len(lines) and not lines[k].strip():
            k += 1
        s2 = lines[k].split() if k < len(lines) else []
        if len(s2) != 4:
            raise InputError("force summary: expected 'mx my mz area' after the force row",
                             source=path, line=k + 1)
        second = _floats(s2, path, k + 1)
        rows.append(ForceSummary(int(s[0]), *first, *second))
        k += 1
    if not rows:
        raise InputError("force summary has no solutions", source=path, line=start + 1)
    return rows


def read_ffmf(path: str | PathLike) -> list[ForceSummary]:
    """Read PANAIR's ``ffmf`` (full-configuration force/moment summary).

    Parameters
    ----------
    path : str or path-like
        The ``ffmf`` file.

    Returns
    -------
    list of ForceSummary, one per solution (angle of attack / sideslip).
    """
    lines = _read_lines(path)
    for k, ln in enumerate(lines):
        if "sol-no" in ln:
            return _parse_summary(lines, k, path)
    raise InputError("no 'sol-no' header: not a PANAIR force summary", source=path)


def read_panair_out_summary(path: str | PathLike) -> list[ForceSummary]:
    """Read the *full configuration forces and moments summary* in ``panair.out``.

    Parameters
    ----------
    path : str or path-like
        PANAIR's listing ``panair.out``.

    Returns
    -------
    list of ForceSummary (the same numbers as ``ffmf``).
    """
    lines = _read_lines(path)
    for k, ln in enumerate(lines):
        if "full configuration forces and moments summary" in ln:
            for j in range(k, min(k + 40, len(lines))):
                if "sol-no" in lines[j]:
                    return _parse_summary(lines, j, path)
    raise InputError("no 'full configuration forces and moments summary' in the listing "
                     "(did PANAIR stop early? read panair.err)", source=path)


def read_agps(path: str | PathLike) -> dict[int, list[np.ndarray]]:
    """Read PANAIR's ``agps`` file (surface Cp at grid points).

    Parameters
    ----------
    path : str or path-like
        The ``agps`` file.

    Returns
    -------
    dict network number (1-based) -> list of arrays, one per grid column,
    each of shape (n_rows, 3 + n_solutions): ``x, y, z, cp1, cp2, ...``
    (coordinates in deck units, Cp by the pressure rule the deck asked for).
    """
    lines = _read_lines(path)
    out: dict[int, list[np.ndarray]] = {}
    k = 0
    n_sol = None
    while k < len(lines):
        m = re.match(r"^n(\d+)c(\d+)\s*$", lines[k].strip())
        if not m:
            k += 1
            continue
        net = int(m.group(1))
        k += 1
        if k < len(lines) and lines[k].split()[:1] == ["irow"]:
            # the header is printed before the first column of a file only
            n_sol = len(lines[k].split()) - 4
            k += 1
        if n_sol is None:
            raise InputError("expected an 'irow x y z cp1 ...' header after the first column name",
                             source=path, line=k + 1)
        ncols = n_sol + 4
        rows = []
        while k < len(lines) and not lines[k].strip().startswith("*eof"):
            s = lines[k].split()
            if s:
                if len(s) != ncols:
                    raise InputError(f"agps row must have {ncols} fields, got {len(s)}",
                                     source=path, line=k + 1)
                rows.append(_floats(s[1:], path, k + 1))
            k += 1
        out.setdefault(net, []).append(np.array(rows, dtype=float).reshape(-1, ncols - 1))
        k += 1
    if not out:
        raise InputError("no network columns (nXXcYYY) in agps file", source=path)
    return out


_FATAL = re.compile(r"stopping|fatal|abnormal|error", re.IGNORECASE)


def check_panair_err(path: str | PathLike) -> list[str]:
    """Check PANAIR's ``panair.err`` for a stop (PANAIR exits 0 even then).

    Parameters
    ----------
    path : str or path-like
        The ``panair.err`` file.

    Returns
    -------
    list of str
        Lines mentioning warnings (e.g. superinclined panels), possibly empty.

    Raises
    ------
    SolverError
        If PANAIR stopped on an error ("PanAir is stopping", fatal errors),
        or the file is missing (PANAIR did not run); the message quotes it.
    """
    path = Path(path)
    if not path.exists():
        raise SolverError(f"{path}: no panair.err: PANAIR did not run in this directory")
    lines = path.read_text(errors="replace").splitlines()
    bad = [ln.strip() for ln in lines if _FATAL.search(ln)]
    if bad:
        raise SolverError(f"{path}: PANAIR stopped: " + " | ".join(bad[:5]))
    return [ln.strip() for ln in lines if re.search(r"warn|superincl", ln, re.IGNORECASE)]
