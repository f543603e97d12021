"""Exceptions and warnings a user can act on.

Every error raised for bad input names where the problem is (file, line,
field) and what was expected, so that the CLI can print it as one line
instead of a traceback from deep inside CasADi or NumPy.
"""
from __future__ import annotations

from os import PathLike


class IronbarkError(Exception):
    """Base class of all Ironbark-Opt errors; ``str(err)`` is user-facing."""


class InputError(IronbarkError, ValueError):
    """Bad user input: a file, a line in it, a field, or an argument.

    Parameters
    ----------
    message : str
        What is wrong and what was expected.
    source : str or path-like, optional
        The file (or other named source) the input came from.
    line : int, optional
        1-based line number in ``source``.
    field : str, optional
        The field / key / element path that is wrong.
    """

    def __init__(self, message: str, *, source: str | PathLike | None = None,
                 line: int | None = None, field: str | None = None):
        self.message = message
        self.source = None if source is None else str(source)
        self.line = line
        self.field = field
        where = ""
        if self.source is not None:
            where = self.source
            if line is not None:
                where += f":{line}"
        if field is not None:
            where = f"{where}: field '{field}'" if where else f"field '{field}'"
        super().__init__(f"{where}: {message}" if where else message)


class NetworkError(IronbarkError):
    """A remote source (ThrustCurve.org, NOAA, UWyo) failed; the message names
    the URL and what to do (retry, use --offline, check the cache)."""


class SolverError(IronbarkError):
    """A numerical solve (rootfinder, IPOPT, panel solver) did not converge;
    the message says which case and why."""


class OutOfRangeWarning(UserWarning):
    """An input fell outside a table's grid and was clamped."""
