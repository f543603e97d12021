"""Body tubes and transitions (shoulders, boattails)."""
from __future__ import annotations

from dataclasses import dataclass

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
    Other parameters as in :class:`~ironbark_opt.rocket.revolution.BodyOfRevolution`.
    """

    fore_radius: float = 0.0
    aft_radius: float = 0.0
    shape: str = "conical"
    shape_parameter: float | None = None
    ogive_radius: float | None = None
    name: str = "transition"

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
        v.set_fields(self, fore_radius=r1, aft_radius=r2, shape=shape,
                     shape_parameter=param, ogive_radius=rho)

    def _local_radius(self, local):
        r1, r2 = self.fore_radius, self.aft_radius
        dr = abs(r2 - r1)
        local = np.asarray(local, dtype=float)
        if r2 > r1:
            return r1 + shape_radius(self.shape, self.shape_parameter, local, self.length, dr)
        return r2 + shape_radius(self.shape, self.shape_parameter, self.length - local,
                                 self.length, dr)
