"""Shared pieces of the ``ironbark`` command line: JSON output and errors.

JSON contract: every command accepts ``--json`` and then prints exactly one
JSON object on stdout whose keys carry their unit as a suffix
(``apogee_agl_m``, ``max_speed_mps``, ``burn_time_s``, ``mass_kg``,
``inclination_deg``); dimensionless keys have no suffix.  Errors go to stderr
as one line ``error: ...`` with exit status 2 (bad input) or 3 (network /
solver failure).
"""
from __future__ import annotations

import functools
import json
import math
import sys
import warnings

import click
import numpy as np

from ironbark_opt.errors import InputError, IronbarkError

json_option = click.option("--json", "as_json", is_flag=True,
                           help="Print the result as one JSON object with unit-suffixed keys.")
table_option = click.option(
    "--table", "table", type=click.Path(dir_okay=False),
    help="Fly this aerodynamic table (from 'ironbark aero build') instead of the file's aero.")


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
            click.echo(f"error: {err}", err=True)
            sys.exit(3)
        except (FileNotFoundError, IsADirectoryError, PermissionError) as err:
            click.echo(f"error: {err.filename}: {err.strerror}", err=True)
            sys.exit(2)
    return wrapper
