"""PANAIR (A502) interoperability: deck writer and external-PANAIR runner.

The deck is written the way PANIN (the PDAS preprocessor) writes it from a
LaWGS file and an ``.aux`` command file (format read from real decks in
``tests/data/panair``): fixed 10-column fields, ``$POINTS`` groups with
the network's boundary-condition type ``kt`` (1 impermeable surface,
5 base, 18 wake; a base-wake tube is PANIN's ``-18``, written ``18 1``),
``nm`` points per column and ``nn`` columns, two points per line.

The runner executes a user-installed PANAIR (``IRONBARK_PANAIR`` or
``panair`` on PATH) in a fresh directory per case (PANAIR leaves stale
scratch files that corrupt later runs), checks ``panair.err`` (PANAIR
exits 0 even when it stops on an error) and parses ``ffmf`` and ``agps``.

Numeric-only (file I/O and subprocesses).  Lengths in the deck are in
whatever unit the networks use; reference quantities must match.
"""
from __future__ import annotations

import os
import shutil
import subprocess
import tempfile
from dataclasses import dataclass
from os import PathLike
from pathlib import Path

import numpy as np

from ironbark_opt.errors import InputError, SolverError

from .a502_output import ForceSummary, check_panair_err, read_agps, read_ffmf

__all__ = ["write_a502", "find_panair", "run_panair", "PanairRun"]

_KT = {"surface": 1, "base": 5, "wake": 18}


def _f10(v: float, decimals: int = 6) -> str:
    """A number in a 10-column field with as many decimals as fit."""
    for d in range(decimals, -1, -1):
        s = f"{v:10.{d}f}"
        if len(s) <= 10:
            return s
    raise InputError(f"value {v} does not fit a 10-column PANAIR field", field="deck")


def _kt_of(net) -> int:
    return int(net.meta.get("kt", _KT[net.kind]))


def write_a502(path: str | PathLike, networks, *, mach: float, alpha_deg, beta_deg=0.0,
               alpc_deg: float | None = None, sref: float, cref: float, bref: float = 1.0,
               dref: float | None = None, xref: float = 0.0, zref: float = 0.0,
               symmetric: bool = True, title: str = "Ironbark-Opt panel networks") -> Path:
    """Write a PANAIR A502 input deck (``a502.in``).

    Parameters
    ----------
    path : str or path-like
        Output deck.
    networks : sequence of panair.lawgs.Network
        ``meta["kt"]`` overrides the kt derived from ``kind`` (use -18 for a
        base-wake tube).
    mach : float [-]
    alpha_deg, beta_deg : float or sequence [deg]
        Angles of attack / sideslip, one solution each (broadcast).
    alpc_deg : float [deg], optional
        Compressibility direction; default the first alpha.  Use one deck
        per alpha with ``alpc_deg = alpha`` to match the reference runs.
    sref : float [length^2]; cref, bref, dref : float [length]
    xref, zref : float [length] moment reference point.
    symmetric : bool
        Half model with xz-plane symmetry (``$SYM 1``).
    title : str

    Returns
    -------
    Path of the deck.
    """
    alphas, betas = np.broadcast_arrays(np.atleast_1d(np.asarray(alpha_deg, float)),
                                        np.atleast_1d(np.asarray(beta_deg, float)))
    if len(alphas) > 6:
        raise InputError("at most 6 solutions per deck in this writer; split the cases",
                         field="alpha_deg")
    alpc = float(alphas[0] if alpc_deg is None else alpc_deg)
    dref = bref if dref is None else dref
    out = ["$TITLE    Created by Ironbark-Opt panair.a502", f"{title[:80]:<80s}",
           f"{'Created by Ironbark-Opt':<80s}", "$DATACHECK", "    0.0000", "$SYM",
           f"{'    1.0000' if symmetric else '    0.0000'}    0.0000", "$MACH NUMBER",
           f"{mach:10.4f}", "$CASES", f"{float(len(alphas)):10.4f}", "$ANGLES OF ATTACK",
           f"{alpc:10.4f}", "".join(f"{a:10.4f}" for a in alphas), "$YAW ANGLES",
           f"{0.0:10.4f}", "".join(f"{b:10.4f}" for b in betas),
           "$REFERENCE DATA FOR 3-D FORCES AND MOMENTS",
           f"{xref:10.4f}{0.0:10.4f}{zref:10.4f}{1.0:10.4f}",
           _f10(sref) + _f10(bref) + _f10(cref) + _f10(dref),
           "$PRINTOUT CONTROL", "       0.0" * 6, "       0.0" * 6,
           "$EAT", "  0.000000" + "       0.0" * 5, "$VELOCITY CORRECTION", "    0.0000"]
    for k, net in enumerate(networks, start=1):
        name = net.name.split()[0][:10] if net.name.strip() else f"net{k}"
        kt = _kt_of(net)
        out.append(f"$POINTS for network #{k:3d}   {name:<50s}")
        out.append("       1.0")
        if kt == -18:
            out.append(f"{18.0:10.1f}{1.0:10.1f}" + " " * 20 + "       0.0       0.0")
        else:
            out.append(f"{float(kt):10.1f}" + " " * 30 + "       0.0       0.0")
        nn, nm = net.shape
        out.append(f"{float(nm):10.1f}{float(nn):10.1f}" + " " * 50 + f"{name:<10s}")
        for col in net.points:
            for j in range(0, nm, 2):
                out.append("".join(_f10(v) for p in col[j:j + 2] for v in p))
    out.append("$END OF INPUT DATA")
    path = Path(path)
    path.write_text("\n".join(out) + "\n")
    return path


def find_panair() -> str | None:
    """The PANAIR executable: ``$IRONBARK_PANAIR`` or ``panair`` on PATH (or None)."""
    exe = os.environ.get("IRONBARK_PANAIR")
    if exe:
        return exe
    return shutil.which("panair")


@dataclass(frozen=True)
class PanairRun:
    """Outputs of one PANAIR run: ``forces`` (one ForceSummary per
    solution), ``cp`` (the agps dict, or None), ``directory`` (kept for
    inspection), ``warnings`` (lines from panair.err)."""

    forces: list
    cp: dict | None
    directory: Path
    warnings: list


def run_panair(networks, *, mach: float, alpha_deg, workdir: str | PathLike | None = None,
               executable: str | None = None, timeout: float = 3600.0, **deck) -> PanairRun:
    """Run an external PANAIR on networks, one fresh directory per call.

    Parameters
    ----------
    networks : sequence of panair.lawgs.Network
    mach : float [-]
    alpha_deg : float or sequence [deg]
    workdir : path, optional
        Parent directory for the case directory (default: system temp).
    executable : str, optional
        Default :func:`find_panair`.
    timeout : float [s]
    **deck
        Passed to :func:`write_a502` (sref, cref, xref, symmetric, ...).

    Returns
    -------
    PanairRun

    Raises
    ------
    SolverError
        No executable configured, PANAIR failed, stopped on an error (read
        from ``panair.err``), timed out, or wrote no ``ffmf``; or a result
        is non-physical (|coefficient| > 100: PANAIR's garbage on
        superinclined panels).
    """
    exe = executable or find_panair()
    if not exe:
        raise SolverError("no PANAIR executable: set IRONBARK_PANAIR or put 'panair' on PATH")
    if workdir is not None:
        Path(workdir).mkdir(parents=True, exist_ok=True)
    case = Path(tempfile.mkdtemp(prefix=f"panair_M{mach:g}_", dir=workdir))
    write_a502(case / "a502.in", networks, mach=mach, alpha_deg=alpha_deg, **deck)
    try:
        proc = subprocess.run([exe], cwd=case, input="a502.in\n", capture_output=True,
                              text=True, timeout=timeout)
    except FileNotFoundError as exc:
        raise SolverError(f"PANAIR executable not found: {exe}") from exc
    except subprocess.TimeoutExpired as exc:
        raise SolverError(f"PANAIR timed out after {timeout:.0f} s in {case}") from exc
    if proc.returncode != 0:
        raise SolverError(f"PANAIR exited with status {proc.returncode} in {case}: "
                          f"{proc.stderr.strip()[-300:]}")
    warnings = check_panair_err(case / "panair.err")
    if not (case / "ffmf").exists():
        raise SolverError(f"PANAIR wrote no ffmf in {case}: read panair.out")
    forces: list[ForceSummary] = read_ffmf(case / "ffmf")
    for f in forces:
        vals = np.array([f.fx, f.fy, f.fz, f.mx, f.my, f.mz])
        if not np.all(np.isfinite(vals)) or np.abs(vals).max() > 100:
            raise SolverError(f"PANAIR result is not physical (Mach {mach}, alpha "
                              f"{f.alpha_deg} deg: coefficients {vals}); superinclined "
                              f"panels or Mach-cone coincidences? case kept in {case}")
    cp = read_agps(case / "agps") if (case / "agps").exists() else None
    return PanairRun(forces, cp, case, warnings)
