"""Mass build-up with OpenRocket's component rules (numeric-only).

Per component (OpenRocket 22-24 ``getComponentVolume``/``getComponentMass``):

- nose cones and transitions: the shell between the outer profile and an
  inner one offset by the wall thickness normal to the surface, summed as
  thin frustum slices (``SymmetricComponent.integrate``; Ironbark's
  :mod:`ironbark_opt.rocket.revolution`), plus shoulders as tubes and their
  caps as discs of the shoulder's wall thickness;
- body tubes, inner tubes, couplers, centering rings, bulkheads, engine
  blocks, launch lugs: rings rho pi (ro^2 - ri^2) L; thick-walled tube
  moments I_axial = m (ro^2 + ri^2)/2, I_transverse = m ((ro^2 + ri^2)/4 +
  L^2/12) (Meriam & Kraige, *Dynamics*, App. B table B/4); inner-tube
  clusters multiply by the tube count (their radial offsets are neglected);
- fin sets: planform area x thickness x cross-section factor (square 1.0,
  rounded 0.99, airfoil 0.85, ``FinSet.CrossSection``) x fin count, plus
  tabs (height x length x thickness) and root fillets (:func:`fillet_area`
  per side along the root chord); CG at the planform centroid;
- rail buttons: flange + base discs of the outer diameter and the inner
  post (``RailButton.getComponentVolume``), per instance;
- mass objects (mass components, parachutes, streamers, shock cords): a
  given mass, or canopy area pi d^2/4 x surface density + lines x line
  length x line density, strip area x surface density, cord length x line
  density; a filled cylinder of the packed size for the moments
  (``MassObject``: I_axial = m r^2/2, I_transverse = m (3 r^2 + L^2)/12).

Overrides (``RocketComponent.getOverrideMass/CG``): a mass override scales
the component (or, with ``overridesubcomponentsmass``, the whole subtree)
to the given mass; a CG override moves its CG to ``x + overridecg``.
"""
from __future__ import annotations

import math

import numpy as np

from ironbark_opt.openrocket import convert
from ironbark_opt.openrocket.components import PARALLEL, OrkComponent
from ironbark_opt.rocket.mass import MassProperties, combine_properties


def _zero(x: float) -> MassProperties:
    return MassProperties(0.0, x, np.zeros((3, 3)))


def ring(rho: float, ro: float, ri: float, x0: float, length: float) -> MassProperties:
    """A thick-walled tube or disc (numeric-only).

    Parameters
    ----------
    rho : float [kg/m^3]
    ro, ri : float [m]
        Outer and inner radius (``ri`` clipped to [0, ro]).
    x0 : float [m]
        Front face, aft of the nose tip.
    length : float [m]
    """
    ro, ri = max(ro, 0.0), max(min(ri, ro), 0.0)
    m = rho * math.pi * (ro * ro - ri * ri) * length
    if m <= 0.0:
        return _zero(x0 + 0.5 * length)
    s = ro * ro + ri * ri
    return MassProperties.axisymmetric(m, x0 + 0.5 * length, m * (s / 4.0 + length ** 2 / 12.0),
                                       m * s / 2.0)


def cylinder(mass: float, x0: float, length: float, radius: float) -> MassProperties:
    """A filled cylinder (OpenRocket ``MassObject`` moments; numeric-only).

    Parameters
    ----------
    mass : float [kg]
    x0 : float [m]
        Front end, aft of the nose tip.
    length, radius : float [m]
        Packed length and radius.
    """
    if mass <= 0.0:
        return _zero(x0 + 0.5 * length)
    return MassProperties.axisymmetric(mass, x0 + 0.5 * length,
                                       mass * (3 * radius ** 2 + length ** 2) / 12.0,
                                       mass * radius ** 2 / 2.0)


def _instances(mp: MassProperties, count: int, sep: float) -> MassProperties:
    if count <= 1 or mp.mass <= 0.0:
        return mp
    return combine_properties([MassProperties(mp.mass, mp.cg_x + i * sep, mp.inertia)
                               for i in range(count)])


def _bulk(comp: OrkComponent) -> float:
    m = comp.material
    return m.density if (m is not None and m.kind == "bulk") else 0.0


def _density(mat, kind: str) -> float:
    return mat.density if (mat is not None and mat.kind == kind) else 0.0


def _shoulders(comp: OrkComponent, rho: float) -> list:
    g, out = comp.geo, []
    for end in ("fore", "aft"):
        rs, ls, ts, capped = g[f"{end}_shoulder"]
        if rs <= 0.0 or ls <= 0.0:
            continue
        x0 = comp.x_end if end == "aft" else comp.x - ls
        out.append(ring(rho, rs, rs - ts, x0, ls))
        if capped and ts > 0.0:
            xc = comp.x_end + ls - ts if end == "aft" else comp.x - ls
            out.append(ring(rho, max(rs - ts, 0.0), 0.0, xc, ts))
    return out


def fillet_area(fillet_radius: float, body_radius: float) -> float:
    """Cross-section [m^2] of one root fillet (one side of a fin).

    A circular concave fillet of radius ``rf`` [m] tangent to the fin and to a
    body of radius ``rb`` [m] (OpenRocket ``FinSet.calculateFilletCrossSection``):
    with h = rf + rb, the triangle body centre / fillet centre / fin tangent
    point of area tan(b) rf^2 / 2, b = acos(rf/h), minus the fillet sector
    b rf^2 / 2 and the body sector a rb^2 / 2, a = asin(rf/h).  Tends to
    (1 - pi/4) rf^2 on a flat body.
    """
    rf, rb = fillet_radius, body_radius
    if rf <= 0.0:
        return 0.0
    if rb <= 0.0:
        return (1.0 - math.pi / 4.0) * rf * rf
    h = rf + rb
    a, b = math.asin(rf / h), math.acos(rf / h)
    return max(math.tan(b) * rf * rf / 2.0 - b * rf * rf / 2.0 - a * rb * rb / 2.0, 0.0)


def _fins(comp: OrkComponent, parent_radius: float) -> MassProperties:
    g, rho = comp.geo, _bulk(comp)
    if g["thickness"] <= 0.0:
        return _zero(comp.x)
    fins = convert.fin_set(comp, with_density=1.0)
    base = fins.mass_properties(parent_radius)            # square section, density 1
    factor = convert.SECTION_VOLUME.get(g["section"], 1.0)
    parts = [base.scaled_to(base.mass * rho * factor)] if rho > 0 else []
    count, t = g["count"], g["thickness"]
    if g["tab_height"] > 0 and g["tab_length"] > 0 and rho > 0:
        pos, rel = g["tab_position"]
        root = fins.root_chord
        start = {"front": pos, "center": 0.5 * (root - g["tab_length"]) + pos,
                 "end": root - g["tab_length"] + pos}.get(rel.lower(), pos)
        m = rho * g["tab_height"] * g["tab_length"] * t * count
        parts.append(cylinder(m, comp.x + start, g["tab_length"], parent_radius))
    fr, fmat = g["fillet_radius"], g["fillet_material"]
    if fr > 0 and fmat is not None and fmat.density > 0:
        m = fmat.density * fillet_area(fr, parent_radius) * 2 * fins.root_chord * count
        parts.append(cylinder(m, comp.x, fins.root_chord, parent_radius))
    return combine_properties(parts) if parts else _zero(comp.x)


def own_mass(comp: OrkComponent) -> MassProperties:
    """Mass properties of ``comp`` alone (no subcomponents, no overrides), all its
    cluster instances included (their radial offsets neglected)."""
    mp = _single_mass(comp)
    return mp.scaled_to(mp.mass * comp.cluster_count) if comp.cluster_count > 1 else mp


def _single_mass(comp: OrkComponent) -> MassProperties:
    g, k, rho = comp.geo, comp.kind, _bulk(comp)
    if k == "stage":
        return _zero(comp.x)
    if k in ("nosecone", "transition", "bodytube"):
        parts = [convert.body_component(comp, with_mass=True).mass_properties()]
        if k != "bodytube":
            parts += _shoulders(comp, rho)
        return combine_properties(parts)
    if k in ("trapezoidfinset", "ellipticalfinset", "freeformfinset"):
        return _fins(comp, g.get("parent_radius", 0.0))
    if k in ("innertube", "tubecoupler", "engineblock", "centeringring", "bulkhead"):
        ro = g["outer_radius"]
        ri = g["inner_radius"] if k in ("centeringring", "bulkhead") else ro - g["thickness"]
        n, sep = g["instances"]
        return _instances(ring(rho, ro, ri, comp.x, comp.length), n, sep)
    if k == "launchlug":
        n, sep = g["instances"]
        return _instances(ring(rho, g["radius"], g["radius"] - g["thickness"], comp.x,
                               g["length"]), n, sep)
    if k == "railbutton":
        od, idia, h = g["outer_diameter"], g["inner_diameter"], g["height"]
        fh, bh, sh = g["flange_height"], g["base_height"], g["screw_height"]
        vol = math.pi * (od / 2) ** 2 * (fh + bh) + math.pi * (idia / 2) ** 2 * max(h - fh - bh, 0.0) \
            + 2.0 / 3.0 * math.pi * (od / 2) ** 2 * sh
        n, sep = g["instances"]
        return _instances(cylinder(rho * vol, comp.x, od, od / 2), n, sep)
    if k == "tubefinset":
        ro = g["outer_radius"] or 0.0
        mp = ring(rho, ro, ro - g["thickness"], comp.x, g["length"])
        return mp.scaled_to(mp.mass * g["count"])
    if k == "masscomponent":
        m = g["mass"]
    elif k == "shockcord":
        m = g["cord_length"] * _density(comp.material, "line")
    elif k == "parachute":
        m = math.pi * (g["diameter"] / 2) ** 2 * _density(comp.material, "surface") \
            + g["line_count"] * g["line_length"] * _density(g["line_material"], "line")
    elif k == "streamer":
        m = g["strip_length"] * g["strip_width"] * _density(comp.material, "surface")
    else:
        return _zero(comp.x)
    return cylinder(m, comp.x, g["packed_length"], g["packed_radius"])


def _moved(mp: MassProperties, cg_x: float) -> MassProperties:
    return MassProperties(mp.mass, cg_x, mp.inertia)


def subtree_mass(comp: OrkComponent, parallel: bool = True) -> MassProperties:
    """``comp`` and everything below it, with OpenRocket's override rules
    (``parallel=False``: without parallel boosters, the core after their separation)."""
    if not parallel and comp.kind in PARALLEL:
        return _zero(comp.x)
    own = own_mass(comp)
    if comp.override_mass is not None and not comp.override_mass_subtree:
        own = own.scaled_to(comp.override_mass)
    if comp.override_cg is not None and not comp.override_cg_subtree:
        own = _moved(own, comp.x + comp.override_cg)
    if comp.override_mass is not None and comp.override_mass_subtree:
        # the override replaces this component and all its subcomponents
        total = combine_properties([own] + [subtree_mass(c, parallel) for c in comp.children])
        total = total.scaled_to(comp.override_mass) if total.mass > 0 else \
            MassProperties(comp.override_mass, comp.x + 0.5 * comp.length, np.zeros((3, 3)))
    else:
        total = combine_properties([own] + [subtree_mass(c, parallel) for c in comp.children])
        if total.mass == 0.0:
            total = _zero(comp.x + 0.5 * comp.length)
    if comp.override_cg is not None and comp.override_cg_subtree:
        total = _moved(total, comp.x + comp.override_cg)
    if comp.kind in PARALLEL:
        total = parallel_instances(total, comp.geo["instances"], comp.geo["radius"])
    return total


def parallel_instances(mp: MassProperties, count: int, radius: float) -> MassProperties:
    """``count`` copies of ``mp`` evenly spaced around the axis at ``radius`` [m]
    (parallel boosters): mass x count, CG on the axis, and by the parallel-axis
    theorem roll inertia + count m r^2 and each transverse inertia + count m r^2 / 2
    (the sum of m r^2 cos^2 over evenly spaced angles is count m r^2 / 2 for
    count >= 2).  One copy (count 1) stays on the axis (its lateral CG offset neglected)."""
    if count <= 1 or mp.mass <= 0.0:
        return mp
    m, r2 = mp.mass, radius * radius
    extra = np.diag([count * m * r2, count * m * r2 / 2.0, count * m * r2 / 2.0])
    return MassProperties(count * m, mp.cg_x, count * np.asarray(mp.inertia) + extra)


def component_table(stages) -> list[tuple[OrkComponent, MassProperties, MassProperties]]:
    """``(component, own, subtree)`` mass properties of every component, depth first."""
    out = []
    for s in stages:
        for c in s.walk():
            out.append((c, own_mass(c), subtree_mass(c)))
    return out


def rocket_mass(stages, parallel: bool = True) -> MassProperties:
    """Dry mass properties (no motors) of the given stages (``parallel=False``:
    without their parallel boosters)."""
    return combine_properties([subtree_mass(s, parallel) for s in stages])
