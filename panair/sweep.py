"""Mach x angle-of-attack sweeps of the panel solver -> AeroTable.

Angles are the polar aeroballistic convention: ``alpha`` is the total
angle of attack, in the body's x-z plane (for a rocket with 4 (or any
even number of) fins meshed with no fin in that plane).  For every Mach
number the panels' influence matrix is built and factorised once and all
angles are right-hand sides (on a full model meshed as its own mirror image, e.g. 3
fins rolled 0 or 90 deg: for one panel of each mirror pair,
:class:`panair.solver.panels.MirrorFold`); Mach numbers run in parallel in a
process pool with a progress bar.

The table's axial force is ``CA = CA_pressure + CA_base``; skin friction is
flown at the flight's own Reynolds number (:mod:`ironbark_opt.aero.model`
adds it at every step), so:

* ``CA_pressure`` is the zero-lift pressure drag model of
  :mod:`panair.transonic` (separated flow and edges below the critical Mach
  number, the transonic rise, the supersonic panel wave drag) plus the panel
  solution's angle-of-attack increment (``CA_pressure_linear`` keeps the
  panel solution itself);
* ``CA_friction`` is :class:`ironbark_opt.aero.friction.FrictionDrag`
  (component build-up) at the sea-level ISA unit Reynolds number of each
  Mach number, Re/m = rho0 a0 M / mu0 (ICAO standard atmosphere, 1993:
  rho0 = 1.225 kg/m^3, a0 = 340.294 m/s, mu0 = 1.7894e-5 Pa s), for
  reference only (part of ``CA`` with ``friction_in_table``);
* ``CA_base`` is :class:`ironbark_opt.aero.base_drag.BaseDrag` (power
  off; ``CA_power_on`` uses the jet area given; its model, by default
  McCoy's MC DRAG base pressure above Mach 1, is recorded in the metadata
  as ``base_drag_model``).

Friction and base drag have no incidence model of their own: both columns (and the
friction the flight adds) fall as Jorgensen's cos^2 alpha (NASA TR R-474, 1977,
eq. 2; :func:`ironbark_opt.aero.crossflow.axial_factor`), zero at 90 deg.

Likewise ``CN = CN_pressure + CN_crossflow`` and ``Cm = Cm_pressure +
Cm_crossflow``: a potential solution has no viscous cross-flow, the
non-linear body lift that dominates at large angles of attack.  It is the
viscous cross-flow model of Allen & Perkins (NACA TR 1048, 1951; as
Jorgensen, NASA TR R-474, 1977, eq. 1: CN = eta(l/d) Cdc(M sin alpha)
(A_plan/A_ref) sin^2 alpha at the body planform's centroid,
:mod:`ironbark_opt.aero.crossflow`), as in the rest of Ironbark
(:func:`ironbark_opt.aero.barrowman.body_lift`; ``crossflow_k``: Galejs'
constant K instead of eta Cdc).  It has zero slope at alpha = 0, so CN-alpha and the static margin are the
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
SolverError: a table never contains an unsolved number silently.  A
supersonic Mach number linear theory cannot solve at all (panels steeper
than the Mach cone, non-physical pressures at the lifting angles) is solved
by the local-inclination method instead (tangent cone, tangent wedge,
Prandtl-Meyer; :mod:`panair.solver.local_inclination`), listed in the
metadata ``mach_local_inclination``, after more tries: on a body mesh free of the
cross-body Mach-cone coincidence at that Mach number, then on a coarser and a finer mesh
(a local singularity moves with the panel layout; :func:`_remesh_refused`, refinements
in ``mach_remeshed_refine``).  A
supersonic Mach number whose shared mesh is near that coincidence (a run of equal
body panels with a phase below :data:`panair.coincidence.COINCIDENCE_BAND`; there the
solution passes every check but is off) is solved on its own body spacing from the
start; the Mach numbers solved on their own mesh are listed in ``mach_remeshed``
(their spacings in ``mach_remeshed_body_spacing_cal``).  So is a supersonic Mach number
whose nose tip needs a longer conical tip than the shared mesh's: each one's tip is
sharpened for it alone (:func:`panair.mesh.tip_options`; the shared mesh's for the lowest
supersonic Mach number), the fraction of the nose its cone covers listed in
``mach_tip_cone_fraction`` (0: none).  The other exception is
recorded: a supersonic angle of attack above the largest one linear theory solves
(it breaks at large angles: expansion past vacuum) continues the last solved one with Jorgensen's potential-flow shape
(:func:`_solve_one`); those angles are listed per Mach number in the
metadata ``alpha_deg_extrapolated`` and ``ironbark aero build`` warns.
A fin leading edge that is sonic for linear theory (its pressure singular and
beyond stagnation there, the load integrable) keeps linear theory's solution;
such Mach numbers are listed in ``mach_sonic_leading_edge``
(:func:`panair.solver.supersonic._sonic_leading_edge`).  Out-of-range pressures confined
to a few panels (a local singularity: at most ``CLIP_AREA_MAX`` of the wetted area with at
most ``CLIP_LOAD_MAX`` x the tolerated load, :mod:`panair.solver.supersonic`) are clipped
to vacuum / stagnation and the solution kept; those Mach numbers are listed in
``mach_cp_clipped``.

**No leading-edge suction on the fins.**  The fins' axial pressure force keeps its
zero-incidence value at every angle of attack (:func:`_without_fin_suction`): a thin
fin's pressure load at incidence acts normal to its plane, and the potential solution's
forward "suction" force at the leading edge is not realised where the flow separates
there, as it does at the sharp or small-radius edges of rocket fins (Polhamus, NASA TN
D-3767, 1966: on sharp edges the potential-flow leading-edge suction is not obtained).
The panels' near-field suction is also no measure of it: summed over the fins it tilts
their force to the normal of the free stream or beyond (no induced drag at all; fins 5,
10, 12 of Allen's tunnel models at Mach 0.6).  Measured on those models (Allen,
NASA/TM-2001-210652; tests/validation/test_allen_finbody.py), CA(alpha 3-4 deg) -
CA(0): tunnel -0.0055 ... -0.018 at Mach 0.6 / 0.9, the panel solution with the fins'
suction -0.010 ... -0.053, without it -0.002 ... -0.005.  The body's increment (the
nose's attached flow) is kept, as are the normal force and moment.  An external
PANAIR's supersonic forces are its own (no panel pressures read back).

Numeric-only.
"""
from __future__ import annotations

import hashlib
import json
import math
from concurrent.futures import as_completed
from contextlib import nullcontext
from dataclasses import replace

import numpy as np

from ironbark_opt.aero.barrowman import body_lift
from ironbark_opt.aero.crossflow import axial_factor
from ironbark_opt.aero.crossflow import eta as crossflow_eta
from ironbark_opt.errors import InputError, SolverError

from .a502 import find_panair, run_panair
from .bridge import transonic_bridge
from .mach_pool import MachPool
from .coincidence import coincidence_free_options
from .mesh import MeshOptions, RocketGeometry, mesh_rocket, tip_cone_fraction, tip_options
from .solver import MACH_SUBSONIC_MAX, MACH_SUPERSONIC_MIN, build_panels, make_solver
from .solver.panels import mirror_plane

__all__ = ["sweep_pressure", "build_table", "body_planform", "body_fineness",
           "SEA_LEVEL_RE_PER_M_PER_MACH"]

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


def body_fineness(body) -> float:
    """Fineness ratio [-] of a body of revolution: length over maximum diameter."""
    x, r = np.asarray(body.x, float), np.asarray(body.r, float)
    return float((x[-1] - x[0]) / (2.0 * np.max(r)))


def blunt_leading_edge_ca(geometry: RocketGeometry, mach, sref: float) -> np.ndarray:
    """Pressure drag of blunt (square, also an unbevelled hexagon edge; rounded) fin leading edges [-] on ``sref``
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
        if f.leading_edge_kind not in ("square", "rounded", "airfoil"):
            continue
        sweep = math.atan2(float(f.le_at(1.0)), f.span)
        ca += (leading_edge_cd(m, f.leading_edge_kind) * math.cos(sweep) ** 2
               * int(f.count) * f.thickness * f.span / sref)
    return ca


def separated_transitions_ca(geometry: RocketGeometry, mach, sref: float, base_drag=None) -> np.ndarray:
    """Zero-lift axial force [-] of the fully separated boattails and reducers in a
    supersonic solution (0 without any): the base pressure on their annuli, Niskanen
    2013 eq. 3.88 (gamma < 1) as the subsonic table and OpenRocket apply it at every
    Mach number, with the table's base-pressure model
    (:func:`ironbark_opt.aero.base_drag.cd_base`).  Their panels are left out of the
    supersonic solve (:attr:`panair.mesh.MeshOptions.separated_transitions`)."""
    from ironbark_opt.aero.base_drag import cd_base
    m = np.asarray(mach, float)
    annuli = sum(math.pi * (r0 ** 2 - r1 ** 2) for _, _, r0, r1 in geometry.body.separated_transitions())
    if not annuli:
        return np.zeros_like(m)
    model = (base_drag.model, base_drag.afterbody_calibers) if base_drag is not None else ()
    return np.asarray(cd_base(m, *model), float) * annuli / sref


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
    at or below a solved angle is raised.  Subsonic, the same holds above a solved
    lifting angle: a local pressure that grows with the angle past the singular bound
    (a fin's wake meeting the sharp leading edge of a fin in line behind it, where
    linear theory's velocity is infinite: a fuzzed stack with 0.39 m fins, |Cp| 550 at
    4 deg and 1.25e4 at 20 deg); with no lifting angle solved the error is raised (a
    degenerate mesh fails at every angle)."""
    panels, mach, alphas, sref, lref, xref, rule = args[:7]
    body_mask = args[7] if len(args) > 7 else None
    if isinstance(panels, _OwnMesh):
        panels = panels.build()
    try:
        # every angle is in the x-z plane: a mirror-symmetric full model solves half its panels
        solver = make_solver(panels, mach, sref=sref, lref=lref, xref=xref, pressure_rule=rule,
                             mirror=True)
    except SolverError:
        if mach < MACH_SUPERSONIC_MIN:
            raise
        return _local_inclination(panels, mach, alphas, sref, lref, xref)
    def body_cp_min(r0):
        if body_mask is not None and np.any(body_mask) and abs(alphas[0]) < 1e-12:
            # incompressible minimum Cp on the body (Prandtl-Glauert factor removed)
            return float(np.min(r0.cp[body_mask])) * math.sqrt(1.0 - mach * mach)
        return None

    try:
        res = solver.solve(alphas)
        return (mach, _without_fin_suction(panels, res, sref, solver), [], body_cp_min(res[0]),
                _linear_how(solver))
    except SolverError:
        pass
    res, cp_min = [], None
    for i, a in enumerate(alphas):
        try:
            r = solver.solve(a)[0]
            if i == 0:
                cp_min = body_cp_min(r)
        except SolverError:
            if not res or abs(_jorgensen_potential(alphas[i - 1])) < 1e-12:
                if mach < MACH_SUPERSONIC_MIN:
                    raise
                # linear theory solves no lifting angle of this Mach number: all of it
                # from local inclination (one method per Mach number, never mixed)
                return _local_inclination(panels, mach, alphas, sref, lref, xref)
            break
        res.append(r)
    rows = [list(row) for row in _without_fin_suction(panels, res, sref, solver)]
    (ca0, cn0, cm0), g0 = rows[-1], _jorgensen_potential(alphas[len(rows) - 1])
    extra = [float(a) for a in alphas[len(rows):]]      # the first failure and all above it
    rows += [[ca0, cn0 * _jorgensen_potential(a) / g0, cm0 * _jorgensen_potential(a) / g0]
             for a in extra]
    return mach, np.array(rows), extra, cp_min, _linear_how(solver)


def _job_cost(job) -> float:
    """A Mach-number job's relative cost: panels squared, four potential evaluations
    per supersonic matrix entry."""
    return float(job[0].n) ** 2 * (4 if job[1] >= MACH_SUPERSONIC_MIN else 1)


def _linear_how(solver) -> str:
    """The method of a linear solution: "linear", with "-sonic-le" where a fin
    leading edge is sonic for linear theory and its pressures went out of range
    (kept in the forces; :func:`panair.solver.supersonic._sonic_leading_edge`) and
    "-clipped" where a local singularity's pressures were clipped
    (:data:`panair.solver.supersonic.CLIP_AREA_MAX`)."""
    return ("linear" + ("-sonic-le" if getattr(solver, "sonic_le_out_of_range", False) else "")
            + ("-clipped" if getattr(solver, "cp_clipped", False) else ""))


class _OwnMesh:
    """A supersonic Mach number's own mesh (``options``, :mod:`panair.coincidence`),
    built where its job runs (meshing is cheap next to the supersonic influence matrix,
    which is per Mach number anyway); ``n`` [-] the shared mesh's panel count, for
    :func:`_job_cost`."""

    def __init__(self, geometry, options, symmetric, n):
        self.geometry, self.options, self.symmetric, self.n = geometry, options, symmetric, n

    def build(self):
        panels = build_panels(mesh_rocket(self.geometry, symmetric=self.symmetric,
                                          options=self.options), symmetric=self.symmetric)
        mirror_plane(panels)
        return panels


REMESH_REFINE = (0.8, 1.25)
"""Mesh refinement factors [-] (on the Mach number's own options) of the last tries of a
supersonic Mach number linear theory refused, before it falls to local inclination
(:func:`_remesh_refused`).  A local singularity (a fin-tip corner, a sliver next to a
near-sonic edge) is a property of the panel layout, not of the flow: another layout moves
it.  Measured (session 18, 20 random student rockets, tests/random_rockets.py seeds
30-49): three had Mach 1.2 refused (out-of-range panels on 0.003-0.23 % of the area
carrying 5.2-6.7 x the tolerated load, just past :data:`panair.solver.supersonic.CLIP_LOAD_MAX`)
and fell to local inclination, whose strip-theory lift was 2.1 x (39.0 against 18.6 /rad
at Mach 0.9 and 20.3 at Mach 1.5), 1.3 x and 1.4 x the neighbours'.  On the coarser or
the finer mesh each solved, in line with its neighbours: seed 37 on refine 1.25, CN-alpha
20.0 /rad; seed 45 on 0.8, 26.4 (a refine 1.3 mesh 26.3); seed 49 on 0.8, 31.4 (1.5: 27.1).
Cost: up to three more solves of a refused Mach number (build of seed 37: 12.8 -> 24.8 s
under load)."""


def _remesh_refused(geometry, tip_opt, symmetric, alpha, sref, lref, xref, rule, method,
                    spacing, store) -> None:
    """Every supersonic Mach number linear theory refused on its mesh (method
    "local-inclination") tried again, first on a body mesh free of the cross-body Mach-cone
    coincidence (with the Mach number's own nose tip, ``tip_opt`` [Mach -> options],
    :func:`panair.mesh.tip_options`; :func:`panair.coincidence.coincidence_free_options`
    with no band: the candidate spacing whose runs' smallest phase is largest; not for
    one solved on its own body spacing already, ``spacing``), then on its own options
    coarser and finer (:data:`REMESH_REFINE`); the first try linear theory solves replaces
    its results, by ``store(mach, coefficients, extrapolated, cp_min, method,
    body_spacing, refine)`` (:func:`sweep_pressure`'s: results, checkpoint, ``spacing``,
    ``refines``).  Panels steeper than the Mach cone (no mesh helps) stay refused.

    A Mach number solved only at small angles (its higher ones continued with Jorgensen's
    shape, :func:`_solve_one`) is not retried: measured (session 18, seeds 30-49 of
    tests/random_rockets.py) two stopped below 8 deg for a local singularity (seed 37,
    Mach 1.5, from 4 deg; seed 45, Mach 1.2, from 6 deg); on the finer mesh seed 37 solved
    to 12 deg with CN-alpha 1.3-4 % above the continuation at 2-8 deg, for 2.4 x the
    Mach number's solving time."""
    refused = sorted(m for m, how in method.items() if how == "local-inclination")
    for m in refused:
        tries = []
        if m not in spacing:
            opt_m = coincidence_free_options(geometry, tip_opt[m], m, band=math.inf)
            if opt_m != tip_opt[m]:
                tries.append(opt_m)
        base = coincidence_free_options(geometry, tip_opt[m], m)
        tries += [coincidence_free_options(geometry, replace(base, refine=base.refine * f), m)
                  for f in REMESH_REFINE]
        for opt_m in tries:
            try:
                job = (_OwnMesh(geometry, opt_m, symmetric, 0), m, alpha, sref, lref, xref, rule)
                mm, arr, extra, cpm, how = _solve_one(job)
            except SolverError:
                continue
            if how != "local-inclination":
                store(mm, arr, extra, cpm, how, opt_m.body_spacing, opt_m.refine)
                break


def _local_inclination(panels, mach, alphas, sref, lref, xref):
    """The fallback of a supersonic Mach number linear theory cannot solve
    (:mod:`panair.solver.local_inclination`)."""
    from .solver.local_inclination import LocalInclinationSolver
    solver = LocalInclinationSolver(panels, mach, sref=sref, lref=lref, xref=xref)
    res = solver.solve(alphas)
    return mach, _without_fin_suction(panels, res, sref, solver), [], None, "local-inclination"


def _fin_axial_force(panels, results, sref: float, integrated: np.ndarray) -> np.ndarray:
    """Axial pressure force coefficient [-] (on ``sref`` [m^2]) of the fin panels
    (:meth:`PanelSet.fin_mask`) the solver puts in the forces, ``integrated`` ((n,) bool,
    the solver's own ``integrated``: the supersonic solver leaves the fin tip caps out), in
    each of ``results`` (their ``cp`` per panel; a panel a solver left out is NaN there
    and counts 0)."""
    from .solver.pressure import integrate_forces
    _, cen, nrm, area = panels.geometry()
    nrm = panels.force_normals(nrm)
    sel = integrated & panels.fin_mask()
    return np.array([integrate_forces(np.nan_to_num(np.asarray(r.cp, float)[sel]), cen[sel],
                                      nrm[sel], area[sel], sref=sref, lref=1.0, xref=0.0,
                                      symmetric=panels.symmetric)["CA"] for r in results])


def _without_fin_suction(panels, results, sref: float, solver) -> np.ndarray:
    """(n_alpha, 3) CA, CN, Cm of ``results``, the fins' axial pressure force held at its
    zero-incidence value (module docstring: no leading-edge suction); ``solver`` solves
    alpha = 0 when ``results`` do not start there."""
    rows = np.array([[r.CA, r.CN, r.Cm] for r in results], float)
    if not len(results):
        return rows
    ref = results[0] if abs(results[0].alpha) < 1e-12 else solver.solve(0.0)[0]
    fin = _fin_axial_force(panels, list(results) + [ref], sref, solver.integrated)
    rows[:, 0] -= fin[:-1] - fin[-1]
    return rows


def _panair_one(nets, mach, alphas, sref, lref, xref, symmetric, workdir):
    rows = []
    for a in alphas:                      # ALPC = alpha: one deck per angle
        a_deg = math.degrees(a)
        run = run_panair(nets, mach=mach, alpha_deg=a_deg, alpc_deg=a_deg, sref=sref, cref=lref,
                         bref=lref, xref=xref, symmetric=symmetric, workdir=workdir)
        f = run.forces[0]
        rows.append([f.CA, f.CN, f.Cm])
    return np.array(rows)


class _Checkpoint:
    """Per-Mach results on disk (``checkpoint_dir``), so a failed or interrupted
    build keeps what it solved.  One ``.npz`` per Mach number, named by a hash of
    everything the solution depends on; written atomically."""

    def __init__(self, folder, nets, nets_sup, alpha, rule, use_panair):
        self.folder = None
        if folder is None:
            return
        from pathlib import Path
        self.folder = Path(folder)
        h = hashlib.sha256()
        for group in (nets, nets_sup):
            for n in group:
                h.update(n.name.encode())
                h.update(np.ascontiguousarray(np.round(n.points, 12)).tobytes())
                for k, v in sorted(n.meta.items()) if getattr(n, "meta", None) else ():
                    h.update(k.encode())
                    h.update(np.ascontiguousarray(v).tobytes())
        h.update(np.ascontiguousarray(np.round(alpha, 12)).tobytes())
        h.update(f"{rule}|{use_panair}|{CHECKPOINT_VERSION}".encode())
        self.key = h.hexdigest()[:20]

    def _path(self, mach):
        return self.folder / f"{self.key}_M{mach:.6f}.npz"

    def load(self, mach):
        if self.folder is None or not self._path(mach).is_file():
            return None
        try:
            with np.load(self._path(mach)) as z:
                cpm = float(z["cp_min"]) if np.isfinite(z["cp_min"]) else None
                spacing = float(z["body_spacing"]) if "body_spacing" in z.files else math.nan
                refine = float(z["refine"]) if "refine" in z.files else math.nan
                return (np.array(z["coefficients"]), [float(a) for a in z["extrapolated"]], cpm,
                        str(z["method"]), None if math.isnan(spacing) else spacing,
                        None if math.isnan(refine) else refine)
        except (OSError, ValueError, KeyError):
            return None                   # a damaged file is solved again

    def save(self, mach, arr, extra, cpm, how, spacing=None, refine=None):
        """``spacing``: the body spacing [calibres] of a Mach number solved on its own
        mesh (None: the shared one); ``refine`` [-] its own mesh refinement (None: the
        shared one's)."""
        if self.folder is None:
            return
        import os
        self.folder.mkdir(parents=True, exist_ok=True)
        tmp = self._path(mach).with_suffix(".tmp.npz")
        np.savez(tmp, coefficients=arr, extrapolated=np.asarray(extra, float),
                 cp_min=np.nan if cpm is None else cpm, method=np.array(how),
                 body_spacing=np.nan if spacing is None else spacing,
                 refine=np.nan if refine is None else refine)
        os.replace(tmp, self._path(mach))


#: bump when the solver's numbers change, so old checkpoints are not reused
CHECKPOINT_VERSION = 8


def sweep_pressure(geometry: RocketGeometry, mach, alpha, *, sref: float, lref: float,
                   xref: float, symmetric: bool = True, options: MeshOptions | None = None,
                   pressure_rule: str = "second-order", workers: int = 2, progress: bool = True,
                   use_panair: bool = False, panair_workdir=None, executor=None,
                   checkpoint_dir=None, pool=None):
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
    checkpoint_dir : path, optional
        Every Mach number is saved there as soon as it is solved (keyed by the
        mesh, the angles, the pressure rule and the Mach number) and a rerun
        (e.g. after an interrupted or partly failed build) reuses it.
    pool : panair.mach_pool.MachPool, optional
        Run the Mach numbers there (shared with other sweeps running in other
        threads, e.g. a multi-stage rocket's configurations) instead of in a pool
        of ``workers`` processes of this sweep's own.

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
    opt_sup = supersonic_mesh_options(opt, sup)
    # each supersonic Mach number's nose tip sharpened for it alone (the shared mesh's
    # is the lowest one's; panair.mesh.tip_options)
    tip_opt = {float(m): tip_options(geometry, opt_sup, float(m)) for m in sup}
    nets = mesh_rocket(geometry, symmetric=symmetric, options=opt)
    nets_sup = nets if opt_sup == opt else mesh_rocket(geometry, symmetric=symmetric,
                                                       options=opt_sup)
    panels = build_panels(nets, symmetric=symmetric) if len(sub) or not len(sup) else None
    panels_sup = (panels if nets_sup is nets and panels is not None
                  else build_panels(nets_sup, symmetric=symmetric) if len(sup) else None)
    for ps in {id(p): p for p in (panels, panels_sup) if p is not None}.values():
        mirror_plane(ps)          # found once here, kept on the panels the jobs carry
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
    cp_min: dict[float, float] = {}
    method: dict[float, str] = {}
    spacing: dict[float, float] = {}     # Mach -> body spacing [cal] of its own mesh
    refines: dict[float, float] = {}     # Mach -> refinement of its own mesh (_remesh_refused)
    ckpt = _Checkpoint(checkpoint_dir, nets, nets_sup, alpha, pressure_rule, use_panair)
    for m in list(builtin) + list(external):
        hit = ckpt.load(float(m))
        if hit is not None:
            results[float(m)], extrapolated[float(m)], cp_min[float(m)], method[float(m)], sp, rf = hit
            if sp is not None:
                spacing[float(m)] = sp
            if rf is not None:
                refines[float(m)] = rf
    builtin_all = builtin
    builtin = np.array([m for m in builtin if float(m) not in results])
    external_all = external
    external = np.array([m for m in external if float(m) not in results])
    body_mask = None
    if panels is not None:
        body_ids = [k for k, n in enumerate(nets) if n.name == "body"]
        body_mask = np.isin(panels.network, body_ids) & panels.integrate
        # The body's critical Mach number is read from its own suction peak: leave out
        # the fin-root strips, whose potential solution is singular at the fin-body
        # corners (Cp -7 beside a square 2 mm fin root on a model rocket) and whose
        # compressibility is the fins' own (Korn/Lock, panair.transonic.fin_critical_mach)
        x_c = panels.corners[:, :, 0].mean(axis=1)
        for f in geometry.fins:
            pad = max(2.0 * f.thickness, 0.05 * f.root_chord)
            body_mask &= ~((x_c > f.x_root - pad) & (x_c < f.x_root + f.root_chord + pad))
    # a supersonic Mach number whose tip needs a longer cone than the shared mesh's, or
    # whose shared mesh is near a cross-body Mach-cone coincidence, is solved on its own
    # mesh (its own tip, panair.mesh.tip_options; its own body spacing, panair.coincidence)
    own = {float(m): o for m in builtin if m >= MACH_SUPERSONIC_MIN
           for o in [coincidence_free_options(geometry, tip_opt[float(m)], float(m))] if o != opt_sup}
    jobs = [(_OwnMesh(geometry, own[float(m)], symmetric, panels_sup.n) if float(m) in own
             else panels_sup if m >= MACH_SUPERSONIC_MIN else panels, float(m), alpha, sref, lref,
             xref, pressure_rule, None if m >= MACH_SUPERSONIC_MIN else body_mask)
            for m in builtin]

    def store(m, arr, extra, cpm, how, body_spacing=None, refine=None):
        """One Mach number's results, checkpointed; ``body_spacing`` [cal] and ``refine``
        [-] of its own mesh (None: the shared one's; entered in ``spacing``, ``refines``
        where they differ)."""
        results[m], extrapolated[m], cp_min[m], method[m] = arr, extra, cpm, how
        if body_spacing is not None and body_spacing != opt_sup.body_spacing:
            spacing[m] = body_spacing
        if refine is not None and refine != opt_sup.refine:
            refines[m] = refine
        ckpt.save(m, arr, extra, cpm, how, spacing.get(m), refines.get(m))

    def store_own(m, arr, extra, cpm, how):
        store(m, arr, extra, cpm, how, own[m].body_spacing if m in own else None)

    # longest first (supersonic: more panels and four potential evaluations per
    # matrix), so the last Mach numbers to finish are short ones and the workers
    # end together; results are keyed by Mach number, the order changes nothing else
    jobs.sort(key=lambda job: -_job_cost(job))
    if len(jobs):
        # compile the influence kernels (or load them from the on-disk cache) once
        # here, so the worker processes forked below inherit them
        from .solver.kernels import warm_up
        warm_up()
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
            for m, arr, extra, cpm, how in done:
                store_own(m, arr, extra, cpm, how)
        elif pool is not None or (workers > 1 and len(jobs) > 1):
            # Mach numbers in parallel (panair.mach_pool: one BLAS thread per worker, the
            # costliest first), in a pool shared with other sweeps or this sweep's own;
            # each saved as soon as it is solved
            with nullcontext(pool) if pool is not None else MachPool(min(workers, len(jobs))) as mp:
                futures = [mp.submit(_job_cost(job), _solve_one, job) for job in jobs]
                try:
                    for fut in as_completed(futures):
                        m, arr, extra, cpm, how = fut.result()
                        store_own(m, arr, extra, cpm, how)
                        if bar:
                            bar.update()
                finally:
                    for fut in futures:
                        fut.cancel()
        else:
            for job in jobs:
                m, arr, extra, cpm, how = _solve_one(job)
                store_own(m, arr, extra, cpm, how)
                if bar:
                    bar.update()
        for m in external:
            nets_m = (nets_sup if tip_opt[float(m)] == opt_sup else
                      mesh_rocket(geometry, symmetric=symmetric, options=tip_opt[float(m)]))
            store(float(m), _panair_one(nets_m, float(m), alpha, sref, lref, xref, symmetric,
                                        panair_workdir), [], None, "panair")
            if bar:
                bar.update()
    finally:
        if bar:
            bar.close()
    _remesh_refused(geometry, tip_opt, symmetric, alpha, sref, lref, xref, pressure_rule,
                    method, spacing, store)
    # blunt fin leading edges: meshed as wedges without axial force where linear
    # theory cannot solve them (supersonic meshes); their drag is Niskanen's
    sharpened = [float(m) for m in builtin_all if m >= MACH_SUPERSONIC_MIN and opt_sup.blunt_le_wedge > 0
                 and any(f.leading_edge_kind in ("square", "rounded", "airfoil") for f in geometry.fins)]
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
            "mach_solved_builtin": [float(m) for m in builtin_all],
            "mach_solved_panair": [float(m) for m in external_all],
            "mach_bridged": [float(m) for m in gap],
            "geometry_hash": digest.hexdigest()[:16], "symmetric": bool(symmetric),
            "mach_blunt_le_model": sharpened,
            "alpha_deg_extrapolated": {f"{m:g}": [round(math.degrees(a), 6) for a in extra]
                                       for m, extra in sorted(extrapolated.items()) if extra},
            "pressure_rule": pressure_rule,
            "mach_local_inclination": sorted(m for m, how in method.items()
                                             if how == "local-inclination"),
            "mach_remeshed": sorted(set(spacing) | set(refines)
                                    | {m for m, o in tip_opt.items() if o != opt_sup}),
            "mach_remeshed_body_spacing_cal": {f"{m:g}": spacing[m] for m in sorted(spacing)},
            "mach_remeshed_refine": {f"{m:g}": refines[m] for m in sorted(refines)},
            "mach_tip_cone_fraction": {f"{m:g}": round(tip_cone_fraction(geometry.body, o), 6)
                                       for m, o in sorted(tip_opt.items())},
            "mach_sonic_leading_edge": sorted(m for m, how in method.items()
                                              if how.startswith("linear-sonic-le")),
            "mach_cp_clipped": sorted(m for m, how in method.items() if how.endswith("-clipped")),
            "body_cp_min_incompressible": next((cp_min[m] for m in sorted(cp_min)
                                                if cp_min[m] is not None), None)}
    return coeffs, info


#: Angles of attack [deg] above a sweep's largest, filled by the high-angle model
ALPHA_EXTEND_DEG = (30.0, 45.0, 60.0, 75.0, 90.0)


def _extend_alpha(values, alpha, alpha_ext, kind):
    """Continue (n_mach, n_alpha) coefficients of the potential solution past its largest
    angle: CN, Cm with Jorgensen's potential-flow shape sin(2 alpha) cos(alpha/2) (NASA
    TR R-474, eq. 1; same centre of pressure), CA with cos^2 alpha (the axial part of the
    same decomposition, Jorgensen eq. 2: CA = CA(0) cos^2 alpha)."""
    last = values[:, -1:]
    a0 = alpha[-1]
    if kind == "CA":
        return np.hstack([values, last * (np.cos(alpha_ext) ** 2 / math.cos(a0) ** 2)[None, :]])
    g0 = _jorgensen_potential(a0)
    if abs(g0) < 1e-12:
        return np.hstack([values, np.zeros((values.shape[0], len(alpha_ext)))])
    return np.hstack([values, last * (_jorgensen_potential(alpha_ext) / g0)[None, :]])


def supersonic_mesh_options(options: MeshOptions | None, mach_sup) -> MeshOptions:
    """The shared mesh options of a sweep's supersonic Mach numbers ``mach_sup`` [-]:
    finer fin strips (:meth:`MeshOptions.for_mach`) and the nose tip subinclined at the
    lowest of them (``tip_mach``, :func:`panair.mesh._sharpened_tip`; none when that
    one needs no conical tip).  A higher Mach number that needs a longer conical tip is
    solved on its own mesh (:func:`panair.mesh.tip_options`, :func:`sweep_pressure`)."""
    opt_sup = (options or MeshOptions()).for_mach(MACH_SUPERSONIC_MIN)
    if len(mach_sup):
        opt_sup = replace(opt_sup, tip_mach=(float(np.min(mach_sup)),))
    return opt_sup


def build_table(geometry: RocketGeometry, mach, alpha, *, sref: float, lref: float, xref: float,
                friction=None, base_drag=None, symmetric: bool = True,
                options: MeshOptions | None = None, workers: int = 2, progress: bool = True,
                use_panair: bool = False, pressure_rule: str = "second-order",
                extra_metadata: dict | None = None, executor=None,
                crossflow_k: float | None = None, subsonic_pressure=None,
                friction_in_table: bool = False, alpha_extend_deg=ALPHA_EXTEND_DEG,
                checkpoint_dir=None, pool=None, nose=None):
    """Sweep -> AeroTable with the transonic, separated-flow, viscous and base parts.

    Parameters
    ----------
    geometry : RocketGeometry [m]
    mach : 1-D array [-]; alpha : 1-D array [rad], starting at 0
    sref : float [m^2]; lref : float [m]; xref : float [m]
    friction : ironbark_opt.aero.friction.FrictionDrag, optional
        Tabulated as ``CA_friction`` at the sea-level unit Reynolds number of each
        Mach number for reference; part of ``CA`` only with ``friction_in_table``
        (otherwise the flight adds friction at its own Reynolds number).
    base_drag : ironbark_opt.aero.base_drag.BaseDrag, optional
    symmetric, options, workers, progress, use_panair, pressure_rule, executor
        As in :func:`sweep_pressure`.
    extra_metadata : dict, optional
    crossflow_k : float or None [-]
        None: the body's viscous cross-flow eta(l/d) Cdc(M sin alpha) of Allen &
        Perkins / Jorgensen; a number: that constant in place of eta Cdc
        (Galejs' K = 1.1 was the default before session 13; 0: none).
    subsonic_pressure : callable mach -> CA [-], optional
        Zero-lift pressure drag below the critical Mach number (separated flow and
        edges, e.g. :func:`ironbark_opt.aero.empirical_drag.separated_pressure_ca`);
        None: 0 (d'Alembert).  See :mod:`panair.transonic`.
    nose : (float, float, float), optional
        ``(x_end [m], tau [-], area_ratio [-])`` of an ogival nose (meeting the body
        tangentially): its end, base diameter / length and base area / ``sref``; its
        transonic drag is then McCoy's (:mod:`panair.transonic`, item 4).  None: the
        nose follows the area-rule anchor with the rest.
    friction_in_table : bool
        Add friction to ``CA`` (a table for a tool that has no friction model).
    alpha_extend_deg : sequence of float [deg]
        Angles above the largest of ``alpha`` added by the high-angle model
        (:func:`_extend_alpha` plus the viscous cross-flow), up to 90 deg.
    checkpoint_dir : path, optional
        Each solved Mach number is saved there and reused by a rerun
        (:func:`sweep_pressure`).
    pool : panair.mach_pool.MachPool, optional
        As in :func:`sweep_pressure`.

    Returns
    -------
    ironbark_opt.aero.table.AeroTable with CA (pressure + base [+ friction]),
    CA_power_on, CN, Cm (totals), CA_pressure, CA_pressure_linear (the panel
    solution before the zero-lift model), CA_friction, CA_base, CN_pressure,
    Cm_pressure, CN_crossflow, Cm_crossflow.
    """
    from ironbark_opt import __version__
    from ironbark_opt.aero.table import AeroTable
    from .transonic import (body_critical_mach, fin_critical_mach, nose_supersonic_share,
                            nose_transonic, zero_lift_pressure)
    if crossflow_k is not None and not (math.isfinite(crossflow_k) and crossflow_k >= 0):
        raise InputError(f"crossflow_k must be >= 0, got {crossflow_k}", field="crossflow_k")
    alpha = np.asarray(alpha, float)
    if len(alpha) == 0 or abs(alpha[0]) > 1e-12:
        raise InputError("the angle-of-attack grid must start at 0 (the zero-lift drag is "
                         "read there)", field="alpha")
    coeffs, info = sweep_pressure(geometry, mach, alpha, sref=sref, lref=lref, xref=xref,
                                  symmetric=symmetric, options=options, workers=workers,
                                  progress=progress, use_panair=use_panair,
                                  pressure_rule=pressure_rule, executor=executor,
                                  checkpoint_dir=checkpoint_dir, pool=pool)
    mach = np.asarray(mach, float)
    # ---- fully separated boattails' and reducers' base pressure, at the supersonic Mach numbers the
    # built-in solver solved without it (an external PANAIR integrates its own panels)
    builtin_sup = np.isin(mach, info["mach_solved_builtin"]) & (mach >= MACH_SUPERSONIC_MIN)
    coeffs["CA"] = coeffs["CA"] + np.where(builtin_sup, separated_transitions_ca(geometry, mach, sref, base_drag),
                                           0.0)[:, None]
    # ---- zero-lift pressure drag: subsonic separated flow, critical Mach, transonic rise
    ca_lin = coeffs["CA"]
    d_ca = ca_lin - ca_lin[:, :1]                       # angle-of-attack increments (panel)
    cp_min = info.get("body_cp_min_incompressible")
    m_cr_body = body_critical_mach(cp_min) if cp_min is not None else 0.95
    m_cr_fins = [fin_critical_mach(f) for f in geometry.fins]
    m_cr = float(min([m_cr_body] + m_cr_fins))
    sub_fn = subsonic_pressure if subsonic_pressure is not None else (lambda m: 0.0 * np.asarray(m))
    solved_sup = sorted(m for m in info["mach_solved_builtin"] + info["mach_solved_panair"]
                        if m >= MACH_SUPERSONIC_MIN)
    m_sup = np.array(solved_sup)
    p_sup = np.array([ca_lin[int(np.argmin(np.abs(mach - m))), 0] for m in solved_sup])
    anchor_solved = []
    # an ogival nose rises from its own critical Mach number (McCoy), which may lie below m_cr
    m_cr_nose, rise = nose_transonic(nose[1], nose[2]) if nose is not None else (m_cr, None)
    if np.any(mach > min(m_cr, m_cr_nose)) and not len(m_sup):
        # a supersonic anchor for the transonic rise although the grid has none
        m_anchor = float(MACH_SUPERSONIC_MIN)
        c1, i1 = sweep_pressure(geometry, [m_anchor], np.zeros(1), sref=sref, lref=lref,
                                xref=xref, symmetric=symmetric, options=options, workers=1,
                                progress=False, use_panair=use_panair,
                                pressure_rule=pressure_rule, checkpoint_dir=checkpoint_dir)
        p_anchor = float(c1["CA"][0, 0]) + (0.0 if use_panair else
                                             float(separated_transitions_ca(geometry, m_anchor, sref, base_drag)))
        m_sup, p_sup = np.array([m_anchor]), np.array([p_anchor])
        anchor_solved = [m_anchor]
    # each fin set rises from its own critical Mach number on its own exposed planform
    lock_sets = [(m_i, int(f.count) * f.span * float(np.mean(f.chord_at(np.linspace(0, 1, 65)))) / sref)
                 for m_i, f in zip(m_cr_fins, geometry.fins)]
    # an ogival nose's own transonic drag (McCoy) in place of its share of the sonic anchor
    # (decided on the lower of the configuration's and the nose's own critical Mach number)
    nose_model, nose_meta = None, None
    if nose is not None and len(m_sup) and np.any((mach > min(m_cr, m_cr_nose)) & (mach < m_sup[0])):
        x_end, tau, area_ratio = nose
        grid_sup = mach[mach >= MACH_SUPERSONIC_MIN] if not anchor_solved else m_sup
        share = nose_supersonic_share(geometry.body, float(m_sup[0]), x_end, sref=sref,
                                      options=supersonic_mesh_options(options, grid_sup),
                                      pressure_rule=pressure_rule)
        if share is not None:
            nose_model = (rise, share)
            m_cr = min(m_cr, m_cr_nose)
            nose_meta = {"model": "McCoy 1981 (MC DRAG) transonic head drag", "tau": tau,
                         "mach_critical": m_cr_nose, "sonic_ca": float(rise(1.0)),
                         "supersonic_share_ca": share, "supersonic_share_mach": float(m_sup[0])}
    p0 = zero_lift_pressure(mach, m_cr, sub_fn, m_sup, p_sup, lock_sets=lock_sets, nose=nose_model)
    ca_p = p0[:, None] + d_ca
    includes = ["pressure"]
    ca_f = np.zeros(len(mach))
    if friction is not None:
        re = np.maximum(mach, 1e-3) * SEA_LEVEL_RE_PER_M_PER_MACH
        ca_f = np.asarray(friction.CA(mach, re), float)
        if friction_in_table:
            includes.append("friction")
    ca_b = np.zeros(len(mach))
    ca_b_on = np.zeros(len(mach))
    if base_drag is not None:
        ca_b = np.asarray(base_drag.CA_power_off(mach), float)
        ca_b_on = np.asarray(base_drag.CA_power_on(mach), float)
        includes.append("base")
    bad = p0 + ca_b < -1e-9
    if np.any(bad):
        raise SolverError("zero-lift pressure plus base drag is negative (a thrust) at Mach "
                          + ", ".join(f"{m:g} ({v:+.4f})" for m, v in zip(mach[bad], (p0 + ca_b)[bad]))
                          + ": the panel solution is not physical for this geometry")
    # ---- angles of attack past the sweep: high-angle model up to 90 deg
    ext = np.radians([a for a in alpha_extend_deg if a > math.degrees(alpha[-1]) + 1e-9])
    cn_p, cm_p = coeffs["CN"], coeffs["Cm"]
    if len(ext):
        ca_lin = _extend_alpha(ca_lin, alpha, ext, "CA")
        ca_p = _extend_alpha(ca_p, alpha, ext, "CA")
        cn_p = _extend_alpha(cn_p, alpha, ext, "CN")
        cm_p = _extend_alpha(cm_p, alpha, ext, "Cm")
        alpha = np.concatenate([alpha, ext])
    n_a = len(alpha)
    cn_x = np.zeros((len(mach), n_a))
    cm_x = np.zeros((len(mach), n_a))
    fineness = body_fineness(geometry.body)
    if crossflow_k is None or crossflow_k > 0:
        a_plan, x_plan = body_planform(geometry.body)
        cn_x, _ = body_lift(alpha[None, :], a_plan, x_plan, sref, mach=mach[:, None],
                            fineness_ratio=fineness, k=crossflow_k)
        cn_x = np.asarray(cn_x, float) * np.ones((len(mach), n_a))
        cm_x = -cn_x * (x_plan - xref) / lref
        includes.append("crossflow")
    # friction and base have no incidence model of their own: Jorgensen's cos^2 alpha
    # (NASA TR R-474 eq. 2), as the flight applies to friction kept out of the table
    jorg = axial_factor(alpha)[None, :]
    f_in = ca_f[:, None] * jorg if friction_in_table else 0.0
    table = {"CA": ca_p + f_in + ca_b[:, None] * jorg,
             "CA_power_on": ca_p + f_in + ca_b_on[:, None] * jorg,
             "CN": cn_p + cn_x, "Cm": cm_p + cm_x, "CA_pressure": ca_p,
             "CA_pressure_linear": ca_lin,
             "CA_friction": ca_f[:, None] * jorg, "CA_base": ca_b[:, None] * jorg,
             "CN_pressure": cn_p, "Cm_pressure": cm_p,
             "CN_crossflow": cn_x, "Cm_crossflow": cm_x}
    meta = {"generator": "ironbark panair.sweep (built-in panel solver)",
            "version": __version__, "name": geometry.name, "body_axes": "x aft, z up; "
            "alpha = total angle of attack (polar aeroballistic)",
            "transonic_bridge": bool(info["mach_bridged"]),
            "transonic_bridge_model": "angle-of-attack increments: monotone cubic Hermite "
                                      "(Fritsch & Carlson 1980)",
            "zero_lift_pressure_model": "panair.transonic: subsonic separated-flow and edge drag "
                                        "(Niskanen 2013 eq. 3.81/3.88/3.89) below the critical "
                                        "Mach number, monotone rise to the sonic (area-rule) "
                                        "value (an ogival nose: McCoy's transonic head drag, "
                                        "see nose_transonic), supersonic panel solutions above",
            "supersonic_separated_transitions_x_m": [[x0, x1] for x0, x1, _, _ in
                                                     geometry.body.separated_transitions()],
            "mach_critical": m_cr, "mach_critical_body": m_cr_body,
            "mach_critical_fins": m_cr_fins, "mach_sonic_anchor_solved": anchor_solved,
            "nose_transonic": nose_meta,
            "friction_reynolds": ("sea-level ISA unit Reynolds number at each Mach (in CA)"
                                  if friction_in_table else
                                  "not in CA: the flight adds friction at its own Reynolds "
                                  "number; CA_friction is the sea-level value for reference"),
            **({"base_drag_model": getattr(base_drag, "model", type(base_drag).__name__),
                "base_jet_area_m2": float(getattr(base_drag, "jet_area", 0.0))}
               if base_drag is not None else {}),
            "crossflow_model": (("viscous cross-flow, Allen & Perkins (NACA TR 1048) as Jorgensen "
                                 "(NASA TR R-474 eq. 1): CN = eta(l/d) Cdc(M sin alpha) (A_plan/A_ref) "
                                 f"sin^2 alpha at the planform centroid, l/d = {fineness:.4g}, eta = "
                                 f"{crossflow_eta(fineness):.4g}, Cdc subcritical (ironbark_opt.aero.crossflow)")
                                if crossflow_k is None else
                                (f"viscous cross-flow with a constant coefficient: CN = K (A_plan/A_ref) "
                                 f"sin^2 alpha at the planform centroid, K = {crossflow_k:g}")),
            "alpha_deg_high_angle_model": [round(math.degrees(a), 6) for a in ext],
            "high_angle_model": "potential part continued with Jorgensen's shape sin 2a cos(a/2), "
                                "CA with cos^2 a (NASA TR R-474 eq. 1-2), plus the cross-flow; "
                                "friction and base CA(0) cos^2 a at every angle (eq. 2)",
            **info, **(extra_metadata or {})}
    json.dumps(meta)   # must be serialisable
    return AeroTable(mach, alpha, table, reference_area=sref,
                     reference_length=lref, moment_reference_x=xref, includes=tuple(includes),
                     metadata=meta)
