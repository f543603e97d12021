"""Nose cones (conical, ogives, elliptical, parabolic/power/Haack series)."""
from __future__ import annotations

from dataclasses import dataclass

from ironbark_opt import validate as v
from ironbark_opt.rocket.revolution import BodyOfRevolution
from ironbark_opt.rocket.shapes import canonical_shape, shape_radius


@dataclass(frozen=True, kw_only=True)
class NoseCone(BodyOfRevolution):
    """A nose cone: pointed at ``x``, base radius ``radius`` at ``x + length``.

    Parameters
    ----------
    shape : str
        ``conical``, ``tangent_ogive`` (``ogive``), ``secant_ogive``,
        ``elliptical``, ``parabolic``, ``power``, ``haack``, ``von_karman``
        (= ``ld_haack``, Haack C = 0) or ``lv_haack`` (C = 1/3).
    length : float [m]
    radius : float [m]
        Base radius.
    shape_parameter : float [-] or None
        K of the parabolic series (default 1), n of the power series
        (default 0.5), C of the Haack series (default 0).
    ogive_radius : float [m] or None
        Arc radius of a secant ogive (required for that shape).
    x, thickness, filled, density, mass, name
        See :class:`~ironbark_opt.rocket.revolution.BodyOfRevolution`.
    """

    shape: str = "von_karman"
    radius: float = 0.0
    shape_parameter: float | None = None
    ogive_radius: float | None = None
    name: str = "nose cone"

    def __post_init__(self):
        self._check_common()
        radius = v.positive(self.radius, "radius")
        p = v.optional(v.number, self.shape_parameter, "shape_parameter")
        rho = v.optional(v.positive, self.ogive_radius, "ogive_radius")
        shape, param = canonical_shape(self.shape, p, rho, self.length, radius)
        v.set_fields(self, radius=radius, shape=shape, shape_parameter=param,
                     ogive_radius=rho)
        if self.thickness is not None and not self.filled and self.thickness > radius:
            from ironbark_opt.errors import InputError
            raise InputError(f"wall thickness {self.thickness} m exceeds the radius {radius} m",
                             field="thickness")

    @property
    def aft_radius(self) -> float:
        """Base radius [m] (exact, not re-evaluated from the shape formula)."""
        return self.radius

    def _local_radius(self, local):
        return shape_radius(self.shape, self.shape_parameter, local, self.length, self.radius)
