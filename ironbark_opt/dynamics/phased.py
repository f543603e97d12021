"""The phase-by-phase ascent of :class:`~ironbark_opt.dynamics.model.FlightModel` from
Python: the numeric rail exit (bracket, interpolated guess, secant, Illinois fallback),
boost, coast to a horizon and the apogee refinement.  ``run`` falls back to it where
the fused ascent (:mod:`~ironbark_opt.dynamics.ascent`) does not apply; it raises what
it finds.
"""
from __future__ import annotations

import numpy as np

from ironbark_opt import params
from ironbark_opt.dynamics.constants import G0, RAIL_TOL_M
from ironbark_opt.errors import InputError, SolverError
from ironbark_opt.roots import illinois


def coast_to_descent(fly, t_b: float, t_end: float, what: str):
    """``(X, v_z, k, t_end)``: the coast flown by ``fly(t_end) -> (X, v_z)`` from burnout
    ``t_b`` to ``t_end`` [s], the horizon grown 1.5x (at most twice more) until a step
    ends at ``v_z <= 0``; ``k`` is the first such step.  ``what`` names the apogee in the
    error when none is reached."""
    for _ in range(3):
        X, vz = fly(t_end)
        below = np.nonzero(vz <= 0)[0]
        if below.size:
            return X, vz, int(below[0]), t_end
        t_end = t_b + 1.5 * (t_end - t_b)
    raise SolverError(f"{what} not reached within the coast horizon")


class PhasedMixin:
    """Phase-by-phase ascent of a :class:`~ironbark_opt.dynamics.model.FlightModel` (mixin)."""

    def _rail_travel(self, t_r: float, p: np.ndarray, geom) -> tuple[float, np.ndarray]:
        """(travel along the rail minus the exit distance [m], states) at ``t_r`` [s]."""
        x0, e, exit_distance = geom
        X = np.array(self._run["rail"](x0, 0.0, t_r, p))
        return float(e @ X[0:3, -1]) - exit_distance, X

    def _x0(self, p):
        return np.array(self._launch(p)[0]).ravel()

    def rail_exit(self, p: np.ndarray) -> float:
        """Rail-exit time [s] for numeric ``p``.

        The root of the same residual the symbolic model's ``rootfinder``
        uses (rail phase with ``n_rail`` equal steps over ``[0, t_r]``): a
        first run brackets it and interpolates a guess from its samples,
        then secant steps (no derivative needed, so it runs on the compiled
        functions too), with a bracketing Illinois fallback.
        """
        return self._rail_exit(p)[0]

    def _rail_exit(self, p: np.ndarray) -> tuple[float, np.ndarray]:
        """(rail-exit time [s], rail-phase states at it (13 x n_rail)): see :meth:`rail_exit`;
        the states of the last residual evaluation are kept, not integrated again."""
        exit_distance = self.rail_exit_distance(p)
        if exit_distance <= 0:
            raise InputError(f"rail length {p[params.index('rail_length')]:.3f} m is shorter than the "
                             f"distance from the nozzle to the rail guide ({self.setup.rail_exit_offset:.3f} m)",
                             field="rail_length")
        x0, e = (np.array(v).ravel() for v in self._launch(p))
        geom = (x0, e, exit_distance)
        burn = float(self.burn_time(p))
        lo, g_lo, hi = 0.0, -exit_distance, min(0.5, burn)
        while True:
            g_hi, X = self._rail_travel(hi, p, geom)
            if g_hi > 0:
                break
            if hi >= burn:
                raise InputError("the rocket does not leave the rail before motor burnout: check thrust, "
                                 "mass and rail length", field="rail_length")
            lo, g_lo, hi = hi, g_hi, min(2 * hi, burn)
        travel = np.concatenate([[g_lo], e @ X[0:3, :] - exit_distance]) if lo == 0 else None
        if travel is not None:
            k = int(np.argmax(travel > 0))
            dt = hi / (travel.size - 1)
            t_a = (k - 1) * dt + dt * (-travel[k - 1]) / (travel[k] - travel[k - 1])
            t_b = t_a * (1 + 1e-4)
            g_a, X_a = self._rail_travel(t_a, p, geom)
            for _ in range(8):                      # secant from the interpolated guess
                if abs(g_a) < RAIL_TOL_M:
                    return t_a, X_a
                g_b, X_b = self._rail_travel(t_b, p, geom)
                if g_b == g_a:
                    break
                t_a, g_a, X_a, t_b = t_b, g_b, X_b, t_b - g_b * (t_b - t_a) / (g_b - g_a)
                if not lo <= t_b <= hi:
                    break
        # Illinois regula falsi fallback
        t, _, X, _, done = illinois(lambda t: self._rail_travel(t, p, geom), lo, g_lo, hi, g_hi,
                                    gtol=np.nextafter(RAIL_TOL_M, 0.0), xtol=np.nextafter(1e-12, 0.0))
        if not done:
            raise SolverError(f"rail-exit time did not converge (bracket {lo:.6f}..{hi:.6f} s)")
        return t, X

    def _ascent_phased(self, p) -> dict:
        """The ascent phase by phase from Python (rail-exit secant, boost, coast to a
        horizon, apogee refinement): the path :meth:`_ascent_fused` falls back to."""
        x0 = self._x0(p)
        t_r, X_rail = self._rail_exit(p)
        t_b = self.burn_time(p)
        if t_r >= t_b:
            raise InputError(f"motor burns out ({t_b:.2f} s) before rail exit ({t_r:.2f} s)",
                             field="motor")
        x_r = X_rail[:, -1].copy()
        X_boost = np.array(self._run["boost"](x_r, t_r, t_b, p))
        x_b = X_boost[:, -1]
        vz_b = float(self.vz_l(x_b))
        if vz_b <= 0:
            raise SolverError("vertical velocity at burnout is not positive: the rocket never climbs; check the "
                              "launch mass, the motor, launch.inclination_deg and the wind")
        # Drag only shortens the coast below the vacuum time v_z / g; the margin
        # covers gravity falling off with height.
        def fly(t_end):
            X_dm = self._run["coast"](x_b, t_b, t_end, p)
            X = np.array(X_dm)
            return X, np.array(self._mapped("vz", X.shape[1])(X_dm)).ravel()    # no NumPy round trip

        X_coast, vz, k, t_end = coast_to_descent(fly, t_b, t_b + vz_b / G0 + 2.0, "apogee")
        fr = self.coast_fractions_of(p)
        span = t_end - t_b
        dt_c = span * (fr[k + 1] - fr[k])
        x_k = x_b if k == 0 else X_coast[:, k - 1]
        t_k = t_b + span * fr[k]
        vz_k = vz_b if k == 0 else vz[k - 1]
        h0 = dt_c * vz_k / (vz_k - vz[k]) if vz_k != vz[k] else dt_c
        h, x_a = self._apogee_run(x_k, t_k, h0, dt_c, p)
        return dict(x0=x0, t_r=t_r, X_rail=X_rail, t_b=t_b, X_boost=X_boost, span=span, k=k,
                    X_coast=X_coast[:, :k], t_a=t_k + float(h), x_a=np.array(x_a).ravel())
