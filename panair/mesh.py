"""Rocket geometry -> structured panel networks.

The geometry is described here on its own terms (so the mesher does not
depend on the rocket package): a body of revolution ``x, r(x)`` [m] (x aft
of the nose tip) ending in a flat base, plus fin sets.
:func:`panair.geometry_adapter.from_rocket` converts an
``ironbark_opt.rocket.Rocket``.

Networks follow PANAIR's rule (normal = line direction x point direction,
pointing into the flow) and its network kinds:

* ``body`` (surface): meridian lines from the bottom (theta = 0, z < 0)
  through +y; points along x.  A blunt nose gets a ``nosecap``.
* ``base`` (base) and ``basewake`` (the wake tube shed from the base edge,
  ``MeshOptions.wake_length`` body lengths long).
* per fin ``finK`` (surface): spanwise lines root -> tip, points around
  the section from the lower trailing edge over the leading edge to the
  upper trailing edge; ``capK`` (flat tip cap) and ``wakeK`` (trailing-edge
  wake).  Fin sections: ``double_wedge`` (diamond, or hexagonal with
  bevels), ``square``/``rounded`` (a blunt leading edge rounded with radius
  t/2 — a square one too, whose corners the panel method cannot integrate,
  see :meth:`FinGeometry.half_thickness`; the blunt
  trailing edge is closed by a wedge over the last thickness of chord so
  the panel method has a Kutta edge; the wedge's panels carry no force and
  are left out of the supersonic solve — the separated base behind a blunt
  trailing edge is the base-drag model's part, ``BaseDrag(...,
  fin_trailing_edge_area=)``), ``airfoil`` (NACA 00xx).  Fin roots are cut on
  the body surface: two body lines per fin follow the root section, so
  body and fin share their junction points; the body panels between them
  (under the root) stay in the subsonic solve but carry no force.  Any
  planform with a straight root: trapezoidal, or an outline (elliptical,
  free-form: leading edge and chord along the span); fin cant is not meshed.

Half model (``symmetric=True``): y >= 0 only, for configurations
symmetric about the x-z plane with no fin in that plane (e.g. four fins at
45 deg).  Numeric-only.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field, replace
from types import SimpleNamespace

import numpy as np

from ironbark_opt.errors import InputError
from ironbark_opt.rocket.fin_sections import leading_edge_kind

from .lawgs import Network

__all__ = ["BodyGeometry", "FinGeometry", "RocketGeometry", "mesh_rocket", "MeshOptions",
           "tip_options", "tip_cone_fraction"]


@dataclass(frozen=True)
class BodyGeometry:
    """Body of revolution.

    Parameters
    ----------
    x : array [m]
        Stations aft of the nose tip, non-decreasing (a repeated x is a step).
    r : array [m]
        Radius at each station (>= 0); the body ends in a flat base of
        radius ``r[-1]`` (0 = closed tail).
    """

    x: np.ndarray
    r: np.ndarray

    def __post_init__(self):
        x = np.asarray(self.x, float)
        r = np.asarray(self.r, float)
        if x.ndim != 1 or x.shape != r.shape or len(x) < 2:
            raise InputError("body x and r must be 1-D arrays of equal length >= 2", field="body")
        if np.any(np.diff(x) < 0) or np.any(r < 0) or not np.all(np.isfinite(x + r)):
            raise InputError("body x must be non-decreasing and r >= 0, finite", field="body")
        if r.max() <= 0:
            raise InputError("body has zero radius everywhere", field="body.r")
        object.__setattr__(self, "x", x)
        object.__setattr__(self, "r", r)

    def radius_at(self, x):
        """Radius [m] at ``x`` [m] (the aft value at a step)."""
        return np.interp(x, self.x, self.r)

    def separated_transitions(self) -> list[tuple[float, float, float, float]]:
        """``(x_fore, x_aft, r_fore, r_aft)`` [m] of each contracting run of the
        profile (a boattail, a mid-body reducer) that Niskanen's criterion (OpenRocket
        technical documentation, 2013, eq. 3.88: gamma = length / (fore diameter -
        aft diameter) < 1) calls fully separated: such a transition carries base
        pressure on its annulus (:func:`ironbark_opt.aero.empirical_drag.
        boattail_separation_fraction`, the criterion the subsonic table uses).  An abrupt
        step down (two stations at one x: a wide tube on a narrow one without a
        transition) is such a run of length 0 (gamma 0): until session 22 it was left out,
        meshed as an attached steep cone over one panel strip and its annulus given no
        drag (a 157 -> 133 mm step, tests/odd_rockets.py seed 10 without its reducer:
        zero-lift pressure + base CA 0.098 -> 0.136 at Mach 0.35, 0.221 -> 0.248 at
        Mach 2; CN-alpha at Mach 2 8.16 -> 8.53 /rad, the attached cone's negative
        lift gone)."""
        from ironbark_opt.aero.empirical_drag import boattail_separation_fraction
        x, r = self.x, self.r
        out, i, n = [], 0, len(x)
        while i < n - 1:
            j = i                                   # the contracting run from station i
            while j < n - 1 and x[j + 1] >= x[j] and r[j + 1] < r[j]:
                j += 1
            run = SimpleNamespace(fore_radius=float(r[i]), aft_radius=float(r[j]), length=float(x[j] - x[i]))
            if j > i and boattail_separation_fraction(run) >= 1.0:
                out.append((float(x[i]), float(x[j]), float(r[i]), float(r[j])))
            i = max(j, i + 1)
        return out


@dataclass(frozen=True)
class FinGeometry:
    """A set of identical fins (trapezoidal, or any outline), equally spaced in roll.

    Parameters
    ----------
    count : int
    root_chord, tip_chord, span, sweep : float [m]
        ``sweep`` = axial distance root LE -> tip LE; span from the body
        surface.
    x_root : float [m]
        Root leading edge aft of the nose tip.
    thickness : float [m]
    roll : float [rad]
        Roll angle of the first fin from +z (up) toward +y.
    section : str
        ``double_wedge``, ``square``, ``rounded`` or ``airfoil``.
    le_bevel, te_bevel : float [m] or None
        Bevel lengths of a hexagonal section (None: sharp diamond).
    outline : (span_fraction, le_offset, chord) arrays or None
        A non-trapezoidal planform (elliptical, free-form): the leading-edge
        offset aft of the root leading edge [m] and the chord [m] at
        increasing span fractions from 0 (root) to 1 (tip), linearly
        interpolated.  None: the trapezoid of root_chord, tip_chord, sweep.
    blunt_leading_edge : bool
        Set by :meth:`sharpened`: the leading-edge bevel stands in for a
        blunt edge (its panels carry no axial force).
    blunt_trailing_edge : bool
        Set by :meth:`sharpened`: the trailing-edge bevel closes a blunt edge
        (its panels carry no axial force, as the leading edge's wedge).
    stand_in_first : bool
        Set by :meth:`sharpened` for a hexagon with one square edge: on a chord too
        short for both bevels the square edge's stand-in wedge keeps its length (up
        to half the chord) and the user's bevel takes the rest (:meth:`bevels`).
    """

    count: int
    root_chord: float
    tip_chord: float
    span: float
    sweep: float
    x_root: float
    thickness: float
    roll: float = np.pi / 4
    section: str = "double_wedge"
    le_bevel: float | None = None
    te_bevel: float | None = None
    outline: tuple | None = field(default=None, compare=False)
    blunt_leading_edge: bool = False
    blunt_trailing_edge: bool = False
    stand_in_first: bool = False

    def __post_init__(self):
        for name in ("root_chord", "span", "thickness"):
            if not getattr(self, name) > 0:
                raise InputError(f"fin {name} must be > 0 [m]", field=f"fins.{name}")
        if self.tip_chord < 0 or int(self.count) < 1:
            raise InputError("fin tip_chord >= 0 [m] and count >= 1 required", field="fins")
        if self.section not in ("double_wedge", "square", "rounded", "airfoil"):
            raise InputError(f"unknown fin section {self.section!r}", field="fins.section")
        if self.outline is not None:
            fr, le, ch = (np.asarray(a, float) for a in self.outline)
            if not (fr.ndim == 1 and fr.shape == le.shape == ch.shape and len(fr) >= 2
                    and fr[0] == 0.0 and fr[-1] == 1.0 and np.all(np.diff(fr) > 0)
                    and np.all(ch >= 0) and np.all(np.isfinite(le))):
                raise InputError("fin outline: span fractions 0 ... 1 increasing, chords >= 0",
                                 field="fins.outline")
            if abs(ch[0] - self.root_chord) > 1e-9 * self.root_chord or abs(le[0]) > 1e-12 \
                    or abs(ch[-1] - self.tip_chord) > 1e-9 * self.root_chord:
                raise InputError("fin outline must start at the root chord (offset 0) and end "
                                 "at the tip chord", field="fins.outline")
            object.__setattr__(self, "outline", (fr, le, ch))

    def chord_at(self, fraction):
        """Chord [m] at span ``fraction`` (0 root ... 1 tip)."""
        if self.outline is None:
            return self.root_chord + fraction * (self.tip_chord - self.root_chord)
        return np.interp(fraction, self.outline[0], self.outline[2])

    def fin_angles(self) -> np.ndarray:
        """Roll angle [rad] of each fin, from +z toward +y, in [0, 2 pi)."""
        return (self.roll + 2 * np.pi * np.arange(int(self.count)) / int(self.count)) % (2 * np.pi)

    def le_at(self, fraction):
        """Leading edge [m] aft of the root leading edge at span ``fraction``."""
        if self.outline is None:
            return fraction * self.sweep
        return np.interp(fraction, self.outline[0], self.outline[1])

    @property
    def leading_edge_kind(self) -> str:
        """:func:`ironbark_opt.rocket.fin_sections.leading_edge_kind` of this fin's section."""
        return leading_edge_kind(self.section, self.le_bevel)

    def trailing_edge_closure(self, chord) -> float:
        """Chordwise length [m] of the wedge that closes a blunt trailing edge
        (square, rounded, or a hexagon with te_bevel = 0) for the panel
        method; 0 for a sharp trailing edge.  Its panels carry no force: the
        separated base behind a blunt edge is the base-drag model's part."""
        if self.section in ("square", "rounded"):
            return min(self.thickness, chord / 2)
        if self.blunt_trailing_edge:
            return self.bevels(chord)[1]
        if self.section == "double_wedge" and self.te_bevel == 0.0:
            # a square trailing edge: the square section's closure (until session 19 a step
            # over the last chordwise panel; where the leading-edge bevel took the whole
            # chord, toward a short tip, that panel stood square to the stream and the
            # subsonic equations were singular: |Cp| 1.5e5)
            return min(self.thickness, chord / 2)
        return 0.0

    def bevels(self, chord) -> tuple[float, float]:
        """Leading- and trailing-edge bevel lengths [m] of a double wedge at ``chord``
        [m] (None: the ridge at mid-chord; scaled down to fit a short chord)."""
        le = chord / 2 if self.le_bevel is None else self.le_bevel
        te = chord / 2 if self.te_bevel is None else self.te_bevel
        if self.stand_in_first and le + te > chord:
            # scaled together, a bevel much longer than the chord squeezed the stand-in
            # wedge to a sliver steeper than the Mach cone (le_bevel 5.7 m on a 0.28 m
            # chord: 48 superinclined panels at Mach 1.5, local inclination)
            if self.blunt_trailing_edge:
                te = min(te, chord / 2)
                return chord - te, te
            le = min(le, chord / 2)
            return le, chord - le
        k = min(1.0, chord / (le + te)) if le + te > 0 else 1.0
        return le * k, te * k

    def sharpened(self, wedge: float) -> "FinGeometry":
        """A blunt (square, rounded) leading edge replaced by a wedge ``wedge``
        fin thicknesses long and the blunt trailing edge closed by another (the
        section becomes a hexagon; neither wedge carries axial force); a
        round-nosed airfoil likewise, with a sharp trailing edge bevelled over
        the aft 70 % of the mean chord; other sections
        unchanged.  The wedge's panels carry no
        axial force: linear supersonic theory cannot solve a blunt edge (it is
        superinclined), so its drag is modelled separately (panair.sweep)."""
        if wedge <= 0:
            return self
        if self.section == "double_wedge" and self.le_bevel is not None:
            # a hexagon with one edge unbevelled (bevel 0: a square edge, e.g. a plate with
            # only its leading edge bevelled) has that edge's square face: superinclined at
            # the leading edge, and at the trailing edge a step that left the tip caps
            # Mach-inclined and the influence matrix singular (Basic Finner planform with a
            # bevelled leading edge and a square trailing edge: Mach 1.8 singular, 2.4 and
            # 3.1 superinclined, all to local inclination).  Each square edge gets the
            # square section's wedge and its flags, the bevelled one is kept.
            le, te = self.le_bevel, self.te_bevel
            if le > 0 and te > 0:
                return self
            return replace(self, le_bevel=le if le > 0 else wedge * self.thickness,
                           te_bevel=te if te > 0 else wedge * self.thickness,
                           blunt_leading_edge=le == 0, blunt_trailing_edge=te == 0,
                           stand_in_first=True)
        if self.section not in ("square", "rounded", "airfoil"):
            return self
        if self.section == "airfoil":
            # a round-nosed NACA 00xx section: the same leading-edge wedge, and a sharp
            # trailing edge bevelled from the maximum thickness at 30 % of the mean chord
            mean_chord = 0.5 * (float(self.chord_at(0.0)) + float(self.chord_at(1.0)))
            return replace(self, section="double_wedge", le_bevel=wedge * self.thickness,
                           te_bevel=0.7 * mean_chord, blunt_leading_edge=True)
        # the blunt trailing edge closed by a wedge as long as the leading edge's (no
        # axial force on it: the base behind a blunt edge is the base-drag model's); a
        # square step there made the body panels behind a fin root singular in
        # cross-flow wherever the body runs on past the fins (EuRoC'22 Andromeda,
        # Cp -7.8 at Mach 1.5, alpha 2 deg)
        return replace(self, section="double_wedge", le_bevel=wedge * self.thickness,
                       te_bevel=wedge * self.thickness, blunt_leading_edge=True,
                       blunt_trailing_edge=True)

    def half_thickness(self, xi, chord):
        """Half thickness [m] at ``xi`` [m] aft of the local leading edge."""
        t, c = self.thickness, chord
        s = np.clip(xi / max(c, 1e-300), 0.0, 1.0)
        if self.section == "double_wedge":
            le, te = self.bevels(c)
            if self.te_bevel == 0.0:        # square trailing edge: closed as the square section's
                te = self.trailing_edge_closure(c)
            h = np.minimum(np.minimum(xi / max(le, 1e-300), (c - xi) / max(te, 1e-300)), 1.0)
            return 0.5 * t * np.clip(h, 0.0, 1.0)
        if self.section == "airfoil":   # NACA 00xx, Abbott & von Doenhoff (1959) eq. 6.2, closed TE
            return 5 * t * (0.2969 * np.sqrt(s) - 0.1260 * s - 0.3516 * s**2
                            + 0.2843 * s**3 - 0.1036 * s**4)
        tail = np.clip((c - xi) / self.trailing_edge_closure(c), 0.0, 1.0)   # TE closure wedge
        # square and rounded: a round nose of radius t/2.  A square leading edge is
        # meshed as the rounded one (subsonic meshes; supersonic ones replace both by
        # a wedge, :meth:`sharpened`).  The lift of attached potential flow is
        # rho U Gamma whatever the leading edge's shape (Kutta-Joukowski theorem, e.g.
        # Anderson, Fundamentals of Aerodynamics, 5th ed., sec. 3.16), Gamma being set
        # by the Kutta condition at the trailing edge (the same closure here); but the
        # panel method cannot integrate the pressure at the square edge's two corners
        # (the flow round a 90-degree corner is singular as r^(-1/3)): with the same
        # Gamma, the square fins' pressure-integrated normal force fell 16-18 % short
        # of their own Kutta-Joukowski force 2 Gamma w per strip (rounded within
        # 1-2 %), and meshing the face with 4 ... 16 panels did not converge (body + 4
        # fins, t/c 3.9 %, Mach 0.5: CN-alpha 12.45, 12.89, 12.81, 12.35 /rad; rounded
        # 13.98, Diederich with slender-body interference 14.25); the face's zero-lift
        # axial force was CA 0.26 where d'Alembert's is 0 (rounded 0.008).  Its drag
        # is the empirical edge drag's (empirical_drag.separated_pressure_ca by the
        # section kind: Niskanen 2013 eq. 3.86-3.87 for square edges)
        nose = np.sqrt(np.clip(1 - (1 - np.minimum(xi, t / 2) / (t / 2)) ** 2, 0, 1))
        return 0.5 * t * np.minimum(nose, tail)


@dataclass(frozen=True)
class RocketGeometry:
    """Body plus fin sets; ``name`` for titles."""

    body: BodyGeometry
    fins: tuple = ()
    name: str = "rocket"

    def with_fins_rolled(self, offset: float) -> "RocketGeometry":
        """The same rocket with every fin set rolled ``offset`` [rad] further (from +z
        toward +y)."""
        return replace(self, fins=tuple(replace(f, roll=(f.roll + offset) % (2 * np.pi)) for f in self.fins))


POINTED_TIP_STRIP = 1.0
"""Smallest width of the strip closing a pointed fin tip in subsonic meshes [fin
thicknesses, at most half the span] (:func:`_span_stations`): its triangles then
rise at most atan(1/2) = 27 deg from the fin plane."""

SUPERSONIC_LE_WEDGE = 3.0
"""Length of the wedge standing in for a blunt fin leading edge in supersonic
meshes [fin thicknesses]: half-angle atan(1/6) = 9.5 deg, subinclined (the
wetted panels shallower than the Mach cone) up to Mach 6."""


@dataclass(frozen=True)
class MeshOptions:
    """Mesh density.  ``refine`` multiplies every count (2 = twice finer).

    n_theta : panels around the full circle; n_nose : axial panels on the
    nose; body_spacing : axial panel length on the rest of the body
    [calibers]; n_chord : chordwise panels per fin side; n_span : spanwise
    panels per fin; wake_length : wake length [body lengths];
    chord_clustering : 0 uniform ... 1 full cosine clustering of the
    chordwise stations at the fin leading and trailing edges;
    supersonic_span_factor, supersonic_chord_factor : n_span and n_chord are
    multiplied by these for supersonic Mach numbers (:meth:`for_mach`; the defaults
    mesh the fins 12 x 20 subsonic, 12 x 30 supersonic); blunt_le_wedge : blunt (square,
    rounded) fin leading edges are meshed as a wedge this many fin
    thicknesses long (0: as they are; :meth:`for_mach` sets
    ``SUPERSONIC_LE_WEDGE`` for supersonic Mach numbers, where linear theory
    cannot solve a blunt edge; :meth:`FinGeometry.sharpened`); tip_mach :
    the supersonic Mach numbers the mesh is solved at (empty: none): a
    nose tip steeper than their Mach cones is meshed as a cone (see
    :func:`_sharpened_tip`); mirror_seam : the seam of a full-circle mesh goes in
    the widest gap between fins nearest the x-z plane (else the first widest gap):
    a layout that is its own mirror image in that plane (3 fins rolled 0 deg) is
    then meshed as one, which both solvers solve on half its panels
    (:func:`panair.solver.panels.mirror_map`).  Supersonic meshes too since the
    fin sides are decided with a tolerance (:func:`panair.solver.supersonic._fin_sides`;
    with the sign of rounding noise, Bella Lui's Mach 1.2 failed with this seam);
    separated_transitions : a boattail or reducer that Niskanen's eq. 3.88 calls
    fully separated (:meth:`BodyGeometry.separated_transitions`) is left out of the
    solve, its drag the base pressure on its annulus (:meth:`for_mach` sets it for
    supersonic Mach numbers; subsonic tables take the zero-lift drag of such a
    transition from the same criterion, :mod:`panair.transonic`); sharp_le_axial :
    the axial force of the first panel behind a sharp fin leading edge (a double
    wedge's) is integrated (True, :meth:`for_mach`'s supersonic meshes: the edge wedge's
    wave drag) or left out (False, subsonic): attached potential flow puts a leading-edge
    suction there that a sharp edge cannot sustain, the flow separating at the edge instead
    (Polhamus, NASA TN D-3767, 1966: the suction is lost, its force turning normal); with
    it the Kestrel's table CA at 8 deg went negative at Mach 0.35 (0.071 -> -0.055) and the
    Basic Finner's CA(4 deg) - CA(0) was -0.0136 against PANAIR's -0.0090 (without it
    -0.0077).  Rounded and airfoil edges keep theirs (a round nose sustains suction).
    fin_strips : how the fin strips are spaced along the span (:func:`_span_stations`):
    ``"outline"`` (subsonic) shares the planform outline's length and keeps the strip
    closing a pointed tip one fin thickness wide; ``"sine"`` (:meth:`for_mach`'s
    supersonic meshes, as before session 17) equal strips, sine-spaced on an
    outline, whose pointed tips' sideways slivers the supersonic solver treats as a
    tip cap (:func:`panair.solver.supersonic._pointed_tip_closure`).

    Why two fin meshes: the two solvers converge differently in the fin
    strip width (measured on the Basic Finner, session 2).  The supersonic
    source solution needs narrow strips: Mach 1.6, n_span 6 -> 12 moves
    CN-alpha +2.0 % and Cm-alpha +3.3 %, and with 12 strips the default vs
    twice-finer change is under 1.3 %.  The subsonic doublet solution
    converges on PANAIR from above as the strips narrow (Basic Finner, Mach
    0.6, n_span 6 / 9 / 12 / 24: CN-alpha +3.4 / +2.1 / +1.4 / +0.5 %,
    Cm-alpha +4.2 / +2.4 / +1.4 / +0.1 %) and hardly with the chordwise count
    (12 strips, n_chord 15 / 20 / 30 / 45: CN-alpha +1.39 / +1.39 / +1.41 /
    +1.43 %), so the subsonic fins are 12 x 20 (session 17; before: 6 x 30):
    Basic Finner Mach 0.4 / 0.6 / 0.8 CN-alpha +3.3 / +3.4 / +3.6 -> +1.4 / +1.4 /
    +1.5 %, Cm-alpha +4.2 / +4.2 / +4.4 -> +1.3 / +1.3 / +1.3 % vs PANAIR, default
    vs twice finer CN-alpha -1.6 -> -0.4 %, at about the same panel count (1948 ->
    1976); the supersonic fins stay 12 x 30 (supersonic_chord_factor 1.5).  That
    needed the pointed tips meshed without slivers (:attr:`fin_strips`; ICL APEX
    did not build on sine strips).  (Until the sharp leading edge entered the
    surface-gradient stencil, session 15, 6 looked best, -1.9 %, and 12 / 24
    drifted to -3.8 / -4.7 %: the leading-edge loss cancelled the strip-width error.)
    """

    n_theta: int = 32
    n_nose: int = 20
    body_spacing: float = 0.4
    n_chord: int = 20
    n_span: int = 12
    wake_length: float = 5.0
    refine: float = 1.0
    chord_clustering: float = 1.0
    supersonic_span_factor: float = 1.0
    supersonic_chord_factor: float = 1.5
    blunt_le_wedge: float = 0.0
    tip_mach: tuple = ()
    mirror_seam: bool = True
    separated_transitions: bool = False
    sharp_le_axial: bool = False
    fin_strips: str = "outline"

    def scaled(self, name):
        return max(2, int(round(getattr(self, name) * self.refine)))

    def for_mach(self, mach: float) -> "MeshOptions":
        """The options to mesh with for Mach ``mach`` [-] (supersonic: finer fin strips)."""
        if mach <= 1.0:
            return self
        if self.supersonic_span_factor == 1.0 and self.supersonic_chord_factor == 1.0 \
                and self.blunt_le_wedge > 0 and self.separated_transitions and self.sharp_le_axial \
                and self.fin_strips == "sine":
            return self
        return replace(self, n_span=max(1, int(round(self.n_span * self.supersonic_span_factor))),
                       n_chord=max(1, int(round(self.n_chord * self.supersonic_chord_factor))),
                       supersonic_span_factor=1.0, supersonic_chord_factor=1.0,
                       blunt_le_wedge=self.blunt_le_wedge or SUPERSONIC_LE_WEDGE,
                       separated_transitions=True, sharp_le_axial=True, fin_strips="sine")


def _chord_stations(n, clustering):
    """Chordwise stations in [0, 1]: blend of uniform and cosine spacing."""
    s = np.linspace(0.0, 1.0, n + 1)
    return (1 - clustering) * s + clustering * 0.5 * (1 - np.cos(np.pi * s))


MIN_STRIPS_BETWEEN_ROOTS = 2
"""Fewest strips of body panels between two neighbouring fin-root meridians.  A single
strip had root lines (and their zero-width slivers) on both sides, and its surface
gradient took a fin wake's potential jump: two fin sets with roots 15 deg apart (3 fins,
4 canards) gave body Cp -38 and CN of the wrong sign (tests/unit/
test_panair_fin_sets_close_roots.py).  Changes only gaps under 1.5 x the mesh's spacing
(16.9 deg at 32 lines): two fin sets, or more than 21 fins."""


def _meridians(th_start: float, th_end: float, fin_thetas, n_theta: int) -> np.ndarray:
    """Body meridian angles [rad] from ``th_start`` to ``th_end``, with every fin
    root angle on a line and each gap between them split evenly at about
    2 pi / ``n_theta``.  Equal spacing around the circle left a fin root between
    two lines where the fins do not divide the circle like the mesh (3 fins, 32
    lines: a 1.5 deg sliver beside each root), and the supersonic solution was
    singular at the fin trailing edges (EuRoC'22 Andromeda, Cp 5e8 at Mach 1.5).
    Fins that fall on the even spacing (4 fins rolled 45 deg) keep the same mesh."""
    bounds = sorted({th_start, th_end, *(t for t in fin_thetas if th_start < t < th_end)})
    step = 2.0 * np.pi / n_theta
    out = [th_start]
    for a, b in zip(bounds[:-1], bounds[1:]):
        k = max(MIN_STRIPS_BETWEEN_ROOTS, int(round((b - a) / step)))
        out.extend(a + (b - a) * np.arange(1, k + 1) / k)
    return np.array(out)


#: Largest B tan(delta) of the conical tip panels: g1 = (1 - (B t)^2) / (1 + (B t)^2)
#: = 0.072, inside the solver's own limit G1_MIN = 0.05 (B t = 0.951;
#: panair.solver.supersonic) with room for the faceting of the flat panels; a tip
#: the solver accepts is left as it is
TIP_BT_MAX = 0.93
#: The conical tip may replace at most this fraction of the nose length.  Measured
#: (session 17, with the per-panel nose blend of panair.solver.supersonic
#: NOSE_WEIGHT_PER_PANEL; TR R-100 fineness-3 noses on a cylinder against Stoney's
#: free-flight pressure drag, tests/validation/test_nose_drag_tr_r100.py, the cone forced
#: longer than the Mach number needs): von Karman at Mach 3.0 (needs 0.21) drag +0.0000 /
#: +0.0026 / +0.0035 / +0.0038 / +0.0041 / +0.0064 / +0.0102 at cone fractions 0.21 / 0.35
#: / 0.50 / 0.58 / 0.66 / 0.73 / 0.79 (data 0.083: +4.9 % at 0.66, +12 % at 0.79), nose
#: CN-alpha 3.18 / 3.18 / 3.03 / 2.95 / 2.91 / 3.00 / 3.22 /rad, CP within 0.05 cal; power 3/4
#: at Mach 2.8 (needs 0.05; data 0.078) drag +0.0005 ... +0.0010 to 0.27, +0.0055 at 0.50,
#: +0.0081 at 0.58, +0.0109 at 0.66 (+14 %), CN-alpha within 3 % and CP within 0.08 cal to
#: 0.58.  0.6: the nose's drag within the issue's 10 % of the data and its CP within 0.1
#: cal on both up to the cosine station 0.58, while a longer cone lets linear theory solve
#: what fell to local inclination at 0.1 (Allen's 3-cal ogive at Mach 3.95 needs 0.58, fin
#: 10 CN-alpha 5.35 -> 8.45 /rad, tunnel 7.09, CP 5.06 -> 6.20 cal, tunnel 6.19; EuRoC
#: Andromeda's 2-cal von Karman at Mach 2.0 needs 0.15).
TIP_MAX_FRACTION = 0.6


def _sharpened_tip(nose_x, body: BodyGeometry, machs) -> list:
    """Nose stations ``nose_x`` [m] (tip first) without those inside a conical
    tip: the first panel runs from the tip to the first station whose secant
    slope r/(x - x_tip) is shallow enough (B tan(delta) <= ``TIP_BT_MAX``) for the
    largest Mach number of ``machs`` that a tip of at most ``TIP_MAX_FRACTION`` of
    the nose length satisfies; the stations as they are when none is (or none
    needs it).  Higher Mach numbers stay superinclined (the solver's fallback).
    A sweep meshes each supersonic Mach number's tip for that Mach number alone
    (:func:`tip_options`).

    Why: the meridian of a Haack (von Karman, LV-Haack) or power-law nose starts
    with an infinite slope (r ~ x^(3/4) for Haack), and the cosine-clustered
    stations make the first ring of panels steeper than the Mach cone: linear
    supersonic theory has no solution for superinclined panels (PAN AIR user's
    manual, NASA CR-3252, 1981, on panel inclination; the solver's check), and the
    whole Mach number fell to local inclination (EuRoC'22 Andromeda: 2 cal von
    Karman nose, 34 tip panels superinclined at Mach 1.5).  A conical tip is the
    usual modelling of such a nose for linear theory; it changes the surface over the
    first few per cent of the nose at low supersonic Mach numbers (Andromeda at Mach 1.5:
    2.4 %), more at high ones (2.0: 15 %; Allen's 3-cal ogive at 3.95: 58 %)."""
    rn = body.radius_at(nose_x)
    sec = rn[1:] / np.maximum(nose_x[1:] - nose_x[0], 1e-300)
    limit = nose_x[0] + TIP_MAX_FRACTION * (nose_x[-1] - nose_x[0]) * (1 + 1e-9)
    for mach in sorted((m for m in machs if m > 1.0), reverse=True):
        ok = np.nonzero(math.sqrt(mach * mach - 1.0) * sec <= TIP_BT_MAX)[0]
        if not len(ok) or nose_x[int(ok[0]) + 1] > limit:
            continue
        first = int(ok[0]) + 1
        return [float(nose_x[0])] + [float(v) for v in nose_x[first:]]
    return [float(v) for v in nose_x]


def _nose_stations(body: BodyGeometry, opt: MeshOptions):
    """(stations [m] of the nose, tip first, conical tip applied; the nose's end x [m])."""
    x, r = body.x, body.r
    d = 2 * r.max()
    keep = [x[0]]
    n_nose = opt.scaled("n_nose")
    # nose = up to the first station where r reaches its first plateau or max
    i_nose = int(np.argmax(r >= 0.999 * r.max()))
    x_nose = x[i_nose] if i_nose > 0 else x[0]
    if x_nose > x[0]:
        s = 0.5 * (1 - np.cos(np.linspace(0, np.pi, n_nose + 1)))
        keep.extend(x[0] + s[1:] * (x_nose - x[0]))
    if len(opt.tip_mach) and len(keep) > 2 and r[0] <= 1e-9 * d:
        keep = _sharpened_tip(np.array(keep), body, opt.tip_mach)
    return keep, x_nose


def tip_cone_fraction(body: BodyGeometry, opt: MeshOptions) -> float:
    """The fraction [-] of the nose length a mesh with ``opt`` replaces by its
    conical tip (:func:`_sharpened_tip`; 0: the stations as they are)."""
    plain, x_nose = _nose_stations(body, replace(opt, tip_mach=()))
    keep, _ = _nose_stations(body, opt)
    if len(keep) == len(plain) or x_nose <= plain[0]:
        return 0.0
    return float((keep[1] - keep[0]) / (x_nose - keep[0]))


def tip_options(geometry, options: MeshOptions, mach: float) -> MeshOptions:
    """The mesh options of supersonic Mach ``mach`` [-] with its nose tip sharpened for
    that Mach number alone (``tip_mach = (mach,)``): ``options`` itself when its
    stations are the same (e.g. a sweep's shared mesh, sharpened for its lowest
    supersonic Mach number, :func:`panair.sweep.supersonic_mesh_options`).  A tip
    sharpened for a higher Mach number moves a lower one (a cone longer than it needs:
    a nose + cylinder at Mach 1.5, CN(2 deg) -13 % with the tip of Mach 2.015)."""
    own = replace(options, tip_mach=(float(mach),))
    if own == options:
        return options
    a, _ = _nose_stations(geometry.body, own)
    b, _ = _nose_stations(geometry.body, options)
    return options if len(a) == len(b) and np.array_equal(a, b) else own


def _axial_stations(body: BodyGeometry, fins, opt: MeshOptions):
    x, r = body.x, body.r
    d = 2 * r.max()
    keep, x_nose = _nose_stations(body, opt)
    step = opt.body_spacing * d / opt.refine
    # keep the corners of the profile after the nose (joints, transitions,
    # boattails: where the slope changes), not every station of a dense profile
    slope = np.diff(r) / np.maximum(np.diff(x), 1e-12 * d)
    corner = np.zeros(len(x), bool)
    corner[1:-1] = np.abs(np.diff(slope)) > 1e-3
    corner[[0, -1]] = True
    breaks = [xx for xx, c in zip(x, corner) if c and xx > x_nose]
    # curved parts after the nose (ogive boattails): at most every 4th station
    sloped = np.zeros(len(x), bool)
    sloped[:-1] |= np.abs(slope) > 1e-6
    sloped[1:] |= np.abs(slope) > 1e-6
    breaks += [xx for xx in x[sloped][::4] if xx > x_nose]
    # an abrupt step down (two stations at one x) closed by a 45 deg strip ahead of it,
    # its own length: with the body's spacing it began up to a calibre ahead, and the
    # supersonic meshes, which leave it out as separated (BodyGeometry.
    # separated_transitions), left out the body beside fin roots ending there
    down = np.nonzero((np.diff(x) <= 0) & (np.diff(r) < 0))[0]
    breaks += [x[i] - (r[i] - r[i + 1]) for i in down if x[i] - (r[i] - r[i + 1]) > x_nose]
    for f in fins:
        breaks += [f.x_root, f.x_root + f.root_chord]
        c = f.root_chord
        u = _chord_stations(opt.scaled("n_chord"), opt.chord_clustering)
        breaks.extend(f.x_root + u * c)          # the fin root's own chordwise stations
    pts = np.unique(np.round(np.concatenate([keep, breaks]), 12))
    out = [pts[0]]
    for a, b in zip(pts[:-1], pts[1:]):
        k = max(1, int(np.ceil((b - a) / step - 1e-9))) if a >= x_nose else 1
        out.extend(a + (b - a) * np.arange(1, k + 1) / k)
    xs = np.unique(np.round(np.array(out), 12))
    return xs


def mesh_rocket(geom: RocketGeometry, *, symmetric: bool = False,
                options: MeshOptions | None = None) -> list[Network]:
    """Panel networks of a rocket (see the module docstring for layout).

    Parameters
    ----------
    geom : RocketGeometry
        Lengths in [m].
    symmetric : bool
        Half model y >= 0 (for :func:`panair.solver.panels.build_panels`
        with ``symmetric=True``).
    options : MeshOptions

    Returns
    -------
    list of Network

    Raises
    ------
    InputError
        A half model with a fin in (or crossing) the symmetry plane.
    """
    opt = options or MeshOptions()
    if opt.blunt_le_wedge > 0:
        geom = replace(geom, fins=tuple(f.sharpened(opt.blunt_le_wedge) for f in geom.fins))
    body = geom.body
    xs = _axial_stations(body, geom.fins, opt)
    rs = body.radius_at(xs)
    n_th = opt.scaled("n_theta")
    th_end = np.pi if symmetric else 2 * np.pi
    n_lines = n_th // 2 + 1 if symmetric else n_th + 1
    theta = np.linspace(0.0, th_end, n_lines)            # from the bottom (-z) through +y
    fin_angles = []
    for f in geom.fins:
        for k in range(int(f.count)):
            phi = (f.roll + 2 * np.pi * k / f.count) % (2 * np.pi)     # from +z toward +y
            th = (np.pi - phi) % (2 * np.pi)
            if symmetric:
                y_root = np.sin(phi) * body.radius_at(f.x_root)
                if abs(y_root) <= f.thickness / 2 + 1e-12 * body.r.max():
                    raise InputError("half model: a fin lies in the symmetry plane y = 0; "
                                     "roll the fins (e.g. roll = 45 deg for 4 fins) or mesh "
                                     "the full configuration", field="fins.roll")
                if y_root < 0:
                    continue                           # mirror image of a y > 0 fin
            fin_angles.append((f, phi, th))
    # Fin roots: two body lines per fin that open from the fin's centre line
    # to the root section's surface (angle asin(h/r)) along the root chord,
    # so body and fin share their junction points (a watertight junction);
    # the footprint between them is inside the fin: no force, no gradient.
    eps = 1e-9
    if not symmetric and fin_angles:
        # put the seam of the full circle mid-way in the widest gap between fins
        ths = np.sort([th for _, _, th in fin_angles])
        gaps = np.diff(np.append(ths, ths[0] + 2 * np.pi))
        k = int(np.argmax(gaps))
        if opt.mirror_seam:
            # of equally wide gaps the one whose middle is nearest the x-z plane (theta
            # 0 or pi), the first on a tie (MeshOptions.mirror_seam)
            mids = (ths + 0.5 * gaps) % np.pi
            off_plane = np.where(gaps >= gaps.max() - 1e-9,
                                 np.round(np.minimum(mids, np.pi - mids), 9), np.inf)
            k = int(np.argmin(off_plane))
        theta0 = ths[k] + 0.5 * gaps[k]
        theta = theta0 + np.linspace(0.0, 2 * np.pi, n_lines)
        fin_angles = [(f, phi, theta0 + (th - theta0) % (2 * np.pi)) for f, phi, th in fin_angles]
    if fin_angles:
        theta = _meridians(theta[0], theta[-1], [th for _, _, th in fin_angles], n_th)
    for (_, _, th) in fin_angles:
        theta = np.concatenate([theta, [th - eps, th + eps]])
    theta = np.unique(np.round(theta, 12))
    T, X = np.meshgrid(theta, xs, indexing="ij")
    R = np.interp(X, xs, rs)
    no_force = np.zeros((len(theta) - 1, len(xs) - 1), bool)
    xc = 0.5 * (xs[:-1] + xs[1:])
    # fins in line (a booster's behind a sustainer's, same roll) share the two lines:
    # each line opens along every root on it
    opened: dict[int, np.ndarray] = {}
    for f, phi, th in fin_angles:
        xi = xs - f.x_root
        h = np.where((xi >= 0) & (xi <= f.root_chord), f.half_thickness(xi, f.root_chord), 0.0)
        lo = int(np.argmin(np.abs(theta - (th - eps))))
        hi = int(np.argmin(np.abs(theta - (th + eps))))
        dang = np.maximum(np.arcsin(np.clip(h / np.maximum(rs, 1e-300), 0.0, 1.0)),
                          opened.get(lo, 0.0))
        opened[lo] = dang
        T[lo] = th - dang
        T[hi] = th + dang
        inside = (xc > f.x_root) & (xc < f.x_root + f.root_chord)
        no_force[lo:hi, :] |= inside[None, :]
    pts = np.stack([X, R * np.sin(T), -R * np.cos(T)], axis=-1)
    meta = {"no_force": no_force}
    if opt.separated_transitions:
        # fully separated boattails and reducers (supersonic meshes): their panels are
        # left out of the solve and carry base pressure instead (panair.sweep adds it on
        # the annulus); attached linear theory there is wrong and, steeper than the
        # Mach cone or expanding past vacuum, has no solution at all
        on = np.zeros(len(xc), bool)
        for x0, x1, _, _ in body.separated_transitions():
            if x1 <= x0:      # an abrupt step: meshed on the strip ahead of it (_axial_stations)
                x0 = float(xs[xs < x1].max())
            on |= (xc > x0) & (xc < x1)
        sep_mask = np.broadcast_to(on[None, :], no_force.shape) & ~no_force
        if sep_mask.any():
            meta["separated"] = np.array(sep_mask)
    nets = []
    nets.append(Network("body", pts, "surface", meta))
    if rs[0] > 1e-9 * rs.max():
        rr = np.linspace(rs[0], 0.0, 3)
        cap = np.stack([np.full((len(theta), 3), xs[0]),
                        rr[None, :] * np.sin(theta)[:, None],
                        -rr[None, :] * np.cos(theta)[:, None]], axis=-1)
        nets.append(Network("nosecap", cap[::-1], "surface"))
    length = xs[-1] - xs[0]
    if rs[-1] > 1e-9 * rs.max():
        rb = np.linspace(rs[-1], 0.0, 3)
        base = np.stack([np.full((3, len(theta)), xs[-1]),
                         rb[:, None] * np.sin(theta)[None, :],
                         -rb[:, None] * np.cos(theta)[None, :]], axis=-1)
        nets.append(Network("base", base[:, ::-1], "base"))
        ring = pts[:, -1]
        far = ring + np.array([opt.wake_length * length, 0, 0])
        nets.append(Network("basewake", np.stack([ring, far], axis=1), "wake"))
    for k, (f, phi, th) in enumerate(fin_angles):
        behind = sorted((g for g, _, th2 in fin_angles
                         if abs(th2 - th) < 1e-9 and g.x_root >= f.x_root + f.root_chord - 1e-12),
                        key=lambda g: g.x_root)
        nets.extend(_fin_networks(f, phi, body, opt, k, length, behind or None))
    return nets


def _wake_through(te, far, behind: list, body) -> tuple[np.ndarray, np.ndarray]:
    """A trailing-edge wake (points ``te`` -> ``far``, one line per span station) that
    meets fins in line behind it (``behind``, front to back: a booster's fins behind a
    sustainer's, same roll): points te, aft leading edge, far, and the mask of the
    panels left out (``interior``): the wake of a span station ends on the leading
    edge of the first fin behind whose span it meets.  (Only the first fin behind was
    looked at until session 20: a sustainer's fin wider than the booster's forward
    set passed beside it into the aft set's fin, in its plane: the stack of two
    stages with two fin sets each in line had |Cp| 3.5e4 at Mach 0.05.)

    Through a thick fin the sheet put that fin's control points on it, where the
    doublet potential jumps (the stack's system was singular: CN ~1e4).  Ending it
    there is the continuous problem's wake through the fin: the part inside the
    closed fin does not change the flow outside (Green's theorem: an interior doublet
    sheet is absorbed by the surface doublets of the Dirichlet formulation), and the
    fin's own Kutta condition sheds at its trailing edge the whole jump mu_upper -
    mu_lower, the circulation of the fin ahead included (a wake restarted from the
    aft trailing edge counted it twice: stack CN-alpha 60-200 /rad).  Span stations
    outside the aft fin's span keep their straight wake."""
    r = np.hypot(te[:, 1], te[:, 2])
    inside = np.zeros(len(te), bool)
    # stations beside every fin behind: their (straight) line is split at the first fin's
    # tip leading edge, where a strip reaching over that tip ends (below)
    x_mid = np.full(len(te), float(behind[0].x_root + behind[0].le_at(1.0)))
    for aft in behind:
        frac = (r - float(body.radius_at(aft.x_root))) / aft.span
        hit = ~inside & (frac >= -1e-9) & (frac <= 1.0 + 1e-9)
        x_mid[hit] = aft.x_root + np.array([aft.le_at(v) for v in np.clip(frac[hit], 0.0, 1.0)])
        inside |= hit
    pts = np.stack([te, te, far], axis=1)
    pts[:, 1, 0] = np.clip(x_mid, te[:, 0], far[:, 0])
    interior = np.zeros((len(te) - 1, 2), bool)
    # a strip with a station inside ends there: a strip reaching over the fin's tip (one
    # station inside, one beside it) carried on past the leading edge ran its sheet
    # through the fin's tip panels (a sustainer's 0.39 m fins ahead of a booster's 0.35
    # m: |Cp| 1.3e6 at Mach 0.05); its shed vorticity leaves at that fin's tip instead
    interior[:, 1] = inside[:-1] | inside[1:]
    return pts, interior


def _span_stations(f: FinGeometry, n_s: int, opt) -> np.ndarray:
    """Span fractions of the fin's ``n_s`` strip edges, 0 (root) ... 1 (tip), by
    :attr:`MeshOptions.fin_strips`.

    ``"sine"``: equal strips, or on an outline sine-spaced ones narrowing toward
    the tip.  ``"outline"``: strips sharing the planform outline's length (leading
    plus trailing edge, :func:`_outline_stations`: equal strips on a trapezoid,
    sine-like at an elliptical tip, where the edges turn chordwise), and the strip
    that closes a pointed tip (chord 0) at least one fin thickness wide
    (:data:`POINTED_TIP_STRIP`), the others sharing the rest.  Why: the closing
    strip is a fan of triangles from the full thickness to the tip point; narrower
    than the thickness, its triangles face sideways like a tip cap, and the
    subsonic surface gradient on them was singular (ICL APEX's fins, Mach 0.05,
    alpha 12 deg, 12 x 20 sine strips: fan 0.4 / 0.9 / 1.4 mm wide (t = 2.5 mm):
    |Cp| 1.8e4 / 4.8e3 / 17; the same planform as a two-point outline, 24 x 40:
    |Cp| 941 on sine strips, 22 on outline strips).  The outline's length also
    follows APEX's planform, whose chord falls fastest near the root, better than
    sine strips: meshed planform area with 6 / 12 strips +9.2 / +1.7 % (sine) ->
    -1.0 / -0.3 %."""
    if opt.fin_strips == "sine":
        s = np.linspace(0.0, 1.0, n_s + 1)
        return np.sin(0.5 * np.pi * s) if f.outline is not None else s
    s = _outline_stations(f, n_s, 1.0)
    if n_s > 1 and f.chord_at(1.0) == 0.0:
        inner = 1.0 - min(POINTED_TIP_STRIP * f.thickness / f.span, 0.5)
        if s[-2] > inner:
            s = np.append(_outline_stations(f, n_s - 1, inner), 1.0)
    return s


def _outline_stations(f: FinGeometry, n: int, end: float) -> np.ndarray:
    """``n`` + 1 span fractions from 0 to ``end`` splitting the length of the
    planform's leading and trailing edges (in the fin plane, from the root to span
    fraction ``end``) into equal parts (equal strips on a trapezoid)."""
    if f.outline is None:
        return np.linspace(0.0, end, n + 1)
    fr = np.union1d(np.linspace(0.0, end, 513), f.outline[0][f.outline[0] < end])
    le = f.le_at(fr)
    te = le + f.chord_at(fr)
    dy = np.diff(fr) * f.span
    arc = np.concatenate([[0.0], np.cumsum(np.hypot(dy, np.diff(le)) + np.hypot(dy, np.diff(te)))])
    s = np.interp(np.linspace(0.0, arc[-1], n + 1), arc, fr)
    s[-1] = end
    return s


def _fin_networks(f: FinGeometry, phi, body, opt, k, length, behind: list | None = None):
    e_r = np.array([0.0, np.sin(phi), np.cos(phi)])      # spanwise
    e_t = np.array([0.0, np.cos(phi), -np.sin(phi)])     # thickness (e_r x e_t = -x ... any)
    n_c = opt.scaled("n_chord")
    n_s = opt.scaled("n_span")
    s = _span_stations(f, n_s, opt)
    # chordwise parameter clustered at LE and TE
    u = _chord_stations(n_c, opt.chord_clustering)
    lines = []
    no_force = np.zeros((n_s, 2 * n_c), bool)       # panels closing a blunt trailing edge
    no_axial = np.zeros((n_s, 2 * n_c), bool)       # a wedge standing in for a blunt LE
    mid = 0.5 * (u[:-1] + u[1:])
    for j, sj in enumerate(0.5 * (s[:-1] + s[1:])):
        chord = f.chord_at(sj)
        if chord <= 0:
            continue
        closure = f.trailing_edge_closure(chord)
        if closure > 0:
            aft = mid >= 1.0 - closure / chord                 # intervals centred in it
            aft[-1] = True
            aft2 = np.concatenate([aft[::-1], aft])            # lower TE -> LE, then upper LE -> TE
            if f.blunt_trailing_edge:
                # supersonic: the pressure difference across the fin carries on to the
                # trailing edge (no Kutta unloading); only the wedge's axial force is
                # left out (the blunt base's drag is the base-drag model's)
                no_axial[j] |= aft2
            else:
                no_force[j] = aft2
        if f.blunt_leading_edge:
            fore = mid * chord < f.bevels(chord)[0]
            no_axial[j] |= np.concatenate([fore[::-1], fore])
        elif f.section == "double_wedge" and not opt.sharp_le_axial:
            fore = np.arange(n_c) == 0                          # the panel behind the sharp edge
            no_axial[j] |= np.concatenate([fore[::-1], fore])
    for sj in s:
        chord = f.chord_at(sj)
        xle = f.x_root + f.le_at(sj)
        xi = u * chord
        h = f.half_thickness(xi, chord) if chord > 0 else np.zeros_like(xi)   # pointed tip
        r_root = body.radius_at(xle + xi)
        # the root follows the body; the span is measured from the body at the root
        # leading edge, so the tip stays straight over a boattail or transition
        r_le = float(body.radius_at(f.x_root))
        rad = np.sqrt(np.maximum(r_root**2 - h**2, 0.0)) + sj * (f.span + r_le - r_root)
        lower = (xle + xi)[:, None] * np.array([1.0, 0, 0]) + rad[:, None] * e_r - h[:, None] * e_t
        upper = (xle + xi)[:, None] * np.array([1.0, 0, 0]) + rad[:, None] * e_r + h[:, None] * e_t
        # from lower TE over LE to upper TE
        lines.append(np.vstack([lower[::-1], upper[1:]]))
    fin = np.array(lines)
    masks = {"separated": no_force, "no_axial": no_axial}
    meta = {key: m for key, m in masks.items() if m.any()}
    net = Network(f"fin{k}", fin, "surface", meta)
    if _cell_normal(fin, 0, n_c + n_c // 2) @ e_t < 0:      # an upper-side panel
        net = Network(f"fin{k}", fin[:, ::-1], "surface",
                      {key: m[:, ::-1] for key, m in meta.items()})
    out = [net]
    tip = fin[-1]
    if f.tip_chord > 0:
        m = n_c + 1
        low, up = tip[:m][::-1], tip[m - 1:]
        cap = np.array([low, up])
        capn = Network(f"cap{k}", cap, "surface")
        if _cell_normal(cap, 0, n_c // 2) @ e_r < 0:
            capn = Network(f"cap{k}", cap[::-1], "surface")
        out.append(capn)
    te = net.points[:, 0]
    far = te + np.array([opt.wake_length * length, 0, 0])
    if behind is None:
        out.append(Network(f"wake{k}", np.stack([te, far], axis=1), "wake"))
    else:                                       # through the fin in line behind
        wake, interior = _wake_through(te, far, behind, body)
        out.append(Network(f"wake{k}", wake, "wake", {"interior": interior}))
    return out


def _cell_normal(pts, i, j):
    """Normal (Q3 - Q1) x (Q2 - Q4) of grid cell (i, j) (PANAIR orientation)."""
    return np.cross(pts[i + 1, j + 1] - pts[i, j], pts[i, j + 1] - pts[i + 1, j])
