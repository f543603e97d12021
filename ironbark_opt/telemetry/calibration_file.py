"""Calibration files: what ``ironbark calibrate`` learned, for the next solve.

TOML (``.toml``) or JSON (``.json``)::

    [calibration]
    rocket = "IREC Team 84"
    log = "flight.csv"
    [parameters]            # applied as the rocket's nominal parameter values (SI)
    drag_scale = 0.9726
    thrust_scale = 0.9929
    [standard_errors]
    drag_scale = 0.0030
    ...

``apply_calibration(setup, path)`` sets ``[parameters]`` as the setup's
nominal values (so ``simulate``, ``ballast`` and ``montecarlo`` — whose
dispersions are about the nominal — all fly the calibrated rocket); an
offset parameter (``dry_mass_offset``) is an offset by definition.  The
nuisance values of the fit (time shift, static-port coefficient) are kept
under ``[fit]`` for the record and not applied.
"""
from __future__ import annotations

import dataclasses
import json
import math
import os
import tempfile
import tomllib
from pathlib import Path

from ironbark_opt import params
from ironbark_opt.errors import InputError


def _toml_value(v) -> str:
    if isinstance(v, str):
        return json.dumps(v)
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, (list, tuple)):
        return "[" + ", ".join(_toml_value(x) for x in v) + "]"
    v = float(v)
    return repr(v) if math.isfinite(v) else "nan"


def write_calibration(calibration, path) -> Path:
    """Write ``calibration`` (a :class:`Calibration`) to ``path`` (.toml or .json), atomically."""
    path = Path(path)
    d = calibration.to_dict()
    model = calibration.parameter_values()
    doc = {"calibration": {"rocket": calibration.rocket, "log": str(calibration.log),
                           "channels": list(calibration.channels),
                           "window_start_s": d["window_start_s"], "window_end_s": d["window_end_s"]},
           "parameters": model,
           "standard_errors": {k: calibration.standard_errors[k] for k in model},
           "correlation": d["correlation"],
           "fit": {**{k: v for k, v in calibration.values.items() if k not in model},
                   **{f"{k}_standard_error": calibration.standard_errors[k] for k in calibration.values
                      if k not in model},
                   **{k: v for k, v in d.items() if k.startswith(("rms_", "noise_")) or k in ("chi2_reduced", "samples")}}}
    if path.suffix.lower() == ".json":
        text = json.dumps(doc, indent=2)
    else:
        lines = ["# ironbark calibration: [parameters] are applied with --calibration FILE"]
        for section, body in doc.items():
            lines.append(f"\n[{section}]")
            for k, v in body.items():
                if k == "matrix":
                    v = [list(map(float, row)) for row in v]
                    lines.append(f"{k} = [" + ", ".join("[" + ", ".join(repr(x) for x in row) + "]" for row in v) + "]")
                else:
                    lines.append(f"{k} = {_toml_value(v)}")
        text = "\n".join(lines) + "\n"
    fd, tmp = tempfile.mkstemp(dir=path.parent or ".", prefix=f".{path.name}.", suffix=".tmp")
    with os.fdopen(fd, "w") as fh:
        fh.write(text)
    os.replace(tmp, path)
    return path


def read_calibration(path) -> dict[str, float]:
    """``[parameters]`` of a calibration file: name -> value (SI), validated."""
    path = Path(path)
    if path.suffix.lower() not in (".toml", ".json"):
        raise InputError(f"unknown calibration file type {path.suffix or '(none)'!r}; expected .toml or "
                         ".json (as 'ironbark calibrate --output' writes)", source=path)
    if path.is_dir():
        raise InputError("is a directory, not a calibration file", source=path)
    try:
        text = path.read_text()
    except FileNotFoundError:
        raise InputError("calibration file not found", source=path) from None
    except (OSError, UnicodeDecodeError) as err:
        raise InputError(f"cannot read the calibration file ({err})", source=path) from None
    try:
        doc = json.loads(text) if path.suffix.lower() == ".json" else tomllib.loads(text)
    except (tomllib.TOMLDecodeError, json.JSONDecodeError) as err:
        raise InputError(f"not a valid calibration file ({err})", source=path) from None
    if not isinstance(doc, dict):
        raise InputError("expected a table with [parameters]", source=path, field="parameters")
    body = doc.get("parameters")
    if not isinstance(body, dict) or not body:
        raise InputError("no [parameters] table (write one with 'ironbark calibrate ... --output FILE')",
                         source=path, field="parameters")
    out = {}
    for k, v in body.items():
        if k not in params.INDEX:
            raise InputError(f"unknown parameter; known: {', '.join(params.NAMES)}", source=path,
                             field=f"parameters.{k}")
        if not isinstance(v, (int, float)) or isinstance(v, bool) or not math.isfinite(v):
            raise InputError(f"expected a finite number, got {v!r}", source=path, field=f"parameters.{k}")
        if k.endswith("_scale") and not v > 0:     # a factor on thrust, drag, ...: > 0 by definition
            raise InputError(f"a scale factor must be > 0, got {v!r}", source=path, field=f"parameters.{k}")
        out[k] = float(v)
    return out


def apply_calibration(setup, path):
    """``setup`` with the calibration file's parameters as its nominal values."""
    if path is None:
        return setup
    return dataclasses.replace(setup, nominal={**dict(setup.nominal), **read_calibration(path)})
