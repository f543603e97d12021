"""Build the positioned component tree of an OpenRocket design (numeric-only).

:func:`build_tree` walks ``<rocket>/<subcomponents>`` stage by stage,
places body components end to end (stages follow each other, as in
OpenRocket's ``AxialStage``), positions every inner and external component
relative to its parent (:func:`.components.axial_position`) and resolves
``auto`` radii the way OpenRocket does: a body tube takes its neighbour's
radius, a nose cone's base or a transition's end the adjacent body radius,
a coupler / bulkhead / engine block / centering ring's outside the parent's
inner radius, and a centering ring's inside the largest inner tube beside
it (``CenteringRing.getInnerRadius``).
"""
from __future__ import annotations

import math
import warnings
from dataclasses import dataclass, field

from ironbark_opt.openrocket import components as oc
from ironbark_opt.openrocket.xmlread import Element


@dataclass
class OrkRocket:
    """The rocket of an .ork file: name and stages (``OrkComponent`` of kind ``stage``)."""

    name: str
    stages: list
    element: Element
    #: parallel boosters (kind ``parallelstage``), also children of the body
    #: component they are attached to
    pods: list = field(default_factory=list)

    def components(self):
        """All components, depth first (stages and parallel boosters included)."""
        for s in self.stages:
            yield from s.walk()

    def core_components(self):
        """The components of the core vehicle: :meth:`components` without the
        parallel boosters' subtrees."""
        def walk(c):
            if c.kind in oc.PARALLEL:
                return
            yield c
            for k in c.children:
                yield from walk(k)
        for s in self.stages:
            yield from walk(s)

    def body(self):
        """Body components in order from the nose tip."""
        return [c for s in self.stages for c in s.children if c.kind in oc.BODY]

    def base_drag_hack(self):
        """The body's last component if it is OpenRocket's 'base drag hack', else None.

        The hack (OpenRocket's example 'Base drag hack (short-wide)', whose comment gives
        the recipe) puts behind the flat base of a short rocket a transition starting from a
        point (0.001 in) and widening back to full diameter over pi diameters, with
        OpenRocket's mass, CG and drag overrides ticked, so that OpenRocket's Barrowman
        centre of pressure moves aft.  It is not hardware.  Recognised by all of: a transition, last in the body, starting
        narrower than :data:`~ironbark_opt.rocket.body.PINCH_FRACTION` of the largest body
        radius and widening behind it, the component ahead ending at more than half that
        radius (a step down to a point), and an OpenRocket mass or drag override on it (the
        recipe).  Any other pinch stays the body's, and the panel mesh refuses it."""
        from ironbark_opt.rocket.body import PINCH_FRACTION
        body = self.body()
        if len(body) < 2 or body[-1].kind != "transition":
            return None
        last, ahead = body[-1], body[-2]
        r_max = max(outer_radius(c) for c in body)
        g, ga = last.geo, ahead.geo
        r_ahead = ga["radius"] if ahead.kind == "bodytube" else ga["aft_radius"]
        pinched = g["fore_radius"] < PINCH_FRACTION * r_max and g["aft_radius"] > 0.5 * r_max
        recipe = last.override_cd is not None or last.override_mass is not None
        return last if pinched and r_ahead > 0.5 * r_max and recipe else None

    def length(self) -> float:
        """Nose tip to the aft end of the last body component [m]."""
        body = self.body()
        return body[-1].x_end if body else 0.0

    def motor_mounts(self):
        return [c for c in self.components() if c.motors]


def inner_radius(comp: oc.OrkComponent) -> float:
    """Radius [m] available inside ``comp`` for its internal children."""
    g = comp.geo
    if comp.kind == "bodytube":
        return 0.0 if g["filled"] else max(g["radius"] - g["thickness"], 0.0)
    if comp.kind in ("nosecone", "transition"):
        r = max(g["aft_radius"], g["fore_radius"])
        return 0.0 if g["filled"] else max(r - g["thickness"], 0.0)
    if comp.kind in ("innertube", "tubecoupler", "engineblock"):
        return max(g["outer_radius"] - g["thickness"], 0.0)
    if comp.kind == "centeringring":
        return g["inner_radius"]
    return g.get("outer_radius") or 0.0


def outer_radius(comp: oc.OrkComponent) -> float:
    """Outer radius [m] of a body component (the larger end) or a ring."""
    g = comp.geo
    if comp.kind == "bodytube":
        return g["radius"]
    if comp.kind in ("nosecone", "transition"):
        return max(g["aft_radius"], g["fore_radius"])
    return g.get("outer_radius") or 0.0


def _make(el: Element, x_parent: float, len_parent: float, stage: int,
          body_x: float | None = None) -> oc.OrkComponent:
    if el.tag in oc.UNSUPPORTED:
        name = el.text("name") or el.tag
        raise el.error(f"{oc.UNSUPPORTED[el.tag]} '{name}' cannot be flown by Ironbark-Opt "
                       f"yet; remove it (or fly the core vehicle alone)")
    if el.tag not in oc.KNOWN:
        raise el.error(f"unknown component <{el.tag}>; expected one of "
                       f"{', '.join(sorted(oc.KNOWN))}")
    geo, length = oc.parse_geometry(el)
    x = body_x if body_x is not None else oc.axial_position(el, length, x_parent, len_parent)
    comp = oc.OrkComponent(el.tag, el.text("name") or el.tag, el.path, x, length, stage, el,
                           geo=geo, material=oc.material(el))
    oc.parse_overrides(comp)
    oc.parse_motor_mount(comp)
    if el.tag == "innertube":
        comp.cluster_count = geo.get("cluster", 1)
    return comp


def _parallel_stage(el: Element, parent: oc.OrkComponent, pods: list) -> oc.OrkComponent:
    """A set of parallel boosters (OpenRocket ``ParallelStage``): its own body
    components end to end from its front, placed on ``parent`` by its axial
    offset; ``instancecount`` copies around the core at the radial distance
    ``radius`` [m] (``relative``/``surface``: touching the parent's surface plus the
    offset, as OpenRocket's ``RadiusMethod.RELATIVE``; otherwise the offset from the
    axis).  Its stage number follows the axial stages (OpenRocket numbers stages
    depth first; a rocket with both is refused by the staging code)."""
    number = len(pods) + 1000          # renumbered in build_tree once the axial stages are known
    body, cursor = [], 0.0
    sub = el.child("subcomponents")
    for bel in (sub.children() if sub is not None else []):
        if bel.tag not in oc.BODY:
            raise bel.error(f"<{bel.tag}> cannot sit directly in parallel boosters; expected a nose "
                            f"cone, body tube or transition")
        comp = _make(bel, 0.0, 0.0, number, body_x=cursor)
        cursor += comp.length
        body.append(comp)
    if not body:
        raise el.error("parallel boosters without a body component (nose cone, body tube, transition)")
    x = oc.axial_position(el, cursor, parent.x, parent.length)
    for c in body:
        c.x += x
    _resolve_body_radii(body)
    r_pod = max(outer_radius(c) for c in body)
    node = el.child("radiusoffset")
    method = (node.attr("method") if node is not None else None) or "relative"
    offset = el.number("radiusoffset", 0.0)
    radius = outer_radius(parent) + r_pod + offset if method.lower() in ("relative", "surface") else offset
    geo = {"instances": int(el.number("instancecount", 2, minimum=1)), "radius": radius,
           "angle": math.radians(el.number("angleoffset", 0.0)), "pod_radius": r_pod,
           "separation": _separation_settings(el)}
    pod = oc.OrkComponent(el.tag, el.text("name") or "boosters", el.path, x, cursor, number, el, geo=geo)
    oc.parse_overrides(pod)
    pod.children = body
    for c in body:
        _children(c, number, pods)
    pods.append(pod)
    return pod


def _separation_settings(el: Element) -> dict:
    """``{config id or '': (event, delay [s])}``: OpenRocket's stage separation settings."""
    default = ((el.text("separationevent") or "upperignition").lower(), el.number("separationdelay", 0.0))
    out = {"": default}
    for c in el.children("separationconfiguration"):
        out[c.attr("configid", "")] = ((c.text("separationevent") or default[0]).lower(),
                                       c.number("separationdelay", default[1]))
    return out


def _children(parent: oc.OrkComponent, stage: int, pods: list) -> None:
    sub = parent.element.child("subcomponents")
    if sub is None:
        return
    for el in sub.children():
        if el.tag in oc.BODY or el.tag == "stage":
            raise el.error(f"<{el.tag}> cannot sit inside <{parent.kind}> "
                           f"'{parent.name}'; body components belong directly to a stage")
        if el.tag in oc.PARALLEL:
            parent.children.append(_parallel_stage(el, parent, pods))
            continue
        comp = _make(el, parent.x, parent.length, stage)
        # children of a clustered inner tube exist once per tube (OpenRocket instancing)
        comp.cluster_count *= parent.cluster_count
        parent.children.append(comp)
    # outer radii first (they may be the parent's inner radius), then ring insides
    for comp in parent.children:
        g = comp.geo
        if comp.kind in oc.PARALLEL:
            continue
        if comp.kind in oc.RINGS and g.get("outer_radius") is None:
            g["outer_radius"] = inner_radius(parent)
        if "thickness" in g and g["thickness"] is None and comp.kind in oc.RINGS:
            g["thickness"] = g["outer_radius"]          # 'auto' wall: a solid disc
    for comp in parent.children:
        if comp.kind in oc.PARALLEL:
            continue
        if comp.kind == "centeringring" and comp.geo["inner_radius"] is None:
            tubes = [s for s in parent.children if s.kind == "innertube"
                     and s.x < comp.x_end and s.x_end > comp.x]
            comp.geo["inner_radius"] = max((s.geo["outer_radius"] for s in tubes), default=0.0)
        # body radius under fins / lugs (the parent's outside)
        comp.geo["parent_radius"] = outer_radius(parent)
        if comp.kind == "tubefinset" and comp.geo["outer_radius"] is None:
            # OpenRocket's TubeFinSet 'auto' radius: the body's for one or two tubes,
            # else the radius at which neighbouring tubes touch, R sin(pi/n) / (1 - sin(pi/n))
            n, rb = comp.geo["count"], comp.geo["parent_radius"]
            touch = math.sin(math.pi / n) / (1.0 - math.sin(math.pi / n)) if n >= 3 else 1.0
            comp.geo["outer_radius"] = rb * touch
    for comp in parent.children:
        if comp.kind not in oc.PARALLEL:
            _children(comp, stage, pods)


#: OpenRocket's radius of an automatic body radius with nothing to take it from [m]
#: (``SymmetricComponent.DEFAULT_RADIUS``)
DEFAULT_RADIUS = 0.025


class _AutoRadii:
    """OpenRocket's automatic body radii along the body (all stages, nose to tail).

    The rules of ``BodyTube.getAutoOuterRadius``, ``Transition.getAutoForeRadius`` /
    ``getAutoAftRadius`` and their ``getFrontAutoRadius`` / ``getRearAutoRadius`` /
    ``usesPreviousCompAutomatic`` / ``usesNextCompAutomatic`` (OpenRocket
    ``core/.../rocketcomponent``): an automatic body tube takes the radius the component
    before it shows at its aft end unless that one takes its own from the tube, else the
    radius of the component after it; an automatic transition (or nose cone base) end takes
    the neighbouring component's; an automatic radius passes through automatic tubes; -1
    means "none" (a transition's automatic end shows none).  Our body list is OpenRocket's
    ``getPrevious/NextSymmetricComponent`` chain for in-line components (stages follow
    each other; pods are not in it).
    """

    def __init__(self, body: list):
        self.body = body
        self.ref: dict[int, int | None] = {}     # auto tube -> the neighbour it takes from
        self.busy: set[int] = set()

    def _auto(self, i: int, key: str) -> bool:
        return self.body[i].geo.get(key) is None

    def front(self, i: int) -> float:
        """``getFrontAutoRadius``: the radius component ``i`` shows to the one after it."""
        c = self.body[i]
        if c.kind == "bodytube":
            if self._auto(i, "radius"):
                return self.front(i - 1) if i > 0 else -1.0
            return c.geo["radius"]
        return -1.0 if self._auto(i, "aft_radius") else c.geo["aft_radius"]

    def rear(self, i: int) -> float:
        """``getRearAutoRadius``: the radius component ``i`` shows to the one before it."""
        c = self.body[i]
        if c.kind == "bodytube":
            if self._auto(i, "radius"):
                return self.rear(i + 1) if i + 1 < len(self.body) else -1.0
            return c.geo["radius"]
        return -1.0 if self._auto(i, "fore_radius") else c.geo["fore_radius"]

    def uses_next(self, i: int) -> bool:
        c = self.body[i]
        if c.kind == "bodytube":
            return self._auto(i, "radius") and self._ref(i) == i + 1
        return self._auto(i, "aft_radius")

    def uses_previous(self, i: int) -> bool:
        c = self.body[i]
        if c.kind == "bodytube":
            return self._auto(i, "radius") and self._ref(i) == i - 1
        return self._auto(i, "fore_radius")

    def _ref(self, i: int):
        if i not in self.ref:
            self.tube(i)
        return self.ref.get(i)

    def tube(self, i: int) -> float:
        """``BodyTube.getAutoOuterRadius`` of the automatic tube ``i``."""
        if i in self.busy:              # asked again while being worked out: takes from no one yet
            return -1.0
        self.busy.add(i)
        r, ref = -1.0, None
        if i > 0 and not self.uses_next(i - 1):
            r, ref = self.front(i - 1), i - 1
        if r < 0 and i + 1 < len(self.body) and not self.uses_previous(i + 1):
            r, ref = self.rear(i + 1), i + 1
        self.busy.discard(i)
        self.ref[i] = ref
        return r

    def fore(self, i: int) -> float:
        return self.front(i - 1) if i > 0 else DEFAULT_RADIUS

    def aft(self, i: int) -> float:
        return self.rear(i + 1) if i + 1 < len(self.body) else DEFAULT_RADIUS


def _resolve_body_radii(body: list) -> None:
    """Fill ``auto`` radii of body components from their neighbours (OpenRocket rules,
    :class:`_AutoRadii`).  A radius OpenRocket would find none for (-1: e.g. an automatic
    transition end beside another one) takes the value the file cached after ``auto``,
    else it is an error."""
    rules = _AutoRadii(body)
    found = []
    for i, c in enumerate(body):
        if c.kind == "bodytube" and c.geo["radius"] is None:
            found.append((c, "radius", rules.tube(i)))
        if c.kind in ("nosecone", "transition"):
            if c.geo["fore_radius"] is None:
                found.append((c, "fore_radius", rules.fore(i)))
            if c.geo["aft_radius"] is None:
                found.append((c, "aft_radius", rules.aft(i)))
    for c, key, r in found:             # all worked out from the file's values, then set
        if r < 0:
            tag = "radius" if key == "radius" else key.replace("_", "")
            cached = oc.auto_cache(c.element, tag)
            if cached is None:
                raise c.element.error(f"'auto' {key.replace('_', ' ')} of '{c.name}' has no "
                                      f"neighbouring component to take it from", tag)
            r = cached
        c.geo[key] = r


def build_tree(root: Element) -> OrkRocket:
    """The positioned tree of the ``<rocket>`` in the file's root element."""
    rocket_el = root.require("rocket")
    sub = rocket_el.require("subcomponents")
    stages_el = sub.children()
    if not stages_el:
        raise sub.error("the rocket has no stages")
    stages, cursor = [], 0.0
    for si, sel in enumerate(stages_el):
        if sel.tag != "stage":
            if sel.tag in oc.UNSUPPORTED:
                _make(sel, 0.0, 0.0, si)
            raise sel.error(f"expected <stage> under <rocket>, got <{sel.tag}>")
        stage = oc.OrkComponent("stage", sel.text("name") or f"stage {si + 1}", sel.path,
                                cursor, 0.0, si, sel)
        oc.parse_overrides(stage)
        ssub = sel.child("subcomponents")
        for el in (ssub.children() if ssub is not None else []):
            if el.tag not in oc.BODY:
                _make(el, 0.0, 0.0, si)     # raises for unknown/unsupported tags
                raise el.error(f"<{el.tag}> cannot sit directly in a stage; expected a nose "
                               f"cone, body tube or transition")
            comp = _make(el, 0.0, 0.0, si, body_x=cursor)
            cursor += comp.length
            stage.children.append(comp)
        stage.length = cursor - stage.x
        stages.append(stage)
    ork = OrkRocket(rocket_el.text("name") or "rocket", stages, rocket_el)
    body = ork.body()
    if not body:
        raise sub.error("the rocket has no body components (nose cone, body tube, transition)")
    _resolve_body_radii(body)
    for s in stages:
        for comp in s.children:
            _children(comp, s.stage, ork.pods)
    for i, pod in enumerate(ork.pods):            # stage numbers after the axial stages
        for c in pod.walk():
            c.stage = len(stages) + i
    _warn_cd_overrides(ork)
    return ork


def _warn_cd_overrides(ork: OrkRocket) -> None:
    """Warn, naming each component, that OpenRocket's drag-coefficient overrides
    (``<overridecd>``, written only when set) are not flown: Ironbark-Opt's drag comes
    from the geometry (empirical or panel tables), so a Cd override (e.g. the 'base drag
    hack' Cd 0) would otherwise be dropped without a word; and that a 'base drag hack'
    transition is left out (:meth:`OrkRocket.base_drag_hack`)."""
    hack = ork.base_drag_hack()               # build.geometry leaves it out
    if hack is not None:
        warnings.warn(
            f"'{hack.name}' ({hack.element.path}) is OpenRocket's 'base drag hack' (a transition "
            f"from a {1e3 * hack.geo['fore_radius']:.3g} mm point behind the base, with OpenRocket's "
            "mass/drag overrides), not hardware: left out of the aerodynamics; the rocket flies "
            "with its real flat base (base drag from the base-drag model, stability without the "
            "hack's extra lift aft)", UserWarning, stacklevel=3)
    for c in ork.components():
        if c.override_cd is not None and c is not hack:
            warnings.warn(f"'{c.name}' ({c.element.path}): OpenRocket's drag coefficient "
                          f"override Cd = {c.override_cd:g} is not applied; its drag is computed "
                          f"from the geometry", UserWarning, stacklevel=3)
