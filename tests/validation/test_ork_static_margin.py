"""Static margin, CP and CG early in the climb vs the values OpenRocket stored in each .ork.

Source: the stored simulations of OpenRocket's example files (tests/data/ork and
tests/data/ork/stability; every
file with flight data whose simulation is up to date, i.e. flown with the design as
saved).  The compared state is one stored row: on the ascent, before the first burnout,
stage separation or ejection, between Mach 0.02 and 0.5, the row of least angle of
attack (OpenRocket's CP moves with the angle of attack through its body lift; asserted
below 1 degree, where that shift is negligible).

Ours at that row: the CP of our Barrowman build-up (:func:`~ironbark_opt.aero.model.
lift_geometry`, linear part) at the stored Mach; the CG of our mass build-up plus the
motors at the stored time: a motor with a local file (tests/data/ork/motors) at its mass
then if it burns from launch (the bottom stage's, lit at launch without delay), else
full; the rest of OpenRocket's stored "Motor mass" shared among the other tubes; every
motor's CG at half its length (OpenRocket's RASP convention, as
tests/validation/test_ork_mass.py).  OpenRocket rounds stored values to 3 significant
figures.

Tolerances: CP and static margin 0.1 cal, CG 1 % of the rocket's length.  Designs with
pods (parallel stages) are left out: their lift is built by
:mod:`ironbark_opt.openrocket.parallel`, not by the single-body build-up compared here.
"""
from __future__ import annotations

import math
from functools import lru_cache
from pathlib import Path

import pytest

from ironbark_opt.aero.model import lift_geometry
from ironbark_opt.openrocket import convert
from ironbark_opt.openrocket import read_ork as _read_ork
from ironbark_opt.openrocket.build import geometry
from ironbark_opt.openrocket.motors import _local
from ironbark_opt.rocket.rocket import Rocket

DATA = Path(__file__).parents[1] / "data" / "ork"
#: designs compared here only (tests/data/ork/stability/README.md)
STABILITY = DATA / "stability"
_ENDS = ("burnout", "stageseparation", "ejectioncharge", "apogee")


@lru_cache(maxsize=None)
def read_ork(path):
    return _read_ork(path)


def _stored_row(sim):
    """The compared row of a stored simulation (column -> value), or None."""
    df = sim.data()
    if df is None or df.empty or not {"cp_x_m", "cg_x_m", "mach"} <= set(df.columns):
        return None
    t_end = min([t for t, kind, _ in sim.events() if kind.lower() in _ENDS] or [math.inf])
    rows = df[(df["time_s"] < t_end) & df["cp_x_m"].notna() & df["cg_x_m"].notna()
              & (df["mach"] > 0.02) & (df["mach"] < 0.5)]
    if rows.empty:
        return None
    row = rows.loc[rows["angle_of_attack_rad"].abs().idxmin()]
    return {k: float(v) for k, v in row.items()}


def _cases():
    for path in sorted(DATA.glob("*.ork")) + sorted(STABILITY.glob("*.ork")):
        doc = read_ork(path)
        if doc.rocket.pods:
            continue
        for i, sim in enumerate(doc.simulations):
            if sim.status in ("uptodate", "loaded", "") and _stored_row(sim):
                yield pytest.param(path, i, id=f"{path.stem}:{sim.name}")


def _motors_at(doc, cfg, row):
    """(mass, cg fwd of nozzle, 0, 0) per motor of ``cfg`` at the row's time."""
    bottom = max(s.stage for s in doc.rocket.stages)
    known = {}
    for k, (mount, e) in enumerate(cfg.motors):
        hit = _local(e.designation, e.manufacturer, [DATA / "motors"], e.digest)
        if hit is not None and hit.verified is not False:
            lit = mount.stage == bottom and e.ignition_event in ("automatic", "launch") \
                and e.ignition_delay == 0.0
            known[k] = float(hit.motor.mass(row["time_s"] if lit else 0.0))
    rest = row["motor_mass_kg"] - sum(known[k] * cfg.motors[k][0].cluster_count for k in known)
    tubes = sum(m.cluster_count for k, (m, _) in enumerate(cfg.motors) if k not in known)
    return [(known.get(k, rest / tubes if tubes else 0.0), 0.5 * e.length, 0.0, 0.0)
            for k, (_, e) in enumerate(cfg.motors)]


def _as_openrocket_flies_it(doc):
    """Our Rocket of ``doc``; with an OpenRocket 'base drag hack' transition put back
    (``build.geometry`` leaves it out, tests/unit/test_ork_base_drag_hack.py), since
    OpenRocket's stored CP includes its lift: the comparison is of the Barrowman
    build-up on the same geometry."""
    rocket = geometry(doc)
    hack = doc.rocket.base_drag_hack()
    if hack is None:
        return rocket
    return Rocket(rocket.name, list(rocket.components) + [convert.body_component(hack)],
                  mass_override=rocket.mass_override)


@pytest.mark.parametrize("path,index", list(_cases()))
def test_static_margin_cp_cg_match_openrocket(path, index):
    doc = read_ork(path)
    name = path.name
    sim = doc.simulations[index]
    row = _stored_row(sim)
    cfg = doc.config(sim.config_id) if sim.config_id else doc.config()
    rocket = _as_openrocket_flies_it(doc)
    aref = rocket.reference_area()
    lifts = lift_geometry(rocket).components(row["mach"], aref)
    cp = sum(float(c.cn_alpha) * float(c.x_cp) for c in lifts) / sum(float(c.cn_alpha) for c in lifts)
    cg = doc.launch_mass_properties(cfg, _motors_at(doc, cfg, row)).cg_x
    d = 2 * rocket.reference_radius()
    margin = (cp - cg) / d
    length = doc.length()
    print(f"\n{name} / {sim.name} at t = {row['time_s']:.2f} s, Mach {row['mach']:.2f}, "
          f"AoA {math.degrees(row['angle_of_attack_rad']):.2f} deg: CP {cp:.4f} vs OR {row['cp_x_m']:.4f} m, "
          f"CG {cg:.4f} vs OR {row['cg_x_m']:.4f} m, margin {margin:.2f} vs OR "
          f"{row['stability_margin_cal']:.2f} cal (d {d:.4f} vs OR {row['reference_length_m']:.4f} m)")
    assert abs(row["angle_of_attack_rad"]) < math.radians(1.0)
    assert abs(d - row["reference_length_m"]) <= 0.005 * d + 0.0005   # stored to 3 figures
    assert abs(cp - row["cp_x_m"]) / d < 0.1
    assert abs(cg - row["cg_x_m"]) <= 0.01 * length
    assert abs(margin - row["stability_margin_cal"]) < 0.1
