"""Body tubes and transitions (shoulders, boattails)."""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from ironbark_opt.errors import InputError
from ironbark_opt import validate as v
from ironbark_opt.rocket.revolution import BodyOfRevolution
from ironbark_opt.rocket.shapes import canonical_shape, shape_radius

#: An interior station of the body narrower than this fraction of its largest radius, with
#: the body widening again behind it, is a pinch: no flow model here represents it (the panel
#: mesh refuses it, :func:`panair.geometry_adapter._check_no_pinch`; an OpenRocket 'base drag
#: hack' transition starts from one, :meth:`ironbark_opt.openrocket.tree.OrkRocket.base_drag_hack`) [-]
PINCH_FRACTION = 0.02

#: shapes OpenRocket clips in a transition (``Transition.Shape`` ELLIPSOID, POWER and HAACK
#: are ``canClip``; its conical, ogive and parabolic transitions are never clipped)
CLIPPABLE = ("elliptical", "power", "haack")


@dataclass(frozen=True, kw_only=True)
class BodyTube(BodyOfRevolution):
    """A cylindrical tube of outer ``radius`` [m] and ``length`` [m] starting at ``x`` [m].

    Other parameters as in :class:`~ironbark_opt.rocket.revolution.BodyOfRevolution`.
    """

    radius: float = 0.0
    name: str = "body tube"

    def __post_init__(self):
        self._check_common()
        v.set_fields(self, radius=v.positive(self.radius, "radius"))
        if self.thickness is not None and not self.filled and self.thickness > self.radius:
            raise InputError(f"wall thickness {self.thickness} m exceeds the radius "
                             f"{self.radius} m", field="thickness")

    def _local_radius(self, local):
        return np.full_like(np.asarray(local, dtype=float), self.radius)

    def profile(self, n: int = 2, spacing: str = "uniform"):
        """Stations ``(x, r)`` [m]; two are exact for a cylinder."""
        return super().profile(max(int(n), 2), "uniform")


@dataclass(frozen=True, kw_only=True)
class Transition(BodyOfRevolution):
    """A change of radius from ``fore_radius`` to ``aft_radius`` (a boattail when it shrinks).

    Parameters
    ----------
    fore_radius, aft_radius : float [m]
        Radii at the front and aft ends (>= 0, not both 0, not equal).
    shape : str
        Any nose-cone shape (default ``conical``); the shape's pointed end lies
        at the smaller radius, as in OpenRocket's ``Transition``:
        r(x) = r_small + |dr| f(distance from the small end).
    shape_parameter, ogive_radius
        As for :class:`~ironbark_opt.rocket.nose.NoseCone`, with the radius
        change |aft_radius - fore_radius| in place of the base radius.
    clipped : bool
        OpenRocket's clipped transition (its default for the ``elliptical``,
        ``power`` and ``haack`` shapes, :data:`CLIPPABLE`; no effect on others): the
        nose shape of the larger radius, lengthened beyond the small end by the clip
        length c at which it has the smaller radius, and cut there:
        r(d) = f(c + d; r_large, c + length), d from the small end (OpenRocket
        ``Transition.getRadius`` / ``calculateClip``).  Unclipped (default), the
        shape spans the radius change alone: r(d) = r_small + f(d; |dr|, length).
    Other parameters as in :class:`~ironbark_opt.rocket.revolution.BodyOfRevolution`.
    """

    fore_radius: float = 0.0
    aft_radius: float = 0.0
    shape: str = "conical"
    shape_parameter: float | None = None
    ogive_radius: float | None = None
    clipped: bool = False
    name: str = "transition"
    #: clip length c [m] (0 when not clipped), set from the other fields
    clip_length: float = field(default=0.0, init=False, repr=False, compare=False)

    def __post_init__(self):
        self._check_common()
        r1 = v.nonnegative(self.fore_radius, "fore_radius")
        r2 = v.nonnegative(self.aft_radius, "aft_radius")
        if r1 == r2:
            raise InputError(f"fore_radius and aft_radius are equal ({r1} m): use a body tube",
                             field="aft_radius")
        p = v.optional(v.number, self.shape_parameter, "shape_parameter")
        rho = v.optional(v.positive, self.ogive_radius, "ogive_radius")
        shape, param = canonical_shape(self.shape, p, rho, self.length, abs(r2 - r1))
        if not isinstance(self.clipped, (bool, np.bool_)):
            raise InputError(f"clipped must be true or false, got {self.clipped!r}", field="clipped")
        v.set_fields(self, fore_radius=r1, aft_radius=r2, shape=shape,
                     shape_parameter=param, ogive_radius=rho, clipped=bool(self.clipped))
        if self.clipped and shape in CLIPPABLE and min(r1, r2) > 0.0:
            v.set_fields(self, clip_length=self._solve_clip(min(r1, r2), max(r1, r2)))

    def _solve_clip(self, small: float, large: float) -> float:
        """The clip length c [m] at which the nose shape of radius ``large`` and length
        c + length has the radius ``small``, as OpenRocket's ``calculateClip`` (the shape's
        radius rises with c; the bracket doubles from ``length``; Brent's root)."""
        from scipy.optimize import brentq        # not at import: command start-up

        def excess(c):
            return float(shape_radius(self.shape, self.shape_parameter, c, c + self.length, large)) - small
        lo, hi = 0.0, self.length
        for _ in range(200):
            if excess(hi) > 0.0:
                break
            lo, hi = hi, 2.0 * hi
        return float(brentq(excess, lo, hi, xtol=1e-12 * self.length))

    def _local_radius(self, local):
        r1, r2 = self.fore_radius, self.aft_radius
        dr = abs(r2 - r1)
        local = np.asarray(local, dtype=float)
        d = local if r2 > r1 else self.length - local        # from the small end
        if self.clip_length > 0.0:
            c = self.clip_length
            return shape_radius(self.shape, self.shape_parameter, c + d, c + self.length, max(r1, r2))
        return min(r1, r2) + shape_radius(self.shape, self.shape_parameter, d, self.length, dr)
