"""``ironbark simulate ROCKET``: fly a rocket file to apogee (and landing)."""
from __future__ import annotations

import click

from ironbark_opt.cli.common import (PLOT_SUFFIXES, apply_forecast, atmosphere_load_kwargs,
                                     atmosphere_label, atmosphere_options, atmosphere_summary, atomic_write,
                                     atomic_write_text,
                                     check_output_path, emit, handle_errors, json_option, table_option)
from ironbark_opt.vehicle import RAIL_EXIT_RULES


@click.command("simulate")
@click.argument("rocket", type=click.Path(dir_okay=False))
@click.option("--rail-length", type=float, help="Rail length [m] (default: from the file).")
@click.option("--inclination", "inclination_deg", type=float, help="Rail angle above horizontal [deg].")
@click.option("--heading", "heading_deg", type=float, help="Rail heading, clockwise from north [deg].")
@click.option("--elevation", "elevation_m", type=float, help="Site elevation above sea level [m].")
@click.option("--rail-exit", type=click.Choice(RAIL_EXIT_RULES), default="forward_button", show_default=True,
              help="When the rocket counts as off the rail.")
@click.option("--ballast", "ballast_kg", type=float, help="Ballast mass [kg].")
@click.option("--ballast-x", "ballast_x_m", type=float, help="Ballast position, aft of the nose tip [m].")
@click.option("--config", "config", type=str, help="Motor configuration, or a stored simulation by name (OpenRocket files; its launch conditions too).")
@table_option
@click.option("--calibration", "calibration_path", type=click.Path(dir_okay=False),
              help="Apply a calibration file (from 'ironbark calibrate --output').")
@atmosphere_options
@click.option("--descent/--no-descent", default=False, help="Continue to landing.")
@click.option("--jit/--no-jit", default=None,
              help="Compile the model to C now / never (default: compiled when cached, else compiled in the background).")
@click.option("--csv", "csv_path", type=click.Path(dir_okay=False, writable=True), help="Write the time series.")
@click.option("--csv-format", type=click.Choice(["ironbark", "openrocket"]), default="ironbark", show_default=True,
              help="Columns of --csv: Ironbark-Opt's SI names, or OpenRocket's 'Export as CSV' layout.")
@click.option("--kml", "kml_path", type=click.Path(dir_okay=False, writable=True),
              help="Write the trajectory for Google Earth (KML; needs the site's latitude/longitude).")
@click.option("--plot", "plot_path", type=click.Path(dir_okay=False, writable=True),
              help="Write an overview figure (PNG/PDF/SVG).")
@click.option("--allow-unstable", is_flag=True, help="Fly a rocket whose static margin falls below zero.")
@json_option
@handle_errors
def simulate_command(rocket, rail_length, inclination_deg, heading_deg, elevation_m, rail_exit, ballast_kg,
                     ballast_x_m, config, table, calibration_path, atmosphere, atmosphere_time, forecast,
                     site, time, descent, jit, csv_path, csv_format, kml_path, plot_path, allow_unstable, as_json):
    """Simulate ROCKET (.toml or .ork) to apogee and print the summary."""
    import dataclasses

    from ironbark_opt.flight import simulate
    from ironbark_opt.report.geodesy import site_position
    from ironbark_opt.vehicle import load_setup

    from ironbark_opt.plausibility import check_ascent_stability, check_flight_inputs, option_overrides

    check_output_path(csv_path, "--csv", (".csv", ".txt"))
    check_output_path(plot_path, "--plot", PLOT_SUFFIXES)
    check_output_path(kml_path, "--kml", (".kml",))
    if csv_format != "ironbark" and csv_path is None:
        raise click.UsageError("--csv-format needs --csv FILE")
    kwargs = {"rail_exit": rail_exit, "table": table,
              **atmosphere_load_kwargs(atmosphere, atmosphere_time, forecast, site, time)}
    if config is not None:
        kwargs["config"] = config
    setup = apply_forecast(load_setup(rocket, **kwargs), forecast, site, time)
    if calibration_path is not None:
        from ironbark_opt.telemetry.calibration_file import apply_calibration
        setup = apply_calibration(setup, calibration_path)
    opts = option_overrides(setup, rail_length=rail_length, inclination_deg=inclination_deg,
                            heading_deg=heading_deg, elevation_m=elevation_m, ballast_kg=ballast_kg,
                            ballast_x_m=ballast_x_m, body_length=setup.body_length)
    if opts["site_elevation"] is not None:
        setup = dataclasses.replace(setup, site_elevation=opts["site_elevation"])
    overrides = opts["parameters"]
    check_flight_inputs(setup, {**setup.nominal, **overrides}, allow_unstable=allow_unstable)
    if kml_path:
        site_position(setup, "--kml")            # refused before the flight when the site is unknown
    flight = simulate(setup, parameters=overrides, descent=descent, jit="auto" if jit is None else jit)
    check_ascent_stability(setup, allow_unstable=allow_unstable, summary=flight.summary_values)
    result = flight.to_dict()
    result["rocket"] = setup.name
    result["recovery_devices"] = len(setup.parachutes)
    result["atmosphere"], line = atmosphere_summary(setup)
    if csv_path and csv_format == "openrocket":
        from ironbark_opt.report.exports import openrocket_csv
        atomic_write_text(csv_path, openrocket_csv(flight, setup.latitude, getattr(setup, "longitude", None)))
    elif csv_path:
        atomic_write(csv_path, lambda tmp: flight.to_dataframe().to_csv(tmp, index=False))
    if kml_path:
        from ironbark_opt.report.kml import flight_kml
        atomic_write_text(kml_path, flight_kml(flight, *site_position(setup), atmosphere=atmosphere_label(setup)))
    if plot_path:
        import matplotlib
        matplotlib.use("Agg")
        from ironbark_opt.plots import plot_flight
        atomic_write(plot_path, lambda tmp: plot_flight(flight, filename=tmp, atmosphere=atmosphere_label(setup)))
    emit(result, as_json, flight.summary() + "\n" + line)


COMMANDS = [simulate_command]
