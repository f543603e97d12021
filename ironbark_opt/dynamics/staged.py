"""Serial two-stage flight: the stack to separation, then the sustainer alone.

The event sequence is fixed per configuration (OpenRocket's "ignite the
upper stage at the booster's burnout + delay" and "separate at the upper
stage's ignition / booster burnout + delay"), so every phase is one RK4
``mapaccum`` of one right-hand side and no switch falls inside a step:

1. ``rail``, ``boost``: the whole stack (its dry mass, aero and the
   sustainer's motor carried unlit) through the phases of
   :class:`~ironbark_opt.dynamics.model.FlightModel`, to the booster's burnout
   ``t_b1``;
2. ``stack_coast`` (only when the separation comes after burnout, delay > 0):
   the stack coasting to ``t_s = t_b1 + delay``;
3. separation at ``t_s``: the state passes to the sustainer, whose CG lies
   ``d = x_cg,stack - x_cg,sustainer`` ahead of the stack's on the body axis:
   ``r_s = r + T_LB d e_x``, ``v_s = v + w x d e_x`` (rigid body), same
   attitude and rates;
4. ``sustainer_boost``: the sustainer (its own dry mass, aero and motor, lit
   at ``t_s``) to its burnout, then ``sustainer_coast`` to apogee (the root of
   ``v_z``, refined inside its step as in ``FlightModel.run``).

The sustainer's apogee is the answer.  :meth:`StagedFlightModel.final_state_symbolic`
is the same sequence as one CasADi (MX) graph with the final time an
input, so ballast and sensitivities differentiate it like a single-stage
flight; Monte Carlo loops over samples (:meth:`StagedFlightModel.run_batch`).
"""
from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass

import casadi as ca
import numpy as np

from ironbark_opt import params
from ironbark_opt.dynamics import rhs as rhs_mod
from ironbark_opt.dynamics.frames import rotation_matrix
from ironbark_opt.dynamics.integrator import phase_trajectory, rk4_step
from ironbark_opt.dynamics.model import G0, FlightModel, Steps
from ironbark_opt.dynamics.phased import coast_to_descent
from ironbark_opt.errors import InputError, SolverError


@dataclass(frozen=True)
class StagedSetup:
    """A serial two-stage rocket (plain container; never simulates).

    Parameters
    ----------
    stack : FlightSetup
        Both stages together, booster motor lit, the sustainer's motor unlit.
    sustainer : FlightSetup
        The upper stage alone; its motor a
        :class:`~ironbark_opt.motors.composite.DelayedMotor` lit at separation.
    separation_delay : float [s]
        Separation (and sustainer ignition) after the booster's burnout.
    booster_name, sustainer_name : str
    booster : FlightSetup or None
        The booster alone after separation (spent motor aboard), positions
        from its own front end; flown to its landing point when given.
    booster_x : float [m]
        The booster's front end aft of the stack's nose tip.
    booster_burnout : float [s] or None
        Parallel boosters: their motors' burnout (unscaled), where the stack's
        boost ends (the stack's own motor, the core's, burns on); None: the
        stack motor's burnout.
    parallel : bool
        Parallel boosters (:mod:`ironbark_opt.openrocket.parallel`): the core is the
        "sustainer", lit at launch, and the stack keeps its thrust between the
        boosters' burnout and the separation.
    """

    stack: object
    sustainer: object
    separation_delay: float = 0.0
    booster_name: str = "booster"
    sustainer_name: str = "sustainer"
    booster: object = None
    booster_x: float = 0.0
    booster_burnout: float | None = None
    parallel: bool = False
    #: Cd x area [m^2] of the booster tumbling (:func:`ironbark_opt.aero.tumble.tumble_cd_area`),
    #: flown when it is statically unstable at separation; None: never tumbles.
    booster_tumble_cd_area: float | None = None
    #: Launch environment shared by every vehicle: given (e.g. through
    #: ``dataclasses.replace(staged, atmosphere=..., site_elevation=..., latitude=...)``,
    #: as the CLI does for a forecast), they replace the vehicles' own.
    atmosphere: object = None
    site_elevation: float | None = None
    latitude: float | None = None
    longitude: float | None = None

    def __post_init__(self):
        env = {k: getattr(self, k) for k in ("atmosphere", "site_elevation", "latitude", "longitude")
               if getattr(self, k) is not None}
        if env:
            for key in ("stack", "sustainer", "booster"):
                vehicle = getattr(self, key)
                if vehicle is not None:
                    object.__setattr__(self, key, dataclasses.replace(vehicle, **env))
        for k in ("atmosphere", "site_elevation", "latitude", "longitude"):
            object.__setattr__(self, k, getattr(self.stack, k))

    # What simulate() and the summary read from a setup:
    name = property(lambda self: self.sustainer.name)
    aero = property(lambda self: self.sustainer.aero)
    motor = property(lambda self: self.sustainer.motor)
    source = property(lambda self: self.stack.source)
    dry = property(lambda self: self.sustainer.dry)               # the ballast sits in the sustainer
    ballast_mass_max = property(lambda self: self.sustainer.ballast_mass_max)
    ballast_x_range = property(lambda self: self.sustainer.ballast_x_range)
    airbrakes = None
    body_length = property(lambda self: self.stack.body_length)   # the whole stack on the pad
    nominal = property(lambda self: self.stack.nominal)
    parachutes = property(lambda self: self.sustainer.parachutes)  # the answer is the sustainer's flight

    def nominal_parameters(self, **overrides) -> np.ndarray:
        return self.stack.nominal_parameters(**overrides)

    @property
    def stack_burnout(self) -> float:
        """End of the stack's boost [s, unscaled]: the lower stage's or the boosters' burnout."""
        return float(self.booster_burnout if self.booster_burnout is not None else self.stack.motor.burn_time)

    def __getattr__(self, name):
        return _not_for_staged(name)


def _not_for_staged(name):
    """The one refusal of what staged rockets do not have yet (``__getattr__`` of both classes)."""
    if name.startswith("__"):
        raise AttributeError(name)
    raise InputError(f"'{name}' is not available for staged rockets yet (they fly simulate, ballast, "
                     "sensitivity and montecarlo to the sustainer's apogee; no descent, JIT or cluster)",
                     field="stages")


class StagedFlightModel:
    """Compiled-once functions of a :class:`StagedSetup` (numeric runs)."""

    #: length of the parameter vector ``p`` (as :attr:`FlightModel.n_p`)
    n_p = params.SIZE

    def __init__(self, setup: StagedSetup, steps: Steps | None = None, *, jit: bool = False):
        self.setup = setup
        self.steps = steps or Steps()
        self.jit = jit
        self.stack = FlightModel(setup.stack, self.steps, jit=jit)
        sus = setup.sustainer
        self.rhs = {"rail": self.stack.rhs["rail"], "boost": self.stack.rhs["boost"],
                    # parallel boosters: the core burns on between their burnout and separation
                    "stack_coast": self.stack.rhs["boost" if setup.parallel else "coast"],
                    "sustainer_boost": rhs_mod.build(sus, "boost"), "coast": rhs_mod.build(sus, "coast")}
        self._step = {k: rk4_step(self.rhs[k], f"step_{k}") for k in ("sustainer_boost", "coast", "stack_coast")}
        b2 = float(sus.motor.motor.burn_time)
        self.n_sboost = max(20, int(math.ceil(b2 / self.steps.dt_boost)))
        self.n_scoast = max(self.steps.n_coast, 400)
        self.n_stack_coast = max(4, int(math.ceil(setup.separation_delay / self.steps.dt_boost)))
        self.vz_l = self.stack.vz_l
        xs, ts, ps = ca.SX.sym("x", 13), ca.SX.sym("t"), ca.SX.sym("p", params.SIZE)
        i_cg = rhs_mod.OUTPUT_NAMES.index("cg_x_m")
        d = self.rhs["stack_coast"](xs, ts, ps)[1][i_cg] - self.rhs["coast"](xs, ts, ps)[1][i_cg]
        e = ca.vertcat(d, 0, 0)
        self.separate = ca.Function("separate", [xs, ts, ps], [ca.vertcat(
            xs[0:3] + rotation_matrix(xs[6:10]) @ e, xs[3:6] + ca.cross(xs[10:13], e), xs[6:13])])
        self._traj = {"stack_coast": phase_trajectory(self._step["stack_coast"], self.n_stack_coast, "traj_stc")}
        self._set_sustainer_steps("sustainer_boost", self.n_sboost)
        self._set_sustainer_steps("coast", self.n_scoast)
        self._choose_sustainer_grid(setup.nominal_parameters())

    def _choose_sustainer_grid(self, p) -> None:
        """The sustainer's RK4 steps from the *nominal* flight, by the stability rule of
        the single-stage grid (:mod:`ironbark_opt.dynamics.grid`: |lambda| dt within
        ``STABLE_LAMBDA_DT`` at the stiffest states, the boost's steps doubled while a
        provisional boost blows up).  Fixed once, so every later run, batch and the
        symbolic flight share it.  Before (fixed 0.02 s boost steps and 400 coast steps
        over the coast), a light sustainer whose pitch mode is stiffer than that (2.3 kg,
        85 mm, Mach 1.4 at burnout: 6 coast steps to Mach 412) diverged and was refused."""
        from ironbark_opt.dynamics.grid import doubled_until_finite
        sep = self._to_separation(p)
        x_sep, _ = self._separate(sep["x"], sep["t_s"], p)
        t_s = sep["t_s"]
        t_b2 = float(self.setup.sustainer.motor.burn_time) * float(p[params.index("burn_time_scale")])
        stable = lambda phase, x, t: self.stack.stable_step(self.rhs[phase], x, t, p)
        x_b = doubled_until_finite(lambda: self._traj["sustainer_boost"](x_sep, t_s, t_b2, p),
                                   lambda: self.n_sboost,
                                   lambda n: self._set_sustainer_steps("sustainer_boost", n))
        dt = min(stable("sustainer_boost", x_sep, t_s), stable("sustainer_boost", x_b, t_b2))
        if (t_b2 - t_s) / self.n_sboost > dt:
            self._set_sustainer_steps("sustainer_boost", int(math.ceil((t_b2 - t_s) / dt)))
            x_b = np.array(self._traj["sustainer_boost"](x_sep, t_s, t_b2, p))[:, -1]
        vz_b = float(self.stack.vz_l(x_b))
        if vz_b > 0:                    # else run() says the sustainer never climbs
            span = vz_b / G0 + 2.0                               # run()'s first coast horizon
            n = int(math.ceil(span / stable("coast", x_b, t_b2)))
            if n > self.n_scoast:
                self._set_sustainer_steps("coast", 25 * int(math.ceil(n / 25)))

    def _set_sustainer_steps(self, phase: str, n: int) -> None:
        """``n`` RK4 steps for the sustainer's ``phase`` ("sustainer_boost" or "coast")."""
        setattr(self, "n_scoast" if phase == "coast" else "n_sboost", int(n))
        self._traj[phase] = phase_trajectory(self._step[phase], int(n),
                                             "traj_sc" if phase == "coast" else "traj_sb")

    def __getattr__(self, name):
        # anything of FlightSetup / FlightModel not built for staged rockets (ballast, AD, batches)
        return _not_for_staged(name)

    # ------------------------------------------------------------------ descents
    def _down_functions(self, key: str) -> dict:
        """Coast and parachute trajectories of the booster or the sustainer alone."""
        cache = self.__dict__.setdefault("_down_cache", {})
        if key not in cache:
            setup = self.setup.booster if key == "booster" else self.setup.sustainer
            chutes = setup.parachutes
            cd = sum(c.cd_area for c in chutes if c.deploy_altitude is None)
            stages = [(None, cd)]
            for alt in sorted({c.deploy_altitude for c in chutes if c.deploy_altitude is not None}, reverse=True):
                cd += sum(c.cd_area for c in chutes if c.deploy_altitude == alt)
                stages.append((alt, cd))
            fns = {"stages": stages, "coast_rhs": self.rhs["coast"] if key == "sustainer" else rhs_mod.build(setup, "coast")}
            fns["coast"] = phase_trajectory(rk4_step(fns["coast_rhs"], f"step_{key}_c"), 100, f"traj_{key}_c")
            for i, (_, cd_area) in enumerate(stages):
                if cd_area > 0:
                    fns[i] = phase_trajectory(rk4_step(rhs_mod.build(setup, "descent", cd_area=cd_area),
                                                       f"step_{key}_d{i}"), 100, f"traj_{key}_d{i}")
            tumble = self.setup.booster_tumble_cd_area if key == "booster" else None
            if tumble:
                # a statically unstable booster tumbles: a point mass with the tumbling drag
                # (OpenRocket's BasicTumbleStepper; Niskanen 2013 sec. 3.5), chutes adding theirs
                fns["tumble_stages"] = [(a, cd + tumble) for a, cd in stages]
                for i, (_, cd_area) in enumerate(fns["tumble_stages"]):
                    fns[f"t{i}"] = phase_trajectory(rk4_step(rhs_mod.build(setup, "descent", cd_area=cd_area),
                                                             f"step_{key}_t{i}"), 100, f"traj_{key}_t{i}")
            cache[key] = fns
        return cache[key]

    def _fly_down(self, key: str, x, t, p, *, to_apogee: bool) -> dict:
        """Numeric flight of one vehicle to the ground: (optionally) 6-DOF coast to its
        apogee (0.01 s steps), then point mass under the chutes open at apogee and
        those opening at their altitude on the way down (0.05 s steps; ballistic 6-DOF,
        0.02 s, without a chute).  Events at the first sample past them; the landing
        interpolated linearly between samples."""
        fn = self._down_functions(key)
        tumbling = self.tumbling(key, x, t, p)
        stages, out = fn["tumble_stages" if tumbling else "stages"], {"tumbling": tumbling}
        for k in range(0 if to_apogee else 1, len(stages) + 1):
            if k == 0:
                traj, dt = (fn["t0"], 0.05) if tumbling else (fn["coast"], 0.01)
                done = (lambda X: np.array(self.stack.vz_l.map(X.shape[1])(X)).ravel() <= 0)
            else:
                alt_end = stages[k][0] if k < len(stages) else 0.0
                traj, dt = (fn["coast"], 0.02) if stages[k - 1][1] <= 0 else \
                    (fn[f"t{k - 1}" if tumbling else k - 1], 0.05)
                done = (lambda X, a=alt_end: X[2] <= a)
            for _ in range(3000):
                X = np.array(traj(x, t, t + 100 * dt, p))
                hit = np.nonzero(done(X))[0]
                if hit.size:
                    j = int(hit[0])
                    prev = x if j == 0 else X[:, j - 1]
                    if k == len(stages):
                        f = prev[2] / (prev[2] - X[2, j]) if prev[2] != X[2, j] else 1.0
                        out.update(t_landing=float(t + (j + f) * dt), x_landing=prev + f * (X[:, j] - prev))
                    x, t = X[:, j], t + (j + 1) * dt
                    if k == 0:
                        out.update(apogee_agl=float(max(prev[2], x[2])), t_apogee=float(t))
                    break
                x, t = X[:, -1], t + 100 * dt
            else:
                raise SolverError(f"the {key} did not reach the ground within the time limit")
        return out

    def tumbling(self, key: str, x, t, p) -> bool:
        """Does ``key``'s vehicle tumble from state ``x`` at ``t``: the booster with a
        tumbling drag given and its static margin at that state negative."""
        fn = self._down_functions(key)
        if "tumble_stages" not in fn:
            return False
        i = rhs_mod.OUTPUT_NAMES.index("static_margin_cal")
        return float(np.array(fn["coast_rhs"](x, t, p)[1]).ravel()[i]) < 0.0

    def fly_booster(self, x_stack, t_s, p) -> dict:
        """The booster from separation (its CG placed from the stack's by the rigid
        body's geometry) to its apogee and the ground (:meth:`_fly_down`).

        Returns dict ``booster_apogee_agl_m``, ``booster_apogee_time_s``,
        ``booster_landing_time_s``, ``booster_landing_east_m``, ``booster_landing_north_m``.
        """
        fn = self._down_functions("booster")
        i_cg = rhs_mod.OUTPUT_NAMES.index("cg_x_m")
        cg_stack = float(np.array(self.rhs["stack_coast"](x_stack, t_s, p)[1]).ravel()[i_cg])
        cg_b = float(np.array(fn["coast_rhs"](x_stack, t_s, p)[1]).ravel()[i_cg]) + self.setup.booster_x
        e = np.array([-(cg_b - cg_stack), 0.0, 0.0])          # booster CG from the stack's, body axes
        x = x_stack.copy()
        x[0:3] = x_stack[0:3] + np.array(rotation_matrix(x_stack[6:10])) @ e
        x[3:6] = x_stack[3:6] + np.cross(x_stack[10:13], e)
        d = self._fly_down("booster", x, t_s, p, to_apogee=True)
        xl = d["x_landing"]
        return dict(booster_apogee_agl_m=d["apogee_agl"], booster_apogee_time_s=d["t_apogee"],
                    booster_landing_time_s=d["t_landing"], booster_landing_east_m=float(xl[0]),
                    booster_landing_north_m=float(xl[1]),
                    # tumbling drag flown (0: it flew stable, 6-DOF)
                    booster_tumble_cd_area_m2=float(self.setup.booster_tumble_cd_area) if d["tumbling"] else 0.0)

    def final_state_symbolic(self, p, T, t_rail_guess: float):
        """MX state of the sustainer at time ``T`` [s] in its coast, through every
        phase (rail exit by the stack's rootfinder); what ballast and
        sensitivities differentiate.  Returns ``(x_T, t_rail, x_rail, X_boost)``."""
        st = self.stack
        P = params.unpack(p)
        s = P["burn_time_scale"]
        t_r = st.rail_exit_root(t_rail_guess, p)
        x_r = st.trajectory["rail"](st.initial_state(p), 0, t_r, p)[:, -1]
        t_b1 = self.setup.stack_burnout * s
        X_b = st.trajectory["boost"](x_r, t_r, t_b1, p)
        x, t_s = X_b[:, -1], t_b1
        if self.setup.separation_delay > 0:
            t_s = t_b1 + self.setup.separation_delay * s
            x = self._traj["stack_coast"](x, t_b1, t_s, p)[:, -1]
        x = self.separate(x, t_s, p)
        t_b2 = float(self.setup.sustainer.motor.burn_time) * s
        x = self._traj["sustainer_boost"](x, t_s, t_b2, p)[:, -1]
        return self._traj["coast"](x, t_b2, T, p)[:, -1], t_r, x_r, X_b

    def run_batch(self, P, *, descent: bool = False) -> dict:
        """:meth:`run` for each column of ``P`` (params.SIZE x n): the Monte Carlo path
        (a loop: staged rockets are not mapped over samples yet)."""
        P = np.asarray(P, dtype=float)
        runs = [self.run(P[:, i], descent=descent) for i in range(P.shape[1])]
        x_a = np.column_stack([r["x_apogee"] for r in runs])
        return dict(apogee_agl=x_a[2], t_apogee=np.array([r["t_apogee"] for r in runs]),
                    t_rail=np.array([r["t_rail"] for r in runs]),
                    rail_exit_speed=np.array([np.linalg.norm(r["x_rail"][3:6]) for r in runs]),
                    t_burnout=np.array([r["t_burnout"] for r in runs]), x_apogee=x_a,
                    **({} if not descent else dict(t_landing=np.array([r["t_landing"] for r in runs]),
                                                   x_landing=np.column_stack([r["x_landing"] for r in runs]))))

    def _separate(self, x, t, p):
        """Stack state -> sustainer state at separation (rigid-body CG shift)."""
        return np.array(self.separate(x, t, p)).ravel(), None

    def _to_separation(self, p) -> dict:
        """The stack from the pad to separation: rail, boost and (with a delay) its
        coast; the stack's state ``x`` at ``t_s`` and the samples for the time series."""
        st = self.stack
        p = np.asarray(p, dtype=float).ravel()
        s = p[params.index("burn_time_scale")]
        x0 = st._x0(p)
        t_r = st.rail_exit(p)
        t_b1 = self.setup.stack_burnout * s
        X_rail = np.array(st._run["rail"](x0, 0.0, t_r, p))
        X_boost = np.array(st._run["boost"](X_rail[:, -1], t_r, t_b1, p))
        parts_t = [np.array([0.0]), np.linspace(0, t_r, X_rail.shape[1] + 1)[1:],
                   st.boost_times(t_r, t_b1, p)]
        parts_x = [x0[:, None], X_rail, X_boost]
        phases = ["rail"] * (X_rail.shape[1] + 1) + ["boost"] * X_boost.shape[1]
        x, t_s = X_boost[:, -1], t_b1
        if self.setup.separation_delay > 0:
            t_s = t_b1 + self.setup.separation_delay * s
            X = np.array(self._traj["stack_coast"](x, t_b1, t_s, p))
            parts_t.append(t_b1 + (t_s - t_b1) * np.arange(1, X.shape[1] + 1) / X.shape[1])
            parts_x.append(X)
            phases += ["stack_coast"] * X.shape[1]
            x = X[:, -1]
        return dict(parts_t=parts_t, parts_x=parts_x, phases=phases, x=x, t_s=t_s, t_r=t_r, t_b1=t_b1,
                    X_rail=X_rail)

    def run(self, p, *, descent: bool = False) -> dict:
        """Fly to the sustainer's apogee (see the module docstring).

        Returns
        -------
        dict as :meth:`FlightModel.run` (``t_burnout``: the sustainer's burnout; with
        ``descent`` the sustainer's ``t_landing`` and ``x_landing``, the time series
        ending at apogee)
        plus ``t_separation`` [s], ``x_separation`` (13,), ``t_booster_burnout`` [s]
        and ``booster`` (:meth:`fly_booster`, when the setup has the booster).
        """
        st = self.stack
        p = np.asarray(p, dtype=float).ravel()
        s = p[params.index("burn_time_scale")]
        sep = self._to_separation(p)
        parts_t, parts_x, phases = sep["parts_t"], sep["parts_x"], sep["phases"]
        x, t_s, t_r, t_b1, X_rail = sep["x"], sep["t_s"], sep["t_r"], sep["t_b1"], sep["X_rail"]
        x_sep, _ = self._separate(x, t_s, p)
        t_b2 = float(self.setup.sustainer.motor.burn_time) * s
        X_sb = np.array(self._traj["sustainer_boost"](x_sep, t_s, t_b2, p))
        parts_t.append(t_s + (t_b2 - t_s) * np.arange(1, X_sb.shape[1] + 1) / X_sb.shape[1])
        parts_x.append(X_sb)
        phases += ["sustainer_boost"] * X_sb.shape[1]
        x_b = X_sb[:, -1]
        vz_b = float(st.vz_l(x_b))
        if vz_b <= 0:
            raise SolverError("the sustainer's vertical velocity at burnout is not positive")

        def fly(t_end):
            X = np.array(self._traj["coast"](x_b, t_b2, t_end, p))
            return X, np.array(st.vz_l.map(X.shape[1])(X)).ravel()

        X_c, vz, k, t_end = coast_to_descent(fly, t_b2, t_b2 + vz_b / G0 + 2.0, "the sustainer's apogee is")
        dt = (t_end - t_b2) / self.n_scoast
        x_k = x_b if k == 0 else X_c[:, k - 1]
        vz_k = vz_b if k == 0 else vz[k - 1]
        t_k = t_b2 + k * dt
        h = dt * vz_k / (vz_k - vz[k]) if vz_k != vz[k] else dt
        step = self._step["coast"]
        for _ in range(8):                    # secant on the step length (as FlightModel.refine_in_step)
            a = float(st.vz_l(step(x_k, t_k, h, p)))
            b = float(st.vz_l(step(x_k, t_k, h * (1 + 1e-6) + 1e-9, p)))
            der = (b - a) / (h * 1e-6 + 1e-9)
            if der == 0 or abs(a) < 1e-10:
                break
            h = float(np.clip(h - a / der, 0.0, dt))
        x_a = np.array(step(x_k, t_k, h, p)).ravel()
        t_a = t_k + h
        parts_t += [t_b2 + dt * np.arange(1, k + 1), np.array([t_a])]
        parts_x += [X_c[:, :k], x_a[:, None]]
        phases += ["coast"] * (k + 1)
        out = {} if not descent else self._fly_down("sustainer", x_a, t_a, p, to_apogee=False)
        return dict(t=np.concatenate(parts_t), x=np.hstack(parts_x), phase=np.array(phases), p=p, **out,
                    t_rail=t_r, t_burnout=t_b2, t_apogee=t_a, x_rail=X_rail[:, -1].copy(), x_burnout=x_b,
                    x_apogee=x_a, t_separation=t_s, x_separation=x_sep, t_booster_burnout=t_b1,
                    booster=self.fly_booster(x, t_s, p) if self.setup.booster is not None else {})

    def outputs(self, t, x, phase, p) -> np.ndarray:
        """Derived quantities (rows of ``rhs.OUTPUT_NAMES``), each phase by its own vehicle."""
        y = np.zeros((len(rhs_mod.OUTPUT_NAMES), t.size))
        for ph in np.unique(phase):
            idx = np.nonzero(phase == ph)[0]
            fm = self.rhs[ph].map(idx.size)
            y[:, idx] = np.array(fm(x[:, idx], t[idx][None, :], np.repeat(p[:, None], idx.size, axis=1))[1])
        return y
