"""LaWGS (Langley Wireframe Geometry Standard) networks: read and write.

Format (Craidon, "A Description of the Langley Wireframe Geometry Standard
(LaWGS) Format", NASA TM-85767, 1985): a title line, then for each network
a name line, a header line

    ID NLINE NPNT ISYM RX RY RZ TX TY TZ XSCALE YSCALE ZSCALE ISCALE

and NLINE x NPNT points given as free-format ``x y z`` triples (any number
per line).  A network is a structured grid of points: ``NLINE`` contours
of ``NPNT`` points each.  PANAIR's PANIN reads the same files (point order
along a contour = PANAIR "rows", contours = "columns").

All functions here are numeric-only (file I/O).  Coordinates are stored in
whatever length unit the file uses; the caller states it (PANAIR decks are
commonly in calibers).
"""
from __future__ import annotations

from dataclasses import dataclass, field
from os import PathLike
from pathlib import Path

import numpy as np

from ironbark_opt.errors import InputError

__all__ = ["Network", "read_lawgs", "write_lawgs"]


@dataclass(frozen=True)
class Network:
    """One structured network of surface points.

    Parameters
    ----------
    name : str
        Network name (first word is used by PANAIR; keep it <= 10 chars).
    points : ndarray, shape (n_lines, n_points, 3) [length unit of the file]
        Grid points: ``points[i, j]`` is point ``j`` of contour ``i``.
    kind : str
        What the network is for the built-in solver and the A502 writer:
        ``"surface"`` (impermeable, forces integrated; PANAIR kt=1),
        ``"base"`` (impermeable, forces not integrated; PANAIR kt=5),
        ``"wake"`` (doublet wake; PANAIR kt=18).
    """

    name: str
    points: np.ndarray
    kind: str = "surface"
    meta: dict = field(default_factory=dict, compare=False)

    def __post_init__(self):
        pts = np.asarray(self.points, dtype=float)
        if pts.ndim != 3 or pts.shape[2] != 3 or pts.shape[0] < 2 or pts.shape[1] < 2:
            raise InputError(
                f"network points must have shape (n_lines >= 2, n_points >= 2, 3), got {pts.shape}",
                field=f"network '{self.name}'")
        if not np.all(np.isfinite(pts)):
            raise InputError("network points contain NaN or infinity", field=f"network '{self.name}'")
        if self.kind not in ("surface", "base", "wake"):
            raise InputError(f"network kind must be 'surface', 'base' or 'wake', got {self.kind!r}",
                             field=f"network '{self.name}'")
        object.__setattr__(self, "points", pts)

    @property
    def shape(self) -> tuple[int, int]:
        """(n_lines, n_points) of the point grid."""
        return self.points.shape[0], self.points.shape[1]

    @property
    def n_panels(self) -> int:
        """Number of quadrilateral panels, (n_lines - 1) * (n_points - 1)."""
        return (self.shape[0] - 1) * (self.shape[1] - 1)

    def with_kind(self, kind: str) -> "Network":
        """Copy of this network with another ``kind``."""
        return Network(self.name, self.points, kind, dict(self.meta))


def _tokens_with_lines(lines, start):
    for k in range(start, len(lines)):
        for tok in lines[k].split():
            yield tok, k + 1


def read_lawgs(path: str | PathLike) -> tuple[str, list[Network]]:
    """Read a LaWGS file.

    Parameters
    ----------
    path : str or path-like
        The ``.wgs`` file (LF or CRLF line endings).

    Returns
    -------
    title : str
    networks : list of Network
        In file order, all of kind ``"surface"`` (LaWGS carries no boundary
        type: set kinds from the PANIN ``BOUN`` line or your own knowledge).

    Raises
    ------
    InputError
        Naming the file and line of a malformed header or point, a wrong
        point count, or a rotation (non-zero RX, RY, RZ: not supported).
    """
    path = Path(path)
    try:
        text = path.read_text(errors="replace")
    except OSError as exc:
        raise InputError(f"cannot read LaWGS file: {exc.strerror}", source=path) from exc
    lines = text.splitlines()
    if not lines:
        raise InputError("empty LaWGS file", source=path)
    title = lines[0].strip()
    networks = []
    k = 1
    while k < len(lines):
        if not lines[k].strip():
            k += 1
            continue
        name = lines[k].strip()
        name_line = k + 1
        if k + 1 >= len(lines):
            raise InputError(f"network '{name}' has no header line", source=path, line=name_line)
        head = lines[k + 1].split()
        if len(head) < 14:
            raise InputError("network header must have 14 fields "
                             "(ID NLINE NPNT ISYM RX RY RZ TX TY TZ XSCALE YSCALE ZSCALE ISCALE), "
                             f"got {len(head)}", source=path, line=k + 2)
        try:
            nline, npnt = int(head[1]), int(head[2])
            rot = [float(v) for v in head[4:7]]
            trans = np.array([float(v) for v in head[7:10]])
            scale = np.array([float(v) for v in head[10:13]])
        except ValueError as exc:
            raise InputError(f"bad number in network header: {exc}", source=path, line=k + 2) from exc
        if nline < 2 or npnt < 2:
            raise InputError(f"network '{name}': NLINE and NPNT must be >= 2, got {nline}, {npnt}",
                             source=path, line=k + 2)
        if any(r != 0.0 for r in rot):
            raise InputError(f"network '{name}': rotations (RX RY RZ = {rot}) are not supported; "
                             "apply them to the points", source=path, line=k + 2)
        need = 3 * nline * npnt
        vals = []
        last_line = k + 2
        for tok, ln in _tokens_with_lines(lines, k + 2):
            if len(vals) == need:
                break
            try:
                vals.append(float(tok.replace("D", "E").replace("d", "e")))
            except ValueError as exc:
                raise InputError(f"network '{name}': expected a coordinate, got {tok!r} "
                                 f"({len(vals) // 3} of {nline * npnt} points read)",
                                 source=path, line=ln) from exc
            last_line = ln
        if len(vals) < need:
            raise InputError(f"network '{name}': file ends after {len(vals) // 3} of "
                             f"{nline * npnt} points", source=path, line=name_line)
        pts = np.array(vals).reshape(nline, npnt, 3) * scale + trans
        networks.append(Network(name, pts))
        k = last_line  # last consumed line is fully numeric (3 values per point)
    if not networks:
        raise InputError("no networks in LaWGS file", source=path)
    return title, networks


def write_lawgs(path: str | PathLike, networks, title: str = "written by ironbark panair") -> Path:
    """Write networks as a LaWGS file (one point per line, no transform).

    Parameters
    ----------
    path : str or path-like
        Output file.
    networks : sequence of Network
    title : str
        First line of the file.

    Returns
    -------
    Path of the written file.
    """
    path = Path(path)
    out = [title.replace("\n", " ")]
    for net in networks:
        nline, npnt = net.shape
        out.append(net.name.split()[0] if net.name.strip() else "net")
        out.append(f"1 {nline} {npnt} 0   0 0 0   0 0 0    1 1 1  0")
        for p in net.points.reshape(-1, 3):
            out.append(f"{p[0]:.9e} {p[1]:.9e} {p[2]:.9e}")
    path.write_text("\n".join(out) + "\n")
    return path
