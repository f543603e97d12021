"""Design study: geometry variants -> panel table each -> ballast solve each -> one tidy table.

A team sweeping fin planforms (or the ballast bay position) asks, for every
variant: how much ballast puts apogee on the target, and what are the
stability margin and rail-exit speed then?  :func:`design_study` answers
with one row per variant:

1. **Variants** from a grid (:func:`design_grid`, every combination) or a
   seeded sample (:func:`design_samples`, uniform in ranges), of the
   :data:`DESIGN_PARAMETERS` (fin span, root and tip chord, sweep, fin
   position, ballast position).
2. **Aerodynamics per variant**: the built-in panel solver
   (:func:`panair.sweep.sweep_pressure`) gives ``CN`` and ``Cm`` on a
   subsonic Mach x alpha grid — split into one task per (variant, Mach) on
   the executor.  ``CA`` is the empirical pressure-drag estimate of the
   variant (:func:`ironbark_opt.aero.empirical_drag.pressure_drag_table`);
   skin friction (with the variant's fin area) and base drag are added by
   the aero model.  The panel method's own subsonic pressure ``CA`` is not
   used: by d'Alembert's paradox it is zero for inviscid subsonic flow
   and what remains is discretisation error.
3. **Ballast per variant**: :func:`ironbark_opt.optimise.ballast.solve_ballast`,
   one task per variant, the setup shipped to the worker.

Executors as in :mod:`ironbark_opt.executors` (``"local"``, ``"local:N"``,
``"dask://HOST:PORT"``).  Numeric-only.
"""
from __future__ import annotations

import dataclasses
import itertools
import math
from dataclasses import dataclass, field
from pathlib import Path
from typing import Mapping, Sequence

import numpy as np
import pandas as pd

from ironbark_opt.errors import InputError, IronbarkError

#: Design parameters [m] -> (output column, what it changes)
DESIGN_PARAMETERS = {
    "fin_span": ("fin_span_m", "span of every trapezoidal fin set"),
    "fin_root_chord": ("fin_root_chord_m", "root chord"),
    "fin_tip_chord": ("fin_tip_chord_m", "tip chord"),
    "fin_sweep_length": ("fin_sweep_length_m", "axial distance root to tip leading edge"),
    "fin_x": ("fin_x_m", "root leading edge, aft of the nose tip"),
    "ballast_x": ("ballast_x_m", "ballast position, aft of the nose tip"),
}
_FIN_FIELDS = {"fin_span": "span", "fin_root_chord": "root_chord", "fin_tip_chord": "tip_chord",
               "fin_sweep_length": "sweep_length", "fin_x": "x"}
#: Default grids: subsonic Mach (the built-in solver's range for finned rockets) [-], alpha [deg]
MACH = (0.05, 0.3, 0.6, 0.8, 0.9)
ALPHA_DEG = (0.0, 2.0, 5.0, 10.0, 20.0)


def _check_names(names) -> None:
    for name in names:
        if name not in DESIGN_PARAMETERS:
            raise InputError(f"unknown design parameter {name!r}: expected one of {', '.join(DESIGN_PARAMETERS)}",
                             field=name)


def design_grid(**values: Sequence[float]) -> list[dict]:
    """Every combination of the given values [m], e.g. ``design_grid(fin_span=[0.09, 0.11])``."""
    _check_names(values)
    if not values:
        raise InputError("a design grid needs at least one parameter", field="grid")
    names = list(values)
    axes = []
    for name in names:
        v = np.atleast_1d(np.asarray(values[name], dtype=float))
        if v.ndim != 1 or v.size == 0 or not np.all(np.isfinite(v)):
            raise InputError("expected a non-empty list of finite numbers [m]", field=name)
        axes.append(v)
    return [dict(zip(names, map(float, combo))) for combo in itertools.product(*axes)]


def design_samples(n: int, ranges: Mapping[str, tuple[float, float]], *, seed: int = 0) -> list[dict]:
    """``n`` variants drawn uniformly in ``ranges`` {name: (low, high) [m]} (seeded, reproducible)."""
    _check_names(ranges)
    if isinstance(n, bool) or not isinstance(n, (int, np.integer)) or n < 1:
        raise InputError(f"n must be a positive integer, got {n!r}", field="n")
    rng = np.random.default_rng(seed)
    cols = {}
    for name, bounds in ranges.items():
        try:
            lo, hi = (float(b) for b in bounds)
        except (TypeError, ValueError):
            raise InputError("expected (low, high) [m]", field=name) from None
        if not lo <= hi:
            raise InputError(f"expected low <= high, got ({lo}, {hi})", field=name)
        cols[name] = rng.uniform(lo, hi, int(n))
    return [{k: float(v[i]) for k, v in cols.items()} for i in range(int(n))]


def apply_design(rf, case: Mapping[str, float]):
    """A copy of the RocketFile ``rf`` with the variant's fin geometry (numeric-only).

    Fin parameters apply to every trapezoidal fin set; ``ballast_x`` is
    applied by the ballast solve, not here.
    """
    from ironbark_opt.rocket import Rocket

    _check_names(case)
    fins = {f: case[p] for p, f in _FIN_FIELDS.items() if p in case}
    if not fins:
        return rf
    comps, found = [], False
    for comp in rf.rocket.components:
        if type(comp).__name__ == "TrapezoidalFins":
            comp, found = dataclasses.replace(comp, **fins), True
        comps.append(comp)
    if not found:
        raise InputError("fin parameters need a trapezoidal fin set in the rocket", source=rf.source,
                         field=", ".join(p for p in case if p in _FIN_FIELDS))
    old = rf.rocket
    rocket = Rocket(old.name, comps, mass_override=old.mass_override, reference_radius=old._reference_radius)
    return dataclasses.replace(rf, rocket=rocket)


def _panel_task(geometry, mach, alpha, sref, lref, options):
    """Executor task: CN, Cm (n_alpha,) at one Mach number for one geometry (moment about the nose tip)."""
    from panair.geometry_adapter import is_symmetric
    from panair.sweep import sweep_pressure
    coeffs, info = sweep_pressure(geometry, [mach], alpha, sref=sref, lref=lref, xref=0.0, options=options,
                                  symmetric=is_symmetric(geometry), workers=1, progress=False)
    return coeffs["CN"][0], coeffs["Cm"][0], int(info["panels"])


def _ballast_task(payload, target, kwargs):
    """Executor task: ("ok", BallastSolution) or ("error", message)."""
    from ironbark_opt.optimise.ballast import solve_ballast
    try:
        return "ok", solve_ballast(payload.load(), target, **kwargs)
    except IronbarkError as err:
        return "error", str(err)


def variant_setup(rf, rocket, panel_rows, mach, alpha, *, rail_exit: str = "forward_button"):
    """FlightSetup of one variant: panel CN/Cm + empirical pressure CA table (numeric-only).

    Parameters
    ----------
    rf : RocketFile (already :func:`apply_design`-ed)
    rocket : Rocket (``rf.dry_rocket(motor)``)
    panel_rows : list of (CN, Cm) arrays, one per Mach [-], Cm about the nose tip
    mach : 1-D array [-]; alpha : 1-D array [rad]
    """
    from ironbark_opt.aero.empirical_drag import pressure_drag_table
    from ironbark_opt.aero.model import build_aero_model
    from ironbark_opt.aero.table import AeroTable
    from ironbark_opt.vehicle import setup_from_file

    setup = setup_from_file(rf, rail_exit=rail_exit)
    ca_tab = pressure_drag_table(rocket)
    ca = np.array([[float(ca_tab.evaluate("CA", m, 0.0)) for _ in alpha] for m in mach])
    table = AeroTable(mach, alpha, {"CA": ca, "CN": np.array([r[0] for r in panel_rows]),
                                    "Cm": np.array([r[1] for r in panel_rows])},
                      reference_area=rocket.reference_area(), reference_length=2 * rocket.reference_radius(),
                      moment_reference_x=0.0, includes=("pressure",),
                      metadata={"generator": "ironbark_opt.analysis.design_study (panel CN/Cm, empirical CA)"})
    aero = build_aero_model(rocket, table=table, surface_roughness=rf.aero.surface_roughness,
                            re_transition=rf.aero.re_transition, jet_area=setup.motor.nozzle_exit_area or 0.0)
    return dataclasses.replace(setup, aero=aero)


@dataclass(frozen=True)
class DesignStudy:
    """Result of :func:`design_study` (immutable): one row per variant.

    Attributes
    ----------
    name : str
    target : str
    parameters : tuple of str
        Varied design parameters (registry names of :data:`DESIGN_PARAMETERS`).
    """

    name: str
    target: str
    parameters: tuple
    _table: pd.DataFrame = field(repr=False)

    def __repr__(self) -> str:
        t = self._table
        return (f"DesignStudy({self.name!r}: {len(t)} variants of {', '.join(self.parameters)}, "
                f"{int(t['feasible'].sum())} feasible)")

    def to_dataframe(self) -> pd.DataFrame:
        """Tidy table (a copy): variant, parameters [m], CN_alpha_per_rad, panels, table (file or
        None), ballast_kg, apogee_agl_m, zero_ballast_apogee_agl_m, static_margin_rail_exit_cal,
        rail_exit_speed_mps, feasible, status."""
        return self._table.copy()

    def to_dict(self) -> dict:
        return {"rocket": self.name, "target": self.target, "parameters": list(self.parameters),
                "variants": self._table.to_dict(orient="records")}

    def best(self) -> pd.Series | None:
        """Feasible variant with the least ballast (None if none is feasible)."""
        ok = self._table[self._table["feasible"]]
        return None if ok.empty else ok.loc[ok["ballast_kg"].idxmin()]

    def summary(self) -> str:
        cols = [DESIGN_PARAMETERS[p][0] for p in self.parameters]
        lines = [f"Design study of {self.name}: {len(self._table)} variants, target {self.target}",
                 "  " + " ".join(f"{c:>18s}" for c in cols)
                 + f" {'CN_a /rad':>9s} {'ballast kg':>10s} {'margin cal':>10s} {'feasible':>8s}"]
        for _, row in self._table.iterrows():
            lines.append("  " + " ".join(f"{row[c]:18.4f}" for c in cols)
                         + f" {row['CN_alpha_per_rad']:9.2f} {row['ballast_kg']:10.3f}"
                         f" {row['static_margin_rail_exit_cal']:10.2f} {'yes' if row['feasible'] else 'no':>8s}")
        best = self.best()
        lines.append("  least ballast: variant " + (str(int(best["variant"])) if best is not None else "none feasible"))
        return "\n".join(lines)


def design_study(path, cases: Sequence[Mapping[str, float]], target, *, mach=MACH, alpha_deg=ALPHA_DEG,
                 mesh=None, executor=None, rail_exit: str = "forward_button", tables_dir=None,
                 **ballast_kwargs) -> DesignStudy:
    """Panel table and ballast solve for every design variant (numeric-only).

    Parameters
    ----------
    path : path-like
        Rocket TOML file (the baseline design).
    cases : sequence of mapping
        Variants, e.g. from :func:`design_grid` or :func:`design_samples`
        ({name: value [m]}; names in :data:`DESIGN_PARAMETERS`).
    target : str or float
        Apogee target as in :func:`~ironbark_opt.optimise.ballast.solve_ballast`.
    mach : sequence [-]
        Mach grid of the panel tables (subsonic: at most 0.9 with fins).
    alpha_deg : sequence [deg]
        Angle-of-attack grid.
    mesh : panair.mesh.MeshOptions, optional
        Panel density (default: the mesher's defaults).
    executor : see :func:`ironbark_opt.executors.get_executor`
        Panel solves run as one task per (variant, Mach), ballast solves
        as one task per variant.
    rail_exit : str
    tables_dir : path-like, optional
        Write each variant's AeroTable there (``variant-0000.csv/.json``;
        the ``table`` column of the result names it).
    ballast_kwargs
        Passed to ``solve_ballast`` (mass_max, min_margin, ...).
    """
    from ironbark_opt.executors import SetupPayload, run_chunks, use_executor
    from ironbark_opt.rocket.toml_io import load_rocket_toml
    from ironbark_opt.vehicle import load_motor_for
    from panair.geometry_adapter import from_rocket

    cases = [dict(c) for c in cases]
    if not cases:
        raise InputError("no design variants given", field="cases")
    names = tuple(dict.fromkeys(k for c in cases for k in c))
    _check_names(names)
    if any(set(c) != set(names) for c in cases):
        raise InputError("every variant must give the same parameters", field="cases")
    mach = np.asarray(mach, dtype=float)
    alpha = np.radians(np.asarray(alpha_deg, dtype=float))
    base = load_rocket_toml(path)
    motor = load_motor_for(base.motor)
    variants, panel_tasks = [], []
    for k, case in enumerate(cases):
        rf = apply_design(base, case)
        rocket = rf.dry_rocket(motor)
        variants.append((rf, rocket))
        geom = from_rocket(rocket)
        sref, lref = rocket.reference_area(), 2 * rocket.reference_radius()
        panel_tasks += [(geom, float(m), alpha, sref, lref, mesh) for m in mach]
    with use_executor(executor) as ex:
        panels = run_chunks(ex, _panel_task, panel_tasks, label="panel")
        rows, ballast_tasks = [], []
        for k, (case, (rf, rocket)) in enumerate(zip(cases, variants)):
            chunk = panels[k * len(mach):(k + 1) * len(mach)]
            setup = variant_setup(rf, rocket, chunk, mach, alpha, rail_exit=rail_exit)
            table_file = None
            if tables_dir is not None:
                Path(tables_dir).mkdir(parents=True, exist_ok=True)
                table_file = str(setup.aero.table.save(Path(tables_dir) / f"variant-{k:04d}")[0])
            kwargs = dict(ballast_kwargs)
            if "ballast_x" in case:
                kwargs["ballast_x"] = case["ballast_x"]
            ballast_tasks.append((SetupPayload.of(setup), target, kwargs))
            cn = np.array([r[0] for r in chunk])
            # normal-force slope from the two smallest angles at the lowest Mach [1/rad]
            rows.append({"variant": k, **{DESIGN_PARAMETERS[n][0]: case[n] for n in names},
                         "CN_alpha_per_rad": float((cn[0, 1] - cn[0, 0]) / (alpha[1] - alpha[0]))
                         if len(alpha) > 1 else math.nan, "panels": chunk[0][2], "table": table_file})
        solved = run_chunks(ex, _ballast_task, ballast_tasks, label="ballast")
    for row, (status, value) in zip(rows, solved):
        if status == "ok":
            v = value.values
            row.update(ballast_kg=v["ballast_kg"], apogee_agl_m=v["apogee_agl_m"],
                       zero_ballast_apogee_agl_m=v["zero_ballast_apogee_agl_m"],
                       static_margin_rail_exit_cal=v["static_margin_rail_exit_cal"],
                       rail_exit_speed_mps=v["rail_exit_speed_mps"], feasible=bool(value.feasible),
                       status=value.status)
        else:
            row.update(ballast_kg=math.nan, apogee_agl_m=math.nan, zero_ballast_apogee_agl_m=math.nan,
                       static_margin_rail_exit_cal=math.nan, rail_exit_speed_mps=math.nan, feasible=False,
                       status=value)
    return DesignStudy(base.rocket.name, str(target), names, pd.DataFrame(rows))


def plot_design_study(study: DesignStudy, x: str | None = None, y: str = "ballast_kg", *, ax=None,
                      filename=None):
    """``y`` against design parameter ``x`` (default the first), one line per value of the others.

    Feasible variants are filled markers, infeasible ones hollow.  Returns the figure.
    """
    import matplotlib.pyplot as plt

    df = study.to_dataframe()
    x = x or study.parameters[0]
    xcol = DESIGN_PARAMETERS.get(x, (x,))[0]
    if xcol not in df or y not in df:
        raise InputError(f"columns {xcol!r} / {y!r} not in the study ({', '.join(df.columns)})", field="x/y")
    if ax is None:
        fig, ax = plt.subplots(figsize=(6, 4))
    else:
        fig = ax.figure
    others = [DESIGN_PARAMETERS[p][0] for p in study.parameters if DESIGN_PARAMETERS[p][0] != xcol]
    groups = df.groupby(others) if others else [((), df)]
    for key, g in groups:
        g = g.sort_values(xcol)
        key = key if isinstance(key, tuple) else (key,)
        label = ", ".join(f"{c} = {v:.4g}" for c, v in zip(others, key)) or None
        line, = ax.plot(g[xcol], g[y], "-", label=label)
        ok = g["feasible"].to_numpy(bool)
        ax.plot(g[xcol][ok], g[y][ok], "o", color=line.get_color())
        ax.plot(g[xcol][~ok], g[y][~ok], "o", mfc="none", color=line.get_color())
    ax.set_xlabel(xcol)
    ax.set_ylabel(y)
    ax.set_title(f"{study.name}: design study, target {study.target}")
    if others:
        ax.legend(fontsize="small")
    ax.grid(True, alpha=0.3)
    if filename:
        fig.savefig(filename, bbox_inches="tight")
    return fig
