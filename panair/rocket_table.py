"""A rocket's aerodynamic table from its geometry: the one recipe behind
``ironbark aero build`` and the validation tests.

Parts (see :func:`panair.sweep.build_table` and :mod:`panair.transonic`):
the panel solution (subsonic and supersonic), the zero-lift pressure drag
model (separated flow and edges below the critical Mach number, transonic
rise, supersonic wave drag), base drag (McCoy's MC DRAG above Mach 1) with
blunt fin trailing edges, the body's viscous cross-flow lift, a high-angle
extension to 90 deg, and skin friction kept out of ``CA`` so the flight
evaluates it at its own Reynolds number and surface finish.

Numeric-only.
"""
from __future__ import annotations

import math

import numpy as np

__all__ = ["DEFAULT_MACH", "DEFAULT_ALPHA_DEG", "rocket_table", "default_mach_grid"]

#: Default Mach grid: subsonic solutions to 0.9, supersonic ones from 1.2 to 2, and the
#: transonic gap sampled every 0.05 (no panel solution there: the zero-lift drag is the
#: transonic model of :mod:`panair.transonic`, the angle-of-attack increments the
#: bridge's).  Without the gap points the flight's spline ran straight from Mach 0.9 to
#: 1.2 under the modelled rise to the sonic value (APEX I, peak Mach 1.1: table CA at
#: Mach 1.0 about 0.28 where the model says 0.40).
DEFAULT_MACH = (0.05, 0.2, 0.35, 0.5, 0.6, 0.7, 0.8, 0.9, 0.95, 1.0, 1.05, 1.1, 1.2, 1.5, 2.0)
#: Default angles of attack solved by the panel method [deg]; 30-90 deg are added by
#: the high-angle model (panair.sweep.ALPHA_EXTEND_DEG)
DEFAULT_ALPHA_DEG = (0.0, 2.0, 4.0, 6.0, 8.0, 12.0, 16.0, 20.0)


def default_mach_grid(peak_mach: float | None = None) -> np.ndarray:
    """:data:`DEFAULT_MACH`, extended past 2 in steps of 0.5 to cover 1.3 x
    ``peak_mach`` [-] when given, up to the supersonic solver's largest Mach number
    (a flight beyond it is flown on the table's last row, with the clamp warning)."""
    from .solver import MACH_SUPERSONIC_MAX
    grid = list(DEFAULT_MACH)
    if peak_mach is not None and math.isfinite(peak_mach):
        while grid[-1] < 1.3 * peak_mach and grid[-1] + 0.5 <= MACH_SUPERSONIC_MAX:
            grid.append(grid[-1] + 0.5)
    return np.array(grid)


def ogival_nose(rocket):
    """``(x_end [m], tau [-], area_ratio [-])`` of the rocket's nose when it meets the
    body tangentially (joint angle at most
    :data:`ironbark_opt.aero.empirical_drag.OGIVAL_JOINT_MAX`: tangent ogive, Haack /
    von Karman, parabolic K = 1, elliptical), else None: its end aft of the tip, base
    diameter / length and base area / reference area (McCoy's transonic head drag,
    :mod:`panair.transonic` item 4)."""
    from ironbark_opt.aero.empirical_drag import OGIVAL_JOINT_MAX, joint_half_angle
    from ironbark_opt.rocket.nose import NoseCone
    front = rocket.front_component()
    if not isinstance(front, NoseCone) or joint_half_angle(front) > OGIVAL_JOINT_MAX:
        return None
    return (float(front.x + front.length), 2.0 * front.radius / front.length,
            front.radius ** 2 / rocket.reference_radius() ** 2)


def rocket_table(rocket, aero_spec, mach=None, alpha_deg=None, *, refine: float = 1.0,
                 workers: int = 2, progress: bool = False, use_panair: bool = False,
                 checkpoint_dir=None, extra_metadata: dict | None = None,
                 fin_roll_offset: float = 0.0, pool=None, fixed_roll: bool = False):
    """Build the AeroTable of ``rocket`` (:class:`ironbark_opt.rocket.Rocket`).

    Parameters
    ----------
    rocket : Rocket
    aero_spec : AeroSpec
        For the surface roughness and transition Reynolds number of the
        (reference) friction column.
    mach : 1-D array [-], optional (default :func:`default_mach_grid`)
    alpha_deg : 1-D array [deg], optional (default :data:`DEFAULT_ALPHA_DEG`)
    refine : float
        Mesh refinement factor.
    workers, progress, use_panair, checkpoint_dir, pool
        As :func:`panair.sweep.build_table`.
    extra_metadata : dict, optional
    fin_roll_offset : float [rad]
        Every fin set meshed rolled this much further (from +z toward +y); a
        roll average of two orthogonal rolls (:mod:`panair.parallel_table`).
    fixed_roll : bool
        One or two fins at their own roll (:func:`~panair.geometry_adapter.from_rocket`;
        a wind-tunnel model), not at the roll average a flight table needs.
    """
    from ironbark_opt.aero.base_drag import BaseDrag
    from ironbark_opt.aero.empirical_drag import separated_pressure_ca
    from ironbark_opt.aero.friction import FrictionDrag
    from ironbark_opt.aero.model import friction_components

    from .geometry_adapter import from_rocket, is_symmetric
    from .mesh import MeshOptions
    from .sweep import build_table

    mach = default_mach_grid() if mach is None else np.asarray(mach, float)
    alpha_deg = np.asarray(DEFAULT_ALPHA_DEG if alpha_deg is None else alpha_deg, float)
    geom = from_rocket(rocket, fixed_roll=fixed_roll)
    if fin_roll_offset:
        geom = geom.with_fins_rolled(fin_roll_offset)
    sref = rocket.reference_area()
    lref = 2.0 * rocket.reference_radius()
    friction = FrictionDrag(friction_components(rocket, aero_spec.surface_roughness), sref,
                            aero_spec.re_transition)
    r_base = float(geom.body.r[-1])
    base = BaseDrag(math.pi * r_base ** 2, sref,
                    fin_trailing_edge_area=sum(fs.trailing_edge_base_area()
                                               for fs in rocket.fin_sets()))
    return build_table(geom, mach, np.radians(alpha_deg), sref=sref, lref=lref, xref=0.0,
                       friction=friction, base_drag=base, symmetric=is_symmetric(geom),
                       options=MeshOptions(refine=refine), workers=workers, progress=progress,
                       use_panair=use_panair,
                       subsonic_pressure=lambda m: separated_pressure_ca(rocket, m, streamlined_edges=False),
                       checkpoint_dir=checkpoint_dir, extra_metadata=extra_metadata, pool=pool,
                       nose=ogival_nose(rocket))
