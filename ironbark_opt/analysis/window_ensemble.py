"""Launch window over an ensemble forecast (GEFS): every member of an hour flown.

Each member is its own atmosphere (``forecast.setup_with_forecast(...,
member=m)``) and is flown by :func:`~ironbark_opt.analysis.window.fly_hour`
exactly as a deterministic hour.  With a target, the ballast is solved once
per hour on the first member (the control run, perturbation number 0): one
ballast is loaded, so every member flies that ballast and the spread of
their apogees is what the weather's uncertainty does to it.

Per hour, over the members: the median and the 5 and 95 % points
(``numpy.percentile``, linear interpolation; Hyndman & Fan 1996, definition 7)
of apogee, drift, landing distance, rail-exit speed, wind at rail exit and
static margin; P(in band) as the fraction of members whose apogee is within
the band of the target (with a dispersion spec: the members' Monte Carlo
flights pooled, equal weight per member); and the go/no-go of every member
counted: the hour is go when at least ``min_go_fraction`` of its members are.
Numeric-only.
"""
from __future__ import annotations

import math

import numpy as np

from ironbark_opt.errors import InputError, NetworkError

#: member number -> (median key, 5 % key, 95 % key) summarised over the members
SPREAD = {"apogee_agl_m": ("apogee_p05_agl_m", "apogee_p95_agl_m"),
          "apogee_drift_m": ("apogee_drift_p05_m", "apogee_drift_p95_m"),
          "landing_distance_m": ("landing_distance_p05_m", "landing_distance_p95_m"),
          "rail_exit_speed_mps": ("rail_exit_speed_p05_mps", "rail_exit_speed_p95_mps"),
          "rail_exit_wind_mps": ("rail_exit_wind_p05_mps", "rail_exit_wind_p95_mps"),
          "static_margin_rail_exit_cal": ("static_margin_rail_exit_p05_cal", "static_margin_rail_exit_p95_cal")}
#: the same for every member (the hour's ballast, solved on the control run)
SHARED = ("ballast_kg", "ballast_x_m", "ballast_feasible", "target_agl_m", "launch_mass_kg")


def fetch_members(setup, forecast: str, when, where, members) -> list:
    """Every member's atmosphere for one hour: ``(member, setup, ProfileColumns)`` per member, or
    ``{"member", "error"}`` for a later member without a forecast (listed, not counted).

    The first member must have a forecast (else its InputError/NetworkError is raised: the hour
    has none).  Only fetching is caught here; the flights (:func:`fly_members`) are not, so a
    flight's own error (e.g. a target below the site) is raised as on a deterministic hour."""
    from ironbark_opt.atmosphere.forecast import setup_with_forecast

    out = []
    for m in members:
        try:
            m_setup, columns = setup_with_forecast(setup, forecast, when, where, member=m)
        except (InputError, NetworkError) as err:
            if not out:
                raise
            out.append({"member": m, "error": str(err)})
            continue
        out.append((m, m_setup, columns))
    return out


def fly_members(fetched, *, target=None, band=50.0, spec=None, samples=200, seed=None, ballast_options=None,
                limits=None, min_go_fraction: float = 1.0) -> tuple[dict, object]:
    """Fly every member :func:`fetch_members` returned: ``(hour row, ProfileColumns of the first member)``."""
    from ironbark_opt.analysis.window import WindowLimits, fly_hour

    limits = WindowLimits() if limits is None else limits
    rows, columns0, ballast, pooled = [], None, None, []
    for item in fetched:
        if isinstance(item, dict):
            rows.append(item)
            continue
        m, m_setup, columns = item
        got: dict = {}
        row = {"member": m, "valid_time_utc": None if columns.valid_time is None else
               columns.valid_time.strftime("%Y-%m-%dT%H:%M:%SZ"), "atmosphere": columns.source}
        row.update(fly_hour(m_setup, target=target, band=band, spec=spec, samples=samples, seed=seed,
                            ballast_options=ballast_options, limits=limits, ballast=ballast, objects=got))
        if columns0 is None:
            columns0 = columns
            if target is not None:
                ballast = (row["ballast_kg"], row["ballast_x_m"])
        if "dispersion" in got:
            pooled.append(got["dispersion"].column("apogee_agl_m"))
        rows.append(row)
    return summarise(rows, band=band if target is not None else None, pooled=pooled,
                     min_go_fraction=min_go_fraction), columns0


def summarise(rows, *, band=None, pooled=(), min_go_fraction: float = 1.0) -> dict:
    """The hour row of the member rows (see the module docstring)."""
    flown = [r for r in rows if "error" not in r]
    first = flown[0]
    out = {k: first[k] for k in SHARED if k in first}
    for key, (k05, k95) in SPREAD.items():
        v = np.array([r[key] for r in flown if key in r], dtype=float)
        if v.size:
            out[key], out[k05], out[k95] = (float(x) for x in np.percentile(v, [50.0, 5.0, 95.0]))
    out["static_margin_min_cal"] = min(r["static_margin_min_cal"] for r in flown)
    out["max_mach"] = max(r["max_mach"] for r in flown)
    out["max_dynamic_pressure_Pa"] = max(r["max_dynamic_pressure_Pa"] for r in flown)
    target = first.get("target_agl_m")
    if band is not None and target is not None:
        if pooled:
            apo = np.concatenate(pooled)
            out["apogee_p05_agl_m"], out["apogee_p95_agl_m"] = (float(x) for x in np.percentile(apo, [5.0, 95.0]))
            out["monte_carlo_samples"] = int(apo.size)
        else:
            apo = np.array([r["apogee_agl_m"] for r in flown])
        prob = float(np.mean(np.abs(apo - target) <= band))
        # binomial standard error of a proportion, sqrt(p (1 - p) / n)
        out.update(probability_in_band=prob, probability_in_band_stderr=math.sqrt(prob * (1 - prob) / apo.size))
    go = [r for r in flown if r["go"]]
    out.update(members_flown=len(flown), members_go=len(go), members_go_fraction=len(go) / len(flown))
    reasons = [f"member {r['member']}: {r['no_go_reasons'][0]}" for r in flown if not r["go"]]
    out["go"] = len(go) / len(flown) >= min_go_fraction
    out["no_go_reasons"] = [] if out["go"] else (
        [f"{len(flown) - len(go)}/{len(flown)} members no-go (go needs {min_go_fraction:.0%})"] + reasons[:3])
    out["members"] = rows
    return out


def card_ensemble(row: dict, forecast: str, band=None) -> dict:
    """The ensemble numbers a flight card of an ensemble hour prints (from the hour's row)."""
    keys = ("apogee_agl_m", "apogee_p05_agl_m", "apogee_p95_agl_m", "apogee_drift_p95_m",
            "rail_exit_speed_p05_mps", "rail_exit_wind_p95_mps", "members_flown", "members_go",
            "probability_in_band")
    flown = [m for m in row["members"] if "error" not in m]
    out = {"forecast": forecast.upper(), "member": flown[0]["member"], "band_m": band}
    out.update({k: row[k] for k in keys if k in row})
    if all("landing_east_m" in m for m in flown):     # every member's landing point, for the map
        out.update(landing_east_m=[m["landing_east_m"] for m in flown],
                   landing_north_m=[m["landing_north_m"] for m in flown])
    return out
