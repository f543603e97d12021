"""Diaphragms ahead of subsonic fin leading edges for the supersonic source-panel solver.

Linear theory (Evvard, NACA Report 951, 1950; Jones & Cohen, *High Speed Wing Theory*,
1960, sec. 6): ahead of a leading edge that is subsonic (swept behind the Mach line)
the upper and lower flows of a thin wing communicate through the part of the wing's
plane inside the Mach cone of the wing (the "diaphragm"): there the flow is continuous,
normal velocity and potential alike, and carries no load.  A source model whose fin
faces act on their own side only (:func:`panair.solver.supersonic._fin_sides`) treats
that plane as a wall (nothing there, w = 0 on each side), which loses the leading-edge
suction peak of a subsonic edge (flat delta wing, 63.4 deg sweep, Mach 1.6: CN-alpha
-12.6 % of Stewart's exact value, tests/unit/test_panair_delta_wing.py).  PAN AIR needs
nothing extra: its doublet sheet's potential is continuous off the wing (Epton &
Magnus, NASA CR-3251).

The diaphragm is meshed as a two-faced sheet in the fin's plane (as the wake sheets,
:mod:`.supersonic_wake`, each face a source acting on its own side), from the fin's
leading edge forward to the Mach line through the root leading-edge point, along every
spanwise strip of the fin where the edge lies behind that line; its conditions are
the wake's with no potential jump (continuity of the normal mass flux and of the
potential, :func:`.supersonic_wake.wake_rows` with ``te = -1``).  Solved, never
integrated.  Numeric-only.
"""
from __future__ import annotations

import numpy as np

from .influence import planar_corners
from .supersonic_wake import WakeSheets, fin_plane

__all__ = ["diaphragm_sheets", "merge_sheets"]

MARGIN = 0.5
"""The sheet starts this many fin chordwise panel lengths ahead of the Mach line
through the root leading-edge point (nothing ahead of that line is disturbed by the
fin, so that part of the sheet carries nothing; the margin keeps the sheet's front edge
off the Mach line of the fin's own corner: a Mach-cone coincidence)."""


LE_GRADED = True
"""The diaphragm's cells graded toward the leading edge: lengths growing quadratically
from the fin's own first chordwise panel there (cell boundaries equally spaced in the
square root of the distance from the edge, the form of a subsonic edge's singularity:
the normal velocity ahead of the edge and the load behind it go like 1 / sqrt(distance),
Evvard NACA Rep. 951; Jones & Cohen 1960, sec. 6) to at most about two fin panel lengths
at the Mach line.  False: cells of one (median) fin chordwise panel length, the model of
sessions 12-18, whose first cell was ~10 x the fin's cosine-clustered leading-edge panel
and lost the suction peak ahead of the edge."""


def _two_faced(cells, fin_idx, panels, cen_all, fins) -> WakeSheets | None:
    """The cells (corners, physical) of the fins ``fins[fin_idx]`` as a two-faced sheet
    with no potential jump: the faces looking to +e_t of their fin's plane, then the
    others (None without cells)."""
    if not cells:
        return None
    cells = np.array(cells)
    fin_idx = np.array(fin_idx, np.int64)
    _, _, nrm, _ = planar_corners(cells)
    e_t_fin = np.array([fin_plane(cen_all[panels.network == f])[1] for f in fins])
    sgn = np.sign(np.einsum("nj,nj->n", nrm, e_t_fin[fin_idx]))
    pos = np.where(sgn[:, None, None] > 0, cells, cells[:, ::-1])     # faces looking to +e_t
    w = len(cells)
    return WakeSheets(corners=np.concatenate([pos, pos[:, ::-1]]),
                      fin=np.concatenate([fin_idx, fin_idx]),
                      side=np.concatenate([np.ones(w), -np.ones(w)]),
                      x_root_te=np.full(len(fins), np.inf), te=-np.ones((w, 2), np.int64))


def _fin_mid_plane(panels, cen_all, f, size: float):
    """The mid-plane of fin network ``f``: (on, c0, e_t, e_s, pts, s, x, st, x_le) with
    ``on`` its panels, ``c0, e_t`` its plane (:func:`.supersonic_wake.fin_plane`), ``e_s``
    the spanwise direction (outward), ``pts`` its corners, ``s, x`` the spanwise and
    axial coordinates of the corners in the mid-plane, ``st`` the spanwise stations and
    ``x_le`` the leading edge at each; None for a fin of fewer than two stations."""
    xhat = np.array([1.0, 0.0, 0.0])
    on = panels.network == f
    c0, e_t = fin_plane(cen_all[on])
    e_s = np.cross(e_t, xhat)
    e_s /= np.linalg.norm(e_s)
    if c0 @ e_s < 0:
        e_s = -e_s
    pts = panels.corners[on].reshape(-1, 3)
    mid = np.abs((pts - c0) @ e_t) < 1e-6 * size          # the edges in the mid-plane
    s = np.round(pts[mid] @ e_s, 9)
    x = pts[mid, 0]
    # the leading edge: mid-plane corners of forward-facing panels (the leading-edge
    # wedge or bevel); the trailing edge's stations need not be the leading edge's
    _, _, nrm_on, _ = planar_corners(panels.corners[on])
    fwd = np.repeat(nrm_on[:, 0] < 0.0, panels.corners.shape[1])
    lead = fwd[mid]
    st = np.unique(s[lead])
    if len(st) < 2:
        return None
    return on, c0, e_t, e_s, pts, s, x, st, np.array([x[lead & (s == v)].min() for v in st])


def _first_panel(pts, e_s, st, x_le, size: float) -> np.ndarray:
    """Axial length of the fin's first chordwise panel behind its leading edge at each
    spanwise station ``st`` (from the fin's corners ``pts``)."""
    s_all = np.round(pts @ e_s, 9)
    out = np.empty(len(st))
    for k, (v, x0) in enumerate(zip(st, x_le)):
        xs = np.unique(pts[np.abs(s_all - v) < 1e-6 * size, 0])
        xs = xs[xs > x0 + 1e-9 * size]
        out[k] = xs.min() - x0 if len(xs) else np.inf
    return out


def diaphragm_sheets(panels, keep, fins, B: float) -> WakeSheets | None:
    """Diaphragm cells (physical coordinates) of the fins ``fins`` (network ids) at
    Mach number sqrt(1 + B^2), or None where no fin has a subsonic leading edge.
    Each strip between two spanwise stations of the fin's leading edge is split in
    cells about one fin chordwise panel long."""
    size = float(np.ptp(panels.corners.reshape(-1, 3), axis=0).max())
    tol = 1e-9 * size
    _, cen_all, _, _ = planar_corners(panels.corners)
    xhat = np.array([1.0, 0.0, 0.0])
    cells, fin_idx = [], []
    for k, f in enumerate(fins):
        fm = _fin_mid_plane(panels, cen_all, f, size)
        if fm is None:
            continue
        on, c0, e_t, e_s, pts, s, x, st, x_le = fm
        dx = float(np.median(np.ptp(panels.corners[on][..., 0], axis=1)))
        x_mach = x_le[0] + B * (st - st[0]) - MARGIN * dx
        h_le = _first_panel(pts, e_s, st, x_le, size)
        length = x_le - x_mach
        d = float(c0 @ e_t)
        for j in range(len(st) - 1):
            if length[j] <= MARGIN * dx + tol and length[j + 1] <= MARGIN * dx + tol:
                continue                       # a supersonic strip: ahead of the Mach line
            if LE_GRADED:
                span_len = max(length[j], length[j + 1])
                h = min(h_le[j], h_le[j + 1])
                n = max(1, int(np.ceil(span_len / dx)), int(np.ceil(np.sqrt(span_len / h))))
                fr = 1.0 - np.linspace(1.0, 0.0, n + 1) ** 2      # graded to the edge
            else:
                n = max(1, int(np.ceil(max(length[j], length[j + 1]) / dx)))
                fr = np.linspace(0.0, 1.0, n + 1)
            xa = x_mach[j] + fr * (x_le[j] - x_mach[j])
            xb = x_mach[j + 1] + fr * (x_le[j + 1] - x_mach[j + 1])
            for i in range(n):
                q = np.array([xa[i] * xhat + st[j] * e_s + d * e_t,
                              xb[i] * xhat + st[j + 1] * e_s + d * e_t,
                              xb[i + 1] * xhat + st[j + 1] * e_s + d * e_t,
                              xa[i + 1] * xhat + st[j] * e_s + d * e_t])
                cells.append(q)
                fin_idx.append(k)
    return _two_faced(cells, fin_idx, panels, cen_all, fins)


def merge_sheets(a: WakeSheets | None, b: WakeSheets | None) -> WakeSheets | None:
    """One WakeSheets of two (faces +e_t of both, then the others; ``x_root_te`` of
    ``a``, the wakes)."""
    if a is None or b is None:
        return a if b is None else b
    wa, wb = a.n_cells, b.n_cells

    def cat(u, v):
        return np.concatenate([u[:wa], v[:wb], u[wa:], v[wb:]])
    return WakeSheets(corners=cat(a.corners, b.corners), fin=cat(a.fin, b.fin),
                      side=cat(a.side, b.side), x_root_te=a.x_root_te,
                      te=np.concatenate([a.te, b.te]))


TIP_GROWTH = 1.5
"""Spanwise growth ratio of the tip diaphragm's cells outboard of the tip (the first
one the fin's tip strip wide)."""
TIP_WIDTH = 4.0
"""Largest width of a tip diaphragm outboard of the tip [fin spans] (the Mach cone of
the fin is cut there; beyond, the fin's plane is a wall again)."""


def tip_sheets(panels, keep, fins, B: float, stations=None,
               width: float | None = None) -> WakeSheets | None:
    """Diaphragm cells (physical coordinates) outboard of the fin tips ``fins``
    (network ids) at Mach number sqrt(1 + B^2), or None when no fin has a tip chord
    or a body behind it.

    A fin's side edge (its tip chord, parallel to the stream) is a subsonic edge: the
    upper and lower flows communicate around it through the part of the fin's plane
    outboard of the tip inside the fin's Mach cone, where the flow is continuous and
    carries no load (Evvard, NACA Report 951, 1950, the diaphragm; Jones & Cohen,
    *High Speed Wing Theory*, 1960, sec. 6 on side edges).  That communication is the
    lift lost to the tip: linear theory's rectangular wing CL-alpha = 4/B (1 - 1 /
    (2 B A)) (B A >= 1; Bonney, J. Aero. Sci. 14, 1947), where a plane that is a wall
    outboard of the tip (the fin faces' sources act on their own side only,
    :func:`panair.solver.supersonic._fin_sides`) keeps most of Ackeret's 4/B.

    The sheet lies in the fin's plane outboard of its tip station, from the Mach line
    of the fin's leading edge that reaches the tip first (less ``MARGIN`` chordwise
    panels) to the aft end of the kept panels, each chordwise row out to that line's
    Mach cone (plus one cell), at most ``width`` (default TIP_WIDTH) fin spans.  Rows:
    the fin's chordwise panel length alongside the tip chord, then the body's axial
    stations ``stations`` (as the wake sheets; default: the same panel length);
    spanwise cells growing by TIP_GROWTH.  Conditions: as :func:`diaphragm_sheets`
    (continuity of the normal mass flux and of the potential).  Solved, never
    integrated."""
    width = TIP_WIDTH if width is None else width
    size = float(np.ptp(panels.corners.reshape(-1, 3), axis=0).max())
    tol = 1e-9 * size
    x_end = float(panels.corners[keep][..., 0].max())
    _, cen_all, _, _ = planar_corners(panels.corners)
    xhat = np.array([1.0, 0.0, 0.0])
    cells, fin_idx = [], []
    for k, f in enumerate(fins):
        fm = _fin_mid_plane(panels, cen_all, f, size)
        if fm is None:
            continue
        on, c0, e_t, e_s, pts, s, x, st, x_le = fm
        x_te_tip = float(x[s == st[-1]].max())
        x_le_tip = float(x_le[-1])
        if x_te_tip - x_le_tip <= tol or x_le_tip >= x_end - tol:
            continue                                   # a pointed tip, or nothing aft
        dx = float(np.median(np.ptp(panels.corners[on][..., 0], axis=1)))
        ds = float(st[-1] - st[-2])
        span = float(st[-1] - st[0])
        # where the fin's Mach cone (from its leading edge) first reaches the tip station
        x_start = float(np.min(x_le + B * (st[-1] - st))) - MARGIN * dx
        # alongside the tip chord the rows follow the fin's own chordwise stations at its
        # tip (cell corners off the fin panels' corners put collocation points near
        # Mach lines of the cells: non-physical pressures on twice finer meshes)
        s_all = np.round(pts @ e_s, 9)
        x_tip = np.unique(np.round(pts[np.abs(s_all - st[-1]) < 1e-6 * size, 0], 12))
        x_tip = x_tip[(x_tip > x_le_tip + tol) & (x_tip < x_te_tip - tol)]
        n_ahead = max(1, int(np.ceil((x_le_tip - x_start) / dx))) if x_le_tip > x_start else 0
        xs = np.concatenate([np.linspace(x_start, x_le_tip, n_ahead + 1) if n_ahead else [],
                             [x_le_tip], x_tip])
        aft = np.asarray(stations if stations is not None else np.arange(x_te_tip, x_end, dx))
        aft = aft[(aft > x_te_tip + 0.5 * dx) & (aft < x_end - tol)]
        xs = np.concatenate([xs, [x_te_tip], aft, [x_end]])
        xs = np.unique(np.round(xs, 12))
        edges = [0.0, ds]
        while edges[-1] < width * span:
            edges.append(edges[-1] + (edges[-1] - edges[-2]) * TIP_GROWTH)
        edges = np.minimum(np.array(edges), width * span)
        edges = np.unique(edges)
        d = float(c0 @ e_t)
        for xa, xb in zip(xs[:-1], xs[1:]):
            reach = float(np.max(st + (xb - x_le) / B)) - st[-1]       # Mach cone at xb
            for sa, sb in zip(edges[:-1], edges[1:]):
                if sa > reach + tol:
                    break
                q = np.array([xa * xhat + (st[-1] + sa) * e_s + d * e_t,
                              xa * xhat + (st[-1] + sb) * e_s + d * e_t,
                              xb * xhat + (st[-1] + sb) * e_s + d * e_t,
                              xb * xhat + (st[-1] + sa) * e_s + d * e_t])
                cells.append(q)
                fin_idx.append(k)
    return _two_faced(cells, fin_idx, panels, cen_all, fins)
