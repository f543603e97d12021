"""Solid rocket motor from a tabulated thrust curve.

The thrust curve (t_k, F_k) is the piecewise-linear interpolant of the file's
points (RASP convention: if the first point is after t = 0 the curve starts
from (0, 0)).  Its integral, the impulse, is piecewise quadratic, but

    H(tau) = I0(tau) - tau F0(tau) / 2

is continuous and piecewise *linear* (on a segment F = b + g tau and
I = a + b tau + g tau^2 / 2, so H = a + b tau / 2).  One linear table of
(F, H) on the knots therefore gives the thrust and the exact impulse
I0 = H + tau F0 / 2 (so I0(t_burnout) is exactly the trapezoid integral of
the file's points).  Numbers go through ``np.interp``; symbols through one
``casadi.interpolant(..., 'linear')`` call per time, which measured 2-6x
faster inside an SX RK4 step than a ramp sum  sum_k c_k max(0, tau - t_k)
(the cost of the ramp sum grows with the number of points, the table
look-up's does not).  Thrust is 0 before ignition and after burnout (clipped
time, factors [tau >= 0] [tau <= t_burnout]); a first point at t = 0 with
non-zero thrust is a jump at ignition, a last point with non-zero thrust a
drop to 0 just after it, and a repeated time inside the curve becomes a ramp
``JUMP_WIDTH`` long.

Mass model: propellant burned in proportion to delivered impulse,
m_p(tau) = m_p0 (1 - I0(tau) / I_total); dry and propellant CGs fixed; the
propellant's own inertia from :mod:`ironbark_opt.motors.grains` (BATES grains
if given, else a hollow cylinder filling the case), both burning from the
inside out; everything moved to the motor's current CG by the parallel-axis
theorem.
"""
from __future__ import annotations

import hashlib
import math
from dataclasses import KW_ONLY, dataclass

import casadi as ca
import numpy as np

from ironbark_opt import _math as sm
from ironbark_opt.errors import InputError
from ironbark_opt.motors.base import Motor
from ironbark_opt.motors.grains import Grains, hollow_cylinder_inertia, thin_tube_inertia

#: Depth to which two symbolic times are compared to reuse a table look-up.
SAME_EXPRESSION_DEPTH = 8

#: Width [s] of the ramp that replaces a jump in thrust at a repeated time.
JUMP_WIDTH = 1e-6


class _BoundDataMethod:
    """``motor.thrust`` / ``motor.propellant_mass``: the symbolic-safe method of
    :class:`Motor` (call it with ``t``) that also carries the constructor's
    data (``.data``; ``np.asarray`` / ``float`` work on it)."""

    __slots__ = ("_motor", "_name", "data")

    def __init__(self, motor, name, data):
        self._motor = motor
        self._name = name
        self.data = data

    def __call__(self, t, thrust_scale=1.0, time_scale=1.0):
        return getattr(Motor, self._name)(self._motor, t, thrust_scale, time_scale)

    def __array__(self, dtype=None, copy=None):
        return np.asarray(self.data, dtype=dtype)

    def __float__(self):
        return float(self.data)

    def __repr__(self):
        return repr(self.data)


class _DataMethod:
    """Data descriptor letting a dataclass field share its name with a method.

    The ``SolidMotor`` constructor takes ``thrust`` (the curve's values) and
    ``propellant_mass`` (the initial mass), and the ``Motor`` interface has
    the methods ``thrust(t)`` and ``propellant_mass(t)``.  The field's value
    is stored under ``_<name>_data``; reading the attribute gives a callable
    that evaluates the method and carries the data, so ``dataclasses.replace``
    (which reads every field) round-trips.
    """

    def __init__(self, *, default=None, required=True):
        self._default = default
        self._required = required

    def __set_name__(self, owner, name):
        self._name = name
        self._slot = f"_{name}_data"

    def __get__(self, obj, objtype=None):
        if obj is None:
            if self._required:
                raise AttributeError(self._name)   # dataclass: field has no default
            return self._default
        return _BoundDataMethod(obj, self._name, obj.__dict__[self._slot])

    def __set__(self, obj, value):
        if isinstance(value, _BoundDataMethod):
            value = value.data
        obj.__dict__[self._slot] = value


def _positive(value, field, source, *, allow_zero=False, allow_none=False):
    if value is None and allow_none:
        return None
    try:
        x = float(value)
    except (TypeError, ValueError):
        raise InputError(f"expected a number, got {value!r}", source=source, field=field) from None
    if not math.isfinite(x) or x < 0 or (x == 0 and not allow_zero):
        raise InputError(f"expected a finite {'non-negative' if allow_zero else 'positive'} "
                         f"number, got {value!r}", source=source, field=field)
    return x


@dataclass(frozen=True, eq=False, repr=False)
class SolidMotor(Motor):
    """Solid motor: tabulated thrust curve + fixed-geometry mass model.

    Parameters
    ----------
    time : array [s]
        Times of the thrust points, non-decreasing, >= 0 (a repeated time is a
        jump in thrust).
    thrust : array [N]
        Thrust at ``time`` (>= 0).  After construction ``motor.thrust(t)`` is
        the thrust method and ``motor.thrust.data`` these values.
    propellant_mass : float [kg], optional
        Initial propellant mass; if None it is derived from ``grains``.
    dry_mass : float [kg]
        Mass of the motor without propellant (>= 0).  0 means the casing,
        closures and nozzle are counted in the rocket's own mass (as
        RocketPy's examples give some motors); the motor then adds only its
        propellant, whose CG is the motor's CG.
    diameter : float [m]
    length : float [m]
    designation, manufacturer : str
    delays : tuple of float [s]
        Ejection delays offered; ``math.inf`` = plugged (no ejection charge).
    dry_cg : float [m], optional
        Dry CG forward of the nozzle exit; default ``length / 2``.
    propellant_cg : float [m], optional
        Propellant (grains') CG forward of the nozzle exit; default ``length / 2``.
    dry_inertia : (float, float) [kg m^2], optional
        (I_transverse, I_axial) of the dry motor about ``dry_cg``; default a
        thin-walled tube of the dry mass, radius ``diameter / 2``, ``length`` long.
    grains : Grains, optional
        BATES grain geometry for the propellant inertia (and mass if
        ``propellant_mass`` is None); default a hollow cylinder filling the case
        with a bore of half the case radius.
    nozzle_exit_area : float [m^2], optional
        For :meth:`pressure_thrust_correction`.
    reference_pressure : float [Pa]
        Ambient pressure the curve was measured at.
    source : str, optional
        File the motor came from (named in error messages).

    All methods of :class:`Motor` are symbolic-safe; properties are numeric.
    """

    time: np.ndarray
    thrust: np.ndarray = _DataMethod()
    _: KW_ONLY
    propellant_mass: float | None = _DataMethod(default=None, required=False)
    dry_mass: float
    diameter: float
    length: float
    designation: str = ""
    manufacturer: str = ""
    delays: tuple = ()
    dry_cg: float | None = None
    propellant_cg: float | None = None
    dry_inertia: tuple | None = None
    grains: Grains | None = None
    nozzle_exit_area: float | None = None
    reference_pressure: float = 101325.0
    source: str | None = None

    def __post_init__(self):
        src = None if self.source is None else str(self.source)
        object.__setattr__(self, "source", src)
        t, F = self._checked_curve(src)
        t.flags.writeable = F.flags.writeable = False     # frozen like the dataclass
        object.__setattr__(self, "time", t)
        object.__setattr__(self, "_thrust_data", F)
        object.__setattr__(self, "dry_mass", _positive(self.dry_mass, "dry_mass", src, allow_zero=True))
        for name in ("diameter", "length", "reference_pressure"):
            object.__setattr__(self, name, _positive(getattr(self, name), name, src))
        for name in ("dry_cg", "propellant_cg"):
            v = getattr(self, name)
            if v is not None:
                object.__setattr__(self, name, _positive(v, name, src, allow_zero=True))
        object.__setattr__(self, "nozzle_exit_area",
                           _positive(self.nozzle_exit_area, "nozzle_exit_area", src, allow_none=True))
        if self.grains is not None and not isinstance(self.grains, Grains):
            raise InputError(f"expected a Grains object, got {type(self.grains).__name__}",
                             source=src, field="grains")
        mp = self._propellant_mass_data
        if mp is None:
            if self.grains is None:
                raise InputError("no propellant mass: give propellant_mass [kg] or grains",
                                 source=src, field="propellant_mass")
            mp = self.grains.mass
        object.__setattr__(self, "_mp0", _positive(mp, "propellant_mass", src))
        object.__setattr__(self, "_propellant_mass_data",
                           None if self._propellant_mass_data is None else self._mp0)
        try:
            delays = tuple(float(d) for d in self.delays)
        except (TypeError, ValueError):
            raise InputError(f"expected a sequence of delays in seconds, got {self.delays!r}",
                             source=src, field="delays") from None
        object.__setattr__(self, "delays", delays)
        if self.dry_inertia is None:
            di = thin_tube_inertia(self.dry_mass, self.diameter / 2.0, self.length)
        else:
            try:
                di = tuple(float(x) for x in self.dry_inertia)
            except (TypeError, ValueError):
                di = ()
            if len(di) != 2 or not all(math.isfinite(x) and x >= 0 for x in di):
                raise InputError(f"expected (I_transverse, I_axial) in kg m^2, got "
                                 f"{self.dry_inertia!r}", source=src, field="dry_inertia")
        object.__setattr__(self, "_dry_inertia", di)
        self._build_terms()

    def __getstate__(self):
        """Pickle without the cached CasADi interpolant (rebuilt on first use)."""
        state = dict(self.__dict__)
        state.pop("_interpolant", None)
        state.pop("_last_symbolic", None)
        return state

    # ---------------------------------------------------------------- checks
    def _checked_curve(self, src):
        try:
            t = np.array(self.time, dtype=float).ravel()
            F = np.array(self._thrust_data, dtype=float).ravel()
        except (TypeError, ValueError):
            raise InputError("thrust curve must be numbers", source=src, field="thrust") from None
        if t.size != F.size:
            raise InputError(f"time has {t.size} points but thrust has {F.size}",
                             source=src, field="thrust")
        if t.size < 1:
            raise InputError("thrust curve has no points", source=src, field="thrust")
        if not (np.all(np.isfinite(t)) and np.all(np.isfinite(F))):
            raise InputError("thrust curve contains NaN or infinite values", source=src, field="thrust")
        if t[0] < 0:
            raise InputError(f"time must be >= 0, got {t[0]} s", source=src, field="time")
        bad = np.nonzero(np.diff(t) < 0)[0]
        if bad.size:
            k = int(bad[0])
            raise InputError(f"time decreases at point {k + 2}: {t[k]} s then {t[k + 1]} s",
                             source=src, field="time")
        if np.any(F < 0):
            k = int(np.nonzero(F < 0)[0][0])
            raise InputError(f"negative thrust {F[k]} N at t = {t[k]} s", source=src, field="thrust")
        if t[-1] <= 0:
            raise InputError("burn time must be positive (last time > 0)", source=src, field="time")
        return t, F

    # ------------------------------------------------ curve representation
    def _build_terms(self):
        t, F = self.time, self._thrust_data
        if t[0] > 0:                       # RASP: the curve starts from (0, 0)
            t, F = np.r_[0.0, t], np.r_[0.0, F]
        # several points at t = 0: keep the last (a jump at ignition, made by
        # the [tau >= 0] factor); repeated later times: a jump, made a ramp
        # of width JUMP_WIDTH [s] (the impulse changes by < max thrust * JUMP_WIDTH)
        first = int(np.searchsorted(t, 0.0, side="right")) - 1
        t, F = t[first:].copy(), F[first:].copy()
        for k in range(1, t.size):
            if t[k] <= t[k - 1]:
                t[k] = t[k - 1] + JUMP_WIDTH
        if t.size < 2:
            raise InputError("thrust curve needs a point after t = 0", source=self.source,
                             field="time")
        # I(tau) is piecewise quadratic, but H = I - tau F / 2 is continuous and
        # piecewise linear (on a segment F = b + g tau, I = a + b tau + g tau^2 / 2,
        # so I - tau F / 2 = a + b tau / 2), so one linear interpolant of (F, H)
        # on the knots gives F and the exact I = H + tau F / 2.
        dI = np.diff(t) * (F[1:] + F[:-1]) / 2.0          # trapezoid rule, exact here
        cumI = np.r_[0.0, np.cumsum(dI)]
        H = cumI - t * F / 2.0
        object.__setattr__(self, "_knots", (t, F, H))
        object.__setattr__(self, "_burnout", float(t[-1]))
        object.__setattr__(self, "_max_thrust", float(np.max(F)))
        object.__setattr__(self, "_total_impulse", float(cumI[-1]))
        if self._total_impulse <= 0:
            raise InputError("thrust curve has zero total impulse", source=self.source, field="thrust")

    def _casadi_curve(self):
        """The linear ``casadi.interpolant`` tau -> (F, H), built on first use."""
        f = self.__dict__.get("_interpolant")
        if f is None:
            t, F, H = self._knots
            # the name is a hash of the curve: unique per motor (several motors
            # can share one generated C file) and stable across runs (JIT cache)
            digest = hashlib.sha1(np.r_[t, F].tobytes()).hexdigest()[:12]
            f = ca.interpolant(f"thrust_curve_{digest}", "linear", [t],
                               np.column_stack([F, H]).ravel())
            object.__setattr__(self, "_interpolant", f)
        return f

    def _curve(self, tau):
        """(F0(tau) [N], I0(tau) [N s]); symbolic-safe, one table look-up."""
        tb = self._burnout
        if sm.is_symbolic(tau):
            # thrust(t), mass(t), cg(t), inertia(t) called one after another on
            # the same expression share one table look-up (the SX virtual
            # machine does not merge repeated calls by itself)
            last = self.__dict__.get("_last_symbolic")
            if (last is not None and type(last[0]) is type(tau)
                    and ca.is_equal(last[0], tau, SAME_EXPRESSION_DEPTH)):
                return last[1]
            tc = sm.clip(tau, 0.0, tb)
            if tc.numel() == 1:
                fh = self._casadi_curve()(tc)
                f, h = fh[0], fh[1]
            else:                          # a vector of times: one look-up each
                fh = self._casadi_curve().map(tc.numel())(ca.reshape(tc, 1, tc.numel()))
                f = ca.reshape(fh[0, :], tc.shape)
                h = ca.reshape(fh[1, :], tc.shape)
            out = sm.fmax(f, 0.0) * (tau >= 0) * (tau <= tb), h + tc * f / 2.0
            object.__setattr__(self, "_last_symbolic", (tau, out))
            return out
        t, F, H = self._knots
        x = np.asarray(tau, dtype=float)
        tc = np.clip(x, 0.0, tb)
        f = np.interp(tc, t, F)
        i = np.interp(tc, t, H) + tc * f / 2.0
        f = np.maximum(f, 0.0) * (x >= 0) * (x <= tb)
        if not isinstance(tau, np.ndarray):
            f, i = float(f), float(i)
        return f, i

    def _thrust_unscaled(self, tau):
        """F0(tau) [N]; symbolic-safe (linear interpolation of the points)."""
        return self._curve(tau)[0]

    def _impulse_unscaled(self, tau):
        """I0(tau) [N s]; symbolic-safe (exact integral of the interpolation)."""
        return self._curve(tau)[1]

    def _thrust_and_mass_properties_unscaled(self, tau):
        f, i = self._curve(tau)
        return f, self._mass_properties_from_impulse(i)

    def _mass_properties_unscaled(self, tau):
        """(m_p [kg], cg [m], (I_t, I_a) [kg m^2]) at tau; symbolic-safe."""
        return self._mass_properties_from_impulse(self._impulse_unscaled(tau))

    def mass_driver(self, t, time_scale=1.0):
        """The delivered impulse drives the mass (see the module doc): ``d = I0(t / s)``,
        ``d_dot = F0(t / s) / s`` (I0' = F0, 0 outside the burn like F0), from the same
        table look-up as the thrust, so the mass rate needs no derivative of the table."""
        f, i = self._curve(t / time_scale)
        return i, f / time_scale, self._mass_properties_from_impulse

    def _mass_properties_from_impulse(self, impulse):
        """Mass properties once the delivered impulse [N s] is known."""
        mp0, md = self._mp0, self.dry_mass
        mp = mp0 * (1.0 - impulse / self._total_impulse)
        xd, xp = self.dry_cg_value, self.propellant_cg_value
        m = md + mp
        # Casing counted in the rocket (dry mass 0): the motor's CG is the
        # propellant's, also after burnout (no 0/0 when the propellant is gone).
        if sm.is_symbolic(md):            # a motor slot (motors/slot.py): dry mass is a symbol
            cg = sm.if_else(md == 0.0, xp + 0.0 * mp, (md * xd + mp * xp) / m)
        else:
            cg = xp + 0.0 * mp if md == 0.0 else (md * xd + mp * xp) / m
        if self.grains is not None:
            ip_t, ip_a = self.grains.inertia(mp, mp0)
        else:
            ip_t, ip_a = hollow_cylinder_inertia(mp, mp0, self.diameter / 2.0, self.length)
        id_t, id_a = self._dry_inertia
        dd, dp = xd - cg, xp - cg
        i_t = id_t + md * dd * dd + ip_t + mp * dp * dp
        return mp, cg, (i_t, id_a + ip_a)

    # ------------------------------------------------------------ properties
    @property
    def burn_time(self) -> float:
        """Time of the last thrust point [s] (unscaled), numeric."""
        return self._burnout

    @property
    def total_impulse(self) -> float:
        """Impulse of the whole curve [N s] (unscaled), numeric."""
        return self._total_impulse

    @property
    def propellant_mass_initial(self) -> float:
        """Propellant mass at ignition [kg], numeric."""
        return self._mp0

    @property
    def max_thrust(self) -> float:
        """Largest thrust point [N], numeric."""
        return self._max_thrust

    @property
    def dry_cg_value(self) -> float:
        """Dry CG forward of the nozzle exit with the default applied [m]."""
        return self.length / 2.0 if self.dry_cg is None else self.dry_cg

    @property
    def propellant_cg_value(self) -> float:
        """Propellant CG forward of the nozzle exit with the default applied [m]."""
        return self.length / 2.0 if self.propellant_cg is None else self.propellant_cg

    @property
    def dry_inertia_value(self) -> tuple[float, float]:
        """(I_transverse, I_axial) of the dry motor about its CG with the
        default applied [kg m^2]."""
        return self._dry_inertia

    @property
    def plugged(self) -> bool:
        """True if the motor has no ejection charge (delay ``P``)."""
        return any(math.isinf(d) for d in self.delays)

    def to_dict(self) -> dict:
        """Headline numbers (see :meth:`Motor.to_dict`) plus delays and source."""
        d = super().to_dict()
        d["delays_s"] = ["P" if math.isinf(x) else x for x in self.delays]
        d["source"] = self.source
        return d
