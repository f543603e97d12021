"""Dispersion specs: which parameters vary in a Monte Carlo run, and how.

A spec is a TOML file (``dispersions.toml``)::

    seed = 20260704                     # optional; makes the run reproducible

    [parameters.thrust_scale]           # a name from ironbark_opt.params
    distribution = "normal"
    std = 0.01                          # mean defaults to the rocket's nominal value

    [parameters.inclination_deg]        # angle parameters may be given in degrees
    distribution = "normal"
    mean = 84.0
    std = 1.0

    [parameters.wind_east]
    distribution = "uniform"
    low = -3.0
    high = 3.0

    [parameters.drag_scale]
    distribution = "file"               # resampled with replacement
    file = "drag_scale_samples.csv"     # relative to the spec file
    column = "drag_scale"

Values are in the parameter's SI unit (see :mod:`ironbark_opt.params`),
except for keys ending in ``_deg``, which give an angle parameter (unit
``rad``) in degrees.  Every mistake raises :class:`InputError` naming the
file, the line and the field.

Numeric-only (NumPy); nothing here is symbolic.
"""
from __future__ import annotations

import math
import re
from dataclasses import dataclass, field
from pathlib import Path
from typing import Mapping

import numpy as np

from ironbark_opt import params
from ironbark_opt.errors import InputError

try:
    import tomllib
except ModuleNotFoundError:        # Python 3.10
    import tomli as tomllib

DISTRIBUTIONS = ("normal", "uniform", "file")
_KEYS = {"normal": ("mean", "std"), "uniform": ("low", "high"), "file": ("file", "column")}


@dataclass(frozen=True)
class Normal:
    """Gaussian dispersion.

    Parameters
    ----------
    std : float [parameter unit, SI]
        Standard deviation (0 gives a constant).
    mean : float or None [parameter unit, SI]
        None: the case's nominal value.
    """

    std: float
    mean: float | None = None

    def draw(self, rng: np.random.Generator, n: int, nominal: float) -> np.ndarray:
        """``n`` samples [SI] around ``mean`` (or ``nominal`` [SI])."""
        centre = nominal if self.mean is None else self.mean
        return centre + self.std * rng.standard_normal(n)

    def quantile(self, u: np.ndarray, nominal: float) -> np.ndarray:
        """Inverse CDF at probabilities ``u`` in (0, 1) [SI]."""
        from scipy.special import ndtri
        return (nominal if self.mean is None else self.mean) + self.std * ndtri(u)

    def mean_value(self, nominal: float) -> float:
        """Expected value [SI]."""
        return nominal if self.mean is None else self.mean

    def describe(self, scale: float = 1.0) -> str:
        mean = "nominal" if self.mean is None else f"{self.mean * scale:g}"
        return f"normal(mean={mean}, std={self.std * scale:g})"

    def to_dict(self, scale: float = 1.0) -> dict:
        """As in the spec file (values times ``scale``); no ``mean``: nominal."""
        out = {"distribution": "normal", "std": self.std * scale}
        if self.mean is not None:
            out["mean"] = self.mean * scale
        return out


@dataclass(frozen=True)
class Uniform:
    """Uniform dispersion on ``[low, high]`` [parameter unit, SI]."""

    low: float
    high: float

    def draw(self, rng: np.random.Generator, n: int, nominal: float) -> np.ndarray:
        return rng.uniform(self.low, self.high, n)

    def quantile(self, u: np.ndarray, nominal: float) -> np.ndarray:
        return self.low + (self.high - self.low) * np.asarray(u)

    def mean_value(self, nominal: float) -> float:
        return 0.5 * (self.low + self.high)

    def describe(self, scale: float = 1.0) -> str:
        return f"uniform(low={self.low * scale:g}, high={self.high * scale:g})"

    def to_dict(self, scale: float = 1.0) -> dict:
        return {"distribution": "uniform", "low": self.low * scale, "high": self.high * scale}


@dataclass(frozen=True, eq=False)
class Empirical:
    """Values read from a file, resampled with replacement.

    Parameters
    ----------
    values : array [parameter unit, SI]
    source : str
        ``file:column`` for reports.
    """

    values: np.ndarray = field(repr=False)
    source: str = ""

    def draw(self, rng: np.random.Generator, n: int, nominal: float) -> np.ndarray:
        return self.values[rng.integers(0, self.values.size, n)]

    def quantile(self, u: np.ndarray, nominal: float) -> np.ndarray:
        """Inverse CDF of resampling with replacement (each value weight 1/size)."""
        k = np.minimum((np.asarray(u) * self.values.size).astype(int), self.values.size - 1)
        return np.sort(self.values)[k]

    def mean_value(self, nominal: float) -> float:
        return float(np.mean(self.values))

    def describe(self, scale: float = 1.0) -> str:
        return f"file({self.source}, {self.values.size} values, mean {np.mean(self.values) * scale:g})"

    def to_dict(self, scale: float = 1.0) -> dict:
        return {"distribution": "file", "source": self.source, "count": int(self.values.size),
                "mean": float(np.mean(self.values)) * scale, "std": float(np.std(self.values)) * scale}


@dataclass(frozen=True)
class DispersionSpec:
    """Which parameters are dispersed and the seed.

    Parameters
    ----------
    parameters : mapping registry name -> Normal | Uniform | Empirical
        Values in SI (angles in radians).
    seed : int or None
        Seed of the random generator (None: fresh entropy per run).
    source : str or None
        The file the spec came from.
    """

    parameters: Mapping[str, object]
    seed: int | None = None
    source: str | None = None

    def __repr__(self) -> str:
        names = ", ".join(self.parameters) or "none"
        return f"DispersionSpec({len(self.parameters)} parameters: {names}; seed={self.seed})"

    def sample(self, n: int, nominal: np.ndarray, rng: np.random.Generator) -> np.ndarray:
        """Parameter matrix (``params.SIZE`` x ``n``) [mixed SI].

        Undispersed rows hold ``nominal``; dispersed ones are drawn in
        registry order, so the samples depend only on the seed, ``n`` and
        the spec (not on how a run is chunked).
        """
        nominal = np.asarray(nominal, dtype=float).ravel()
        P = np.repeat(nominal[:, None], n, axis=1)
        for name in params.NAMES:
            if name in self.parameters:
                i = params.index(name)
                P[i] = self.parameters[name].draw(rng, n, nominal[i])
        return P

    def sample_lhs(self, n: int, nominal: np.ndarray, rng: np.random.Generator) -> np.ndarray:
        """As :meth:`sample`, a Latin hypercube: each dispersed parameter's ``n`` values fall
        one in each of ``n`` equal-probability strata, in an independent random order
        (McKay, Beckman & Conover, Technometrics 21(2), 1979).  Every column is still a draw
        from the spec; a mean over the columns of a function that is nearly additive in the
        parameters (the apogee) has far less variance than over independent draws (Stein,
        Technometrics 29(2), 1987)."""
        nominal = np.asarray(nominal, dtype=float).ravel()
        P = np.repeat(nominal[:, None], n, axis=1)
        for name in params.NAMES:
            if name in self.parameters:
                i = params.index(name)
                u = (rng.permutation(n) + rng.random(n)) / n
                P[i] = self.parameters[name].quantile(np.clip(u, 1e-12, 1 - 1e-12), nominal[i])
        return P

    def means(self, nominal: np.ndarray) -> np.ndarray:
        """Parameter vector with every dispersed entry at its expected value [mixed SI]."""
        p = np.array(nominal, dtype=float).ravel()
        for name, dist in self.parameters.items():
            i = params.index(name)
            p[i] = dist.mean_value(p[i])
        return p

    def to_dict(self) -> dict:
        """{key: distribution fields} as in the spec file (angles as ``NAME_deg`` in degrees)."""
        out = {}
        for name, dist in self.parameters.items():
            if params.INFO[name].unit == "rad":
                out[name + "_deg"] = dist.to_dict(180.0 / math.pi)
            else:
                out[name] = dist.to_dict()
        return out

    def describe(self) -> list[str]:
        """One line per dispersed parameter, angles in degrees."""
        lines = []
        for name, dist in self.parameters.items():
            unit = params.INFO[name].unit
            if unit == "rad":
                lines.append(f"{name + '_deg':24s} {dist.describe(180.0 / math.pi)} [deg]")
            else:
                lines.append(f"{name:24s} {dist.describe()} [{unit}]")
        return lines


# ---------------------------------------------------------------- file reading
def _line_of(lines: list[str], name: str, key: str | None = None) -> int | None:
    """1-based line of ``[parameters.name]`` (or of ``key`` inside it)."""
    header = re.compile(r'^\s*\[\s*parameters\s*\.\s*["\']?' + re.escape(name) + r'["\']?\s*\]')
    start = next((i for i, line in enumerate(lines) if header.match(line)), None)
    if start is None:                      # inline table or dotted keys: the first mention
        return next((i + 1 for i, line in enumerate(lines) if re.search(rf"\b{re.escape(name)}\b", line)), None)
    if key is None:
        return start + 1
    pattern = re.compile(r"^\s*" + re.escape(key) + r"\s*=")
    for i in range(start + 1, len(lines)):
        if lines[i].lstrip().startswith("["):
            break
        if pattern.match(lines[i]):
            return i + 1
    return start + 1


def _number(entry: dict, key: str, where) -> float:
    if key not in entry:
        raise where(f"missing '{key}'", key)
    value = entry[key]
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value):
        raise where(f"expected a finite number, got {value!r}", key)
    return float(value)


def _read_column(path: Path, column: str, where) -> np.ndarray:
    import pandas as pd

    if not path.exists():
        raise where(f"sample file {str(path)!r} not found", "file")
    try:
        table = pd.read_csv(path, comment="#")
    except (ValueError, OSError) as err:
        raise InputError(f"cannot read the sample table: {err}", source=path) from None
    if column not in table.columns:
        raise where(f"column {column!r} not in {path.name} (columns: {', '.join(map(str, table.columns))})",
                    "column")
    values = pd.to_numeric(table[column], errors="coerce").to_numpy(dtype=float)
    bad = np.nonzero(~np.isfinite(values))[0]
    if bad.size:
        # +2: header line, 1-based
        raise InputError(f"column {column!r} holds a non-number {table[column].iloc[bad[0]]!r}",
                         source=path, line=int(bad[0]) + 2, field=column)
    if values.size == 0:
        raise where(f"column {column!r} of {path.name} has no values", "column")
    return values


def _distribution(name: str, entry, scale: float, base: Path | None, where):
    if not isinstance(entry, dict):
        raise where(f"expected a table with 'distribution = ...', got {entry!r}", None)
    kind = entry.get("distribution")
    if kind not in DISTRIBUTIONS:
        raise where(f"distribution must be one of {', '.join(map(repr, DISTRIBUTIONS))}, got {kind!r}",
                    "distribution")
    allowed = set(_KEYS[kind]) | {"distribution"}
    extra = sorted(set(entry) - allowed)
    if extra:
        raise where(f"unknown key {extra[0]!r} for a {kind} distribution (expected {', '.join(_KEYS[kind])})",
                    extra[0])
    if kind == "normal":
        std = _number(entry, "std", where) * scale
        if std < 0:
            raise where(f"std must be >= 0, got {entry['std']}", "std")
        mean = _number(entry, "mean", where) * scale if "mean" in entry else None
        return Normal(std=std, mean=mean)
    if kind == "uniform":
        low, high = _number(entry, "low", where) * scale, _number(entry, "high", where) * scale
        if high < low:
            raise where(f"high ({entry['high']}) must be >= low ({entry['low']})", "high")
        return Uniform(low, high)
    for key in ("file", "column"):
        if not isinstance(entry.get(key), str) or not entry[key]:
            raise where(f"expected a text value for '{key}'", key)
    path = Path(entry["file"])
    if not path.is_absolute() and base is not None:
        path = base / path
    values = _read_column(path, entry["column"], where) * scale
    return Empirical(values=values, source=f"{path.name}:{entry['column']}")


def spec_from_dict(data: Mapping, *, source=None, text: str | None = None) -> DispersionSpec:
    """Build a :class:`DispersionSpec` from parsed TOML (or an equivalent dict); numeric-only.

    Parameters
    ----------
    data : mapping
        ``{"seed": int, "parameters": {name: {...}}}``.
    source : path-like, optional
        File name for error messages; relative sample files resolve against
        its directory.
    text : str, optional
        The file's text, to name line numbers in errors.
    """
    lines = text.splitlines() if text else []
    src = None if source is None else str(source)
    base = Path(source).parent if source is not None else None

    def where_for(name):
        def where(message, key):
            line = _line_of(lines, name, key) if lines else None
            fld = f"parameters.{name}" + (f".{key}" if key else "")
            return InputError(message, source=src, line=line, field=fld)
        return where

    unknown = sorted(set(data) - {"seed", "parameters"})
    if unknown:
        line = next((i + 1 for i, ln in enumerate(lines) if re.match(rf"^\s*\[?\s*{re.escape(unknown[0])}\b", ln)),
                    None)
        raise InputError(f"unknown key {unknown[0]!r}: a spec has 'seed' and [parameters.NAME] tables",
                         source=src, line=line, field=unknown[0])
    seed = data.get("seed")
    if seed is not None and (isinstance(seed, bool) or not isinstance(seed, int) or seed < 0):
        line = next((i + 1 for i, ln in enumerate(lines) if re.match(r"^\s*seed\s*=", ln)), None)
        raise InputError(f"seed must be a non-negative integer, got {seed!r}", source=src, line=line, field="seed")
    table = data.get("parameters", {})
    if not isinstance(table, dict):
        raise InputError("'parameters' must be a table of [parameters.NAME] sections", source=src,
                         field="parameters")
    out: dict[str, object] = {}
    for key, entry in table.items():
        where = where_for(key)
        name, scale = key, 1.0
        if key.endswith("_deg") and key[:-4] in params.INFO:
            name, scale = key[:-4], math.pi / 180.0
            if params.INFO[name].unit != "rad":
                raise where(f"'{name}' is not an angle ({params.INFO[name].unit}); drop the _deg suffix", None)
        if name not in params.INFO:
            raise where(f"unknown parameter {key!r}; known: {', '.join(params.NAMES)} "
                        "(angles also as NAME_deg)", None)
        if name in out:
            raise where(f"'{name}' is given twice (in radians and in degrees)", None)
        out[name] = _distribution(name, entry, scale, base, where)
    ordered = {name: out[name] for name in params.NAMES if name in out}
    return DispersionSpec(parameters=ordered, seed=seed, source=src)


def load_spec(path) -> DispersionSpec:
    """Read a ``dispersions.toml`` (see the module docstring); numeric-only.

    Parameters
    ----------
    path : path-like
    """
    path = Path(path)
    if not path.is_file():
        raise InputError("dispersion spec not found", source=path)
    text = path.read_text(encoding="utf-8")
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as err:
        match = re.search(r"line (\d+)", str(err))
        raise InputError(f"not valid TOML: {err}", source=path,
                         line=int(match.group(1)) if match else None) from None
    return spec_from_dict(data, source=path, text=text)
