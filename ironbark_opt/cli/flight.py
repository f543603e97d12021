"""``ironbark flight compare ROCKET LOG`` and ``ironbark calibrate ROCKET LOG``."""
from __future__ import annotations

import click

from ironbark_opt.cli.common import (PLOT_SUFFIXES, atomic_write, check_output_path, emit, handle_errors,
                                     json_option, table_option)

_FILE_OUT = click.Path(dir_okay=False, writable=True)


def _log_options(func):
    for option in reversed([
        click.option("--format", "log_format", help="Force the log reader (default: detected from content)."),
        click.option("--columns", help="Generic CSV column map, e.g. 'time=T:ms,altitude=Alt:ft'."),
        click.option("--config", "config", type=str, help="Motor configuration, or a stored simulation by name (OpenRocket files; its launch conditions too)."),
        table_option,
        click.option("--calibration", "calibration_path", type=click.Path(dir_okay=False),
                     help="Apply a calibration file (from 'ironbark calibrate --output')."),
    ]):
        func = option(func)
    return func


def _load(rocket, log_path, log_format, columns, config, table, calibration_path):
    from ironbark_opt.telemetry import read_log
    from ironbark_opt.telemetry.calibration_file import apply_calibration
    from ironbark_opt.vehicle import load_setup

    log = read_log(log_path, format=log_format, columns=columns)
    kwargs = {"table": table}
    if config is not None:
        kwargs["config"] = config
    setup = apply_calibration(load_setup(rocket, **kwargs), calibration_path)
    return setup, log


def _agg():
    import matplotlib
    matplotlib.use("Agg")


@click.group("flight")
def flight_group():
    """Work with real flight logs (altimeter / flight-computer exports)."""


@flight_group.command("compare")
@click.argument("rocket", type=click.Path(dir_okay=False))
@click.argument("log", type=click.Path(dir_okay=False))
@_log_options
@click.option("--plot", "plot_path", type=_FILE_OUT, help="Write the overlay figure (PNG/PDF/SVG).")
@json_option
@handle_errors
def compare_command(rocket, log, log_format, columns, config, table, calibration_path, plot_path, as_json):
    """Simulate ROCKET and compare it with the flight LOG (apogee, times, channels)."""
    from ironbark_opt.telemetry.compare import compare_flight

    check_output_path(plot_path, "--plot", PLOT_SUFFIXES)
    setup, flight_log = _load(rocket, log, log_format, columns, config, table, calibration_path)
    comparison = compare_flight(setup, flight_log)
    if plot_path:
        _agg()
        from ironbark_opt.telemetry.plots import plot_comparison
        atomic_write(plot_path, lambda tmp: plot_comparison(comparison, filename=tmp))
    emit(comparison.to_dict(), as_json, flight_log.summary() + "\n" + comparison.summary())


@click.command("calibrate")
@click.argument("rocket", type=click.Path(dir_okay=False))
@click.argument("log", type=click.Path(dir_okay=False))
@_log_options
@click.option("--param", "names", multiple=True, metavar="NAME",
              help="Parameter to fit (repeatable; default drag_scale and thrust_scale).")
@click.option("--channel", "channels", multiple=True,
              type=click.Choice(["altitude", "vertical_speed", "acceleration"]),
              help="Channel to fit (repeatable; default altitude and acceleration where logged).")
@click.option("--until", "until_s", type=float, help="End of the fit window [s of log time].")
@click.option("--until-fraction", type=click.FloatRange(0, 1, min_open=True),
              help="End of the fit window as a fraction of the time to apogee.")
@click.option("--no-time-offset", is_flag=True, help="Do not fit the log's time shift.")
@click.option("--no-baro-port", is_flag=True, help="Do not fit the static-port pressure coefficient.")
@click.option("--output", "-o", "output", type=_FILE_OUT, help="Write the calibration file (.toml or .json).")
@click.option("--plot", "plot_path", type=_FILE_OUT, help="Write the residual figure (PNG/PDF/SVG).")
@json_option
@handle_errors
def calibrate_command(rocket, log, log_format, columns, config, table, calibration_path, names, channels,
                      until_s, until_fraction, no_time_offset, no_baro_port, output, plot_path, as_json):
    """Fit drag/thrust (and other) parameters of ROCKET to the flight LOG."""
    from ironbark_opt.flight import simulate
    from ironbark_opt.telemetry.calibrate import DEFAULT_PARAMETERS, calibrate
    from ironbark_opt.telemetry.calibration_file import write_calibration
    from ironbark_opt.errors import InputError
    check_output_path(output, "--output", (".toml", ".json"))
    check_output_path(plot_path, "--plot", PLOT_SUFFIXES)
    if until_s is not None and not (0.0 < until_s < float("inf")):
        raise InputError(f"must be a time > 0 s after the log's start, got {until_s}", field="--until")
    if until_fraction is not None and not 0.0 < until_fraction <= 1.0:      # click lets NaN through
        raise InputError(f"must be a fraction in (0, 1], got {until_fraction}", field="--until-fraction")
    setup, flight_log = _load(rocket, log, log_format, columns, config, table, calibration_path)
    cal = calibrate(setup, flight_log, parameters=names or DEFAULT_PARAMETERS, channels=channels or None,
                    until=until_s, until_fraction=until_fraction, fit_time_offset=not no_time_offset,
                    fit_baro_port=not no_baro_port)
    before = simulate(setup).apogee_agl                     # same (cached) model as the fit
    after = simulate(setup, parameters=cal.parameter_values()).apogee_agl
    if output:
        write_calibration(cal, output)
    if plot_path:
        _agg()
        from ironbark_opt.telemetry.plots import plot_residuals
        atomic_write(plot_path, lambda tmp: plot_residuals(cal, filename=tmp))
    result = cal.to_dict()
    result.update(logged_apogee_agl_m=flight_log.apogee_agl, uncalibrated_apogee_agl_m=before,
                  calibrated_apogee_agl_m=after, uncalibrated_apogee_error_m=before - flight_log.apogee_agl,
                  calibrated_apogee_error_m=after - flight_log.apogee_agl)
    human = (cal.summary() + f"\n  apogee         logged {flight_log.apogee_agl:.1f} m; uncalibrated "
             f"{before:.1f} m ({before - flight_log.apogee_agl:+.1f}), calibrated {after:.1f} m "
             f"({after - flight_log.apogee_agl:+.1f})" + (f"\n  written        {output}" if output else ""))
    emit(result, as_json, human)


COMMANDS = [flight_group, calibrate_command]
