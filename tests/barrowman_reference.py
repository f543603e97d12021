"""Barrowman's normal-force slope and centre of pressure of a rocket (the empirical
path's components, ironbark_opt.aero.model.lift_geometry), optionally with the fins'
lift carried over onto the body: an independent reference for the panel tables (tests)."""
from ironbark_opt.aero import barrowman
from ironbark_opt.aero.model import lift_geometry


def _carryover(fin) -> float:
    """K_W(B) + K_B(W) = (1 + r/(s + r))^2 (slender-body theory: Pitts, Nielsen & Kaattari,
    NACA Rep. 1307) over Barrowman's K_T(B) for the fin set ``fin`` of
    :func:`~ironbark_opt.aero.model.lift_geometry` [-]."""
    return (barrowman.slender_body_interference(fin.planform.span, fin.body_radius)
            / barrowman.interference_factor(fin.planform.span, fin.body_radius))


def barrowman_cna_cp(rocket, mach: float, fins_only_from: float | None = None,
                     carryover: bool = False) -> tuple[float, float]:
    """(CN-alpha [1/rad], CP [m]) by Barrowman at ``mach`` [-]; with ``fins_only_from``
    [m] the fins whose CP lies aft of it only; with ``carryover`` each fin set's lift
    times K_W(B) + K_B(W) = (1 + r/(s + r))^2 over Barrowman's K_T(B) (the body's
    carry-over, slender-body theory: Pitts, Nielsen & Kaattari, NACA Rep. 1307)."""
    geo = lift_geometry(rocket)
    comps = geo.components(mach, rocket.reference_area())
    scale = [1.0] * len(geo.bodies) + [_carryover(f) if carryover else 1.0 for f in geo.fins]
    pairs = [(float(c.cn_alpha) * k, float(c.x_cp)) for c, k in zip(comps, scale)
             if fins_only_from is None or c.x_cp > fins_only_from]
    cna = sum(n for n, _ in pairs)
    return cna, sum(n * x for n, x in pairs) / cna


def planar_wake_cna_cp(rocket, mach: float) -> tuple[float, float]:
    """(CN-alpha [1/rad], CP [m]) as :func:`barrowman_cna_cp` with carry-over, but each
    fin set (a canard) with a set behind it in line (a fin at the same roll angle)
    reaching at least as far out gives its lift back on that set: slender-body theory
    with a flat wake, where a configuration's lift is that of its aft-most cross section
    (R. T. Jones, NACA Rep. 835, 1946; J. N. Nielsen, Missile Aerodynamics, 1960, ch. 7,
    wing-tail interference).  The canard's lift and the tail's loss make a pure couple,
    so the CP moves forward with CN-alpha as without the canard: the other bound, next
    to Barrowman's no interference, of what linear potential flow gives."""
    from ironbark_opt.rocket.rocket import _share_a_fin_line
    geo = lift_geometry(rocket)
    comps = geo.components(mach, rocket.reference_area())
    nb = len(geo.bodies)
    pairs = [(float(c.cn_alpha), float(c.x_cp)) for c in comps[:nb]]
    sets = rocket.fin_sets()
    for k, (c, f, fs) in enumerate(zip(comps[nb:], geo.fins, sets)):
        n = float(c.cn_alpha) * _carryover(f)
        pairs.append((n, float(c.x_cp)))
        behind = [(j, g) for j, (g, gs) in enumerate(zip(geo.fins, sets)) if gs.x > fs.x_end
                  and _share_a_fin_line(fs, gs)
                  and g.body_radius + g.planform.span >= f.body_radius + f.planform.span - 1e-9]
        if behind:
            j, _ = min(behind, key=lambda p: sets[p[0]].x)
            pairs.append((-n, float(comps[nb + j].x_cp)))
    cna = sum(n for n, _ in pairs)
    return cna, sum(n * x for n, x in pairs) / cna
