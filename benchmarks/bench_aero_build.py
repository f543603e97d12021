"""``ironbark aero build`` speed: the Kestrel example at its default mesh, here
against the same command in a checkout of the starting commit (issue 16: goal
>= 3x), the five flights' rocket_geometry.toml files (issue 13: goal <= 60 s per
rocket) and the per-Mach split of one process's CPU time (influence matrices,
LU factorisation, the angles' right-hand sides).

Whole commands are fresh processes run in turn (here, baseline, here, ...) with
the ratio taken pair by pair, wall and CPU (the process and its Mach-number
worker processes); the machine is shared, so the 1-minute load average is
printed next to every run and the CPU ratio is the one to trust when the load
is high.  The first build with an empty kernel cache (Numba compiling, cache in a
temp dir) is timed separately.

Run:  python benchmarks/bench_aero_build.py [--baseline CHECKOUT | --commit 7804b72]
          [--runs 1] [--flights [--flight astra ...]] [--per-mach] [--no-kestrel]

Without ``--baseline`` the tree of ``--commit`` is extracted with ``git archive``
into a temp dir.  Each Kestrel build takes minutes on a loaded 2-core machine
(baseline ~3 CPU-minutes).
"""
from __future__ import annotations

import argparse
import os
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))
sys.path.insert(0, str(ROOT / "benchmarks"))

from bench_commands import timed          # noqa: E402  (wall, cpu of one whole process)

KESTREL = "examples/kestrel/kestrel.toml"
START_COMMIT = "7804b72"


def _env(root: Path, numba_cache: Path | None = None) -> dict:
    env = dict(os.environ, PYTHONPATH=str(root), MPLBACKEND="Agg")
    if numba_cache is not None:
        env["NUMBA_CACHE_DIR"] = str(numba_cache)
    return env


def _build_cmd(rocket: str, out: Path, workers: int) -> list[str]:
    return [sys.executable, "-m", "ironbark_opt.cli", "aero", "build", rocket, "--out", str(out),
            "--no-progress", "--no-resume", "--json", "--workers", str(workers)]


def _load() -> float:
    return os.getloadavg()[0]


def _tables_agree(a: Path, b: Path) -> str:
    x = np.loadtxt(a.with_suffix(".csv"), delimiter=",", skiprows=1)
    y = np.loadtxt(b.with_suffix(".csv"), delimiter=",", skiprows=1)
    if a.with_suffix(".csv").read_bytes() == b.with_suffix(".csv").read_bytes():
        return "byte-identical"
    if x.shape != y.shape:
        return f"DIFFERENT shapes {x.shape} / {y.shape}"
    rel = np.abs(x - y).max() / max(np.abs(y).max(), 1e-300)
    return f"max |difference| / max |value| = {rel:.3g}"


def kestrel(baseline: Path, runs: int, workers: int, tmp: Path) -> None:
    print(f"aero build {KESTREL} (default mesh, {workers} workers), here vs {baseline}:")
    # first run here with an empty kernel cache: the one-off compile
    cold_cache = tmp / "numba-cold"
    load = _load()
    wall, cpu = timed(_build_cmd(KESTREL, tmp / "cold", workers), _env(ROOT, cold_cache), cwd=ROOT,
                      timeout=3600)
    print(f"  here, empty kernel cache (compiles): {wall:7.1f} s wall {cpu:7.1f} s cpu "
          f"(load {load:.1f})")
    ratios_wall, ratios_cpu = [], []
    for k in range(runs):
        res = {}
        for label, root in (("here", ROOT), ("baseline", baseline)):
            load = _load()
            out = tmp / f"{label}{k}"
            res[label] = timed(_build_cmd(KESTREL, out, workers),
                               _env(root, cold_cache if label == "here" else None), cwd=root,
                               timeout=3600)
            print(f"  run {k + 1} {label:8s}: {res[label][0]:7.1f} s wall {res[label][1]:7.1f} s cpu "
                  f"(load {load:.1f} -> {_load():.1f})")
        ratios_wall.append(res["baseline"][0] / res["here"][0])
        ratios_cpu.append(res["baseline"][1] / res["here"][1])
    print(f"  baseline / here: {statistics.median(ratios_wall):.2f}x wall, "
          f"{statistics.median(ratios_cpu):.2f}x cpu (median of {runs} pair(s); goal >= 3)")
    print(f"  tables: {_tables_agree(tmp / 'here0', tmp / 'baseline0')}")


def flights(workers: int, tmp: Path, only=None) -> None:
    print(f"aero build of the flights' rocket_geometry.toml ({workers} workers; goal <= 60 s):")
    for f in sorted((ROOT / "tests/data/flights").glob("*/rocket_geometry.toml")):
        if only and f.parent.name not in only:
            continue
        load = _load()
        rel = str(f.relative_to(ROOT))
        try:
            wall, cpu = timed(_build_cmd(rel, tmp / f.parent.name, workers), _env(ROOT), cwd=ROOT,
                              timeout=3600)
        except (RuntimeError, subprocess.TimeoutExpired) as e:
            print(f"  {f.parent.name:10s} FAILED: {str(e)[-200:]}")
            continue
        import json
        meta = json.loads(Path(str(tmp / f.parent.name) + ".json").read_text())
        print(f"  {f.parent.name:10s} {meta['panels']:6d} panels ({meta['panels_supersonic']:6d} "
              f"supersonic), {len(meta['mach_solved_builtin'])} Mach solved: {wall:7.1f} s wall "
              f"{cpu:7.1f} s cpu, {cpu / workers:6.1f} s cpu/worker (load {load:.1f} -> {_load():.1f})")


def per_mach() -> None:
    """One process, one Mach number at a time: CPU seconds of the influence
    matrices (setup minus LU), the LU factorisation and the solve of all angles."""
    import scipy.linalg

    from ironbark_opt.errors import SolverError
    from ironbark_opt.vehicle import load_rocket_geometry
    from panair.geometry_adapter import from_rocket, is_symmetric
    from panair.mesh import MeshOptions, mesh_rocket
    from panair.rocket_table import DEFAULT_ALPHA_DEG, default_mach_grid
    from panair.solver import MACH_SUBSONIC_MAX, MACH_SUPERSONIC_MIN, build_panels, make_solver
    from panair.solver import kernels, subsonic, supersonic

    lu_time = [0.0]

    def timed_lu(*a, **k):
        t = time.process_time()
        try:
            return scipy.linalg.lu_factor(*a, **k)
        finally:
            lu_time[0] += time.process_time() - t

    subsonic.lu_factor = timed_lu
    causal_init = supersonic.CausalLU.__init__

    def timed_causal(self, *a, **k):
        t = time.process_time()
        try:
            return causal_init(self, *a, **k)
        finally:
            lu_time[0] += time.process_time() - t

    supersonic.CausalLU.__init__ = timed_causal
    t = time.process_time()
    kernels.warm_up()
    print(f"per Mach number, one process (CPU s; kernel load/compile {time.process_time() - t:.2f} s):")
    rk, _ = load_rocket_geometry(str(ROOT / KESTREL))
    geom = from_rocket(rk)
    sym = is_symmetric(geom)
    opt = MeshOptions()
    meshes = {}
    alphas = np.radians(DEFAULT_ALPHA_DEG)
    print("   Mach  panels  influence      LU  solve(8 alpha)")
    for m in default_mach_grid():
        if MACH_SUBSONIC_MAX < m < MACH_SUPERSONIC_MIN:
            continue
        o = opt.for_mach(m) if m >= MACH_SUPERSONIC_MIN else opt
        if o not in meshes:
            meshes[o] = build_panels(mesh_rocket(geom, symmetric=sym, options=o), symmetric=sym)
        lu_time[0] = 0.0
        t0 = time.process_time()
        solver = make_solver(meshes[o], float(m), sref=rk.reference_area(),
                             lref=2 * rk.reference_radius())
        t1 = time.process_time()
        try:
            solver.solve(alphas)
            note = ""
        except SolverError:
            note = " (not every angle solved: the sweep re-solves one by one)"
        t2 = time.process_time()
        print(f"  {m:5.2f} {meshes[o].n:7d} {t1 - t0 - lu_time[0]:10.2f} {lu_time[0]:7.2f} "
              f"{t2 - t1:8.2f}{note}")


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--baseline", type=Path, help="checkout of the starting commit")
    ap.add_argument("--commit", default=START_COMMIT, help="extracted when no --baseline")
    ap.add_argument("--runs", type=int, default=1, help="Kestrel pairs (here, baseline)")
    ap.add_argument("--workers", type=int, default=2)
    ap.add_argument("--flights", action="store_true", help="also the five flights (slow)")
    ap.add_argument("--flight", action="append", help="only this flight (repeatable)")
    ap.add_argument("--per-mach", action="store_true", help="also the in-process per-Mach split")
    ap.add_argument("--no-kestrel", action="store_true", help="skip the Kestrel comparison")
    args = ap.parse_args()
    print(f"{os.cpu_count()} CPUs, load average {' '.join(f'{x:.1f}' for x in os.getloadavg())}")
    with tempfile.TemporaryDirectory(prefix="ironbark-aero-bench-") as tmp:
        tmp = Path(tmp)
        if not args.no_kestrel:
            baseline = args.baseline
            if baseline is None:
                baseline = tmp / "baseline"
                baseline.mkdir()
                tar = subprocess.run(["git", "-C", str(ROOT), "archive", args.commit],
                                     check=True, capture_output=True).stdout
                subprocess.run(["tar", "-x", "-C", str(baseline)], input=tar, check=True)
            kestrel(baseline, args.runs, args.workers, tmp)
        if args.per_mach:
            per_mach()
        if args.flights:
            flights(args.workers, tmp, args.flight)


if __name__ == "__main__":
    main()
