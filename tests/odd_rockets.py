"""Less common but real student-rocket layouts as rocket TOML text (tests): a second
robustness corpus for ``ironbark aero build`` next to tests/random_rockets.py (one nose,
one body, one fin set).  Deterministic per seed (random.Random); the layout cycles with
the seed through LAYOUTS so any ten consecutive seeds cover every one of them:

- ``step_down``: a wide payload bay over a narrower booster joined by a conical reducer
  (NDRT 2020: 203 -> 155 mm), 0.65-0.85 of the radius, 8-30 deg half angle;
- ``step_up``: a narrow forward section flaring to a wider booster (fore/aft 0.65-0.85);
  on 30 % of either, no reducer: an abrupt step between the two tubes;
- ``canards``: a forward set of 4 (or 3) small canards 1-2 calibres behind the nose as
  well as the aft fins;
- ``many_fins``: 6 or 8 fins; ``two_fins``: 2 fins (meshed at their roll average);
- ``fins_past_base``: fins whose trailing edge sticks out 15-45 % of the root chord aft
  of the base;
- ``shoulder``: a nose of 0.75-0.9 of the body radius with a short (0.2-0.6 calibre)
  conical shoulder to the body;
- ``long_thin``: fineness 22-26; ``short_fat``: fineness 5.5-7;
- ``clipped_delta``: large swept clipped-delta fins (root 2.5-3.5 calibres, tip 0.15-0.3
  x root, leading edge swept 50-65 deg, span 1.0-1.6 calibres);
- and on any layout (30 %) airfoil fins, most of them 8-10 % of the root chord thick (at
  most 25 mm; the format's fin thickness is constant along the span, so a tapered fin's
  tip section is thicker still), and (25 %) a launch lug instead of rail buttons.

The TOML keys are those of docs/rocket-toml.md (tube fins are .ork-only)."""
from __future__ import annotations

import math
import random

from random_rockets import MOTOR_DIAMETERS, MOTORS, SECTIONS, _nose

LAYOUTS = ("step_down", "canards", "many_fins", "fins_past_base", "shoulder", "long_thin",
           "step_up", "clipped_delta", "short_fat", "two_fins")


def _tube(length: float, radius: float) -> str:
    return f'[[component]]\ntype = "body_tube"\nlength = {length:.4f}\nradius = {radius:.4f}\n'


def _transition(length: float, fore: float, aft: float) -> str:
    return (f'[[component]]\ntype = "transition"\nlength = {length:.4f}\nfore_radius = {fore:.4f}\n'
            f"aft_radius = {aft:.4f}\n")


def _trapezoid(name: str, count: int, x: float, cr: float, ct: float, span: float, sweep: float,
               t: float, section: str, roll: float | None = None) -> str:
    roll_line = "" if roll is None else f"roll_deg = {roll:g}\n"
    return (f'[[component]]\ntype = "trapezoidal_fins"\nname = "{name}"\ncount = {count}\n{roll_line}'
            f'x = {x:.4f}\nroot_chord = {cr:.4f}\ntip_chord = {ct:.4f}\nspan = {span:.4f}\n'
            f'sweep_length = {sweep:.4f}\nthickness = {t:.4f}\nsection = "{section}"\n')


def _fin_shape(r: random.Random, d: float, layout: str) -> tuple[float, float, float, float]:
    """(root chord, tip chord, span, sweep length) [m] of the aft fins."""
    if layout == "clipped_delta":
        cr, span = r.uniform(2.5, 3.5) * d, r.uniform(1.0, 1.6) * d
        ct = r.uniform(0.15, 0.3) * cr
        sweep = min(span * math.tan(math.radians(r.uniform(50, 65))), cr - ct + 0.3 * cr)
        return cr, ct, span, sweep
    cr, span = r.uniform(1.0, 2.5) * d, r.uniform(0.6, 1.4) * d
    if layout == "many_fins":
        span *= 0.75
    ct = cr * r.choice([0.2, 0.4, 0.6])
    return cr, ct, span, r.uniform(0.3, 1.0) * (cr - ct) + r.uniform(0.0, 0.2) * cr


def odd_rocket(seed: int) -> str:
    """The rocket TOML text [SI] of odd rocket ``seed`` (its layout LAYOUTS[seed % 10])."""
    layout = LAYOUTS[seed % len(LAYOUTS)]
    r = random.Random(1000 + seed)
    motor, motor_d = r.choice(list(MOTOR_DIAMETERS.items()))
    radius = max(motor_d / 2 + 0.005, r.choice([0.0381, 0.0508, 0.0635, 0.0775, 0.0785, 0.1015]))
    aft_radius = radius                               # the booster's radius (fins, motor)
    if layout == "step_down":                         # the bay widened if the motor sets the booster
        q = r.uniform(0.65, 0.85)
        aft_radius = max(motor_d / 2 + 0.004, radius * q)
        radius = max(radius, aft_radius / q)
    d = 2 * radius
    fineness = {"long_thin": r.uniform(22, 26), "short_fat": r.uniform(5.5, 7.0)}.get(layout, r.uniform(12, 20))
    parts, total, step = [], 0.0, None               # step: the reducer's (part index, length)
    if layout == "shoulder":
        nose_r = radius * r.uniform(0.75, 0.9)
        nose, total = _nose(r, nose_r)
        sh = r.uniform(0.2, 0.6) * d
        parts += [nose, _transition(sh, nose_r, radius)]
        total += sh
    elif layout == "step_up":
        fore_r = max(radius * r.uniform(0.65, 0.85), 0.03)
        nose, total = _nose(r, fore_r)
        fore = r.uniform(0.3, 0.45) * (fineness * d - total)
        flare = (radius - fore_r) / math.tan(math.radians(r.uniform(8, 30)))
        parts += [nose, _tube(fore, fore_r), _transition(flare, fore_r, radius)]
        total += fore + flare
        step = (len(parts) - 1, flare)
    else:
        nose, total = _nose(r, radius, (1.5, 2.5) if layout == "short_fat" else (2.5, 6.0))
        parts.append(nose)
    nose_len = total                                  # canards: the body starts here
    cr, ct, span, sweep = _fin_shape(r, 2 * aft_radius, layout)
    if layout == "step_down":
        bay = r.uniform(0.3, 0.5) * (fineness * d - total)
        red = (radius - aft_radius) / math.tan(math.radians(r.uniform(8, 30)))
        parts += [_tube(bay, radius), _transition(red, radius, aft_radius)]
        total += bay + red
        step = (len(parts) - 1, red)
    body = max(fineness * d - total, 1.3 * cr)
    parts.append(_tube(body, aft_radius))
    total += body
    section = "airfoil" if r.random() < 0.3 else r.choice(SECTIONS)
    t = min(max(0.025 * cr, 0.003), 0.008) * r.uniform(0.7, 1.3)
    if section == "airfoil" and r.random() < 0.7:
        t = min(r.uniform(0.08, 0.10) * cr, 0.025)    # a thick (3-D printed) airfoil fin, at most 25 mm
    count = {"many_fins": r.choice([6, 8]), "two_fins": 2}.get(layout, r.choice([3, 4, 4]))
    x_fin = total - cr - r.uniform(0.0, 0.2) * cr
    if layout == "fins_past_base":
        x_fin = total - cr * r.uniform(0.55, 0.85)
    parts.append(_trapezoid("fins", count, x_fin, cr, ct, span, sweep, t, section))
    if layout == "canards":
        ccr, cspan = r.uniform(0.5, 1.0) * d, r.uniform(0.3, 0.5) * d
        ccount = r.choice([3, 4, 4])
        parts.append(_trapezoid("canards", ccount, nose_len + r.uniform(1.0, 2.0) * d, ccr, 0.5 * ccr, cspan,
                                0.5 * ccr, min(max(0.03 * ccr, 0.003), 0.006), r.choice(SECTIONS),
                                roll=(45 if ccount == 4 else 90) + r.choice([0, 45 if ccount == 4 else 60])))
    if r.random() < 0.25:
        parts.append(f'[[component]]\ntype = "launch_lug"\nx = {0.6 * total:.3f}\nlength = 0.15\n'
                     "outer_radius = 0.0127\ninner_radius = 0.0115\n")
    else:
        parts.append(f'[[component]]\ntype = "rail_buttons"\nx_fore = {0.5 * total:.3f}\n'
                     f"x_aft = {0.8 * total:.3f}\nouter_diameter = 0.0124\nheight = 0.0142\n")
    if step is not None and r.random() < 0.3:        # no reducer: an abrupt step, the booster tube longer
        k, length = step
        parts[k:k + 2] = [_tube(body + length, aft_radius)]
    mass = 3.0 * (radius / 0.05) ** 2 * (total / 2.0) * r.uniform(0.8, 1.5) + 1.0
    head = (f'[rocket]\nname = "odd{seed}-{layout}"\n[rocket.mass_override]\nmass = {mass:.3f}\n'
            f"cg_x = {0.55 * total:.3f}\nI_transverse = {mass * total ** 2 / 12:.3f}\n"
            f"I_axial = {mass * radius ** 2 / 2:.4f}\n")
    tail = f'[motor]\nfile = "{(MOTORS / motor).as_posix()}"\nnozzle_x = {total:.4f}\n[launch]\nrail_length = 5.0\n'
    return head + "".join(parts) + tail
