"""Fin trailing-edge wakes of the supersonic source-panel solver: the vortex sheet
behind a fin, where a body continues behind it.

Linear theory (Epton & Magnus, PAN AIR theory document, NASA CR-3251, 1990, sec.
B.3 and the wake networks of sec. 5; Ward, *Linearized Theory of Steady High-Speed
Flow*, 1955, ch. 8): a thin wake carries no load and no thickness, so across it the
pressure (linear theory: the axial perturbation velocity u) and the normal mass flux
are continuous, while the potential jumps by the fin's trailing-edge value, carried
unchanged along the stream.  In a source formulation whose fin faces act only on
their own side (:func:`panair.solver.supersonic._fin_sides`) that jump has nowhere to
live behind the trailing edge: without a wake the two sides meet on the body behind
the fin and the potential jump dies out there (measured on the Allen fin-body
configurations at Mach 1.6: the body's potential jump at the wake line fell from
4.9e-3 at the trailing edge to 1.2e-3 two calibers aft), which is the flow of a fin
with no trailing vortices; the afterbody then carried a spurious download (CN-alpha
-1.04 /rad behind Allen's fin 10, 26 % of the fins' own lift, its moment 0.6 calibre
of centre of pressure).  Slender-body theory with a flat vortex wake gives the
afterbody no lift at all (the apparent mass of the fin section is kept, e.g.
Nielsen, *Missile Aerodynamics*, 1960, ch. 5).

The wake is therefore meshed for the supersonic solve as a sheet of two faces in the
fin's plane, from the trailing edge to the end of the body (nothing further aft acts
on an integrated panel: the theory is causal), each face a source panel acting on
its own side only (as the fin's faces), with two conditions per cell instead of the
wall's: continuity of the normal mass flux and of u.  The wake of a fin with another
fin in line behind it stops at that fin's leading edge (the aft fin's wake carries
on; the forward fin's jump is not passed through it).  The sheets are solved, never
integrated.  Numeric-only.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .influence import planar_corners

__all__ = ["WakeSheets", "fin_plane", "tip_caps", "wake_sheets", "cut_wake_neighbours", "sheet_twins",
           "sheet_geometry", "sheet_sides", "wake_rows"]

#: Cells per body panel length behind the trailing edge (measured on Allen's fin 10 at
#: Mach 1.6: 1, 2 and 4 give the configuration's CN-alpha within 0.07 % and its
#: Cm-alpha within 0.1 %)
CELLS_PER_BODY_PANEL = 1


@dataclass
class WakeSheets:
    """Two-faced wake cells (physical coordinates).

    corners : ndarray (2 w, 4, 3) [m]
        Faces: rows 0 .. w-1 the faces on the +e_t side of their fin's plane, rows
        w .. 2w-1 the same cells facing the other way (reversed corner order).
    fin : ndarray (2 w,) of int
        Index of the fin (in :func:`panair.solver.supersonic._fin_sides` order).
    side : ndarray (2 w,) [-]
        +1 / -1: the side of the fin's plane each face looks to.
    x_root_te : ndarray (n_fins,) [m]
        Where each fin's wake leaves the body (its innermost cell's leading x; inf
        for a fin without a sheet).
    te : ndarray (w, 2) of int
        Per cell, the fin's trailing-edge panels its strip is shed from (PanelSet
        indices), the one facing +e_t first.
    """

    corners: np.ndarray
    fin: np.ndarray
    side: np.ndarray
    x_root_te: np.ndarray
    te: np.ndarray

    @property
    def n_cells(self) -> int:
        return len(self.corners) // 2


def fin_plane(fin_centroids):
    """A fin's mid-plane: (point, unit normal) of the least-squares plane through its
    panel centroids (the smallest singular direction).  ``full_matrices=False``: the same
    right singular vectors (bitwise, checked on this LAPACK) without the (n, n) left
    ones, which took ~45 ms a call for a fin's ~1000 panels (ten calls per supersonic
    Mach number of the Kestrel).

    The normal is oriented by the geometry, not by LAPACK's sign: along the roll
    direction e_x x c0 at the fin's centroid (for a fin whose centroid is on the axis,
    its largest y-z component positive).  The planes are computed both in physical
    space (the wake and diaphragm sheets' faces, :func:`wake_sheets`) and in the
    solver's scaled space (x / B, :func:`panair.solver.supersonic._fin_planes`), and the
    sides of the sheets' faces must mean the same there: the singular vector's sign
    alone flipped between the two for some Mach numbers (measured on 3 or 4 fins
    rolled 0 deg and 3 rolled 17 deg, Mach 1.2 ... 3: one fin in three or four, at
    Mach 2.5 all four), which sided a wake sheet's faces opposite to its fin's."""
    c0 = fin_centroids.mean(axis=0)
    e_t = np.linalg.svd(fin_centroids - c0, full_matrices=False)[2][2]
    roll = np.array([0.0, -c0[2], c0[1]])
    extent = float(np.ptp(fin_centroids, axis=0).max())
    if np.linalg.norm(roll) > 1e-6 * extent and abs(float(e_t @ roll)) > 1e-6 * np.linalg.norm(roll):
        s = float(e_t @ roll)
    else:
        s = float(e_t[1:][np.argmax(np.abs(e_t[1:]))])
    return c0, (e_t if s >= 0 else -e_t)


def tip_caps(panels, keep, fins) -> np.ndarray:
    """Panels of networks that touch a fin network (tip caps) and are not
    the body: networks sharing points with a fin whose panels all face
    sideways."""
    net = panels.network[keep]
    out = np.zeros(len(net), bool)
    if not len(fins):
        return out
    fin_pts = panels.corners[np.isin(panels.network, fins)].reshape(-1, 3)
    lo, hi = fin_pts.min(0), fin_pts.max(0)
    c = panels.corners[keep].mean(axis=1)
    inside = np.all((c >= lo - 1e-9) & (c <= hi + 1e-9), axis=1)
    for k in np.unique(net):
        on = net == k
        if k not in fins and inside[on].all():
            out |= on
    return out


def wake_sheets(panels, keep, fins) -> WakeSheets | None:
    """The wake sheets of the fins ``fins`` (network ids) behind which the kept
    (integrated) panels continue, or None when no fin has a body behind it.

    Streamwise cells from each trailing-edge strip of a fin's PanelSet wake to the
    aft end of the kept panels (or to the leading edge of a fin in line behind),
    split at the body's axial panel stations there (each body interval in
    CELLS_PER_BODY_PANEL cells)."""
    if not len(fins) or not len(panels.wake_corners):
        return None
    size = float(np.ptp(panels.corners.reshape(-1, 3), axis=0).max())
    tol = 1e-9 * size
    kept = panels.corners[keep]
    x_end = float(kept[..., 0].max())
    fin_of_panel = panels.network
    # the body: neither a fin nor a fin's tip cap (a cap alongside the tip chord is no
    # body radius for the guard below: it stopped the wakes of a fin whose tip runs aft
    # of its root trailing edge, a swept trailing edge, at the tip chord's x)
    body_like = ~np.isin(fin_of_panel, fins) & keep
    body_like[np.nonzero(keep)[0][tip_caps(panels, keep, fins)]] = False
    stations = np.unique(np.round(panels.corners[body_like][..., 0].ravel(), 12))
    if CELLS_PER_BODY_PANEL > 1 and len(stations) > 1:
        sub = np.linspace(0.0, 1.0, CELLS_PER_BODY_PANEL + 1)[1:-1]
        mids = stations[:-1, None] + np.diff(stations)[:, None] * sub[None, :]
        stations = np.unique(np.concatenate([stations, mids.ravel()]))
    # the body's radius at its stations (largest corner radius), for the guard below
    bc = panels.corners[body_like].reshape(-1, 3)
    bx = np.round(bc[:, 0], 12)
    r_st = np.array([np.linalg.norm(bc[bx == x][:, 1:], axis=1).max() for x in np.unique(bx)])
    x_st = np.unique(bx)
    _, cen_all, nrm_all, _ = planar_corners(panels.corners)
    planes = [fin_plane(cen_all[fin_of_panel == f]) for f in fins]
    x_range = [(float(panels.corners[fin_of_panel == f][..., 0].min()),
                float(panels.corners[fin_of_panel == f][..., 0].max())) for f in fins]
    lifting = np.nonzero(~panels.wake_at_base)[0]
    cells, fin_idx, te_idx = [], [], []
    for k, f in enumerate(fins):
        c0, e_t = planes[k]
        # a fin in line behind (same plane, starts aft of this one): stop there
        x_stop = x_end
        for k2, f2 in enumerate(fins):
            c2, e2 = planes[k2]
            r0, r2 = c0 * [0.0, 1.0, 1.0], c2 * [0.0, 1.0, 1.0]
            same_side = float(r0 @ r2) > 0.99 * float(np.linalg.norm(r0) * np.linalg.norm(r2))
            if (k2 != k and same_side and abs(abs(float(e_t @ e2)) - 1.0) < 1e-6
                    and abs(float((c2 - c0) @ e_t)) < 1e-6 * size
                    and x_range[k2][0] > x_range[k][1] - tol):
                x_stop = min(x_stop, x_range[k2][0])
        mine = lifting[fin_of_panel[panels.wake_upper[lifting]] == f]
        strips: dict = {}
        for w in mine:                                # the first wake panel of each strip
            key = (int(panels.wake_upper[w]), int(panels.wake_lower[w]))
            xmin = float(panels.wake_corners[w][:, 0].min())
            if key not in strips or xmin < strips[key][0]:
                strips[key] = (xmin, w)
        for (up, lo), (_, w) in strips.items():
            if lo < 0:
                continue
            pair = (up, lo) if float(nrm_all[up] @ e_t) >= float(nrm_all[lo] @ e_t) else (lo, up)
            wc = panels.wake_corners[w]
            te = wc[np.argsort(wc[:, 0], kind="stable")[:2]]     # the trailing-edge edge
            if np.linalg.norm(te[0] - te[1]) <= tol:
                continue
            x0 = float(te[:, 0].max())
            xs = stations[(stations > x0 + tol) & (stations < x_stop - tol)]
            xs = np.append(xs, x_stop) if x_stop > x0 + tol else xs
            prev = te.copy()
            for xn in xs:
                nxt = te.copy()
                nxt[:, 0] = xn
                q = np.array([prev[0], prev[1], nxt[1], nxt[0]])
                # a body growing behind the fin would put the sheet inside it: stop there
                r_in = float(np.linalg.norm(q[:, 1:], axis=1).min())
                if r_in < float(np.interp(xn, x_st, r_st)) - 1e-6 * size:
                    break
                if np.linalg.norm(np.cross(q[2] - q[0], q[1] - q[3])) > tol * size:
                    cells.append(q)
                    fin_idx.append(k)
                    te_idx.append(pair)
                prev = nxt
    if not cells:
        return None
    cells = np.array(cells)
    fin_idx = np.array(fin_idx, np.int64)
    _, _, nrm, _ = planar_corners(cells)
    e_t = np.array([planes[k][1] for k in fin_idx])
    s = np.sign(np.einsum("nj,nj->n", nrm, e_t))
    pos = np.where(s[:, None, None] > 0, cells, cells[:, ::-1])      # faces looking to +e_t
    corners = np.concatenate([pos, pos[:, ::-1]])
    radial = np.linalg.norm(cells.mean(axis=1)[:, 1:], axis=1)
    x_root_te = np.full(len(fins), np.inf)
    for k in np.unique(fin_idx):
        on = np.nonzero(fin_idx == k)[0]
        inner = on[radial[on] <= radial[on].min() * (1 + 1e-9) + tol]
        x_root_te[k] = float(cells[inner][..., 0].min())
    return WakeSheets(corners=corners, fin=np.concatenate([fin_idx, fin_idx]),
                      side=np.concatenate([np.ones(len(cells)), -np.ones(len(cells))]),
                      x_root_te=x_root_te, te=np.array(te_idx, np.int64))


def cut_wake_neighbours(nb, cen, sides_recv, fins_x_te, is_fin):
    """Surface-gradient neighbours (kept panels, (m, 4)) without the pairs that
    straddle a wake's root line on the body: two body panels aft of fin k's root
    trailing edge, both in its half of the cross-section, on opposite sides of its
    plane (``sides_recv[k]``: -1/+1, 0 outside the half).  The potential jumps there
    (the wake's jump), so a gradient across it is meaningless."""
    out = nb.copy()
    valid = out >= 0
    j = np.where(valid, out, 0)
    for k, x_te in enumerate(fins_x_te):
        r = sides_recv[k]
        aft = (cen[:, 0] > x_te) & ~is_fin
        cross = valid & aft[:, None] & aft[j] & (r[:, None] * r[j] < 0)
        out[cross] = -1
    return out


def sheet_twins(p_panels, cen_sheet, nrm_sheet, tol, reflect=None) -> np.ndarray | None:
    """Mirror twins of the kept panels followed by the sheet faces: ``p_panels`` the
    panels' own twins (kept indexing), the faces matched by mirrored centroid and
    normal (``reflect``: the mirror plane's reflection of vectors (k, 3), default the
    x-z plane's); None if a face has no twin."""
    from scipy.spatial import cKDTree
    if reflect is None:
        flip = np.array([1.0, -1.0, 1.0])
        reflect = lambda v: v * flip          # noqa: E731
    key = np.hstack([cen_sheet, nrm_sheet * tol * 1e3])
    dist, q = cKDTree(key).query(np.hstack([reflect(cen_sheet), reflect(nrm_sheet) * tol * 1e3]))
    if not np.all(dist <= 10 * tol) or not np.array_equal(q[q], np.arange(len(q))):
        return None
    m = len(p_panels)
    return np.concatenate([p_panels, m + q])


def sheet_geometry(sheets: WakeSheets, B: float):
    """Flat corners, centroids, normals (scaled space, x / B) and regularisation
    length (as the solver's panels: sqrt(area), at most the shortest edge) of the
    sheet faces."""
    c = sheets.corners.copy()
    c[..., 0] /= B
    flat, cen, nrm, area = planar_corners(c)
    edges = np.linalg.norm(np.roll(flat, -1, axis=1) - flat, axis=-1)
    shortest = np.where(edges > 1e-9 * edges.max(), edges, np.inf).min(axis=1)
    return flat, cen, nrm, np.minimum(np.sqrt(np.maximum(area, 1e-300)), shortest)


def sheet_sides(sides, sheets: WakeSheets, recv_sheet):
    """The fin-side assignment (recv, src_fin, src_side) of the kept panels extended
    by the sheet faces: a face acts on its own side of its fin's plane only (as the
    fin's faces, ``sheets.side``) and receives as ``recv_sheet`` (n_fins, 2 w) says
    (:func:`panair.solver.supersonic._receiver_sides`: its own fin's side, with
    THIN_WING also a coplanar fin's; both in the orientation of
    :func:`fin_plane`)."""
    recv, src_fin, src_side = sides
    return (np.hstack([recv, recv_sheet]), np.concatenate([src_fin, sheets.fin]),
            np.concatenate([src_side, sheets.side]))


def wake_rows(A, Phi, m: int, sheets: WakeSheets, rowpos, kept_index):
    """Replace the sheet faces' rows of the (folded) influence matrix ``A`` (row
    ``rowpos(j)`` for unknown j) by the wake conditions of each cell c (faces u = m + c
    looking to +e_t, l = m + w + c): continuity of the normal mass flux (the faces'
    conormal fluxes sum to zero) and the potential jump of the fin's trailing edge
    carried unchanged: phi(u) - phi(l) = phi(te+) - phi(te-) (``Phi``: the potential
    rows at the collocation points, folded columns; ``kept_index`` maps PanelSet
    indices to unknowns).  This is PAN AIR's wake condition (doublet strength constant
    along the stream, NASA CR-3251 sec. 5); the pointwise form, continuity of u, made
    the marching along a strip unstable with constant-strength sources (pivots 1e-11
    at the last cells).  Folded twins share one row pair; a cell that is its own
    mirror image keeps the mass-flux row only."""
    n_cells = sheets.n_cells
    An, done = {}, set()
    for c in range(n_cells):
        u, lo = m + c, m + n_cells + c
        ru, rl = rowpos(u), rowpos(lo)
        pair = (min(ru, rl), max(ru, rl))
        if pair in done:
            continue
        done.add(pair)
        an_u = An.setdefault(ru, A[ru].copy())
        an_l = An.setdefault(rl, A[rl].copy())
        A[pair[0]] = an_u + an_l if ru != rl else an_u
        if ru != rl:
            A[pair[1]] = Phi[ru] - Phi[rl]
            if sheets.te[c, 0] >= 0:       # a wake (-1: a diaphragm, no jump)
                tp, tn = (rowpos(int(kept_index[t])) for t in sheets.te[c])
                A[pair[1]] -= Phi[tp] - Phi[tn]
    return sorted({r for p in done for r in p})


def folded_wake_systems(fold, twins, Phi0, Phi1, step, m: int, sheets: WakeSheets, kept_index):
    """The even and odd systems of a mirror fold in a plane other than x-z
    (:class:`panair.solver.panels.MirrorFold`, ``fold.odd``) with the wake conditions
    of :func:`wake_rows`: ``[(Phi_even, A_even), (Phi_odd, A_odd)]``.

    ``Phi0``, ``Phi1``: the potential rows of the representatives at the collocation
    points and their offset points (full columns); ``twins``: every unknown's mirror
    twin.  A row of a non-representative is its twin's row with the columns mirrored
    (the mesh is its own mirror image).  Each cell's two conditions (mass-flux
    continuity, the trailing-edge potential jump) replace its faces' representatives'
    rows in both systems; a mirror pair of cells shares those rows (its conditions
    fold onto the same equations).  A cell that is its own mirror image (a fin in
    the plane; faces u and l twins) keeps the mass-flux row in the even system, where
    the jump of a symmetric flow is zero, and the jump row in the odd one, where the
    two faces' fluxes cancel."""
    reps = fold.reps
    E0, EA = fold.fold_difference(Phi0, Phi1, reps, step[reps])
    O0, OA = fold.fold_difference(Phi0, Phi1, reps, step[reps], odd=True)
    odd_pos = -np.ones(len(reps), np.int64)
    odd_pos[fold.paired] = np.arange(int(fold.paired.sum()))

    def full(i, influence: bool):
        """Row i of the full potential (or influence) matrix."""
        j = i if twins[i] >= i else int(twins[i])
        r = (Phi1[j] - Phi0[j]) / step[j] if influence else Phi0[j]
        return r if j == i else r[twins]

    n_cells, done = sheets.n_cells, set()
    for c in range(n_cells):
        u, lo = m + c, m + n_cells + c
        ru, rl = int(fold.rep_of[u]), int(fold.rep_of[lo])
        pair = (min(ru, rl), max(ru, rl))
        if pair in done:
            continue
        done.add(pair)
        flux = (full(u, True) + full(lo, True))[None, :]
        jump = (full(u, False) - full(lo, False))[None, :]
        if sheets.te[c, 0] >= 0:           # a wake (-1: a diaphragm, no jump)
            tp, tn = (int(kept_index[t]) for t in sheets.te[c])
            jump = jump - (full(tp, False) - full(tn, False))[None, :]
        EA[ru] = fold.fold(flux)[0]
        if ru != rl:
            EA[rl] = fold.fold(jump)[0]
            for r, cond in ((ru, flux), (rl, jump)):
                if odd_pos[r] >= 0:
                    OA[odd_pos[r]] = _odd_row(fold, cond)
        elif odd_pos[ru] >= 0:
            OA[odd_pos[ru]] = _odd_row(fold, jump)
    return [(E0, EA), (O0, OA)]


def _odd_row(fold, row):
    """One full row (1, n) folded into the odd system's columns (n_paired,)."""
    reps, paired = fold.reps, fold.paired
    a, b = reps[paired], fold._twin[paired]
    return row[0, a] - row[0, b]
