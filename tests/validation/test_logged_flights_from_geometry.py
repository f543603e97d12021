"""Logged flights with their OpenRocket design (issue 13): the apogee from the .ork
geometry alone (panel table built by ``ironbark aero build``), flown with the stored
simulation of that flight (its launch site, rail, wind) and the design's motor, against
the altimeter's logged apogee, next to the prediction OpenRocket stored in the same file.

- NUSTARS FT1 (AeroTech L1940X, sim "Michiana - FT1"): goal, ours closer than OpenRocket's.
- NUSTARS FT2 (AeroTech M1315W, sim "Pence FT2") and Imperial College APEX I (Cesaroni
  I216, sim "Final Sim (?)", the one the team's launch-day commit names): their motors are
  not in the fixtures; the thrust curves are OpenRocket 15.03's own copies
  (tests/data/thrustcurve/openrocket-15.03, digests equal to the ones the .ork files
  store).  Printed; bounded at the measured state so a regression fails (session 6:
  FT2 +2.5 % vs OpenRocket's +2.9 %; APEX +5.1 % vs OpenRocket's +1.0 %, not closer: its
  boost runs through Mach 0.95-1.1 where our transonic rise starts at the fins' critical
  Mach 0.88 and OpenRocket's nose-cone rise from about Mach 0.7; session 9: APEX +5.9 %,
  its Mach 1.2-2 rows now solved by linear theory (pointed fin tips' closure slivers,
  panair.solver.supersonic._pointed_tip_closure) instead of local inclination; session 13,
  the body's viscous cross-flow of Allen & Perkins / Jorgensen in place of K = 1.1: FT1
  -0.56 -> -0.61 %, FT2 +2.53 -> +2.05 %, APEX +5.89 -> +5.86 % on the panel tables;
  empirical FT1 +1.17 -> +1.10 %, FT2 +6.41 -> +5.79 %, APEX +8.37 -> +8.32 %, measured
  without the guides' drag).
- Session 12, the launch guides' drag (ironbark_opt.aero.protuberance; FT1/FT2 carry
  three 12.4 mm x 14.2 mm buttons, APEX none): FT1 -0.56 -> -2.08 % (OpenRocket +1.89 %:
  the FT1 goal is NOT MET any more), FT2 +2.53 -> +1.10 %, APEX +5.89 % unchanged;
  empirical path FT1 +1.17 -> -0.45 %, FT2 +6.41 -> +4.81 %.
- Session 16, McCoy's transonic drag of ogival noses in place of their share of the sonic
  anchor (panair.transonic item 4; NASA TR R-100 nose data): FT1 -2.13 -> -2.09 %, FT2
  +0.64 -> +0.72 %, APEX +5.86 -> +6.26 % (less nose drag at Mach 0.9-1.2: APEX's boost
  runs through it).
- Session 17, the subsonic fins meshed 12 x 20 instead of 6 x 30 (panair.mesh.MeshOptions),
  pointed tips closed by a strip one fin thickness wide (on the old sine strips the finer
  mesh gave APEX a sliver panel, |Cp| 1.8e4, and aero build refused): FT1 -2.09 -> -2.08 %,
  FT2 +0.72 -> +0.77 %, APEX +6.26 -> +6.27 %.
- Session 20, a set of one or two fins meshed at 45 deg, its roll average (FT1/FT2's
  two-fin camera housings were in the pitch plane, no lift): FT1 -2.08 -> -2.15 %, FT2
  +0.77 -> +0.51 %, APEX +6.25 % unchanged.
- Session 21, no leading-edge suction on the fins (panair.sweep: the fins' axial force at
  incidence held at its zero-incidence value): FT1 -2.15 -> -2.18 %, FT2 +0.51 -> +0.41 %,
  APEX +6.25 % unchanged.
- Session 22, our axial-force coefficient beside the one OpenRocket stored along its own
  trajectory (APEX's file stores it; FT1/FT2's do not): printed per Mach number, boost and
  coast.  APEX's +6.25 % against OpenRocket's +1.01 % is mostly the boost: OpenRocket keeps
  the whole base drag while the motor burns, we take the 38 mm motor's cross-section off
  it (68 % of the base; Niskanen 2013 sec. 3.4.5): without that relief APEX flies +2.16 %,
  FT1 -2.97 %, FT2 -1.57 % (with it +6.25, -2.17, +0.42 %).

Source: tests/data/telemetry (copied from ../shared/fixtures/telemetry; README there:
FT1 2198.6 m AGL, FT2 2669.0 m AGL, APEX 9335 ft = 2845.3 m AGL, max of the logs).
Slow (a whole table build per rocket, 40-90 s idle).
"""
import json
from pathlib import Path

import pytest
from click.testing import CliRunner

DATA = Path(__file__).parents[1] / "data"
TEL = DATA / "telemetry"
MOTORS = DATA / "thrustcurve" / "openrocket-15.03"

#: name: (.ork, stored simulation, logged apogee [m AGL], bound on |ours/logged - 1|, goal
#: "closer than OpenRocket's stored prediction").  FT1's goal is not met since the launch
#: guides' drag (session 12/13: -2.08 % vs OpenRocket's +1.89 %); bounded at that state.
FLIGHTS = {
    "FT1": ("nustars-2026-ft1-telemega.ork", "Michiana - FT1", 2198.6, 0.03, True),
    "FT2": ("nustars-2026-ft2-telemega.ork", "Pence FT2", 2669.0, 0.04, False),
    "APEX": ("icl-apex1-pnut.ork", "Final Sim (?)", 2845.3, 0.07, False),
}


@pytest.mark.slow
@pytest.mark.parametrize("name", FLIGHTS)
def test_logged_flight_from_ork_geometry(name, tmp_path, monkeypatch):
    from ironbark_opt.cli import main
    from ironbark_opt.openrocket import read_ork
    ork_name, sim_name, logged, bound, goal = FLIGHTS[name]
    ork = TEL / ork_name
    monkeypatch.setenv("IRONBARK_CACHE_DIR", str(tmp_path / "cache"))
    monkeypatch.setenv("IRONBARK_OFFLINE", "1")
    monkeypatch.setenv("IRONBARK_MOTOR_PATH", str(MOTORS))
    stem = tmp_path / name
    res = CliRunner().invoke(main, ["aero", "build", str(ork), "--out", str(stem), "--no-progress", "--json"])
    assert res.exit_code == 0, res.output
    flown = {}
    for label, extra in (("panel", ["--table", f"{stem}.csv"]), ("empirical", [])):
        res = CliRunner().invoke(main, ["simulate", str(ork), "--config", sim_name, *extra, "--json"])
        assert res.exit_code == 0, res.output
        flown[label] = json.loads(res.output[res.output.index("{"):])["apogee_agl_m"]
    stored = read_ork(ork).simulation(sim_name).summary["apogee_m"]
    ours = flown["panel"]
    e_ours, e_emp, e_or = ours / logged - 1, flown["empirical"] / logged - 1, stored / logged - 1
    print(f"\n{name} ({sim_name}): logged {logged:.1f} m; ours (panel table from the .ork) {ours:.1f} m "
          f"({100 * e_ours:+.2f} %); ours empirical {flown['empirical']:.1f} m ({100 * e_emp:+.2f} %); "
          f"OpenRocket stored {stored:.1f} m ({100 * e_or:+.2f} %); "
          f"{'closer' if abs(e_ours) < abs(e_or) else 'NOT closer'} than OpenRocket"
          + (" (goal NOT MET)" if goal and abs(e_ours) >= abs(e_or) else ""))
    assert abs(e_ours) < bound
    rows = _drag_beside_openrocket(ork, sim_name, f"{stem}.csv")
    for phase, mach, ours_ca, or_ca, ours_parts, or_parts in rows:
        print(f"  {phase} Mach {mach:.3f}: CA ours {ours_ca:.3f} (friction {ours_parts[0]:.3f}, "
              f"pressure {ours_parts[1]:+.3f}, base {ours_parts[2]:.3f}), OpenRocket {or_ca:.3f} "
              f"(friction {or_parts[0]:.3f}, pressure {or_parts[1]:+.3f}, base {or_parts[2]:.3f}): "
              f"{100 * (ours_ca / or_ca - 1):+.1f} %")
    # measured (session 22, APEX, the one file storing its drag): coast within -13.8 ...
    # +3.1 % (our zero pressure drag below the critical Mach number 0.88 against
    # OpenRocket's 0.018-0.129); boost -16.6 ... -38.0 % (OpenRocket keeps the whole base
    # drag while the motor burns, we take the motor's cross-section off it, 68 % of
    # APEX's base: Niskanen 2013 sec. 3.4.5)
    coast = [100 * (o / r - 1) for phase, m, o, r, _, _ in rows if phase == "coast" and m <= 0.95]
    assert all(abs(e) <= 20.0 for e in coast), coast


def _drag_beside_openrocket(ork, sim_name, table_csv, machs=(0.3, 0.5, 0.7, 0.8, 0.9, 1.0)):
    """Our axial-force coefficient against the one OpenRocket stored along its own
    trajectory of ``sim_name`` (where the file stores it): at the stored step nearest
    each of ``machs`` (within 0.03), in the boost and in the coast, our CA at
    OpenRocket's Mach and Reynolds numbers (its Reynolds number is on the rocket's
    length).  Rows (phase, Mach, ours, OpenRocket's, (our friction, pressure, base),
    (its friction, pressure, base)); none when the file stores no flight data."""
    import warnings

    import numpy as np

    from ironbark_opt import load_setup
    from ironbark_opt.aero.table import AeroTable
    from ironbark_opt.openrocket import read_ork
    data = read_ork(ork).flight_data(sim_name)
    if data is None or "ca" not in data:
        return []
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        setup = load_setup(ork, table=table_csv, config=sim_name)
    aero, table = setup.aero, AeroTable.load(table_csv)
    data = data[np.isfinite(data["ca"]) & (data["time_s"] > 0.1)]
    assert abs(float(data["reference_area_m2"].iloc[0]) / aero.reference_area - 1) < 1e-3
    rows = []
    for phase, part in (("boost", data[data["thrust_n"] > 0]), ("coast", data[data["thrust_n"] <= 0])):
        for m in machs:
            near = part[(part["mach"] - m).abs() < 0.03]
            if near.empty:
                continue
            r = near.iloc[int((near["mach"] - m).abs().argmin())]
            mach, re_m = float(r["mach"]), float(r["reynolds"]) / setup.body_length
            ours = float(aero.axial(mach, 0.0, re_m, phase == "boost"))
            friction = float(aero.friction.CA(mach, re_m))
            pressure = float(table.evaluate("CA_pressure", mach, 0.0))
            rows.append((phase, mach, ours, float(r["ca"]), (friction, pressure, ours - friction - pressure),
                         (float(r["cd_friction"]), float(r["cd_pressure"]), float(r["cd_base"]))))
    return rows
