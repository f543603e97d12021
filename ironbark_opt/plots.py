"""Figures of results: ``plot_x(result, ax=None, *, filename=None) -> Figure``.

Numeric-only (matplotlib).  Each function draws on ``ax`` when given (so
figures can be composed), otherwise on a new figure; ``filename`` saves it.
"""
from __future__ import annotations

import matplotlib.pyplot as plt


def _axes(ax, projection=None):
    if ax is not None:
        return ax.figure, ax
    fig = plt.figure(figsize=(7, 4.5))
    return fig, fig.add_subplot(111, projection=projection)


def _finish(fig, filename):
    if filename is not None:
        fig.savefig(filename, dpi=120, bbox_inches="tight")
    return fig


def _vs_time(flight, column, ylabel, ax, filename, scale=1.0, overlay=None, ascent_only=False):
    df = flight.to_dataframe()
    if ascent_only:     # under a parachute the body's angle of attack is not a flight quantity
        df = df[df["phase"].isin(["rail", "boost", "coast"])]
    fig, ax = _axes(ax)
    ax.plot(df["time_s"], df[column] * scale, label="Ironbark-Opt")
    if overlay is not None and column in overlay:
        ax.plot(overlay["time_s"], overlay[column] * scale, "--", label="reference")
        ax.legend()
    ax.axvline(flight.summary_values["burnout_time_s"], color="0.7", lw=0.8)
    ax.set_xlabel("time [s]")
    ax.set_ylabel(ylabel)
    ax.grid(True, alpha=0.3)
    return _finish(fig, filename)


def plot_altitude(flight, ax=None, *, filename=None, overlay=None):
    """Altitude above ground [m] vs time [s]; ``overlay`` a DataFrame with the same columns."""
    return _vs_time(flight, "altitude_agl_m", "altitude AGL [m]", ax, filename, overlay=overlay)


def plot_speed(flight, ax=None, *, filename=None, overlay=None):
    """Speed [m/s] vs time."""
    return _vs_time(flight, "speed_mps", "speed [m/s]", ax, filename, overlay=overlay)


def plot_acceleration(flight, ax=None, *, filename=None, overlay=None):
    """Acceleration magnitude [m/s^2] vs time."""
    return _vs_time(flight, "acceleration_mps2", "acceleration [m/s$^2$]", ax, filename, overlay=overlay)


def plot_mach(flight, ax=None, *, filename=None, overlay=None):
    """Mach number vs time."""
    return _vs_time(flight, "mach", "Mach [-]", ax, filename, overlay=overlay)


def plot_alpha(flight, ax=None, *, filename=None, overlay=None):
    """Total angle of attack [deg] vs time, ascent only (rail exit to apogee)."""
    return _vs_time(flight, "alpha_deg", "angle of attack [deg]", ax, filename, overlay=overlay,
                    ascent_only=True)


def plot_trajectory_3d(flight, ax=None, *, filename=None):
    """3-D trajectory (east, north, altitude AGL) [m]."""
    df = flight.to_dataframe()
    fig, ax = _axes(ax, projection="3d")
    ax.plot(df["x_east_m"], df["y_north_m"], df["altitude_agl_m"])
    ax.set_xlabel("east [m]")
    ax.set_ylabel("north [m]")
    ax.set_zlabel("altitude AGL [m]")
    return _finish(fig, filename)


def plot_flight(flight, *, filename=None, atmosphere: str | None = None):
    """Overview: altitude, speed, acceleration, Mach, angle of attack, trajectory
    (``atmosphere``: the atmosphere flown, added to the title)."""
    fig = plt.figure(figsize=(13, 8))
    panels = (plot_altitude, plot_speed, plot_acceleration, plot_mach, plot_alpha)
    for i, func in enumerate(panels):
        func(flight, fig.add_subplot(2, 3, i + 1))
    plot_trajectory_3d(flight, fig.add_subplot(2, 3, 6, projection="3d"))
    fig.suptitle(repr(flight) + (f"\n{atmosphere}" if atmosphere else ""), fontsize=10)
    fig.tight_layout()
    return _finish(fig, filename)
