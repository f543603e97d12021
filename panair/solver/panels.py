"""Panels from networks: geometry, neighbours for surface gradients, and
the trailing-edge connectivity of wakes (the Kutta condition).

Numeric-only.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ironbark_opt.errors import InputError

from .influence import planar_corners

__all__ = ["PanelSet", "build_panels"]


@dataclass
class PanelSet:
    """Low-order panels of a configuration (one unknown per body panel).

    Attributes
    ----------
    corners : ndarray (n, 4, 3) [m]
        Body (kind surface/base) panel corners, physical coordinates.
    network : ndarray (n,) of int
        Index of the network each panel came from.
    integrate : ndarray (n,) of bool
        True for ``surface`` networks (forces integrated; PANAIR kt=1),
        False for ``base`` networks.
    neighbours : ndarray (n, 4) of int
        Same-network neighbour panels (-1 = none, -2 = own mirror image in
        the symmetry plane y = 0).
    wake_corners : ndarray (w, 4, 3) [m]
        Wake panel corners.
    wake_upper, wake_lower : ndarray (w,) of int
        Body panels on the two sides of the trailing edge a wake panel's
        strip is shed from: wake doublet = mu_upper - mu_lower (Kutta
        condition, e.g. Katz & Plotkin 2001, eq. 12.27); ``wake_lower`` is
        -1 for a wake shed from a body-base edge.
    wake_at_base : ndarray (w,) of bool
        Wake panel shed from a body-base edge.  Such a wake tube is
        modelled as the solid continuation of the body (sources
        sigma = -U.n on it, doublet = the body's trailing-edge doublet,
        interior potential zero, as the body's): the flow past the base
        sees a semi-infinite body, which is what a separated base flow
        looks like to the potential flow ahead of it, and the base panels
        it caps are dropped.  (A closed base instead makes the flow turn
        the base corner: strong suction on the last caliber of the body
        that real flows do not show.)
    symmetric : bool
        Half model: the mirror image y -> -y is added to every influence.
    axial : ndarray (n,) of bool
        False for panels whose axial (x) pressure force is left out of the
        integration (network meta ``no_axial``: a wedge standing in for a blunt
        fin leading edge, whose drag is modelled separately).
    """

    corners: np.ndarray
    network: np.ndarray
    integrate: np.ndarray
    neighbours: np.ndarray
    wake_corners: np.ndarray
    wake_upper: np.ndarray
    wake_lower: np.ndarray
    wake_at_base: np.ndarray
    symmetric: bool
    names: list
    axial: np.ndarray | None = None

    def force_normals(self, normals):
        """``normals`` (n, 3) with the x component zeroed where ``axial`` is False."""
        if self.axial is None or self.axial.all():
            return normals
        out = np.array(normals, copy=True)
        out[~self.axial, 0] = 0.0
        return out

    def fin_mask(self) -> np.ndarray:
        """(n,) bool: panels of the fins' networks (``fin<k>`` surfaces and their
        ``cap<k>`` tip caps, :func:`panair.mesh.mesh_rocket`)."""
        names = np.array(self.names, dtype=str)[self.network]
        return np.char.startswith(names, "fin") | np.char.startswith(names, "cap")

    @property
    def n(self) -> int:
        """Number of body panels (unknowns)."""
        return len(self.corners)

    def geometry(self, stretch: float = 1.0):
        """Flat corners, centroids, unit normals and areas, with x scaled by
        ``stretch`` [-] (the Prandtl-Glauert transform x' = x / beta)."""
        c = self.corners.copy()
        c[..., 0] *= stretch
        return planar_corners(c)

    def wake_geometry(self, stretch: float = 1.0):
        """Same as :meth:`geometry` for the wake panels."""
        c = self.wake_corners.copy()
        c[..., 0] *= stretch
        return planar_corners(c)


def _grid_corners(pts):
    return np.stack([pts[:-1, :-1], pts[:-1, 1:], pts[1:, 1:], pts[1:, :-1]], axis=2)


def build_panels(networks, *, symmetric: bool = False, tol: float | None = None) -> PanelSet:
    """Cut networks into quadrilateral panels and connect wakes.

    Parameters
    ----------
    networks : sequence of panair.lawgs.Network
        Networks with ``kind`` "surface", "base" or "wake"; normals follow
        PANAIR's rule (line direction x point direction) and must point
        into the flow.
    symmetric : bool
        Half model with the plane y = 0 as symmetry plane.
    tol : float, optional [m]
        Distance under which two points are the same (default 1e-6 x the
        configuration size).

    Returns
    -------
    PanelSet

    Raises
    ------
    InputError
        If a wake's upstream edge does not coincide with panel edges of
        the surface networks (the Kutta condition cannot be applied).
    """
    allpts = np.concatenate([n.points.reshape(-1, 3) for n in networks])
    size = float(np.ptp(allpts, axis=0).max()) or 1.0
    tol = 1e-6 * size if tol is None else tol
    corners, netid, integ, nbrs, names, isbase, axial, hidden = [], [], [], [], [], [], [], []
    offset = 0
    for k, net in enumerate(networks):
        names.append(net.name)
        if net.kind == "wake":
            continue
        cr = _grid_corners(net.points)                 # (L-1, P-1, 4, 3)
        nl, npt = cr.shape[:2]
        _, _, _, area = planar_corners(cr.reshape(-1, 4, 3))
        keep = (area > 1e-10 * size**2).reshape(nl, npt)
        idx = -np.ones((nl, npt), dtype=int)
        idx[keep] = offset + np.arange(keep.sum())
        nb = -np.ones((nl, npt, 4), dtype=int)
        nb[1:, :, 0] = idx[:-1, :]
        nb[:-1, :, 1] = idx[1:, :]
        nb[:, 1:, 2] = idx[:, :-1]
        nb[:, :-1, 3] = idx[:, 1:]
        if symmetric:
            on_plane_line0 = np.all(np.abs(net.points[0, :, 1]) < tol)
            on_plane_line1 = np.all(np.abs(net.points[-1, :, 1]) < tol)
            if on_plane_line0:
                nb[0, :, 0] = -2
            if on_plane_line1:
                nb[-1, :, 1] = -2
        corners.append(cr[keep])
        nbrs.append(nb[keep])
        netid.append(np.full(keep.sum(), k))
        hid = _meta_mask(net, "no_force", nl, npt)       # e.g. body panels under a fin root
        separated = _meta_mask(net, "separated", nl, npt)  # wetted, its force another model's
        force = (net.kind == "surface") & ~hid & ~separated
        integ.append(force[keep])
        hidden.append(hid[keep])
        axial.append(~_meta_mask(net, "no_axial", nl, npt)[keep])
        isbase.append(np.full(keep.sum(), net.kind == "base"))
        offset += int(keep.sum())
    if offset == 0:
        raise InputError("no surface networks to solve for", field="networks")
    corners = np.concatenate(corners)
    # edge dictionary of body panels: key = sorted rounded end points
    # (the keys of _edge_key, rounded for all corners at once)
    edge_map: dict = {}
    ends = np.round(corners / tol).astype(np.int64).tolist()
    short = (np.linalg.norm(corners - np.roll(corners, -1, axis=1), axis=-1) <= tol).tolist()
    for p in range(len(corners)):
        for e in range(4):
            if short[p][e]:
                continue
            a, b = tuple(ends[p][e]), tuple(ends[p][(e + 1) % 4])
            edge_map.setdefault((a, b) if a <= b else (b, a), []).append(p)
    wc, wu, wl, wb = [], [], [], []
    _, cen, _, _ = planar_corners(corners)
    for net in networks:
        if net.kind != "wake":
            continue
        c, u, l = _attach_wake(net, edge_map, cen, tol)
        base_flag = np.concatenate(isbase)
        up_is_base = base_flag[u]
        if np.any(up_is_base):
            raise InputError(f"wake network '{net.name}': base panel on the upper side of "
                             "its trailing edge: check the base network's normals (must point aft)",
                             field=f"network '{net.name}'")
        wb.append(base_flag[l])
        wc.append(c)
        wu.append(u)
        wl.append(l)
    netid = np.concatenate(netid)
    # orientation: V = 1/2 Integral (y n_y + z n_z) dS (divergence theorem with
    # F = (0, y, z)/2) is the enclosed volume for outward normals, and caps
    # normal to x (bases, cut noses) or lying in y = 0 do not change it.
    _, cc, cn, ca = planar_corners(corners)
    vol = 0.5 * np.sum((cc[:, 1] * cn[:, 1] + cc[:, 2] * cn[:, 2]) * ca)
    if vol < 0:
        raise InputError("panel normals point into the body (enclosed volume "
                         f"{vol:.4g} < 0): reverse the point order of the networks "
                         "(PANAIR rule: normal = line direction x point direction)",
                         field="networks")
    integ = np.concatenate(integ)
    nbrs = np.concatenate(nbrs)
    # panels hidden under a fin root carry interior values: not gradient neighbours
    hidden = np.concatenate(hidden)
    nbrs = np.where((nbrs >= 0) & hidden[np.maximum(nbrs, 0)], -1, nbrs)
    wu = np.concatenate(wu) if wu else np.zeros(0, int)
    wl = np.concatenate(wl) if wl else np.zeros(0, int)
    wb = np.concatenate(wb) if wb else np.zeros(0, bool)
    # A base capped by a base wake is inside the semi-infinite body formed by
    # the body and its wake tube: drop its panels (see PanelSet).
    drop = np.isin(netid, np.unique(netid[wl[wb]])) if wb.any() else np.zeros(len(netid), bool)
    new = -np.ones(len(netid), dtype=int)
    new[~drop] = np.arange((~drop).sum())
    nbrs = np.where(nbrs >= 0, new[np.maximum(nbrs, 0)], nbrs)[~drop]
    axial = np.concatenate(axial)
    return PanelSet(corners=corners[~drop], network=netid[~drop], integrate=integ[~drop],
                    axial=axial[~drop],
                    neighbours=nbrs,
                    wake_corners=np.concatenate(wc) if wc else np.zeros((0, 4, 3)),
                    wake_upper=new[wu], wake_lower=np.where(wb, -1, new[wl]),
                    wake_at_base=wb, symmetric=symmetric, names=names)


def _meta_mask(net, key, nl, npt):
    """Panel mask ``net.meta[key]`` as (nl, npt) booleans (all False when absent)."""
    if key not in net.meta:
        return np.zeros((nl, npt), bool)
    return np.asarray(net.meta[key], bool).reshape(nl, npt)


def _edge_key(a, b, tol):
    return tuple(sorted((tuple(np.round(a / tol).astype(np.int64)),
                         tuple(np.round(b / tol).astype(np.int64)))))


def _attach_wake(net, edge_map, centroids, tol):
    """Find which side of a wake network is its trailing edge; return the
    wake panels and, per panel, the upper and lower body panels."""
    pts = net.points
    cr = _grid_corners(pts)                       # cr[i, j]: between lines i, i+1 and points j, j+1
    sides = {  # side -> (points along the side, strips of panels hanging from each edge, TE row)
        "line0": (pts[0], cr.transpose(1, 0, 2, 3), 0),
        "lineN": (pts[-1], cr.transpose(1, 0, 2, 3), -1),
        "point0": (pts[:, 0], cr, 0),
        "pointN": (pts[:, -1], cr, -1),
    }
    best = None
    for side, (edge_pts, strips, row) in sides.items():
        found = []
        for a, b in zip(edge_pts[:-1], edge_pts[1:]):
            if np.linalg.norm(a - b) <= tol:
                found.append(None)
                continue
            found.append(edge_map.get(_edge_key(a, b, tol)))
        hits = sum(1 for f in found if f is not None and len(f) == 2)
        if best is None or hits > best[0]:
            best = (hits, found, edge_pts, strips, row)
    hits, found, edge_pts, strips, row = best
    # wake panels inside a closed surface (a wake routed through a fin behind it,
    # panair.mesh._wake_through) are left out
    interior = _meta_mask(net, "interior", *cr.shape[:2])
    keep = interior.T if strips is not cr else interior
    keep = ~keep
    valid = [f for f in found if f is not None]
    if hits == 0 or any(len(f) != 2 for f in valid):
        raise InputError(f"wake network '{net.name}': its upstream edge must lie on edges "
                         "shared by exactly two surface panels (a trailing edge)",
                         field=f"network '{net.name}'")
    corners, up, lo = [], [], []
    for s, f in enumerate(found):
        if f is None:
            continue
        strip = strips[s]
        _, _, wn, _ = planar_corners(strip[[row]])
        te = 0.5 * (edge_pts[s] + edge_pts[s + 1])
        h = [(centroids[p] - te) @ wn[0] for p in f]
        upper, lower = (f[0], f[1]) if h[0] >= h[1] else (f[1], f[0])
        strip = strip[keep[s]]
        corners.append(strip)
        up.extend([upper] * len(strip))
        lo.extend([lower] * len(strip))
    return np.concatenate(corners), np.array(up), np.array(lo)


#: Largest distance [x configuration size] between a panel's mirrored corners and its
#: twin's for :func:`mirror_map` (meshes built mirror-symmetric agree to ~1e-15)
MIRROR_TOL = 1e-10


def _reflection(normal):
    """v -> v reflected in the plane through the x axis with unit normal ``normal``
    (0, n_y, n_z); the x-z plane (normal (0, 1, 0)) exactly as y -> -y."""
    n = np.asarray(normal, float)
    if n[0] == 0.0 and n[1] == 1.0 and n[2] == 0.0:
        flip = np.array([1.0, -1.0, 1.0])
        return lambda v: v * flip
    return lambda v: v - 2.0 * (v @ n)[..., None] * n


def mirror_map(panels: PanelSet, normal=(0.0, 1.0, 0.0)) -> np.ndarray | None:
    """Mirror twins of a full model's panels in the x-z plane (or in the plane through
    the x axis with unit normal ``normal`` = (0, n_y, n_z)), or None.

    ``p[i]`` is the panel whose corners are panel ``i``'s mirrored (y -> -y, within
    MIRROR_TOL x the configuration size) with the mirrored normal (``p[i] == i`` for a
    panel that is its own image), every wake panel has such a twin shedding from the
    twins of its trailing-edge panels (upper and lower swapped where the twin's normal
    is reversed: a wake in the plane), and twins agree in ``integrate``.  Then the
    linear system of a flow symmetric in that plane (no sideslip) is invariant under
    the permutation, its unique solution takes equal values on twins, and the solvers
    solve it for one panel of each pair (:class:`MirrorFold`), with the same solution
    to rounding.  None for a half model or a mesh that is not its own mirror image.
    """
    from scipy.spatial import cKDTree
    if panels.symmetric or panels.n == 0:
        return None
    reflect = _reflection(normal)
    size = float(np.ptp(panels.corners.reshape(-1, 3), axis=0).max()) or 1.0
    tol = MIRROR_TOL * size

    def twins(corners):
        flat, cen, nrm, _ = planar_corners(corners)
        dist, p = cKDTree(cen).query(reflect(cen))
        if not np.all(dist <= tol):
            return None, None
        mc = reflect(corners)                     # every mirrored corner on a twin corner
        gap = np.linalg.norm(mc[:, :, None, :] - corners[p][:, None, :, :], axis=-1)
        if not np.all(gap.min(axis=2) <= tol) or not np.array_equal(p[p], np.arange(len(p))):
            return None, None
        return p, np.einsum("nj,nj->n", nrm[p], reflect(nrm))

    p, same = twins(panels.corners)
    if p is None or np.any(same < 1 - 1e-6) or not np.array_equal(panels.integrate[p],
                                                                  panels.integrate):
        return None
    if len(panels.wake_corners):
        w, sw = twins(panels.wake_corners)
        if w is None:
            return None
        up, lo = panels.wake_upper, panels.wake_lower
        low = np.where(lo >= 0, p[np.maximum(lo, 0)], -1)
        direct = (sw > 1 - 1e-6) & (up[w] == p[up]) & (lo[w] == low)
        swapped = (sw < -1 + 1e-6) & (lo >= 0) & (up[w] == low) & (lo[w] == p[up])
        if not np.all(direct | swapped):
            return None
    return p


#: Unit normal of the x-z plane, the mirror plane of half models and of :func:`mirror_map`
XZ_NORMAL = (0.0, 1.0, 0.0)


def mirror_plane(panels: PanelSet):
    """A plane through the x axis in which a full model is its own mirror image:
    ``(p, normal)`` with the twins ``p`` of :func:`mirror_map` and the plane's unit
    normal (0, n_y, n_z), or None.  The x-z plane first; else the planes that map the
    first fin onto a fin (a mirror plane of the layout maps fin 0, at roll phi_0,
    onto some fin k: the plane at (phi_0 + phi_k) / 2), e.g. 3 fins rolled 90 deg,
    whose plane through the fin at 210 deg is one (the mesh's seam lies in it,
    :func:`panair.mesh.mesh_rocket`).  Fins are the networks that shed trailing-edge
    wakes; a fin's roll angle is that of the mean of its corners (on its mid-plane).

    The answer is kept on ``panels`` with a digest of its geometry and connectivity (a
    sweep finds it once; its Mach-number jobs get it with the pickled panels)."""
    key = _digest(panels)
    cached = getattr(panels, "_mirror_plane", None)
    if cached is not None and cached[0] == key:
        return cached[1]
    found = _find_mirror_plane(panels)
    panels._mirror_plane = (key, found)
    return found


def _digest(panels: PanelSet) -> str:
    import hashlib
    h = hashlib.sha1()
    for a in (panels.corners, panels.wake_corners, panels.network, panels.integrate,
              panels.wake_upper, panels.wake_lower, panels.wake_at_base):
        h.update(np.ascontiguousarray(a).tobytes())
    h.update(bytes([bool(panels.symmetric)]))
    return h.hexdigest()


def _find_mirror_plane(panels: PanelSet):
    p = mirror_map(panels)
    if p is not None:
        return p, np.array(XZ_NORMAL)
    lifting = ~panels.wake_at_base
    if panels.symmetric or not np.any(lifting):
        return None
    fins = np.unique(panels.network[panels.wake_upper[lifting]])
    mean = [panels.corners[panels.network == f].reshape(-1, 3).mean(axis=0) for f in fins]
    phi = [math.atan2(c[1], c[2]) for c in mean]            # roll, from +z toward +y
    tried = []
    for phi_k in phi:
        psi = (0.5 * (phi[0] + phi_k)) % math.pi               # the plane's angle, mod pi
        if any(abs(math.remainder(psi - t, math.pi)) < 1e-9 for t in tried + [0.0]):
            continue                                           # (x-z: tried above)
        tried.append(psi)
        normal = np.array([0.0, math.cos(psi), -math.sin(psi)])
        p = mirror_map(panels, normal)
        if p is not None:
            return p, normal
    return None


class MirrorFold:
    """A mirror-symmetric mesh's system on one panel per twin pair (``p`` from
    :func:`mirror_map`, the plane's unit ``normal`` from :func:`mirror_plane`):
    rows ``reps`` (the lower index of each pair).

    The even part of a solution (a flow symmetric in the plane) takes equal values on
    twins: ``fold`` adds the columns of twins and ``expand`` copies the
    representatives' values to them.  The odd part (a flow antisymmetric in the
    plane) takes opposite values on twins and 0 on a panel that is its own image:
    ``fold_odd`` subtracts the twins' columns, on the rows of the paired
    representatives only (a panel in the plane has an odd equation 0 = 0), and
    ``expand_odd`` copies with the sign changed.  A linear system invariant under
    the mirror permutation splits exactly into the two (each free stream's even and
    odd parts, :meth:`parts`), each half the size (an eighth of the LU each).
    ``odd`` is False for the x-z plane (flows without sideslip are even there: the
    solvers solve only the even part and refuse sideslip), True for another plane.
    """

    def __init__(self, p: np.ndarray, normal=XZ_NORMAL):
        n = len(p)
        self.n = n
        self.reps = np.nonzero(np.arange(n) <= p)[0]
        pos = -np.ones(n, np.int64)
        pos[self.reps] = np.arange(len(self.reps))
        self.rep_of = pos[np.minimum(np.arange(n), p)]
        self._twin = p[self.reps]
        self._paired = self._twin != self.reps
        self.normal = np.asarray(normal, float)
        self.odd = not np.array_equal(self.normal, XZ_NORMAL)
        self._reflect = _reflection(self.normal)

    def fold(self, M: np.ndarray, rows=None) -> np.ndarray:
        """(m, n) coefficients of all unknowns -> (m, len(reps)); with ``rows`` only
        those rows of ``M`` (without copying them first)."""
        return self._fold(M, rows, self.reps, np.where(self._paired, self._twin, -1), 1.0)

    def expand(self, x: np.ndarray) -> np.ndarray:
        """Values of the representatives (len(reps), ...) -> all panels (n, ...)."""
        return x[self.rep_of]

    @property
    def paired(self) -> np.ndarray:
        """Positions in ``reps`` of the representatives that have a twin (bool mask)."""
        return self._paired

    def fold_odd(self, M: np.ndarray, rows=None) -> np.ndarray:
        """(len(reps), n) coefficients (the representatives' rows, or those ``rows`` of
        ``M``) of all unknowns -> the odd system (n_paired, n_paired): rows and columns
        of the paired representatives, the twins' columns subtracted."""
        rows = np.arange(len(self.reps)) if rows is None else np.asarray(rows)
        return self._fold(M, rows[self._paired], self.reps[self._paired],
                          self._twin[self._paired], -1.0)

    def fold_difference(self, M0, M1, rows, step, odd: bool = False):
        """(fold(M0), (fold(M1) - fold(M0)) / step) for the rows ``rows`` of M0, M1
        (the representatives'), ``step`` per representative; ``odd``: :meth:`fold_odd`
        (rows and steps of the paired ones)."""
        rows = np.asarray(rows, np.int64)
        step = np.asarray(step, float)
        if odd:
            args = (rows[self._paired], self.reps[self._paired], self._twin[self._paired], -1.0)
            step = step[self._paired]
        else:
            args = (rows, self.reps, np.where(self._paired, self._twin, -1), 1.0)
        from .kernels import HAVE_NUMBA, fold_difference
        if HAVE_NUMBA:
            r, a, b, sign = args
            return fold_difference(np.ascontiguousarray(M0, float), np.ascontiguousarray(M1, float),
                                   r, np.asarray(a, np.int64), np.asarray(b, np.int64),
                                   float(sign), np.ascontiguousarray(step))
        f0, f1 = self._fold(M0, *args), self._fold(M1, *args)
        return f0, (f1 - f0) / step[:, None]

    @staticmethod
    def _fold(M, rows, a, b, sign):
        """M[rows][:, a] +- M[rows][:, b] (b < 0: nothing added)."""
        from .kernels import HAVE_NUMBA, fold_columns
        rows = np.arange(len(M)) if rows is None else np.asarray(rows, np.int64)
        if HAVE_NUMBA and M.dtype == np.float64:
            return fold_columns(np.ascontiguousarray(M), rows, np.asarray(a, np.int64),
                                np.asarray(b, np.int64), float(sign))
        out = M[np.ix_(rows, a)]
        has = b >= 0
        if sign > 0:
            out[:, has] += M[np.ix_(rows, b[has])]
        else:
            out[:, has] -= M[np.ix_(rows, b[has])]
        return out

    def expand_odd(self, x: np.ndarray) -> np.ndarray:
        """Odd values of the paired representatives (n_paired, ...) -> all panels:
        their twins the opposite, panels in the plane 0."""
        out = np.zeros((self.n,) + x.shape[1:])
        out[self.reps[self._paired]] = x
        out[self._twin[self._paired]] = -x
        return out

    def basis(self) -> np.ndarray:
        """Rows: the x axis and the plane's cross direction (0, n_z, -n_y), both in the
        plane (symmetric), and its normal (antisymmetric): every vector is a combination."""
        ny, nz = self.normal[1], self.normal[2]
        return np.array([[1.0, 0.0, 0.0], [0.0, nz, -ny], [0.0, ny, nz]])

    def parts(self, v: np.ndarray):
        """(even, odd) parts (v + R v) / 2, (v - R v) / 2 of vectors ``v`` (k, 3) under
        the reflection R in the plane."""
        rv = self._reflect(np.asarray(v, float))
        return 0.5 * (v + rv), 0.5 * (v - rv)
