"""Allen's parametric fin-body wind-tunnel data (NASA/TM-2001-210652, via MAPLEAF;
tests/data/aero/allen/finNN: geometry.md and derived.csv, copied from
../shared/reference/aero) against the table ``panair.rocket_table`` builds from the
geometry alone.

Compared per Mach number: forebody CA0 (pressure + skin friction at the tunnel's unit
Reynolds number, no base: the balance measured the forebody), CN-alpha [1/rad] and
the centre of pressure [calibers from the nose tip] from the 3.5 deg secant, as
derived.csv was made.  Goal (issue 13): CA0 within 10 %, CN-alpha within 10 %, CP
within 0.3 caliber at every Mach number, all five fin sets.

Measured (session 4, fins 1 and 5): CA0 -17 ... +29 %, CN-alpha +21 ... +39 % at Mach
0.6-0.9 and -2 ... +14 % at 1.2-2.96 where linear theory solves, CP within 0.9 cal;
the goals are not met.  Mach numbers solved by the local-inclination fallback are
printed, not bounded (no interference, and lift on the whole cylinder).

Assumptions (not in the source): the fins are flat plates of the listed thickness
with rounded edges (as the flight conversions assume where a section is not
published); the surface is smooth to 2 um (MAPLEAF's value).  Slow.
"""
from __future__ import annotations

import math
import re
from pathlib import Path

import numpy as np
import pytest

DATA = Path(__file__).parents[1] / "data" / "aero" / "allen"
FINS = ("fin01", "fin05", "fin09", "fin10", "fin12")
D = 0.0762                                  # body diameter, reference length [m]
X_MRC = 7.0 * D                             # moment reference [m aft of the nose tip]
#: tunnel unit Reynolds number [1/m] by Mach (geometry.md)
RE_PER_M = {0.6: 8.86e6, 0.9: 6.56e6, 1.2: 5.58e6}
RE_PER_M_SUPERSONIC = 6.56e6
TOL_CA, TOL_CNA, TOL_XCP = 0.10, 0.10, 0.3


def _row(text, key):
    m = re.search(r"^\| " + re.escape(key) + r"[^|]*\| ([0-9.]+) m", text, re.M)
    return float(m.group(1))


def _toml(fin: str) -> str:
    g = (DATA / fin / "geometry.md").read_text()
    sweep = float(re.search(r"tip leading edge lies ([0-9.]+) m", g).group(1))
    motor = Path(__file__).parents[1] / "data" / "motors" / "Cesaroni_M1670.eng"
    return f"""
[rocket]
name = "Allen {fin}"
[rocket.mass_override]
mass = 5.0
cg_x = {X_MRC}
I_transverse = 0.5
I_axial = 0.01
[[component]]
type = "nose_cone"
shape = "tangent_ogive"
length = {3 * D}
radius = {D / 2}
[[component]]
type = "body_tube"
length = {9 * D}
radius = {D / 2}
[[component]]
type = "trapezoidal_fins"
count = 2
x = {_row(g, "root leading edge position")}
root_chord = {_row(g, "root chord cr")}
tip_chord = {_row(g, "tip chord ct")}
span = {_row(g, "span per fin s")}
sweep_length = {sweep}
thickness = {_row(g, "thickness")}
section = "rounded"
[aero]
surface_roughness = 2e-6
[motor]
file = "{motor}"
nozzle_x = {12 * D}
[launch]
rail_length = 3.0
"""


def _measured(fin):
    rows = [ln for ln in (DATA / fin / "derived.csv").read_text().splitlines()
            if ln and not ln.startswith("#")]
    head = rows[0].split(",")
    return [dict(zip(head, r.split(","))) for r in rows[1:]]


@pytest.mark.slow
@pytest.mark.parametrize("fin", FINS)
def test_allen_fin_body(fin, tmp_path):
    from ironbark_opt.aero.friction import FrictionDrag
    from ironbark_opt.aero.model import friction_components
    from ironbark_opt.vehicle import load_rocket_geometry
    from panair.rocket_table import rocket_table
    path = tmp_path / f"{fin}.toml"
    path.write_text(_toml(fin))
    rk, spec = load_rocket_geometry(path)
    meas = [r for r in _measured(fin) if float(r["mach"]) <= 4.0]
    mach = np.array([float(r["mach"]) for r in meas])
    alpha = np.radians([0.0, 2.0, 3.5, 5.0])
    t = rocket_table(rk, spec, mach=np.concatenate([[0.05, 0.3], mach]), alpha_deg=np.degrees(alpha))
    fr = FrictionDrag(friction_components(rk, spec.surface_roughness), rk.reference_area(),
                      spec.re_transition)
    ok, worst = [], []
    print(f"\n{fin}: Mach  CA0 meas/ours  err%   CNa meas/ours  err%   xcp meas/ours  d(cal)")
    for r, m in zip(meas, mach):
        re_m = RE_PER_M.get(m, RE_PER_M_SUPERSONIC)
        ca0 = float(t.evaluate("CA_pressure", m, 0.0)) + float(fr.CA(m, re_m))
        a1 = math.radians(3.5)
        cn = float(t.evaluate("CN", m, a1))
        cm = float(t.evaluate("Cm", m, a1)) + cn * X_MRC / D       # Cm about the nose tip -> MRC
        cna = cn / a1
        xcp = X_MRC / D - cm / cn
        e_ca = ca0 / float(r["CA0"]) - 1
        e_cn = cna / float(r["CNa_per_rad"]) - 1
        d_x = xcp - float(r["xcp_cal"])
        good = abs(e_ca) <= TOL_CA and abs(e_cn) <= TOL_CNA and abs(d_x) <= TOL_XCP
        ok.append(good)
        print(f"   {m:4.2f}  {float(r['CA0']):.4f}/{ca0:.4f} {100 * e_ca:+6.1f}   "
              f"{float(r['CNa_per_rad']):6.2f}/{cna:6.2f} {100 * e_cn:+6.1f}   "
              f"{float(r['xcp_cal']):5.2f}/{xcp:5.2f} {d_x:+5.2f}  {'ok' if good else 'NOT MET'}")
        if m not in t.metadata["mach_local_inclination"]:        # linear theory solved it
            worst.append((abs(e_ca), abs(e_cn), abs(d_x)))
    print(f"{fin}: {sum(ok)} of {len(ok)} Mach numbers meet all three goals")
    print(f"{fin}: local-inclination Mach numbers (not bounded): {t.metadata['mach_local_inclination']}")
    w = np.max(np.array(worst), axis=0)
    # regression bounds at the Mach numbers linear theory solved: the measured state of
    # session 4 (CN-alpha 20-40 % high subsonic; the goals are printed per Mach number)
    assert w[0] < 0.35 and w[1] < 0.5 and w[2] < 1.2
