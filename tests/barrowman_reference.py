"""Barrowman's normal-force slope and centre of pressure of a rocket (the empirical
path's components, ironbark_opt.aero.model.lift_geometry), optionally with the fins'
lift carried over onto the body: an independent reference for the panel tables (tests)."""
from ironbark_opt.aero import barrowman
from ironbark_opt.aero.model import lift_geometry


def barrowman_cna_cp(rocket, mach: float, fins_only_from: float | None = None,
                     carryover: bool = False) -> tuple[float, float]:
    """(CN-alpha [1/rad], CP [m]) by Barrowman at ``mach`` [-]; with ``fins_only_from``
    [m] the fins whose CP lies aft of it only; with ``carryover`` each fin set's lift
    times K_W(B) + K_B(W) = (1 + r/(s + r))^2 over Barrowman's K_T(B) (the body's
    carry-over, slender-body theory: Pitts, Nielsen & Kaattari, NACA Rep. 1307)."""
    geo = lift_geometry(rocket)
    comps = geo.components(mach, rocket.reference_area())
    scale = [1.0] * len(geo.bodies) + [
        barrowman.slender_body_interference(f.planform.span, f.body_radius)
        / barrowman.interference_factor(f.planform.span, f.body_radius) if carryover else 1.0
        for f in geo.fins]
    pairs = [(float(c.cn_alpha) * k, float(c.x_cp)) for c, k in zip(comps, scale)
             if fins_only_from is None or c.x_cp > fins_only_from]
    cna = sum(n for n, _ in pairs)
    return cna, sum(n * x for n, x in pairs) / cna
