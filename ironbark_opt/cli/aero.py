"""``ironbark aero``: aerodynamic tables from geometry (panel solver).

* ``ironbark aero build ROCKET.toml`` — mesh the rocket, sweep Mach x
  alpha with the built-in panel solver (subsonic and supersonic, the
  transonic gap bridged; supersonic through an external PANAIR with
  ``--panair``), add friction and base drag, write an AeroTable (CSV +
  JSON) into ``tables/``.
* ``ironbark aero plot TABLE`` — CA, CN, Cm and CP position vs Mach and
  alpha.
"""
from __future__ import annotations

import math
import re
import warnings
from pathlib import Path

import click
import numpy as np

from ironbark_opt.cli.common import check_output_path, emit, handle_errors, json_option
from ironbark_opt.errors import InputError


def _floats(text: str, name: str) -> np.ndarray:
    try:
        vals = np.array([float(v) for v in text.split(",") if v.strip()])
    except ValueError as exc:
        raise InputError(f"expected comma-separated numbers, got {text!r}", field=name) from exc
    if len(vals) == 0 or not np.all(np.isfinite(vals)):
        raise InputError(f"expected comma-separated finite numbers, got {text!r}", field=name)
    if np.any(np.diff(vals) <= 0):
        raise InputError("expected a strictly increasing list", field=name)
    return vals


#: Highest Mach number built: the methods are checked to Mach 3.95 (Allen & Perkins' fin-body
#: tunnel data, tests/validation/test_allen_finbody.py); beyond ~5 real-gas effects start.
MAX_MACH = 5.0
#: Mesh refinement: panels grow with its square and the dense solve with its fourth power
#: (refine 4 is ~16x the panels of the default mesh, already hours of solving).
MAX_REFINE = 4.0
MAX_WORKERS = 256


@click.group("aero")
def aero_group():
    """Aerodynamic tables from the rocket's geometry (panel solver)."""


@aero_group.command("build")
@click.argument("rocket", type=click.Path(dir_okay=False))
@click.option("--mach", default=None,
              help="Mach numbers (comma-separated; default 0.05,0.2,0.35,0.5,0.6,0.7,0.8,0.9,"
                   "0.95,1.0,1.05,1.1,1.2,1.5,2.0, extended in steps of 0.5 to 1.3 x the "
                   "rocket's peak Mach from a flight on the file's own aerodynamics). Between "
                   "the critical Mach number and 1.2 the table is the transonic model "
                   "(panair.transonic).")
@click.option("--alpha-deg", default="0,2,4,6,8,12,16,20", show_default=True,
              help="Angles of attack solved by the panel method [deg] (comma-separated, "
                   "from 0); 30, 45, 60, 75, 90 deg are added by the high-angle model.")
@click.option("--out", "out", default=None, type=click.Path(),
              help="Table path stem (default tables/<rocket name>; a two-stage rocket (.ork, or "
                   "TOML with [[stage]]) writes STEM-stack and STEM-sustainer; an .ork with "
                   "parallel boosters STEM, STEM-core and STEM-booster).")
@click.option("--workers", default=2, show_default=True, help="Parallel processes (Mach).")
@click.option("--refine", default=1.0, show_default=True, help="Mesh refinement factor.")
@click.option("--panair", "use_panair", is_flag=True,
              help="Solve the supersonic Mach numbers with an external PANAIR (IRONBARK_PANAIR).")
@click.option("--no-progress", is_flag=True, help="No progress bar.")
@click.option("--no-resume", is_flag=True,
              help="Solve every Mach number again instead of reusing the ones a previous "
                   "(interrupted or failed) build of the same mesh saved next to the table.")
@json_option
@handle_errors
def build(rocket, mach, alpha_deg, out, workers, refine, use_panair, no_progress, no_resume,
          as_json):
    """Build the AeroTable of ROCKET (a rocket TOML or OpenRocket .ork file).

    A serial multi-stage rocket (.ork, or a TOML with [[stage]]) gets one table per
    flight configuration: OUT-stack
    (every stage, before the first separation), OUT-sustainer (the top stage
    alone; OUT-upper<n> for the top n stages of a taller stack), each meshed from
    its own geometry; fly them with one --table per table."""
    from ironbark_opt.vehicle import load_rocket_geometry, load_stage_configurations
    from panair.rocket_table import default_mach_grid, rocket_table

    mach_v = None if mach is None else _floats(mach, "--mach")
    alpha_v = _floats(alpha_deg, "--alpha-deg")
    if alpha_v[0] != 0.0:
        raise InputError("the first angle must be 0 (the zero-lift drag is read there)",
                         field="--alpha-deg")
    if np.any(alpha_v > 90.0):
        raise InputError("total angles of attack must be within 0..90 deg", field="--alpha-deg")
    if mach_v is not None and (np.any(mach_v <= 0) or np.any(mach_v > MAX_MACH)):
        raise InputError(f"Mach numbers must be in (0, {MAX_MACH:g}]", field="--mach")
    if not 1 <= workers <= MAX_WORKERS:
        raise InputError(f"must be in 1..{MAX_WORKERS}, got {workers}", field="--workers")
    if not 0 < refine <= MAX_REFINE:
        raise InputError(f"must be in (0, {MAX_REFINE:g}], got {refine}", field="--refine")
    if out is not None:
        check_output_path(out, "--out")
    if Path(rocket).suffix.lower() == ".ork":
        from ironbark_opt.cli.aero_parallel import build_parallel, ork_with_boosters
        doc = ork_with_boosters(rocket)
        if doc is not None:             # parallel boosters: one table per flight configuration
            return build_parallel(doc, rocket, mach_v, alpha_v, out, workers=workers, refine=refine,
                                  use_panair=use_panair, progress=not no_progress and not as_json,
                                  resume=not no_resume, as_json=as_json)
    configs = load_stage_configurations(rocket)
    if configs is None:
        rk, aero_spec = load_rocket_geometry(rocket)
        parts = [(None, rk)]
    else:                               # serial stages: one table per flight configuration
        from ironbark_opt.rocket.specs import AeroSpec
        aero_spec = AeroSpec() if Path(rocket).suffix.lower() == ".ork" else load_rocket_geometry(rocket)[1]
        parts = [(c, c.rocket) for c in configs]
    # the flight for the grid's reach only once the file is known to be a rocket
    peak = estimated_peak_mach(rocket) if mach_v is None else None
    if mach_v is None:
        mach_v = default_mach_grid(peak)
    if out is None:
        out = default_out(parts[0][1].name)
    def one(conf, rk, pool=None):
        stem = Path(out) if conf is None else Path(f"{out}-{conf.key}")
        ckpt = None if no_resume else Path(str(stem) + ".solved")
        extra = {"rocket_file": str(rocket), "peak_mach_estimate": peak,
                 **(conf.metadata() if conf is not None else {})}
        try:
            table = rocket_table(rk, aero_spec, mach_v, alpha_v, refine=refine, workers=workers,
                                 progress=not no_progress and not as_json, use_panair=use_panair,
                                 checkpoint_dir=ckpt, extra_metadata=extra, pool=pool)
        except InputError as err:       # the panel geometry's own checks: name the rocket file
            if err.source is not None:
                raise
            raise InputError(err.message, source=rocket, field=err.field) from None
        return conf, rk, stem, ckpt, table

    if len(parts) > 1 and workers > 1:
        built = _configurations_together(one, parts, workers)
    else:
        built = [one(conf, rk) for conf, rk in parts]
    # every table solved before any is written: a failed build leaves no part of the set
    results, lines = [], []
    for conf, rk, stem, ckpt, table in built:
        res, line = _save(table, rk, stem, ckpt, "" if conf is None else f"{conf.key}: ")
        if conf is not None:
            res = {"configuration": conf.key, "stages": list(conf.stages), "length_m": rk.length(), **res}
        results.append(res)
        lines.append(line)
    common = {"mach": mach_v, "peak_mach_estimate": peak, "alpha_deg": np.degrees(built[0][4].alpha)}
    if configs is None:
        emit({**results[0], **common}, as_json, lines[0])
        return
    import shlex
    fly = " ".join(f"--table {shlex.quote(r['table_csv'])}" for r in results)
    emit({"tables": results, **common}, as_json,
         "\n".join(lines) + f"\nfly them: ironbark simulate {shlex.quote(str(rocket))} {fly}")


def _configurations_together(one, parts, workers: int) -> list:
    """``one(conf, rocket, pool)`` of every configuration at once, each in a thread,
    their Mach numbers in one pool of ``workers`` processes, the costliest first
    (:class:`panair.mach_pool.MachPool`): no core idles between the configurations'
    sweeps.  The first failure is raised once every thread has stopped (the queued
    jobs cancelled)."""
    from concurrent.futures import FIRST_EXCEPTION, CancelledError, ThreadPoolExecutor, wait

    from panair.mach_pool import MachPool
    with MachPool(workers) as pool, ThreadPoolExecutor(max_workers=len(parts)) as threads:
        futures = [threads.submit(one, conf, rk, pool) for conf, rk in parts]
        try:
            wait(futures, return_when=FIRST_EXCEPTION)
        finally:
            if not all(f.done() and f.exception() is None for f in futures):
                pool.cancel_queued()
        wait(futures)
    errors = [f.exception() for f in futures if f.exception() is not None]
    if errors:          # the failure, not the other configurations' cancelled jobs
        raise next((e for e in errors if not isinstance(e, CancelledError)), errors[0])
    return [f.result() for f in futures]


def default_out(name: str) -> Path:
    """The table stem ``aero build`` writes without ``--out``: tables/<rocket name>."""
    return Path("tables") / (re.sub(r"[^A-Za-z0-9_.-]+", "_", name).strip("_") or "rocket")


def _save(table, rk, stem, ckpt, label: str) -> tuple[dict, str]:
    """Write ``table`` at ``stem``, drop its per-Mach saves, warn about the methods
    some Mach numbers needed; (JSON result, one human line)."""
    Path(stem).parent.mkdir(parents=True, exist_ok=True)
    csv_path, json_path = table.save(stem)
    if ckpt is not None and ckpt.is_dir():          # built: the per-Mach saves are not needed
        import shutil
        shutil.rmtree(ckpt, ignore_errors=True)
    md = table.metadata
    extrapolated, inclination, sonic_le = method_warnings(md, label)
    n_sup = md.get("panels_supersonic", 0)
    result = {"table_csv": str(csv_path), "table_json": str(json_path), "panels": md["panels"],
              "panels_supersonic": n_sup, "alpha_deg_extrapolated": extrapolated,
              "mach_local_inclination": inclination, "mach_sonic_leading_edge": sonic_le,
              "mach_cp_clipped": md.get("mach_cp_clipped", []),
              "reference_area_m2": rk.reference_area(), "mach_critical": md.get("mach_critical"),
              "reference_length_m": 2.0 * rk.reference_radius(), "moment_reference_x_m": 0.0}
    human = (f"{label}wrote {csv_path} and {json_path}: {len(table.mach)} Mach x {len(table.alpha)} alpha, "
             f"{md['panels']} panels ({n_sup} supersonic), includes {', '.join(table.includes)}")
    return result, human


def method_warnings(md: dict, label: str = "") -> tuple:
    """Warn (each message prefixed by ``label``) about the Mach numbers and angles a
    table's metadata ``md`` says were not solved by linear theory as such; returns
    (alpha_deg_extrapolated, mach_local_inclination, mach_sonic_leading_edge)."""
    extrapolated = md.get("alpha_deg_extrapolated", {})
    if extrapolated:
        warnings.warn(f"{label}the panel solution did not solve every angle of attack (linear supersonic "
                      "theory's limits, or a subsonic local pressure past the singular bound); continued "
                      "with Jorgensen's potential-flow shape at Mach: " + "; ".join(
                          f"{m} ({', '.join(f'{a:g}' for a in al)} deg)"
                          for m, al in extrapolated.items()))
    inclination = md.get("mach_local_inclination", [])
    if inclination:
        warnings.warn(f"{label}linear supersonic theory has no solution at Mach "
                      + ", ".join(f"{m:g}" for m in inclination)
                      + " (panels steeper than the Mach cone, or non-physical pressure beyond a local "
                        "singularity): those Mach numbers use the local-inclination method (tangent cone / "
                        "tangent wedge, no fin-body carry-over; less accurate)")
    clipped = md.get("mach_cp_clipped", [])
    if clipped:
        warnings.warn(f"{label}linear supersonic theory's pressure at a local singularity (a fin tip's "
                      "corners, a near-sonic edge) clipped to vacuum / stagnation at Mach "
                      + ", ".join(f"{m:g}" for m in clipped))
    sonic_le = md.get("mach_sonic_leading_edge", [])
    if sonic_le:
        warnings.warn(f"{label}a fin leading edge is sonic at Mach " + ", ".join(f"{m:g}" for m in sonic_le)
                      + ": linear theory's integrable edge load kept there (Jones & Cohen)")
    return extrapolated, inclination, sonic_le


def estimated_peak_mach(rocket, config: str | None = None) -> float | None:
    """The rocket's peak Mach number [-] from one flight of the file as it is (its own
    aerodynamics: drag curves, a table, or the empirical model; its motor and launch),
    which sets how far the default Mach grid reaches (issue 13: 1.3 x the peak); a staged
    rocket's is the whole staged flight's (stack and sustainer: every configuration's
    table gets the same grid); ``config``: an .ork flight configuration (default: the
    file's selected one); None (and a warning) when the file cannot be flown (e.g.
    no motor resolvable)."""
    from ironbark_opt import load_setup, simulate
    try:
        return float(simulate(load_setup(rocket, config=config)).summary_values["max_mach"])
    except Exception as err:        # best effort: the build itself does not need a flight
        warnings.warn(f"no flight to estimate the peak Mach number ({err}); the default Mach "
                      "grid ends at 2")
        return None


@aero_group.command("plot")
@click.argument("table", type=click.Path(dir_okay=False))
@click.option("--out", "out", default=None, type=click.Path(), help="Image file (default TABLE.png).")
@json_option
@handle_errors
def plot(table, out, as_json):
    """Plot CA, CN, Cm and CP position of TABLE vs Mach and alpha."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from ironbark_opt.aero.table import AeroTable
    from ironbark_opt.cli.common import PLOT_SUFFIXES, atomic_write
    out = Path(out) if out else Path(table).with_suffix(".png")
    check_output_path(out, "--out", PLOT_SUFFIXES)
    t = AeroTable.load(table)
    for name in ("CA", "CN", "Cm"):
        if not t.has(name):
            raise InputError(f"table has no '{name}' coefficient", source=table, field=name)
    fig = table_figure(t, Path(table).stem)
    try:
        atomic_write(out, lambda tmp: fig.savefig(tmp, dpi=120))
    finally:
        plt.close(fig)
    emit({"image": str(out)}, as_json, f"wrote {out}")


def table_figure(t, name: str):
    """The 2 x 2 figure of ``aero plot``: CA vs Mach, CN and Cm vs alpha, CP position vs
    Mach, of the AeroTable ``t`` titled ``name``."""
    import matplotlib.pyplot as plt
    a_deg = np.degrees(t.alpha)
    # one colour per curve, in the order of its angle / Mach number (the default cycle has
    # 10 colours: a table's 13 angles and 15 Mach numbers would share them)
    c_alpha = plt.get_cmap("viridis")(np.linspace(0.0, 0.92, len(a_deg)))
    c_mach = plt.get_cmap("plasma")(np.linspace(0.0, 0.9, len(t.mach)))
    fig, ax = plt.subplots(2, 2, figsize=(11, 8))
    for j, a in enumerate(a_deg):
        ax[0, 0].plot(t.mach, t.values("CA")[:, j], "o-", ms=3, color=c_alpha[j], label=f"{a:g} deg")
    ax[0, 0].set(xlabel="Mach [-]", ylabel="CA [-]", title="axial force")
    ax[0, 0].legend(fontsize=7, title="alpha")
    for i, m in enumerate(t.mach):
        ax[0, 1].plot(a_deg, t.values("CN")[i], "o-", ms=3, color=c_mach[i], label=f"M {m:g}")
        ax[1, 0].plot(a_deg, t.values("Cm")[i], "o-", ms=3, color=c_mach[i], label=f"M {m:g}")
    ax[0, 1].set(xlabel="alpha [deg]", ylabel="CN [-]", title="normal force")
    ax[0, 1].legend(fontsize=7)
    ax[1, 0].set(xlabel="alpha [deg]", ylabel=f"Cm [-] about x = {t.moment_reference_x:g} m",
                 title="pitching moment")
    cn, cm = t.values("CN"), t.values("Cm")
    ok = np.abs(cn) > 1e-9
    xcp = np.where(ok, t.moment_reference_x - cm / np.where(ok, cn, 1.0) * t.reference_length,
                   np.nan)
    for j, a in enumerate(a_deg):
        if a > 0:
            ax[1, 1].plot(t.mach, xcp[:, j], "o-", ms=3, color=c_alpha[j], label=f"{a:g} deg")
    ax[1, 1].set(xlabel="Mach [-]", ylabel="x_cp [m aft of nose tip]", title="centre of pressure")
    ax[1, 1].legend(fontsize=7, title="alpha")
    fig.suptitle(f"{name}: includes {', '.join(t.includes)}")
    fig.tight_layout()
    return fig


COMMANDS = [aero_group]
