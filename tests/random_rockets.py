"""Random plausible student rockets as rocket TOML text (tests): a robustness corpus for
``ironbark aero build`` beyond the fixtures.  Deterministic per seed (random.Random).

Ranges (a K-M high-power rocket of 3-8 inch calibre): any of the nine nose shapes,
2.5-6 calibres long; a body 6-16 calibres; a boattail (4-20 deg, to 0.6-0.9 of the
radius) on a third of them, the fins on it on 40 % of those; 3 or 4 trapezoidal (tip
chord 0-1 x root, swept), elliptical or free-form fins of every section, root chord
1-3 calibres, span 0.6-1.6 calibres, 2.5 % thick (3-8 mm, +-30 %); OpenRocket-size rail
buttons; a mass override and one of eight K-M motors (tests/data/motors)."""
from __future__ import annotations

import math
import random
from pathlib import Path

MOTORS = Path(__file__).parent / "data" / "motors"
#: motor file: its diameter [m]
MOTOR_DIAMETERS = {"AeroTech_K1000T.eng": 0.054, "AeroTech_L1940X.eng": 0.075, "AeroTech_M1939W.eng": 0.098,
                   "Cesaroni_2772L640-P.eng": 0.075, "AeroTech_I357T.eng": 0.038, "AeroTech_M1305M.eng": 0.098,
                   "AMW_6774M2050-P.eng": 0.098, "AeroTech_K550W.eng": 0.054}
NOSES = ("conical", "tangent_ogive", "secant_ogive", "elliptical", "parabolic", "power", "haack",
         "von_karman", "lv_haack")
SECTIONS = ("square", "rounded", "airfoil", "double_wedge")


def _nose(r: random.Random, radius: float, calibres: tuple[float, float] = (2.5, 6.0)) -> tuple[str, float]:
    """A nose cone's TOML text and its length [m]: any shape, ``calibres`` long."""
    shape = r.choice(NOSES)
    length = r.uniform(*calibres) * 2 * radius
    extra = ""
    if shape == "power":
        extra = f"shape_parameter = {r.choice([0.33, 0.5, 0.75])}\n"
    elif shape == "parabolic":
        extra = f"shape_parameter = {r.choice([0.5, 0.75, 1.0])}\n"
    elif shape == "secant_ogive":
        extra = f"ogive_radius = {1.3 * (length ** 2 + radius ** 2) / (2 * radius):.4f}\n"
    return (f'[[component]]\ntype = "nose_cone"\nshape = "{shape}"\n{extra}length = {length:.4f}\n'
            f"radius = {radius:.4f}\n"), length


def _fins(r: random.Random, d: float, x_end: float, boattail_len: float, on_boattail: bool) -> str:
    kind = r.choices(["trapezoidal_fins", "elliptical_fins", "freeform_fins"], [0.75, 0.15, 0.1])[0]
    cr, span = r.uniform(1.0, 3.0) * d, r.uniform(0.6, 1.6) * d
    section = r.choice(SECTIONS)
    t = min(max(0.025 * cr, 0.003), 0.008) * r.uniform(0.7, 1.3)
    if on_boattail:
        x = x_end - boattail_len - cr * r.uniform(0.3, 0.7)
    else:
        x = x_end - cr - r.uniform(0, 0.3) * cr
    text = (f'[[component]]\ntype = "{kind}"\ncount = {r.choice([3, 4, 4, 4])}\nx = {x:.4f}\n'
            f'thickness = {t:.4f}\nsection = "{section}"\n')
    if kind == "trapezoidal_fins":
        ct = cr * r.choice([0.0, 0.2, 0.4, 0.6, 1.0])
        sweep = r.uniform(0.0, 1.2) * (cr - ct) + r.uniform(0, 0.3) * cr
        return text + f"root_chord = {cr:.4f}\ntip_chord = {ct:.4f}\nspan = {span:.4f}\nsweep_length = {sweep:.4f}\n"
    if kind == "elliptical_fins":
        return text + f"root_chord = {cr:.4f}\nspan = {span:.4f}\n"
    # the tip chord 0.3 x root from a leading edge swept by 0.3-1.1 x root: its trailing edge
    # may sweep aft of the root's (until session 19 it was clipped to the root's station, which
    # crossed the outline whenever the tip's leading edge lay aft of the root trailing edge)
    tip_x = r.uniform(0.3, 1.1) * cr
    return text + (f"points = [[0, 0], [{tip_x:.4f}, {span:.4f}], [{tip_x + 0.3 * cr:.4f}, "
                   f"{span:.4f}], [{cr:.4f}, 0]]\n")


def random_rocket(seed: int) -> str:
    """The rocket TOML text [SI] of random rocket ``seed``."""
    r = random.Random(seed)
    motor, motor_d = r.choice(list(MOTOR_DIAMETERS.items()))
    radius = max(motor_d / 2 + 0.005, r.choice([0.0381, 0.0508, 0.0635, 0.0775, 0.0785, 0.1015]))
    d = 2 * radius
    nose, total = _nose(r, radius)
    body = r.uniform(6, 16) * d
    total += body
    parts = [nose, f'[[component]]\ntype = "body_tube"\nlength = {body:.4f}\nradius = {radius:.4f}\n']
    boattail = r.random() < 0.35
    on_boattail = boattail and r.random() < 0.4
    bt_len = 0.0
    if boattail:
        aft_r = max(motor_d / 2 + 0.002, radius * r.uniform(0.6, 0.9))
        bt_len = (radius - aft_r) / math.tan(math.radians(r.uniform(4, 20)))
        parts.append(f'[[component]]\ntype = "transition"\nlength = {bt_len:.4f}\nfore_radius = {radius:.4f}\n'
                     f"aft_radius = {aft_r:.4f}\n")
    total += bt_len
    parts.append(_fins(r, d, total, bt_len, on_boattail))
    parts.append(f'[[component]]\ntype = "rail_buttons"\nx_fore = {0.5 * total:.3f}\nx_aft = {0.8 * total:.3f}\n'
                 "outer_diameter = 0.0124\nheight = 0.0142\n")
    mass = 3.0 * (radius / 0.05) ** 2 * (total / 2.0) * r.uniform(0.8, 1.5) + 1.0
    head = (f'[rocket]\nname = "random{seed}"\n[rocket.mass_override]\nmass = {mass:.3f}\ncg_x = {0.55 * total:.3f}\n'
            f"I_transverse = {mass * total ** 2 / 12:.3f}\nI_axial = {mass * radius ** 2 / 2:.4f}\n")
    tail = f'[motor]\nfile = "{(MOTORS / motor).as_posix()}"\nnozzle_x = {total:.4f}\n[launch]\nrail_length = 5.0\n'
    return head + "".join(parts) + tail
