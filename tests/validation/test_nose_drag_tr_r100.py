"""Nose-cone pressure drag through the transonic range: the tables ``panair.rocket_table``
builds from geometry against free-flight data for nine nose shapes of fineness ratio 3
(Stoney, NASA TR R-100, 1961, p. 16; tests/data/aero/stoney_tr_r100, README there).

Each nose sits on a 7-calibre cylinder, so the table's zero-alpha pressure CA (base drag
is its own column) is the nose's pressure drag on its base area, the quantity of the
report.  Printed per Mach number with the table's method there (subsonic model, the
transonic model of :mod:`panair.transonic`, a linear-theory solution, or the
local-inclination fallback); goal as the issue's forebody CA0: within 10 %.

Measured (session 16): linear theory at Mach 1.6-2.4 is within -0.008 ... +0.022 of the
data on the smooth pointed noses (von Karman, LV-Haack, parabolic K = 1, 3/4, 1/2, power
3/4), but high on the blunt-tipped ones (elliptical +0.06 ... +0.17, power 1/2 +0.04 ...
+0.06, power 1/4 +0.08 ... +0.20): their tips are steeper than the Mach cone.  Between
Mach 1.0 and 1.2 the transonic model used to carry the first supersonic solution's drag
down to Mach 1 (the transonic area rule's sonic value), where the data of the noses
meeting the body tangentially are a quarter to a third of their Mach 1.2 value: at Mach
1.0 / 1.05 / 1.1 von Karman +0.074 / +0.046 / +0.031, LV-Haack +0.101 / +0.059 / +0.041,
parabolic K = 1 +0.080 / +0.029 / +0.012.  With McCoy's transonic head drag for those
noses (panair.transonic, item 4): von Karman +0.024 / +0.012 / +0.011, LV-Haack +0.027 /
+0.007 / +0.010, parabolic K = 1 +0.010 / -0.018 / -0.013; McCoy's drag rise starts at
Mach 0.90 for fineness 3 (data: 0.90-0.95), so at Mach 0.95 +0.017 / +0.017 / +0.027.  The
noses with a shoulder angle (power 3/4, parabolic K = 1/2, 3/4) keep the area-rule anchor:
their data stay near the Mach 1.2 value and the model is within -0.024 ... +0.029.
Mach 1.4 was refused by linear theory on the tables' shared mesh (a Mach-cone coincidence
across the cylinder, tests/unit/test_panair_supersonic_coincidence.py) and fell to local
inclination; re-meshed (panair.sweep._remesh_refused) it is solved: von Karman +0.027 ->
+0.005, LV-Haack +0.041 -> +0.019, parabolic 3/4 +0.023 -> +0.005, power 3/4 +0.004 -> -0.002.
Session 17: each supersonic Mach number's conical tip is its own (panair.mesh.tip_options;
before, every one had the tip of the table's largest Mach number whose cone fitted in 10 %
of the nose), up to 60 % of the nose (von Karman Mach 3.0, local inclination -> linear
theory: -0.0017 -> +0.0000), and the nose's tangent-cone blend goes per panel
(panair.solver.supersonic.NOSE_WEIGHT_PER_PANEL; before, the steepest panel, the tip ring,
set it for the whole nose, so a Mach number's own steep tip alone made LV-Haack at Mach 1.2
+0.025 -> +0.072).  Linear theory on the pointed noses from Mach 1.6: -0.0077 ... +0.0217
(10 points) -> -0.0016 ... +0.0099 (11 points); von Karman 1.2 / 1.4 / 1.6 / 2.0 +0.020 /
+0.005 / +0.012 / +0.006 -> +0.019 / +0.002 / -0.002 / +0.001, LV-Haack 1.2 / 1.4 / 1.6 /
2.0 +0.025 / +0.019 / +0.022 / +0.009 -> +0.021 / +0.006 / +0.003 / -0.000, power 3/4 2.8
-0.008 -> +0.001; the blunt-tipped noses: elliptical Mach 1.2 / 2.0 / 2.4 +0.168 / +0.084 /
+0.062 -> +0.030 / +0.047 / +0.016, power 1/2 +0.037 ... +0.050 -> +0.014 ... +0.025, power
1/4 +0.08 ... +0.20 -> -0.10 ... +0.19 (1.6 now linear theory: +0.157 -> +0.190).  The
asserts bound that measured state (a regression, or the area-rule anchor back on the
tangent noses, fails); the goal is printed per row.  The empirical path's nose drag
(McCoy's MC DRAG head drag, :func:`ironbark_opt.aero.empirical_drag.nose_pressure_ca`) is
printed beside it and bounded the same way.
Slow (nine tables, ~1 min).
"""
from __future__ import annotations

from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from model_toml import model_toml

DATA = Path(__file__).parents[1] / "data"
D = 0.1                                   # calibre of the models [m] (the data are coefficients)
GOAL = 0.10
#: the smooth pointed shapes (tip not steeper than a cone of the nose's fineness ratio)
POINTED = {("von_karman", ""), ("lv_haack", ""), ("parabolic", "1.0"), ("parabolic", "0.75"),
           ("parabolic", "0.5"), ("power", "0.75")}


def _toml(shape: str, parameter: str) -> str:
    return model_toml(f"TR R-100 {shape} {parameter}", calibre=D, nose_shape=shape,
                      shape_parameter=parameter, nose_calibres=3, body_calibres=7, cg_x=5 * D)


def _method(md, m) -> str:
    if m in md.get("mach_local_inclination", []):
        return "local inclination"
    if m in md.get("mach_bridged", []):
        return "transonic model"
    if m < 1.0:
        return "subsonic model"          # the table's subsonic zero-lift drag (panair.transonic)
    return "solved" if m in md.get("mach_solved_builtin", []) else "?"


@pytest.fixture(scope="module")
def comparison(tmp_path_factory):
    from ironbark_opt.aero.empirical_drag import pressure_ca
    from ironbark_opt.vehicle import load_rocket_geometry
    from panair.rocket_table import rocket_table
    ref = pd.read_csv(DATA / "aero" / "stoney_tr_r100" / "nose_pressure_drag.csv", comment="#",
                      dtype={"shape_parameter": str}).fillna("")
    tmp = tmp_path_factory.mktemp("tr_r100")
    rows = []
    for (shape, p), grp in ref.groupby(["shape", "shape_parameter"], sort=False):
        path = tmp / f"{shape}_{p}.toml"
        path.write_text(_toml(shape, p))
        rk, spec = load_rocket_geometry(path)
        mach = np.array(sorted(m for m in grp["mach"] if m <= 3.0), float)
        t = rocket_table(rk, spec, mach=np.concatenate([[0.3, 0.6], mach]),
                         alpha_deg=np.array([0.0, 2.0]), workers=2)
        for m, cd in zip(grp["mach"], grp["cd_pressure"]):
            if m > 3.0:
                continue
            rows.append((shape, p, float(m), float(cd),
                         float(t.evaluate("CA_pressure", m, 0.0)), _method(t.metadata, float(m)),
                         float(pressure_ca(rk, [m])[0])))
    return pd.DataFrame(rows, columns=["shape", "p", "mach", "measured", "ours", "method",
                                       "empirical"])


@pytest.mark.slow
def test_nose_pressure_drag_vs_tr_r100(comparison):
    print("\nnose (fineness 3)      Mach  TR R-100   ours    diff    err%   method"
          "                empirical  diff")
    for r in comparison.itertuples():
        err = (r.ours / r.measured - 1) if r.measured > 0 else float("nan")
        flag = "" if abs(err) <= GOAL else " NOT MET"
        print(f"{r.shape:10s} {r.p:5s}  {r.mach:7.3f}  {r.measured:7.3f}  {r.ours:7.4f}  "
              f"{r.ours - r.measured:+7.4f}  {100 * err:+6.1f}  {r.method + flag:22s}"
              f"{r.empirical:7.4f} {r.empirical - r.measured:+7.4f}")
    pointed = comparison[[(s, p) in POINTED for s, p in zip(comparison["shape"], comparison["p"])]]
    sup = pointed[(pointed["mach"] >= 1.6) & (pointed["method"] == "solved")]
    son = pointed[(pointed["mach"] >= 1.0) & (pointed["mach"] <= 1.1)]
    print(f"pointed noses, linear theory Mach >= 1.6: diff {sup['ours'].sub(sup['measured']).min():+.4f}"
          f" ... {sup['ours'].sub(sup['measured']).max():+.4f} ({len(sup)} points)")
    print(f"pointed noses, Mach 1.0-1.1 (transonic model): diff "
          f"{son['ours'].sub(son['measured']).min():+.4f} ... {son['ours'].sub(son['measured']).max():+.4f}")
    assert len(sup) >= 8
    # measured state (module docstring): linear theory on the pointed noses within 0.015 of the
    # data from Mach 1.6 (0.025 until session 17's per-panel nose blend: +0.0217 then); the transonic model within -0.03 ... +0.035 of the data at Mach
    # 1.0-1.1 (the area-rule anchor on the tangent noses: up to +0.10)
    assert np.all(np.abs(sup["ours"] - sup["measured"]) < 0.015)
    assert np.all(son["ours"] - son["measured"] > -0.03)
    assert np.all(son["ours"] - son["measured"] < 0.035)
    # below the drag rise (measured 0) the smooth noses have little pressure drag (McCoy's
    # rise starts at Mach 0.90 for fineness 3, the data at 0.90-0.95)
    quiet = pointed[(pointed["measured"] == 0.0)]
    assert np.all(quiet["ours"] < 0.03)
    # the empirical path (ironbark_opt.aero.empirical_drag: McCoy's MC DRAG head drag; it had
    # none on the tangent noses before session 16): on the pointed noses within -0.06 ...
    # +0.07 of the data from Mach 1.0 (von Karman, the minimum-drag shape, +0.06 at Mach
    # 1.1-1.2 where McCoy's ogive fit is above it), below 0.03 before the drag rise (as the
    # tables: McCoy's rise starts at Mach 0.90)
    emp = pointed[pointed["mach"] >= 1.0]
    d_emp = emp["empirical"] - emp["measured"]
    print(f"empirical path, pointed noses, Mach >= 1.0: diff {d_emp.min():+.4f} ... {d_emp.max():+.4f}")
    assert np.all(d_emp > -0.06) and np.all(d_emp < 0.07)
    assert np.all(quiet["empirical"] < 0.03)
