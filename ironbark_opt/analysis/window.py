"""Launch window: the rocket flown through every forecast hour.

:func:`launch_window` fetches the RAP, GFS or GEFS forecast over the site for each
hour (``forecast.setup_with_forecast``: THREDDS NCSS, NOMADS, archive, all
through :mod:`ironbark_opt.net` and its cache, so a second run is offline),
flies the nominal flight to landing, optionally solves the ballast for a
target (``solve_ballast``) and runs a Monte Carlo under a dispersion spec
with that ballast (5-95 % apogee band, P(in band)), and marks each hour go or
no-go against the user's limits: wind at rail exit, static margin at rail
exit, rail-exit speed.

RAP and GFS are deterministic forecasts: one profile per hour; the dispersion
spec (``wind_scale``, ``wind_east``/``wind_north``) carries the forecast's wind
uncertainty.  GEFS is an ensemble: every member of an hour is flown as its own
atmosphere and the hour is summarised over the members
(:mod:`ironbark_opt.analysis.window_ensemble`).

Every hour builds its own model (the profile is part of the equations) and
flies on the CasADi VM (``jit=False``): a C compile per hour would cost more
than the flights.  Numeric-only.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field
from datetime import timedelta
from typing import Mapping

import numpy as np

from ironbark_opt.errors import InputError, NetworkError

#: Per-hour numbers, their labels and units for the table and the plot.
COLUMNS = (("apogee_agl_m", "apogee", "m"), ("apogee_p05_agl_m", "apogee p05", "m"),
           ("apogee_p95_agl_m", "apogee p95", "m"), ("apogee_drift_m", "apogee drift", "m"),
           ("landing_distance_m", "landing", "m"), ("rail_exit_speed_mps", "rail exit", "m/s"),
           ("rail_exit_wind_mps", "wind@rail", "m/s"), ("static_margin_rail_exit_cal", "margin", "cal"),
           ("ballast_kg", "ballast", "kg"), ("probability_in_band", "P(band)", "-"))


@dataclass(frozen=True)
class WindowLimits:
    """Go/no-go limits (None: not checked).

    Parameters
    ----------
    max_rail_wind : float [m/s]
        Largest wind speed at the rail-exit altitude.
    min_margin : float [cal]
        Smallest static margin at rail exit.
    min_rail_speed : float [m/s]
        Smallest rail-exit speed.
    """

    max_rail_wind: float | None = None
    min_margin: float | None = None
    min_rail_speed: float | None = None

    def check(self, row: Mapping[str, float]) -> list[str]:
        """Reasons the hour is no-go (empty: go)."""
        out = []
        if self.max_rail_wind is not None and row["rail_exit_wind_mps"] > self.max_rail_wind:
            out.append(f"wind at rail exit {row['rail_exit_wind_mps']:.1f} > {self.max_rail_wind:g} m/s")
        if self.min_margin is not None and row["static_margin_rail_exit_cal"] < self.min_margin:
            out.append(f"margin {row['static_margin_rail_exit_cal']:.2f} < {self.min_margin:g} cal")
        if self.min_rail_speed is not None and row["rail_exit_speed_mps"] < self.min_rail_speed:
            out.append(f"rail exit {row['rail_exit_speed_mps']:.1f} < {self.min_rail_speed:g} m/s")
        if row.get("ballast_feasible") is False:
            out.append("target not reachable with the ballast bay")
        return out

    def to_dict(self) -> dict:
        return {"max_rail_wind_mps": self.max_rail_wind, "min_margin_cal": self.min_margin,
                "min_rail_speed_mps": self.min_rail_speed}


@dataclass(frozen=True)
class LaunchWindow:
    """Result of :func:`launch_window` (immutable).

    ``hours``: one dict per forecast hour with unit-suffixed keys
    (``time_utc``, ``valid_time_utc``, ``apogee_agl_m``, ``apogee_p05_agl_m``,
    ``apogee_p95_agl_m``, ``rail_exit_speed_mps``, ``rail_exit_wind_mps``,
    ``static_margin_rail_exit_cal``, ``static_margin_min_cal``, ``max_mach``,
    ``max_dynamic_pressure_Pa``, ``apogee_east_m``/``apogee_north_m``/``apogee_drift_m``,
    ``landing_east_m``/``landing_north_m``/``landing_distance_m``, ``ballast_kg``,
    ``ballast_x_m``, ``probability_in_band``, ``landing_ellipse`` (1-sigma, from the Monte
    Carlo: ``center_east_m``, ``semi_major_m``, ``azimuth_deg``, ...), ``go``, ``no_go_reasons``,
    ``atmosphere``),
    or ``{"time_utc", "error"}`` for an hour without a forecast.  An ensemble hour has the
    members' median under those keys, their 5 and 95 % points (``apogee_p05_agl_m``,
    ``rail_exit_wind_p95_mps``, ... see ``window_ensemble.SPREAD``), ``members_flown``,
    ``members_go``, ``members_go_fraction`` and ``members``: one row per member (``member``
    and the keys of a deterministic hour).
    """

    name: str
    motor: str
    forecast: str
    site: str
    target_agl_m: float | None
    band_m: float | None
    limits: WindowLimits
    hours: tuple
    notes: tuple = field(default_factory=tuple)
    #: ensemble members flown per hour (GEFS perturbation numbers, control first); () = deterministic
    members: tuple = ()
    min_go_fraction: float = 1.0

    def __repr__(self) -> str:
        go = sum(1 for h in self.hours if h.get("go"))
        return f"LaunchWindow({self.name!r}, {self.forecast} at {self.site}: {len(self.hours)} hours, {go} go)"

    @property
    def flown(self) -> list[dict]:
        """The hours that have a forecast."""
        return [h for h in self.hours if "error" not in h]

    def to_dict(self) -> dict:
        return {"rocket": self.name, "motor": self.motor, "forecast": self.forecast, "site": self.site,
                "target_agl_m": self.target_agl_m, "band_m": self.band_m, "limits": self.limits.to_dict(),
                "ensemble_members": len(self.members) or 1, "members": list(self.members),
                "min_go_fraction": self.min_go_fraction if self.members else None,
                "hours": [dict(h) for h in self.hours], "notes": list(self.notes)}

    def summary(self) -> str:
        """The table, one line per hour (a string)."""
        head = f"  {'time (UTC)':17s}" + "".join(f" {label:>11s}" for _, label, _ in COLUMNS) + "  go"
        units = f"  {'':17s}" + "".join(f" {'[' + unit + ']':>11s}" for _, _, unit in COLUMNS)
        lines = [f"Launch window for {self.name} on {self.motor}: {self.forecast.upper()} forecast at {self.site}"
                 + (f", target {self.target_agl_m:.0f} m AGL +/- {self.band_m:g} m" if self.target_agl_m else "")]
        if self.members:
            solved = f" (ballast solved on member {self.members[0]})" if self.target_agl_m else ""
            lines.append(f"  {len(self.members)} ensemble members per hour{solved}: median, 5 and 95 % over the "
                         "members; go = members go / flown")
        lines += [head, units]
        for h in self.hours:
            if "error" in h:
                lines.append(f"  {h['time_utc'][:16]:17s} no forecast: {h['error'].splitlines()[0][:90]}")
                continue
            cells = []
            for key, _, unit in COLUMNS:
                v = h.get(key)
                cells.append(f" {'-':>11s}" if v is None else f" {v:11.3f}" if unit in ("-", "kg") else
                             f" {v:11.2f}" if unit == "cal" else f" {v:11.1f}")
            count = f" {h['members_go']}/{h['members_flown']}" if "members_go" in h else ""
            lines.append(f"  {h['time_utc'][:16]:17s}" + "".join(cells) + (f"  GO{count}" if h["go"] else
                         f"  NO-GO{count}: " + "; ".join(h["no_go_reasons"])))
        lines += [f"  {n}" for n in self.notes]
        return "\n".join(lines)


def rail_exit_wind(setup, flight) -> float:
    """Wind speed [m/s] at the rail-exit altitude: the profile's wind there times
    ``wind_scale`` plus the constant ``wind_east``/``wind_north`` (as the RHS adds them)."""
    s, cols, p = flight.summary_values, flight._columns, flight.parameters
    h = float(np.interp(s["rail_exit_time_s"], cols["time_s"], cols["altitude_agl_m"])) + setup.site_elevation
    east, north = (float(v) for v in setup.atmosphere.wind_l(h))
    return math.hypot(p["wind_scale"] * east + p["wind_east"], p["wind_scale"] * north + p["wind_north"])


def fly_hour(setup, *, target=None, band=None, spec=None, samples=200, seed=None, ballast_options=None,
             limits: WindowLimits = WindowLimits(), objects: dict | None = None, ballast=None) -> dict:
    """The numbers of one hour (``setup`` already flies that hour's atmosphere); numeric-only.

    ``ballast`` ``(kg, x_m)``, if given, is flown instead of solving for ``target`` (which then
    only scores the Monte Carlo).  ``objects``, if given, receives what the numbers came from:
    ``flight``, ``parameters`` and, where flown, ``solution`` (the ballast) and ``dispersion``
    (the Monte Carlo), so a flight card of the hour prints the same numbers."""
    objects = {} if objects is None else objects
    from ironbark_opt.flight import flight_model, simulate

    model = flight_model(setup, jit=False)
    overrides: dict = {}
    row: dict = {}
    if ballast is not None:
        row.update(ballast_kg=float(ballast[0]), ballast_x_m=float(ballast[1]))
        overrides = {"ballast_mass": float(ballast[0]), "ballast_x": float(ballast[1])}
    elif target is not None:
        from ironbark_opt.optimise.ballast import solve_ballast
        sol = solve_ballast(setup, target, **dict(ballast_options or {}))
        row.update(ballast_kg=sol.values["ballast_kg"], ballast_x_m=sol.values["ballast_x_m"],
                   ballast_feasible=sol.feasible, target_agl_m=sol.values["target_agl_m"])
        overrides = {"ballast_mass": sol.values["ballast_kg"], "ballast_x": sol.values["ballast_x_m"]}
        objects["solution"] = sol
    flight = simulate(setup, parameters=overrides, descent=True, model=model)
    objects.update(flight=flight, parameters=dict(overrides))
    s = flight.summary_values
    for key in ("apogee_agl_m", "apogee_time_s", "apogee_east_m", "apogee_north_m", "rail_exit_speed_mps",
                "static_margin_rail_exit_cal", "static_margin_min_cal", "max_mach", "max_dynamic_pressure_Pa",
                "max_speed_mps", "launch_mass_kg", "landing_east_m", "landing_north_m", "landing_distance_m",
                "landing_time_s"):
        if key in s:
            row[key] = float(s[key])
    row["apogee_drift_m"] = math.hypot(row["apogee_east_m"], row["apogee_north_m"])
    row["rail_exit_wind_mps"] = rail_exit_wind(setup, flight)
    row.setdefault("ballast_kg", float(flight.parameters["ballast_mass"]))
    row.setdefault("ballast_x_m", float(flight.parameters["ballast_x"]))
    if spec is not None:
        from ironbark_opt.analysis.montecarlo import montecarlo
        mc = montecarlo(setup, spec, samples, seed=seed, target=target, band=band if target is not None else None,
                        parameters=overrides, progress=False, jit=False, model=model, descent=True)
        objects["dispersion"] = mc
        a = mc.stats["apogee_agl_m"]
        row.update(apogee_mean_agl_m=a["mean"], apogee_p05_agl_m=a["p05"], apogee_p95_agl_m=a["p95"],
                   monte_carlo_samples=int(samples), monte_carlo_seed=mc.seed,
                   landing_ellipse=dict(mc.extra["landing_ellipse"]))
        if "probability_in_band" in mc.extra:
            row.update(probability_in_band=mc.extra["probability_in_band"],
                       probability_in_band_stderr=mc.extra["probability_in_band_stderr"])
    reasons = limits.check(row)
    row.update(go=not reasons, no_go_reasons=reasons)
    return row


def launch_window(setup, forecast: str, site, start, hours: int, *, step_hours: int = 1, target=None,
                  band: float = 50.0, spec=None, samples: int = 200, seed: int | None = None,
                  limits: WindowLimits = WindowLimits(), ballast_options: Mapping | None = None,
                  progress=None, members: int | None = None, min_go_fraction: float = 1.0) -> LaunchWindow:
    """Fly ``setup`` through the ``forecast`` ("rap", "gfs" or "gefs") of every hour from ``start``.

    Parameters
    ----------
    setup : FlightSetup
    forecast : {"rap", "gfs", "gefs"}
    site : Site or str
        Launch-site preset (see :mod:`ironbark_opt.atmosphere.sites`).
    start : datetime or ISO 8601 str
        First hour (UTC).
    hours : int
        Number of forecast hours flown (``start``, ``start + step``, ...).
    step_hours : int
    target : str or float, optional
        Apogee target: each hour gets the ballast that hits it (and the Monte
        Carlo flies with that ballast).
    band : float [m]
        Half-width of the scoring band for P(in band).
    spec : DispersionSpec or path, optional
        Dispersions: 5-95 % apogee band and P(in band) per hour.
    samples, seed : Monte Carlo size and seed (the same samples every hour).
    limits : WindowLimits
    ballast_options : mapping, optional
        Passed to ``solve_ballast`` (``mass_max``, ``ballast_x``, ...).
    progress : callable, optional
        Called with (index, hour dict) after each hour.
    members : int, optional
        Ensemble forecasts (GEFS): fly the first ``members`` members of the dataset's Ensemble
        axis (control first; default all).  With a target the ballast is solved on the first.
    min_go_fraction : float
        Ensemble forecasts: an hour is go when at least this fraction of its members is go.

    Returns
    -------
    LaunchWindow
    """
    from ironbark_opt.analysis.distributions import DispersionSpec, load_spec
    from ironbark_opt.analysis.window_ensemble import fetch_members, fly_members
    from ironbark_opt.atmosphere.forecast import ENSEMBLES, gefs_members, setup_with_forecast
    from ironbark_opt.atmosphere.ncss import parse_iso, reuse_dataset_info
    from ironbark_opt.atmosphere.sites import get_site

    if forecast not in ENSEMBLES and members is not None:
        raise InputError(f"{forecast.upper()} is deterministic (one profile per hour): it has no members",
                         field="--members")
    if not 0.0 < min_go_fraction <= 1.0:
        raise InputError(f"must be in (0, 1], got {min_go_fraction}", field="--min-go-fraction")
    for name, value in (("hours", hours), ("step_hours", step_hours), ("samples", samples)):
        if isinstance(value, bool) or not isinstance(value, (int, np.integer)) or value < 1:
            raise InputError(f"{name} must be a positive integer, got {value!r}", field=name)
    if hours > 120:
        raise InputError(f"at most 120 hours, got {hours}", field="hours")
    where = get_site(site) if isinstance(site, str) else site
    t0 = parse_iso(start) if isinstance(start, str) else start
    if spec is not None and not isinstance(spec, DispersionSpec):
        spec = load_spec(spec)
    if spec is not None and seed is None:
        seed = spec.seed if spec.seed is not None else 0
    with reuse_dataset_info():          # one dataset.xml per collection for the whole window
        flown_members = gefs_members(members) if forecast in ENSEMBLES else ()
        rows, network_errors = [], []
        for k in range(int(hours)):
            when = t0 + timedelta(hours=k * int(step_hours))
            stamp = when.strftime("%Y-%m-%dT%H:%M:%SZ")
            try:                          # only the forecast's absence makes an hour an error row
                if flown_members:
                    fetched = fetch_members(setup, forecast, when, where, flown_members)
                    hour_setup, columns = None, fetched[0][2]
                else:
                    hour_setup, columns = setup_with_forecast(setup, forecast, when, where)
            except (InputError, NetworkError) as err:
                if isinstance(err, NetworkError):
                    network_errors.append(err)
                rows.append({"time_utc": stamp, "hour_offset_h": float(k * step_hours), "error": str(err)})
                if progress:
                    progress(k, rows[-1])
                continue
            row = {"time_utc": stamp, "hour_offset_h": float(k * step_hours),
                   "valid_time_utc": None if columns.valid_time is None else columns.valid_time.strftime(
                       "%Y-%m-%dT%H:%M:%SZ"),
                   "site_elevation_m": float(hour_setup.site_elevation if hour_setup is not None else
                                             where.elevation if columns.ground_elevation is None else
                                             columns.ground_elevation), "atmosphere": columns.source}
            if hour_setup is None:
                row.update(fly_members(fetched, target=target, band=band, spec=spec, samples=samples, seed=seed,
                                       ballast_options=ballast_options, limits=limits,
                                       min_go_fraction=min_go_fraction)[0])
            else:
                row.update(fly_hour(hour_setup, target=target, band=band, spec=spec, samples=samples,
                                    seed=seed, ballast_options=ballast_options, limits=limits))
            rows.append(row)
            if progress:
                progress(k, row)
    if not any("error" not in r for r in rows):
        text = f"no forecast for any of the {hours} hours; first: {rows[0]['error']}"
        raise NetworkError(text) if network_errors else InputError(text, field="--from")
    notes = [f"{forecast.upper()}: members {', '.join(map(str, flown_members))} flown every hour"
             if flown_members else f"{forecast.upper()} is deterministic: one profile per hour, no ensemble members"]
    if spec is not None:
        notes.append(f"Monte Carlo: {samples} samples per hour, seed {seed} (the same samples every hour)"
                     + (", flown with each hour's ballast" if target is not None else ""))
    flown = [r for r in rows if "error" not in r]
    return LaunchWindow(name=setup.name, motor=getattr(setup.motor, "designation", "motor"), forecast=forecast,
                        site=getattr(where, "name", str(site)),
                        target_agl_m=flown[0].get("target_agl_m") if target is not None else None,
                        band_m=float(band) if target is not None else None, limits=limits, hours=tuple(rows),
                        notes=tuple(notes), members=tuple(flown_members), min_go_fraction=float(min_go_fraction))


def plot_window(window: LaunchWindow, filename=None):
    """Apogee (with its 5-95 % band), drift, rail-exit speed, ballast and P(in band) against
    the hour, no-go hours shaded; an ensemble window adds the members' apogees, the 5-95 % band
    over the members of every series and the fraction of members go.  Returns the Figure (saved
    to ``filename`` if given)."""
    import matplotlib.pyplot as plt
    from matplotlib.patches import Patch

    from ironbark_opt.analysis.window_ensemble import SPREAD

    rows = window.flown
    hrs = np.array([r["hour_offset_h"] for r in rows])
    t0 = window.hours[0]["time_utc"][:16].replace("T", " ")
    apogee_label = "apogee with the hour's ballast" if window.target_agl_m else "apogee"
    panels = [("apogee AGL [m]", [("apogee_agl_m", apogee_label)]),
              ("distance [m]", [("apogee_drift_m", "apogee drift"), ("landing_distance_m", "landing distance")]),
              ("speed [m/s]", [("rail_exit_speed_mps", "rail-exit speed"),
                               ("rail_exit_wind_mps", "wind at rail exit")]),
              ("ballast [kg]", [("ballast_kg", "ballast needed" if window.target_agl_m else "ballast flown")])]
    if any("probability_in_band" in r for r in rows):
        panels.append(("P(in band) [-]", [("probability_in_band", f"P(|apogee - target| <= {window.band_m:g} m)"
                                           + (" over members" if window.members else ""))]))
    if window.members:
        panels.append(("members go [-]", [("members_go_fraction", "fraction of members go")]))
    fig, axes = plt.subplots(len(panels), 1, figsize=(8, 2.1 * len(panels) + 0.8), sharex=True)
    nogo = [r["hour_offset_h"] for r in rows if not r["go"]]
    half = 0.5 * (float(np.min(np.diff(hrs))) if hrs.size > 1 else 1.0)       # [h] shading of an hour
    for ax, (ylabel, series) in zip(axes, panels):
        for key, label in series:
            line, = ax.plot(hrs, [r.get(key, np.nan) for r in rows], "o-", ms=4,
                            label=label + (" (median of members)" if window.members and key in SPREAD else ""))
            if window.members and key in SPREAD and key != "apogee_agl_m":
                ax.fill_between(hrs, [r[SPREAD[key][0]] for r in rows], [r[SPREAD[key][1]] for r in rows],
                                color=line.get_color(), alpha=0.15, label=f"{label}: 5-95 % over members")
        if series[0][0] == "apogee_agl_m" and "apogee_p05_agl_m" in rows[0]:
            pooled = "monte_carlo_samples" in rows[0]
            ax.fill_between(hrs, [r["apogee_p05_agl_m"] for r in rows], [r["apogee_p95_agl_m"] for r in rows],
                            alpha=0.25, label="5-95 % over members" + (" x Monte Carlo" if pooled else "")
                            if window.members else "Monte Carlo 5-95 %")
        if series[0][0] == "apogee_agl_m" and window.members:
            pts = [(r["hour_offset_h"], m["apogee_agl_m"]) for r in rows for m in r["members"] if "error" not in m]
            ax.plot(*zip(*pts), ".", color="0.35", ms=3, label="members")
        if series[0][0] == "members_go_fraction":
            ax.axhline(window.min_go_fraction, color="tab:red", ls=":", lw=1, label="go threshold")
        if series[0][0] in ("members_go_fraction", "probability_in_band"):
            ax.set_ylim(-0.05, 1.05)
        if series[0][0] == "apogee_agl_m" and window.target_agl_m:
            ax.axhline(window.target_agl_m, color="k", ls="--", lw=1, label="target")
        if series[0][0] == "rail_exit_speed_mps" and window.limits.max_rail_wind is not None:
            ax.axhline(window.limits.max_rail_wind, color="tab:red", ls=":", lw=1, label="max rail wind")
        if series[0][0] == "rail_exit_speed_mps" and window.limits.min_rail_speed is not None:
            ax.axhline(window.limits.min_rail_speed, color="tab:purple", ls=":", lw=1, label="min rail-exit speed")
        for h in nogo:
            ax.axvspan(h - half, h + half, color="tab:red", alpha=0.08, lw=0)
        handles, labels = ax.get_legend_handles_labels()
        if nogo and ax is axes[0]:
            handles.append(Patch(color="tab:red", alpha=0.15))
            labels.append("no-go hour")
        ax.legend(handles, labels, fontsize=7, loc="best")
        ax.set_ylabel(ylabel)
        ax.grid(alpha=0.3)
    axes[-1].set_xlabel(f"hours after {t0} UTC [h]")
    source = rows[0].get("atmosphere", window.forecast.upper()).split(" http")[0]
    if window.members:
        source = source.replace(f" member {window.members[0]}", "")
    per_hour = (f"{len(window.members)} ensemble members per hour" if window.members else
                "one profile per hour")
    fig.suptitle(f"Launch window: {window.name} ({window.motor}) at {window.site}\n"
                 f"atmosphere: {source} forecast, {per_hour}", fontsize=10)
    fig.tight_layout()
    if filename is not None:
        fig.savefig(filename, dpi=120)
        plt.close(fig)
    return fig


def window_card(setup, window: LaunchWindow, forecast: str, site, *, hour: str | None = None, target=None,
                band: float = 50.0, spec=None, samples: int = 200, seed: int | None = None,
                limits: WindowLimits = WindowLimits(), ballast_options: Mapping | None = None):
    """The :class:`~ironbark_opt.report.card.FlightCard` of one hour of ``window``: ``hour``
    (its ``time_utc``), else the first go hour, else the first hour flown.  The hour is
    flown again exactly as :func:`launch_window` flew it (the forecast comes from the
    cache, the Monte Carlo has the same seed), so the card prints the window's numbers.
    An ensemble hour's card is its first member's flight (the control run, which the
    ballast was solved on) with the hour's numbers over the members.
    Returns ``(card, row)``; numeric-only."""
    import dataclasses

    from ironbark_opt.analysis.window_ensemble import card_ensemble
    from ironbark_opt.atmosphere.forecast import setup_with_forecast
    from ironbark_opt.atmosphere.ncss import parse_iso
    from ironbark_opt.atmosphere.sites import get_site
    from ironbark_opt.report.card import apogee_per_100g, build_card

    flown = window.flown
    if hour is not None:
        want = parse_iso(hour).strftime("%Y-%m-%dT%H:%M:%SZ")
        rows = [r for r in flown if r["time_utc"] == want]
        if not rows:
            raise InputError(f"{want} is not a flown hour of the window; flown: "
                             + ", ".join(r["time_utc"] for r in flown), field="--card-hour")
    else:
        rows = [r for r in flown if r["go"]] or flown
    row = rows[0]
    where = get_site(site) if isinstance(site, str) else site
    member = window.members[0] if window.members else None
    hour_setup, _ = setup_with_forecast(setup, forecast, parse_iso(row["time_utc"]), where, member=member)
    if spec is not None and seed is None:
        seed = row.get("monte_carlo_seed")
    objects: dict = {}
    fly_hour(hour_setup, target=target, band=band, spec=spec, samples=samples, seed=seed,
             ballast_options=ballast_options, limits=limits, objects=objects)
    card = build_card(hour_setup, objects["flight"], solution=objects.get("solution"),
                      dispersion=objects.get("dispersion"),
                      apogee_per_100g_m=apogee_per_100g(hour_setup, objects["parameters"]),
                      launch_time=row["time_utc"], site_name=getattr(where, "name", str(site)))
    if member is not None:
        card = dataclasses.replace(card, ensemble=card_ensemble(row, forecast, window.band_m))
    return card, row
