"""Air brakes (any deployable drag device): drag table and deployment schedule.

Drag: a table of the brakes' drag coefficient against deployment level
(0 = stowed, 1 = fully open) and Mach, read from a CSV with columns
``deployment_level, mach, cd`` (RocketPy's air-brake drag-curve layout,
e.g. the camoes team's ``drag_airbrakes.csv``).  Two meanings of ``cd``:

- ``increment``: the brakes' own drag coefficient, added to the rocket's
  axial-force coefficient (RocketPy ``override_rocket_drag=False``);
- ``total``: the whole rocket's drag coefficient with the brakes at that
  deployment (RocketPy ``override_rocket_drag=True``).  Only the brakes'
  share ``cd(M, d) - cd(M, 0)`` is added to the rocket's own drag model, so
  the rocket's drag is not counted twice; with the rocket flying the same
  team curve as its power-off drag, this equals the override.

Both are referred to ``reference_area`` (default: the rocket's reference
area) and evaluated symbolically with a cubic B-spline over the grid
(``casadi.interpolant``), inputs clamped to the grid.

Deployment ``d`` [-] (symbolic-safe, :meth:`BrakeSchedule.deployment`):
the brakes act only in the coast (after burnout; competition rules such as
EuRoC's forbid deploying under thrust) and open along the C1 "smoothstep"
``S(u) = 3u^2 - 2u^3`` on ``u`` in [0, 1] (0 below, 1 above), so apogee stays
a smooth function of the schedule's parameters (no switch inside a step):

- ``time``: ``d = L S(r (t - t0) / (1.5 L))`` with level ``L`` =
  ``p[airbrake_level]``, start ``t0`` = ``p[airbrake_start_time]`` [s after
  ignition] and rate limit ``r`` [1/s]: the largest opening rate
  ``max dd/dt = 1.5 L / tau`` equals ``r`` exactly.
- ``altitude`` / ``mach`` / ``vertical_speed``: ``d = L S(u)`` with ``u`` the
  distance of the trigger variable past its threshold over ``ramp`` (in the
  trigger's unit: m AGL rising, Mach falling, m/s falling); the opening
  then takes ``ramp / |ds/dt|`` seconds, and the flight reports its largest
  opening rate so the rate limit can be checked.
- ``controller``: a user's Python function of the sampled state (numeric
  only, :mod:`ironbark_opt.dynamics.controlled`); between samples the
  deployment is held at ``p[airbrake_level]`` (zero-order hold).
"""
from __future__ import annotations

import csv
import importlib.util
import math
from dataclasses import dataclass
from pathlib import Path
from typing import Any, Callable

import casadi as ca
import numpy as np

from ironbark_opt import _math as m
from ironbark_opt.aero.table import spline_degree
from ironbark_opt.errors import InputError
from ironbark_opt.validate import is_float

TRIGGERS = ("time", "altitude", "mach", "vertical_speed", "controller")
DRAG_MEANINGS = ("increment", "total")
#: unit of ``start`` and ``ramp`` for each trigger
TRIGGER_UNITS = {"time": "s", "altitude": "m", "mach": "-", "vertical_speed": "m/s", "controller": "-"}
_LEVEL_FLOOR = 1e-3   # [-] keeps the time ramp finite when an optimiser drives the level to 0


def smoothstep(u):
    """C1 ramp: 0 for u <= 0, ``3u^2 - 2u^3`` on [0, 1], 1 for u >= 1 [-]; symbolic-safe."""
    uc = m.clip(u, 0.0, 1.0)
    return uc * uc * (3.0 - 2.0 * uc)


@dataclass(frozen=True)
class BrakeDrag:
    """Drag-coefficient increment of the brakes on a (deployment, Mach) grid.

    Parameters
    ----------
    deployment : array (n_d,) [-]
        Increasing deployment levels, 0 (stowed) to 1 (open).
    mach : array (n_m,) [-]
        Increasing Mach numbers.
    delta_cd : array (n_d, n_m) [-]
        Drag-coefficient increment over the stowed rocket, on ``reference_area``.
    reference_area : float or None [m^2]
        None: the rocket's reference area.
    source : str
    """

    deployment: np.ndarray
    mach: np.ndarray
    delta_cd: np.ndarray
    reference_area: float | None = None
    source: str = ""

    def function(self) -> ca.Function:
        """The B-spline ``(d, M) -> delta_cd`` (built once): cubic on an axis of four or
        more points, linear otherwise (the AeroTable rule, ``spline_degree``)."""
        fn = self.__dict__.get("_fn")
        if fn is None:
            degree = [spline_degree(self.deployment.size), spline_degree(self.mach.size)]
            fn = ca.interpolant("airbrake_cd", "bspline", [self.deployment, self.mach],
                                np.asarray(self.delta_cd, dtype=float).ravel(order="F"), {"degree": degree})
            object.__setattr__(self, "_fn", fn)
        return fn

    def evaluate(self, deployment, mach):
        """``delta_cd`` [-] at ``deployment`` [-] and ``mach`` [-], inputs clamped
        to the grid; symbolic-safe (a CasADi expression for symbolic inputs)."""
        d = m.clip(deployment, float(self.deployment[0]), float(self.deployment[-1]))
        mc = m.clip(mach, float(self.mach[0]), float(self.mach[-1]))
        out = self.function()(ca.vertcat(d, mc)) if m.is_symbolic(d, mc) else \
            np.array(self.function()(np.vstack([np.ravel(d), np.ravel(mc)]))).reshape(np.shape(d))
        return out


def read_brake_drag(path, *, meaning: str = "increment", reference_area: float | None = None) -> BrakeDrag:
    """Read a ``deployment_level, mach, cd`` CSV (header optional; any row
    order; a full grid) into :class:`BrakeDrag`; numeric-only.

    Parameters
    ----------
    path : path-like
    meaning : {'increment', 'total'}
        See the module docstring.
    reference_area : float or None [m^2]
    """
    path = Path(path)
    if meaning not in DRAG_MEANINGS:
        raise InputError(f"drag_is must be one of {', '.join(DRAG_MEANINGS)}, got {meaning!r}", field="drag_is")
    if not path.is_file():
        raise InputError("file not found", source=path)
    order, rows = (0, 1, 2), []
    with open(path, newline="", encoding="utf-8-sig") as fh:
        for n, rec in enumerate(csv.reader(fh), start=1):
            cells = [c.strip() for c in rec]
            if not cells or not any(cells) or cells[0].startswith("#"):
                continue
            if not all(is_float(c) for c in cells):
                if rows:
                    raise InputError(f"expected three numbers (deployment_level, mach, cd), got {rec!r}",
                                     source=path, line=n)
                names = [c.lower() for c in cells]
                try:
                    order = (next(i for i, c in enumerate(names) if "deploy" in c),
                             next(i for i, c in enumerate(names) if "mach" in c),
                             next(i for i, c in enumerate(names) if c.startswith("cd") or "drag" in c))
                except StopIteration:
                    raise InputError(f"header must name the columns deployment_level, mach and cd, got {rec!r}",
                                     source=path, line=n) from None
                continue
            if len(cells) != 3:
                raise InputError(f"expected three columns (deployment_level, mach, cd), got {len(cells)}",
                                 source=path, line=n)
            vals = [float(c) for c in cells]
            if not all(math.isfinite(v) for v in vals):
                raise InputError("non-finite value", source=path, line=n)
            if vals[order[2]] < 0:       # a negative drag coefficient is a thrust, not a brake
                raise InputError(f"cd must be >= 0, got {vals[order[2]]:g}", source=path, line=n, field="cd")
            if vals[order[1]] < 0:
                raise InputError(f"mach must be >= 0, got {vals[order[1]]:g}", source=path, line=n, field="mach")
            rows.append((n, vals[order[0]], vals[order[1]], vals[order[2]]))
    if not rows:
        raise InputError("no data rows (expected deployment_level, mach, cd)", source=path)
    d_grid = np.unique([r[1] for r in rows])
    m_grid = np.unique([r[2] for r in rows])
    for grid, what in ((d_grid, "deployment levels"), (m_grid, "Mach numbers")):
        if grid.size < 2:
            raise InputError(f"the table needs at least two {what}", source=path)
    if d_grid[0] < 0 or d_grid[-1] > 1:
        raise InputError(f"deployment levels must lie in [0, 1], got {d_grid[0]:g}..{d_grid[-1]:g}", source=path)
    if meaning == "total" and d_grid[0] != 0:
        raise InputError("drag_is = 'total' needs the stowed row (deployment_level 0) to subtract", source=path)
    cd = np.full((d_grid.size, m_grid.size), np.nan)
    for n, d, mach, c in rows:
        i, j = np.searchsorted(d_grid, d), np.searchsorted(m_grid, mach)
        if not np.isnan(cd[i, j]):
            raise InputError(f"deployment {d:g}, Mach {mach:g} given twice", source=path, line=n)
        cd[i, j] = c
    if np.isnan(cd).any():
        i, j = np.argwhere(np.isnan(cd))[0]
        raise InputError(f"incomplete grid: no value for deployment {d_grid[i]:g} at Mach {m_grid[j]:g} "
                         f"({d_grid.size} x {m_grid.size} expected)", source=path)
    if meaning == "total":
        cd = cd - cd[0:1, :]
    return BrakeDrag(d_grid, m_grid, cd, reference_area, str(path))


def load_controller(spec: str, base: Path | None = None) -> Callable:
    """The Python function ``"file.py:function"`` names (path relative to
    ``base``); numeric-only.  It is called as ``f(time_s, state) -> deployment``
    with ``state`` a dict of ``altitude_agl_m``, ``vz_mps``, ``speed_mps``,
    ``mach``, ``deployment`` (the current one) and ``time_s``."""
    if not isinstance(spec, str) or ":" not in spec:
        raise InputError(f"controller must be 'file.py:function', got {spec!r}", field="controller")
    file, _, name = spec.rpartition(":")
    path = Path(file) if base is None else (Path(base) / file)
    if not path.is_file():
        raise InputError(f"controller file not found: {path}", field="controller")
    mod_spec = importlib.util.spec_from_file_location(f"ironbark_controller_{path.stem}", path)
    module = importlib.util.module_from_spec(mod_spec)
    try:
        mod_spec.loader.exec_module(module)
    except Exception as exc:                         # a user's file: report, don't crash
        raise InputError(f"controller file failed to load: {type(exc).__name__}: {exc}", source=path,
                         field="controller") from None
    func = getattr(module, name, None)
    if not callable(func):
        raise InputError(f"no function {name!r} in the controller file", source=path, field="controller")
    return func


@dataclass(frozen=True)
class BrakeSchedule:
    """When and how far the brakes open (see the module docstring).

    Parameters
    ----------
    drag : BrakeDrag
    trigger : {'time', 'altitude', 'mach', 'vertical_speed', 'controller'}
    start : float
        Threshold in the trigger's unit: [s after ignition], [m AGL] (rising),
        Mach [-] (falling) or vertical speed [m/s] (falling); the nominal
        ``airbrake_start_time`` for 'time'.
    level : float [-]
        Deployment held once open (nominal ``airbrake_level``), in (0, 1].
    rate : float or None [1/s]
        Opening-rate limit (time trigger and controller: enforced).
    ramp : float or None
        State triggers: trigger-variable travel over which the brakes open.
    controller : callable or None
    sampling_rate : float or None [Hz]
        Controller sampling rate.
    """

    drag: BrakeDrag
    trigger: str = "time"
    start: float = 0.0
    level: float = 1.0
    rate: float | None = None
    ramp: float | None = None
    controller: Any = None
    sampling_rate: float | None = None

    def __post_init__(self):
        if self.trigger not in TRIGGERS:
            raise InputError(f"trigger must be one of {', '.join(TRIGGERS)}, got {self.trigger!r}", field="trigger")
        if not 0.0 < self.level <= 1.0:
            raise InputError(f"level must be in (0, 1], got {self.level}", field="level")
        if self.trigger in ("time", "controller") and (self.rate is None or self.rate <= 0):
            raise InputError(f"the {self.trigger} trigger needs a deployment rate limit rate > 0 [1/s]", field="rate")
        if self.trigger in ("altitude", "mach", "vertical_speed") and (self.ramp is None or self.ramp <= 0):
            raise InputError(f"the {self.trigger} trigger needs ramp > 0 [{TRIGGER_UNITS[self.trigger]}]: "
                             "the trigger-variable travel over which the brakes open", field="ramp")
        if self.trigger == "controller" and (self.controller is None or not self.sampling_rate
                                             or self.sampling_rate <= 0):
            raise InputError("the controller trigger needs controller = 'file.py:function' and "
                             "sampling_rate > 0 [Hz]", field="controller")

    @property
    def differentiable(self) -> bool:
        """False for a Python controller (numeric only)."""
        return self.trigger != "controller"

    def deployment(self, t, altitude_agl, mach, vz, P):
        """Deployment level [-] in the coast; symbolic-safe.

        Parameters
        ----------
        t : [s] since ignition; altitude_agl : [m]; mach : [-]; vz : [m/s] up
        P : dict of parameters (``airbrake_level``, ``airbrake_start_time``)
        """
        level = P["airbrake_level"]
        if self.trigger == "controller":
            return m.clip(level, 0.0, 1.0)
        if self.trigger == "time":
            u = (t - P["airbrake_start_time"]) * self.rate / (1.5 * m.fmax(level, _LEVEL_FLOOR))
        elif self.trigger == "altitude":
            u = (altitude_agl - self.start) / self.ramp
        elif self.trigger == "mach":
            u = (self.start - mach) / self.ramp
        else:
            u = (self.start - vz) / self.ramp
        return level * smoothstep(u)

    def nominal(self) -> dict:
        """Nominal parameter values this schedule sets (name -> SI value)."""
        out = {"airbrake_level": self.level}
        if self.trigger == "time":
            out["airbrake_start_time"] = self.start
        return out
