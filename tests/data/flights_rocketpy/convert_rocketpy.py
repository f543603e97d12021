"""Run a RocketPy example notebook's set-up cells (rocketpy 1.13, the `bench` extra) and
write the rocket as an Ironbark TOML (geometry only; the team's drag curves are not used)
plus its thrust curve as RocketPy flies it.  Data files the notebook names are looked up
by name in ../shared (reference/rockets, fixtures/motors, fixtures/weather/reanalysis) and
under --data DIR (e.g. the RocketPy repository's data/ folder extracted to a temp dir).

Usage: python convert_rocketpy.py NAME NOTEBOOK.ipynb OUT_DIR [--data DIR] [--shared]

Default: OUT_DIR/rocket_geometry.toml and OUT_DIR/thrust.csv in this folder's test form
(the notebook's reanalysis file named as `atmosphere`, gravity given; the Spaceport America
flights' pad temperature and pressure were added by hand, see README.md).
--shared: the form of ../shared/reference/flights (rocket_geometry.toml, rocket.toml with
the team's drag curves as drag_power_off.csv / drag_power_on.csv, motor.eng, no weather
file: ISA through the pad temperature and pressure with the pad wind constant with height,
no gravity key, a motor dry mass of 0 given as 1e-06 kg, recovery devices).

Handles trapezoidal, elliptical and free-form fins, tails (boattails), rail buttons or
none, solid motors, and hybrid / liquid motors flown as a solid one: the propellant at
ignition at one fixed CG (RocketPy's at ignition), as ../shared/reference/flights/README.md
describes for defiance.  A thrust curve starting after t = 0 gets (0, 0), (t0, 0) rows.
Every approximation is written into the TOML header (and printed)."""
import glob
import json
import math
import os
import re
import sys
import types
from pathlib import Path

import matplotlib
import numpy as np

matplotlib.use("Agg")
from rocketpy import Environment  # noqa: E402

args = [a for a in sys.argv[1:] if not a.startswith("--")]
SHARED_FORM = "--shared" in sys.argv
DATA_DIRS = [sys.argv[i + 1] for i, a in enumerate(sys.argv) if a == "--data"]
args = [a for a in args if a not in DATA_DIRS]
name, nb_path, out_dir = args[0], args[1], args[2]
os.makedirs(out_dir, exist_ok=True)
SHARED = str(Path(__file__).resolve().parents[4] / "shared")


def resolve(p):
    base = os.path.basename(p)
    rel = p.split("data/", 1)[1] if "data/" in p else base
    for d in DATA_DIRS:                    # the notebook's own path first (many rockets share names)
        for cand in (f"{d}/{rel}", f"{d}/data/{rel}"):
            if os.path.exists(cand):
                return cand
    hits = glob.glob(f"{SHARED}/reference/rockets/*/{base}") + glob.glob(f"{SHARED}/fixtures/motors/{base}") \
        + glob.glob(f"{SHARED}/fixtures/weather/reanalysis/{base}")
    for d in DATA_DIRS:
        hits += glob.glob(f"{d}/**/{base}", recursive=True)
    return hits[0] if hits else p


# --- what the notebooks need that this machine does not have -------------------------
# hedy: the pad elevation comes from Open-Elevation (network); the notebook's printed
# apogee (5406.918 m ASL | 5246.918 m AGL) gives 160 m.
ELEVATION = {"hedy": 160.0}
# hedy: CoolProp densities.  Ethanol and LOX from the notebook's own printed burn times
# (ethanol 9.225280880958138 s at 0.45 kg/s from 5.27 L; LOX 10.662815399911576 s at
# 0.56 kg/s from 5.27 L); N2 at 298.15 K, 30 MPa: 290 kg/m^3 (NIST webbook, Z ~ 1.17) --
# only the pressurant gas's volume in the tanks depends on it.
_DENS = {"ethanol": 0.45 * 9.225280880958138 / 5.27e-3, "oxygen": 0.56 * 10.662815399911576 / 5.27e-3,
         "N2": 290.0}
cp = types.ModuleType("CoolProp")
cp.CoolProp = types.SimpleNamespace(PropsSI=lambda what, a, av, b, bv, fluid: _DENS[fluid])
sys.modules.setdefault("CoolProp", cp)
sys.modules.setdefault("CoolProp.CoolProp", cp.CoolProp)

rec = {}
_orig_atm = Environment.set_atmospheric_model
_orig_elev = Environment.set_elevation


def fake_atm(self, type=None, file=None, dictionary=None, **kw):
    rec["atm"] = dict(type=type, file=file)
    if file is None or os.path.exists(str(file)):
        _orig_atm(self, type=type, file=file, dictionary=dictionary, **kw)   # pad T, p, wind


def fake_elev(self, elevation=0.0):
    if isinstance(elevation, str):
        elevation = ELEVATION[name]
        rec.setdefault("notes", []).append(f"pad elevation {elevation} m (the notebook asks Open-Elevation; "
                                           "from its printed ASL and AGL apogee)")
    _orig_elev(self, elevation)


Environment.set_atmospheric_model = fake_atm
# A HybridMotor's add_tank re-derives the grain's regression from the thrust curve (an ODE that
# stalls with rocketpy 1.13 on halcyon's motor: hours, GBs).  The solid form needs only the
# contents at ignition (the grain's initial mass, the tanks' contents), so the tank is added
# to the liquid part alone and the split is done below.
from rocketpy import HybridMotor  # noqa: E402
from rocketpy.mathutils.function import reset_funcified_methods  # noqa: E402


def _hybrid_add_tank(self, tank, position):
    self.liquid.add_tank(tank, position)
    reset_funcified_methods(self)


HybridMotor.add_tank = _hybrid_add_tank
Environment.set_elevation = fake_elev


class Stop(Exception):
    pass


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
notes = list(rec.get("notes", []))
kind_map = {"vonkarman": "von_karman", "von karman": "von_karman", "tangent": "tangent_ogive", "ogive": "tangent_ogive",
            "lvhaack": "lv_haack", "lv haack": "lv_haack", "conical": "conical", "elliptical": "elliptical",
            "parabolic": "parabolic", "powerseries": "power"}
ns_ = nose[0]
kind = kind_map.get(ns_.kind.lower().replace("_", "").replace("-", ""), ns_.kind.lower())
comps.append(("nose_cone", dict(name="nose", shape=kind, length=ns_.length, radius=ns_.base_radius)))
x = ns_.length
r_now = ns_.base_radius
tails = sorted([(s, X(z)) for s, z in surfs if type(s).__name__ == "Tail"], key=lambda t: t[1])
fins = [(s, X(z)) for s, z in surfs if "Fins" in type(s).__name__]
nozzle_x = X(rk.nozzle_position)
end = max([nozzle_x] + [xf + f.root_chord for f, xf in fins] + [xt + t.length for t, xt in tails])
for t, xt in tails:
    if xt > x + 1e-6:
        comps.append(("body_tube", dict(name="body", length=xt - x, radius=r_now)))
    comps.append(("transition", dict(name="tail", x=xt, length=t.length, fore_radius=t.top_radius,
                                     aft_radius=t.bottom_radius)))
    x, r_now = xt + t.length, t.bottom_radius
if end > x + 1e-6:
    comps.append(("body_tube", dict(name="aft body", length=end - x, radius=r_now)))
    what = "fin root TE" if any(abs(xf + f.root_chord - end) < 1e-9 for f, xf in fins) else "nozzle exit"
    notes.append(f"body after the last component ({x:.4f} m) run as a {r_now:.4f} m tube to the {what} {end:.4f} m "
                 "(RocketPy has no body-tube length)")
for f, xf in fins:
    root = f.root_chord
    thick = min(max(0.025 * root, 0.003), 0.008)
    cant = math.degrees(f.cant_angle_rad) if hasattr(f, "cant_angle_rad") else float(getattr(f, "cant_angle", 0.0))
    d = dict(name=f.name or "Fins", count=f.n, x=xf, thickness=round(thick, 4), section="rounded", cant_deg=cant)
    tname = type(f).__name__
    if tname == "TrapezoidalFins":
        d.update(root_chord=root, tip_chord=f.tip_chord, span=f.span, sweep_length=f.sweep_length)
        comps.append(("trapezoidal_fins", d))
    elif tname == "EllipticalFins":
        d.update(root_chord=root, span=f.span)
        comps.append(("elliptical_fins", d))
    elif tname == "FreeFormFins":
        pts = [tuple(map(float, p)) for p in f.shape_points]
        if len(pts) > 1 and np.allclose(pts[0], pts[-1]):
            pts = pts[:-1]                       # RocketPy closes the outline itself
        i0 = int(np.argmin([abs(px) + abs(py) for px, py in pts]))
        pts = pts[i0:] + pts[:i0]                # start at the root leading edge
        # root trailing edge: the point of the largest x among those at the root (y <= 0)
        root_pts = [k for k, (px, py) in enumerate(pts) if py <= 1e-9 and k > 0]
        k_te = max(root_pts, key=lambda k: pts[k][0])
        if k_te == 1:                            # RocketPy order LE -> root TE -> tip: reverse
            pts = [pts[0]] + pts[1:][::-1]
        neg = min(py for px, py in pts)
        out = [[round(px, 6), round(max(py, 0.0), 6)] for px, py in pts]
        out = [p for k, p in enumerate(out) if k == 0 or p != out[k - 1]]
        d["points"] = out
        comps.append(("freeform_fins", d))
        if neg < 0:
            notes.append(f"fin set '{d['name']}': the outline's root dips {-neg * 1000:.1f} mm below its leading edge "
                         "(drawn along a boattail); those points given at y = 0 (the format's root follows the body)")
    else:
        raise SystemExit(f"fin type {tname} not converted")
    notes.append(f"fin set '{d['name']}': thickness and section not in the published data; assumed {thick*1000:.1f} mm "
                 "(2.5 % of the root chord, clipped to 3-8 mm), section 'rounded'")
rb = rk.rail_buttons[0] if rk.rail_buttons else None
if rb is not None:
    bz = rb.position.z
    xs = sorted([X(bz), X(bz + csys * rb.component.buttons_distance * 1.0)]) if hasattr(rb.component, "buttons_distance") else None
    if xs:
        comps.append(("rail_buttons", dict(x_fore=xs[0], x_aft=xs[1])))
else:
    notes.append("no rail buttons in the case: none written (rail exit by travel)")
m = rk.motor
mtype = type(m).__name__
mo = {}
orient = 1 if m.coordinate_system_orientation == "nozzle_to_combustion_chamber" else -1
fwd = lambda p: orient * (p - m.nozzle_position)
src_t = np.asarray(m.thrust.source, dtype=float).copy()
if np.isnan(src_t).any():                  # halcyon: rocketpy 1.13 reads the .eng's t = 0 row as NaN
    notes.append(f"RocketPy's thrust curve has NaN at t = {', '.join(f'{t:g}' for t in src_t[np.isnan(src_t[:, 1]), 0])} s "
                 "(how rocketpy 1.13 reads the file's first row); those rows dropped")
    src_t = src_t[~np.isnan(src_t).any(axis=1)]
src_t[:, 1] = np.maximum(src_t[:, 1], 0.0)
t_ign = float(src_t[np.argmax(src_t[:, 1] > 0), 0])
if src_t[0, 0] > 0:
    notes.append(f"thrust curve starts at t = {src_t[0, 0]:g} s with {src_t[0, 1]:.1f} N: written as (0, 0), "
                 f"({src_t[0, 0]:g}, 0) then the curve, so the thrust is 0 before it as in RocketPy")
    src_t = np.vstack([[0.0, 0.0], [src_t[0, 0], 0.0], src_t] if src_t[0, 1] > 0 else [[0.0, 0.0], src_t])
dry = float(m.dry_mass)
if dry <= 0 and SHARED_FORM:
    notes.append("motor dry mass 0.0 kg (casing in the rocket mass): the format needs > 0, given as 1e-06 kg")
    dry = 1e-06
mo["dry_mass"] = dry
mo["dry_cg"] = float(fwd(m.center_of_dry_mass_position))
mo["dry_inertia"] = [float(m.dry_I_11), float(m.dry_I_33)]
if mtype == "SolidMotor":
    mo["propellant_mass"] = float(m.propellant_initial_mass)
    cgp = getattr(m, "grains_center_of_mass_position", None)
    mo["propellant_cg"] = float(fwd(cgp))
elif mtype == "GenericMotor":              # prometheus: thrust, propellant mass and a chamber
    mo["propellant_mass"] = float(m.propellant_initial_mass)
    mo["propellant_cg"] = float(fwd(m.chamber_position))
else:
    liq = m.liquid if mtype == "HybridMotor" else m
    p0, p_ign = float(liq.propellant_mass(0.0)), float(liq.propellant_mass(t_ign))
    mom = p_ign * float(liq.center_of_propellant_mass(t_ign))
    if mtype == "HybridMotor":                      # the grain, unburnt at ignition
        g = float(m.solid.propellant_initial_mass)
        p0, p_ign, mom = p0 + g, p_ign + g, mom + g * float(m.grains_center_of_mass_position)
    mo["propellant_mass"] = p_ign
    cg_ign = float(fwd(mom / p_ign))
    mo["propellant_cg"] = cg_ign
    tb = np.linspace(t_ign, float(m.burn_out_time), 200)
    cgs = [X(rk.nozzle_position) - float(fwd(liq.center_of_propellant_mass(t))) for t in tb[:-1]]
    tanks = ", ".join(f"{pt['tank'].name} {float(pt['tank'].fluid_mass(t_ign)):.2f} kg at "
                      f"{X(rk.nozzle_position) - float(fwd(pt['position'])):.3f} m" for pt in m.positioned_tanks)
    notes.append(f"{'hybrid' if mtype == 'HybridMotor' else 'liquid'} motor ({mtype}): tanks ({tanks})"
                 f"{' and grain regression' if mtype == 'HybridMotor' else ''} cannot be given in the solid form; flown "
                 "as a solid motor with the total propellant mass at one fixed CG and default hollow-cylinder propellant inertia")
    notes.append(f"RocketPy's {'oxidiser' if mtype == 'HybridMotor' else 'propellant'} CG moves {min(cgs):.3f}..{max(cgs):.3f} m from the nose during the burn; "
                 f"the format has one fixed propellant CG ({X(rk.nozzle_position) - cg_ign:.6f} m, RocketPy's at ignition)")
    if abs(p0 - p_ign) > 1e-6:
        notes.append(f"propellant {p0:.4f} kg at t = 0 but {p_ign:.4f} kg at ignition (t = {t_ign:g} s; drains on the "
                     "pad): the format burns propellant with impulse only, so the ignition value is given")
# diameter and length of the grain stack / the motor (the flight does not use them: dry inertia given)
if mtype == "SolidMotor":
    mo["diameter"] = 2 * float(m.grain_outer_radius)
    mo["length"] = float(m.grain_number * m.grain_initial_height + (m.grain_number - 1) * m.grain_separation)
elif mtype == "GenericMotor":
    mo["diameter"] = 2 * float(m.chamber_radius)
    mo["length"] = float(m.chamber_height)
else:
    mo["diameter"] = 2 * R
    mo["length"] = float(max(abs(float(fwd(pt["position"]))) + pt["tank"].geometry.total_height / 2
                             for pt in m.positioned_tanks))
I_tr, I_ax = float(rk.I_11_without_motor), float(rk.I_33_without_motor)
if I_ax > 2 * I_tr:          # halcyon: (24.56, 24.56, 70.074); no rigid body has I_axial > 2 I_transverse
    notes.append(f"rocket I_axial {I_ax:g} kg m^2 exceeds twice I_transverse {I_tr:g} kg m^2 (impossible; RocketPy "
                 f"flies it, the format refuses it): read as {I_ax / 1000:g} kg m^2 (a g m^2 figure; a "
                 f"{2 * R * 1000:.1f} mm tube of this mass has about {rk.mass * R ** 2 / 2:.3f}..{rk.mass * R ** 2:.3f})")
    I_ax /= 1000
lines = []
w = lines.append
if SHARED_FORM:
    w(f"# Converted from RocketPy's docs/examples/{os.path.basename(nb_path)} (RocketPy-Team/RocketPy d41dd11e) by")
    w("# tests/data/flights_rocketpy/convert_rocketpy.py --shared, in the form of ../shared/reference/flights.")
    w("# Positions aft of the nose tip [m]; SI units; angles in degrees.")
else:
    w(f"# Converted from RocketPy's docs/examples/{os.path.basename(nb_path)} (RocketPy-Team/RocketPy d41dd11e) by")
    w("# tests/data/flights_rocketpy/convert_rocketpy.py; positions aft of the nose tip [m], SI units")
atm = rec.get("atm", {}) or {}
WEATHER = Path(__file__).resolve().parents[1] / "weather" / "reanalysis"
atm_file = atm.get("file") and os.path.exists(atm["file"]) and (WEATHER / os.path.basename(atm["file"])).exists()
pad_form = SHARED_FORM or (atm.get("type") is not None and not atm_file)
if pad_form:
    elev = float(env.elevation)
    T, p = float(env.temperature(elev)), float(env.pressure(elev))
    ws, wd = float(env.wind_speed(elev)), float(env.wind_direction(elev))
    atm_txt = (f"RocketPy flew {atm.get('type') or 'the standard atmosphere'}"
               + (f" ({os.path.basename(str(atm['file']))})" if atm.get("file") else ""))
    why = "the format names no weather file here" if SHARED_FORM else "the weather file is not in tests/data/weather"
    notes.append(f"atmosphere: {atm_txt}; {why}, so ISA through the pad T {T:.3f} K / "
                 f"p {p:.1f} Pa with the pad wind ({ws:.2f} m/s) constant with height is flown")
if SHARED_FORM:
    g_txt = f"a constant {env.gravity(0)} m/s^2" if env.gravity(0) == env.gravity(5000) else "its height-dependent gravity"
    notes.append(f"gravity: RocketPy used {g_txt}; the format has no gravity key (WGS-84 normal gravity is flown)")
for n_ in notes:
    w(f"#  - {n_}")
    print("note:", n_)
w("")
w("[rocket]"); w(f'name = "{name}"'); w(f"reference_radius = {R}")
w("")
w("[rocket.mass_override]")
w(f"mass = {rk.mass}"); w(f"cg_x = {X(rk.center_of_mass_without_motor)}"); w(f"I_transverse = {I_tr}"); w(f"I_axial = {I_ax}")
for kind_, d in comps:
    w(""); w("[[component]]"); w(f'type = "{kind_}"')
    for k, v in d.items():
        w(f"{k} = {json.dumps(v) if isinstance(v, (str, list)) else v}")
if SHARED_FORM:
    motor_file = f"{out_dir}/motor.eng"
    with open(motor_file, "w") as fh:
        fh.write(f"; thrust curve RocketPy 1.13 flies for case {name}\n")
        fh.write(f"Thrust_curve {mo['diameter'] * 1000:.3f} {mo['length'] * 1000:.3f} P {mo['propellant_mass']:.6f} "
                 f"{mo['propellant_mass'] + dry:.6f} case\n")
        for t_, f_ in src_t:
            fh.write(f"{t_:.6f} {f_:.6f}\n")
    del mo["diameter"], mo["length"]
else:
    motor_file = f"{out_dir}/thrust.csv"
    np.savetxt(motor_file, src_t, delimiter=",", fmt="%.6f", header="time_s,thrust_N", comments="")
w(""); w("[motor]"); w(f'file = "{os.path.basename(motor_file)}"')
if SHARED_FORM:
    w('designation = "Thrust_curve"')
w(f"nozzle_x = {nozzle_x}")
w(""); w("[motor.overrides]")
for k, v in mo.items(): w(f"{k} = {v}")
if mtype == "SolidMotor":
    w(""); w("[motor.overrides.grains]")
    w(f"count = {m.grain_number}"); w(f"density = {m.grain_density}"); w(f"outer_radius = {m.grain_outer_radius}")
    w(f"inner_radius = {m.grain_initial_inner_radius}"); w(f"height = {m.grain_initial_height}"); w(f"separation = {m.grain_separation}")
w(""); w("[launch]")
if not SHARED_FORM:
    if atm_file:
        w(f'atmosphere = {{file = "../../weather/reanalysis/{os.path.basename(atm["file"])}", time = "{env.datetime_date.strftime("%Y-%m-%dT%H:%MZ")}"}}')
    w("gravity = 9.80665")
w(f"rail_length = {float(fk['rail_length'])}"); w(f"inclination_deg = {float(fk.get('inclination', 80))}")
w(f"heading_deg = {float(fk.get('heading', 90))}")
w(f"site_elevation = {float(env.elevation)}"); w(f"latitude_deg = {env.latitude}"); w(f"longitude_deg = {env.longitude}")
if pad_form:
    w(f"site_temperature = {T:.3f}"); w(f"site_pressure = {p:.1f}")
    w(f"wind_speed = {ws:.6f}"); w(f"wind_from_deg = {wd:.4f}")
if SHARED_FORM:
    for para in rk.parachutes:
        trig = para.trigger
        if callable(trig):
            trig = "apogee"
            print("note: parachute", para.name, "has a trigger function; written as apogee")
        w(""); w("[[recovery]]"); w(f'name = "{para.name}"'); w(f"cd_area = {float(para.cd_s)}")
        w(f"deploy = {json.dumps(trig) if isinstance(trig, str) else float(trig)}"); w(f"lag = {float(para.lag)}")
text = "\n".join(lines) + "\n"
open(f"{out_dir}/rocket_geometry.toml", "w").write(text)
if SHARED_FORM:
    drag = {}
    # as RocketPy flies them: its Mach function on Mach 0..3 in steps of 0.01 (the form of
    # ../shared/reference/flights: 301 rows); the team's raw file may repeat, reverse or
    # fall back in Mach (hedy, Berkeley, andromeda), RocketPy sorts and interpolates it
    mach = np.round(np.arange(0.0, 3.0 + 1e-9, 0.01), 2)
    for key, fn in (("drag_power_off", rk.power_off_drag), ("drag_power_on", rk.power_on_drag)):
        np.savetxt(f"{out_dir}/{key}.csv", np.c_[mach, [float(fn(x)) for x in mach]], delimiter=",",
                   fmt=("%.4f", "%.6f"))
        drag[key] = f"{key}.csv"
    if len(drag) == 2:
        open(f"{out_dir}/rocket.toml", "w").write(text + f'\n[aero]\ndrag_power_off = "{drag["drag_power_off"]}"\n'
                                                  f'drag_power_on = "{drag["drag_power_on"]}"\n')
print(text)
