"""Export of panel networks and surface Cp to VTK legacy files (ParaView).

Numeric-only (file output).  The legacy ASCII format (Kitware, "VTK File
Formats", VTK User's Guide, sec. 19.3) is used so no VTK library is needed:
an ``UNSTRUCTURED_GRID`` of quads (cell type 9) with cell data ``cp`` and
``network``.
"""
from __future__ import annotations

from os import PathLike
from pathlib import Path

import numpy as np

from ironbark_opt.errors import InputError

__all__ = ["write_vtk"]


def write_vtk(path: str | PathLike, corners: np.ndarray, *, cp: np.ndarray | None = None,
              network: np.ndarray | None = None, title: str = "ironbark panels") -> Path:
    """Write panels (and optionally Cp per panel) as a VTK legacy file.

    Parameters
    ----------
    path : str or path-like
        Output ``.vtk`` file.
    corners : ndarray (n, 4, 3) [m]
        Panel corners (e.g. ``PanelSet.corners``).
    cp : ndarray (n,) [-], optional
        Pressure coefficient per panel (``PanelResult.cp``).
    network : ndarray (n,) of int, optional
        Network index per panel.
    title : str

    Returns
    -------
    Path of the written file.
    """
    corners = np.asarray(corners, float)
    if corners.ndim != 3 or corners.shape[1:] != (4, 3):
        raise InputError(f"corners must have shape (n, 4, 3), got {corners.shape}", field="corners")
    n = len(corners)
    for name, arr in (("cp", cp), ("network", network)):
        if arr is not None and len(arr) != n:
            raise InputError(f"{name} has {len(arr)} values for {n} panels", field=name)
    path = Path(path)
    lines = ["# vtk DataFile Version 3.0", title.replace("\n", " ")[:255], "ASCII",
             "DATASET UNSTRUCTURED_GRID", f"POINTS {4 * n} double"]
    lines += [f"{p[0]:.9g} {p[1]:.9g} {p[2]:.9g}" for p in corners.reshape(-1, 3)]
    lines.append(f"CELLS {n} {5 * n}")
    lines += [f"4 {4 * i} {4 * i + 1} {4 * i + 2} {4 * i + 3}" for i in range(n)]
    lines.append(f"CELL_TYPES {n}")
    lines += ["9"] * n
    if cp is not None or network is not None:
        lines.append(f"CELL_DATA {n}")
    if cp is not None:
        lines += ["SCALARS cp double 1", "LOOKUP_TABLE default"]
        lines += [f"{v:.9g}" for v in np.asarray(cp, float)]
    if network is not None:
        lines += ["SCALARS network int 1", "LOOKUP_TABLE default"]
        lines += [str(int(v)) for v in network]
    path.write_text("\n".join(lines) + "\n")
    return path
