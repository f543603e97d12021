"""Regenerate the three MAPLEAF validation flights of this folder from the MAPLEAF
repository (henrystoldt/MAPLEAF, MIT licence), reading its files with ``git show``.

    /work/venv/bin/python tests/data/flights_mapleaf/make_from_mapleaf.py [MIRROR_GIT_DIR]

Writes, per flight, ``rocket_geometry.toml`` (geometry + mass override + motor +
launch), ``motor.eng`` (RASP, converted from MAPLEAF's motor table), copies of
MAPLEAF's motor table (``mapleaf_motor.txt``, for the impulse test) and of the
digitised altitude curves (measured, OpenRocket 0.9, RockSim 8), and prints the
numbers the README quotes.  See README.md for what each number means and assumes.
"""
from __future__ import annotations

import math
import re
import subprocess
import sys
from pathlib import Path

import numpy as np

COMMIT = "af970d3e8200832f5e70d537b15ad38dd74fa551"
MIRROR = "/work/.mirror/henrystoldt+MAPLEAF/repo"
HERE = Path(__file__).parent
VV = "MAPLEAF/Examples/V&V/"

#: name -> (sim file, batch-case overrides of OpenRocketCases.mapleaf, motor file,
#:          V&V folder/prefix, RASP header: designation, diameter_mm, length_mm, delays,
#:          manufacturer, rail length [m] or None (format default))
FLIGHTS = {
    "b4_4": ("MAPLEAF/Examples/Simulations/Jake1.mapleaf",
             {"GeneralMass.mass": "0.0129", "GeneralMass.MOI": "(5.53E-06 5.53E-06 5.22E-07)"},
             "MAPLEAF/Examples/Motors/B4-4.txt", "B4-4SimpleRocket/B4-4",
             ("B4-4", 18, 70, "4", "MAPLEAF_B4-4"), 1.0),
    "c6_3": ("MAPLEAF/Examples/Simulations/Jake1.mapleaf",
             {"GeneralMass.mass": "0.00952", "GeneralMass.MOI": "(4.08e-06 4.08e-06 3.86e-07)"},
             "MAPLEAF/Examples/Motors/C6-3.txt", "C6-3SimpleRocket/C6-3",
             ("C6-3", 18, 70, "3", "MAPLEAF_C6-3"), 1.0),
    "haisunaata": ("MAPLEAF/Examples/Simulations/Haisunaata.mapleaf", {},
                   "MAPLEAF/Examples/Motors/J115.txt", "HaisunaataRocket/Haisunaata",
                   ("J115", 54, 614, "P", "MAPLEAF_J115"), None),
}


def show(path: str, mirror: str) -> str:
    return subprocess.run(["git", "-C", mirror, "show", f"{COMMIT}:{path}"], check=True,
                          capture_output=True, text=True).stdout


def parse_mapleaf(text: str) -> dict:
    """MAPLEAF's nested ``Name{ key value }`` format -> flat {'A.B.key': 'value'}."""
    out, stack = {}, []
    for line in text.splitlines():
        line = line.split("#")[0].strip()
        if not line:
            continue
        if line.endswith("{"):
            stack.append(line[:-1].strip())
        elif line == "}":
            stack.pop()
        else:
            key, _, value = line.partition(" ")
            out[".".join(stack + [key])] = value.strip()
    return out


def vec(s: str) -> np.ndarray:
    return np.array([float(v) for v in s.strip("()").split()])


def parse_motor(text: str):
    """MAPLEAF motor table: 4 CG lines, then rows ``t thrust oxFlow fuelFlow (oxMOI) (fuelMOI)``.
    Returns (fuel CG z [m, MAPLEAF frame], t [s], thrust [N], oxidiser + fuel mass [kg])."""
    lines = [ln for ln in (re.sub("#.*", "", x).strip() for x in text.splitlines()) if ln]
    cgs = [float(ln.split()[1]) for ln in lines[:4]]
    rows = np.array([[float(v) for v in ln.split()[:4]] for ln in lines[4:]])
    t, thrust, ox, fuel = rows.T
    # MAPLEAF (Rocket/Propulsion.py) integrates the flow rates with the trapezoid rule
    mass = np.trapezoid(ox, t) + np.trapezoid(fuel, t)
    return cgs, t, thrust, mass


def shell_inertia(kind: str, m: float, length: float, r: float, span: float = 0.0):
    """Own [I_transverse, I_axial] [kg m^2] where MAPLEAF gives none: thin-walled cylinder
    m(r^2/2 + L^2/12), m r^2; thin conical shell about its CG m(r^2/4 + L^2/18), m r^2/2
    (the ogive as a cone); fin set of thin plates at mid-span radius rm: axial m rm^2,
    transverse m rm^2/2 + m c^2/12 (c = root chord)."""
    if kind == "tube":
        return m * (r * r / 2 + length ** 2 / 12), m * r * r
    if kind == "nose":
        return m * (r * r / 4 + length ** 2 / 18), m * r * r / 2
    rm = r + span / 2
    return m * rm * rm / 2 + m * length ** 2 / 12, m * rm * rm


def convert(name: str, mirror: str) -> dict:
    sim_file, overrides, motor_file, vv, (desig, dia, mlen, delays, mfr), rail = FLIGHTS[name]
    sim = parse_mapleaf(show(sim_file, mirror))
    S = "Rocket.Sustainer."
    for k, v in overrides.items():
        sim[S + k] = v
    g = lambda comp, key: sim[f"{S}{comp}.{key}"]  # noqa: E731

    # --- geometry (MAPLEAF: z up from the nose tip, so x = -z) -------------------
    d = float(g("Nosecone", "baseDiameter"))
    r = d / 2
    x_tube = -vec(g("UpperBodyTube", "position"))[2]
    l_tube = float(g("UpperBodyTube", "length"))
    nose_len_ar = float(g("Nosecone", "aspectRatio")) * d
    fin_x = -vec(g("TailFins", "position"))[2]
    span = float(g("TailFins", "span"))
    sweep = float(g("TailFins", "sweepAngle"))           # LE sweep from the span-wise normal
    root, tip = float(g("TailFins", "rootChord")), float(g("TailFins", "tipChord"))

    # --- mass override: every component except the motor, MAPLEAF's Inertia.combineInertias
    comps = []
    for comp, kind, length in (("Nosecone", "nose", x_tube), ("UpperBodyTube", "tube", l_tube),
                               ("GeneralMass", None, 0), ("AltimeterMass", None, 0),
                               ("TailFins", "fins", root)):
        if f"{S}{comp}.mass" not in sim:
            continue
        m = float(g(comp, "mass"))
        x = -(vec(g(comp, "position"))[2] + vec(sim.get(f"{S}{comp}.cg", "(0 0 0)"))[2])
        if f"{S}{comp}.MOI" in sim:
            moi = vec(g(comp, "MOI"))
            it, ia, src = moi[0], moi[2], "MAPLEAF"
        else:
            it, ia = shell_inertia(kind, m, length, r, span)
            src = f"shape estimate (MAPLEAF flies 0.01 m = {0.01 * m:.4g})"
        comps.append((comp, m, x, it, ia, src))
    mass = sum(c[1] for c in comps)
    cg = sum(c[1] * c[2] for c in comps) / mass
    i_t = sum(c[3] + c[1] * (c[2] - cg) ** 2 for c in comps)
    i_a = sum(c[4] for c in comps)

    # --- motor --------------------------------------------------------------------
    cgs, t, thrust, prop = parse_motor(show(motor_file, mirror))
    impulse = float(np.trapezoid(thrust, t))
    nozzle_x = x_tube + l_tube                          # assumed: nozzle at the body's aft end
    prop_cg = nozzle_x - (-cgs[2])                      # BurnedFuelInitialCG, forward of the nozzle
    out = HERE / name
    out.mkdir(exist_ok=True)
    rows = "\n".join(f"{a:.6g} {b:.6g}" for a, b in zip(t, thrust))
    (out / "motor.eng").write_text(
        f"; converted from MAPLEAF {motor_file} (henrystoldt/MAPLEAF @ {COMMIT[:10]}) by\n"
        f"; ../make_from_mapleaf.py: thrust table as given; propellant = trapezoid integral of\n"
        f"; MAPLEAF's oxidiser + fuel flow rates; dry mass 0 (the casing is a MAPLEAF mass\n"
        f"; component, counted in the rocket's mass override; total = propellant + 1 mg, as RASP\n"
        f"; needs total > propellant; [motor.overrides] dry_mass = 0); diameter/length assumed\n"
        f"{desig} {dia} {mlen} {delays} {prop:.8f} {prop + 1e-6:.8f} {mfr}\n{rows}\n")
    (out / "mapleaf_motor.txt").write_text(show(motor_file, mirror))
    refs = {}
    for kind in ("ExpData", "OriginalOR", "RockSim"):
        text = show(f"{VV}{vv}{kind}.csv", mirror)
        (out / f"{kind}.csv").write_text(text)
        a = np.loadtxt(text.splitlines()[1:], delimiter=",")
        refs[kind] = (float(a[:, 1].max()), float(a[a[:, 1].argmax(), 0]), float(a[-1, 0]))
    a = np.loadtxt(show(f"{VV}{vv}ReplicatedOR.csv", mirror).splitlines()[1:], delimiter=",")
    refs["ReplicatedOR"] = (float(a[:, 1].max()), float(a[a[:, 1].argmax(), 0]), float(a[-1, 0]))

    wind = vec(sim.get("Environment.ConstantMeanWind.velocity", "(0 0 0)"))
    elevation = float(sim.get("Environment.LaunchSite.elevation", "0"))
    section = ('section = "square"   # Niskanen 2009 sec. 6.1: "the fin profiles were left rectangular"'
               if name != "haisunaata" else
               "# section: not given by the source; the format's default (square)")
    rail_line = (f"rail_length = {rail}   # Niskanen 2009 sec. 6.1: 1 m tower launcher (MAPLEAF: none)"
                 if rail else "# rail_length: not given (MAPLEAF: none); the format's default 5.2 m")
    toml = f"""# {name}: converted from MAPLEAF (henrystoldt/MAPLEAF @ {COMMIT[:10]}) by
# ../make_from_mapleaf.py from {sim_file}{' + OpenRocketCases.mapleaf overrides' if overrides else ''}.
# Positions aft of the nose tip [m]; SI units; angles in degrees. Assumptions: ../README.md.

[rocket]
name = "{name}"
reference_radius = {r:.6g}

[rocket.mass_override]   # MAPLEAF's components without the motor, combined about their CG
mass = {mass:.6g}
cg_x = {cg:.6g}
I_transverse = {i_t:.6g}
I_axial = {i_a:.6g}

[[component]]
type = "nose_cone"
name = "Nosecone"
shape = "tangent_ogive"
length = {x_tube:.6g}   # = the body tube's position (aspect ratio x diameter = {nose_len_ar:.6g})
radius = {r:.6g}
surface_roughness = {float(g("Nosecone", "surfaceRoughness")):.6g}

[[component]]
type = "body_tube"
name = "UpperBodyTube"
length = {l_tube:.6g}
radius = {r:.6g}
surface_roughness = {float(g("UpperBodyTube", "surfaceRoughness")):.6g}

[[component]]
type = "trapezoidal_fins"
name = "TailFins"
count = {int(g("TailFins", "numFins"))}
x = {fin_x:.6g}
root_chord = {root:.6g}
tip_chord = {tip:.6g}
span = {span:.6g}
sweep_length = {span * math.tan(math.radians(sweep)):.6g}   # span x tan(LE sweep {sweep} deg)
thickness = {float(g("TailFins", "thickness")):.6g}
{section}
surface_roughness = {float(g("TailFins", "surfaceRoughness")):.6g}

[motor]
file = "motor.eng"
designation = "{desig}"
nozzle_x = {nozzle_x:.6g}   # assumed: the body tube's aft end

[motor.overrides]
dry_mass = 0.0   # the casing is a MAPLEAF mass component, inside the mass override
dry_cg = 0.0
dry_inertia = [0.0, 0.0]
propellant_cg = {prop_cg:.6g}   # MAPLEAF BurnedFuelInitialCG, x = {-cgs[2]:.6g} m

[launch]   # MAPLEAF's environment: US standard atmosphere, constant wind, vertical launch
inclination_deg = 90.0
heading_deg = 0.0
site_elevation = {elevation:.6g}
wind_speed = {float(np.linalg.norm(wind)):.6g}   # MAPLEAF ConstantMeanWind ({' '.join(f'{w:g}' for w in wind)}) m/s
wind_from_deg = 270.0   # assumed (MAPLEAF's +x); a vertical flight's apogee does not depend on it
{rail_line}
"""
    (out / "rocket_geometry.toml").write_text(toml)
    return dict(name=name, mass=mass, cg=cg, i_t=i_t, i_a=i_a, comps=comps, impulse=impulse,
                prop=prop, burn=float(t[thrust > 0][-1]), refs=refs, nozzle_x=nozzle_x)


def main(argv):
    mirror = argv[1] if len(argv) > 1 else MIRROR
    for name in FLIGHTS:
        s = convert(name, mirror)
        print(f"\n== {name}: rocket without motor {s['mass']:.5f} kg, CG {s['cg']:.5f} m, "
              f"I_t {s['i_t']:.5g}, I_a {s['i_a']:.5g} kg m^2")
        for c in s["comps"]:
            print(f"   {c[0]:14s} m {c[1]:.5g} kg  x {c[2]:.5g} m  I_t {c[3]:.4g}  I_a {c[4]:.4g}  ({c[5]})")
        print(f"   motor: total impulse {s['impulse']:.3f} N s, propellant {s['prop']:.5f} kg, "
              f"last thrust at {s['burn']:.3f} s, average {s['impulse'] / s['burn']:.2f} N")
        for k, (h, th, tl) in s["refs"].items():
            print(f"   {k:13s} max {h:8.2f} m at {th:.2f} s (series ends {tl:.2f} s)")


if __name__ == "__main__":
    main(sys.argv)
