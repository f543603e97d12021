"""Fin cross-sections: area and centroid of a chordwise section.

A section of chord ``c`` [m] and maximum thickness ``t`` [m]:

- ``square`` (``flat``): a rectangle, area c t.
- ``rounded``: leading and trailing edges rounded with radius t/2, area
  c t - (1 - pi/4) t^2 (below c = t the section is taken as an ellipse,
  pi c t / 4, which matches at c = t).
- ``airfoil``: the NACA four-digit symmetric thickness form, Abbott & von
  Doenhoff, *Theory of Wing Sections* (1959), eq. 6.2,
  y_t = 5 t (0.2969 sqrt(x) - 0.1260 x - 0.3516 x^2 + 0.2843 x^3 - 0.1015 x^4),
  integrated in closed form below.
- ``double_wedge`` (``hexagonal``): flat centre with straight bevels of
  length ``le_bevel`` and ``te_bevel`` [m] from full thickness to a sharp
  edge; when the bevels meet (or are not given) it is a double wedge
  (diamond).  Bevels longer than the local chord (near a tapered tip) are
  scaled down in proportion so that le + te = c.

All functions are numeric (NumPy) and vectorised over the chord.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ironbark_opt.errors import InputError
from ironbark_opt import validate as v

# NACA 00xx half-thickness coefficients (Abbott & von Doenhoff eq. 6.2)
_NACA_A = (0.2969, -0.1260, -0.3516, 0.2843, -0.1015)
_NACA_P = (0.5, 1.0, 2.0, 3.0, 4.0)
#: section area / (c t) of the NACA form: 10 * Int_0^1 y_t/(5t) dx
NACA_AREA_FACTOR = 10.0 * sum(a / (p + 1.0) for a, p in zip(_NACA_A, _NACA_P))
#: centroid / c of the NACA form
NACA_CENTROID = (10.0 * sum(a / (p + 2.0) for a, p in zip(_NACA_A, _NACA_P))) / NACA_AREA_FACTOR

KINDS = {"square": "square", "flat": "square", "rounded": "rounded", "airfoil": "airfoil",
         "double_wedge": "double_wedge", "hexagonal": "double_wedge", "diamond": "double_wedge"}



def leading_edge_kind(kind: str, le_bevel) -> str:
    """The leading edge's shape for its drag and its supersonic stand-in: ``square`` for a
    square section and for a hexagon whose leading edge is not bevelled (``le_bevel`` 0),
    else the section ``kind``."""
    return "square" if kind == "double_wedge" and le_bevel == 0.0 else kind

@dataclass(frozen=True, kw_only=True)
class FinSection:
    """Chordwise cross-section of a fin (value object; methods numeric-only).

    Parameters
    ----------
    kind : str
        ``square``/``flat``, ``rounded``, ``airfoil``, ``double_wedge``/``hexagonal``.
    le_bevel, te_bevel : float [m] or None
        Bevel lengths of a double-wedge/hexagonal section, measured along the
        chord; None (both) = sharp double wedge with the ridge at mid-chord.
    """

    kind: str = "square"
    le_bevel: float | None = None
    te_bevel: float | None = None

    def __post_init__(self):
        key = str(self.kind).strip().lower().replace(" ", "_").replace("-", "_")
        if key not in KINDS:
            raise InputError(f"unknown fin section '{self.kind}'; expected one of "
                             f"{', '.join(KINDS)}", field="section")
        kind = KINDS[key]
        le = v.optional(v.nonnegative, self.le_bevel, "le_bevel")
        te = v.optional(v.nonnegative, self.te_bevel, "te_bevel")
        if kind != "double_wedge" and (le or te):
            raise InputError(f"bevel lengths only apply to a double_wedge/hexagonal section, "
                             f"not '{kind}'", field="le_bevel")
        if kind == "double_wedge" and (le is None) != (te is None):
            raise InputError("give both le_bevel and te_bevel [m] (or neither for a "
                             "sharp double wedge)", field="te_bevel")
        if kind == "double_wedge" and le is not None and le + te == 0.0:
            raise InputError("zero bevels make a square section: use section = 'square'",
                             field="le_bevel")
        object.__setattr__(self, "kind", kind)
        object.__setattr__(self, "le_bevel", le)
        object.__setattr__(self, "te_bevel", te)

    @property
    def leading_edge_kind(self) -> str:
        """:func:`leading_edge_kind` of this section."""
        return leading_edge_kind(self.kind, self.le_bevel)

    @property
    def trailing_edge_base_fraction(self) -> float:
        """Share of the trailing edge's frontal area (thickness x span) that
        carries base drag [-]: 1 for a blunt (square) trailing edge, 1/2 for a
        rounded one (it recovers part of the pressure), 0 for sharp ones
        (airfoil, double wedge / hexagonal with a trailing-edge bevel), as
        OpenRocket's fin base drag (FinSetCalc.calculateComponentBaseCD;
        Niskanen 2013, sec. 3.4.5)."""
        if self.kind == "square" or (self.kind == "double_wedge" and self.te_bevel == 0.0):
            return 1.0
        if self.kind == "rounded":
            return 0.5
        return 0.0

    def _bevels(self, chord):
        chord = np.asarray(chord, dtype=float)
        if self.le_bevel is None:
            return 0.5 * chord, 0.5 * chord
        total = self.le_bevel + self.te_bevel
        scale = np.minimum(1.0, chord / total)
        return self.le_bevel * scale, self.te_bevel * scale

    def area(self, chord, thickness: float):
        """Section area [m^2] at ``chord`` [m] for maximum ``thickness`` [m]."""
        c = np.asarray(chord, dtype=float)
        t = thickness
        if self.kind == "square":
            return c * t
        if self.kind == "rounded":
            return np.where(c >= t, c * t - (1.0 - np.pi / 4.0) * t * t, np.pi / 4.0 * c * t)
        if self.kind == "airfoil":
            return NACA_AREA_FACTOR * c * t
        le, te = self._bevels(c)
        # rectangle minus two bevel triangles of legs (bevel, t/2) on each side
        return c * t - 0.5 * t * (le + te)

    def centroid(self, chord, thickness: float):
        """Chordwise centroid [m] aft of the section's leading edge."""
        c = np.asarray(chord, dtype=float)
        if self.kind in ("square", "rounded"):
            return 0.5 * c
        if self.kind == "airfoil":
            return NACA_CENTROID * c
        le, te = self._bevels(c)
        t = thickness
        a_le, a_te = 0.5 * t * le, 0.5 * t * te   # removed areas, centroids at le/3, c - te/3
        area = c * t - a_le - a_te
        safe = np.where(area > 0.0, area, 1.0)
        first = c * t * 0.5 * c - a_le * le / 3.0 - a_te * (c - te / 3.0)
        return np.where(area > 0.0, first / safe, 0.5 * c)

    def leading_edge_half_angle(self, chord, thickness: float):
        """Wedge half-angle [rad] of a sharp leading edge; pi/2 for blunt sections."""
        if self.kind != "double_wedge":
            return np.full_like(np.asarray(chord, dtype=float), np.pi / 2.0)
        le, _ = self._bevels(chord)
        return np.arctan2(0.5 * thickness, le)
