"""``ironbark aero build`` on every rocket of issue 13's list, as a user runs it.

Goal (issue 13): the default build succeeds to Mach 2 on every rocket in
../shared/reference/flights, examples/ and the OpenRocket fixtures in <= 60 s
per rocket on this (2-core) machine, and no table has a negative zero-alpha
pressure-plus-base CA.

Each rocket is one fresh process, ``nice -n 10 python -m ironbark_opt.cli aero
build FILE --out TMP --no-progress --no-resume --json`` (default Mach grid,
angles, mesh and workers), one after the other.  Printed per rocket: wall time
and the CPU time of the process and its Mach-number workers, Mach numbers in
the table, panels (subsonic / supersonic mesh), PASS/FAIL against 60 s wall,
the minimum over Mach of CA_pressure + CA_base at alpha 0, and the 1-minute
load average before and after (the machine is shared: when the load is above
the core count the wall time is mostly other people's, the CPU time is the
figure to compare between runs).

With ``--keep DIR`` the tables are kept there; ``--compare DIR`` compares every
table with the one of the same rocket in DIR (an earlier run, e.g. of the
starting commit with ``--root``): the largest |difference| of any coefficient
relative to that coefficient's largest |value| in the table.

Run:  python benchmarks/bench_aero_build_all.py [--only NAME ...] [--root TREE]
          [--keep DIR] [--compare DIR] [--workers N]
"""
from __future__ import annotations

import argparse
import json
import os
import re
import resource
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
SHARED = (ROOT / ".." / ".." / "shared").resolve()
if not SHARED.is_dir():
    SHARED = (ROOT / ".." / "shared").resolve()
GOAL_S = 60.0


def rockets() -> list[tuple[str, Path]]:
    """(label, file) of every rocket of the issue's list that exists here."""
    out = []
    for f in sorted((SHARED / "reference" / "flights").glob("*/rocket_geometry.toml")):
        out.append((f"flight:{f.parent.name}", f))
    for f in sorted(ROOT.glob("examples/*/*.toml")):
        if f.stem == f.parent.name:                    # the rocket file, not dispersions.toml
            out.append((f"example:{f.stem}", f))
    for f in sorted((SHARED / "fixtures").rglob("*.ork")):
        out.append((f"ork:{f.stem}", f))
    return out


def _slug(label: str) -> str:
    return re.sub(r"[^A-Za-z0-9_.-]+", "_", label)


def _uptime() -> str:
    try:
        return subprocess.run(["uptime"], capture_output=True, text=True).stdout.strip()
    except OSError:
        return "load average " + " ".join(f"{x:.2f}" for x in os.getloadavg())


def build(root: Path, rocket: Path, out: Path, workers: int | None, timeout: float):
    """(wall [s], cpu [s], json result or None, error text)."""
    cmd = ["nice", "-n", "10", sys.executable, "-m", "ironbark_opt.cli", "aero", "build",
           str(rocket), "--out", str(out), "--no-progress", "--no-resume", "--json"]
    if workers is not None:
        cmd += ["--workers", str(workers)]
    env = dict(os.environ, PYTHONPATH=str(root), MPLBACKEND="Agg")
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    t0 = time.perf_counter()
    try:
        proc = subprocess.run(cmd, env=env, cwd=str(rocket.parent), capture_output=True,
                              timeout=timeout)
    except subprocess.TimeoutExpired:
        return time.perf_counter() - t0, float("nan"), None, f"timeout after {timeout:g} s"
    wall = time.perf_counter() - t0
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    if proc.returncode != 0:
        err = proc.stderr.decode().strip().splitlines()
        return wall, cpu, None, f"exit {proc.returncode}: {err[-1] if err else ''}"[:300]
    return wall, cpu, json.loads(proc.stdout), ""


def _table(csv: Path):
    head = csv.read_text().splitlines()[0].split(",")
    return head, np.loadtxt(csv, delimiter=",", skiprows=1)


def min_zero_alpha_pressure_base(csv: Path) -> tuple[float, float]:
    """(min over Mach of CA_pressure + CA_base at alpha 0, Mach where)."""
    head, x = _table(csv)
    col = {h: k for k, h in enumerate(head)}
    z = x[np.abs(x[:, col["alpha_deg"]]) < 1e-9]
    v = z[:, col["CA_pressure"]] + z[:, col["CA_base"]]
    k = int(np.argmin(v))
    return float(v[k]), float(z[k, col["mach"]])


def compare(a: Path, b: Path) -> str:
    """Largest |a - b| of any coefficient relative to its largest |b| in the table."""
    if not b.is_file():
        return "no reference table"
    if a.read_bytes() == b.read_bytes():
        return "byte-identical"
    ha, x = _table(a)
    hb, y = _table(b)
    if ha != hb or x.shape != y.shape:
        return f"DIFFERENT layout {x.shape} / {y.shape}"
    scale = np.maximum(np.abs(y).max(axis=0), 1e-300)
    rel = np.abs(x - y).max(axis=0) / scale
    k = int(np.argmax(rel))
    return f"max rel. diff {rel[k]:.2g} ({ha[k]})"


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--only", action="append", help="labels containing this text (repeatable)")
    ap.add_argument("--root", type=Path, default=ROOT, help="source tree to run (default this)")
    ap.add_argument("--workers", type=int, default=None, help="--workers (default: the CLI's)")
    ap.add_argument("--keep", type=Path, help="keep the tables in this folder")
    ap.add_argument("--compare", type=Path, help="compare with the tables kept in this folder")
    ap.add_argument("--timeout", type=float, default=1800.0)
    args = ap.parse_args()
    print(f"{os.cpu_count()} CPUs; {_uptime()}")
    print(f"tree {args.root}; `aero build FILE` defaults{'' if args.workers is None else f', --workers {args.workers}'}"
          f"; goal <= {GOAL_S:g} s wall per rocket")
    print(f"{'rocket':34s} {'wall s':>7s} {'cpu s':>7s} {'Mach':>4s} {'panels':>11s} {'<=60s':>5s}"
          f" {'min CA_p+b(a=0)':>16s}  load before/after  table")
    todo = [(lab, f) for lab, f in rockets()
            if not args.only or any(o in lab for o in args.only)]
    n_pass = 0
    with tempfile.TemporaryDirectory(prefix="ironbark-aero-all-") as tmp:
        folder = args.keep or Path(tmp)
        folder.mkdir(parents=True, exist_ok=True)
        for label, f in todo:
            out = folder / _slug(label)
            load0 = os.getloadavg()[0]
            wall, cpu, res, err = build(args.root.resolve(), f, out, args.workers, args.timeout)
            load1 = os.getloadavg()[0]
            if res is None:
                print(f"{label:34s} {wall:7.1f} {cpu:7.1f}  FAILED ({err})  load {load0:.1f}/{load1:.1f}")
                continue
            ok = wall <= GOAL_S
            n_pass += ok
            # a multi-stage rocket: one table per flight configuration (stack, sustainer)
            for k, tab in enumerate(res.get("tables", [res])):
                csv = Path(tab["table_csv"])
                ca_min, m_at = min_zero_alpha_pressure_base(csv)
                cmp = compare(csv, args.compare / csv.name) if args.compare else ""
                name = label if "configuration" not in tab else f"{label}:{tab['configuration']}"
                head = (f"{wall:7.1f} {cpu:7.1f} {len(res['mach']):4d}" if k == 0 else f"{'':20s}")
                print(f"{name:34s} {head} {tab['panels']:5d}/{tab['panels_supersonic']:5d} "
                      f"{'PASS' if ok else 'FAIL':>5s} {ca_min:+9.4f} @M{m_at:<5g}  {load0:5.1f}/{load1:5.1f}  {cmp}",
                      flush=True)
    print(f"{n_pass}/{len(todo)} within {GOAL_S:g} s; {_uptime()}")


if __name__ == "__main__":
    main()
