"""Walk OpenRocket's component tree into positioned component records (numeric-only).

Only the direct ``<subcomponents>`` children of each component are walked
(never ``.//tag``: ``<motorconfiguration>`` also has ``<stage>`` children).
Every record carries its absolute front position ``x`` [m] aft of the nose
tip, its axial ``length`` [m], parsed geometry in SI (radians for angles;
the file stores component angles in degrees), its material and its mass,
CG and cluster/instance data; :mod:`.ormass` turns them into mass
properties with OpenRocket's rules.

Positions follow OpenRocket's ``AxialMethod`` (``RocketComponent.
getAxialOffset``): ``top`` front to parent front, ``middle`` centre to
centre, ``bottom`` aft end to parent aft end, ``absolute`` from the nose
tip, ``after`` (body components) right behind the previous sibling.  Files
before 1.8 use ``<position type=...>`` with the same methods.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

from ironbark_opt.openrocket.xmlread import Element
from ironbark_opt.rocket.materials import FINISHES, ORK_FINISHES

BODY = ("nosecone", "bodytube", "transition")
FINS = ("trapezoidfinset", "ellipticalfinset", "freeformfinset")
RINGS = ("innertube", "tubecoupler", "centeringring", "bulkhead", "engineblock")
MASS_OBJECTS = ("masscomponent", "parachute", "streamer", "shockcord")
EXTERNAL = ("launchlug", "railbutton", "tubefinset")
#: parallel boosters (OpenRocket ``ParallelStage``; ``boosterset`` in older files)
PARALLEL = ("parallelstage", "boosterset")
UNSUPPORTED = {"podset": "pods (podset)"}
KNOWN = BODY + FINS + RINGS + MASS_OBJECTS + EXTERNAL + ("stage",)
#: fin cross-sections read from ``<crosssection>`` (OpenRocket 1.0-24.12 ``FinSet.CrossSection``)
FIN_SECTIONS = ("square", "rounded", "airfoil")

#: OpenRocket ``ClusterConfiguration`` names -> number of tubes
CLUSTER_COUNTS = {"single": 1, "double": 2, "3-row": 3, "triple": 3, "3-ring": 3, "4-row": 4,
                  "quad": 4, "4-ring": 4, "5-ring": 5, "6-ring": 6, "6-star": 7, "7-ring": 7,
                  "8-ring": 8, "9-star": 9, "9-ring": 9}


@dataclass
class Material:
    """A material: ``kind`` bulk [kg/m^3], surface [kg/m^2] or line [kg/m]."""

    name: str
    kind: str
    density: float


@dataclass
class MotorEntry:
    """One motor of one configuration in a motor mount (as the file gives it)."""

    config_id: str
    designation: str
    manufacturer: str
    digest: str | None
    delay: float | None          # [s], None = plugged
    diameter: float | None       # [m]
    length: float | None         # [m]
    ignition_event: str
    ignition_delay: float        # [s]


@dataclass
class OrkComponent:
    """A positioned component of the tree.

    Parameters
    ----------
    kind : str
        XML tag (``bodytube``, ``trapezoidfinset``, ...).
    name : str
    path : str
        Element path, e.g. ``rocket/subcomponents/stage[1]/subcomponents/bodytube[2]``.
    x : float [m]
        Front end aft of the nose tip.
    length : float [m]
        Axial length used for positioning.
    stage : int
        Index of the axial stage (0 = top).
    geo : dict
        Parsed geometry in SI and radians.
    material : Material or None
    element : Element
        The XML element (for error messages).
    children : list of OrkComponent
    motors : dict config id -> MotorEntry (motor mounts only)
    overhang : float [m]
        Motor overhang aft of a motor mount.
    cluster_count : int [-]
        Instances of this component in a clustered inner tube (itself included).
    override_mass : float [kg] or None
    override_mass_subtree : bool
        The mass override replaces the component *and* its subcomponents.
    override_cg : float [m] or None
        CG override, aft of the component's front end.
    override_cg_subtree : bool
    override_cd : float [-] or None
        Read, not applied to the aerodynamics (warned about: tree._warn_cd_overrides).
    """

    kind: str
    name: str
    path: str
    x: float
    length: float
    stage: int
    element: Element
    geo: dict = field(default_factory=dict)
    material: Material | None = None
    children: list = field(default_factory=list)
    motors: dict = field(default_factory=dict)
    overhang: float = 0.0
    cluster_count: int = 1
    override_mass: float | None = None
    override_mass_subtree: bool = False
    override_cg: float | None = None
    override_cg_subtree: bool = False
    override_cd: float | None = None

    @property
    def x_end(self) -> float:
        return self.x + self.length

    def walk(self):
        """This component and all below it, depth first."""
        yield self
        for c in self.children:
            yield from c.walk()


def material(el: Element, tag: str = "material") -> Material | None:
    """The ``<material type=... density=...>`` child, or None."""
    m = el.child(tag)
    if m is None:
        return None
    kind = m.attr("type", "bulk")
    if kind not in ("bulk", "surface", "line"):
        raise el.error(f"material type must be bulk, surface or line, got {kind!r}", tag)
    try:
        density = float(m.attr("density", ""))
    except ValueError:
        raise el.error(f"material density must be a number, got {m.attr('density')!r}",
                       tag) from None
    if not density >= 0.0 or not math.isfinite(density):
        raise el.error(f"material density must be >= 0, got {density}", tag)
    return Material((m.node.text or "").strip(), kind, density)


def axial_position(el: Element, length: float, parent_x: float, parent_len: float) -> float:
    """Absolute front x [m] from ``<axialoffset method=..>`` or ``<position type=..>``."""
    node = el.child("axialoffset")
    method_attr = "method"
    if node is None:
        node = el.child("position")
        method_attr = "type"
    if node is None:
        return parent_x
    method = (node.attr(method_attr) or "top").lower()
    value = el.number(node.tag, 0.0)
    if method == "top":
        return parent_x + value
    if method == "middle":
        return parent_x + 0.5 * (parent_len - length) + value
    if method == "bottom":
        return parent_x + parent_len - length + value
    if method == "absolute":
        return value
    if method == "after":
        return parent_x + parent_len + value
    raise el.error(f"unknown axial method {method!r}; expected top, middle, bottom, absolute "
                   f"or after", node.tag)


def _radius(el, tag, minimum=0.0):
    """A radius, or None when ``auto``: OpenRocket (``DoubleSetter`` with the ``auto``
    special string) sets the number written after ``auto`` and then switches the radius to
    automatic, so the component takes it from its neighbour (or parent) whenever it is read;
    the number is the value cached when the file was saved, stale once a neighbour changed
    (:func:`auto_cache`)."""
    return None if _is_auto(el, tag) else el.number(tag, None, auto=True, minimum=minimum)


def _is_auto(el, tag) -> bool:
    raw = el.text(tag)
    return raw is not None and raw.strip().lower().startswith("auto")


def auto_cache(el, tag):
    """The number saved after ``auto`` in ``tag`` (``auto 0.0125``), or None."""
    return el.number(tag, None, auto=True) if _is_auto(el, tag) else None


def _thickness(el, tag="thickness"):
    raw = el.text(tag)
    if raw is not None and raw.lower() == "filled":
        return None, True
    return el.number(tag, 0.0, minimum=0.0), False


def _angle(el, tag):
    """A component angle: stored in degrees, returned in radians."""
    return math.radians(el.number(tag, 0.0))


def _finish(el: Element) -> float | None:
    """Roughness height [m] of the component's ``<finish>`` (OpenRocket's finishes), or
    None when the element has none (OpenRocket's default then applies: regular paint)."""
    name = (el.text("finish") or "").strip().lower()
    if not name:
        return None
    if name not in ORK_FINISHES:
        raise el.error(f"unknown surface finish {name!r}; expected one of "
                       f"{', '.join(ORK_FINISHES)}", "finish")
    return FINISHES[ORK_FINISHES[name]]


def parse_geometry(el: Element) -> tuple[dict, float]:
    """Geometry of one component and its positioning length [m]."""
    k = el.tag
    g: dict = {"roughness": _finish(el)}
    if k in ("nosecone", "transition"):
        g["length"] = el.number("length", required=True, minimum=0.0)
        g["shape"] = (el.text("shape") or "conical").lower()
        g["shape_parameter"] = el.number("shapeparameter", None)
        g["fore_radius"] = 0.0 if k == "nosecone" else _radius(el, "foreradius")
        g["aft_radius"] = _radius(el, "aftradius")
        g["thickness"], g["filled"] = _thickness(el)
        g["flipped"] = el.flag("isflipped", False)
        g["clipped"] = el.flag("shapeclipped", True)
        for end in ("fore", "aft"):
            g[f"{end}_shoulder"] = (el.number(f"{end}shoulderradius", 0.0, minimum=0.0),
                                    el.number(f"{end}shoulderlength", 0.0, minimum=0.0),
                                    el.number(f"{end}shoulderthickness", 0.0, minimum=0.0),
                                    el.flag(f"{end}shouldercapped", False))
        return g, g["length"]
    if k == "bodytube":
        g["length"] = el.number("length", required=True, minimum=0.0)
        g["radius"] = _radius(el, "radius")
        g["thickness"], g["filled"] = _thickness(el)
        return g, g["length"]
    if k in FINS:
        g["count"] = int(el.number("fincount", 3, minimum=1))
        g["thickness"] = el.number("thickness", required=True, minimum=0.0)
        g["cant"] = _angle(el, "cant")
        g["section"] = (el.text("crosssection") or "square").strip().lower()
        if g["section"] not in FIN_SECTIONS:
            # e.g. a later OpenRocket's 'triangular' (bevelled leading edge): its drag and
            # mass differ from a square plate's, so no silent square
            raise el.error(f"fin set '{el.text('name') or k}': cross-section {g['section']!r} is not "
                           f"supported; expected one of {', '.join(FIN_SECTIONS)} (OpenRocket's "
                           f"FinSet.CrossSection)", "crosssection")
        g["fillet_radius"] = el.number("filletradius", 0.0, minimum=0.0)
        g["fillet_material"] = material(el, "filletmaterial")
        g["tab_height"] = el.number("tabheight", 0.0, minimum=0.0)
        g["tab_length"] = el.number("tablength", 0.0, minimum=0.0)
        tab = el.child("tabposition")
        g["tab_position"] = (el.number("tabposition", 0.0),
                             (tab.attr("relativeto") if tab is not None else None) or "front")
        if k == "trapezoidfinset":
            g["root_chord"] = el.number("rootchord", required=True, minimum=0.0)
            g["tip_chord"] = el.number("tipchord", required=True, minimum=0.0)
            g["span"] = el.number("height", required=True, minimum=0.0)
            g["sweep_length"] = el.number("sweeplength", 0.0)
            return g, g["root_chord"]
        if k == "ellipticalfinset":
            g["root_chord"] = el.number("rootchord", required=True, minimum=0.0)
            g["span"] = el.number("height", required=True, minimum=0.0)
            return g, g["root_chord"]
        pts_el = el.require("finpoints")
        pts = []
        for p in pts_el.children("point"):
            try:
                pts.append((float(p.attr("x")), float(p.attr("y"))))
            except (TypeError, ValueError):
                raise p.error("a fin point needs numeric x and y attributes") from None
        if len(pts) < 3:
            raise pts_el.error(f"a free-form fin needs at least 3 points, got {len(pts)}")
        g["points"] = pts
        return g, pts[-1][0]
    if k in RINGS:
        g["length"] = el.number("length", required=True, minimum=0.0)
        g["outer_radius"] = _radius(el, "outerradius")
        if k in ("centeringring",):
            g["inner_radius"] = _radius(el, "innerradius")
        elif k == "bulkhead":
            g["inner_radius"] = 0.0
        else:
            g["thickness"] = el.number("thickness", None, auto=True, minimum=0.0)
        g["instances"] = (int(el.number("instancecount", 1, minimum=1)),
                          el.number("instanceseparation", 0.0))
        if k == "innertube":
            cfg = (el.text("clusterconfiguration") or "single").lower()
            if cfg not in CLUSTER_COUNTS:
                raise el.error(f"unknown cluster configuration {cfg!r}", "clusterconfiguration")
            g["cluster"] = CLUSTER_COUNTS[cfg]
        return g, g["length"]
    if k in MASS_OBJECTS:
        g["packed_length"] = el.number("packedlength", 0.0, minimum=0.0, auto=True) or 0.0
        g["packed_radius"] = el.number("packedradius", 0.0, minimum=0.0, auto=True) or 0.0
        if k == "masscomponent":
            g["mass"] = el.number("mass", 0.0, minimum=0.0)
        elif k == "shockcord":
            g["cord_length"] = el.number("cordlength", 0.0, minimum=0.0)
        elif k == "parachute":
            g["diameter"] = el.number("diameter", required=True, minimum=0.0)
            g["line_count"] = int(el.number("linecount", 0, minimum=0))
            g["line_length"] = el.number("linelength", 0.0, minimum=0.0)
            g["line_material"] = material(el, "linematerial")
        elif k == "streamer":
            g["strip_length"] = el.number("striplength", required=True, minimum=0.0)
            g["strip_width"] = el.number("stripwidth", required=True, minimum=0.0)
        if k in ("parachute", "streamer"):
            g["cd"] = el.number("cd", None, auto=True)
            g["deploy_event"] = (el.text("deployevent") or "ejection").lower()
            g["deploy_altitude"] = el.number("deployaltitude", 200.0)
            g["deploy_delay"] = el.number("deploydelay", 0.0, minimum=0.0)
            g["deploy_per_config"] = {
                dc.attr("configid", ""): ((dc.text("deployevent") or g["deploy_event"]).lower(),
                                          dc.number("deployaltitude", g["deploy_altitude"]),
                                          dc.number("deploydelay", g["deploy_delay"], minimum=0.0))
                for dc in el.children("deploymentconfiguration")}
        return g, g["packed_length"]
    if k == "launchlug":
        g["length"] = el.number("length", required=True, minimum=0.0)
        g["radius"] = el.number("radius", required=True, minimum=0.0)
        g["thickness"] = el.number("thickness", 0.0, minimum=0.0)
        g["instances"] = (int(el.number("instancecount", 1, minimum=1)),
                          el.number("instanceseparation", 0.0))
        return g, g["length"]
    if k == "railbutton":
        g["outer_diameter"] = el.number("outerdiameter", 0.0097, minimum=0.0)
        g["inner_diameter"] = el.number("innerdiameter", 0.008, minimum=0.0)
        g["height"] = el.number("height", 0.0097, minimum=0.0)
        g["base_height"] = el.number("baseheight", 0.002, minimum=0.0)
        g["flange_height"] = el.number("flangeheight", 0.002, minimum=0.0)
        g["screw_height"] = el.number("screwheight", 0.0, minimum=0.0)
        g["instances"] = (int(el.number("instancecount", 2, minimum=1)),
                          el.number("instanceseparation", 0.0))
        return g, g["outer_diameter"]
    if k == "tubefinset":
        g["length"] = el.number("length", required=True, minimum=0.0)
        g["count"] = int(el.number("fincount", 6, minimum=1))
        # OpenRocket's TubeFinSet writes its outer radius as <radius> ('auto': tree.py)
        g["outer_radius"] = _radius(el, "radius")
        g["thickness"] = el.number("thickness", 0.0, minimum=0.0)
        return g, g["length"]
    return g, 0.0


def parse_overrides(comp: OrkComponent) -> None:
    """Mass, CG and Cd overrides with their subcomponent flags (in place)."""
    el = comp.element
    comp.override_mass = el.number("overridemass", None, minimum=0.0)
    comp.override_cg = el.number("overridecg", None)
    comp.override_cd = el.number("overridecd", None)
    comp.override_mass_subtree = el.flag("overridesubcomponentsmass", False)
    comp.override_cg_subtree = el.flag("overridesubcomponentscg", False)


def parse_motor_mount(comp: OrkComponent) -> None:
    """Motors per configuration, overhang and ignition of a motor mount (in place)."""
    mm = comp.element.child("motormount")
    if mm is None:
        return
    comp.overhang = mm.number("overhang", 0.0)
    event = (mm.text("ignitionevent") or "automatic").lower()
    delay = mm.number("ignitiondelay", 0.0)
    per_config = {}
    for ic in mm.children("ignitionconfiguration"):
        # OpenRocket 1.5+ writes child elements (older drafts used attributes)
        ev = ic.text("ignitionevent") or ic.attr("ignitionevent") or event
        dl = ic.number("ignitiondelay", None)
        if dl is None:
            dl = float(ic.attr("ignitiondelay") or delay)
        per_config[ic.attr("configid", "")] = (ev.lower(), dl)
    for m in mm.children("motor"):
        cid = m.attr("configid")
        if not cid:
            raise m.error("a <motor> needs a configid attribute")
        designation = m.text("designation")
        if not designation:
            raise m.error("required element <designation> is missing in <motor>", "designation")
        raw_delay = (m.text("delay") or "none").lower()
        motor_delay = None if raw_delay in ("none", "nan", "") else m.number("delay")
        ev, dl = per_config.get(cid, (event, delay))
        comp.motors[cid] = MotorEntry(cid, designation, m.text("manufacturer") or "",
                                      m.text("digest"), motor_delay,
                                      m.number("diameter", None, minimum=0.0),
                                      m.number("length", None, minimum=0.0), ev, dl)
