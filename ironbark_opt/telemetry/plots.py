"""Figures of a flight comparison and of a calibration's residuals (numeric-only)."""
from __future__ import annotations

_LABELS = {"altitude": "altitude AGL [m]", "vertical_speed": "vertical speed [m/s]",
           "acceleration": "axial acceleration - g [m/s²]"}


def plot_comparison(comparison, *, filename=None, title=None):
    """Altitude, speed and acceleration, simulated vs logged, on one figure (stacked axes)."""
    import matplotlib.pyplot as plt

    log, sim = comparison.to_dataframe(), comparison.simulated()
    chans = [c for c in _LABELS if c in log]
    fig, axes = plt.subplots(len(chans), 1, sharex=True, figsize=(8, 2.6 * len(chans) + 0.6), squeeze=False)
    t_end = max(comparison.errors["logged_apogee_time_s"], comparison.errors["simulated_apogee_time_s"]) \
        + comparison.time_shift_s + 3.0
    view = log["time_s"] <= t_end
    for ax, c in zip(axes[:, 0], chans):
        ax.plot(log["time_s"][view], log[c][view], ".", ms=2, color="0.35", label="logged")
        ax.plot(sim["time_s"], sim[c], "-", color="tab:red", lw=1.4, label="simulated")
        ax.set_ylabel(_LABELS[c])
        ax.grid(alpha=0.3)
    axes[0, 0].legend(loc="lower right")
    axes[-1, 0].set_xlabel("time from launch detection [s]")
    axes[-1, 0].set_xlim(min(-0.5, comparison.time_shift_s - 0.5), t_end)
    e = comparison.errors
    fig.suptitle(title or f"{comparison.rocket}: apogee error {e['apogee_error_m']:+.1f} m, "
                          f"time {e['apogee_time_error_s']:+.2f} s")
    fig.tight_layout()
    if filename:
        fig.savefig(filename, dpi=120)
    return fig


def plot_residuals(calibration, *, filename=None):
    """Residuals (simulated - logged) per channel over the fit window."""
    import matplotlib.pyplot as plt

    res = calibration.residuals
    chans = list(calibration.channels)
    fig, axes = plt.subplots(len(chans), 1, sharex=True, figsize=(8, 2.4 * len(chans) + 0.6), squeeze=False)
    for ax, c in zip(axes[:, 0], chans):
        r = res[res["channel"] == c]
        ax.plot(r["time_s"], r["residual"], ".", ms=2, color="tab:blue")
        s = calibration.noise[c]
        ax.axhspan(-2 * s, 2 * s, color="0.85", label="±2 σ log noise")
        ax.axhline(0, color="k", lw=0.8)
        ax.set_ylabel(f"{c} residual [{ {'altitude': 'm', 'vertical_speed': 'm/s'}.get(c, 'm/s²')}]")
        ax.grid(alpha=0.3)
    axes[0, 0].legend(loc="upper right")
    axes[-1, 0].set_xlabel("time from launch detection [s]")
    vals = ", ".join(f"{k} {v:.4g}" for k, v in calibration.values.items())
    fig.suptitle(f"Calibration residuals ({vals})", fontsize=9)
    fig.tight_layout()
    if filename:
        fig.savefig(filename, dpi=120)
    return fig
