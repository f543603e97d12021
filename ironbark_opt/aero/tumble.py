"""Drag of a tumbling body (numeric-only).

S. Niskanen, *OpenRocket technical documentation* (2013-05-10 revision for
OpenRocket 13.05), sec. 3.5 "Drag estimation of tumbling bodies", from drop
tests of tumbling model-rocket stages:

    Cd A = 1.42 sum_fin sets (eta_N A_fin) + 0.56 sum_bodies A_planform

with ``A_fin`` the planform area of one fin of a set of ``N`` fins, ``eta_N``
the fin-count efficiency 0.5, 1.0, 1.41, 1.81, 1.73, 1.90, 1.85 for 1-7
fins (held above 7), and ``A_planform`` each body component's side
projection (length x diameter for a tube).  OpenRocket flies a statically
unstable lower stage or booster after separation with it (``BasicTumbleStepper``).
"""
from __future__ import annotations

#: drag coefficients of tumbling fins and bodies (Niskanen 2013, sec. 3.5)
CD_FIN, CD_BODY = 1.42, 0.56
#: fin-count efficiency eta_N, index N (Niskanen 2013, sec. 3.5 table)
FIN_EFFICIENCY = (0.0, 0.5, 1.0, 1.41, 1.81, 1.73, 1.90, 1.85)


def tumble_cd_area(rocket) -> float:
    """Cd x area [m^2] of ``rocket`` (a :class:`~ironbark_opt.rocket.Rocket`) tumbling."""
    fins = sum(FIN_EFFICIENCY[min(fs.count, len(FIN_EFFICIENCY) - 1)] * fs.planform_area()
               for fs in rocket.fin_sets())
    body = sum(c.planform_area() for c in rocket.body_components())
    return CD_FIN * fins + CD_BODY * body
