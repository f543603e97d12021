"""OpenRocket components -> Ironbark geometry value objects (numeric-only).

Shapes map as OpenRocket's ``Transition.Shape``: ``conical``, ``ogive``
(parameter 1 = tangent ogive, 0 < p < 1 = secant ogive of arc radius
rho = sqrt((L^2 + R^2) ((2 - p)^2 L^2 + p^2 R^2) / (4 p^2 R^2)), OpenRocket
``Transition.Shape.OGIVE.getRadius``), ``ellipsoid``, ``power`` (n),
``parabolic`` (K) and ``haack`` (C).
"""
from __future__ import annotations

import math

from ironbark_opt.errors import InputError
from ironbark_opt.openrocket.components import OrkComponent
from ironbark_opt.rocket.body import CLIPPABLE, BodyTube, Transition
from ironbark_opt.rocket.fin_sections import FinSection
from ironbark_opt.rocket.fins import EllipticalFins, FreeformFins, TrapezoidalFins
from ironbark_opt.rocket.nose import NoseCone

#: OpenRocket ``FinSet.CrossSection`` relative volumes (square, rounded, airfoil)
SECTION_VOLUME = {"square": 1.0, "rounded": 0.99, "airfoil": 0.85}
_SECTIONS = {"square": "square", "rounded": "rounded", "airfoil": "airfoil"}


#: Ironbark field names -> the OpenRocket XML element that holds the value
ORK_ELEMENTS = {"points": "finpoints", "root_chord": "rootchord", "tip_chord": "tipchord",
                "span": "height", "sweep_length": "sweeplength", "count": "fincount",
                "fore_radius": "foreradius", "aft_radius": "aftradius",
                "shape_parameter": "shapeparameter", "ogive_radius": "shapeparameter"}


def _wrap(comp: OrkComponent, err: InputError) -> InputError:
    """``err`` naming the component and the file's element (``.../freeformfinset[1]/finpoints``)."""
    field = f"{comp.path}/{ORK_ELEMENTS.get(err.field, err.field)}" if err.field else comp.path
    return InputError(f"'{comp.name}': {err.message}", source=comp.element.source, field=field)


def shape_args(comp: OrkComponent, radius_change: float) -> dict:
    """Ironbark ``shape``/``shape_parameter``/``ogive_radius`` of a nose or transition."""
    g = comp.geo
    shape, p, L, R = g["shape"], g["shape_parameter"], g["length"], radius_change
    if shape == "conical":
        return {"shape": "conical"}
    if shape == "ogive":
        p = 1.0 if p is None else p
        if p >= 0.999 or R <= 0.0:
            return {"shape": "tangent_ogive"}
        if p < 0.001:
            return {"shape": "conical"}
        rho = math.sqrt((L * L + R * R) * (((2 - p) * L) ** 2 + (p * R) ** 2) / (4 * (p * R) ** 2))
        return {"shape": "secant_ogive", "ogive_radius": rho}
    if shape in ("ellipsoid", "elliptical"):
        return {"shape": "elliptical"}
    if shape == "power":
        return {"shape": "power", "shape_parameter": min(max(0.5 if p is None else p, 1e-3), 1.0)}
    if shape == "parabolic":
        return {"shape": "parabolic", "shape_parameter": min(max(1.0 if p is None else p, 0.0), 1.0)}
    if shape == "haack":
        return {"shape": "haack", "shape_parameter": min(max(0.0 if p is None else p, 0.0), 2 / 3)}
    raise comp.element.error(f"unknown nose/transition shape {shape!r}; expected conical, "
                             f"ogive, ellipsoid, power, parabolic or haack", "shape")


def body_component(comp: OrkComponent, *, with_mass: bool = False):
    """NoseCone / BodyTube / Transition for ``comp`` (density only if ``with_mass``)."""
    g = comp.geo
    bulk = comp.material is not None and comp.material.kind == "bulk" and comp.material.density > 0
    density = comp.material.density if (with_mass and bulk) else None
    thick, filled = g.get("thickness") or 0.0, g.get("filled", False)
    if density is not None and not filled and thick <= 0.0:
        density = None                      # a zero-thickness shell has no mass
    r_max = max(g.get("radius") or 0.0, g.get("aft_radius") or 0.0, g.get("fore_radius") or 0.0)
    if not filled and thick >= r_max > 0.0:
        filled = True
    common = dict(length=g["length"], x=comp.x, name=comp.name, density=density,
                  filled=filled, thickness=(thick if (density is not None and not filled) else None),
                  roughness=g.get("roughness"))
    if g["length"] <= 0.0:
        raise comp.element.error(f"'{comp.name}' has length {g['length']} m; expected > 0", "length")
    try:
        if comp.kind == "bodytube":
            return BodyTube(radius=g["radius"], **common)
        if comp.kind == "nosecone":
            if g.get("flipped"):
                raise comp.element.error("a flipped nose cone (tail cone) is not supported; use a "
                                         "transition", "isflipped")
            return NoseCone(radius=g["aft_radius"], **shape_args(comp, g["aft_radius"]), **common)
        r1, r2 = g["fore_radius"], g["aft_radius"]
        if abs(r1 - r2) < 1e-12:
            return BodyTube(radius=r1, **common)
        # OpenRocket clips its ellipsoid, power and Haack transitions unless <shapeclipped>
        # says false (Transition.Shape.canClip; the file omits it for the other shapes)
        shape = shape_args(comp, abs(r2 - r1))
        clipped = bool(g.get("clipped", True)) and shape["shape"] in CLIPPABLE
        return Transition(fore_radius=r1, aft_radius=r2, clipped=clipped, **shape, **common)
    except InputError as err:
        raise _wrap(comp, err) from None


def fin_set(comp: OrkComponent, *, with_density: float | None = None):
    """The Ironbark fin set of ``comp`` (square section when ``with_density`` is given:
    OpenRocket's section factor is applied to the mass separately)."""
    g = comp.geo
    section = FinSection(kind="square" if with_density is not None
                         else _SECTIONS.get(g["section"], "square"))
    thickness = g["thickness"] if g["thickness"] > 0 else 1e-6
    el = comp.element
    rotation = el.number("rotation", None) if el.child("rotation") is not None else \
        el.number("angleoffset", None) if el.child("angleoffset") is not None else None
    common = dict(count=g["count"], x=comp.x, thickness=thickness, cant=g["cant"],
                  section=section, density=with_density, name=comp.name,
                  roughness=g.get("roughness"),
                  # OpenRocket's fin rotation: the first fin's angle from +y toward +z [deg]
                  roll=None if rotation is None else math.radians(rotation))
    try:
        if comp.kind == "trapezoidfinset":
            return TrapezoidalFins(root_chord=g["root_chord"], tip_chord=g["tip_chord"],
                                   span=g["span"], sweep_length=g["sweep_length"], **common)
        if comp.kind == "ellipticalfinset":
            return EllipticalFins(root_chord=g["root_chord"], span=g["span"], **common)
        pts = [(float(a), max(float(b), 0.0)) for a, b in g["points"]]
        pts[0] = (0.0, 0.0)
        pts[-1] = (pts[-1][0], 0.0)
        return FreeformFins(points=tuple(pts), **common)
    except InputError as err:
        raise _wrap(comp, err) from None
