"""The user config file (TOML): endpoints, network settings, launch sites.

Location: ``IRONBARK_CONFIG`` if set, else ``$XDG_CONFIG_HOME/ironbark/config.toml``
(``~/.config/ironbark/config.toml``; ``%APPDATA%\\ironbark\\config.toml`` on
Windows).  A missing file is an empty config.  Example::

    [endpoints]                  # base URLs; IRONBARK_*_URL variables win
    thrustcurve = "https://www.thrustcurve.org/api/v1"
    thredds = "https://thredds.ucar.edu/thredds"

    [network]
    timeout_s = 20
    retries = 2
    backoff_s = 1.0
    offline = false

    [sites.home_field]           # adds (or overrides) a launch-site preset
    latitude_deg = 43.1
    longitude_deg = -89.4
    elevation_m = 260
    description = "Club field"

Numeric-only (file I/O).
"""
from __future__ import annotations

import os
import re
from pathlib import Path

try:
    import tomllib
except ModuleNotFoundError:  # Python < 3.11
    import tomli as tomllib

from ironbark_opt.errors import InputError

_SECTIONS = ("endpoints", "network", "sites")


def config_path() -> Path:
    """Path of the user config file (it need not exist)."""
    env = os.environ.get("IRONBARK_CONFIG")
    if env:
        return Path(env).expanduser()
    if os.name == "nt":
        base = os.environ.get("APPDATA") or str(Path.home() / "AppData" / "Roaming")
        return Path(base) / "ironbark" / "config.toml"
    return Path(os.environ.get("XDG_CONFIG_HOME") or Path.home() / ".config") / "ironbark" / "config.toml"


def load(path: str | os.PathLike | None = None) -> dict:
    """Read the user config file; ``{}`` when it does not exist.

    Parameters
    ----------
    path : path-like, optional
        Config file (default :func:`config_path`).

    Raises
    ------
    InputError
        Invalid TOML (with the line), or a known section that is not a table.
    """
    path = Path(path) if path is not None else config_path()
    if not path.is_file():
        return {}
    try:
        data = tomllib.loads(path.read_text(encoding="utf-8"))
    except tomllib.TOMLDecodeError as err:
        line = getattr(err, "lineno", None)
        if line is None:   # Python 3.11's tomllib puts the line only in the text
            m = re.search(r"at line (\d+)", str(err))
            line = int(m.group(1)) if m else None
        raise InputError(f"invalid TOML ({err})", source=path, line=line) from None
    except UnicodeDecodeError:
        raise InputError("not a UTF-8 text file", source=path) from None
    for section in _SECTIONS:
        if section in data and not isinstance(data[section], dict):
            raise InputError("expected a table", source=path, field=section)
    return data
