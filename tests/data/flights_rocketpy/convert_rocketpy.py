"""Run a RocketPy example notebook's set-up cells (rocketpy 1.13, the `bench` extra) and
write the rocket as an Ironbark TOML (geometry only; the team's drag curves are not used)
plus its thrust curve as RocketPy flies it.  Data files the notebook names are looked up
by name in ../shared (reference/rockets, fixtures/motors, fixtures/weather/reanalysis).

Usage: python convert_rocketpy.py NAME NOTEBOOK.ipynb OUT_DIR
(writes OUT_DIR/rocket_geometry.toml and OUT_DIR/thrust.csv; the Spaceport America
flights' pad temperature and pressure were added by hand, see README.md)."""
import glob
import json
import math
import os
import re
import sys
from pathlib import Path

import matplotlib
import numpy as np

matplotlib.use("Agg")
from rocketpy import Environment  # noqa: E402

name, nb_path, out_dir = sys.argv[1], sys.argv[2], sys.argv[3]
os.makedirs(out_dir, exist_ok=True)
SHARED = str(Path(__file__).resolve().parents[4] / "shared")
def resolve(p):
    base = os.path.basename(p)
    hits = glob.glob(f"{SHARED}/reference/rockets/*/{base}") + glob.glob(f"{SHARED}/fixtures/motors/{base}") \
        + glob.glob(f"{SHARED}/fixtures/weather/reanalysis/{base}")
    return hits[0] if hits else p
rec = {}
def fake_atm(self, type=None, file=None, dictionary=None, **kw):
    rec["atm"] = dict(type=type, file=file)
Environment.set_atmospheric_model = fake_atm
class Stop(Exception): pass
class FakeFlight:
    def __init__(self, **kw):
        rec["flight"] = kw
        raise Stop()
nb = json.load(open(nb_path))
ns = {}
for c in nb["cells"]:
    if c["cell_type"] != "code":
        continue
    src = "".join(c["source"])
    src = re.sub(r'"(\.\./\.\./data/[^"]+)"', lambda m: repr(resolve(m.group(1))), src)
    src = re.sub(r"\)\.(draw|info|all_info)\(\)", ")", src)
    lines = [l for l in src.splitlines() if not re.search(r"\.(info|all_info|draw|plots|prints)\b|^%|plt\.|\.plot\(", l)]
    src = "\n".join(lines)
    try:
        exec(compile(src, "cell", "exec"), ns)
    except Stop:
        break
    except Exception as e:
        if "Flight(" in src:
            raise
        print("cell failed:", type(e).__name__, str(e)[:200], file=sys.stderr)
    ns["Flight"] = lambda **kw: FakeFlight(**kw)
fk = rec["flight"]
rk, env = fk["rocket"], fk["environment"]
csys = 1 if rk.coordinate_system_orientation == "tail_to_nose" else -1
surfs = [(s, p.z) for s, p in rk.aerodynamic_surfaces]
nose = [(s, z) for s, z in surfs if type(s).__name__ == "NoseCone"][0]
z_tip = nose[1]
X = lambda z: csys * (z_tip - z)         # aft of the nose tip
R = rk.radius
comps = []
kind_map = {"vonkarman": "von_karman", "von karman": "von_karman", "tangent": "tangent_ogive", "ogive": "tangent_ogive",
            "lvhaack": "lv_haack", "conical": "conical", "elliptical": "elliptical", "parabolic": "parabolic", "powerseries": "power_series"}
ns_ = nose[0]
kind = kind_map.get(ns_.kind.lower().replace("_", "").replace("-", ""), ns_.kind.lower())
comps.append(("nose_cone", dict(name="nose", shape=kind, length=ns_.length, radius=ns_.base_radius)))
x = ns_.length
r_now = ns_.base_radius
tails = sorted([(s, X(z)) for s, z in surfs if type(s).__name__ == "Tail"], key=lambda t: t[1])
fins = [(s, X(z)) for s, z in surfs if "Fins" in type(s).__name__]
nozzle_x = X(rk.nozzle_position)
end = max([nozzle_x] + [xf + f.root_chord for f, xf in fins] + [xt + t.length for t, xt in tails])
notes = []
for t, xt in tails:
    if xt > x + 1e-6:
        comps.append(("body_tube", dict(name="body", length=xt - x, radius=r_now)))
    comps.append(("transition", dict(name="tail", length=t.length, fore_radius=t.top_radius, aft_radius=t.bottom_radius)))
    x, r_now = xt + t.length, t.bottom_radius
if end > x + 1e-6:
    comps.append(("body_tube", dict(name="aft body", length=end - x, radius=r_now)))
    notes.append(f"body after the last component run as a {r_now:.4f} m tube to {end:.4f} m (RocketPy has no body-tube length)")
for f, xf in fins:
    root = f.root_chord
    thick = min(max(0.025 * root, 0.003), 0.008)
    d = dict(name="Fins", count=f.n, x=xf, thickness=round(thick, 4), section="rounded", cant_deg=math.degrees(f.cant_angle_rad) if hasattr(f, "cant_angle_rad") else float(getattr(f, "cant_angle", 0.0)),
             root_chord=root, tip_chord=f.tip_chord, span=f.span, sweep_length=f.sweep_length)
    comps.append(("trapezoidal_fins", d))
    notes.append(f"fin set thickness and section not in the published data; assumed {thick*1000:.1f} mm (2.5 % of root chord, clipped to 3-8 mm), 'rounded'")
rb = rk.rail_buttons[0] if rk.rail_buttons else None
if rb is not None:
    bz = rb.position.z
    xs = sorted([X(bz), X(bz + csys * rb.component.buttons_distance * 1.0)]) if hasattr(rb.component, "buttons_distance") else None
    if xs:
        comps.append(("rail_buttons", dict(x_fore=xs[0], x_aft=xs[1])))
m = rk.motor
mo = {}
orient = 1 if m.coordinate_system_orientation == "nozzle_to_combustion_chamber" else -1
fwd = lambda p: orient * (p - m.nozzle_position)
mo["dry_mass"] = float(m.dry_mass)
mo["dry_cg"] = float(fwd(m.center_of_dry_mass_position))
mo["dry_inertia"] = [float(m.dry_I_11), float(m.dry_I_33)]
mo["propellant_mass"] = float(m.propellant_initial_mass)
cgp = getattr(m, "grains_center_of_mass_position", None)
if cgp is None:
    cgp = getattr(m, "chamber_position", 0.0)
mo["propellant_cg"] = float(fwd(cgp))
lines = []
w = lines.append
w(f"# Converted from RocketPy's docs/examples/{os.path.basename(nb_path)} (RocketPy-Team/RocketPy d41dd11e) by")
w("# tests/data/flights_rocketpy/convert_rocketpy.py; positions aft of the nose tip [m], SI units")
for n_ in notes: w(f"#  - {n_}")
w("[rocket]"); w(f'name = "{name}"'); w(f"reference_radius = {R}")
w("[rocket.mass_override]")
w(f"mass = {rk.mass}"); w(f"cg_x = {X(rk.center_of_mass_without_motor)}"); w(f"I_transverse = {rk.I_11_without_motor}"); w(f"I_axial = {rk.I_33_without_motor}")
for kind_, d in comps:
    w("[[component]]"); w(f'type = "{kind_}"')
    for k, v in d.items():
        w(f"{k} = {json.dumps(v) if isinstance(v, str) else v}")
src_t = np.asarray(m.thrust.source).copy(); src_t[:, 1] = np.maximum(src_t[:, 1], 0.0)
motor_file = f"{out_dir}/thrust.csv"
np.savetxt(motor_file, src_t, delimiter=",", fmt="%.6f", header="time_s,thrust_N", comments="")
# diameter and length of the grain stack (the flight does not use them: dry inertia given)
if hasattr(m, "grain_number"):
    mo["diameter"] = 2 * float(m.grain_outer_radius)
    mo["length"] = float(m.grain_number * m.grain_initial_height + (m.grain_number - 1) * m.grain_separation)
else:
    mo["diameter"] = 2 * float(getattr(m, "chamber_radius", 0.05)); mo["length"] = float(getattr(m, "chamber_height", 0.5))
w("[motor]"); w(f'file = "{os.path.basename(motor_file)}"'); w(f"nozzle_x = {nozzle_x}")
w("[motor.overrides]")
for k, v in mo.items(): w(f"{k} = {v}")
if hasattr(m, "grain_number"):
    w("[motor.overrides.grains]")
    w(f"count = {m.grain_number}"); w(f"density = {m.grain_density}"); w(f"outer_radius = {m.grain_outer_radius}")
    w(f"inner_radius = {m.grain_initial_inner_radius}"); w(f"height = {m.grain_initial_height}"); w(f"separation = {m.grain_separation}")
w("[launch]")
atm = rec.get("atm", {})
if atm.get("file") and os.path.exists(atm["file"]):
    w(f'atmosphere = {{file = "../../weather/reanalysis/{os.path.basename(atm["file"])}", time = "{env.datetime_date.strftime("%Y-%m-%dT%H:%MZ")}"}}')
w(f"gravity = 9.80665")
w(f"rail_length = {fk['rail_length']}"); w(f"inclination_deg = {fk.get('inclination', 80)}"); w(f"heading_deg = {fk.get('heading', 90)}")
w(f"site_elevation = {env.elevation}"); w(f"latitude_deg = {env.latitude}"); w(f"longitude_deg = {env.longitude}")
open(f"{out_dir}/rocket_geometry.toml", "w").write("\n".join(lines) + "\n")
print("\n".join(lines))
