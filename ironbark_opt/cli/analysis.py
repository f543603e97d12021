"""``ironbark sensitivity ROCKET`` and ``ironbark montecarlo ROCKET``."""
from __future__ import annotations

import sys

import click

from ironbark_opt.cli.common import (PLOT_SUFFIXES, apply_forecast, atmosphere_load_kwargs,
                                     atmosphere_label, atmosphere_options, atmosphere_summary, atomic_write,
                                     atomic_write_text,
                                     check_output_path, emit, handle_errors, json_option, table_option)
from ironbark_opt.vehicle import RAIL_EXIT_RULES

_FILE_OUT = click.Path(dir_okay=False, writable=True)
#: Most Monte Carlo flights per run (~120 bytes each per output column set; split bigger studies by --seed).
MAX_SAMPLES = 1_000_000


def _common(func):
    """Options shared by both commands (rocket file and nominal point)."""
    options = [
        click.option("--rail-exit", type=click.Choice(RAIL_EXIT_RULES), default="forward_button", show_default=True,
                     help="When the rocket counts as off the rail."),
        click.option("--config", "config", type=str, help="Motor configuration, or a stored simulation by name (OpenRocket files; its launch conditions too)."),
        table_option,
        click.option("--ballast", "ballast_kg", type=float, help="Ballast mass [kg] (nominal point)."),
        click.option("--ballast-x", "ballast_x_m", type=float, help="Ballast position, aft of the nose tip [m]."),
        click.option("--allow-unstable", is_flag=True,
                     help="Accept a static margin below zero (at launch or on the nominal ascent)."),
    ]
    for option in reversed(options):
        func = option(func)
    return atmosphere_options(func)


def _load(rocket, rail_exit, config, ballast_kg, ballast_x_m, table=None, allow_unstable=False,
          weather=None):
    from ironbark_opt.vehicle import load_setup

    weather = weather or {}
    kwargs = {"rail_exit": rail_exit, "table": table, **atmosphere_load_kwargs(**weather)}
    if config is not None:
        kwargs["config"] = config
    setup = apply_forecast(load_setup(rocket, **kwargs), **weather)
    from ironbark_opt.plausibility import check_flight_inputs, option_overrides
    overrides = option_overrides(setup, ballast_kg=ballast_kg, ballast_x_m=ballast_x_m,
                                 body_length=setup.body_length)["parameters"]
    check_flight_inputs(setup, {**setup.nominal, **overrides}, allow_unstable=allow_unstable)
    return setup, overrides


def _margin_line(margin: dict) -> str:
    return f"  min static margin  {margin['static_margin_min_cal']:10.2f} cal at " \
           f"{margin['static_margin_min_time_s']:.2f} s"


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
def sensitivity_command(rocket, target, names, rail_exit, config, table, ballast_kg, ballast_x_m,
                        allow_unstable, atmosphere, atmosphere_time, forecast, site, time, csv_path,
                        plot_path, as_json):
    """Exact (AD) sensitivities of apogee, apogee time and speeds for ROCKET."""
    from ironbark_opt.analysis.sensitivity import sensitivities

    check_output_path(csv_path, "--csv", (".csv", ".txt"))
    check_output_path(plot_path, "--plot", PLOT_SUFFIXES)
    weather = dict(atmosphere=atmosphere, atmosphere_time=atmosphere_time, forecast=forecast, site=site,
                   time=time)
    setup, overrides = _load(rocket, rail_exit, config, ballast_kg, ballast_x_m, table, allow_unstable,
                             weather)
    if target is not None and "ballast_mass" in overrides:
        from ironbark_opt.errors import InputError
        raise InputError("--ballast and --target exclude each other: the target decides the ballast",
                         field="ballast")
    from ironbark_opt.plausibility import check_ascent_stability
    if target is None:           # the nominal flight, checked before the derivatives are taken
        margin = check_ascent_stability(setup, overrides, allow_unstable=allow_unstable)
    sens = sensitivities(setup, parameters=overrides, names=list(names) or None, target=target)
    if target is not None:       # the flight at the solved ballast
        margin = check_ascent_stability(setup, dict(sens.point), allow_unstable=allow_unstable)
    if csv_path:
        atomic_write(csv_path, lambda tmp: sens.to_dataframe().to_csv(tmp, index=False))
    if plot_path:
        _agg()
        from ironbark_opt.analysis.plots import plot_sensitivities
        atomic_write(plot_path, lambda tmp: plot_sensitivities(sens, filename=tmp))
    result = {**sens.to_dict(), **margin}
    result["atmosphere"], line = atmosphere_summary(setup)
    emit(result, as_json, sens.summary() + "\n" + _margin_line(margin) + "\n" + line)


@click.command("montecarlo")
@click.argument("rocket", type=click.Path(dir_okay=False))
@click.option("--spec", "spec_path", type=click.Path(dir_okay=False), required=True,
              help="Dispersion spec (TOML: seed, [parameters.NAME] distribution = normal|uniform|file).")
@click.option("--samples", type=click.IntRange(min=1, max=MAX_SAMPLES), default=1000, show_default=True, help="Number of flights.")
@click.option("--seed", type=click.IntRange(min=0), help="Random seed (overrides the spec's).")
@click.option("--descent/--no-descent", default=False, help="Fly every sample to landing (landing ellipse).")
@click.option("--target", type=str, help="Apogee target (e.g. 30000ft, 3000m) for the success probability.")
@click.option("--band", "band_m", type=float, help="Half-width of the band around the target [m].")
@_common
@click.option("--chunk", type=click.IntRange(min=1), default=250, show_default=True, help="Samples per batch.")
@click.option("--jit/--no-jit", default=None,
              help="Compile the model to C now / never (default: compiled when cached, else compiled in the background).")
@click.option("--executor", default="local", show_default=True, metavar="local|local:N|dask://HOST:PORT",
              help="Where the chunks run: this process, N local processes, or a Dask scheduler.")
@click.option("--results-dir", "results_dir", type=click.Path(file_okay=False),
              help="Stream each chunk to a Parquet file here; re-running into it resumes.")
@click.option("--progress/--no-progress", default=None,
              help="Progress bar on stderr (default: when stderr is a terminal).")
@click.option("--csv", "csv_path", type=_FILE_OUT, help="Write every sample (parameters and results).")
@click.option("--samples-out", "samples_path", type=_FILE_OUT,
              help="Write every sample to .csv or .parquet (Parquet needs pyarrow).")
@click.option("--kml", "kml_path", type=_FILE_OUT,
              help="Write the 1/2/3-sigma landing (without --descent: apogee) ellipses for Google Earth (KML).")
@click.option("--histogram", "hist_path", type=_FILE_OUT, help="Write the apogee histogram (PNG/PDF/SVG).")
@click.option("--ellipse", "ellipse_path", type=_FILE_OUT,
              help="Write the landing (or, without --descent, apogee) dispersion ellipses.")
@click.option("--calibration", "calibration_path", type=click.Path(dir_okay=False),
              help="Apply a calibration file (from 'ironbark calibrate --output').")
@json_option
@handle_errors
def montecarlo_command(rocket, spec_path, samples, seed, descent, target, band_m, rail_exit, config, table,
                       ballast_kg, ballast_x_m, allow_unstable, atmosphere, atmosphere_time, forecast, site,
                       time, chunk, jit, executor, results_dir, progress, csv_path, samples_path, kml_path, hist_path,
                       ellipse_path, calibration_path, as_json):
    """Monte Carlo dispersion of ROCKET: apogee, drift and landing statistics."""
    from ironbark_opt.analysis.distributions import load_spec
    from ironbark_opt.analysis.montecarlo import montecarlo
    from ironbark_opt.errors import InputError

    from ironbark_opt.report.exports import check_samples_path, write_samples
    from ironbark_opt.report.geodesy import site_position

    check_output_path(csv_path, "--csv", (".csv", ".txt"))
    check_samples_path(samples_path, "--samples-out")
    check_output_path(kml_path, "--kml", (".kml",))
    check_output_path(hist_path, "--histogram", PLOT_SUFFIXES)
    check_output_path(ellipse_path, "--ellipse", PLOT_SUFFIXES)
    check_output_path(results_dir, "--results-dir", directory=True)
    if band_m is not None and not (band_m > 0 and band_m < float("inf")):
        raise InputError(f"must be > 0 m, got {band_m}", field="--band")
    weather = dict(atmosphere=atmosphere, atmosphere_time=atmosphere_time, forecast=forecast, site=site,
                   time=time)
    setup, overrides = _load(rocket, rail_exit, config, ballast_kg, ballast_x_m, table, allow_unstable,
                             weather)
    if calibration_path is not None:
        from ironbark_opt.telemetry.calibration_file import apply_calibration
        setup = apply_calibration(setup, calibration_path)
    if kml_path:
        site_position(setup, "--kml")            # refused before the flights when the site is unknown
    spec = load_spec(spec_path)
    from ironbark_opt.plausibility import check_ascent_stability
    margin = check_ascent_stability(setup, overrides, allow_unstable=allow_unstable)   # before the samples
    if progress is None:                        # a bar only where someone watches it
        progress = sys.stderr.isatty()
    disp = montecarlo(setup, spec, samples, seed=seed, descent=descent, target=target, band=band_m, chunk=chunk,
                      progress=progress, parameters=overrides, jit="auto" if jit is None else jit,
                      executor=executor, output=results_dir, allow_failed=allow_unstable)
    if csv_path:
        atomic_write(csv_path, lambda tmp: write_samples(disp, tmp))
    if samples_path:
        atomic_write(samples_path, lambda tmp: write_samples(disp, tmp))
    result = {**disp.to_dict(), **{f"nominal_{k}": v for k, v in margin.items()}}
    result["atmosphere"], line = atmosphere_summary(setup)
    if kml_path:
        from ironbark_opt.report.kml import dispersion_kml
        atomic_write_text(kml_path, dispersion_kml(disp, *site_position(setup), setup.site_elevation,
                                                   atmosphere=atmosphere_label(setup)))
    if hist_path or ellipse_path:
        _agg()
        from ironbark_opt.analysis.plots import plot_apogee_histogram, plot_landing_ellipse
        if hist_path:
            atomic_write(hist_path, lambda tmp: plot_apogee_histogram(disp, filename=tmp,
                                                                      atmosphere=atmosphere_label(setup)))
        if ellipse_path:
            atomic_write(ellipse_path, lambda tmp: plot_landing_ellipse(disp, filename=tmp,
                                                                        atmosphere=atmosphere_label(setup)))
    emit(result, as_json, disp.summary() + "\nnominal flight: " + _margin_line(margin) + "\n" + line)


COMMANDS = [sensitivity_command, montecarlo_command]
