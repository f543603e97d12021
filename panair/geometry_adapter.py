"""``ironbark_opt.rocket.Rocket`` -> :class:`panair.mesh.RocketGeometry`.

Numeric-only.  Trapezoidal fin sets are meshed as they are; elliptical
and free-form fins by their outline (leading edge and chord along the
span, :meth:`ironbark_opt.rocket.fins.FinSet.outline`).  Fin cant is not
meshed: it changes roll moments, not CA/CN/Cm to first order, and the
table has no roll coefficients.
"""
from __future__ import annotations

import warnings
from dataclasses import replace

import numpy as np

from ironbark_opt.errors import InputError
from ironbark_opt.rocket.body import PINCH_FRACTION

from .mesh import BodyGeometry, FinGeometry, RocketGeometry

__all__ = ["from_rocket"]


def from_rocket(rocket, *, n_profile: int = 400, fixed_roll: bool = False) -> RocketGeometry:
    """Mesher geometry of a Rocket.

    Parameters
    ----------
    rocket : ironbark_opt.rocket.Rocket
    n_profile : int
        Stations of ``Rocket.body_profile`` used for the body shape.
    fixed_roll : bool
        Mesh a set of one or two fins at its own roll angle (a model held at one roll,
        e.g. a wind-tunnel test).  Default: at 45 deg to the pitch plane, the roll
        average a table flown at every roll angle needs (with a warning).

    Returns
    -------
    RocketGeometry (lengths [m]).
    """
    if rocket.tube_fin_sets():
        raise InputError(f"tube fins '{rocket.tube_fin_sets()[0].name}' cannot be meshed by the panel solver; fly the "
                         "empirical aerodynamics (Ribner's ring-wing lift, no --table)", field="components")
    x, r = rocket.body_profile(n_profile)
    _check_no_pinch(np.asarray(x, float), np.asarray(r, float))
    fins, averaged = [], []
    offset = _common_roll_offset(rocket.fin_sets())
    for k, fs in enumerate(rocket.fin_sets()):
        outline = None
        if type(fs).__name__ != "TrapezoidalFins":           # elliptical, free-form
            frac, le, chord = fs.outline()
            if chord[0] <= 0:
                raise InputError(f"fin set '{fs.name}': the planform has no root chord",
                                 field=f"fin_sets[{k}]")
            outline = (frac, le, chord)
        sec = fs.section
        section = {"square": "square", "rounded": "rounded", "airfoil": "airfoil",
                   "double_wedge": "double_wedge"}[sec.kind]
        # the fin set's roll angle (FinSet.roll_angle: from +y toward +z; by default no
        # fin in the x-z plane for an even count, a fin on top for an odd one) as the
        # mesh's angle from +z toward +y
        roll = (np.pi / 2 - fs.roll_angle) % (2 * np.pi)
        if fs.count >= 3:
            # every set of three or more turned by one angle (_common_roll_offset): the
            # table stands for every roll of the rocket, the sets' relative roll is kept
            roll = (roll + offset) % (2 * np.pi)
        elif not fixed_roll:
            # One or two fins: the normal force in the pitch plane goes with sin^2 of each
            # fin's angle from it and depends on roll, which a polar table (flown at every
            # roll angle) cannot hold.  Meshed at 45 deg, where sum sin^2 = N/2, the roll
            # average Barrowman's N/2 stands for (Barrowman 1967 sec. 3; the empirical
            # path's fin lift), not at the set's own roll (two fins across the pitch plane
            # have twice that lift, two in it none).
            roll = np.pi / 4
            averaged.append(k)
            warnings.warn(f"fin set '{fs.name}' has {fs.count} fin{'s' if fs.count > 1 else ''}: "
                          f"its lift depends on roll; the table holds the roll average (N/2 of "
                          f"one fin's, Barrowman), with the fins at 45 deg to the pitch plane "
                          f"(in the plane of the fins they give no restoring moment)",
                          UserWarning, stacklevel=2)
        if outline is None:
            root, tip, sweep = fs.root_chord, fs.tip_chord, fs.sweep_length
        else:
            root, tip, sweep = outline[2][0], outline[2][-1], outline[1][-1]
        fins.append(FinGeometry(int(fs.count), root, tip, fs.span, sweep, fs.x, fs.thickness,
                                roll=roll, section=section, le_bevel=sec.le_bevel,
                                te_bevel=sec.te_bevel, outline=outline))
    for k in averaged:
        fins[k] = _clear_of_others(fins[k], [f for j, f in enumerate(fins) if j != k])
    x, r = _continue_past_fins(np.asarray(x, float), np.asarray(r, float), fins)
    return _affordable(RocketGeometry(BodyGeometry(x, r), tuple(fins), rocket.name), rocket.fin_sets())


#: Most panels of a whole-rocket model (default subsonic mesh) meshed to keep fin sets'
#: relative roll; the largest whole model among the fixtures, the stack of 'Two stage
#: high power rocket.ork' (two 3-fin sets), has 6536.  A fuzzed stack of four 4-fin
#: sets rolled 45 deg apart had 13016 (18568 supersonic): a worker's dense matrices
#: reached 14.7 GB and the system killed it.
WHOLE_MODEL_MAX_PANELS = 8000


def _affordable(geom: RocketGeometry, fin_sets) -> RocketGeometry:
    """``geom``, or its even fin sets in line (each at pi / count, a half model) with a
    warning, when only their relative roll breaks the mirror symmetry and the whole
    model it needs would exceed :data:`WHOLE_MODEL_MAX_PANELS`."""
    if is_symmetric(geom):
        return geom
    inline = RocketGeometry(geom.body, tuple(
        replace(f, roll=np.pi / f.count) if f.count >= 4 and f.count % 2 == 0 else f for f in geom.fins),
        geom.name)
    if not is_symmetric(inline):
        return geom
    from .mesh import MeshOptions, mesh_rocket
    n = sum((net.points.shape[0] - 1) * (net.points.shape[1] - 1)
            for net in mesh_rocket(geom, symmetric=False, options=MeshOptions()) if net.kind == "surface")
    if n <= WHOLE_MODEL_MAX_PANELS:
        return geom
    names = ", ".join(f"'{fs.name}'" for fs in fin_sets if fs.count >= 4 and fs.count % 2 == 0)
    warnings.warn(f"fin sets {names} are meshed in line (each with no fin in the symmetry plane), not at "
                  f"their relative roll: the whole-rocket model that roll needs has {n} panels, over "
                  f"{WHOLE_MODEL_MAX_PANELS} (its dense matrices outgrow a laptop's memory); the lift a set "
                  "loses in another's wake differs between in line and rolled (by -5 ... +7 % of CN-alpha "
                  "on the rockets measured)", UserWarning, stacklevel=3)
    return inline


def _clear_of_others(f: FinGeometry, others) -> FinGeometry:
    """A set of one or two fins at a roll of its roll average (sum sin^2 = N/2: 45, 135,
    225 or 315 deg) where no fin of another set overlapping it along the axis lies on
    the same line (two one-fin sets at 45 deg were one fin meshed twice: OpenRocket's
    parallel-booster example, its wake network refused)."""
    near = [g for g in others if g.x_root < f.x_root + f.root_chord and f.x_root < g.x_root + g.root_chord]
    taken = np.concatenate([g.fin_angles() for g in near]) if near else np.zeros(0)
    for roll in np.pi / 4 + np.pi / 2 * np.arange(4 if f.count == 1 else 2):
        gap = _angle_gaps(replace(f, roll=roll).fin_angles(), taken)
        if not gap.size or gap.min() > 1e-6:
            return replace(f, roll=float(roll))
    return f


def _angle_gaps(a, b) -> np.ndarray:
    """|a_i - b_j| [rad] wrapped to [0, pi], (len(a), len(b))."""
    return np.abs((np.asarray(a)[:, None] - np.asarray(b)[None, :] + np.pi) % (2 * np.pi) - np.pi)


def _common_roll_offset(fin_sets) -> float:
    """The roll [rad] by which every fin set of three or more fins is turned for the mesh.

    The table is in polar (total angle of attack) axes, so it stands for every roll
    angle of the rocket; for three or more equally spaced fins the linear normal force
    of one set is roll-independent (sum of sin^2 over the fins = N/2, Barrowman 1967
    sec. 3).  So the aft-most such set, if its count is even, is turned to have no fin
    in the symmetry plane (first fin at pi / count: a half model, a quarter of the dense
    solve's work), and every other set by the same angle: their roll *relative* to it is
    the rocket's own.  That relative roll matters: a set in the wake of another, in line
    or between its fins, loses different lift (a fuzzed rocket with a second 4-fin set
    1.2 root chords ahead of the main one, Mach 0.3, CN-alpha: in line 12.39 /rad,
    rolled 45 deg 13.21 /rad; each set alone on the body, summed, 14.65).  Until session 20
    each even set was turned on its own, so sets the file rolls 45 deg apart were meshed
    in line.  Sets whose relative roll breaks the mirror symmetry are meshed whole
    (:func:`is_symmetric`), at about 2.5x the cost."""
    sets = [fs for fs in fin_sets if fs.count >= 3]
    if not sets:
        return 0.0
    ref = max(sets, key=lambda fs: fs.x)
    if ref.count % 2:
        return 0.0
    return float(np.pi / ref.count - (np.pi / 2 - ref.roll_angle) % (2 * np.pi))


def _check_no_pinch(x, r):
    """Refuse a body that narrows to (almost) nothing and widens again, e.g. OpenRocket's
    'base drag hack' (a tube ending in a flat base, then a transition from ~0 radius out to
    the tube's): its near-zero-radius panels make the influence matrix singular (measured:
    |Cp| up to 1e13, a CN at zero alpha), which is a silently wrong table, not a solution.
    The nose tip and a tail closing to a point are not pinches."""
    r_max = float(np.max(r))
    thin = r < PINCH_FRACTION * r_max
    widest_ahead = np.maximum.accumulate(r)
    widest_behind = np.maximum.accumulate(r[::-1])[::-1]
    pinch = thin & (widest_ahead > 0.5 * r_max) & (widest_behind > 0.5 * r_max)
    if np.any(pinch):
        i = int(np.argmax(pinch))
        raise InputError(
            f"the body narrows to a radius of {1e3 * r[i]:.3g} mm at x = {x[i]:.4g} m and widens "
            f"again behind it (largest radius {1e3 * r_max:.3g} mm): a panel mesh cannot represent "
            "such a pinch (an .ork file's 'base drag hack' transition with its mass or drag "
            "override is left out by the reader; this one is the body's); fly the empirical "
            "aerodynamics (no --table), or model the base as a base", field="body")


#: Length of the body continued behind fins that reach the base [root chords]
FIN_BASE_GAP = 0.02


def _continue_past_fins(x, r, fins):
    """Fins whose trailing edge reaches (or passes) the base: the panel body is
    continued as a cylinder of the base radius to :data:`FIN_BASE_GAP` root
    chords behind the aft-most fin root trailing edge, so the base wake leaves
    the body behind the fins (a fin root needs a body under it, and a base
    wake cannot start on a fin's trailing edge).  The added cylinder is
    parallel to the axis: no axial pressure force; the base and its drag
    are unchanged (same radius)."""
    if not fins:
        return x, r
    end = max(f.x_root + f.root_chord for f in fins)
    chord = max(f.root_chord for f in fins)
    if end < x[-1] - FIN_BASE_GAP * chord:
        return x, r
    x_new = end + FIN_BASE_GAP * chord
    if x_new <= x[-1] * (1 + 1e-9):
        return x, r
    return np.append(x, x_new), np.append(r, r[-1])


def is_symmetric(geom: RocketGeometry) -> bool:
    """True if a half model (x-z symmetry plane) is valid for ``geom``: every fin set is
    its own mirror image in the x-z plane (its roll angles phi from +z toward +y map onto
    themselves under phi -> -phi) and no fin lies in that plane (a fin there would be cut
    in half; such layouts, e.g. four fins rolled 0 deg, are meshed whole)."""
    for f in geom.fins:
        phi = f.fin_angles()
        if np.any(np.abs(np.sin(phi)) < 1e-9):
            return False
        if not np.all(_angle_gaps(-phi, phi).min(axis=1) < 1e-9):
            return False
    return True
