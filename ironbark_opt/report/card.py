"""The flight card: one printable page for the range safety officer and the
ballast bay (numeric-only).

:func:`build_card` gathers the numbers of one launch (a :class:`Flight` at
the chosen ballast, optionally the :class:`BallastSolution` and a
:class:`Dispersion`) into a :class:`FlightCard`; :func:`write_flight_card`
renders it (PDF, PNG or SVG by the extension).  The text lines on the page
are exactly :meth:`FlightCard.lines`, which ``--json`` also prints, so the
page and the JSON cannot disagree.
"""
from __future__ import annotations

import math
import textwrap
from dataclasses import dataclass, field, fields
from typing import Mapping

from ironbark_opt.errors import InputError

CARD_SUFFIXES = (".pdf", ".png", ".svg")
_FT = 0.3048
#: ballast step of the card's sensitivity line [kg]
BALLAST_STEP_KG = 0.1


@dataclass(frozen=True)
class FlightCard:
    """The numbers on a flight card (SI, unit-suffixed; None where not known).

    ``apogee_p05_m``/``apogee_p95_m`` come from a Monte Carlo (``samples``
    flights); ``landing_ellipse`` is its 1-sigma landing ellipse
    (:func:`~ironbark_opt.analysis.montecarlo.error_ellipse`);
    ``apogee_per_100g_m`` is the exact derivative of apogee with respect to
    the ballast mass times 0.1 kg.
    """

    rocket: str
    motor: str
    site: str
    launch_time: str | None
    atmosphere: str
    rail: str
    ballast_kg: float
    ballast_x_m: float
    apogee_agl_m: float
    rail_exit_speed_mps: float
    static_margin_rail_exit_cal: float
    static_margin_min_cal: float
    max_mach: float
    max_dynamic_pressure_Pa: float
    apogee_east_m: float
    apogee_north_m: float
    target_agl_m: float | None = None
    apogee_per_100g_m: float | None = None
    apogee_p05_m: float | None = None
    apogee_p95_m: float | None = None
    samples: int | None = None
    band_m: float | None = None
    probability_in_band: float | None = None
    landing_east_m: float | None = None
    landing_north_m: float | None = None
    landing_distance_m: float | None = None
    landing_ellipse: Mapping[str, float] | None = None
    #: a robust ballast solve (:class:`~ironbark_opt.optimise.robust.RobustBallastSolution`): the
    #: nominal and the robust ballast, their P(in band) on the solver's fresh-sample check and its
    #: standard errors, the paired gain, the objective and the sample counts
    robust: Mapping | None = None
    #: an ensemble hour of a launch window (``window_ensemble.card_ensemble``): the forecast, the
    #: member this card flies, and over the members the apogee median and 5-95 %, the 95 % drift,
    #: the 5 % rail-exit speed, the 95 % wind at rail exit, P(in band), members go / flown
    ensemble: Mapping | None = None
    #: the Monte Carlo and the nominal ground track (east, north) [m] (for the
    #: page's figures; not in :meth:`to_dict`)
    dispersion: object = field(default=None, repr=False, compare=False)
    track: tuple | None = field(default=None, repr=False, compare=False)

    def lines(self) -> list[tuple[str, str]]:
        """(heading or label, text) rows exactly as printed on the page; a
        heading has the text ``""``."""
        rows = [("VEHICLE AND SITE", ""), ("rocket", self.rocket), ("motor", self.motor), ("site", self.site),
                ("launch time (UTC)", self.launch_time or "not given"), ("rail", self.rail)]
        rows += [("atmosphere", part) if i == 0 else ("", part)
                 for i, part in enumerate(textwrap.wrap(self.atmosphere, 62) or ["-"])]
        rows += [("BALLAST BAY", ""), ("ballast mass", f"{self.ballast_kg:.3f} kg"),
                 ("ballast position", f"{self.ballast_x_m:.3f} m aft of the nose tip")]
        if self.apogee_per_100g_m is not None:
            rows.append(("apogee per 100 g", f"{self.apogee_per_100g_m:+.1f} m (exact derivative)"))
        rows.append(("PREDICTION", ""))
        if self.target_agl_m is not None:
            rows.append(("target apogee", f"{self.target_agl_m:.1f} m AGL ({self.target_agl_m / _FT:.0f} ft)"))
        rows.append(("predicted apogee", f"{self.apogee_agl_m:.1f} m AGL ({self.apogee_agl_m / _FT:.0f} ft)"))
        if self.apogee_p05_m is not None:
            rows.append(("apogee 5-95 %", f"{self.apogee_p05_m:.1f} to {self.apogee_p95_m:.1f} m AGL "
                                           f"({self.samples} Monte Carlo flights)"))
        else:
            rows.append(("apogee 5-95 %", "no dispersion spec given"))
        if self.probability_in_band is not None:
            rows.append((f"P(+-{self.band_m:.0f} m)", f"{self.probability_in_band:.3f} of the Monte Carlo flights "
                                                      f"within {self.band_m:.1f} m of the target"))
        rows.append(("apogee drift", f"{self.apogee_east_m:.1f} m east, {self.apogee_north_m:.1f} m north"))
        rows += self._robust_rows() + self._ensemble_rows()
        rows += [("RANGE SAFETY", ""), ("rail-exit speed", f"{self.rail_exit_speed_mps:.2f} m/s"),
                 ("stability margin", f"{self.static_margin_rail_exit_cal:.2f} cal at rail exit, "
                                      f"{self.static_margin_min_cal:.2f} cal minimum"),
                 ("max Mach", f"{self.max_mach:.3f}"),
                 ("max q", f"{self.max_dynamic_pressure_Pa / 1000:.2f} kPa")]
        if self.landing_east_m is not None:
            rows.append(("landing (nominal)", f"{self.landing_east_m:.1f} m east, {self.landing_north_m:.1f} m "
                                              f"north ({self.landing_distance_m:.1f} m from the rail)"))
        el = self.landing_ellipse
        if el is not None:
            rows.append(("landing ellipse", f"1 sigma {el['semi_major_m']:.1f} x {el['semi_minor_m']:.1f} m, "
                                            f"major axis {el['azimuth_deg']:.0f} deg from north"))
            rows.append(("", f"centre {el['center_east_m']:.1f} m east, {el['center_north_m']:.1f} m north"))
        return rows

    def _robust_rows(self) -> list[tuple[str, str]]:
        r = self.robust
        if r is None:
            return []
        rows = [("ROBUST BALLAST", ""),
                ("chosen for", f"{r['objective']} under the dispersion spec ({r['samples']} SAA samples)"),
                ("SAA optimum", f"{r['saa_optimum_ballast_kg']:.3f} kg, in-sample gain t = {r['saa_gain_t']:.2f}"
                                + {"t": ": not significant, nominal kept",
                                   "selection": ": not better on fresh samples, nominal kept"}.get(r.get("kept_by"), ""))]
        if "check_probability_in_band" not in r:
            return rows + [("check", "none asked (--check-samples 0)")]
        for label, pre in (("nominal ballast", "nominal_"), ("robust ballast", "")):
            rows.append((label, f"{r[pre + 'ballast_kg']:.3f} kg: P(+-{r['band_m']:.0f} m) "
                                f"{r[f'check_{pre}probability_in_band']:.3f} +/- "
                                f"{r[f'check_{pre}probability_in_band_stderr']:.3f}, E|miss| "
                                f"{r[f'check_{pre}expected_abs_miss_m']:.1f} m"))
        rows.append(("robust - nominal", f"P {r['check_probability_gain']:+.3f} +/- "
                                         f"{r['check_probability_gain_stderr']:.3f} ({r['check_samples']} fresh "
                                         f"flights, seed {r['check_seed']}, paired)"))
        return rows

    def _ensemble_rows(self) -> list[tuple[str, str]]:
        e = self.ensemble
        if e is None:
            return []
        rows = [(f"ENSEMBLE ({e['forecast']})", ""),
                ("this card", f"member {e['member']} (the ballast was solved on it); "
                              f"{e['members_flown']} members flown"),
                ("apogee, members", f"median {e['apogee_agl_m']:.1f} m, 5-95 % {e['apogee_p05_agl_m']:.1f} to "
                                    f"{e['apogee_p95_agl_m']:.1f} m AGL"),
                ("drift, members", f"95 % {e['apogee_drift_p95_m']:.1f} m (apogee)"),
                ("rail exit, members", f"speed 5 % {e['rail_exit_speed_p05_mps']:.2f} m/s, wind 95 % "
                                       f"{e['rail_exit_wind_p95_mps']:.2f} m/s")]
        if e.get("probability_in_band") is not None:
            rows.append((f"P(+-{e['band_m']:.0f} m)", f"{e['probability_in_band']:.3f} over the members"))
        rows.append(("members go", f"{e['members_go']} of {e['members_flown']}"))
        return rows

    def text_lines(self) -> list[str]:
        """:meth:`lines` as the strings placed on the page."""
        return [f"{label:<19s}{text}".rstrip() if text else label for label, text in self.lines()]

    def to_dict(self) -> dict:
        """Unit-suffixed numbers and the printed lines (``lines``)."""
        out = {f.name: getattr(self, f.name) for f in fields(self) if f.compare}   # not the figures' data
        out["landing_ellipse"] = None if self.landing_ellipse is None else dict(self.landing_ellipse)
        out["robust"] = None if self.robust is None else dict(self.robust)
        out["ensemble"] = None if self.ensemble is None else dict(self.ensemble)
        out["lines"] = self.text_lines()
        return out


def _site_text(setup, site_name):
    from ironbark_opt.report.geodesy import position_text

    lat, lon = getattr(setup, "latitude", None), getattr(setup, "longitude", None)
    where = []
    if site_name:
        where.append(site_name)
    if lat is not None and lon is not None:
        where.append(position_text(lat, lon))
    where.append(f"{setup.site_elevation:.1f} m ASL")
    return ", ".join(where)


def apogee_per_100g(setup, parameters: Mapping[str, float]) -> float:
    """Apogee change [m] per +100 g of ballast at ``parameters``: the exact
    (CasADi AD) derivative of :mod:`ironbark_opt.analysis.sensitivity` times 0.1 kg."""
    from ironbark_opt.analysis.sensitivity import sensitivities

    sens = sensitivities(setup, parameters=parameters, names=("ballast_mass",))
    return sens.derivative("apogee_agl_m", "ballast_mass") * BALLAST_STEP_KG


def build_card(setup, flight, *, solution=None, dispersion=None, apogee_per_100g_m: float | None = None,
               launch_time: str | None = None, site_name: str | None = None) -> FlightCard:
    """The :class:`FlightCard` of ``flight`` (flown by ``setup`` at the ballast to print).

    Parameters
    ----------
    setup : FlightSetup
    flight : Flight
        The nominal flight at the card's ballast (with descent for a landing point).
    solution : BallastSolution or RobustBallastSolution, optional
        Adds the target apogee (and a robust solve's comparison with the nominal ballast).
    dispersion : Dispersion, optional
        Monte Carlo around the same ballast: the 5-95 % apogee band and the
        landing (or apogee) ellipse.
    apogee_per_100g_m : float, optional
        From :func:`apogee_per_100g` (not computed here: it costs a Jacobian).
    launch_time, site_name : str, optional
        Printed as given (e.g. the forecast's valid time and site preset).
    """
    from ironbark_opt.atmosphere.files import describe_flown

    s, p, df = flight.summary_values, flight.parameters, flight.to_dataframe()
    d = describe_flown(setup.atmosphere)
    atmosphere = f"{d['model']}: {d['source']}" + (f", valid {d['valid_time']}" if d.get("valid_time") else "")
    if launch_time is None and d.get("valid_time"):
        launch_time = str(d["valid_time"])
    designation = " ".join(x for x in (getattr(setup.motor, "manufacturer", ""),
                                       getattr(setup.motor, "designation", "")) if x) or "(unnamed motor)"
    rail = (f"{p['rail_length']:.2f} m, {math.degrees(p['inclination']):.1f} deg above horizontal, "
            f"heading {math.degrees(p['heading']):.1f} deg")
    kw = {}
    if dispersion is not None:
        a = dispersion.stats["apogee_agl_m"]
        kw.update(apogee_p05_m=a["p05"], apogee_p95_m=a["p95"], samples=dispersion.samples)
        if "target_agl_m" in dispersion.extra:
            kw["target_agl_m"] = float(dispersion.extra["target_agl_m"])
        if "band_m" in dispersion.extra:
            kw.update(band_m=dispersion.extra["band_m"], probability_in_band=dispersion.extra["probability_in_band"])
        if dispersion.descent:
            kw["landing_ellipse"] = dict(dispersion.extra["landing_ellipse"])
    if "landing_east_m" in s:
        kw.update(landing_east_m=s["landing_east_m"], landing_north_m=s["landing_north_m"],
                  landing_distance_m=s["landing_distance_m"])
    if solution is not None:
        kw["target_agl_m"] = float(solution.values["target_agl_m"])
        if getattr(solution, "check_seed", None) is not None:           # a RobustBallastSolution
            kw["robust"] = {k: v for k, v in solution.to_dict().items() if k != "nominal_solution"}
    return FlightCard(rocket=flight.name, motor=designation, site=_site_text(setup, site_name),
                      launch_time=launch_time, atmosphere=atmosphere, rail=rail,
                      ballast_kg=p["ballast_mass"], ballast_x_m=p["ballast_x"], apogee_agl_m=s["apogee_agl_m"],
                      rail_exit_speed_mps=s["rail_exit_speed_mps"],
                      static_margin_rail_exit_cal=s["static_margin_rail_exit_cal"],
                      static_margin_min_cal=s["static_margin_min_cal"], max_mach=s["max_mach"],
                      max_dynamic_pressure_Pa=s["max_dynamic_pressure_Pa"], apogee_east_m=s["apogee_east_m"],
                      apogee_north_m=s["apogee_north_m"], apogee_per_100g_m=apogee_per_100g_m,
                      dispersion=dispersion, track=(df["x_east_m"].to_numpy(), df["y_north_m"].to_numpy()), **kw)


def _map(card, ax):
    """Landing map inset: Monte Carlo ellipses when flown, else the nominal points."""
    disp = card.dispersion
    if disp is not None:
        from ironbark_opt.analysis.plots import plot_landing_ellipse
        plot_landing_ellipse(disp, ax, atmosphere=_short(card.atmosphere, 44))         # half a page wide
    else:
        ax.plot([0.0], [0.0], "k^", ms=8, label="launch rail")
        ax.set_xlabel("east [m]")
        ax.set_ylabel("north [m]")
        ax.set_aspect("equal", adjustable="datalim")
        ax.grid(True, alpha=0.3)
        ax.set_title(f"{card.rocket}: nominal flight\n{_short(card.atmosphere)}", fontsize=10)
    if card.track is not None:
        ax.plot(*card.track, color="0.45", lw=1.0, label="ground track (nominal)")
    ens = card.ensemble or {}
    if "landing_east_m" in ens:
        ax.plot(ens["landing_east_m"], ens["landing_north_m"], "x", color="0.3", ms=5,
                label=f"{ens['forecast']} members' landings")
    ax.plot([card.apogee_east_m], [card.apogee_north_m], "D", color="C4", ms=6, label="nominal apogee")
    if card.landing_east_m is not None:
        ax.plot([card.landing_east_m], [card.landing_north_m], "X", color="C3", ms=8, label="nominal landing")
    ax.legend(fontsize=7, loc="upper center", bbox_to_anchor=(0.5, -0.13), ncol=3, frameon=False)


def _band(card, ax):
    """Apogee histogram of the Monte Carlo with the 5-95 % band and the target."""
    from ironbark_opt.analysis.plots import plot_apogee_histogram
    plot_apogee_histogram(card.dispersion, ax, atmosphere=_short(card.atmosphere, 44))
    ax.legend(fontsize=7, loc="upper center", bbox_to_anchor=(0.5, -0.13), ncol=2, frameon=False)


def _short(atmosphere: str, width: int = 64) -> str:
    """The card's atmosphere line shortened for a figure title, keeping its valid time."""
    source, _, valid = atmosphere.partition(", valid ")
    valid = f", valid {valid[:16]}" if valid else ""
    return textwrap.shorten(source, max(width - len(valid), 20), placeholder=" ...") + valid


def write_flight_card(path, card: FlightCard) -> None:
    """Render ``card`` on one A4 page: ``.pdf``, ``.png`` (150 dpi) or ``.svg``
    (text kept as text) by the extension of ``path``."""
    import matplotlib
    import matplotlib.pyplot as plt
    from pathlib import Path

    from ironbark_opt import __version__

    suffix = Path(path).suffix.lower()
    if suffix not in CARD_SUFFIXES:
        raise InputError(f"unknown file type {suffix or '(none)'!r}; expected one of {', '.join(CARD_SUFFIXES)}",
                         field="--card")
    with matplotlib.rc_context({"svg.fonttype": "none", "pdf.fonttype": 42}):
        fig = plt.figure(figsize=(8.27, 11.69))
        fig.text(0.06, 0.965, f"FLIGHT CARD  {card.rocket}", fontsize=18, weight="bold", va="top")
        fig.text(0.06, 0.935, f"{card.motor}   |   Ironbark-Opt {__version__}", fontsize=9, va="top", color="0.3")
        y, rows = 0.905, list(zip(card.lines(), card.text_lines()))
        headings = sum(1 for (_, text), _ in rows if not text)
        # rows down to 0.41 of the page at most (the figures keep 0.12 .. 0.37): a long card packs tighter
        step = min(0.0185, (y - 0.41 - 0.006 * headings) / len(rows))
        size = 9.5 * min(1.0, step / 0.0165)
        for (label, text), line in rows:
            heading = not text
            if heading:
                y -= 0.006
            fig.text(0.06, y, line, family="monospace", fontsize=size if not heading else size + 0.5,
                     weight="bold" if heading else "normal", va="top")
            y -= step
        top, bottom = min(y - 0.04, 0.37), 0.12         # room below the axes for the legends
        if card.dispersion is not None:
            _map(card, fig.add_axes([0.11, bottom, 0.36, top - bottom]))
            _band(card, fig.add_axes([0.60, bottom, 0.36, top - bottom]))
        else:
            _map(card, fig.add_axes([0.11, bottom, 0.84, top - bottom]))
        fig.savefig(path, dpi=150, format=suffix[1:])
        plt.close(fig)
