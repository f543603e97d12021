"""The phased flight model: rail -> boost -> coast (-> descent).

Phase boundaries are events found exactly, never an ``if`` inside a step:

- **rail exit** ``t_r``: root of ``s(t_r) - (L_rail - offset) = 0`` where
  ``s`` is the distance travelled along the rail, the rail phase integrated
  with ``n_rail`` RK4 steps over ``[0, t_r]`` (CasADi ``rootfinder``);
- **burnout** ``t_b = burn_time * burn_time_scale`` (the thrust curve's end);
- **apogee** ``t_a``: root of the vertical velocity ``v_z(t_a) = 0``, found
  inside the RK4 step where it changes sign by Newton on the step length
  (an exact root of the same RK4 discretisation).

:class:`FlightModel` builds the CasADi Functions once per setup and runs
them numerically; the symbolic pieces (``rhs``, ``step``, ``trajectory``)
are public so sensitivities, Monte Carlo and the optimiser use the very same
expressions.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import casadi as ca
import numpy as np

from ironbark_opt import params
from ironbark_opt.dynamics import rhs as rhs_mod
from ironbark_opt.dynamics.frames import launch_quaternion, rail_direction_l, rotation_matrix
from ironbark_opt.dynamics.integrator import compile_function, phase_trajectory, rk4_step
from ironbark_opt.errors import InputError, SolverError

G0 = 9.80665  # [m/s^2] standard gravity, only for first guesses


@dataclass(frozen=True)
class Steps:
    """Discretisation of the phases.

    Parameters
    ----------
    n_rail : int
        RK4 steps on the rail.
    dt_boost : float [s]
        Target step during the burn (pitch oscillation near max q needs
        <= ~0.02 s for sub-metre apogee accuracy).
    n_coast : int
        RK4 steps from burnout to the apogee bracket.
    dt_descent : float [s]
        Step under parachute (and ballistic descent).
    """

    n_rail: int = 40
    dt_boost: float = 0.01
    n_coast: int = 600
    dt_descent: float = 0.1


class FlightModel:
    """Compiled-once functions of one :class:`FlightSetup`.

    Parameters
    ----------
    setup : FlightSetup
    steps : Steps, optional
    jit : bool
        Compile the trajectory Functions to C (cached on disk); falls back
        to the VM when no C compiler is available.
    """

    def __init__(self, setup, steps: Steps | None = None, *, jit: bool = False):
        self.setup = setup
        self.steps = steps or Steps()
        self.jit = jit
        burn = float(setup.motor.burn_time) * float(setup.nominal.get("burn_time_scale", 1.0))
        self.n_boost = max(20, int(math.ceil(burn / self.steps.dt_boost)))
        self.rhs = {ph: rhs_mod.build(setup, ph) for ph in ("rail", "boost", "coast")}
        self.step = {ph: rk4_step(f, f"step_{ph}") for ph, f in self.rhs.items()}
        n = {"rail": self.steps.n_rail, "boost": self.n_boost, "coast": self.steps.n_coast}
        self.trajectory = {ph: phase_trajectory(self.step[ph], n[ph], f"traj_{ph}") for ph in n}
        self._run = dict(self.trajectory)
        if jit:
            self._run = {ph: compile_function(f) for ph, f in self.trajectory.items()}
        self._build_events()

    # ------------------------------------------------------------------ symbolic
    def initial_state(self, p):
        """State at t = 0: at rest at the rail foot, body axis along the rail."""
        P = params.unpack(p)
        q0 = launch_quaternion(P["inclination"], P["heading"])
        return ca.vertcat(0, 0, 0, 0, 0, 0, q0, 0, 0, 0)

    def rail_residual(self, t_r, p):
        """Distance along the rail minus the distance to leave it [m] (MX)."""
        P = params.unpack(p)
        x = self.trajectory["rail"](self.initial_state(p), 0, t_r, p)[:, -1]
        travel = ca.dot(x[0:3], rail_direction_l(P["inclination"], P["heading"]))
        return travel - (P["rail_length"] - self.setup.rail_exit_offset)

    def _build_events(self):
        t_r = ca.MX.sym("t_r")
        p = ca.MX.sym("p", params.SIZE)
        g = ca.Function("rail_residual", [t_r, p], [self.rail_residual(t_r, p)])
        self.rail_exit_root = ca.rootfinder("rail_exit", "newton", g,
                                            {"abstol": 1e-10, "max_iter": 50, "error_on_fail": True})
        x = ca.SX.sym("x", 13)
        self.vz_l = ca.Function("vz_l", [x], [(rotation_matrix(x[6:10]) @ x[3:6])[2]])
        h = ca.SX.sym("h")
        t = ca.SX.sym("t")
        ps = ca.SX.sym("p", params.SIZE)
        vz = self.vz_l(self.step["coast"](x, t, h, ps))
        self._apex = ca.Function("apex", [x, t, h, ps], [vz, ca.jacobian(vz, h)])

    # ------------------------------------------------------------------ numeric
    def rail_exit(self, p: np.ndarray) -> float:
        """Rail-exit time [s] for numeric ``p`` (bracket by a scan, then Newton)."""
        burn = float(self.setup.motor.burn_time) * float(p[params.index("burn_time_scale")])
        t_scan = min(1.0, burn)
        x0 = self.initial_state(p)
        while True:
            g_end = float(self.rail_residual(t_scan, ca.DM(p)))
            if g_end > 0:
                break
            if t_scan >= burn:
                raise InputError("the rocket does not leave the rail before motor burnout: check thrust, "
                                 "mass and rail length", field="rail_length")
            t_scan = min(2 * t_scan, burn)
        X = np.array(self._run["rail"](x0, 0, t_scan, p))
        e = np.array(rail_direction_l(p[params.index("inclination")], p[params.index("heading")])).ravel()
        travel = e @ X[0:3, :] - (p[params.index("rail_length")] - self.setup.rail_exit_offset)
        k = int(np.argmax(travel > 0))
        dt = t_scan / X.shape[1]
        guess = (k + 1) * dt
        try:
            return float(self.rail_exit_root(guess, p))
        except RuntimeError as err:
            raise SolverError(f"rail-exit time not found near t = {guess:.3f} s: {err}") from None

    def run(self, p, *, descent: bool = False) -> dict:
        """Fly numerically to apogee (optionally to landing).

        Parameters
        ----------
        p : array (params.SIZE) [mixed SI]
        descent : bool
            Continue past apogee to the ground (parachutes from the setup,
            ballistic if it has none).

        Returns
        -------
        dict with ``t`` [s] (n,), ``x`` (13, n), ``phase`` (n,) labels and the
        event times ``t_rail``, ``t_burnout``, ``t_apogee`` [s] and states.
        """
        p = np.asarray(p, dtype=float).ravel()
        if p.size != params.SIZE:
            raise InputError(f"parameter vector has {p.size} entries, expected {params.SIZE}")
        x0 = np.array(self.initial_state(p)).ravel()
        t_r = self.rail_exit(p)
        t_b = float(self.setup.motor.burn_time) * p[params.index("burn_time_scale")]
        if t_r >= t_b:
            raise InputError(f"motor burns out ({t_b:.2f} s) before rail exit ({t_r:.2f} s)",
                             field="motor")
        X_rail = np.array(self._run["rail"](x0, 0.0, t_r, p))
        x_r = X_rail[:, -1].copy()
        X_boost = np.array(self._run["boost"](x_r, t_r, t_b, p))
        x_b = X_boost[:, -1]
        vz_b = float(self.vz_l(x_b))
        if vz_b <= 0:
            raise SolverError("vertical velocity at burnout is not positive: the rocket never climbs")
        t_end = t_b + 1.2 * vz_b / G0 + 2.0
        X_coast = np.array(self._run["coast"](x_b, t_b, t_end, p))
        vz = np.array(self.vz_l.map(X_coast.shape[1])(X_coast)).ravel()
        below = np.nonzero(vz <= 0)[0]
        if below.size == 0:
            raise SolverError("apogee not reached within the coast horizon")
        k = int(below[0])
        dt_c = (t_end - t_b) / self.steps.n_coast
        x_k = x_b if k == 0 else X_coast[:, k - 1]
        t_k = t_b + k * dt_c
        h = self._newton_in_step(self._apex, x_k, t_k, dt_c, p, vz_k=float(self.vz_l(x_k)))
        x_a = np.array(self.step["coast"](x_k, t_k, h, p)).ravel()
        t_a = t_k + h
        n_r, n_b = X_rail.shape[1], X_boost.shape[1]
        t = np.concatenate([[0.0], np.linspace(0, t_r, n_r + 1)[1:], t_r + (t_b - t_r) * np.arange(1, n_b + 1) / n_b,
                            t_b + dt_c * np.arange(1, k + 1), [t_a]])
        x = np.hstack([x0[:, None], X_rail, X_boost, X_coast[:, :k], x_a[:, None]])
        phase = np.array(["rail"] * (n_r + 1) + ["boost"] * n_b + ["coast"] * (k + 1))
        out = dict(t=t, x=x, phase=phase, p=p, t_rail=t_r, t_burnout=t_b, t_apogee=t_a,
                   x_rail=x_r, x_burnout=x_b, x_apogee=x_a)
        if descent:
            out.update(self._descend(t_a, x_a, p, t, x, phase))
        return out

    @staticmethod
    def _newton_in_step(func, x_k, t_k, dt, p, vz_k):
        """Root h in [0, dt] of func(x_k, t_k, h, p)[0] (Newton, safeguarded)."""
        v_end = float(func(x_k, t_k, dt, p)[0])
        h = dt * vz_k / (vz_k - v_end) if vz_k != v_end else dt
        for _ in range(20):
            val, der = func(x_k, t_k, h, p)
            val, der = float(val), float(der)
            if der == 0:
                break
            h_new = min(max(h - val / der, 0.0), dt)
            if abs(h_new - h) < 1e-12:
                h = h_new
                break
            h = h_new
        return h

    def _descend(self, t_a, x_a, p, t, x, phase):
        """Integrate from apogee to the ground (parachutes or ballistic)."""
        chutes = self.setup.parachutes
        cd_area = sum(c.cd_area for c in chutes)
        if cd_area > 0:
            f = rhs_mod.build(self.setup, "descent", cd_area=cd_area)
            step = rk4_step(f, "step_descent")
            label = "descent"
        else:
            step = self.step["coast"]
            label = "ballistic"
        dt = self.steps.dt_descent if cd_area > 0 else 0.02
        chunk = phase_trajectory(step, 200, "traj_descent")
        xs, ts = [], []
        x_cur, t_cur = x_a, t_a
        for _ in range(200):
            X = np.array(chunk(x_cur, t_cur, t_cur + 200 * dt, p))
            below = np.nonzero(X[2, :] <= 0)[0]
            if below.size:
                k = int(below[0])
                x_k = x_cur if k == 0 else X[:, k - 1]
                t_k = t_cur + k * dt
                xs.append(X[:, :k])
                ts.append(t_cur + dt * np.arange(1, k + 1))
                hx, tt, pp, hh = ca.SX.sym("x", 13), ca.SX.sym("t"), ca.SX.sym("p", params.SIZE), ca.SX.sym("h")
                z = step(hx, tt, hh, pp)[2]
                g = ca.Function("ground", [hx, tt, hh, pp], [z, ca.jacobian(z, hh)])
                h = self._newton_in_step(g, x_k, t_k, dt, p, vz_k=float(x_k[2]))
                x_l = np.array(step(x_k, t_k, h, p)).ravel()
                xs.append(x_l[:, None])
                ts.append([t_k + h])
                break
            xs.append(X)
            ts.append(t_cur + dt * np.arange(1, 201))
            x_cur, t_cur = X[:, -1], t_cur + 200 * dt
        else:
            raise SolverError("descent did not reach the ground within the time limit")
        x_d = np.hstack(xs)
        t_d = np.concatenate([np.asarray(v, dtype=float) for v in ts])
        return dict(t=np.concatenate([t, t_d]), x=np.hstack([x, x_d]),
                    phase=np.concatenate([phase, [label] * t_d.size]),
                    t_landing=float(t_d[-1]), x_landing=x_d[:, -1])

    def outputs(self, t, x, phase, p) -> np.ndarray:
        """Derived quantities (rows of ``rhs.OUTPUT_NAMES``) at the samples."""
        y = np.zeros((len(rhs_mod.OUTPUT_NAMES), t.size))
        for ph in np.unique(phase):
            idx = np.nonzero(phase == ph)[0]
            key = {"ballistic": "coast"}.get(ph, ph)
            if key == "descent":
                f = rhs_mod.build(self.setup, "descent", cd_area=sum(c.cd_area for c in self.setup.parachutes))
            else:
                f = self.rhs[key]
            fm = f.map(idx.size)
            y[:, idx] = np.array(fm(x[:, idx], t[idx][None, :], np.repeat(p[:, None], idx.size, axis=1))[1])
        return y


def _final_state(model: FlightModel, p, T, t_rail_guess: float):
    """Symbolic (MX) state at time ``T`` in the coast, through all phases."""
    P = params.unpack(p)
    t_r = model.rail_exit_root(t_rail_guess, p)
    x_r = model.trajectory["rail"](model.initial_state(p), 0, t_r, p)[:, -1]
    t_b = float(model.setup.motor.burn_time) * P["burn_time_scale"]
    x_b = model.trajectory["boost"](x_r, t_r, t_b, p)[:, -1]
    x_t = model.trajectory["coast"](x_b, t_b, T, p)[:, -1]
    return x_t, t_r, x_r


def apogee_functions(model: FlightModel, p_nominal) -> dict:
    """Differentiable CasADi Functions of ``p`` around a nominal flight.

    Returns a dict of MX Functions:

    - ``final_state(p, T) -> (x_T, t_rail, x_rail)``: the phased trajectory
      with the final time ``T`` [s] as an input (rail exit by rootfinder);
    - ``apogee(p) -> (z_apogee [m AGL], t_apogee [s], rail_exit_speed [m/s])``
      with ``t_apogee`` the root of ``v_z(T) = 0`` (rootfinder, so AD gives
      the implicit-function derivatives).

    The rootfinders start from the nominal flight's event times, so they are
    valid for ``p`` in a neighbourhood of ``p_nominal`` (a dispersion or an
    optimisation, not an arbitrary different rocket).
    """
    run = model.run(p_nominal)
    t_rail0, t_apogee0 = run["t_rail"], run["t_apogee"]
    p = ca.MX.sym("p", params.SIZE)
    T = ca.MX.sym("T")
    x_t, t_r, x_r = _final_state(model, p, T, t_rail0)
    final = ca.Function("final_state", [p, T], [x_t, t_r, x_r], ["p", "T"], ["x_T", "t_rail", "x_rail"])
    vz = ca.Function("vz_T", [T, p], [model.vz_l(x_t)])
    t_apo = ca.rootfinder("apogee_time", "newton", vz, {"abstol": 1e-9, "max_iter": 30, "error_on_fail": True})(t_apogee0, p)
    x_a, t_r2, x_r2 = final(p, t_apo)
    apogee = ca.Function("apogee", [p], [x_a[2], t_apo, ca.norm_2(x_r2[3:6])],
                         ["p"], ["apogee_agl", "t_apogee", "rail_exit_speed"])
    return {"final_state": final, "apogee": apogee}
