"""Fin sets: trapezoidal, elliptical and free-form planforms.

Planform coordinates of one fin are local: ``xi`` [m] aft of the root
leading edge (which sits at the set's ``x`` [m] aft of the nose tip) and
``y`` [m] outward from the body surface *at the same x*, so a fin on a
boattail or transition has its root following the surface.  That mapping
(x, y) -> (x, r_body(x) + y) is a shear, so planform area, chords and mean
aerodynamic chord are those of the flat planform.

Mass: strip integration over the span with the section area of
:mod:`~ironbark_opt.rocket.fin_sections`; each strip is a thin chordwise
bar (own transverse moment ``dm c^2/12``, exact for a flat section, an
approximation for the others).  Fin thickness is neglected in the
moments.  For ``count`` >= 3 equally spaced fins the transverse moment is
the same about every diametral axis, ``Int (x - x_cg)^2 dm + 1/2 Int r^2 dm``
(perpendicular-axis average); for 1 or 2 fins this is the mean of the two
transverse moments.
"""
from __future__ import annotations

import abc
import math
import warnings

from dataclasses import dataclass, field
from typing import Callable

import numpy as np

from ironbark_opt.errors import InputError
from ironbark_opt import validate as v
from ironbark_opt.rocket.fin_sections import FinSection
from ironbark_opt.rocket.mass import MassProperties

#: spanwise strips used for mass and MAC integrals
N_STRIPS = 400


@dataclass(frozen=True, kw_only=True)
class FinSet(abc.ABC):
    """Storage common to all fin sets (methods numeric-only).

    Parameters
    ----------
    count : int [-]
        Number of identical fins, equally spaced around the body (>= 1).
    x : float [m]
        Root leading edge, aft of the nose tip.
    thickness : float [m]
        Maximum section thickness.
    cant : float [rad]
        Cant angle of every fin (positive gives positive roll rate).
    section : FinSection
    density : float [kg/m^3] or None
    mass : float [kg] or None
        Mass override of the whole set.
    name : str
    roughness : float [m] or None
        Surface roughness height of the fins (their finish); None: the rocket's
        ``[aero] surface_roughness``.
    roll : float [rad] or None
        Roll angle of the first fin, from the body's +y axis toward +z (the
        x-z plane is the pitch plane; OpenRocket's fin rotation).  None: the
        default layout (an even count with no fin in the pitch plane: 2 fins
        at 0, 4 at 45 deg; an odd count with a fin on top, 90 deg).
    section_lift : tuple or None
        The section's lift data from a file (:mod:`ironbark_opt.rocket.fin_files`):
        ``("curve", (mach, cl_alpha))`` or ``("polar", a0)``; None: thin airfoil.
    """

    count: int = 4
    x: float = 0.0
    thickness: float = 0.0
    cant: float = 0.0
    section: FinSection = field(default_factory=FinSection)
    density: float | None = None
    mass: float | None = None
    name: str = "fins"
    roughness: float | None = None
    roll: float | None = None
    section_lift: tuple | None = None

    @property
    def roll_angle(self) -> float:
        """The first fin's roll angle [rad] (``roll`` or the default layout)."""
        if self.roll is not None:
            return float(self.roll)
        return math.pi / 2 - math.pi / self.count if self.count % 2 == 0 else math.pi / 2

    def _check_common(self) -> None:
        if isinstance(self.count, bool) or not isinstance(self.count, (int, np.integer)) \
                or self.count < 1:
            raise InputError(f"count must be a whole number >= 1, got {self.count!r}",
                             field="count")
        if not isinstance(self.section, FinSection):
            raise InputError("section must be a FinSection", field="section")
        cant = v.number(self.cant, "cant")
        if abs(cant) >= np.pi / 4:
            raise InputError(f"cant must be within +-45 deg, got {np.degrees(cant):.3g} deg",
                             field="cant")
        if self.mass is not None and self.density is None:
            raise InputError("a fin mass override scales the built-up distribution and needs "
                             "a material or density", field="mass")
        v.set_fields(self, count=int(self.count), x=v.nonnegative(self.x, "x"),
                     thickness=v.positive(self.thickness, "thickness"), cant=cant,
                     density=v.optional(v.positive, self.density, "density", "kg/m^3"),
                     mass=v.optional(v.nonnegative, self.mass, "mass", "kg"),
                     roughness=v.optional(v.nonnegative, self.roughness, "surface_roughness", "m"))

    def _check_section_fits(self) -> None:
        """A fin thicker than it is long, or bevels of a double wedge longer together than
        the fin's axial extent, cannot be made (a unit typo: mm for m); shorter bevels meet
        toward a short tip chord by design."""
        extent = float(np.ptp(self.planform_points()[:, 0]))
        if self.thickness > extent:
            raise InputError(f"thickness {self.thickness:.6g} m exceeds the fin's length from "
                             f"leading to trailing edge ({extent:.6g} m)", field="thickness")
        le, te = self.section.le_bevel, self.section.te_bevel
        if le is None:
            return
        if le + te > extent * (1.0 + 1e-9):
            raise InputError(f"le_bevel + te_bevel = {le + te:.6g} m is longer than the fin "
                             f"itself ({extent:.6g} m from leading to trailing edge)",
                             field="le_bevel")

    # -- planform (subclasses) ------------------------------------------------------------
    @abc.abstractmethod
    def planform_points(self, n: int = 64) -> np.ndarray:
        """Outline of one fin, ``(k, 2)`` local ``(xi, y)`` [m] from root LE to root TE."""

    @abc.abstractmethod
    def _strips(self, n: int):
        """``(y, dy, xi_le, chord)`` [m] of spanwise strips (numeric)."""

    @abc.abstractmethod
    def planform_area(self) -> float:
        """Area of one fin's planform [m^2]."""

    # -- derived ------------------------------------------------------------------------------
    @property
    def x_end(self) -> float:
        """Aft-most point of the fins [m] aft of the nose tip."""
        return self.x + float(np.max(self.planform_points()[:, 0]))

    def wetted_area(self) -> float:
        """Both faces of all fins [m^2] (2 x planform x count)."""
        return 2.0 * self.count * self.planform_area()

    def outline(self, n: int = 128):
        """Leading edge and chord along the span, from the planform polygon.

        Returns ``(fraction, xi_le, chord)``: ``n + 1`` span fractions from 0
        (root) to 1 (tip) with the leading edge [m] aft of the root leading
        edge and the chord [m] (first to last crossing of the outline at that
        height; notches are filled, as for the MAC).  Numeric-only.
        """
        pts = np.asarray(self.planform_points(257), float)     # odd: a curved tip's apex
        span = float(pts[:, 1].max())
        frac = np.linspace(0.0, 1.0, int(n) + 1)
        le, te = np.empty_like(frac), np.empty_like(frac)
        p, q = pts, np.roll(pts, -1, axis=0)
        for k, y in enumerate(frac * span):
            lo, hi = np.minimum(p[:, 1], q[:, 1]), np.maximum(p[:, 1], q[:, 1])
            on = (lo <= y + 1e-12 * span) & (hi >= y - 1e-12 * span)
            dy = q[on, 1] - p[on, 1]
            flat = np.abs(dy) <= 1e-12 * span
            t = np.where(flat, 0.0, (y - p[on, 1]) / np.where(flat, 1.0, dy))
            xs = np.concatenate([p[on, 0] + t * (q[on, 0] - p[on, 0]), q[on][flat, 0]])
            le[k], te[k] = xs.min(), xs.max()
        return frac, le - le[0], te - le

    def trailing_edge_base_area(self) -> float:
        """Frontal area of the fins' trailing edges that carries base drag [m^2]:
        count x thickness x span x the section's
        :attr:`~ironbark_opt.rocket.fin_sections.FinSection.trailing_edge_base_fraction`."""
        return self.count * self.thickness * self.span * self.section.trailing_edge_base_fraction

    def aspect_ratio(self) -> float:
        """span^2 / planform area of one fin [-]."""
        return self.span ** 2 / self.planform_area()

    def mean_aerodynamic_chord(self) -> float:
        """MAC = (1/S) Int c^2 dy [m] (e.g. Raymer, *Aircraft Design*, eq. 7.7 generalised)."""
        y, dy, _, c = self._strips(N_STRIPS)
        return float(np.sum(c * c * dy) / np.sum(c * dy))

    def mac_position(self) -> tuple[float, float]:
        """``(xi_le, y)`` [m] of the MAC: area-weighted leading edge and spanwise centroid.

        For a trapezoid these are Barrowman's sweep (c_r + 2 c_t) / (3 (c_r + c_t))
        and span (c_r + 2 c_t) / (3 (c_r + c_t)) (Barrowman, NAR R&D report 1966).
        """
        y, dy, xle, c = self._strips(N_STRIPS)
        area = np.sum(c * dy)
        return float(np.sum(xle * c * dy) / area), float(np.sum(y * c * dy) / area)

    def volume(self) -> float:
        """Material volume of the whole set [m^3]."""
        y, dy, _, c = self._strips(N_STRIPS)
        return float(self.count * np.sum(self.section.area(c, self.thickness) * dy))

    def mass_properties(self, body_radius: Callable | float = 0.0) -> MassProperties:
        """Mass build-up of the set (numeric-only).

        Parameters
        ----------
        body_radius : callable x [m] -> r [m], or float [m]
            Body surface radius under the fins (``Rocket.radius_at``).
        """
        if self.density is None:
            return MassProperties(0.0, self.x, np.zeros((3, 3)))
        y, dy, xle, c = self._strips(N_STRIPS)
        t = self.thickness
        dm = self.count * self.density * self.section.area(c, t) * dy
        xc = self.x + xle + self.section.centroid(c, t)
        # mean r^2 along each strip's chord (body radius may vary under a boattail):
        # 3-point Gauss-Legendre, exact for a body radius linear in x
        r2 = np.zeros_like(xc)
        for g, w in zip(*np.polynomial.legendre.leggauss(3)):
            xg = self.x + xle + 0.5 * (1.0 + g) * c
            rb = body_radius(xg) if callable(body_radius) else float(body_radius)
            r2 = r2 + 0.5 * w * (np.asarray(rb, dtype=float) + y) ** 2
        m = float(np.sum(dm))
        cg = float(np.sum(dm * xc) / m)
        i_axial = float(np.sum(dm * r2))
        i_trans = float(np.sum(dm * ((xc - cg) ** 2 + c * c / 12.0)) + 0.5 * i_axial)
        mp = MassProperties.axisymmetric(m, cg, i_trans, i_axial)
        return mp if self.mass is None else mp.scaled_to(self.mass)


@dataclass(frozen=True, kw_only=True)
class TrapezoidalFins(FinSet):
    """Trapezoidal fins.

    Parameters
    ----------
    root_chord, tip_chord : float [m]
        ``tip_chord`` may be 0 (delta fin).
    span : float [m]
        Root to tip, normal to the body axis.
    sweep_length : float [m]
        Axial distance from the root leading edge to the tip leading edge.
    Other parameters as in :class:`FinSet`.
    """

    root_chord: float = 0.0
    tip_chord: float = 0.0
    span: float = 0.0
    sweep_length: float = 0.0

    def __post_init__(self):
        self._check_common()
        v.set_fields(self, root_chord=v.positive(self.root_chord, "root_chord"),
                     tip_chord=v.nonnegative(self.tip_chord, "tip_chord"),
                     span=v.positive(self.span, "span"),
                     sweep_length=v.number(self.sweep_length, "sweep_length"))
        self._check_section_fits()

    def planform_points(self, n: int = 64) -> np.ndarray:
        s, cr, ct, xs = self.span, self.root_chord, self.tip_chord, self.sweep_length
        return np.array([[0.0, 0.0], [xs, s], [xs + ct, s], [cr, 0.0]])

    def planform_area(self) -> float:
        return 0.5 * (self.root_chord + self.tip_chord) * self.span

    def mean_aerodynamic_chord(self) -> float:
        """Closed form 2/3 (c_r + c_t - c_r c_t / (c_r + c_t)) [m] (Barrowman 1966)."""
        cr, ct = self.root_chord, self.tip_chord
        return 2.0 / 3.0 * (cr + ct - cr * ct / (cr + ct))

    def _strips(self, n: int):
        dy = self.span / n
        y = (np.arange(n) + 0.5) * dy
        f = y / self.span
        return (y, np.full(n, dy), f * self.sweep_length,
                self.root_chord + f * (self.tip_chord - self.root_chord))


@dataclass(frozen=True, kw_only=True)
class EllipticalFins(FinSet):
    """Elliptical fins: half an ellipse of axes ``root_chord`` and 2 ``span``.

    Chord c(y) = c_r sqrt(1 - (y/s)^2), centred on the root's mid-chord.
    Parameters ``root_chord`` [m], ``span`` [m]; others as in :class:`FinSet`.
    """

    root_chord: float = 0.0
    span: float = 0.0

    def __post_init__(self):
        self._check_common()
        v.set_fields(self, root_chord=v.positive(self.root_chord, "root_chord"),
                     span=v.positive(self.span, "span"))
        self._check_section_fits()

    @property
    def tip_chord(self) -> float:
        return 0.0

    @property
    def sweep_length(self) -> float:
        return 0.5 * self.root_chord

    def planform_points(self, n: int = 64) -> np.ndarray:
        phi = np.linspace(np.pi, 0.0, max(int(n), 3))
        return np.column_stack([0.5 * self.root_chord * (1.0 + np.cos(phi)),
                                self.span * np.sin(phi)])

    def planform_area(self) -> float:
        """pi c_r s / 4 [m^2] (a half ellipse)."""
        return np.pi * self.root_chord * self.span / 4.0

    def _strips(self, n: int):
        # midpoints in the angle phi (y = s sin phi) resolve the square-root tip
        dphi = 0.5 * np.pi / n
        phi = (np.arange(n) + 0.5) * dphi
        y = self.span * np.sin(phi)
        dy = self.span * np.cos(phi) * dphi
        c = self.root_chord * np.cos(phi)
        return y, dy, 0.5 * (self.root_chord - c), c


#: largest dip of the root trailing edge below the root line, x the span, taken on the root
ROOT_DIP_MAX = 0.25


def _outline_in_our_order(pts: np.ndarray) -> np.ndarray:
    """A fin outline in RocketPy's form (``FreeFormFins`` shape_points: closed, last point
    = first, running root leading edge -> root trailing edge -> over the tip -> back) as
    the same polygon in ours (root leading edge, over the tip, root trailing edge last).
    A root trailing edge below the root line (RocketPy draws a root along a boattail, e.g.
    hedy's, 12 mm over a 108 mm span) is taken on the root, with a warning, when the dip is
    at most :data:`ROOT_DIP_MAX` of the span.  Any other outline is returned unchanged (the
    checks that follow judge it)."""
    if len(pts) >= 4 and np.array_equal(pts[-1], pts[0]):
        pts = pts[:-1]
    if len(pts) >= 3 and np.all(pts[0] == 0.0) and pts[-1, 1] != 0.0 and pts[1, 1] <= 0.0 < pts[1, 0]:
        pts = np.vstack([pts[:1], pts[1:][::-1]])
    span = float(np.max(pts[:, 1]))
    if pts[-1, 1] < 0.0 and pts[-1, 0] > 0.0 and -pts[-1, 1] <= ROOT_DIP_MAX * span:
        warnings.warn(f"freeform fins: the root trailing edge {pts[-1].tolist()} lies {-pts[-1, 1]:g} m "
                      f"below the root line (a root drawn along a boattail); taken on the root "
                      f"[{pts[-1, 0]:g}, 0]", UserWarning, stacklevel=4)
        pts = pts.copy()
        pts[-1, 1] = 0.0
    return pts


@dataclass(frozen=True, kw_only=True)
class FreeformFins(FinSet):
    """Fins with a polygon planform.

    Parameters
    ----------
    points : sequence of (xi [m], y [m])
        Outline from the root leading edge (0, 0) over the tip to the root
        trailing edge (c_r, 0); y >= 0; the polygon must not cross itself.
        RocketPy's closed form (root leading edge, root trailing edge, over the tip,
        back to (0, 0)) is read as the same polygon (:func:`_outline_in_our_order`).
    Other parameters as in :class:`FinSet`.
    """

    points: tuple = ()

    def __post_init__(self):
        self._check_common()
        try:
            pts = np.asarray(self.points, dtype=float)
        except (TypeError, ValueError):
            raise InputError("points must be a list of [x, y] pairs [m]", field="points") from None
        if pts.ndim != 2 or pts.shape[1] != 2 or len(pts) < 3:
            raise InputError("points must be at least three [x, y] pairs [m]", field="points")
        if not np.all(np.isfinite(pts)):
            raise InputError("points must be finite numbers", field="points")
        pts = _outline_in_our_order(pts)
        if np.any(pts[0] != 0.0):
            raise InputError(f"the first point must be the root leading edge [0, 0], got "
                             f"{pts[0].tolist()}", field="points")
        if pts[-1, 1] != 0.0 or pts[-1, 0] <= 0.0:
            raise InputError(f"the last point must be the root trailing edge [c_r > 0, 0], got "
                             f"{pts[-1].tolist()}", field="points")
        if np.any(pts[:, 1] < 0.0):
            raise InputError("all points need y >= 0 (outward from the body)", field="points")
        if _self_intersects(pts):
            raise InputError("the fin outline crosses itself", field="points")
        if abs(_shoelace(pts)) <= 0.0:
            raise InputError("the fin outline has zero area", field="points")
        v.set_fields(self, points=tuple((float(a), float(b)) for a, b in pts))
        self._check_section_fits()

    @property
    def _pts(self) -> np.ndarray:
        return np.array(self.points, dtype=float)

    @property
    def root_chord(self) -> float:
        return float(self._pts[-1, 0])

    @property
    def span(self) -> float:
        return float(np.max(self._pts[:, 1]))

    @property
    def tip_chord(self) -> float:
        pts = self._pts
        tip = pts[np.isclose(pts[:, 1], self.span)]
        return float(np.ptp(tip[:, 0])) if len(tip) > 1 else 0.0

    @property
    def sweep_length(self) -> float:
        pts = self._pts
        tip = pts[np.isclose(pts[:, 1], self.span)]
        return float(np.min(tip[:, 0]))

    def planform_points(self, n: int = 64) -> np.ndarray:
        return self._pts

    def planform_area(self) -> float:
        """Shoelace formula [m^2]."""
        return abs(_shoelace(self._pts))

    def _strips(self, n: int):
        dy = self.span / n
        ys, dys, xles, cs = [], [], [], []
        pts = self._pts
        closed = np.vstack([pts, pts[:1]])
        for y in (np.arange(n) + 0.5) * dy:
            xs = []
            for (x0, y0), (x1, y1) in zip(closed[:-1], closed[1:]):
                if (y0 <= y < y1) or (y1 <= y < y0):
                    xs.append(x0 + (y - y0) * (x1 - x0) / (y1 - y0))
            xs.sort()
            for a, b in zip(xs[0::2], xs[1::2]):
                ys.append(y)
                dys.append(dy)
                xles.append(a)
                cs.append(b - a)
        return np.array(ys), np.array(dys), np.array(xles), np.array(cs)


def _shoelace(p: np.ndarray) -> float:
    x, y = p[:, 0], p[:, 1]
    return 0.5 * float(np.dot(x, np.roll(y, -1)) - np.dot(y, np.roll(x, -1)))


def _self_intersects(p: np.ndarray) -> bool:
    """True if two non-adjacent edges of the closed polygon cross (numeric)."""
    edges = list(zip(p, np.roll(p, -1, axis=0)))
    k = len(edges)

    def cross(o, a, b):
        return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0])

    for i in range(k):
        for j in range(i + 1, k):
            if j == i + 1 or (i == 0 and j == k - 1):
                continue
            a, b = edges[i]
            c, d = edges[j]
            d1, d2 = cross(c, d, a), cross(c, d, b)
            d3, d4 = cross(a, b, c), cross(a, b, d)
            if d1 * d2 < 0 and d3 * d4 < 0:
                return True
    return False
