"""Mach x angle-of-attack sweeps of the panel solver -> AeroTable.

Angles are the polar aeroballistic convention: ``alpha`` is the total
angle of attack, in the body's x-z plane (for a rocket with 4 (or any
even number of) fins meshed with no fin in that plane).  For every Mach
number the panels' influence matrix is built and factorised once and all
angles are right-hand sides; Mach numbers run in parallel in a process
pool with a progress bar.

The table a user plots is the total: ``CA = CA_pressure + CA_friction +
CA_base`` where

* ``CA_pressure`` is the panel solution (body, fins; base excluded);
* ``CA_friction`` is :class:`ironbark_opt.aero.friction.FrictionDrag`
  (component build-up) at the sea-level ISA unit Reynolds number of each
  Mach number, Re/m = rho0 a0 M / mu0 (ICAO standard atmosphere, 1993:
  rho0 = 1.225 kg/m^3, a0 = 340.294 m/s, mu0 = 1.7894e-5 Pa s) — a table
  has no Reynolds axis, and sea level is where drag matters most;
* ``CA_base`` is :class:`ironbark_opt.aero.base_drag.BaseDrag` (power
  off; ``CA_power_on`` uses the jet area given; its model, by default
  McCoy's MC DRAG base pressure above Mach 1, is recorded in the metadata
  as ``base_drag_model``).

Likewise ``CN = CN_pressure + CN_crossflow`` and ``Cm = Cm_pressure +
Cm_crossflow``: a potential solution has no viscous cross-flow, the
non-linear body lift that dominates at large angles of attack.  It is the
viscous cross-flow model of Allen & Perkins (NACA TR 1048, 1951; as
Jorgensen, NASA TR R-474, 1977, eq. 1: CN = eta Cdc (A_plan/A_ref)
sin^2 alpha at the body planform's centroid), with eta Cdc = K = 1.1 as in
the rest of Ironbark (Galejs; :func:`ironbark_opt.aero.barrowman.body_lift`).
It has zero slope at alpha = 0, so CN-alpha and the static margin are the
panel solution's.

Blunt (square, rounded) fin leading edges are superinclined for linear
supersonic theory; supersonic meshes replace them by a wedge 3 fin
thicknesses long whose panels carry no axial force
(:meth:`panair.mesh.FinGeometry.sharpened`), and their pressure drag is
Niskanen's (:func:`blunt_leading_edge_ca`; metadata ``mach_blunt_le_model``).

Supersonic Mach numbers are solved by the built-in supersonic solver, or
by an external PANAIR when ``use_panair`` is set; Mach numbers between the last
subsonic and first supersonic solution are faired by
:func:`panair.bridge.transonic_bridge`.  Otherwise they raise
SolverError: a table never contains an unsolved number silently.  The one
exception is recorded: a supersonic angle of attack above the largest one
linear theory solves (it breaks at large angles: expansion past vacuum)
continues the last solved one with Jorgensen's potential-flow shape
(:func:`_solve_one`); those angles are listed per Mach number in the
metadata ``alpha_deg_extrapolated`` and ``ironbark aero build`` warns.

Numeric-only.
"""
from __future__ import annotations

import hashlib
import json
import math
from concurrent.futures import ProcessPoolExecutor

import numpy as np

from ironbark_opt.aero.barrowman import BODY_LIFT_K, body_lift
from ironbark_opt.errors import InputError, SolverError

from .a502 import find_panair, run_panair
from .bridge import transonic_bridge
from .mesh import MeshOptions, RocketGeometry, mesh_rocket
from .solver import MACH_SUBSONIC_MAX, MACH_SUPERSONIC_MIN, build_panels, make_solver

__all__ = ["sweep_pressure", "build_table", "body_planform", "SEA_LEVEL_RE_PER_M_PER_MACH"]

#: rho0 a0 / mu0 of the ICAO standard atmosphere at sea level [1/m per unit Mach]
SEA_LEVEL_RE_PER_M_PER_MACH = 1.225 * 340.294 / 1.7894e-5


def body_planform(body) -> tuple[float, float]:
    """Side-view (planform) area [m^2] of a body of revolution and its centroid
    [m aft of the nose tip]: int 2 r dx and int 2 r x dx / area (trapezoids)."""
    x, r = np.asarray(body.x, float), np.asarray(body.r, float)
    w = np.diff(x)
    area = float(np.sum(w * (r[1:] + r[:-1])))
    # centroid of each trapezoid strip (x0..x1, full widths 2 r0 .. 2 r1)
    xc = x[:-1] + w * (r[:-1] + 2 * r[1:]) / (3 * np.maximum(r[:-1] + r[1:], 1e-300))
    moment = float(np.sum(w * (r[1:] + r[:-1]) * xc))
    return area, moment / area


def blunt_leading_edge_ca(geometry: RocketGeometry, mach, sref: float) -> np.ndarray:
    """Pressure drag of blunt (square, rounded) fin leading edges [-] on ``sref``
    [m^2], for the Mach numbers [-] whose mesh replaces them by a wedge
    (:meth:`panair.mesh.FinGeometry.sharpened`: supersonic).

    Niskanen 2013 (OpenRocket technical documentation) sec. 3.4.4, as the
    empirical estimate: square edges 0.85 q_stag/q (eq. 3.86-3.87), rounded
    eq. 3.89, on the frontal area count x thickness x span, times cos^2 of the
    leading-edge sweep.
    """
    from ironbark_opt.aero.empirical_drag import leading_edge_cd
    m = np.asarray(mach, float)
    ca = np.zeros_like(m)
    for f in geometry.fins:
        if f.section not in ("square", "rounded"):
            continue
        sweep = math.atan2(float(f.le_at(1.0)), f.span)
        ca += (leading_edge_cd(m, f.section) * math.cos(sweep) ** 2
               * int(f.count) * f.thickness * f.span / sref)
    return ca


def _jorgensen_potential(alpha):
    """Potential-flow normal-force shape sin(2 alpha) cos(alpha / 2) [-]
    (Jorgensen, NASA TR R-474, 1977, eq. 1, first term)."""
    return np.sin(2 * alpha) * np.cos(alpha / 2)


def _solve_one(args):
    """(mach, (n_alpha, 3) CA CN Cm, extrapolated alphas [rad]).

    A supersonic angle of attack the solver reports unsolvable (linear theory
    breaks: expansion past vacuum, singular corners) above the largest solved
    one takes the last solved coefficients with CN and Cm scaled by Jorgensen's
    potential-flow shape sin(2 alpha) cos(alpha/2) (same centre of pressure)
    and CA held; the angles are returned so the table records them.  A failure
    at or below a solved angle is raised."""
    panels, mach, alphas, sref, lref, xref, rule = args
    solver = make_solver(panels, mach, sref=sref, lref=lref, xref=xref, pressure_rule=rule)
    try:
        return mach, np.array([[r.CA, r.CN, r.Cm] for r in solver.solve(alphas)]), []
    except SolverError:
        if mach < MACH_SUPERSONIC_MIN:
            raise
    rows = []
    for i, a in enumerate(alphas):
        try:
            r = solver.solve(a)[0]
        except SolverError:
            if not rows or abs(_jorgensen_potential(alphas[i - 1])) < 1e-12:
                raise
            break
        rows.append([r.CA, r.CN, r.Cm])
    (ca0, cn0, cm0), g0 = rows[-1], _jorgensen_potential(alphas[len(rows) - 1])
    extra = [float(a) for a in alphas[len(rows):]]      # the first failure and all above it
    rows += [[ca0, cn0 * _jorgensen_potential(a) / g0, cm0 * _jorgensen_potential(a) / g0]
             for a in extra]
    return mach, np.array(rows), extra


def _panair_one(nets, mach, alphas, sref, lref, xref, symmetric, workdir):
    rows = []
    for a in alphas:                      # ALPC = alpha: one deck per angle
        a_deg = math.degrees(a)
        run = run_panair(nets, mach=mach, alpha_deg=a_deg, alpc_deg=a_deg, sref=sref, cref=lref,
                         bref=lref, xref=xref, symmetric=symmetric, workdir=workdir)
        f = run.forces[0]
        rows.append([f.CA, f.CN, f.Cm])
    return np.array(rows)


def sweep_pressure(geometry: RocketGeometry, mach, alpha, *, sref: float, lref: float,
                   xref: float, symmetric: bool = True, options: MeshOptions | None = None,
                   pressure_rule: str = "second-order", workers: int = 2, progress: bool = True,
                   use_panair: bool = False, panair_workdir=None, executor=None):
    """Pressure CA, CN, Cm on a Mach x alpha grid.

    Parameters
    ----------
    geometry : RocketGeometry [m]
    mach : 1-D array [-]; alpha : 1-D array [rad]
    sref : float [m^2]; lref : float [m]; xref : float [m] aft of the nose tip
    symmetric : bool
        Half model (no fin may lie in the x-z plane).
    options : MeshOptions
    pressure_rule : str
    workers : int
        Processes (Mach numbers in parallel); 1 = in this process.
    executor : optional
        Where the Mach numbers run instead (``"local:N"``, ``"dask://HOST:PORT"``,
        a ``distributed.Client``; see :func:`ironbark_opt.executors.get_executor`).
    progress : bool
        tqdm progress bar on stderr.
    use_panair : bool
        Solve the supersonic Mach numbers with an external PANAIR instead.
    panair_workdir : path, optional

    Returns
    -------
    coefficients : dict name -> ndarray (n_mach, n_alpha) for CA, CN, Cm
    info : dict (panels, solved / bridged / PANAIR Mach numbers, geometry hash)

    Raises
    ------
    SolverError
        A Mach number that cannot be solved (transonic without both sides,
        superinclined panels, non-physical pressures), naming it.
    """
    mach = np.asarray(mach, float)
    alpha = np.asarray(alpha, float)
    if mach.ndim != 1 or alpha.ndim != 1 or np.any(np.diff(mach) <= 0) or np.any(np.diff(alpha) <= 0):
        raise InputError("mach and alpha must be strictly increasing 1-D grids", field="mach/alpha")
    sub = mach[mach <= MACH_SUBSONIC_MAX]
    sup = mach[mach >= MACH_SUPERSONIC_MIN]
    # one mesh per regime: supersonic Mach numbers get finer fin strips
    # (MeshOptions.for_mach; the same mesh when the options say so)
    opt = options or MeshOptions()
    opt_sup = opt.for_mach(MACH_SUPERSONIC_MIN)
    nets = mesh_rocket(geometry, symmetric=symmetric, options=opt)
    nets_sup = nets if opt_sup == opt else mesh_rocket(geometry, symmetric=symmetric,
                                                       options=opt_sup)
    panels = build_panels(nets, symmetric=symmetric) if len(sub) or not len(sup) else None
    panels_sup = (panels if nets_sup is nets and panels is not None
                  else build_panels(nets_sup, symmetric=symmetric) if len(sup) else None)
    gap = mach[(mach > MACH_SUBSONIC_MAX) & (mach < MACH_SUPERSONIC_MIN)]
    if use_panair and len(sup) and not find_panair():
        raise SolverError("use_panair: no PANAIR executable (set IRONBARK_PANAIR or put "
                          "'panair' on PATH)")
    if len(gap) and (not len(sub) or not len(sup)):
        raise SolverError(f"Mach {', '.join(f'{m:g}' for m in gap)} is transonic: it can only "
                          "be bridged between a subsonic and a supersonic solution")
    builtin = sub if use_panair else np.concatenate([sub, sup])
    external = sup if use_panair else np.zeros(0)
    results: dict[float, np.ndarray] = {}
    extrapolated: dict[float, list] = {}
    jobs = [(panels_sup if m >= MACH_SUPERSONIC_MIN else panels, float(m), alpha, sref, lref,
             xref, pressure_rule) for m in builtin]
    bar = None
    if progress:
        from tqdm import tqdm
        bar = tqdm(total=len(builtin) + len(external), desc="panel solves (Mach)", unit="Mach")
    try:
        if executor is not None:          # cluster hook: one task per Mach (ironbark_opt.executors)
            from ironbark_opt.executors import run_chunks, use_executor
            with use_executor(executor) as ex:
                done = run_chunks(ex, _solve_one, [(job,) for job in jobs], label="panel",
                                  on_chunk=lambda i, k: bar.update() if bar else None)
            for m, arr, extra in done:
                results[m], extrapolated[m] = arr, extra
        elif workers > 1 and len(jobs) > 1:
            with ProcessPoolExecutor(max_workers=workers) as pool:
                for m, arr, extra in pool.map(_solve_one, jobs):
                    results[m], extrapolated[m] = arr, extra
                    if bar:
                        bar.update()
        else:
            for job in jobs:
                m, arr, extra = _solve_one(job)
                results[m], extrapolated[m] = arr, extra
                if bar:
                    bar.update()
        for m in external:
            results[float(m)] = _panair_one(nets_sup, float(m), alpha, sref, lref, xref, symmetric,
                                            panair_workdir)
            if bar:
                bar.update()
    finally:
        if bar:
            bar.close()
    # blunt fin leading edges: meshed as wedges without axial force where linear
    # theory cannot solve them (supersonic meshes); their drag is Niskanen's
    sharpened = [float(m) for m in builtin if m >= MACH_SUPERSONIC_MIN and opt_sup.blunt_le_wedge > 0
                 and any(f.section in ("square", "rounded") for f in geometry.fins)]
    for m in sharpened:
        results[m] = results[m].copy()
        results[m][:, 0] += blunt_leading_edge_ca(geometry, m, sref)
    solved = np.array(sorted(results))
    stack = np.array([results[m] for m in solved])            # (n_solved, n_alpha, 3)
    full = transonic_bridge(solved, stack, mach) if len(gap) else stack
    coeffs = {name: full[:, :, k] for k, name in enumerate(("CA", "CN", "Cm"))}
    digest = hashlib.sha256()
    for n in nets:
        digest.update(n.name.encode())
        digest.update(np.ascontiguousarray(np.round(n.points, 12)).tobytes())
    first = panels if panels is not None else panels_sup
    info = {"panels": int(first.n), "wake_panels": int(len(first.wake_corners)),
            "panels_supersonic": int(panels_sup.n) if panels_sup is not None else 0,
            "mach_solved_builtin": [float(m) for m in builtin],
            "mach_solved_panair": [float(m) for m in external],
            "mach_bridged": [float(m) for m in gap],
            "geometry_hash": digest.hexdigest()[:16], "symmetric": bool(symmetric),
            "mach_blunt_le_model": sharpened,
            "alpha_deg_extrapolated": {f"{m:g}": [round(math.degrees(a), 6) for a in extra]
                                       for m, extra in sorted(extrapolated.items()) if extra},
            "pressure_rule": pressure_rule}
    return coeffs, info


def build_table(geometry: RocketGeometry, mach, alpha, *, sref: float, lref: float, xref: float,
                friction=None, base_drag=None, symmetric: bool = True,
                options: MeshOptions | None = None, workers: int = 2, progress: bool = True,
                use_panair: bool = False, pressure_rule: str = "second-order",
                extra_metadata: dict | None = None, executor=None,
                crossflow_k: float = BODY_LIFT_K):
    """Sweep -> AeroTable with the viscous and base parts added.

    Parameters
    ----------
    geometry : RocketGeometry [m]
    mach : 1-D array [-]; alpha : 1-D array [rad]
    sref : float [m^2]; lref : float [m]; xref : float [m]
    friction : ironbark_opt.aero.friction.FrictionDrag, optional
        Evaluated at the sea-level unit Reynolds number of each Mach number.
    base_drag : ironbark_opt.aero.base_drag.BaseDrag, optional
    symmetric, options, workers, progress, use_panair, pressure_rule, executor
        As in :func:`sweep_pressure`.
    extra_metadata : dict, optional
    crossflow_k : float [-]
        Viscous cross-flow coefficient eta Cdc of the body (0: none).

    Returns
    -------
    ironbark_opt.aero.table.AeroTable with CA (total), CA_power_on, CN, Cm
    (totals), CA_pressure, CA_friction, CA_base, CN_pressure, Cm_pressure,
    CN_crossflow, Cm_crossflow.
    """
    from ironbark_opt import __version__
    from ironbark_opt.aero.table import AeroTable
    if not (math.isfinite(crossflow_k) and crossflow_k >= 0):
        raise InputError(f"crossflow_k must be >= 0, got {crossflow_k}", field="crossflow_k")
    coeffs, info = sweep_pressure(geometry, mach, alpha, sref=sref, lref=lref, xref=xref,
                                  symmetric=symmetric, options=options, workers=workers,
                                  progress=progress, use_panair=use_panair,
                                  pressure_rule=pressure_rule, executor=executor)
    mach = np.asarray(mach, float)
    n_a = len(alpha)
    ones = np.ones((1, n_a))
    includes = ["pressure"]
    ca_f = np.zeros(len(mach))
    if friction is not None:
        re = np.maximum(mach, 1e-3) * SEA_LEVEL_RE_PER_M_PER_MACH
        ca_f = np.asarray(friction.CA(mach, re), float)
        includes.append("friction")
    ca_b = np.zeros(len(mach))
    ca_b_on = np.zeros(len(mach))
    if base_drag is not None:
        ca_b = np.asarray(base_drag.CA_power_off(mach), float)
        ca_b_on = np.asarray(base_drag.CA_power_on(mach), float)
        includes.append("base")
    cn_x = np.zeros((len(mach), n_a))
    cm_x = np.zeros((len(mach), n_a))
    if crossflow_k > 0:
        a_plan, x_plan = body_planform(geometry.body)
        cn_a, _ = body_lift(np.asarray(alpha, float), a_plan, x_plan, sref, k=crossflow_k)
        cn_x = np.ones((len(mach), 1)) * np.asarray(cn_a)[None, :]
        cm_x = -cn_x * (x_plan - xref) / lref
        includes.append("crossflow")
    ca_p = coeffs["CA"]
    table = {"CA": ca_p + ca_f[:, None] * ones + ca_b[:, None] * ones,
             "CA_power_on": ca_p + ca_f[:, None] * ones + ca_b_on[:, None] * ones,
             "CN": coeffs["CN"] + cn_x, "Cm": coeffs["Cm"] + cm_x, "CA_pressure": ca_p,
             "CA_friction": ca_f[:, None] * ones, "CA_base": ca_b[:, None] * ones,
             "CN_pressure": coeffs["CN"], "Cm_pressure": coeffs["Cm"],
             "CN_crossflow": cn_x, "Cm_crossflow": cm_x}
    meta = {"generator": "ironbark panair.sweep (built-in panel solver)",
            "version": __version__, "name": geometry.name, "body_axes": "x aft, z up; "
            "alpha = total angle of attack (polar aeroballistic)",
            "transonic_bridge": bool(info["mach_bridged"]),
            "transonic_bridge_model": "monotone cubic Hermite (Fritsch & Carlson 1980)",
            "friction_reynolds": "sea-level ISA unit Reynolds number at each Mach",
            **({"base_drag_model": getattr(base_drag, "model", type(base_drag).__name__),
                "base_jet_area_m2": float(getattr(base_drag, "jet_area", 0.0))}
               if base_drag is not None else {}),
            "crossflow_model": (f"viscous cross-flow, Allen & Perkins (NACA TR 1048): CN = K "
                                f"(A_plan/A_ref) sin^2 alpha at the planform centroid, K = "
                                f"{crossflow_k:g}"),
            **info, **(extra_metadata or {})}
    json.dumps(meta)   # must be serialisable
    return AeroTable(mach, np.asarray(alpha, float), table, reference_area=sref,
                     reference_length=lref, moment_reference_x=xref, includes=tuple(includes),
                     metadata=meta)
