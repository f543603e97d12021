"""File exports: a flight as OpenRocket's "Export as CSV", Monte Carlo samples
as CSV or Parquet (numeric-only).

The OpenRocket layout is that of ``net.sf.openrocket.file.CSVExport``
(OpenRocket 15.03-23.09): comment lines ``# <simulation name>``, ``# <n> data
points written for <m> variables.``, an empty ``#``, the field header ``#
Name (unit),Name (unit),...`` with OpenRocket's ``FlightDataType`` names
(the names an .ork file's ``<databranch types=...>`` uses, see
:data:`ironbark_opt.openrocket.simdata.COLUMNS`) and units of its unit
groups, then one row per sample, with ``# Event TYPE occurred at t=T
seconds`` before the first row at or after the event.  Dimensionless units
are OpenRocket's zero-width space.
"""
from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from ironbark_opt.errors import InputError

_NONE = "\u200b"     # OpenRocket's unit string of a dimensionless quantity


def openrocket_columns(flight, latitude: float | None = None, longitude: float | None = None) -> dict:
    """OpenRocket field header (``"Altitude (m)"``, ...) -> values, from ``flight``'s time series.

    ``Vertical acceleration`` is the derivative of the vertical velocity on
    the integrator's grid (second-order central differences, ``numpy.gradient``);
    ``Latitude``/``Longitude`` are added when the site's position [rad] is given.
    """
    df = flight.to_dataframe()
    t = df["time_s"].to_numpy()
    vz = df["vz_l_mps"].to_numpy()
    east, north = df["x_east_m"].to_numpy(), df["y_north_m"].to_numpy()
    cols = {
        "Time (s)": t,
        "Altitude (m)": df["altitude_agl_m"],
        "Altitude above sea level (m)": df["altitude_asl_m"],
        "Vertical velocity (m/s)": vz,
        "Vertical acceleration (m/s²)": np.gradient(vz, t) if len(t) > 1 else np.zeros_like(t),
        "Total velocity (m/s)": df["speed_mps"],
        "Total acceleration (m/s²)": df["acceleration_mps2"],
        "Position East of launch (m)": east,
        "Position North of launch (m)": north,
        "Lateral distance (m)": np.hypot(east, north),
    }
    if latitude is not None and longitude is not None:
        from ironbark_opt.report.geodesy import local_to_geodetic
        lat, lon = local_to_geodetic(east, north, latitude, longitude, df["altitude_asl_m"].to_numpy())
        cols.update({"Latitude (° N)": lat, "Longitude (° E)": lon})
    cols.update({
        "Angle of attack (°)": df["alpha_deg"],
        "Roll rate (°/s)": np.degrees(df["wx_b_radps"]),
        "Pitch rate (°/s)": np.degrees(df["wy_b_radps"]),
        "Yaw rate (°/s)": np.degrees(df["wz_b_radps"]),
        # OpenRocket's orientation of the body axis (x east, y north, z up): "zenith"
        # theta = atan2(z, hypot(x, y)) is the elevation above the horizon and "azimuth"
        # phi = atan2(y, x) counts counter-clockwise from east (OpenRocket
        # RK4SimulationStepper / AbstractSimulationStepper, TYPE_ORIENTATION_THETA/PHI)
        "Vertical orientation (zenith) (°)": df["pitch_deg"],
        "Lateral orientation (azimuth) (°)": (90.0 - df["heading_deg"] + 180.0) % 360.0 - 180.0,
        "Mass (kg)": df["mass_kg"],
        "CP location (m)": df["cp_x_m"],
        "CG location (m)": df["cg_x_m"],
        f"Stability margin calibers ({_NONE})": df["static_margin_cal"],
        f"Mach number ({_NONE})": df["mach"],
        "Thrust (N)": df["thrust_N"],
        f"Axial drag coefficient ({_NONE})": df["CA"],
        f"Normal force coefficient ({_NONE})": df["CN"],
    })
    return {k: np.asarray(v, dtype=float) for k, v in cols.items()}


def flight_events(flight) -> list[tuple[str, float]]:
    """OpenRocket event names and times [s] of ``flight``, in time order."""
    s = flight.summary_values
    events = [("LAUNCH", 0.0), ("IGNITION", 0.0), ("LIFTOFF", 0.0), ("LAUNCHROD", s["rail_exit_time_s"]),
              ("BURNOUT", s["burnout_time_s"]), ("APOGEE", s["apogee_time_s"])]
    if "landing_time_s" in s:
        events.append(("GROUND_HIT", s["landing_time_s"]))
    return sorted(events, key=lambda e: e[1])


def openrocket_csv(flight, latitude: float | None = None, longitude: float | None = None, *,
                   digits: int = 10) -> str:
    """``flight`` as the text of OpenRocket's CSV export (see the module docstring)."""
    cols = openrocket_columns(flight, latitude, longitude)
    names = list(cols)
    data = np.column_stack([cols[n] for n in names])
    lines = [f"# {flight.name} (Ironbark-Opt simulation)",
             f"# {len(data)} data points written for {len(names)} variables.", "#",
             "# " + ",".join(names)]
    events, k = flight_events(flight), 0
    for t, row in zip(cols["Time (s)"], data):
        while k < len(events) and events[k][1] <= t:
            lines.append(f"# Event {events[k][0]} occurred at t={events[k][1]:.4g} seconds")
            k += 1
        lines.append(",".join("NaN" if not math.isfinite(v) else f"{v:.{digits}g}" for v in row))
    lines += [f"# Event {name} occurred at t={t:.4g} seconds" for name, t in events[k:]]
    return "\n".join(lines) + "\n"


SAMPLE_SUFFIXES = (".csv", ".parquet")


def check_samples_path(path, option: str = "--samples-out"):
    """Refuse a samples file before any work: a folder that exists, ``.csv`` or
    ``.parquet``, and for Parquet an installed pyarrow."""
    from ironbark_opt.cli.common import check_output_path

    p = check_output_path(path, option, SAMPLE_SUFFIXES)
    if p is not None and p.suffix.lower() == ".parquet":
        try:
            import pyarrow  # noqa: F401
        except ImportError:
            raise InputError("writing Parquet needs pyarrow (pip install 'ironbark-opt[dask]' or pyarrow); "
                             "or write .csv", field=option) from None
    return p


def write_samples(dispersion, path) -> None:
    """Every Monte Carlo sample (parameters and results, one row each) to
    ``path``: CSV, or Parquet (pyarrow) by the extension.  Not atomic by
    itself: the command line writes through ``ironbark_opt.cli.common.atomic_write``
    (whose temporary file keeps the extension)."""
    df = dispersion.to_dataframe()
    if Path(path).suffix.lower() == ".parquet":
        df.to_parquet(path, index=False)
    else:
        df.to_csv(path, index=False)
