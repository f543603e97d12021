"""Allen's parametric fin-body wind-tunnel data (NASA/TM-2001-210652, via MAPLEAF;
tests/data/aero/allen/finNN: geometry.md, data.csv and derived.csv, copied from
../shared/reference/aero) against the table ``panair.rocket_table`` builds from the
geometry alone.

Compared per Mach number: forebody CA0 (pressure + skin friction at the tunnel's unit
Reynolds number, no base: the balance measured the forebody), CN-alpha [1/rad] and
the centre of pressure [calibers from the nose tip] as the secant between the
measured angles of data.csv (alpha0 ~0 and alpha1 ~2.7-4.1 deg; fins 1 and 9 have no
alpha0 point, so alpha0 = 0 with CN = Cm = 0, as derived.csv assumes), our table
evaluated at the same two angles.  Goal (issue 13): CA0 within 10 %, CN-alpha within
10 %, CP within 0.3 caliber at every Mach number, all five fin sets.

Measured (session 10): 0, 0, 4, 2, 3 of 8 Mach numbers meet all three goals (fins
1, 5, 9, 10, 12; session 9: 0, 0, 1, 3, 2).  Session 13, the body's viscous cross-flow of Allen &
Perkins / Jorgensen (eta(l/d = 12) Cdc(M sin alpha) = 0.70 x 1.20 at these angles) in
place of Galejs' K = 1.1: the secant CN-alpha falls by 0.19-0.20 /rad on every fin set
(the cross-flow's share at 3-4 deg, 0.94 -> 0.72 /rad), CP within 0.02 cal (0.12 on the
local-inclination rows), CA0 unchanged; subsonic CN-alpha fin 1 +26.1 / +36.0 ->
+22.3 / +32.1 %, fin 5 +23.1 / +37.4 -> +20.9 / +35.2 %, fin 10 +0.9 / +1.4 -> -1.7 /
-1.2 %; goals met unchanged (0, 0, 4, 2, 3).  Session 17, the subsonic fins meshed 12 x 20
instead of 6 x 30 (panair.mesh.MeshOptions; closer to PANAIR on the Basic Finner): subsonic
(Mach 0.6 / 0.9) CN-alpha fin 1 +22.3 / +32.1 -> +22.0 / +31.9 %, fin 5 +20.9 / +35.2 ->
+19.5 / +33.0 %, fin 9 +7.5 / +9.2 -> +6.5 / +8.6 %, fin 10 -1.7 / -1.2 -> -3.5 / -2.8 %,
fin 12 +2.2 / +3.6 -> +0.6 / +0.9 %; fin 10's CP at Mach 0.6 -0.27 -> -0.31 cal, so goals
met 0, 0, 5, 2, 3 -> 0, 0, 5, 1, 3 (the finer strips' lift is the converged one: the
coarse strips' excess had covered fin 10's shortfall).  The supersonic CP, 0.2-1.0 cal forward
of the tunnel on every fin set in session 9, was the afterbody (2.2-2.6 cal of body
behind the fins): the supersonic solver had no fin wake, so the fins' potential
jump died out on the body behind them and the afterbody carried a download
(fin 10, Mach 1.6: CN-alpha -1.04 /rad at 11.2 cal; an independent planar estimate
with the same no-wake assumption, w = 0 off the fin in the fin's plane, gives -0.86).
With the wake sheets (panair.solver.supersonic_wake: linear theory's wake, no load,
the trailing-edge potential jump carried aft) the afterbody carries +0.9 ... +2.0 /rad
of carry-over lift, and the CP at Mach 1.6-2.96 is within -0.17 ... +0.25 cal on fins
5, 9, 10, 12 (session 9: -0.79 ... +0.01); fin 1 (single-point secant) +0.02 ... +0.71
at Mach 1.6-2.3; Mach 1.2: -0.02 ... +0.56 (session 9: -0.73 ... -0.23).
What that exposes: supersonic CN-alpha is now high on the short-span fins, fin 10
+14 ... +34 %, fin 5 +10 ... +37 %, fin 1 +21 ... +42 %, while fins 9 and 12 (3 cal
span) are within -4 ... +9 % at Mach 1.2-2 (fin 9 at 2.3 and 2.96: +33 / +27 %, where
the tunnel's CN-alpha drops 26 % from Mach 2 to 2.3); session 9's match there
(fin 10 -2 ... +5 %) was the afterbody's spurious download cancelling it.  Not
resolved: candidates are linear theory's nose (Mach 1.6: 2.84 /rad on the 3-cal
ogive, slender-body theory 2) and, for spans of 0.5 cal, the body boundary layer at
the fin roots (outside a potential solver); Mach 1.2 is transonic for linear theory.
Noticed, not investigated (session 10): a flat delta wing (pointed tip) on a thin body,
our solver vs exact linear theory (Stewart: CL-alpha = 2 pi cot L / E(k)), wing panels
on the wing's area: leading edge 63.4 deg (subsonic) -36 / -30 % at Mach 1.6 / 2.0,
45 deg (supersonic) -15 / -12 %: the fin-side shadow model (no communication around a
subsonic leading edge) and pointed tips deserve a check of their own.
What was ruled out in session 9, with numbers:
the panel mesh (twice finer: CN-alpha fin 1 +0.6 %, fin 5 -1.4 %), the solver (its potential
CN-alpha is within -9 ... +5 % of the independent slender-body interference
estimate below, on all five fins), the single-point secant of fins 1 and 9 (on the
fins that have alpha0 it changes CN-alpha by -1 ... -5 % subsonic), and the body's
turbulent boundary layer at the fin root (a 1/7-power-profile strip estimate takes
12 % off fin 1's fin lift but also 9 % off fin 10's, which has the same span and is
matched to +3 %; no published model adopted).  Mach numbers solved by the
local-inclination fallback are printed, not bounded (no interference, and lift on
the whole cylinder).

Session 14, why fins 1 and 5 are 21-35 % high subsonic (diagnosis; no solver change):
the fins' share of the secant CN-alpha (the configuration minus our body alone, 2.01
/rad potential + 0.61-0.87 /rad cross-flow, printed per fin), tunnel / ours at Mach
0.6 / 0.9: fin 1 0.680 / 0.591, fin 5 0.784 / 0.684, fin 9 0.921 / 0.905, fin 10 1.026
/ 1.018, fin 12 0.976 / 0.962. Ruled out, with numbers: the mesh (twice finer: fin 1
+0.6 / +0.5 %, fin 5 -1.3 / -1.8 %); the compressibility transform (the Mach 0.9 solve
is the incompressible solve of the x/beta-stretched panels to 1e-9 on every panel,
tests/unit/test_panair_goethert.py; on the rocket-level x/beta-stretched geometry,
meshed afresh, fin 1's potential CN-alpha agrees to +0.8 %); the geometry conversion
(fin roots on the body surface, tips at r = 0.0762 / 0.1143 m, fins in the lifting
plane, Sref pi D^2/4); fin thickness (0.5 instead of 2.55 mm: fin 1 -3.3 %, fin 5 +0.7
%, fin 10 -2.3 % in potential CN-alpha); the Kutta edge (a sharp double wedge instead
of the rounded section with its closed trailing edge: fin 1 -2.6 %, fin 10 -3.7 %;
square edges: -8.5 / -8.8 %, both fins alike); the pressure rule (the exact isentropic
relation on the same velocities: fin 1's share -2 % at Mach 0.6, -5 % at 0.9; the
linear rule Cp = -2u is no reference: it gives the body alone 2.95 /rad); the
transonic bridge (Mach 0.6 and 0.9 are solved, not blended). Independent linear theory
agrees with the solver, not with the tunnel: Diederich's fin x the slender-body K_W(B)
+ K_B(W) (fin 1: 1.450 + 0.800) + nose 2 + our cross-flow gives fin 1 6.21 / 6.77, fin
5 14.31 / 15.98 (ours 6.12 / 6.50, 14.42 / 16.28); the 4.93 /rad "matching" fin 1 is
the same sum without the body carry-over K_B(W), which then misses fin 10 by -26 % and
fin 12 by -20 %. Within the tunnel data, fin 1's share is 0.50 of fin 10's (same span
0.5 cal and leading-edge sweep, a third of the area), where linear theory gives 0.83
(Diederich) and slender-body theory 1.0; and the tunnel's fin shares of fins 1 and 5
do not grow from Mach 0.6 to 0.9 (-4 %, +1 %) while those of fins 9, 10, 12 grow as
linear theory says (+15, +3, +10 %; ours +17, +3, +12 %). The ratio falls
monotonically with thickness / mean chord (fin 1 5.0 %, 5 4.3 %, 9 2.5 %, 12 2.3 %, 10
2.0 %) and with the mean-chord Reynolds number (4.5e5 ... 1.05e6 at Mach 0.6); a
viscous section loss cannot produce it through Diederich's formula (fin 1 would need a
section lift slope 0.45 of thin-airfoil theory, fin 5 0.57: implausible for 2-5 %
thick sections). So no fault of the potential solution was found; the short-chord pair
(fins 1 and 5, root chord 1 cal at 8.4 cal) disagrees with the long-chord three and
with every attached-flow method, which points at the data or its geometry (MAPLEAF's
transcription, the report itself not read) or a viscous effect with no published model
here. Not changed.

Session 15, why fin 10 is +14 ... +31 % high supersonic (diagnosis, default unchanged):
the potential CN-alpha split at Mach 0.9 / 1.2 / 1.6 / 2.0 into nose 1.98 / 2.40 / 2.84 /
2.89 (the body alone, the same in every model), fins 3.11 / 4.30 / 3.96 / 3.79 and body
under and behind the fins 1.50 / 3.63 / 2.88 / 2.38 /rad: the fin-body factor (fins +
body) / (wing of the exposed panels alone, 1.98 /rad at Mach 1.2 = slender-wing pi A / 2)
was 3.96 at Mach 1.2 against the slender-body 2.25.  Cause: the source model's fin
plane is a wall outboard of the tip (no side-edge diaphragm), so the tip keeps most of
the two-dimensional lift (rectangular wing, A = 1, Mach 1.6: +24 % of Bonney's value,
tests/unit/test_panair_tip_diaphragm.py); span 0.5 cal fins lie wholly in their tip's
Mach cone.  The thin-wing model with tip diaphragms (supersonic.THIN_WING, off by
default, its docstring has the numbers) gives fin 10 -6.2 / +1.1 / +4.3 / +13.2 / +10.1
% at Mach 1.2 ... 2.96 and a factor of 2.46 / 2.10 / 2.24.

Session 17, Mach 3.95 (and fin 1 at 2.96) fell to local inclination on every fin set
(tangent cone / wedge, no fin-body carry-over; not bounded): the 3-cal ogive's tip needs
a conical tip over 58 % of the nose there, and the limit was 10 %.  With the limit at 60 %
(panair.mesh.TIP_MAX_FRACTION, measured against TR R-100's nose drag), each Mach number's
tip sharpened for it alone (panair.mesh.tip_options) and the nose pressures blended to
tangent-cone per panel (panair.solver.supersonic.NOSE_WEIGHT_PER_PANEL; before, the whole
nose by its steepest panel, the tip ring), linear theory solves Mach 3.95 on fins 5, 9, 10,
12 (fin 1's thick fin stays superinclined at 2.96 and 3.95).  Before -> tip alone -> with
the per-panel blend: CN-alpha fin 5 -23.0 -> +29.1 -> +33.6 %, fin 9 -13.2 -> +47.2 ->
+50.9 %, fin 10 -24.6 -> +14.7 -> +19.2 %, fin 12 -24.1 -> +23.8 -> +26.4 %; CP -0.99 ->
+0.47 -> +0.32, -1.02 -> +0.13 -> -0.00, -1.13 -> +0.17 -> +0.01, -0.66 -> +0.16 -> +0.05
cal; CA0 +29.1 -> +33.5 -> +32.5, +13.5 -> +17.7 -> +16.8, +5.5 -> +10.6 -> +9.4, +44.2 ->
+48.5 -> +47.5 %.  The CA0 excess there was in the local-inclination rows too (the fins'
blunt-edge and wedge drag, not the lift solution); the CN-alpha excess is linear theory's
fin lift, high on fin 9 at 2.3-2.96 too (the tunnel's CN-alpha drops 26 % from Mach 2 to
2.3; session 15's tip diagnosis): Mach 3.95 has its own bounds (CA0 0.55, CN-alpha 0.6, CP
0.45 cal), the others keep theirs.  Mach 1.6-2.96 (19 rows, fins 1 to 2.3): mean |error|
CN-alpha 15.8 -> 17.7 %, CP 0.131 -> 0.117 cal (largest 0.69 -> 0.46), CA0 9.9 -> 9.7 %
(the per-panel blend; the tip alone moves them by at most 0.3 %).

Session 18, a refused supersonic Mach number is tried on a coarser and a finer mesh
before local inclination (panair.sweep.REMESH_REFINE): fin 1 at Mach 2.96 now solves by
linear theory (CN-alpha -8.6 -> +24.9 %, CP -0.81 -> +0.31 cal, CA0 -2.2 -> -4.2 %, in
line with fin 1's +19 ... +45 % at Mach 1.2-2.3); its Mach 3.95 stays on local inclination.

Session 24, the subsonic CA0 is almost all skin friction, and how much of the boundary
layer is laminar decides it: with the flight default (laminar to Re 5e5, Prandtl-Schlichting)
the Mach 0.6 / 0.9 CA0 is -8.7 / -13.4, -9.7 / -17.2, -4.5 / -9.8, -6.1 / -7.8, -3.2 / +2.1 %
(fins 1, 5, 9, 10, 12); turbulent from the leading edges (a model with transition strips, the
usual practice in these tunnels; the TM itself not read, so not adopted) -1.7 / -4.7, -1.6 /
-8.7, +5.2 / +2.3, +2.0 / +2.6, +7.6 / +15.4 % (printed per fin).  Mean |error| 8.2 -> 5.2 %.

Independent method (subsonic, potential part only): nose 2/rad (slender-body theory)
plus the fin pair, 2 x the isolated fin's slope (Diederich, as
:func:`ironbark_opt.aero.barrowman.single_fin_cn_alpha`) x (K_W(B) + K_B(W)) =
(1 + r/s_m)^2, the slender-body fin-body factors of Pitts, Nielsen & Kaattari (NACA
Report 1307, 1957): Barrowman's method with the body carry-over lift K_B(W) it
leaves out.

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

from model_toml import model_toml

DATA = Path(__file__).parents[1] / "data" / "aero" / "allen"
FINS = ("fin01", "fin05", "fin09", "fin10", "fin12")
D = 0.0762                                  # body diameter, reference length [m]
X_MRC = 7.0 * D                             # moment reference [m aft of the nose tip]
#: tunnel unit Reynolds number [1/m] by Mach (geometry.md)
RE_PER_M = {0.6: 8.86e6, 0.9: 6.56e6, 1.2: 5.58e6}
RE_PER_M_SUPERSONIC = 6.56e6
TOL_CA, TOL_CNA, TOL_XCP = 0.10, 0.10, 0.3
#: transition Reynolds number standing for a boundary layer tripped at the leading edge [-]
#: (laminar run of Re 1e3: a few hundredths of a millimetre here)
RE_TRANSITION_TRIPPED = 1.0e3


def _row(text, key):
    m = re.search(r"^\| " + re.escape(key) + r"[^|]*\| ([0-9.]+) m", text, re.M)
    return float(m.group(1))


def _toml(fin: str, fins: bool = True) -> str:
    """The configuration of ``fin`` (``fins=False``: the body alone)."""
    g = (DATA / fin / "geometry.md").read_text()
    sweep = float(re.search(r"tip leading edge lies ([0-9.]+) m", g).group(1))
    return model_toml(f"Allen {fin}", calibre=D, nose_shape="tangent_ogive", nose_calibres=3,
                      body_calibres=9, cg_x=X_MRC, extra=_fins_toml(g, sweep) if fins else "",
                      roughness=2e-6)


def _fins_toml(g, sweep):
    return f"""[[component]]
type = "trapezoidal_fins"
count = 2
x = {_row(g, "root leading edge position")}
root_chord = {_row(g, "root chord cr")}
tip_chord = {_row(g, "tip chord ct")}
span = {_row(g, "span per fin s")}
sweep_length = {sweep}
thickness = {_row(g, "thickness")}
section = "rounded"
"""


def _measured(fin):
    rows = [ln for ln in (DATA / fin / "derived.csv").read_text().splitlines()
            if ln and not ln.startswith("#")]
    head = rows[0].split(",")
    return [dict(zip(head, r.split(","))) for r in rows[1:]]


def _cn_points(fin, mach):
    """[(alpha0, CN0), (alpha1, CN1)] [deg, -] of data.csv at ``mach`` (alpha0 = 0 with CN
    = 0 where there is no alpha ~0 point, as derived.csv assumes)."""
    pts = [(a, cn) for a, _, cn in _points(fin, mach)]
    return pts if len(pts) > 1 else [(0.0, 0.0)] + pts


def _points(fin, mach):
    """[(alpha, CA, CN)] [deg, -, -] of data.csv at ``mach``, by angle."""
    rows = [ln.split(",") for ln in (DATA / fin / "data.csv").read_text().splitlines()
            if ln and ln[0].isdigit()]
    return sorted((float(r[1]), float(r[2]), float(r[3])) for r in rows if float(r[0]) == mach)


def _angles(fin):
    """{mach: (alpha0, alpha1)} [rad] of data.csv's points (alpha0 = 0 where there is
    no alpha ~0 point, as derived.csv assumes)."""
    rows = [ln.split(",") for ln in (DATA / fin / "data.csv").read_text().splitlines()
            if ln and ln[0].isdigit()]
    by_mach = {}
    for r in rows:
        by_mach.setdefault(float(r[0]), []).append(float(r[1]))
    return {m: (math.radians(min(a)) if len(a) > 1 else 0.0, math.radians(max(a)))
            for m, a in by_mach.items()}


def _slender_body_cn_alpha(fin, mach):
    """Independent CN-alpha [1/rad] of the configuration's potential flow at subsonic
    ``mach``: nose 2 + fin pair 2 (CN-alpha)_fin (1 + tau)^2, tau = r/s_m (Pitts,
    Nielsen & Kaattari, NACA Rep. 1307: K_W(B) + K_B(W) = (1 + tau)^2)."""
    from ironbark_opt.aero import barrowman
    g = (DATA / fin / "geometry.md").read_text()
    span = _row(g, "span per fin s")
    sweep = float(re.search(r"tip leading edge lies ([0-9.]+) m", g).group(1))
    plan = barrowman.trapezoid_planform(_row(g, "root chord cr"), _row(g, "tip chord ct"),
                                        span, sweep)
    c1 = float(barrowman.single_fin_cn_alpha(plan, mach, math.pi * D * D / 4))
    return 2.0 + 2.0 * c1 * barrowman.slender_body_interference(span, D / 2)


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
    angles = _angles(fin)
    mach = np.array([float(r["mach"]) for r in meas])
    alpha = np.radians([0.0, 1.0, 2.0, 3.0, 4.0, 5.0])
    # the tunnel model's two fins across the pitch plane, held at that roll
    t = rocket_table(rk, spec, mach=np.concatenate([[0.05, 0.3], mach]), alpha_deg=np.degrees(alpha),
                     fixed_roll=True)
    body_path = tmp_path / f"{fin}_body.toml"
    body_path.write_text(_toml(fin, fins=False))
    subsonic = np.array([m for m in mach if m < 1.0])
    t_body = rocket_table(*load_rocket_geometry(body_path), mach=subsonic,
                          alpha_deg=np.degrees(alpha))
    fr = FrictionDrag(friction_components(rk, spec.surface_roughness), rk.reference_area(),
                      spec.re_transition)
    # the same friction with the boundary layer turbulent from the leading edges (a tunnel
    # model with transition strips; whether this one had them is in the TM, not read here)
    fr_tripped = FrictionDrag(friction_components(rk, spec.surface_roughness),
                              rk.reference_area(), RE_TRANSITION_TRIPPED)

    def cn_cm(m, a):            # CN and Cm about the moment reference at (Mach, alpha)
        cn = float(t.evaluate("CN", m, a))
        return cn, float(t.evaluate("Cm", m, a)) + cn * X_MRC / D

    ok, worst = [], []
    print(f"\n{fin}: Mach  CA0 meas/ours  err%   CNa meas/ours  err%   xcp meas/ours  d(cal)")
    for r, m in zip(meas, mach):
        re_m = RE_PER_M.get(m, RE_PER_M_SUPERSONIC)
        ca0 = float(t.evaluate("CA_pressure", m, 0.0)) + float(fr.CA(m, re_m))
        a0, a1 = angles[m]
        (n0, c0), (n1, c1) = cn_cm(m, a0), cn_cm(m, a1)
        cna = (n1 - n0) / (a1 - a0)
        xcp = X_MRC / D - (c1 - c0) / (n1 - n0)
        e_ca = ca0 / float(r["CA0"]) - 1
        e_cn = cna / float(r["CNa_per_rad"]) - 1
        d_x = xcp - float(r["xcp_cal"])
        good = abs(e_ca) <= TOL_CA and abs(e_cn) <= TOL_CNA and abs(d_x) <= TOL_XCP
        ok.append(good)
        print(f"   {m:4.2f}  {float(r['CA0']):.4f}/{ca0:.4f} {100 * e_ca:+6.1f}   "
              f"{float(r['CNa_per_rad']):6.2f}/{cna:6.2f} {100 * e_cn:+6.1f}   "
              f"{float(r['xcp_cal']):5.2f}/{xcp:5.2f} {d_x:+5.2f}  {'ok' if good else 'NOT MET'}")
        if m not in t.metadata["mach_local_inclination"]:        # linear theory solved it
            # Mach 3.95 (linear theory since session 17) bounded on its own: its CA0 and
            # CN-alpha excess is the fins' (module docstring), its CP within 0.32 cal
            if m < 3.5:
                worst.append((abs(e_ca), abs(e_cn), abs(d_x)))
            else:
                assert abs(e_ca) < 0.55 and abs(e_cn) < 0.6 and abs(d_x) < 0.45
    print(f"{fin}: {sum(ok)} of {len(ok)} Mach numbers meet all three goals")
    for r, m in zip(meas, mach):
        if m < 1.0:
            re_m = RE_PER_M[m]
            ca0 = float(t.evaluate("CA_pressure", m, 0.0)) + float(fr_tripped.CA(m, re_m))
            print(f"{fin}: Mach {m}: CA0 with the boundary layer tripped at the leading edges "
                  f"{ca0:.4f} ({100 * (ca0 / float(r['CA0']) - 1):+5.1f} %; friction "
                  f"{float(fr_tripped.CA(m, re_m)):.4f} vs {float(fr.CA(m, re_m)):.4f} with "
                  f"transition at Re {spec.re_transition:.0e})")
    # the axial force's change with incidence, CA(alpha1) - CA(alpha0) (the tunnel's forebody
    # CA at both measured angles; ours the table's pressure CA, friction and base do not
    # change with alpha here): fins 5, 10 and 12 have both angles
    for m in mach:
        pts = _points(fin, m)
        if len(pts) < 2:
            continue
        (a0, ca0_t, _), (a1, ca1_t, _) = pts[0], pts[-1]
        d_t = ca1_t - ca0_t
        d_o = float(t.evaluate("CA", m, math.radians(a1)) - t.evaluate("CA", m, math.radians(a0)))
        print(f"{fin}: Mach {m}: CA({a1:.2f} deg) - CA({a0:.2f} deg) tunnel {d_t:+.4f}, ours {d_o:+.4f} "
              f"({d_o - d_t:+.4f})")
        # no leading-edge suction on the fins (panair.sweep), measured (session 21): Mach 0.6
        # and 0.9 within -0.0018 ... +0.0135 of the tunnel (before, with the fins' panel
        # suction: -0.0389 ... -0.0042, ours up to 7.5x the tunnel's change); Mach 1.2-3.95
        # within -0.0096 ... +0.0102 (the tunnel's CA rises with alpha there, +0.003 ...
        # +0.013: viscous, not modelled; ours -0.0046 ... +0.0044)
        assert abs(d_o - d_t) < (0.015 if m < 1.0 else 0.013)
    print(f"{fin}: local-inclination Mach numbers (not bounded): {t.metadata['mach_local_inclination']}")
    w = np.max(np.array(worst), axis=0)
    # regression bounds at the Mach numbers linear theory solved: the measured state
    # (CN-alpha 20-40 % high subsonic on fins 1 and 5 and supersonic on fins 1, 5, 10;
    # CP within 0.75 cal; the goals are printed per Mach number)
    assert w[0] < 0.35 and w[1] < 0.5 and w[2] < 0.8
    # the fins' share of the secant CN-alpha: the configuration minus our body alone
    # (slender-body nose 2.0 /rad + the cross-flow), tunnel and ours
    for m in subsonic:
        a0, a1 = angles[m]
        (_, n0), (_, n1) = _cn_points(fin, m)
        body = float(t_body.evaluate("CN", m, a1) - t_body.evaluate("CN", m, a0))
        ours = float(t.evaluate("CN", m, a1) - t.evaluate("CN", m, a0))
        print(f"{fin}: Mach {m}: body alone (ours) CN-alpha {body / (a1 - a0):5.2f}; fins' share "
              f"tunnel {(n1 - n0 - body) / (a1 - a0):6.2f}, ours {(ours - body) / (a1 - a0):6.2f} "
              f"(tunnel / ours {(n1 - n0 - body) / (ours - body):.3f})")
    # the solver against the independent slender-body interference estimate (potential
    # part, small angle; measured -9 ... +5 % on the five fin sets at Mach 0.6 and 0.9)
    for m in (0.6, 0.9):
        a = math.radians(1.0)
        ours = float(t.evaluate("CN_pressure", m, a)) / a
        ref = _slender_body_cn_alpha(fin, m)
        print(f"{fin}: Mach {m}: potential CN-alpha {ours:6.2f}, slender-body interference "
              f"{ref:6.2f} ({100 * (ours / ref - 1):+5.1f} %)")
        assert abs(ours / ref - 1) < 0.12
