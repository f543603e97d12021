"""Skin-friction axial-force coefficient of a rocket by component build-up.

CA_friction = sum_i C_F,i * FF_i * S_wet,i / S_ref, where C_F,i is the flat-plate mean
skin friction of component i at Re_i = (Re per metre) * L_i (`cf_flat_plate`: laminar
Blasius + Eckert, van Driest II turbulent, Prandtl–Schlichting transition, Barrowman
roughness) and FF_i its form factor (Hoerner).  Component build-up as in Niskanen,
OpenRocket technical documentation (2013), eq. 3.85, with Hoerner form factors in place
of OpenRocket's (1 + 1/(2 f_B)) and (1 + 2 t/c).

Drag increments that live at flight conditions like friction (the launch guides,
:mod:`ironbark_opt.aero.protuberance`) are added to the sum (``protuberances``) and
tabulated with it.

`FrictionDrag.CA` is meant for the symbolic RK4 step, so it is cheap: the whole sum is
tabulated once, at construction, on a (Mach, log10 Re per metre) grid and evaluated by
one 2-D B-spline (the same spline in SciPy and CasADi).  Its error against the formulas
is largest next to the kinks of the laminar/turbulent and smooth/rough switches: measured
< 0.75 % maximum and < 0.25 % at the 99th percentile over Mach 0-5, Re 1e3-1e9 per metre
(tests/unit/test_friction.py).  `FrictionDrag.CA_exact`
evaluates the formulas directly (also symbolic-safe) and is the reference the table is
tested against.
"""
from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from ironbark_opt import _math
from ironbark_opt.aero.friction_flatplate import (RE_TRANSITION_DEFAULT, T_DEFAULT, cf_flat_plate,
                                                  form_factor_body, form_factor_fin)
from ironbark_opt.aero.table import GridSpline
from ironbark_opt.errors import InputError

TABLE_MACH_STEP = 0.05        #: Mach spacing of the friction table [-]
TABLE_LOG_RE_STEP = 0.025     #: log10(Re per metre) spacing of the friction table [-]


@dataclass(frozen=True)
class FrictionComponent:
    """One wetted part of the rocket for the friction build-up.

    Parameters
    ----------
    name : str
    wetted_area : float [m^2]
        Area in contact with the flow (both sides for fins).
    length : float [m]
        Run length of the boundary layer (body length, fin mean chord).
    form_factor : float [-]
        >= 1; see `form_factor_body`, `form_factor_fin`.
    roughness : float [m]
        Equivalent sand-grain roughness height; 0 = smooth.
    """

    name: str
    wetted_area: float
    length: float
    form_factor: float = 1.0
    roughness: float = 0.0

    def __post_init__(self):
        for field, val, ok, what in (
                ("wetted_area", self.wetted_area, lambda v: v > 0, "> 0 [m^2]"),
                ("length", self.length, lambda v: v > 0, "> 0 [m]"),
                ("form_factor", self.form_factor, lambda v: v >= 1, ">= 1 [-]"),
                ("roughness", self.roughness, lambda v: v >= 0, ">= 0 [m]")):
            if (isinstance(val, bool) or not isinstance(val, (int, float, np.number))
                    or not math.isfinite(val) or not ok(val)):
                raise InputError(f"component '{self.name}': expected {what}, got {val!r}",
                                 field=field)
        if self.roughness >= self.length:
            raise InputError(f"component '{self.name}': roughness {self.roughness!r} m is not "
                             f"smaller than the length {self.length!r} m", field="roughness")

    @classmethod
    def body(cls, name: str, length: float, diameter: float, wetted_area: float | None = None,
             roughness: float = 0.0) -> "FrictionComponent":
        """A body of revolution; FF from its fineness L/D (`form_factor_body`). Numeric-only.

        ``length`` [m], ``diameter`` [m], ``wetted_area`` [m^2] (default pi D L),
        ``roughness`` [m].
        """
        if not (diameter > 0 and length > 0):
            raise InputError(f"body '{name}': length and diameter must be > 0 [m]", field="diameter")
        area = math.pi * diameter * length if wetted_area is None else wetted_area
        return cls(name, area, length, float(form_factor_body(length / diameter)), roughness)

    @classmethod
    def fins(cls, name: str, wetted_area: float, mean_chord: float, thickness: float,
             roughness: float = 0.0) -> "FrictionComponent":
        """A fin set; FF from t/c (`form_factor_fin`). Numeric-only.

        ``wetted_area`` [m^2] (all fins, both sides), ``mean_chord`` [m], ``thickness`` [m],
        ``roughness`` [m].
        """
        if not (mean_chord > 0 and thickness >= 0):
            raise InputError(f"fins '{name}': need mean_chord > 0 and thickness >= 0 [m]",
                             field="thickness")
        return cls(name, wetted_area, mean_chord, float(form_factor_fin(thickness / mean_chord)),
                   roughness)


class FrictionDrag:
    """Skin-friction CA of a set of components, tabulated for speed.

    Construction is numeric-only (it evaluates `CA_exact` on the table grid); `CA` and
    `CA_exact` are symbolic-safe.

    Parameters
    ----------
    components : sequence of FrictionComponent
    reference_area : float [m^2]
    re_transition : float [-]
        Transition Reynolds number (default 5e5).
    temperature : float [K]
        Static temperature at which the table is built (enters only through the
        Sutherland viscosity ratio in the compressibility corrections: changing it from
        288 K to 220 K changes CA by < 0.75 % up to Mach 3, see the unit tests).
    mach_max : float [-]
        Upper end of the table's Mach axis (0 .. mach_max).
    reynolds_per_m_range : (float, float) [1/m]
        Table range of the unit Reynolds number; below the minimum the value is held
        (near-zero airspeed), above the maximum clamped with a warning.
    protuberances : sequence
        Drag increments evaluated at flight conditions with the friction and tabulated
        with it: objects with ``CA(mach, reynolds_per_m, reference_area)`` (symbolic-safe),
        e.g. the launch guides of :mod:`ironbark_opt.aero.protuberance`.
    """

    def __init__(self, components: Sequence[FrictionComponent], reference_area: float,
                 re_transition: float = RE_TRANSITION_DEFAULT, *, temperature: float = T_DEFAULT,
                 mach_max: float = 5.0, reynolds_per_m_range: tuple[float, float] = (1.0e3, 1.0e9),
                 protuberances: Sequence = ()):
        self.components = tuple(components)
        self.protuberances = tuple(protuberances)
        if not self.components or not all(isinstance(c, FrictionComponent) for c in self.components):
            raise InputError("expected a non-empty sequence of FrictionComponent", field="components")
        if not reference_area > 0:
            raise InputError(f"expected > 0 [m^2], got {reference_area!r}", field="reference_area")
        if not re_transition > 0:
            raise InputError(f"expected > 0, got {re_transition!r}", field="re_transition")
        lo, hi = reynolds_per_m_range
        if not 0 < lo < hi:
            raise InputError(f"expected 0 < min < max, got {reynolds_per_m_range!r}",
                             field="reynolds_per_m_range")
        if not mach_max > 0:
            raise InputError(f"expected > 0, got {mach_max!r}", field="mach_max")
        self.reference_area = float(reference_area)
        self.re_transition = float(re_transition)
        self.temperature = float(temperature)
        n_m = int(math.ceil(mach_max / TABLE_MACH_STEP)) + 1
        n_r = int(math.ceil((math.log10(hi) - math.log10(lo)) / TABLE_LOG_RE_STEP)) + 1
        mach = np.linspace(0.0, mach_max, n_m)
        log_re = np.linspace(math.log10(lo), math.log10(hi), n_r)
        mm, rr = np.meshgrid(mach, log_re, indexing="ij")
        values = self.CA_exact(mm, 10.0 ** rr, self.temperature)
        self._table = GridSpline([mach, log_re], values, name="CA_friction",
                                 axis_names=("mach", "log10_reynolds_per_m"))

    def __repr__(self) -> str:
        extra = f", {len(self.protuberances)} protuberances" if self.protuberances else ""
        return (f"FrictionDrag({len(self.components)} components{extra}, Sref {self.reference_area:g} m^2, "
                f"Re_tr {self.re_transition:g})")

    @property
    def table(self) -> GridSpline:
        """The (Mach, log10 Re per metre) spline behind `CA`."""
        return self._table

    def CA_exact(self, mach, reynolds_per_m, temperature=T_DEFAULT):
        """Friction CA from the formulas [-]; symbolic-safe (but ~100 operations per component).

        Parameters
        ----------
        mach : float, array or SX/MX [-]
        reynolds_per_m : float, array or SX/MX [1/m]
            rho V / mu of the free stream.
        temperature : float or SX/MX [K]
            Free-stream static temperature.
        """
        total = 0.0
        for c in self.components:
            cf = cf_flat_plate(mach, reynolds_per_m * c.length, c.length, c.roughness,
                               self.re_transition, temperature)
            total = total + cf * (c.form_factor * c.wetted_area / self.reference_area)
        for p in self.protuberances:
            total = total + p.CA(mach, reynolds_per_m, self.reference_area)
        return total

    def CA(self, mach, reynolds_per_m):
        """Friction CA from the table [-]; symbolic-safe (one 2-D B-spline evaluation).

        Parameters
        ----------
        mach : float, array or SX/MX [-]
        reynolds_per_m : float, array or SX/MX [1/m]
            Held at the table minimum below it (silently); clamped with a warning
            (numeric input) above the table's Mach or Reynolds range.
        """
        lo = float(10.0 ** self._table.axes[1][0])
        log_re = _math.log10(_math.fmax(reynolds_per_m, lo))
        if not _math.is_symbolic(mach, log_re):
            log_re = np.maximum(log_re, self._table.axes[1][0])  # no warning for the floor
        return self._table.symbolic(mach, log_re)
