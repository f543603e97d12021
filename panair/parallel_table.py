"""Aerodynamic tables of a rocket with parallel boosters (OpenRocket ``ParallelStage``).

Two flight configurations, each one table on the core's reference area,
reference length and moment reference (the core's nose tip):

* ``core``: the core alone (after the boosters separate), its own panel
  solution, exactly :func:`panair.rocket_table.rocket_table` of the core;
* ``stack``: the core with its ``N`` boosters attached, a *component
  build-up*: the core's table plus ``N`` times one booster's, each booster
  (nose, tube, fins, its own base) panel-solved in isolation through the same
  pipeline (zero-lift pressure drag, base drag, friction column, cross-flow,
  high-angle model) and its coefficients moved to the core's references::

      k       = N S_b / S
      C_A,N  += k C_A,N(booster)
      C_m    += k (C_m,b l_b / l - C_N,b x_b / l)      (moment about the core's nose tip)

  with ``S, l`` the core's reference area and length, ``S_b, l_b`` the
  booster's, ``x_b`` its front end aft of the core's nose tip.  The
  boosters' axial forces act off the axis, but for two or more equally spaced
  boosters their moments cancel; for one booster that moment is neglected.

Booster-core aerodynamic interference is **not** modelled (the boosters'
flow fields do not see the core's or each other's), as in OpenRocket's
component build-up (Niskanen 2013, sec. 3.1: every component instance is
computed alone and summed) and DATCOM's body-alone plus fin-alone build-up
(Finck, USAF Stability and Control DATCOM, 1978, sec. 4).  The build says so
in its output.  Meshing the boosters as separate closed bodies in the core's
panel model would include it; measured on OpenRocket's example (the core's
half model plus one booster's full mesh moved to its place, its mirror image
the other; tangent to the core as in the file):

* Mach 0.3: stack CN-alpha 1.48 x the build-up's (refine 0.5 and 1: 1.476,
  1.481), CP 15 mm aft (0.980 vs 0.965 m), CA within 0.5 %: the pair of bodies
  side by side carries much more lift than each alone (slender-body theory:
  the lift follows the growth of the cross-section's apparent mass, which the
  boosters widen);
* but the number is set by the contact line: with the boosters moved out by
  2 % of their radial distance (0.9 mm) the ratio is 1.30, by 10 % 1.17;
* Mach 1.5 and 2: the joined model has no linear solution (non-physical
  pressures near the contact line, Cp -125 ... 148 at Mach 2).

So the joined model is not robust enough to build tables with, and the
build-up is kept: its stack normal-force slope is on the low side (for
boosters aft of the CG, as usual, so is the static margin).

A booster's fins are generally not roll-symmetric (OpenRocket's example: two
fins, 90 deg apart, on the outboard side).  The table is in total-angle-of-
attack axes and stands for every roll angle, so the booster's coefficients
are its roll average.  Linear theory makes that exact with two solutions:
the loads are linear (CN, Cm) or quadratic (the CA increment) in the
cross-flow vector ``V_c (cos phi, sin phi)``, so their average over ``phi``
is the mean of the solutions with the cross-flow along ``z`` and along
``y``, i.e. of the fins as they are and rolled 90 deg.  A fin layout with
``n >= 3``-fold symmetry (every fin set's count divisible by ``n``) is
already roll-independent (Barrowman 1967 sec. 3) and is solved once; of
the two rolls one is chosen, where possible, with the layout its own mirror
image in the x-z plane (a half model, :func:`panair.geometry_adapter.is_symmetric`).
A one-sided layout also carries a normal force and moment at zero angle of
attack (the fins' thickness displaces the flow on one side only: a fixed
vector in the booster's frame, whose component in the pitch plane averages to
zero over the roll, and which cancels between equally spaced boosters); the
two-roll mean would keep half of it, so each solution's zero-alpha CN and Cm
are removed before the mean.  (What remains of the one-sided layout beyond
linear theory, terms even in alpha and quadratic in the cross-flow, is not
averaged out; it vanishes at small angles.)

Mesh: a booster's coefficients enter the stack scaled by ``k`` (0.69 for
OpenRocket's example), so it is meshed at half the core's refinement
(:data:`BOOSTER_REFINE`).  Measured on that booster (Mach 0.5 / 1.5 / 2.0,
4 deg): refine 0.5 vs 1.0, CN -0.8 % / +0.2 % / -0.9 %, CP 0.7 / 1.7 / 0.1 mm
forward (booster length 171 mm), zero-lift CA 0.0 / -0.6 / -0.8 %, at a
quarter of the panels (738 vs 2696) and a fourth of the time; a coarser core
mesh (``--refine`` below 1) keeps the boosters at 0.5 (:func:`booster_refine`).

Numeric-only.
"""
from __future__ import annotations

import math

import numpy as np

from ironbark_opt.errors import InputError

__all__ = ["BOOSTER_REFINE", "booster_refine", "parallel_tables", "booster_roll_average", "stack_table",
           "roll_offsets"]

#: Mesh refinement of a booster relative to the core's (see the module docstring)
BOOSTER_REFINE = 0.5


def booster_refine(refine: float) -> float:
    """A booster's mesh refinement for the core's ``refine``: :data:`BOOSTER_REFINE` x it,
    never coarser than the 0.5 checked in the module docstring (at 0.25 the
    example boosters' CN-alpha at Mach 0.3 came out 37 % above its 0.5 value)."""
    return max(BOOSTER_REFINE * refine, 0.5)

#: what the build output and the stack table say about interference
INTERFERENCE_NOTE = ("booster-core aerodynamic interference is not modelled: the stack's table is the core's "
                     "plus each booster's solved alone (component build-up, as OpenRocket and DATCOM); boosters "
                     "beside the core add normal force this leaves out (OpenRocket's example: a third of the "
                     "stack's CN-alpha at Mach 0.3, see panair/parallel_table.py)")


def roll_offsets(geom) -> list[float]:
    """Extra fin rolls [rad] whose solutions average to the roll average of
    ``geom`` (:class:`panair.mesh.RocketGeometry`): ``[0]`` when the fin layout is
    roll-independent, else two rolls 90 deg apart, the first chosen (from the
    rolls that put a mirror line of the layout on +z) to make as many of the two
    as possible half models."""
    from .geometry_adapter import is_symmetric
    counts = [int(f.count) for f in geom.fins]
    if not counts or math.gcd(*counts) >= 3:
        return [0.0]
    angles = np.concatenate([f.fin_angles() for f in geom.fins])
    # a mirror line of a layout passes through a fin or halfway between two fins
    candidates = [0.0] + sorted({round((-0.5 * (a + b) + k * np.pi / 2) % (2 * np.pi), 12)
                                 for a in angles for b in angles for k in range(2)})
    best = max(candidates, key=lambda d: (is_symmetric(geom.with_fins_rolled(d))
                                          + is_symmetric(geom.with_fins_rolled(d + np.pi / 2)), -d))
    return [best, best + np.pi / 2]


def booster_roll_average(booster, aero_spec, mach, alpha_deg, *, refine: float, checkpoint=None, **kwargs):
    """The roll-averaged table of one booster (a Rocket in its own frame), see the
    module docstring.  ``checkpoint``: a path stem, one folder per roll;
    ``kwargs`` as :func:`panair.rocket_table.rocket_table`."""
    from ironbark_opt.aero.table import AeroTable

    from .geometry_adapter import from_rocket
    from .rocket_table import rocket_table
    # the fins at their own roll (fixed_roll): the two-roll mean below is the roll average
    # (meshing one-fin sets at 45 deg instead put OpenRocket's two one-fin sets on one line)
    kwargs.setdefault("fixed_roll", True)
    offsets = roll_offsets(from_rocket(booster, fixed_roll=kwargs["fixed_roll"]))
    tables = [rocket_table(booster, aero_spec, mach, alpha_deg, refine=refine, fin_roll_offset=d,
                           checkpoint_dir=None if checkpoint is None else f"{checkpoint}-roll{i}.solved", **kwargs)
              for i, d in enumerate(offsets)]
    if len(tables) == 1:
        t = tables[0]
        return AeroTable(t.mach, t.alpha, {c: t.values(c) for c in t.coefficient_names},
                         reference_area=t.reference_area, reference_length=t.reference_length,
                         moment_reference_x=t.moment_reference_x, includes=t.includes,
                         metadata={**t.metadata, "booster_fin_rolls_deg": [math.degrees(offsets[0])],
                                   "booster_roll_average": "fin layout roll-independent: one solution"})
    a, b = tables
    meta = _merged_metadata(a.metadata, [b.metadata])
    zero = {c: [t.values(c)[:, 0] for t in tables] for c in a.coefficient_names if c[:2] in ("CN", "Cm")}
    meta.update(booster_fin_rolls_deg=[round(math.degrees(d), 6) for d in offsets],
                booster_roll_average="mean of the fins as meshed and rolled 90 deg (exact roll average "
                                     "of linear theory's loads), their zero-alpha normal force and moment "
                                     "removed (a fixed force of a one-sided fin layout, zero in the roll average)",
                booster_zero_alpha_cn_removed=[float(np.max(np.abs(v))) for v in zero.get("CN", [])])

    def mean(c):
        va, vb = a.values(c), b.values(c)
        if c in zero:
            va, vb = va - zero[c][0][:, None], vb - zero[c][1][:, None]
        return 0.5 * (va + vb)
    return AeroTable(a.mach, a.alpha, {c: mean(c) for c in a.coefficient_names},
                     reference_area=a.reference_area, reference_length=a.reference_length,
                     moment_reference_x=a.moment_reference_x, includes=a.includes, metadata=meta)


def _merged_metadata(first: dict, others) -> dict:
    """``first`` with the panel counts summed and the per-Mach method notes (the
    ones ``aero build`` warns about) united over ``others``."""
    meta = dict(first)
    for o in others:
        for k in ("panels", "panels_supersonic"):
            meta[k] = int(meta.get(k, 0)) + int(o.get(k, 0))
        for k in ("mach_local_inclination", "mach_sonic_leading_edge", "mach_remeshed", "mach_cp_clipped"):
            meta[k] = sorted(set(meta.get(k, [])) | set(o.get(k, [])))
        extra = {m: list(a) for m, a in meta.get("alpha_deg_extrapolated", {}).items()}
        for m, angles in o.get("alpha_deg_extrapolated", {}).items():
            extra[m] = sorted(set(extra.get(m, [])) | set(angles))
        meta["alpha_deg_extrapolated"] = extra
        if o.get("mach_critical") is not None and meta.get("mach_critical") is not None:
            meta["mach_critical"] = min(meta["mach_critical"], o["mach_critical"])
    return meta


def stack_table(core, booster, count: int, x0: float, *, extra_metadata: dict | None = None):
    """The core's table plus ``count`` boosters' (booster table in its own frame, its
    front end ``x0`` [m] aft of the core's nose tip), on the core's references; see
    the module docstring."""
    from ironbark_opt.aero.table import AeroTable
    if not (np.array_equal(core.mach, booster.mach) and np.array_equal(core.alpha, booster.alpha)):
        raise InputError("the core's and the booster's tables have different grids", field="mach")
    if set(core.coefficient_names) != set(booster.coefficient_names) or core.includes != booster.includes:
        raise InputError("the core's and the booster's tables have different coefficients", field="coefficients")
    s, l, xr = core.reference_area, core.reference_length, core.moment_reference_x
    k = count * booster.reference_area / s
    out = {}
    for c in core.coefficient_names:
        vb = booster.values(c)
        if c.startswith("Cm"):
            cn_b = booster.values("CN" + c[2:])
            # the booster's moment about its own reference, then about the core's
            vb = vb * booster.reference_length / l - cn_b * (x0 + booster.moment_reference_x - xr) / l
        out[c] = core.values(c) + k * vb
    meta = _merged_metadata(core.metadata, [booster.metadata])
    meta.update(extra_metadata or {})
    return AeroTable(core.mach, core.alpha, out, reference_area=s, reference_length=l, moment_reference_x=xr,
                     includes=core.includes, metadata=meta)


def parallel_tables(doc, mach, alpha_deg, *, refine: float = 1.0, checkpoint=None, extra_metadata=None,
                    names: dict | None = None, **kwargs) -> dict:
    """The tables of an :class:`~ironbark_opt.openrocket.document.OrkDocument` with one
    set of parallel boosters: ``{"stack", "core", "booster"}`` -> AeroTable (the
    booster's in its own frame, roll-averaged; the others on the core's references).

    Parameters
    ----------
    doc : OrkDocument
    mach : 1-D array [-]; alpha_deg : 1-D array [deg]
    refine : float
        The core's mesh refinement (boosters: :func:`booster_refine`).
    checkpoint : path stem, optional
        Per-Mach saves for a resumed build: ``<stem>.solved`` (core),
        ``<stem>-booster-roll<i>.solved``.
    names : dict, optional
        File names of the core's and booster's tables, recorded in the stack's
        metadata (``parallel_boosters``) so the flight finds them.
    kwargs
        As :func:`panair.rocket_table.rocket_table` (workers, progress, use_panair).
    """
    from ironbark_opt.openrocket.build import geometry
    from ironbark_opt.openrocket.parallel import booster_rocket, single_booster_set
    from ironbark_opt.rocket.specs import AeroSpec

    from .rocket_table import rocket_table
    pod = single_booster_set(doc)
    count = int(pod.geo["instances"])
    spec = AeroSpec()
    core_rocket, booster = geometry(doc), booster_rocket(doc, pod)
    base_meta = dict(extra_metadata or {})
    core = rocket_table(core_rocket, spec, mach, alpha_deg, refine=refine,
                        checkpoint_dir=None if checkpoint is None else f"{checkpoint}.solved",
                        extra_metadata={**base_meta, "configuration": f"core alone ('{doc.rocket.stages[0].name}', "
                                                                      f"after '{pod.name}' separates)"}, **kwargs)
    one = booster_roll_average(booster, spec, mach, alpha_deg, refine=booster_refine(refine),
                               checkpoint=None if checkpoint is None else f"{checkpoint}-booster",
                               extra_metadata={**base_meta, "configuration": f"one booster of '{pod.name}' alone, "
                                                                             "x from its front end"}, **kwargs)
    info = {"set": pod.name, "count": count, "x_m": float(pod.x),
            "radial_distance_m": float(pod.geo["radius"]), "booster_reference_area_m2": one.reference_area,
            "booster_reference_length_m": one.reference_length, "booster_refine": booster_refine(refine),
            "interference": INTERFERENCE_NOTE, "interference_modelled": False,
            "axial_force_moment": ("cancels (equally spaced boosters)" if count >= 2 else
                                   "neglected (one booster off the axis)"),
            **(names or {})}
    stack = stack_table(core, one, count, float(pod.x), extra_metadata={
        "configuration": f"core with {count} x '{pod.name}' attached", "parallel_boosters": info,
        "panels_core": core.metadata["panels"], "panels_booster": one.metadata["panels"]})
    return {"stack": stack, "core": core, "booster": one}
