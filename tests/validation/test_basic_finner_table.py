"""Basic Finner end to end: the table ``ironbark aero build`` makes from a rocket file
(panel solutions, transonic model, MC DRAG base drag, high-angle model; friction at
the range's Reynolds number) against the free-flight range data (Dupuis & Hathaway
1997, DREV-TM-9703; tests/data/panair/basic_finner/basic_finner_range.csv), Mach
1.077 to 4.3.

The solver-level checks (test_panel_basic_finner_supersonic.py) call the supersonic
solver on a hand-made mesh; this one goes through what a user runs, so it also covers
the transonic model at Mach 1.077 (between the critical Mach number and the first
supersonic solution the table is :mod:`panair.transonic`'s, never a panel solution)
and the table's own base-drag column.  Goals as the solver-level test (the issue's):
CN-alpha within 10 %, Cm-alpha within 15 %, CX0 within 10 %; printed per Mach number
as met / NOT MET; the asserts bound the measured state so a regression fails.

Measured (session 14): CX0 -26.7 % at Mach 1.077 and -13.4 ... -16.2 % at Mach
1.293-4.3, the same shortfall as the solver-level test (its friction and base are
the same models).  At Mach 1.077 the range's CX0 is 0.132 above its Mach 1.293 value
(the transonic peak); the table's rises 0.017 (pressure: the transonic model carries
the first supersonic solution's wave drag down to Mach 1, the transonic area rule's
sonic value; base: MC DRAG).  The peak of measured transonic drag above Mach 1 is
beyond that model (linear theory's fin wave drag grows as 1/beta toward Mach 1 and
is not used there).  CN-alpha within -10.3 ... +11.7 %, Cm-alpha within -6.6 ...
+15.7 % up to Mach 3.15 (+35 / +52 % at Mach 3.7 / 4.3, as the solver-level test).

Assumptions (not in the range report): the fins are sharp double wedges of the
listed thickness (the section the PANAIR reference mesh uses); the model is machined
metal, equivalent sand-grain roughness 2 um (as the Allen tunnel models'); the range
air is the ICAO sea-level atmosphere.  Slow (one table, ~35 s).
"""
from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from model_toml import model_toml

DATA = Path(__file__).parents[1] / "data"
D = 0.030                                   # the range model's calibre [m]
X_CG = 5.0 * D                              # moment reference of the range data [m]
GOAL_CNA, GOAL_CMA, GOAL_CX0 = 0.10, 0.15, 0.10


def _toml() -> str:
    fins = f"""[[component]]
type = "trapezoidal_fins"
count = 4
x = {9.0 * D}
root_chord = {D}
tip_chord = {D}
span = {D}
sweep_length = 0.0
thickness = {0.08 * D}
section = "double_wedge"
"""
    return model_toml("Basic Finner", calibre=D, nose_shape="conical", nose_calibres=2.84,
                      body_calibres=7.16, cg_x=X_CG, mass=1.6, i_transverse=0.01, i_axial=0.0002,
                      extra=fins, roughness=2e-6)


@pytest.mark.slow
def test_basic_finner_table_vs_range(tmp_path):
    from ironbark_opt.aero.friction import FrictionDrag
    from ironbark_opt.aero.model import friction_components
    from ironbark_opt.vehicle import load_rocket_geometry
    from panair.rocket_table import rocket_table
    from panair.sweep import SEA_LEVEL_RE_PER_M_PER_MACH

    path = tmp_path / "basic_finner.toml"
    path.write_text(_toml())
    rk, spec = load_rocket_geometry(path)
    rng = pd.read_csv(DATA / "panair" / "basic_finner" / "basic_finner_range.csv",
                      comment="#").set_index("mach")
    mach = np.concatenate([[0.05, 0.3, 0.6, 0.8, 0.9, 0.95], rng.index.to_numpy(float)])
    t = rocket_table(rk, spec, mach=mach, alpha_deg=np.array([0.0, 2.0, 4.0]))
    assert 1.077 in t.metadata["mach_bridged"]           # the transonic model's, not a solution
    fr = FrictionDrag(friction_components(rk, spec.surface_roughness), rk.reference_area(),
                      spec.re_transition)
    a = math.radians(2.0)
    err, cx0 = {}, {}
    print("\nBasic Finner table vs range:  Mach   CX0 ours/range  err%   (pressure + base + "
          "friction)   CNa ours/range  err%   Cma ours/range  err%")
    for m in rng.index:
        r = rng.loc[m]
        p, b = float(t.evaluate("CA_pressure", m, 0.0)), float(t.evaluate("CA_base", m, 0.0))
        f = float(fr.CA(m, m * SEA_LEVEL_RE_PER_M_PER_MACH))
        cx = cx0[m] = float(t.evaluate("CA", m, 0.0)) + f
        assert cx == pytest.approx(p + b + f, rel=1e-9)   # the table's CA is pressure + base
        cn = float(t.evaluate("CN", m, a))
        cna = cn / a
        cma = (float(t.evaluate("Cm", m, a)) + cn * X_CG / D) / a
        e = (cx / r["CX0"] - 1, cna / r["CNa_per_rad"] - 1, cma / r["CMa_per_rad"] - 1)
        err[m] = e
        flag = lambda v, g: "" if abs(v) <= g else " NOT MET"
        print(f"   {m:5.3f}  {cx:.3f}/{r['CX0']:.3f} {100 * e[0]:+6.1f}{flag(e[0], GOAL_CX0)}"
              f"  ({p:.3f} + {b:.3f} + {f:.3f})   {cna:5.2f}/{r['CNa_per_rad']:5.2f} "
              f"{100 * e[1]:+6.1f}{flag(e[1], GOAL_CNA)}   {cma:6.2f}/{r['CMa_per_rad']:6.2f} "
              f"{100 * e[2]:+6.1f}{flag(e[2], GOAL_CMA)}")
    rise_range = rng.loc[1.077, "CX0"] - rng.loc[1.293, "CX0"]
    rise_ours = cx0[1.077] - cx0[1.293]
    print(f"   transonic peak: CX0(1.077) - CX0(1.293) range {rise_range:+.3f}, ours {rise_ours:+.3f}")
    # regression bounds: the measured state (module docstring)
    assert -0.30 < err[1.077][0] < 0.0
    for m, (e_cx, e_cn, e_cm) in err.items():
        assert abs(e_cx) < 0.20 or m == 1.077
        assert abs(e_cn) < 0.13
        if m <= 3.2:
            assert abs(e_cm) < 0.18
    # the sign of the transonic peak at least (the range's rise is 8x ours)
    assert 0.0 < rise_ours < rise_range
