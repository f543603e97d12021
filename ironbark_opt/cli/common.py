"""Shared pieces of the ``ironbark`` command line: JSON output and errors.

JSON contract: every command accepts ``--json`` and then prints exactly one
JSON object on stdout whose keys carry their unit as a suffix
(``apogee_agl_m``, ``max_speed_mps``, ``burn_time_s``, ``mass_kg``,
``inclination_deg``); dimensionless keys have no suffix.  Errors go to stderr
as one line ``error: ...`` with exit status 2 (bad input) or 3 (network /
solver failure).
"""
from __future__ import annotations

import contextlib
import functools
import io
import json
import math
import os
import sys
import warnings

import click
import numpy as np

from ironbark_opt.errors import InputError, IronbarkError

json_option = click.option("--json", "as_json", is_flag=True,
                           help="Print the result as one JSON object with unit-suffixed keys.")
table_option = click.option(
    "--table", "table", type=click.Path(dir_okay=False), multiple=True,
    help="Fly this aerodynamic table (from 'ironbark aero build') instead of the file's aero; "
         "a multi-stage .ork: once per table its build wrote (stack, sustainer).")


def _clean(obj):
    """Make ``obj`` JSON-serialisable (NumPy scalars/arrays, NaN -> null)."""
    if isinstance(obj, dict):
        return {str(k): _clean(v) for k, v in obj.items()}
    if isinstance(obj, (list, tuple)):
        return [_clean(v) for v in obj]
    if isinstance(obj, np.ndarray):
        return [_clean(v) for v in obj.tolist()]
    if isinstance(obj, np.generic):
        obj = obj.item()
    if isinstance(obj, float) and not math.isfinite(obj):
        return None
    return obj


def emit(result: dict, as_json: bool, human: str) -> None:
    """Print ``result`` as JSON (``--json``) or the human summary ``human``."""
    if as_json:
        click.echo(json.dumps(_clean(result), indent=2))
    else:
        click.echo(human)


def _show_warning(message, category, filename, lineno, file=None, line=None):
    click.echo(f"warning: {message}", err=True)


def handle_errors(func):
    """Decorator: one-line errors with exit codes, one-line warnings on stderr."""
    @functools.wraps(func)
    def wrapper(*args, **kwargs):
        warnings.showwarning = _show_warning
        try:
            return func(*args, **kwargs)
        except InputError as err:
            click.echo(f"error: {err}", err=True)
            sys.exit(2)
        except IronbarkError as err:
            # one short line: a failure with several sources tried keeps the first and a count
            lines = [ln.strip() for ln in str(err).splitlines() if ln.strip()]
            if len(lines) > 1 and lines[0].endswith(":"):      # a heading, then one line per source
                lines = [f"{lines[0]} {lines[1]}"] + lines[2:]
            more = f" (and {len(lines) - 1} more sources failed)" if len(lines) > 1 else ""
            click.echo(f"error: {lines[0] if lines else type(err).__name__}{more}", err=True)
            sys.exit(3)
        except (FileNotFoundError, IsADirectoryError, PermissionError) as err:
            click.echo(f"error: {err.filename}: {err.strerror}", err=True)
            sys.exit(2)
    return wrapper


@contextlib.contextmanager
def native_stdout_to_stderr():
    """While a command runs, the process's file descriptor 1 goes to stderr and only
    Python's ``sys.stdout`` (a new stream on the original descriptor) reaches stdout.

    Native libraries write diagnostics to descriptor 1 directly: the reference BLAS's
    XERBLA (" ** On entry to DTRSV parameter number 6 had an illegal value", from
    SuperLU on a degenerate supersonic influence matrix, whose Mach number then falls
    back to local inclination) landed in front of ``aero build --json``'s document, so
    the output was not JSON.  A no-op when ``sys.stdout`` is not descriptor 1 (click's
    test runner, captured streams)."""
    try:
        fd = sys.stdout.fileno()
    except (AttributeError, OSError, ValueError):
        fd = None
    if fd != 1:
        yield
        return
    old = sys.stdout
    old.flush()
    saved = os.dup(1)
    os.dup2(2, 1)
    sys.stdout = io.TextIOWrapper(io.FileIO(saved, "w", closefd=True), encoding=old.encoding,
                                  errors=old.errors, line_buffering=old.line_buffering)
    try:
        yield
    finally:
        sys.stdout.flush()
        os.dup2(saved, 1)
        sys.stdout.close()
        sys.stdout = old


class OneLineErrorGroup(click.Group):
    """A click group whose usage errors (bad option value, missing option,
    unknown option) are one ``error:`` line naming the option, exit status 2,
    like every other bad input."""

    def main(self, args=None, prog_name=None, complete_var=None, standalone_mode=True, **extra):
        if not standalone_mode:
            return super().main(args, prog_name, complete_var, standalone_mode, **extra)
        try:
            with native_stdout_to_stderr():
                rv = super().main(args, prog_name, complete_var, standalone_mode=False, **extra)
        except click.UsageError as err:
            cmd = err.ctx.command_path if err.ctx is not None else "ironbark"
            click.echo(f"error: {err.format_message()} (see '{cmd} --help')", err=True)
            sys.exit(2)
        except click.ClickException as err:
            click.echo(f"error: {err.format_message()}", err=True)
            sys.exit(err.exit_code)
        except click.Abort:
            click.echo("error: aborted", err=True)
            sys.exit(1)
        sys.exit(rv if isinstance(rv, int) else 0)


def check_output_path(path, option: str, suffixes: tuple | None = None, *, directory: bool = False):
    """Refuse an output path before any work starts (numeric-free, no side effects).

    The parent folder must exist and be a writable folder; the target must
    not be a directory (or, with ``directory``, must be one or not exist) nor
    a device; ``suffixes`` (e.g. ``(".png", ".pdf", ".svg")``) lists the
    accepted extensions.  Errors name ``option``.
    """
    import os
    from pathlib import Path

    if path is None:
        return None
    p = Path(path)
    parent = p.parent if str(p.parent) else Path(".")
    if directory:
        if p.exists() and not p.is_dir():
            raise InputError(f"{p} is a file, expected a folder", field=option)
        parent = p if p.exists() else parent
    elif p.is_dir():
        raise InputError(f"{p} is a directory, expected a file name", field=option)
    elif p.exists() and not p.is_file():
        raise InputError(f"{p} is not a regular file (device or pipe); expected a file name", field=option)
    if not parent.exists():
        raise InputError(f"folder {parent} does not exist (create it first)", field=option)
    if not parent.is_dir():
        raise InputError(f"{parent} is a file, not a folder", field=option)
    if not os.access(parent, os.W_OK) or str(parent.resolve()).startswith(("/proc", "/sys")):
        raise InputError(f"folder {parent} is not writable", field=option)
    if suffixes and not directory and p.suffix.lower() not in suffixes:
        raise InputError(f"unknown file type {p.suffix or '(none)'!r}; expected one of "
                         f"{', '.join(suffixes)}", field=option)
    return p


PLOT_SUFFIXES = (".png", ".pdf", ".svg")


def atomic_write(path, write) -> None:
    """Write ``path`` through ``write(tmp_path)`` into a temporary file in the
    same folder, then ``os.replace`` it into place: never a partial file."""
    import os
    import tempfile
    from pathlib import Path

    path = Path(path)
    fd, tmp = tempfile.mkstemp(prefix=f".{path.stem}.", suffix=f".tmp{path.suffix}", dir=path.parent or ".")
    os.close(fd)
    try:
        write(tmp)
        os.replace(tmp, path)
    except OSError as err:
        raise InputError(f"cannot write {path}: {err.strerror or err}", field=str(path)) from None
    finally:
        if os.path.exists(tmp):
            os.unlink(tmp)


def atomic_write_text(path, text: str) -> None:
    """Write ``text`` (UTF-8) to ``path`` through :func:`atomic_write`."""
    from pathlib import Path

    atomic_write(path, lambda tmp: Path(tmp).write_text(text, encoding="utf-8"))


def forecast_option(required: bool = False, help: str = "Fly through a NOAA forecast profile (needs --site "
                                                               "and --time).", choices=("rap", "gfs")):
    """The shared ``--forecast rap|gfs`` option (``required`` for commands that need one;
    ``choices`` adds ``gefs`` where ensemble members are flown)."""
    return click.option("--forecast", type=click.Choice(list(choices)), required=required, help=help)


site_option = click.option("--site", help="Launch-site preset for the forecast (see 'ironbark weather sites').")


def atmosphere_options(func):
    """The atmosphere options every flying command shares (one definition):
    ``--atmosphere FILE [--atmosphere-time T]`` or ``--forecast rap|gfs --site
    --time``; the command receives them as ``atmosphere, atmosphere_time,
    forecast, site, time`` and hands them to :func:`apply_atmosphere`."""
    options = [
        click.option("--atmosphere", "atmosphere", type=click.Path(dir_okay=False),
                     help="Fly this atmosphere file: a reanalysis netCDF (ERA5-style), a saved "
                          "sounding, or the JSON/CSV 'ironbark weather get' writes (replaces "
                          "the rocket file's [launch] atmosphere)."),
        click.option("--atmosphere-time", "atmosphere_time", metavar="ISO",
                     help="Launch time (ISO 8601 UTC) picking the record of a multi-time "
                          "--atmosphere reanalysis file."),
        forecast_option(),
        site_option,
        click.option("--time", help="Launch time for the forecast, ISO 8601 UTC."),
    ]
    for option in reversed(options):
        func = option(func)
    return func


def atmosphere_load_kwargs(atmosphere=None, atmosphere_time=None, forecast=None, site=None,
                           time=None) -> dict:
    """Keyword arguments for ``load_setup`` from the shared atmosphere options
    (``--atmosphere`` is read at the rocket file's site); checks their
    combinations (``click.UsageError``, exit 2).  ``--forecast`` is applied
    after loading with :func:`apply_forecast`."""
    if atmosphere is not None and forecast is not None:
        raise click.UsageError("give --atmosphere FILE or --forecast rap|gfs, not both")
    if atmosphere_time is not None and atmosphere is None:
        raise click.UsageError("--atmosphere-time needs --atmosphere FILE")
    if atmosphere is None:
        if forecast is None and (site is not None or time is not None):
            raise click.UsageError("--site/--time need --forecast rap|gfs")
        return {}
    if site is not None or time is not None:
        raise click.UsageError("--site/--time belong to --forecast; for a file give --atmosphere-time")
    return {"atmosphere_file": atmosphere, "atmosphere_time": atmosphere_time}


def apply_forecast(setup, forecast=None, site=None, time=None, **_file_options):
    """``setup`` flying the ``--forecast`` profile (unchanged without one)."""
    if forecast is None:
        return setup
    from ironbark_opt.cli.optimise import forecast_atmosphere
    return forecast_atmosphere(setup, forecast, site, time)


def atmosphere_summary(setup) -> tuple[dict, str]:
    """(``--json`` entry, summary line) naming the atmosphere ``setup`` flies."""
    from ironbark_opt.atmosphere.files import describe_flown, flown_line
    return describe_flown(setup.atmosphere), flown_line(setup.atmosphere)


def atmosphere_label(setup) -> str:
    """The atmosphere ``setup`` flies in a few words, for figure titles and map descriptions."""
    return " ".join(atmosphere_summary(setup)[1].split())
