"""The assembled aerodynamic model the flight core evaluates at every step.

Sources, in order of precedence for each coefficient:

- **Axial force CA**: an :class:`AeroTable`'s ``CA`` (``CA_power_on`` while
  the motor burns, when the table has it), plus the skin friction and base
  drag the table does not include (its ``includes`` metadata says which);
  without a table: friction + base drag only, which misses pressure/wave
  drag, so :func:`build_aero_model` refuses that (a table or drag curve is
  required).  The launch guides' drag (:mod:`.protuberance`) goes with the friction.
  Friction, base drag and a drag curve of Mach alone fall with the angle of attack
  as cos^2 alpha (Jorgensen, NASA TR R-474 eq. 2; :func:`.crossflow.axial_factor`).
- **Normal force CN and pitching moment Cm**: the table's ``CN``/``Cm`` when
  present; otherwise the Barrowman baseline (:mod:`.barrowman`) with
  ``CN = CN_alpha(M) sin(alpha)`` plus the body's viscous cross-flow
  ``eta(l/d) Cdc(M sin alpha) (A_plan/A_ref) sin^2(alpha)`` (Allen & Perkins,
  NACA Report 1048; Jorgensen, NASA TR R-474 eq. 1; :mod:`.crossflow`) at the
  planform centroid, so the normal force stays physical at large angles of
  attack (rail exit in wind, near apogee); ``body_lift_k`` replaces eta Cdc by
  Galejs' constant K (NAR Sentinel 39; Niskanen 2013, eq. 3.26).
- **Damping**: pitch/yaw ``Cmq`` about the current CG and roll ``Clp`` and
  cant forcing from :mod:`.damping`, always from geometry.

All methods are symbolic-safe; the flight core calls them with CasADi SX.
"""
from __future__ import annotations

import math
import warnings
from dataclasses import dataclass, field

import casadi as ca
import numpy as np

from ironbark_opt import _math as m
from ironbark_opt.aero import barrowman, damping
from ironbark_opt.aero.base_drag import BaseDrag
from ironbark_opt.aero.crossflow import axial_factor
from ironbark_opt.aero.friction import FrictionComponent, FrictionDrag
from ironbark_opt.errors import InputError
from ironbark_opt.rocket.hardware import DEFAULT_BUTTON

_ALPHA_CP = math.radians(0.5)   # [rad] angle at which a table's CP is read
#: Mach grid of the tabulated Barrowman/damping sums (cubic B-spline; inputs clamped to it)
LIFT_MACH_GRID = np.concatenate([np.arange(0.0, 0.5, 0.02), np.arange(0.5, 2.0, 0.005), np.arange(2.0, 6.0001, 0.05)])


@dataclass(frozen=True)
class FinGeometry:
    """What roll forcing/damping need of one fin set."""

    planform: barrowman.FinPlanform
    count: int
    x_root_le: float
    body_radius: float
    cant: float
    #: section lift data from a file (``FinSet.section_lift``), None: thin airfoil
    section_lift: tuple | None = None


@dataclass(frozen=True)
class LiftGeometry:
    """Barrowman inputs: body components (Mach-independent) and fin sets."""

    bodies: tuple            # of barrowman.Lift
    fins: tuple              # of FinGeometry
    planform_area: float     # [m^2] body side projection, for the viscous cross-flow
    planform_centroid_x: float  # [m]
    fineness_ratio: float    # [-] body length / maximum diameter (cross-flow eta)
    #: tube fin sets: (count, x_le [m], length [m], inner_radius [m]) each
    tubes: tuple = ()

    def components(self, mach, reference_area: float):
        """Barrowman Lift components at ``mach`` (symbolic-safe)."""
        comps = list(self.bodies)
        from ironbark_opt.rocket.fin_files import section_slope
        for f in self.fins:
            comps.append(barrowman.fins(f.planform, f.count, f.x_root_le, f.body_radius,
                                        reference_area, mach, section_slope(f.section_lift)))
        for count, x_le, length, r_in in self.tubes:
            comps.append(barrowman.tube_fins(count, x_le, length, r_in, reference_area, mach))
        return comps


@dataclass(frozen=True)
class AeroModel:
    """Coefficients for the dynamics (see module docstring).

    Parameters
    ----------
    reference_area : float [m^2]
    reference_length : float [m]
    moment_reference_x : float [m]
        Point Cm is given about, aft of the nose tip.
    lift : LiftGeometry
    table : AeroTable or None
    friction : FrictionDrag or None
        Added to CA unless the table includes friction.
    base : BaseDrag or None
        Added to CA unless the table includes base drag.
    jet_relief : BaseDrag or None
        Base drag of the exhaust's share of the base, taken off CA while the
        motor burns when the table's base drag was built without a jet.
    body_lift_k : float or None [-]
        None: the body's viscous cross-flow is Allen & Perkins / Jorgensen's
        (:mod:`ironbark_opt.aero.crossflow`); a number: Galejs' constant K
        (:func:`~ironbark_opt.aero.barrowman.body_lift`, 1.1 before session 13).
    """

    reference_area: float
    reference_length: float
    moment_reference_x: float
    lift: LiftGeometry
    table: object = None
    friction: FrictionDrag | None = None
    base: BaseDrag | None = None
    body_lift_k: float | None = None
    includes: tuple = field(default=())
    jet_relief: BaseDrag | None = None
    jet_area_source: str = ""

    # -- tabulated geometry sums (speed) ----------------------------------------
    def __getstate__(self):
        """Pickle without the cached interpolant ``_sums_fn`` (rebuilt on first use), so
        a pickle (the flight-model cache key) depends on the data, not on past use."""
        state = dict(self.__dict__)
        state.pop("_sums_fn", None)
        state.pop("_mach_fns", None)
        return state

    def _sums_exact(self, mach):
        """(S0, S1, S2, Cl_cant, Clp) at numeric ``mach``: S_k = sum_i CN_alpha_i x_i^k."""
        comps = self.lift.components(mach, self.reference_area)
        s0 = sum(c.cn_alpha + 0 * mach for c in comps)
        s1 = sum(c.cn_alpha * c.x_cp + 0 * mach for c in comps)
        s2 = sum(c.cn_alpha * c.x_cp ** 2 + 0 * mach for c in comps)
        forcing, clp = 0.0 * mach, 0.0 * mach
        for f in self.lift.fins:
            args = (f.planform, f.count, f.body_radius, self.reference_area, self.reference_length, mach)
            if f.cant != 0.0:
                forcing = forcing + f.cant * damping.roll_forcing_cl_delta(*args)
            clp = clp + damping.roll_damping_clp(*args)
        return s0, s1, s2, forcing, clp

    def _sums(self, mach):
        """The same sums from one vector-valued B-spline over ``LIFT_MACH_GRID``.

        The Barrowman fin slope, its CP shift and the roll derivatives are
        smooth functions of Mach alone; tabulating their sums once lets the
        flight step evaluate CP, pitch damping about any CG
        (sum CN_i (x_i - x_cg)^2 = S2 - 2 x_cg S1 + x_cg^2 S0) and roll
        with one interpolant call instead of the full component build-up.
        Tabulation error: < 1e-4 of each sum's range, largest at the ends of the
        transonic blends (M = 0.9, 1.5) where the exact curves are only C1.
        """
        if m.is_symbolic(mach):
            out = self._mach_tables(mach)
            return tuple(out[i] for i in range(5))
        mc = m.clip(mach, LIFT_MACH_GRID[0], LIFT_MACH_GRID[-1])
        fn = self._sums_function()
        flat = np.atleast_1d(np.asarray(mc, dtype=float)).ravel()
        out = np.array(fn(flat[None, :]))                                   # (5, n), one call
        if np.ndim(mach) == 0:
            return tuple(float(out[i, 0]) for i in range(5))
        return tuple(out[i].reshape(np.shape(mach)) for i in range(5))

    def _sums_function(self) -> ca.Function:
        """The cubic B-spline ``mach -> (S0, S1, S2, Cl_cant, Clp)`` over ``LIFT_MACH_GRID``."""
        fn = self.__dict__.get("_sums_fn")
        if fn is None:
            values = np.vstack(self._sums_exact(LIFT_MACH_GRID))          # (5, n)
            fn = ca.interpolant("lift_sums", "bspline", [LIFT_MACH_GRID], values.ravel(order="F"))
            object.__setattr__(self, "_sums_fn", fn)
        return fn

    def _merged_drag(self) -> tuple[str, ...]:
        """The table's axial coefficients that are cubic splines of Mach alone (drag curves):
        evaluated in one B-spline with the lift sums (:meth:`_mach_tables`)."""
        t = self.table
        if t is None or getattr(t, "reynolds", None) is not None:
            return ()
        return tuple(n for n in ("CA", "CA_power_on") if t.has(n) and t._spline(n).mach_only_cubic())

    def _mach_tables(self, mach):
        """Symbolic ``mach`` -> (S0, S1, S2, Cl_cant, Clp, *the :meth:`_merged_drag`
        coefficients), each clamped to its own grid, from one B-spline call
        (:func:`~ironbark_opt.aero.mach_splines.merged_spline`: the same splines to
        rounding; one knot search and basis evaluation per RK4 stage instead of one per
        table), or, inside :func:`~ironbark_opt.aero.mach_splines.table_form` ``("pp")``,
        from one piecewise-cubic table (for generated C code)."""
        from ironbark_opt.aero.mach_splines import current_form
        cache = self.__dict__.setdefault("_mach_fns", {})     # per form (mach_splines.table_form)
        cached = cache.get(current_form())
        if cached is None:
            names = self._merged_drag()
            if not names and current_form() == "bspline":   # nothing to share a call with: the sums' own
                cached = self._sums_function(), float(LIFT_MACH_GRID[0]), float(LIFT_MACH_GRID[-1])
            else:
                from ironbark_opt.aero.mach_splines import merged_spline
                splines = [self.table._spline(n) for n in names]
                cached = merged_spline("mach_tables", [LIFT_MACH_GRID] + [sp.axes[0] for sp in splines],
                                       [self._sums_function()] + [sp.casadi_interpolant() for sp in splines])
            cache[current_form()] = cached
        fn, lo, hi = cached
        return fn(m.clip(mach, lo, hi))

    # -- axial ------------------------------------------------------------------
    def axial(self, mach, alpha, reynolds_per_m, power_on: bool):
        """CA [-] (positive rearward).

        The parts without an incidence model of their own (skin friction, base drag, the
        jet's relief, and a table's CA that depends on Mach alone: drag curves, the
        empirical path) fall with the angle of attack as Jorgensen's cos^2 alpha
        (:func:`~ironbark_opt.aero.crossflow.axial_factor`); a table's CA over angle of
        attack (a panel table's pressure and base) is its own."""
        table_ca = 0.0 * mach
        t = self.table
        if t is not None and t.has("CA"):
            name = "CA_power_on" if (power_on and t.has("CA_power_on")) else "CA"
            # from the merged spline where the step reads the lift sums too (a symbolic angle
            # of attack); the rail phase (alpha = 0, no lift sums) keeps the drag curve's own
            # B-spline, but not in the piecewise-cubic form (one table call costs less there)
            from ironbark_opt.aero.mach_splines import current_form
            shared = m.is_symbolic(alpha) or current_form() == "pp"
            merged = self._merged_drag() if m.is_symbolic(mach) and shared and mach.numel() == 1 else ()
            if name in merged:
                table_ca = table_ca + self._mach_tables(mach)[5 + merged.index(name)]
            else:
                table_ca = table_ca + t.symbolic(name, mach, alpha)
        viscous = 0.0 * mach
        if self.friction is not None and "friction" not in self.includes:
            viscous = viscous + self.friction.CA(mach, reynolds_per_m)
        if self.base is not None and "base" not in self.includes:
            viscous = viscous + (self.base.CA_power_on(mach) if power_on else self.base.CA_power_off(mach))
        if power_on and self.jet_relief is not None:
            viscous = viscous - self.jet_relief.CA_power_off(mach)
        if t is not None and len(t.alpha) == 1:          # a drag curve: Mach alone
            return (table_ca + viscous) * axial_factor(alpha)
        return table_ca + viscous * axial_factor(alpha)

    # -- normal force and moment -------------------------------------------------
    def _barrowman(self, mach, alpha):
        s0, s1, _, _, _ = self._sums(mach)
        x_cp = s1 / s0
        s = m.sin_angle(alpha)
        cn_lin = s0 * s
        cn_body, _ = barrowman.body_lift(alpha, self.lift.planform_area, self.lift.planform_centroid_x,
                                         self.reference_area, mach=mach,
                                         fineness_ratio=self.lift.fineness_ratio, k=self.body_lift_k)
        cn = cn_lin + cn_body
        d = self.reference_length
        cm = -(cn_lin * (x_cp - self.moment_reference_x)
               + cn_body * (self.lift.planform_centroid_x - self.moment_reference_x)) / d
        return cn, cm, x_cp

    def normal(self, mach, alpha):
        """(CN, Cm about ``moment_reference_x``) [-]."""
        t = self.table
        if t is not None and t.has("CN") and t.has("Cm"):
            return t.symbolic("CN", mach, alpha), t.symbolic("Cm", mach, alpha)
        cn, cm, _ = self._barrowman(mach, alpha)
        return cn, cm

    def coefficients(self, mach, alpha, reynolds_per_m, power_on: bool):
        """(CA, CN, Cm) at Mach [-], total angle of attack [rad], Re per metre [1/m]."""
        cn, cm = self.normal(mach, alpha)
        return self.axial(mach, alpha, reynolds_per_m, power_on), cn, cm

    def center_of_pressure(self, mach, alpha):
        """CP [m aft of the nose tip] at small angle of attack (for static margin)."""
        t = self.table
        if t is not None and t.has("CN") and t.has("Cm"):
            a = m.fmax(alpha, _ALPHA_CP)
            # the small-angle (linear) CP: without a table's viscous cross-flow part,
            # which has zero slope at alpha = 0 (panair.sweep.build_table)
            lin = "_pressure" if t.has("CN_pressure") and t.has("Cm_pressure") else ""
            cn, cm = t.symbolic("CN" + lin, mach, a), t.symbolic("Cm" + lin, mach, a)
            return self.moment_reference_x - self.reference_length * cm / cn
        s0, s1, _, _, _ = self._sums(mach)
        return s1 / s0

    # -- damping ----------------------------------------------------------------
    def pitch_damping(self, mach, x_cg):
        """Cmq about the current CG [-/rad] (rate nondimensionalised by d/2V).

        -2 sum_i CN_alpha_i ((x_i - x_cg)/d)^2, as
        :func:`~ironbark_opt.aero.damping.pitch_damping_cmq`, from the
        tabulated sums.
        """
        s0, s1, s2, _, _ = self._sums(mach)
        return -2.0 * (s2 - 2.0 * x_cg * s1 + x_cg * x_cg * s0) / self.reference_length ** 2

    def roll_coefficients(self, mach):
        """(Cl from fin cant [-], Clp [-/rad]) summed over fin sets."""
        _, _, _, forcing, clp = self._sums(mach)
        return forcing, clp


# ----------------------------------------------------------------------------- assembly
def lift_geometry(rocket) -> LiftGeometry:
    """Barrowman inputs from a :class:`~ironbark_opt.rocket.Rocket` (numeric-only)."""
    from ironbark_opt.rocket.body import BodyTube, Transition
    from ironbark_opt.rocket.fins import TrapezoidalFins
    from ironbark_opt.rocket.nose import NoseCone

    aref = rocket.reference_area()
    bodies = []
    plan_area, plan_moment = 0.0, 0.0
    for comp in rocket.body_components():
        if isinstance(comp, NoseCone):
            bodies.append(barrowman.nose_cone(comp.length, comp.radius, aref, volume=comp.volume(),
                                              x_tip=comp.x))
        elif isinstance(comp, Transition):
            bodies.append(barrowman.transition(comp.x, comp.length, comp.fore_radius, comp.aft_radius,
                                               aref, volume=comp.volume()))
        elif not isinstance(comp, BodyTube):
            raise InputError(f"no Barrowman model for component '{comp.name}'", field="component")
        a = comp.planform_area()
        plan_area += a
        plan_moment += a * (comp.x + 0.5 * comp.length)
    fins = []
    for fs in rocket.fin_sets():
        pts = np.asarray(fs.planform_points())
        if isinstance(fs, TrapezoidalFins):
            plan = barrowman.trapezoid_planform(fs.root_chord, fs.tip_chord, fs.span, fs.sweep_length)
        else:
            plan = barrowman.polygon_planform(pts)
        r_body = float(rocket.radius_at(fs.x + 0.5 * float(pts[-1, 0])))   # at mid root chord
        fins.append(FinGeometry(plan, fs.count, fs.x, r_body, fs.cant, fs.section_lift))
    tubes = tuple((t.count, t.x, t.length, t.inner_radius) for t in rocket.tube_fin_sets()
                  if t.inner_radius > 0)
    if not bodies and not fins and not tubes:
        raise InputError("the rocket has no nose, transition or fins: no normal force", field="components")
    return LiftGeometry(tuple(bodies), tuple(fins), plan_area, plan_moment / plan_area if plan_area else 0.0,
                        rocket.fineness(), tubes)


def _own_roughness(component, default: float) -> float:
    """A component's own finish [m] (``roughness``), else ``default`` [m]."""
    own = getattr(component, "roughness", None)
    return default if own is None else float(own)


def friction_components(rocket, roughness: float) -> list[FrictionComponent]:
    """Skin-friction components: the body as one boundary-layer run (Reynolds number
    on the whole length), its wetted area split by surface finish, and each fin set.

    ``roughness`` [m] is the rocket's default finish; a component's own ``roughness``
    replaces it for its wetted area, as OpenRocket evaluates the roughness-limited
    skin friction per component with its finish over the rocket's length (Niskanen
    2013, sec. 3.4.1, eq. 3.79-3.80)."""
    bodies = rocket.body_components()
    length = rocket.length()
    by_finish: dict[float, float] = {}
    for c in bodies:
        k = _own_roughness(c, roughness)
        by_finish[k] = by_finish.get(k, 0.0) + c.wetted_area()
    comps = [FrictionComponent.body("body" if len(by_finish) == 1 else f"body ({k * 1e6:g} um)",
                                    length, 2 * rocket.max_radius(), wetted_area=area,
                                    roughness=k)
             for k, area in sorted(by_finish.items()) if area > 0]
    for fs in rocket.fin_sets():
        comps.append(FrictionComponent.fins(fs.name, fs.wetted_area(), fs.mean_aerodynamic_chord(),
                                            fs.thickness, roughness=_own_roughness(fs, roughness)))
    return comps


def _bore_roughness(roughness: float, tube) -> float:
    """The finish [m] of an open tube's surfaces, kept below half its bore (or length)."""
    return min(roughness, 0.5 * tube.inner_radius if tube.inner_radius > 0 else 0.5 * tube.length)


def guide_drag(rocket, roughness: float = 60e-6) -> tuple[tuple, tuple[str, ...]]:
    """The launch guides' drag increments (:mod:`.protuberance`) of ``rocket`` (a lug's bore
    with the finish ``roughness`` [m]) and the button sizes assumed because the file gave
    none (numeric-only)."""
    from ironbark_opt.aero.protuberance import LaunchLugDrag, RailButtonDrag
    from ironbark_opt.rocket.hardware import LaunchLug, RailButtons
    out, assumed = [], ()
    for c in rocket.components:
        if isinstance(c, RailButtons):
            size, assumed = c.button_size()
            out.append(RailButtonDrag(c.stations(), name=c.name, **size))
        elif isinstance(c, LaunchLug):
            for x in c.fronts:                  # each lug in its own boundary layer
                out.append(LaunchLugDrag(x + 0.5 * c.length, c.length, c.outer_radius, c.inner_radius,
                                         roughness=_bore_roughness(roughness, c), name=c.name))
    return tuple(out), assumed


def tube_fin_drag(rocket, roughness: float = 60e-6) -> tuple:
    """The tube fin sets' drag increments of ``rocket`` (open tubes,
    :class:`~ironbark_opt.aero.protuberance.LaunchLugDrag` with ``count``, their own
    wetted and interstice areas; numeric-only)."""
    from ironbark_opt.aero.protuberance import LaunchLugDrag
    out = []
    for t in rocket.tube_fin_sets():
        out.append(LaunchLugDrag(t.x + 0.5 * t.length, t.length, t.outer_radius, t.inner_radius,
                                 roughness=_bore_roughness(roughness, t), name=t.name,
                                 wetted_area=t.wetted_area_each(),
                                 extra_frontal_area=t.interstice_area_each(), count=t.count))
    return tuple(out)


def build_aero_model(rocket, *, table=None, surface_roughness: float = 60e-6, re_transition: float = 5e5,
                     jet_area: float = 0.0, jet_area_source: str = "", guides: bool = True) -> AeroModel:
    """Assemble the model of ``rocket`` (numeric-only; the result is symbolic-safe).

    The launch guides' drag (:func:`guide_drag`) goes with the skin friction: added
    (at flight conditions) when the table does not include friction, with a warning
    when the rail buttons' size was assumed.

    Parameters
    ----------
    rocket : Rocket
    table : AeroTable or None
        Required for CA (drag curves or a panel/CFD table).
    surface_roughness : float [m]
    re_transition : float [-]
    jet_area : float [m^2]
        Nozzle exit area filling the base while the motor burns.
    jet_area_source : str
        Where ``jet_area`` came from (kept on the model for reports).
    guides : bool
        Add the launch guides' drag (False: without, for comparisons).
    """
    if table is None or not table.has("CA"):
        raise InputError("no axial-force data: give drag curves ([aero] drag_power_off) or an aerodynamic "
                         "table ([aero] table, e.g. from 'ironbark aero build')", field="aero")
    aref = rocket.reference_area()
    dref = 2 * rocket.reference_radius()
    if abs(table.reference_area - aref) > 1e-6 * aref:
        raise InputError(f"table reference area {table.reference_area:.6g} m^2 differs from the rocket's "
                         f"{aref:.6g} m^2", field="aero.table")
    includes = tuple(table.includes)
    r_base = float(rocket.radius_at(rocket.length()))
    jet_area = min(float(jet_area), math.pi * r_base ** 2)     # the jet cannot fill more than the base
    friction = None
    if "friction" not in includes:
        extra, assumed = guide_drag(rocket, surface_roughness) if guides else ((), ())
        extra = extra + tube_fin_drag(rocket, surface_roughness)
        if extra and assumed:
            warnings.warn(f"{rocket.name}: the rail buttons' size is not given; their drag assumes "
                          f"OpenRocket's default button ({', '.join(f'{k} {v * 1e3:g} mm' for k, v in DEFAULT_BUTTON.items() if k in assumed)}"
                          f"); give outer_diameter and height in [[component]] rail_buttons",
                          UserWarning, stacklevel=2)
        friction = FrictionDrag(friction_components(rocket, surface_roughness), aref, re_transition,
                                protuberances=extra)
    base = None
    jet_relief = None
    if "base" not in includes:
        base = BaseDrag(math.pi * r_base ** 2, aref, jet_area)
    elif jet_area > 0 and table.metadata.get("base_jet_area_m2") == 0.0:
        # a panel table's base drag was built without a jet (the motor is not part of the
        # geometry): the exhaust's share of the base is taken off while the motor burns
        jet_relief = BaseDrag(jet_area, aref, model=table.metadata.get("base_drag_model", "mccoy"))
    return AeroModel(aref, dref, float(table.moment_reference_x), lift_geometry(rocket), table,
                     friction, base, includes=includes, jet_relief=jet_relief,
                     jet_area_source=jet_area_source)
