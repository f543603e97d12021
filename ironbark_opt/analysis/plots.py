"""Figures of Monte Carlo and sensitivity results.

Numeric-only (matplotlib).  As in :mod:`ironbark_opt.plots`: each function
draws on ``ax`` when given, otherwise on a new figure, saves to ``filename``
when given and returns the figure.
"""
from __future__ import annotations

import math

import numpy as np

from ironbark_opt.analysis.montecarlo import ELLIPSE_CONTENT, ellipse_points, error_ellipse  # noqa: F401 (re-export)
from ironbark_opt.errors import InputError
from ironbark_opt.plots import _axes, _finish


def _title(text: str, atmosphere: str | None) -> str:
    return text if not atmosphere else f"{text}\n{atmosphere}"


def plot_apogee_histogram(dispersion, ax=None, *, filename=None, bins: int | str = "auto",
                          atmosphere: str | None = None):
    """Histogram of apogee AGL [m] with mean, 5-95 % range, target and band.

    Parameters
    ----------
    dispersion : Dispersion
    bins : int or str
        As in :func:`numpy.histogram_bin_edges`.
    atmosphere : str, optional
        The atmosphere flown, a second title line.
    """
    apo = dispersion.to_dataframe()["apogee_agl_m"].to_numpy()
    s = dispersion.stats["apogee_agl_m"]
    fig, ax = _axes(ax)
    ax.hist(apo, bins=bins, color="C0", alpha=0.75)
    ax.axvline(s["mean"], color="k", lw=1.2, label=f"mean {s['mean']:.1f} m (std {s['std']:.1f} m)")
    ax.axvspan(s["p05"], s["p95"], color="0.85", zorder=0, label="5-95 %")
    extra = dispersion.extra
    if "target_agl_m" in extra:
        ax.axvline(extra["target_agl_m"], color="C3", lw=1.2, ls="--", label=f"target {extra['target_agl_m']:.1f} m")
        if "band_m" in extra:
            t, b = extra["target_agl_m"], extra["band_m"]
            ax.axvspan(t - b, t + b, color="C3", alpha=0.12, zorder=0,
                       label=f"+/- {b:.0f} m: P = {extra['probability_in_band']:.2f}")
    ax.set_xlabel("apogee AGL [m]")
    ax.set_ylabel("samples")
    ax.set_title(_title(f"{dispersion.name}: {dispersion.samples} samples", atmosphere), fontsize=10)
    ax.legend(fontsize=8)
    ax.grid(True, alpha=0.3)
    return _finish(fig, filename)


def plot_landing_ellipse(dispersion, ax=None, *, filename=None, which: str = "auto", sigmas=(1, 2, 3),
                         atmosphere: str | None = None):
    """Scatter of landing (or apogee) points with their 1/2/3-sigma ellipses.

    Parameters
    ----------
    dispersion : Dispersion
    which : {"auto", "landing", "apogee"}
        ``auto``: landing points when the run flew to landing, else apogee.
    sigmas : sequence of float
        Ellipse sizes; a Gaussian scatter has ``1 - exp(-k^2/2)`` of its
        points inside the k-sigma ellipse (39 %, 86 %, 99 %).
    atmosphere : str, optional
        The atmosphere flown, a second title line.
    """
    east, north, which = dispersion.positions(which)
    el = error_ellipse(east, north)
    fig, ax = _axes(ax)
    ax.plot(east, north, ".", ms=3, alpha=0.5, color="C0", label=f"{which} points")
    for i, k in enumerate(sigmas):
        e, n = ellipse_points(el, k)
        content = ELLIPSE_CONTENT.get(k, 1.0 - math.exp(-k * k / 2.0))
        ax.plot(e, n, color=f"C{i + 1}", lw=1.2, label=f"{k:g} sigma ({100 * content:.0f} %)")
    ax.plot([0.0], [0.0], "k^", ms=8, label="launch rail")
    ax.set_xlabel("east [m]")
    ax.set_ylabel("north [m]")
    ax.set_aspect("equal", adjustable="datalim")
    ax.set_title(_title(f"{dispersion.name}: {which} dispersion, {dispersion.samples} samples", atmosphere),
                 fontsize=10)
    ax.legend(fontsize=8)
    ax.grid(True, alpha=0.3)
    return _finish(fig, filename)


def plot_sensitivities(sens, ax=None, *, filename=None, output: str = "apogee_agl_m", top: int | None = None):
    """Tornado chart: change of ``output`` per natural parameter step.

    Parameters
    ----------
    sens : Sensitivities
    output : str
        ``apogee_agl_m``, ``apogee_time_s``, ``rail_exit_speed_mps``,
        ``max_speed_mps``, or ``ballast_kg`` (needs a target).
    top : int, optional
        Only the ``top`` largest.
    """
    labels = {"apogee_agl_m": "apogee [m]", "apogee_time_s": "apogee time [s]",
              "rail_exit_speed_mps": "rail exit speed [m/s]", "max_speed_mps": "max speed [m/s]",
              "ballast_kg": "optimal ballast [kg]"}
    if output not in labels:
        raise InputError(f"unknown output {output!r}; expected one of {', '.join(labels)}", field="output")
    unit = labels[output]
    if output == "ballast_kg":
        if sens.ballast is None:
            raise InputError("no optimal-ballast sensitivities: give a target", field="output")
        items = [(sens.step(n)[1], sens.ballast_change(n)) for n in sens.names if sens.ballast_change(n) is not None]
    else:
        items = [(sens.step(n)[1], sens.change(output, n)) for n in sens.names]
    items.sort(key=lambda it: abs(it[1]))
    if top is not None:
        items = items[-int(top):]
    fig, ax = _axes(ax)
    values = [v for _, v in items]
    ax.barh(range(len(items)), values, color=["C3" if v < 0 else "C2" for v in values])
    ax.set_yticks(range(len(items)), [label for label, _ in items], fontsize=8)
    ax.axvline(0.0, color="k", lw=0.8)
    ax.set_xlabel(f"change of {unit} per step")
    ax.set_title(f"{sens.name}: sensitivities", fontsize=10)
    ax.grid(True, axis="x", alpha=0.3)
    return _finish(fig, filename)
