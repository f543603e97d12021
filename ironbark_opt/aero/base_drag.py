"""Base drag, motor off and motor on.

Empirical base drag coefficient on the base area (Niskanen, OpenRocket technical
documentation, 2013, eq. 3.94, from its ref. [18], p. 23):

    Cd_base = 0.12 + 0.13 M^2   (M < 1),      Cd_base = 0.25 / M   (M > 1).

The two branches meet at 0.25 for M = 1 but their slopes differ (+0.26 / -0.25); for a
smooth symbolic model they are blended by a quintic smooth step over
1 - `BLEND_WIDTH` < M < 1 + `BLEND_WIDTH`, which moves the value by at most 1.5 % of
Cd_base inside that band and not at all outside it (tests/unit/test_base_drag.py).

Motor on: the exhaust fills part of the base, and "a reasonable approximation is achieved
by subtracting the area of the thrusting motors from the base reference area" (Niskanen
2013, sec. 3.4.5).  Here the subtracted ``jet_area`` is the nozzle exit area when known
(our choice; pass the motor cross-section to reproduce OpenRocket).

All functions are symbolic-safe in ``mach``.
"""
from __future__ import annotations

import math

from ironbark_opt import _math
from ironbark_opt.aero.friction_flatplate import smooth_step
from ironbark_opt.errors import InputError

BLEND_WIDTH = 0.1  #: half-width of the subsonic/supersonic blend around M = 1 [-]


def cd_base(mach):
    """Base drag coefficient on the base area [-]; symbolic-safe.

    Parameters
    ----------
    mach : float, array or SX/MX [-]
    """
    w = smooth_step(mach, 1.0 - BLEND_WIDTH, 1.0 + BLEND_WIDTH)
    subsonic = 0.12 + 0.13 * mach * mach                   # Niskanen 2013, eq. 3.94, M < 1
    supersonic = 0.25 / _math.fmax(mach, 0.5)              # Niskanen 2013, eq. 3.94, M > 1
    return (1.0 - w) * subsonic + w * supersonic


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
    """

    def __init__(self, base_area: float, reference_area: float, jet_area: float = 0.0):
        self.base_area = _check_area(base_area, "base_area")
        self.reference_area = _check_area(reference_area, "reference_area")
        self.jet_area = _check_area(jet_area, "jet_area")
        if self.reference_area == 0:
            raise InputError("expected > 0 [m^2]", field="reference_area")

    def __repr__(self) -> str:
        return (f"BaseDrag(base {self.base_area:g} m^2, jet {self.jet_area:g} m^2, "
                f"Sref {self.reference_area:g} m^2)")

    def CA_power_off(self, mach):
        """Base CA with the motor off [-]; symbolic-safe. ``mach`` [-]."""
        return cd_base(mach) * (self.base_area / self.reference_area)

    def CA_power_on(self, mach):
        """Base CA with the motor burning [-]; symbolic-safe. ``mach`` [-].

        The jet area is removed from the base area (Niskanen 2013, sec. 3.4.5).
        """
        return cd_base(mach) * (max(self.base_area - self.jet_area, 0.0) / self.reference_area)
