"""The RK4 grid of :class:`~ironbark_opt.dynamics.model.FlightModel`: boost and coast step
counts, the graded coast, the air-start boost segments and the stiffness-based choice
of the grid from the nominal flight (RK4 stability: |lambda| dt within its region).
"""
from __future__ import annotations

import math

import casadi as ca
import numpy as np

from ironbark_opt import params
from ironbark_opt.dynamics.constants import G0
from ironbark_opt.dynamics.integrator import _splitting, grid_fractions, phase_trajectory
from ironbark_opt.errors import InputError, SolverError

#: |lambda| dt allowed for RK4 (its stability region reaches 2.78 on the real
#: and 2.83 on the imaginary axis); chosen by the RK4-vs-DOP853 validation.
STABLE_LAMBDA_DT = 1.5
#: Fewest coast steps whatever the stiffness (accuracy of the coast's slow part).
MIN_COAST_STEPS = 300
#: A rolling rocket's steps also resolve its roll: |w_x| dt <= STABLE_LAMBDA_DT /
#: SPIN_LAMBDA_FACTOR (0.75 rad a step).  In body axes the transverse rates and the air
#: data rotate at the roll rate with their full amplitude, so RK4's phase and amplitude
#: error there (y^5/120, y^6/144 a step at y = |w_x| dt; 0.063 / 0.079 at 1.5, 0.002 /
#: 0.001 at 0.75) is an error of the whole motion, not of a small oscillation about it.
#: Measured (a 76 mm, 2 kg rocket, fins canted 1.5 deg, 198 rad/s at burnout; RK4 -
#: DOP853 rtol 1e-10): apogee -8.5 m with the stability bound alone, -1.7 m with this
#: bound too (-0.4 m with twice its coast steps).
SPIN_LAMBDA_FACTOR = 2.0
#: Times the nominal boost's step count is doubled at most when its coarse grid blows up
#: before burnout (the stiffness check needs a finite burnout state; 2^6 = 64 x).
MAX_BOOST_DOUBLINGS = 6


def doubled_until_finite(run, steps, set_steps, can_refine=lambda n: True):
    """Final state of a provisional phase grid: ``run()`` flies the phase on the current
    grid (states as columns), ``steps()`` is its step count and ``set_steps(n)`` imposes
    ``n``; the steps are doubled (at most :data:`MAX_BOOST_DOUBLINGS` times, and only
    while ``can_refine(n)``) while the final state is not finite.  Used for the boost of
    a single stage (:meth:`GridMixin._finite_boost`) and for a sustainer's boost
    (:meth:`ironbark_opt.dynamics.staged.StagedFlightModel._choose_sustainer_grid`)."""
    x = None
    for _ in range(MAX_BOOST_DOUBLINGS + 1):
        x = np.array(run())[:, -1]
        if np.all(np.isfinite(x)) or not can_refine(2 * steps()):
            return x
        set_steps(2 * steps())
    return x


class GridMixin:
    """RK4 grid of a :class:`~ironbark_opt.dynamics.model.FlightModel` (mixin)."""

    def _choose_grid(self, p):
        """Fix the RK4 grid from the *nominal* flight (deterministic: the same
        for every later run, batch, chunk or worker)."""
        t_r = self.rail_exit(p)
        t_b = self.burn_time(p)
        if t_r >= t_b:
            raise InputError(f"motor burns out ({t_b:.2f} s) before rail exit ({t_r:.2f} s)", field="motor")
        x_r = np.array(self._run["rail"](self._x0(p), 0.0, t_r, p))[:, -1]
        x_b = self._finite_boost(x_r, t_r, t_b, p)
        vz_b = float(self.vz_l(x_b))
        if vz_b <= 0:
            raise SolverError("vertical velocity at burnout is not positive: the rocket never climbs; check the "
                              "launch mass, the motor, launch.inclination_deg and the wind")
        self._ensure_stable(x_b, t_b, t_b + vz_b / G0 + 2.0, p)

    def _finite_boost(self, x_r, t_r, t_b, p):
        """Burnout state of the nominal boost, the boost's steps doubled (at most
        :data:`MAX_BOOST_DOUBLINGS` times) while the provisional grid blows up before
        burnout.  The stiffness check (:meth:`_ensure_stable`) reads the Jacobian at
        burnout, so it needs a finite state there; a mode stiffer during the boost than
        ``dt_boost`` allows (fins canted 1 deg on a 76 mm, 2 kg rocket: its roll rate, up
        to 198 rad/s, couples pitch and yaw at ~280 rad/s, over RK4's region at 0.02 s steps) made the
        whole state NaN first, and the flight was refused."""
        def set_steps(n):
            self.n_boost = n
            self._set_trajectory("boost", n)
        return doubled_until_finite(lambda: self._run["boost"](x_r, t_r, t_b, self._with_boost_grid(p)),
                                    lambda: self.n_boost, set_steps, self._can_refine_boost)

    def _with_boost_grid(self, p):
        """``p`` for the current boost grid (the grid is in the trajectory Function here;
        a model keeping its grids in ``p`` overrides this)."""
        return p

    def _can_refine_boost(self, n: int) -> bool:
        """Whether a boost grid of ``n`` steps can be flown."""
        return True

    def discretisation(self) -> tuple[int, int, float]:
        """``(n_boost, n_coast, coast_grading)``: the RK4 grid of boost and coast."""
        return int(self.n_boost), int(self.n_coast), float(self.coast_grading)

    def set_discretisation(self, n_boost: int, n_coast: int, coast_grading: float = 1.0) -> None:
        """Impose a grid (e.g. the one a client chose, on a cluster worker)."""
        if (int(n_boost), int(n_coast), float(coast_grading)) == self.discretisation():
            return
        self.n_boost, self.n_coast, self.coast_grading = int(n_boost), int(n_coast), float(coast_grading)
        self._set_trajectory("boost", self.n_boost)
        self._set_trajectory("coast", self.n_coast)
        self._compile_phases()

    @property
    def coast_fractions(self) -> np.ndarray:
        """Coast step boundaries as fractions of the coast (n_coast + 1; read-only)."""
        key = (self.n_coast, self.coast_grading)
        cached = self.__dict__.get("_coast_fractions")
        if cached is None or cached[0] != key:
            fr = grid_fractions(self.n_coast, self.coast_grading)
            fr.flags.writeable = False
            self.__dict__["_coast_fractions"] = cached = (key, fr)
        return cached[1]

    def coast_fractions_of(self, p) -> np.ndarray:
        """Coast step boundaries of the flight with parameters ``p`` (the model's
        own grid; a motor-slot model reads it from ``p``)."""
        return self.coast_fractions

    def burn_time(self, p):
        """Burnout time [s] = the motor's burn time x ``burn_time_scale`` (numbers or MX)."""
        return float(self.setup.motor.burn_time) * p[params.index("burn_time_scale")]

    def _boost_segments(self, n: int) -> list[tuple[float | None, float | None, int]]:
        """The boost grid split at the motor's ignition/burnout events (air-start),
        so no thrust jump falls inside a step: [(start, end, steps)] with start/end
        unscaled event times [s] (None = rail exit / burnout)."""
        events = tuple(getattr(self.setup.motor, "events", ()))
        burn = float(self.setup.motor.burn_time)
        if not events:
            return [(None, None, n)]
        bounds = [None, *events, None]
        lengths = np.diff([0.0, *events, burn])
        counts = [max(4, int(round(n * length / burn))) for length in lengths]
        return [(bounds[i], bounds[i + 1], counts[i]) for i in range(len(counts))]

    def _segmented_boost(self, n: int) -> ca.Function:
        """``(x0, t_rail, t_burnout, p) -> X`` over the segments of :meth:`_boost_segments`
        (event times scaled by ``burn_time_scale``); same signature as a phase trajectory."""
        x0, t0, t1 = ca.MX.sym("x0", 13), ca.MX.sym("t0"), ca.MX.sym("t1")
        p = ca.MX.sym("p", self.n_p)
        s = p[params.index("burn_time_scale")]
        x, blocks = x0, []
        for i, (a, b, k) in enumerate(self._boost_segments(n)):
            traj = phase_trajectory(self.step["boost"], k, f"traj_boost_{i}", rhs=self.rhs["boost"])
            X = traj(x, t0 if a is None else a * s, t1 if b is None else b * s, p)
            blocks.append(X)
            x = X[:, -1]
        return ca.Function("traj_boost", [x0, t0, t1, p], [ca.hcat(blocks)], ["x0", "t0", "t1", "p"], ["X"])

    def boost_times(self, t_r: float, t_b: float, p) -> np.ndarray:
        """Times [s] of the boost trajectory's columns (after each step)."""
        s = float(np.asarray(p, dtype=float).ravel()[params.index("burn_time_scale")])
        out = []
        for a, b, k in self._boost_segments(self.n_boost):
            lo, hi = (t_r if a is None else a * s), (t_b if b is None else b * s)
            out.append(lo + (hi - lo) * np.arange(1, k + 1) / k)
        return np.concatenate(out)

    def _set_trajectory(self, phase: str, n: int):
        grading = self.coast_grading if phase == "coast" else 1.0
        if phase == "boost" and getattr(self.setup.motor, "events", ()):
            self.trajectory[phase] = self._segmented_boost(n)
        else:
            # the rail's roll damping is zero (no rotation): its steps stay in the plain form
            rhs = None if phase == "rail" else self.rhs[phase]
            self.trajectory[phase] = phase_trajectory(self.step[phase], n, f"traj_{phase}", grading, rhs=rhs)
        self._run[phase] = self.trajectory[phase]      # compiled (if asked) once the grid is fixed
        for key in [k for k in self.__dict__.get("_map_cache", {}) if k[0].split(":")[0] == phase]:
            del self._map_cache[key]

    def stable_step(self, f: ca.Function, x, t, p) -> float:
        """Largest step [s] for RK4 at state ``x`` (columns: the worst one counts).

        ``STABLE_LAMBDA_DT / max |eig(df/dx)|`` of the right-hand side ``f``: inside RK4's
        stability region (|lambda dt| < 2.78 on the real and imaginary axes)
        with margin for accuracy.  Roll damping, the stiffest mode of light
        rockets, is left out: the integrator advances it exactly.
        """
        cache = self.__dict__.setdefault("_jac_cache", {})
        key = (f.name(), id(f))         # a staged rocket's sustainer has its own rhs_boost / rhs_coast
        if key not in cache:
            xs, ts, ps = ca.SX.sym("x", 13), ca.SX.sym("t"), ca.SX.sym("p", self.n_p)
            # without the roll equation's damping and forcing: the integrator advances
            # them exactly (integrator._splitting, as rk4_step)
            xdot = _splitting(f, ps)[0](xs, ts)
            cache[key] = ca.Function(f"jac_{f.name()}", [xs, ts, ps], [ca.jacobian(xdot, xs)])
        jac = cache[key]
        x = np.atleast_2d(np.asarray(x, dtype=float).T).T
        t = np.broadcast_to(np.asarray(t, dtype=float), (x.shape[1],))
        p = np.asarray(p, dtype=float)
        p = np.repeat(p[:, None], x.shape[1], axis=1) if p.ndim == 1 else p
        jacs = [np.array(jac(x[:, i], t[i], p[:, i])) for i in range(x.shape[1])]
        bad = next((i for i, j in enumerate(jacs) if not np.all(np.isfinite(j))), None)
        if bad is not None:
            raise SolverError(f"the equations of motion are not finite at t = {float(t[bad]):.3g} s of "
                              "the nominal flight (state or forces NaN/inf): check the aerodynamic "
                              "table (--table) and the motor file for non-finite or absurd values")
        lam = max(np.max(np.abs(np.linalg.eigvals(j))) for j in jacs)
        lam = max(lam, SPIN_LAMBDA_FACTOR * float(np.max(np.abs(x[10]))))    # w_x [rad/s]
        return STABLE_LAMBDA_DT / lam if lam > 0 else np.inf

    def _coast_grid(self, x_b, t_b, t_end, p):
        """(n_coast, grading) from the stiffness along the nominal coast.

        A provisional uniform coast (stable at burnout, the stiffest point) is
        flown; at ~30 states before apogee the largest eigenvalue
        ``lambda(s)`` of the RHS Jacobian is taken, and for each grading ``a``
        of :func:`~ironbark_opt.dynamics.integrator.grid_fractions` the
        smallest ``n`` with ``span g_a'(s) lambda(s) / n <= STABLE_LAMBDA_DT``
        everywhere; the cheapest (n, a) wins.  The stiffness falls with speed
        and density, so finer steps after burnout and coarser ones near
        apogee need about half the steps of a uniform grid.
        """
        span = float(t_end - t_b)
        n_uni = max(self.steps.n_coast, int(math.ceil(span / self.stable_step(self.rhs["coast"], x_b, t_b, p))))
        X = self._coast_probe(x_b, t_b, t_end, p, n_uni)
        vz = np.array(self._mapped("vz", n_uni)(X)).ravel()
        k_top = int(np.argmax(vz <= 0)) if np.any(vz <= 0) else n_uni
        idx = np.unique(np.linspace(0, max(k_top, 1), 30).astype(int))
        states = np.column_stack([x_b] + [X[:, i - 1] for i in idx[1:]])
        frac = idx / n_uni
        lam = np.array([STABLE_LAMBDA_DT / self.stable_step(self.rhs["coast"], states[:, j], t_b + span * f, p)
                        for j, f in enumerate(frac)])
        best = None
        for a in (1.0, 0.7, 0.5, 0.35, 0.25):
            slope = a + 2.0 * (1.0 - a) * frac                    # g_a'(s)
            n = int(math.ceil(np.max(span * slope * lam) / STABLE_LAMBDA_DT))
            n = max(MIN_COAST_STEPS, 25 * int(math.ceil(n / 25)))
            if best is None or n < best[0]:
                best = (n, a)
        return best

    def _coast_probe(self, x_b, t_b, t_end, p, n: int) -> np.ndarray:
        """States after each of ``n`` uniform coast steps from burnout (grid choice only)."""
        return np.array(phase_trajectory(self.step["coast"], n, "traj_coast_probe")(x_b, t_b, t_end, p))

    def _ensure_stable(self, x_b, t_b, t_end, P):
        """Refine the boost step if burnout (the stiffest point) needs it and
        choose the coast grid (:meth:`_coast_grid`); called once, at build."""
        dt_b = self.stable_step(self.rhs["boost"], x_b, t_b, P)
        if self.steps.dt_boost > dt_b:
            self.n_boost = int(math.ceil(self.n_boost * self.steps.dt_boost / dt_b))
            self._set_trajectory("boost", self.n_boost)
        self.n_coast, self.coast_grading = self._coast_grid(x_b, t_b, t_end, P)
        self._set_trajectory("coast", self.n_coast)
