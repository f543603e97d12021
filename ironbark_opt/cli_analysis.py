"""``ironbark sensitivity ROCKET`` and ``ironbark montecarlo ROCKET``."""
from __future__ import annotations

import click

from ironbark_opt.cli_common import (apply_forecast, atmosphere_load_kwargs, atmosphere_options,
                                     atmosphere_summary, emit, handle_errors, json_option, table_option)
from ironbark_opt.vehicle import RAIL_EXIT_RULES

_FILE_OUT = click.Path(dir_okay=False, writable=True)


def _common(func):
    """Options shared by both commands (rocket file and nominal point)."""
    options = [
        click.option("--rail-exit", type=click.Choice(RAIL_EXIT_RULES), default="forward_button", show_default=True,
                     help="When the rocket counts as off the rail."),
        click.option("--config", "config", type=str, help="Motor configuration (OpenRocket files)."),
        table_option,
        click.option("--ballast", "ballast_kg", type=float, help="Ballast mass [kg] (nominal point)."),
        click.option("--ballast-x", "ballast_x_m", type=float, help="Ballast position, aft of the nose tip [m]."),
    ]
    for option in reversed(options):
        func = option(func)
    return atmosphere_options(func)


def _load(rocket, rail_exit, config, ballast_kg, ballast_x_m, table=None, weather=None):
    from ironbark_opt.vehicle import load_setup

    weather = weather or {}
    kwargs = {"rail_exit": rail_exit, "table": table, **atmosphere_load_kwargs(**weather)}
    if config is not None:
        kwargs["config"] = config
    setup = apply_forecast(load_setup(rocket, **kwargs), **weather)
    overrides = {name: value for name, value in (("ballast_mass", ballast_kg), ("ballast_x", ballast_x_m))
                 if value is not None}
    return setup, overrides


def _agg():
    import matplotlib
    matplotlib.use("Agg")


@click.command("sensitivity")
@click.argument("rocket", type=click.Path(dir_okay=False))
@click.option("--target", type=str,
              help="Apogee target (e.g. 30000ft, '3000 m ASL'): solve the ballast first and add its sensitivities.")
@click.option("--param", "names", multiple=True, metavar="NAME",
              help="Parameter to report (repeatable; default: all). Names as in ironbark_opt.params.")
@_common
@click.option("--csv", "csv_path", type=_FILE_OUT, help="Write the table (one row per parameter).")
@click.option("--plot", "plot_path", type=_FILE_OUT, help="Write a tornado chart of the apogee changes.")
@json_option
@handle_errors
def sensitivity_command(rocket, target, names, rail_exit, config, table, ballast_kg, ballast_x_m, atmosphere,
                        atmosphere_time, forecast, site, time, csv_path, plot_path, as_json):
    """Exact (AD) sensitivities of apogee, apogee time and speeds for ROCKET."""
    from ironbark_opt.analysis.sensitivity import sensitivities

    weather = dict(atmosphere=atmosphere, atmosphere_time=atmosphere_time, forecast=forecast, site=site,
                   time=time)
    setup, overrides = _load(rocket, rail_exit, config, ballast_kg, ballast_x_m, table, weather)
    if target is not None and "ballast_mass" in overrides:
        from ironbark_opt.errors import InputError
        raise InputError("--ballast and --target exclude each other: the target decides the ballast",
                         field="ballast")
    sens = sensitivities(setup, parameters=overrides, names=list(names) or None, target=target)
    if csv_path:
        sens.to_dataframe().to_csv(csv_path, index=False)
    if plot_path:
        _agg()
        from ironbark_opt.analysis.plots import plot_sensitivities
        plot_sensitivities(sens, filename=plot_path)
    result = sens.to_dict()
    result["atmosphere"], line = atmosphere_summary(setup)
    emit(result, as_json, sens.summary() + "\n" + line)


@click.command("montecarlo")
@click.argument("rocket", type=click.Path(dir_okay=False))
@click.option("--spec", "spec_path", type=click.Path(dir_okay=False), required=True,
              help="Dispersion spec (TOML: seed, [parameters.NAME] distribution = normal|uniform|file).")
@click.option("--samples", type=click.IntRange(min=1), default=1000, show_default=True, help="Number of flights.")
@click.option("--seed", type=click.IntRange(min=0), help="Random seed (overrides the spec's).")
@click.option("--descent/--no-descent", default=False, help="Fly every sample to landing (landing ellipse).")
@click.option("--target", type=str, help="Apogee target (e.g. 30000ft, 3000m) for the success probability.")
@click.option("--band", "band_m", type=float, help="Half-width of the band around the target [m].")
@_common
@click.option("--chunk", type=click.IntRange(min=1), default=250, show_default=True, help="Samples per batch.")
@click.option("--jit/--no-jit", default=False, help="Compile the model to C (cached on disk).")
@click.option("--executor", default="local", show_default=True, metavar="local|local:N|dask://HOST:PORT",
              help="Where the chunks run: this process, N local processes, or a Dask scheduler.")
@click.option("--results-dir", "results_dir", type=click.Path(file_okay=False),
              help="Stream each chunk to a Parquet file here; re-running into it resumes.")
@click.option("--progress/--no-progress", default=True, help="Progress bar on stderr.")
@click.option("--csv", "csv_path", type=_FILE_OUT, help="Write every sample (parameters and results).")
@click.option("--histogram", "hist_path", type=_FILE_OUT, help="Write the apogee histogram (PNG/PDF/SVG).")
@click.option("--ellipse", "ellipse_path", type=_FILE_OUT,
              help="Write the landing (or, without --descent, apogee) dispersion ellipses.")
@json_option
@handle_errors
def montecarlo_command(rocket, spec_path, samples, seed, descent, target, band_m, rail_exit, config, table,
                       ballast_kg, ballast_x_m, atmosphere, atmosphere_time, forecast, site, time, chunk, jit,
                       executor, results_dir, progress, csv_path, hist_path, ellipse_path, as_json):
    """Monte Carlo dispersion of ROCKET: apogee, drift and landing statistics."""
    from ironbark_opt.analysis.distributions import load_spec
    from ironbark_opt.analysis.montecarlo import montecarlo

    weather = dict(atmosphere=atmosphere, atmosphere_time=atmosphere_time, forecast=forecast, site=site,
                   time=time)
    setup, overrides = _load(rocket, rail_exit, config, ballast_kg, ballast_x_m, table, weather)
    spec = load_spec(spec_path)
    disp = montecarlo(setup, spec, samples, seed=seed, descent=descent, target=target, band=band_m, chunk=chunk,
                      progress=progress, parameters=overrides, jit=jit, executor=executor, output=results_dir)
    if csv_path:
        disp.to_dataframe().to_csv(csv_path, index=False)
    if hist_path or ellipse_path:
        _agg()
        from ironbark_opt.analysis.plots import plot_apogee_histogram, plot_landing_ellipse
        if hist_path:
            plot_apogee_histogram(disp, filename=hist_path)
        if ellipse_path:
            plot_landing_ellipse(disp, filename=ellipse_path)
    result = disp.to_dict()
    result["atmosphere"], line = atmosphere_summary(setup)
    emit(result, as_json, disp.summary() + "\n" + line)


COMMANDS = [sensitivity_command, montecarlo_command]
