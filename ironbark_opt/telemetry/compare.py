"""``compare_flight(setup, log) -> FlightComparison``: a simulation against a log.

The simulation (``simulate``, t = 0 at ignition at rest) is aligned to the
log by the log's detected liftoff (``FlightLog.events['liftoff']``, see
:mod:`~ironbark_opt.telemetry.flightlog`), plus an optional ``time_offset``
[s] (e.g. a calibration's).  Simulated channels at the log times are linear
interpolants of the flight's samples; the accelerometer channel is the
specific force along the body axis minus local gravity, as AltOS logs it
(:mod:`~ironbark_opt.telemetry.sampled`).  Numeric-only.
"""
from __future__ import annotations

from dataclasses import dataclass, field
from typing import Mapping

import numpy as np
import pandas as pd

from ironbark_opt.atmosphere.gravity import gravity
from ironbark_opt.telemetry.flightlog import FlightLog

_UNITS = {"altitude": "m", "vertical_speed": "mps", "acceleration": "mps2"}


@dataclass(frozen=True)
class FlightComparison:
    """Simulated vs logged flight (immutable).

    Attributes
    ----------
    rocket, log : str
    errors : mapping
        Unit-suffixed: ``apogee_error_m`` (simulated - logged), ``apogee_time_error_s``,
        ``simulated_apogee_agl_m``, ``logged_apogee_agl_m``, ``..._apogee_time_s``,
        ``rms_<channel>_<unit>`` over the ascent, ``max_speed_error_mps`` where logged.
    """

    rocket: str
    log: str
    errors: Mapping[str, float]
    time_shift_s: float
    _sim: pd.DataFrame = field(repr=False)
    _log: pd.DataFrame = field(repr=False)

    def __repr__(self) -> str:
        e = self.errors
        return (f"FlightComparison({self.rocket!r} vs {self.log!r}: apogee error {e['apogee_error_m']:+.1f} m, "
                f"time error {e['apogee_time_error_s']:+.2f} s)")

    def to_dict(self) -> dict:
        return {"rocket": self.rocket, "log": self.log, "time_shift_s": self.time_shift_s, **dict(self.errors)}

    def to_dataframe(self) -> pd.DataFrame:
        """Log samples (log time) with the simulated channels beside them (``sim_...``)."""
        return self._log.copy()

    def simulated(self) -> pd.DataFrame:
        """The simulated channels on log time (``time_s`` = simulation time + shift)."""
        return self._sim.copy()

    def summary(self) -> str:
        e = self.errors
        # both apogee times after liftoff (the log's own clock is the simulation's + shift)
        lines = [f"Flight comparison: {self.rocket} vs {self.log}",
                 f"  apogee      simulated {e['simulated_apogee_agl_m']:9.1f} m at {e['simulated_apogee_time_s']:6.2f} s"
                 f",  logged {e['logged_apogee_agl_m']:9.1f} m at {e['logged_apogee_time_s']:6.2f} s"
                 " after liftoff",
                 f"  error       {e['apogee_error_m']:+9.1f} m ({100 * e['apogee_error_m'] / e['logged_apogee_agl_m']:+.2f} %),"
                 f" time {e['apogee_time_error_s']:+.2f} s"]
        for key in ("burnout_time_error_s", "max_speed_error_mps"):
            if key in e:
                lines.append(f"  {key:<28} {e[key]:+9.2f}")
        for c, u in _UNITS.items():
            if f"rms_{c}_{u}" in e:
                lines.append(f"  rms {c} (ascent) {e[f'rms_{c}_{u}']:9.2f} {u}")
        return "\n".join(lines)


def simulated_channels(setup, flight) -> pd.DataFrame:
    """``time_s``, ``altitude``, ``vertical_speed``, ``acceleration`` (accelerometer) of a Flight."""
    df = flight.to_dataframe()
    g_pad = float(gravity(setup.site_elevation, setup.latitude)) if setup.gravity is None \
        else float(setup.gravity(setup.site_elevation))
    return pd.DataFrame({"time_s": df["time_s"].values, "altitude": df["altitude_agl_m"].values,
                         "vertical_speed": df["vz_l_mps"].values,
                         "acceleration": ((df["thrust_N"] + df["axial_force_N"]) / df["mass_kg"]).values - g_pad})


def compare_flight(setup, log: FlightLog, *, flight=None, parameters: Mapping[str, float] | None = None,
                   time_offset: float = 0.0) -> FlightComparison:
    """Compare ``setup`` (simulated, or ``flight`` if given) with ``log``."""
    from ironbark_opt.flight import simulate

    flight = flight or simulate(setup, parameters=parameters)
    sim = simulated_channels(setup, flight)
    shift = float(log.events.get("liftoff", 0.0)) - float(time_offset)
    sim["time_s"] = sim["time_s"] + shift
    df = log.to_dataframe().rename(columns={"altitude_agl_m": "altitude", "vertical_speed_mps": "vertical_speed",
                                            "acceleration_mps2": "acceleration"})
    ascent = (df["time_s"] >= shift) & (df["time_s"] <= min(log.apogee_time, sim["time_s"].iloc[-1]))
    errors = {"simulated_apogee_agl_m": flight.apogee_agl, "logged_apogee_agl_m": log.apogee_agl,
              "simulated_apogee_time_s": flight.apogee_time + shift - log.events.get("liftoff", 0.0),
              "logged_apogee_time_s": log.apogee_time - log.events.get("liftoff", 0.0)}
    errors["apogee_error_m"] = errors["simulated_apogee_agl_m"] - errors["logged_apogee_agl_m"]
    errors["apogee_time_error_s"] = errors["simulated_apogee_time_s"] - errors["logged_apogee_time_s"]
    if "burnout" in log.events:
        errors["burnout_time_error_s"] = flight.summary_values["burnout_time_s"] + shift - log.events["burnout"]
    for c in ("altitude", "vertical_speed", "acceleration"):
        if c not in df:
            continue
        df[f"sim_{c}"] = np.interp(df["time_s"], sim["time_s"], sim[c], left=np.nan, right=np.nan)
        d = (df[f"sim_{c}"] - df[c])[ascent]
        errors[f"rms_{c}_{_UNITS[c]}"] = float(np.sqrt(np.nanmean(d ** 2)))
    if "vertical_speed" in df:
        errors["max_speed_error_mps"] = float(sim["vertical_speed"].max() - df["vertical_speed"][ascent].max())
    return FlightComparison(rocket=setup.name, log=log.source, errors=errors, time_shift_s=shift, _sim=sim, _log=df)
