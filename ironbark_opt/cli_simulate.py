"""``ironbark simulate ROCKET``: fly a rocket file to apogee (and landing)."""
from __future__ import annotations

import math

import click

from ironbark_opt.cli_common import (apply_forecast, atmosphere_load_kwargs, atmosphere_options,
                                     atmosphere_summary, emit, handle_errors, json_option, table_option)
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
@click.option("--config", "config", type=str, help="Motor configuration (OpenRocket files).")
@table_option
@atmosphere_options
@click.option("--descent/--no-descent", default=False, help="Continue to landing.")
@click.option("--jit/--no-jit", default=False, help="Compile the model to C (cached on disk).")
@click.option("--csv", "csv_path", type=click.Path(dir_okay=False, writable=True), help="Write the time series.")
@click.option("--plot", "plot_path", type=click.Path(dir_okay=False, writable=True),
              help="Write an overview figure (PNG/PDF/SVG).")
@json_option
@handle_errors
def simulate_command(rocket, rail_length, inclination_deg, heading_deg, elevation_m, rail_exit, ballast_kg,
                     ballast_x_m, config, table, atmosphere, atmosphere_time, forecast, site, time, descent, jit,
                     csv_path, plot_path, as_json):
    """Simulate ROCKET (.toml or .ork) to apogee and print the summary."""
    import dataclasses

    from ironbark_opt.flight import simulate
    from ironbark_opt.vehicle import load_setup

    kwargs = {"rail_exit": rail_exit, "table": table,
              **atmosphere_load_kwargs(atmosphere, atmosphere_time, forecast, site, time)}
    if config is not None:
        kwargs["config"] = config
    setup = apply_forecast(load_setup(rocket, **kwargs), forecast, site, time)
    if elevation_m is not None:
        setup = dataclasses.replace(setup, site_elevation=elevation_m)
    overrides = {}
    for name, value in (("rail_length", rail_length), ("ballast_mass", ballast_kg), ("ballast_x", ballast_x_m)):
        if value is not None:
            overrides[name] = value
    if inclination_deg is not None:
        overrides["inclination"] = math.radians(inclination_deg)
    if heading_deg is not None:
        overrides["heading"] = math.radians(heading_deg)
    flight = simulate(setup, parameters=overrides, descent=descent, jit=jit)
    if csv_path:
        flight.to_dataframe().to_csv(csv_path, index=False)
    if plot_path:
        import matplotlib
        matplotlib.use("Agg")
        from ironbark_opt.plots import plot_flight
        plot_flight(flight, filename=plot_path)
    result = flight.to_dict()
    result["rocket"] = setup.name
    result["atmosphere"], line = atmosphere_summary(setup)
    emit(result, as_json, flight.summary() + "\n" + line)


COMMANDS = [simulate_command]
