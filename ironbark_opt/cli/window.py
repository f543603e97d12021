"""``ironbark window ROCKET --forecast rap|gfs|gefs --site S --from T0 --hours N``: the launch window."""
from __future__ import annotations

import click

from ironbark_opt.cli.common import (PLOT_SUFFIXES, atomic_write, check_output_path, emit, forecast_option,
                                     handle_errors, json_option, site_option)


@click.command("window")
@click.argument("rocket", type=click.Path(dir_okay=False))
@forecast_option(required=True, choices=("rap", "gfs", "gefs"),
                 help="NOAA forecast flown for every hour (gefs: every ensemble member of every hour).")
@site_option
@click.option("--from", "start", required=True, metavar="ISO", help="First launch hour, ISO 8601 UTC.")
@click.option("--hours", type=int, default=12, show_default=True, help="Number of forecast hours flown.")
@click.option("--step-hours", type=int, default=1, show_default=True, help="Hours between flights.")
@click.option("--target", help="Target apogee: each hour gets the ballast that hits it (e.g. 10000ft).")
@click.option("--band", type=float, default=50.0, show_default=True,
              help="Half-width of the scoring band for P(|apogee - target| <= band) [m].")
@click.option("--spec", "spec_path", type=click.Path(dir_okay=False),
              help="Dispersion spec (dispersions.toml): 5-95 %% apogee band and P(in band) per hour.")
@click.option("--samples", type=int, default=100, show_default=True, help="Monte Carlo samples per hour.")
@click.option("--seed", type=int, help="Monte Carlo seed (default: the spec's).")
@click.option("--max-rail-wind", type=float, help="No-go above this wind speed at rail exit [m/s].")
@click.option("--min-margin", type=float, help="No-go below this static margin at rail exit [calibers].")
@click.option("--min-rail-speed", type=float, help="No-go below this rail-exit speed [m/s].")
@click.option("--members", type=int, help="GEFS: fly the first N ensemble members (control first; "
                                          "default all the dataset has).")
@click.option("--min-go-fraction", type=float, default=1.0, show_default=True,
              help="GEFS: an hour is go when at least this fraction of its members is go.")
@click.option("--max-ballast", type=float, help="Most ballast the bay holds [kg].")
@click.option("--ballast-x", type=float, help="Ballast position, aft of the nose tip [m].")
@click.option("--plot", "plot_path", type=click.Path(dir_okay=False, writable=True),
              help="Plot apogee, drift, rail-exit speed, ballast and P(in band) against the hour (PNG/PDF/SVG).")
@click.option("--card", "card_path", type=click.Path(dir_okay=False, writable=True),
              help="Write the flight card (PDF/PNG/SVG) of one hour: --card-hour, else the first go hour.")
@click.option("--card-hour", metavar="ISO", help="The hour of --card (a flown hour, ISO 8601 UTC).")
@json_option
@handle_errors
def window_command(rocket, forecast, site, start, hours, step_hours, target, band, spec_path, samples, seed,
                   max_rail_wind, min_margin, min_rail_speed, members, min_go_fraction, max_ballast, ballast_x,
                   plot_path, card_path, card_hour, as_json):
    """Fly ROCKET through every forecast hour of a launch window: table, plot, go/no-go."""
    from ironbark_opt.analysis.window import WindowLimits, launch_window, plot_window
    from ironbark_opt.atmosphere.ncss import parse_iso
    from ironbark_opt.atmosphere.sites import get_site
    from ironbark_opt.errors import InputError
    from ironbark_opt.optimise.target import parse_target
    from ironbark_opt.validate import number
    from ironbark_opt.vehicle import load_setup

    check_output_path(plot_path, "--plot", PLOT_SUFFIXES)
    from ironbark_opt.report.card import CARD_SUFFIXES
    check_output_path(card_path, "--card", CARD_SUFFIXES)
    if card_hour is not None and card_path is None:
        raise click.UsageError("--card-hour needs --card FILE")
    if site is None:
        raise click.UsageError("window needs --site NAME (see 'ironbark weather sites')")
    where = get_site(site)
    try:
        t0 = parse_iso(start)
    except InputError as err:
        raise InputError(err.message, field="--from") from None
    for value, option in ((band, "--band"), (max_rail_wind, "--max-rail-wind"), (min_margin, "--min-margin"),
                          (min_rail_speed, "--min-rail-speed"), (max_ballast, "--max-ballast"),
                          (min_go_fraction, "--min-go-fraction")):
        if value is not None:
            try:
                number(value, option)
            except InputError as err:
                raise InputError(err.message, field=option) from None
    if band <= 0:
        raise InputError(f"must be > 0 m, got {band}", field="--band")
    for value, option in ((hours, "--hours"), (step_hours, "--step-hours"), (samples, "--samples"),
                          (1 if members is None else members, "--members")):
        if value < 1:
            raise InputError(f"must be >= 1, got {value}", field=option)
    if target is not None:
        parse_target(target)
    spec = None
    if spec_path is not None:
        from ironbark_opt.analysis.distributions import load_spec
        spec = load_spec(spec_path)
    setup = load_setup(rocket)
    limits = WindowLimits(max_rail_wind=max_rail_wind, min_margin=min_margin, min_rail_speed=min_rail_speed)

    def progress(k, row):       # flown hours only: a run where none flies ends in one error line
        if not as_json and "error" not in row:
            click.echo(f"  {row['time_utc']}: flown, {'go' if row['go'] else 'no-go'}", err=True)

    from ironbark_opt.atmosphere.ncss import reuse_dataset_info

    with reuse_dataset_info():      # the window and its card ask the same collection
        result = launch_window(setup, forecast, where, t0, hours, step_hours=step_hours, target=target, band=band,
                               spec=spec, samples=samples, seed=seed, limits=limits,
                               ballast_options={"mass_max": max_ballast, "ballast_x": ballast_x},
                               progress=progress, members=members, min_go_fraction=min_go_fraction)
        if plot_path:
            atomic_write(plot_path, lambda tmp: plot_window(result, tmp))
        out = result.to_dict()
        text = result.summary()
        if card_path:
            import matplotlib
            matplotlib.use("Agg")
            from ironbark_opt.analysis.window import window_card
            from ironbark_opt.report.card import write_flight_card
            card, row = window_card(setup, result, forecast, where, hour=card_hour, target=target, band=band,
                                    spec=spec, samples=samples, seed=seed, limits=limits,
                                    ballast_options={"mass_max": max_ballast, "ballast_x": ballast_x})
            atomic_write(card_path, lambda tmp: write_flight_card(tmp, card))
            out["flight_card"] = {"time_utc": row["time_utc"], **card.to_dict()}
            text += f"\nflight card of {row['time_utc']}: {card_path}"
    emit(out, as_json, text)


COMMANDS = [window_command]
