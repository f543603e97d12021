"""``simulate(...) -> Flight``: one trajectory, numbers, table and summary.

``Flight`` is an immutable result: constructors never simulate; plots are
functions in :mod:`ironbark_opt.plots`.
"""
from __future__ import annotations

import warnings
import weakref
from dataclasses import dataclass, field
from typing import Mapping

import numpy as np

from ironbark_opt import params as params_mod
from ironbark_opt.dynamics.integrator import jit_mode
from ironbark_opt.dynamics.model import FlightModel, Steps
from ironbark_opt.dynamics.rhs import OUTPUT_NAMES
from ironbark_opt.errors import OutOfRangeWarning, SolverError

_MODELS: dict[int, tuple] = {}


def flight_model(setup, steps: Steps | None = None, jit="auto") -> FlightModel:
    """The (cached) :class:`FlightModel` of ``setup``: built once, reused."""
    jit = jit_mode(jit)
    key = id(setup)
    hit = _MODELS.get(key)
    if hit is not None:
        ref, model = hit
        if ref() is setup and model.steps == (steps or Steps()) and model.jit == jit:
            return model
    from ironbark_opt.dynamics.staged import StagedFlightModel, StagedSetup
    model = (StagedFlightModel if isinstance(setup, StagedSetup) else FlightModel)(setup, steps, jit=jit)
    _MODELS[key] = (weakref.ref(setup), model)
    return model


@dataclass(frozen=True)
class Flight:
    """Result of :func:`simulate`.

    Attributes
    ----------
    name : str
        Rocket name.
    parameters : dict name -> float
        The parameter vector flown (SI, radians).
    summary_values : dict
        Key figures with unit-suffixed keys (see :meth:`to_dict`).
    """

    name: str
    parameters: Mapping[str, float]
    summary_values: Mapping[str, float]
    #: the time series, column name -> 1-D array (pandas is imported only by `to_dataframe`)
    _columns: Mapping[str, np.ndarray] = field(repr=False)

    def __repr__(self) -> str:
        s = self.summary_values
        return (f"Flight({self.name!r}: apogee {s['apogee_agl_m']:.1f} m AGL at {s['apogee_time_s']:.2f} s, "
                f"max speed {s['max_speed_mps']:.1f} m/s)")

    def to_dataframe(self):
        """Time series (a new ``pandas.DataFrame``): one row per integrator sample, SI columns."""
        import pandas as pd
        return pd.DataFrame({k: np.array(v) for k, v in self._columns.items()})

    def to_dict(self) -> dict:
        """Summary with unit-suffixed keys (``apogee_agl_m``, ...) and the parameters."""
        out = dict(self.summary_values)
        out["parameters"] = dict(self.parameters)
        return out

    @property
    def apogee_agl(self) -> float:
        """Apogee above ground level [m]."""
        return self.summary_values["apogee_agl_m"]

    @property
    def apogee_time(self) -> float:
        """Time of apogee [s]."""
        return self.summary_values["apogee_time_s"]

    def summary(self) -> str:
        """Human-readable summary (a string; nothing is printed)."""
        s = self.summary_values
        lines = [
            f"Flight of {self.name}",
            f"  apogee             {s['apogee_agl_m']:10.1f} m AGL  ({s['apogee_asl_m']:.1f} m ASL, "
            f"{s['apogee_agl_m'] / 0.3048:.0f} ft AGL)",
            f"  time to apogee     {s['apogee_time_s']:10.2f} s",
            f"  rail exit          {s['rail_exit_speed_mps']:10.2f} m/s at {s['rail_exit_time_s']:.3f} s, "
            f"static margin {s['static_margin_rail_exit_cal']:.2f} cal",
            f"  burnout            {s['burnout_time_s']:10.2f} s at {s['burnout_altitude_agl_m']:.1f} m AGL",
            f"  max speed          {s['max_speed_mps']:10.1f} m/s (Mach {s['max_mach']:.3f}) at "
            f"{s['max_speed_time_s']:.2f} s",
            f"  max acceleration   {s['max_acceleration_mps2']:10.1f} m/s^2 ({s['max_acceleration_mps2'] / 9.80665:.1f} g)",
            f"  max dynamic press. {s['max_dynamic_pressure_Pa'] / 1000:10.2f} kPa",
            f"  launch mass        {s['launch_mass_kg']:10.3f} kg, static margin at t=0 "
            f"{s['static_margin_initial_cal']:.2f} cal",
            f"  apogee drift       {s['apogee_east_m']:10.1f} m east, {s['apogee_north_m']:.1f} m north",
            f"  min static margin  {s['static_margin_min_cal']:10.2f} cal at {s['static_margin_min_time_s']:.2f} s",
        ]
        if "separation_time_s" in s:
            lines.append(f"  separation         {s['separation_time_s']:10.2f} s at {s['separation_altitude_agl_m']:.1f} m "
                         f"AGL (booster burnout {s['booster_burnout_time_s']:.2f} s)")
        if "booster_landing_time_s" in s:
            lines.append(f"  booster            apogee {s['booster_apogee_agl_m']:.1f} m AGL at "
                         f"{s['booster_apogee_time_s']:.2f} s, lands at {s['booster_landing_time_s']:.1f} s, "
                         f"{s['booster_landing_east_m']:.1f} m east, {s['booster_landing_north_m']:.1f} m north"
                         + (" (tumbling)" if s.get("booster_tumble_cd_area_m2", 0.0) > 0 else ""))
        if "airbrake_max_deployment" in s:
            lines.append(f"  air brakes         {s['airbrake_max_deployment']:10.3f} max deployment, opening from "
                         f"{s['airbrake_open_time_s']:.2f} s at up to {s['airbrake_max_rate_per_s']:.2f} /s")
        if "ejection_time_s" in s:
            when = (f"{s['ejection_before_apogee_s']:.2f} s BEFORE apogee (coasting apogee "
                    f"{s['coasting_apogee_agl_m']:.1f} m)" if "ejection_before_apogee_s" in s
                    else f"{s['ejection_after_apogee_s']:.2f} s after apogee")
            lines.append(f"  ejection charge    {s['ejection_time_s']:10.2f} s (delay {s['ejection_delay_s']:g} s), {when}")
        if "landing_time_s" in s:
            lines.append(f"  landing            {s['landing_time_s']:10.1f} s, {s['landing_east_m']:.1f} m east, "
                         f"{s['landing_north_m']:.1f} m north ({s['landing_distance_m']:.1f} m from the rail)")
            if s.get("recovery_devices") == 0:
                lines.append(f"  NOTE: no recovery device in the file: ballistic impact at "
                             f"{s['landing_speed_mps']:.0f} m/s")
        return "\n".join(lines)


def _table(model: FlightModel, run: dict) -> dict[str, np.ndarray]:
    t, x, phase, p = run["t"], run["x"], run["phase"], run.get("P", run["p"])
    y = model.outputs(t, x, phase, p)
    q = x[6:10]
    q0, q1, q2, q3 = q
    # Body axis in L (first column of T_LB): attitude angles for plots.
    ax_e = q0 * q0 + q1 * q1 - q2 * q2 - q3 * q3
    ax_n = 2 * (q1 * q2 + q0 * q3)
    ax_u = 2 * (q1 * q3 - q0 * q2)
    elev = model.setup.site_elevation
    data = {
        "time_s": t, "phase": phase,
        "x_east_m": x[0], "y_north_m": x[1], "altitude_agl_m": x[2], "altitude_asl_m": x[2] + elev,
        "vx_b_mps": x[3], "vy_b_mps": x[4], "vz_b_mps": x[5],
        "q0": q0, "q1": q1, "q2": q2, "q3": q3,
        "wx_b_radps": x[10], "wy_b_radps": x[11], "wz_b_radps": x[12],
        "pitch_deg": np.degrees(np.arctan2(ax_u, np.hypot(ax_e, ax_n))),
        "heading_deg": np.degrees(np.arctan2(ax_e, ax_n)) % 360.0,
    }
    for i, name in enumerate(OUTPUT_NAMES):
        if name == "alpha_rad":
            data["alpha_deg"] = np.degrees(y[i])
        elif name == "altitude_asl_m":
            continue
        else:
            data[name] = y[i]
    n = len(t)
    return {k: (np.asarray(v) if np.ndim(v) else np.full(n, v)) for k, v in data.items()}


#: Mach number no flight of this tool's rockets reaches: above it, or with non-finite
#: states or an apogee below the pad, the fixed-step integration has diverged
MACH_DIVERGED = 30.0


def _check_converged(model: FlightModel, run: dict, df: dict, flying) -> None:
    """Refuse a diverged integration (exit 3) instead of printing its numbers."""
    mach = np.asarray(df["mach"])[flying]
    alt = np.asarray(df["altitude_agl_m"])[flying]
    apogee = float(run["x_apogee"][2])
    if not (np.all(np.isfinite(mach)) and np.all(np.isfinite(alt)) and np.isfinite(apogee)) \
            or mach.max() > MACH_DIVERGED or apogee < 0.0:
        raise SolverError(f"{model.setup.name}: the flight's integration diverged (max Mach {mach.max():.3g}, "
                          f"apogee {apogee:.6g} m AGL): the fixed-step RK4 grid could not follow this "
                          "flight; no result was written. Please report it with the rocket file")


def _summary(model: FlightModel, run: dict, df: dict) -> dict:
    elev = model.setup.site_elevation
    x_a, x_r = run["x_apogee"], run["x_rail"]
    time = df["time_s"]
    rail = int(np.flatnonzero(time <= run["t_rail"] + 1e-12)[-1])
    i_vmax = int(df["speed_mps"].argmax())
    burn = int(np.flatnonzero(time <= run["t_burnout"] + 1e-12)[-1])
    flying = np.isin(df["phase"], ["rail", "boost", "coast", "stack_coast", "sustainer_boost"])
    _check_converged(model, run, df, flying)
    s = {
        "apogee_agl_m": float(x_a[2]),
        "apogee_asl_m": float(x_a[2] + elev),
        "apogee_time_s": float(run["t_apogee"]),
        "apogee_east_m": float(x_a[0]),
        "apogee_north_m": float(x_a[1]),
        "max_speed_mps": float(df["speed_mps"][i_vmax]),
        "max_speed_time_s": float(time[i_vmax]),
        "max_mach": float(df["mach"][flying].max()),
        "max_acceleration_mps2": float(df["acceleration_mps2"][flying].max()),
        "max_dynamic_pressure_Pa": float(df["dynamic_pressure_Pa"][flying].max()),
        "rail_exit_time_s": float(run["t_rail"]),
        "rail_exit_speed_mps": float(np.linalg.norm(x_r[3:6])),
        "static_margin_rail_exit_cal": float(df["static_margin_cal"][rail]),
        "static_margin_initial_cal": float(df["static_margin_cal"][0]),
        "burnout_time_s": float(run["t_burnout"]),
        "burnout_altitude_agl_m": float(df["altitude_agl_m"][burn]),
        "launch_mass_kg": float(df["mass_kg"][0]),
        "static_margin_min_cal": float(df["static_margin_cal"][flying].min()),
        "static_margin_min_time_s": float(df["time_s"][flying][int(df["static_margin_cal"][flying].argmin())]),
        "site_elevation_m": float(elev),
    }
    if "t_separation" in run:                    # a staged rocket (dynamics/staged.py)
        s.update(booster_burnout_time_s=float(run["t_booster_burnout"]),
                 separation_time_s=float(run["t_separation"]),
                 separation_altitude_agl_m=float(run["x_separation"][2]), **run.get("booster", {}))
    brakes = getattr(model.setup, "airbrakes", None)
    if brakes is not None:
        dep, tt = df["airbrake_deployment"][flying], df["time_s"][flying]
        if brakes.trigger == "controller":
            # a controller's deployment is held between sampling instants and changes by
            # at most rate / f at each (dynamics/controlled.py): its rate is that change
            # times the sampling rate, not the step over the output's sub-sample spacing
            rate = np.diff(dep) * float(brakes.sampling_rate)
        else:
            rate = np.diff(dep) / np.maximum(np.diff(tt), 1e-12)
        s.update(airbrake_max_deployment=float(dep.max()),
                 airbrake_max_rate_per_s=float(np.abs(rate).max()) if rate.size else 0.0)
        opened = np.nonzero(dep > 1e-6)[0]
        s["airbrake_open_time_s"] = float(tt[opened[0]]) if opened.size else float("nan")
        if brakes.rate is not None and brakes.trigger in ("altitude", "mach", "vertical_speed") and \
                s["airbrake_max_rate_per_s"] > brakes.rate * 1.01:
            warnings.warn(f"{model.setup.name}: the air brakes opened at up to {s['airbrake_max_rate_per_s']:.2f} /s, "
                          f"faster than their rate limit {brakes.rate:g} /s: increase [airbrakes] ramp",
                          UserWarning, stacklevel=3)
    from ironbark_opt.dynamics.ejection import describe
    ej, message = describe(run, model.setup)
    s.update(ej)
    if message:
        warnings.warn(message, UserWarning, stacklevel=3)
    if "t_landing" in run:
        xl = run["x_landing"]
        s.update(landing_time_s=float(run["t_landing"]), landing_east_m=float(xl[0]),
                 landing_north_m=float(xl[1]), landing_distance_m=float(np.hypot(xl[0], xl[1])),
                 landing_speed_mps=float(np.linalg.norm(xl[3:6])),
                 recovery_devices=len(model.setup.parachutes))
    return s


def _warn_outside_table(setup, df: dict) -> None:
    """Warn when the ascent left the aerodynamic table's grid (it was clamped)."""
    table = getattr(setup.aero, "table", None)
    if table is None:
        return
    flying = np.isin(df["phase"], ["rail", "boost", "coast"])
    up = {k: df[k][flying] for k in ("mach", "alpha_deg")}
    m_lo, m_hi = table.mach_range
    a_lo, a_hi = table.alpha_range
    outside = []
    if up["mach"].max() > m_hi * (1 + 1e-9):
        outside.append(f"Mach up to {up['mach'].max():.3f} (table to {m_hi:g})")
    if a_hi > a_lo and np.radians(up["alpha_deg"].max()) > a_hi * (1 + 1e-9):
        outside.append(f"angle of attack up to {up['alpha_deg'].max():.1f} deg (table to {np.degrees(a_hi):.1f} deg)")
    if outside:
        warnings.warn(f"{setup.name}: the flight left the aerodynamic table's grid, coefficients were clamped: "
                      + "; ".join(outside), OutOfRangeWarning, stacklevel=3)


def simulate(setup, *, parameters: Mapping[str, float] | None = None, p=None,
             steps: Steps | None = None, jit="auto", descent: bool = False,
             model: FlightModel | None = None) -> Flight:
    """Fly ``setup`` to apogee (and optionally to landing).

    Parameters
    ----------
    setup : FlightSetup
        Vehicle, motor, aerodynamics, atmosphere and site
        (e.g. ``ironbark_opt.vehicle.load_setup("rocket.toml")``).
    parameters : mapping name -> value, optional
        Overrides of the nominal parameters (SI, radians), e.g.
        ``{"ballast_mass": 0.5}``; names from :mod:`ironbark_opt.params`.
    p : array, optional
        A full parameter vector instead of ``parameters``.
    steps : Steps, optional
        Integrator discretisation.
    jit : bool or "auto"
        Use C-compiled trajectory functions (cached on disk); ``"auto"`` (default):
        compiled when cached, else the VM with a background compile for next time.
    descent : bool
        Continue to landing under the setup's parachutes (ballistic if none).
    model : FlightModel, optional
        Reuse an already built model.

    Returns
    -------
    Flight
    """
    model = model or flight_model(setup, steps, jit)
    if p is None:
        p = setup.nominal_parameters(**dict(parameters or {}))
    p = np.asarray(p, dtype=float).ravel()
    brakes = getattr(setup, "airbrakes", None)
    if brakes is not None and not brakes.differentiable:
        from ironbark_opt.dynamics.controlled import run_controlled
        run = run_controlled(model, p, descent=descent)
    else:
        run = model.run(p, descent=descent)
    return flight_of_run(setup, model, p, run)


def flight_of_run(setup, model: FlightModel, p, run: dict) -> Flight:
    """The :class:`Flight` of ``run``, a flight ``model`` has flown with the parameter
    vector ``p`` (``model.run(p)``): what :func:`simulate` returns, without flying
    it again (the ballast solution reports the root's own flight)."""
    df = _table(model, run)
    _warn_outside_table(setup, df)
    return Flight(name=setup.name, parameters=params_mod.to_dict(np.asarray(p, dtype=float)[:params_mod.SIZE]),
                  summary_values=_summary(model, run, df),
                  _columns=df)
