"""``ironbark aero build ROCKET.ork`` for a rocket with parallel boosters: the tables
of its flight configurations (:mod:`panair.parallel_table`).

Writes ``<out>.csv/.json`` (the stack: core with the boosters attached, the
table ``simulate ROCKET.ork --table <out>.csv`` takes), ``<out>-core`` (the core
alone, after separation) and ``<out>-booster`` (one booster alone in its own
frame, flown from separation to the ground).  Not a command module: called by
:func:`ironbark_opt.cli.aero.build`.
"""
from __future__ import annotations

import shutil
import time
import warnings
from pathlib import Path

import numpy as np

from ironbark_opt.cli.common import emit


def ork_with_boosters(path):
    """The OrkDocument of ``path`` when it has parallel boosters, else None."""
    from ironbark_opt.openrocket import read_ork
    from ironbark_opt.vehicle import _existing
    doc = read_ork(_existing(path))
    return doc if doc.rocket.pods else None


def peak_mach(doc, rocket) -> float | None:
    """The largest peak Mach number [-] over the file's motor configurations (the
    grid's reach: the file's selected configuration may fly without the boosters'
    motors, slower than with them); None, warned, when none can be flown."""
    from ironbark_opt.cli.aero import estimated_peak_mach
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        peaks = [p for p in (estimated_peak_mach(rocket, c.config_id) for c in doc.configs) if p is not None]
    if not peaks:
        return estimated_peak_mach(rocket)           # its warning says why
    return max(peaks)


def build_parallel(doc, rocket, mach, alpha_deg, out, *, workers: int, refine: float, use_panair: bool,
                   progress: bool, resume: bool, as_json: bool):
    """Build, save and report the three tables (see the module docstring)."""
    from ironbark_opt.cli.aero import default_out, method_warnings
    from ironbark_opt.openrocket.parallel import single_booster_set
    from panair.parallel_table import INTERFERENCE_NOTE, parallel_tables
    from panair.rocket_table import default_mach_grid

    single_booster_set(doc)                           # refused before the flight and the solves
    peak = peak_mach(doc, rocket) if mach is None else None
    if mach is None:
        mach = default_mach_grid(peak)
    out = default_out(doc.name) if out is None else Path(out)
    out = out.with_suffix("") if out.suffix.lower() in (".csv", ".json") else out
    stems = {"stack": out, "core": Path(f"{out}-core"), "booster": Path(f"{out}-booster")}
    names = {f"{k}_table": f"{stems[k].name}.json" for k in ("core", "booster")}
    t0 = time.perf_counter()
    tables = parallel_tables(doc, mach, alpha_deg, refine=refine, checkpoint=out if resume else None,
                             extra_metadata={"rocket_file": str(rocket), "peak_mach_estimate": peak},
                             names=names, workers=workers, progress=progress, use_panair=use_panair)
    build_s = time.perf_counter() - t0
    out.parent.mkdir(parents=True, exist_ok=True)
    written = {}
    for key in ("booster", "core", "stack"):          # the stack, which names the others, last
        csv_path, json_path = tables[key].save(stems[key])
        written[key] = {"table_csv": str(csv_path), "table_json": str(json_path),
                        "panels": tables[key].metadata["panels"],
                        "panels_supersonic": tables[key].metadata.get("panels_supersonic", 0),
                        "reference_area_m2": tables[key].reference_area,
                        "reference_length_m": tables[key].reference_length,
                        "moment_reference_x_m": tables[key].moment_reference_x,
                        "configuration": tables[key].metadata.get("configuration", "")}
    if resume:
        for folder in (f"{out}.solved", f"{out}-booster-roll0.solved", f"{out}-booster-roll1.solved"):
            shutil.rmtree(folder, ignore_errors=True)
    stack = tables["stack"]
    extrapolated, inclination, sonic_le = method_warnings(stack.metadata)
    warnings.warn(INTERFERENCE_NOTE)
    info = stack.metadata["parallel_boosters"]
    result = {**written["stack"], "configurations": written, "parallel_boosters": info,
              "interference_modelled": False, "interference": INTERFERENCE_NOTE,
              "alpha_deg_extrapolated": extrapolated, "mach_local_inclination": inclination,
              "mach_sonic_leading_edge": sonic_le, "mach_cp_clipped": stack.metadata.get("mach_cp_clipped", []),
              "mach": np.asarray(mach, float), "peak_mach_estimate": peak,
              "alpha_deg": np.degrees(stack.alpha), "mach_critical": stack.metadata.get("mach_critical"),
              "build_time_s": build_s}
    human = "\n".join(
        [f"wrote {len(written)} tables ({len(mach)} Mach x {len(stack.alpha)} alpha, {build_s:.0f} s):"]
        + [f"  {key:8s} {w['table_csv']}: {w['configuration']} ({w['panels']} panels)" for key, w in written.items()]
        + [f"fly them with: ironbark simulate '{rocket}' --table {written['stack']['table_csv']}"])
    emit(result, as_json, human)
