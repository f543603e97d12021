"""Base drag, motor off and motor on.

Two models of the base drag coefficient on the base area, Cd_base = -Cp_base:

``"niskanen"`` (OpenRocket; Niskanen, OpenRocket technical documentation, 2013,
eq. 3.94, from its ref. [18], p. 23)::

    Cd_base = 0.12 + 0.13 M^2   (M < 1),      Cd_base = 0.25 / M   (M > 1).

``"mccoy"`` (default): the same subsonic branch, and above Mach 1 the base
pressure ratio of McCoy's MC DRAG (R. L. McCoy, "MC DRAG - a computer program
for estimating the drag coefficients of projectiles", BRL ARBRL-TR-02293, 1981,
base-drag equations; also McCoy, *Modern Exterior Ballistics*, 1999, ch. 4)::

    p_b / p_inf = 1 / (1 + 0.2477 M^2 + 0.0345 M^4),
    Cd_base     = (1 - p_b / p_inf) * 2 / (gamma M^2)      (gamma = 1.4).

    p_b / p_inf *= 1 + 0.09 M^2 (1 - exp(-L_afterbody / d))

the last factor being MC DRAG's boundary-layer relief with the cylindrical
afterbody length in calibers (applied as published; for rockets, whose
afterbodies are long, it is 1 + 0.09 M^2).  The 0.25/M rule is about half of
measured supersonic base drag of finned bodies (Basic Finner range data,
tests/validation/test_panel_basic_finner_supersonic.py); MC DRAG is bounded by
the vacuum limit 2/(gamma M^2) by construction.

Both models blend their subsonic and supersonic branches with a quintic smooth
step over 1 - `BLEND_WIDTH` < M < 1 + `BLEND_WIDTH` (C2, and exactly the
formulas outside that band).

Motor on: the exhaust fills part of the base, and "a reasonable approximation is achieved
by subtracting the area of the thrusting motors from the base reference area" (Niskanen
2013, sec. 3.4.5).  Here the subtracted ``jet_area`` is the nozzle exit area when known
(our choice; pass the motor cross-section to reproduce OpenRocket).

All coefficient functions are symbolic-safe in ``mach``.
"""
from __future__ import annotations

import math

from ironbark_opt import _math
from ironbark_opt.aero.friction_flatplate import smooth_step
from ironbark_opt.errors import InputError

BLEND_WIDTH = 0.1  #: half-width of the subsonic/supersonic blend around M = 1 [-]
GAMMA = 1.4        #: ratio of specific heats of air [-]
MODELS = ("mccoy", "niskanen")


def _subsonic(mach):
    return 0.12 + 0.13 * mach * mach                       # Niskanen 2013, eq. 3.94, M < 1


#: Cylindrical afterbody length [calibers] assumed when none is given (rockets: long).
AFTERBODY_CALIBERS = 10.0


def base_pressure_ratio_mccoy(mach, afterbody_calibers: float = AFTERBODY_CALIBERS):
    """Supersonic base-to-free-stream pressure ratio p_b/p_inf [-]; symbolic-safe.

    McCoy (1981), MC DRAG base-pressure equation for M > 1 with its
    boundary-layer relief factor.  Meaningful for M >= 1.

    Parameters
    ----------
    mach : float, array or SX/MX [-]
    afterbody_calibers : float [-]
        Cylindrical afterbody length / diameter.
    """
    m2 = mach * mach
    relief = 1.0 + 0.09 * m2 * (1.0 - math.exp(-float(afterbody_calibers)))   # McCoy 1981, MC DRAG
    return relief / (1.0 + 0.2477 * m2 + 0.0345 * m2 * m2)                    # McCoy 1981, MC DRAG, M > 1


def cd_base_supersonic_mccoy(mach, afterbody_calibers: float = AFTERBODY_CALIBERS):
    """Supersonic base drag coefficient on the base area, MC DRAG [-]; symbolic-safe.

    ``(1 - p_b/p_inf) * 2 / (gamma M^2)`` (definition of Cp with the McCoy 1981 ratio).
    Meaningful for M >= 1; ``mach`` is floored at 0.5 to stay finite.

    Parameters
    ----------
    mach : float, array or SX/MX [-]
    afterbody_calibers : float [-]
    """
    m = _math.fmax(mach, 0.5)
    return (1.0 - base_pressure_ratio_mccoy(m, afterbody_calibers)) * (2.0 / GAMMA) / (m * m)


def cd_base(mach, model: str = "niskanen", afterbody_calibers: float = AFTERBODY_CALIBERS):
    """Base drag coefficient on the base area [-]; symbolic-safe.

    Parameters
    ----------
    mach : float, array or SX/MX [-]
    model : str
        ``"niskanen"`` (OpenRocket eq. 3.94, the default here so the OpenRocket-like
        empirical drag stays OpenRocket's) or ``"mccoy"`` (supersonic MC DRAG base
        pressure, see the module docstring).
    """
    if model not in MODELS:
        raise InputError(f"unknown base-drag model {model!r}; expected one of {MODELS}",
                         field="base_drag.model")
    w = smooth_step(mach, 1.0 - BLEND_WIDTH, 1.0 + BLEND_WIDTH)
    if model == "niskanen":
        supersonic = 0.25 / _math.fmax(mach, 0.5)          # Niskanen 2013, eq. 3.94, M > 1
    else:
        supersonic = cd_base_supersonic_mccoy(mach, afterbody_calibers)
    return (1.0 - w) * _subsonic(mach) + w * supersonic


def _check_area(value, field):
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value) \
            or value < 0:
        raise InputError(f"expected an area >= 0 [m^2], got {value!r}", field=field)
    return float(value)


class BaseDrag:
    """Base drag of a rocket as an axial-force coefficient on the reference area.

    Parameters
    ----------
    base_area : float [m^2]
        Area of the flat base (aft end of the body, after any boattail).
    reference_area : float [m^2]
    jet_area : float [m^2]
        Part of the base filled by the exhaust while the motor burns (nozzle exit area,
        or the motor cross-section as in OpenRocket); 0 = no reduction.
    model : str
        ``"mccoy"`` (default; supersonic MC DRAG base pressure) or ``"niskanen"``
        (OpenRocket's 0.25/M), see :func:`cd_base`.
    afterbody_calibers : float [-]
        Cylindrical afterbody length / diameter (MC DRAG's boundary-layer relief).
    fin_trailing_edge_area : float [m^2]
        Blunt fin trailing edges: sum over fins of thickness x span x
        :attr:`~ironbark_opt.rocket.fin_sections.FinSection.trailing_edge_base_fraction`.
        They take the body-base coefficient of Niskanen 2013 eq. 3.94 whatever
        ``model`` is (as OpenRocket's fin base drag; MC DRAG's boundary-layer
        relief is for a body base), with the motor burning or not.
    """

    def __init__(self, base_area: float, reference_area: float, jet_area: float = 0.0,
                 model: str = "mccoy", afterbody_calibers: float = AFTERBODY_CALIBERS,
                 fin_trailing_edge_area: float = 0.0):
        self.base_area = _check_area(base_area, "base_area")
        self.fin_trailing_edge_area = _check_area(fin_trailing_edge_area, "fin_trailing_edge_area")
        self.reference_area = _check_area(reference_area, "reference_area")
        self.jet_area = _check_area(jet_area, "jet_area")
        if self.reference_area == 0:
            raise InputError("expected > 0 [m^2]", field="reference_area")
        if model not in MODELS:
            raise InputError(f"unknown base-drag model {model!r}; expected one of {MODELS}",
                             field="base_drag.model")
        self.model = model
        self.afterbody_calibers = float(afterbody_calibers)

    def __repr__(self) -> str:
        return (f"BaseDrag(base {self.base_area:g} m^2, jet {self.jet_area:g} m^2, fin trailing "
                f"edges {self.fin_trailing_edge_area:g} m^2, Sref {self.reference_area:g} m^2, "
                f"{self.model})")

    def CA_fin_trailing_edges(self, mach):
        """Base CA of the blunt fin trailing edges [-]; symbolic-safe. ``mach`` [-]."""
        if self.fin_trailing_edge_area == 0.0:
            return 0.0 * mach
        return cd_base(mach, "niskanen") * (self.fin_trailing_edge_area / self.reference_area)

    def CA_power_off(self, mach):
        """Base CA with the motor off [-]; symbolic-safe. ``mach`` [-]."""
        return (cd_base(mach, self.model, self.afterbody_calibers) * (self.base_area / self.reference_area)
                + self.CA_fin_trailing_edges(mach))

    def CA_power_on(self, mach):
        """Base CA with the motor burning [-]; symbolic-safe. ``mach`` [-].

        The jet area is removed from the base area (Niskanen 2013, sec. 3.4.5).
        """
        return (cd_base(mach, self.model, self.afterbody_calibers)
                * (max(self.base_area - self.jet_area, 0.0) / self.reference_area)
                + self.CA_fin_trailing_edges(mach))
