"""``FlightLog``: one altimeter / flight-computer log in SI units.

Readers (one module per device family) hand raw columns to
:func:`build_log`, which sorts the rows, drops duplicated samples (two radio
links), measures time from launch detection, marks radio gaps and detects
the events (liftoff, burnout, apogee, deployments).  Numeric-only.

Event detection (documented rules, no tuning to a file):

- **apogee**: the highest altitude sample of the flight (the device's own
  reported value is kept separately in ``device_apogee_agl``);
- **liftoff** (used to align a simulation, whose t = 0 is ignition at
  rest): boost starts with nearly constant acceleration, so
  ``h = a/2 (t - t0)^2`` and ``sqrt(h)`` is linear in ``t``; a least-squares
  line through ``sqrt(h)`` for the samples between 3 and 15 % of apogee
  (and above 5 m) gives ``t0`` as its zero crossing;
- **burnout**: the device's event when it logs one, else the first time
  after liftoff the logged acceleration turns negative, else the time of the
  largest vertical speed (logged, or from a 5-point central difference of
  altitude smoothed over 0.25 s);
- **deployments**: the device's events (pyro / state changes) when logged.

Channel noise (for weighting a fit): the robust standard deviation of the
channel's second differences, ``sigma = 1.4826 MAD(d2) / sqrt(6)`` (white
noise of variance s^2 gives second differences of variance 6 s^2), taken
over the ascent, floored at the quantisation ``resolution / sqrt(12)``.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Mapping

import numpy as np

from ironbark_opt.errors import InputError

CHANNELS = ("altitude", "vertical_speed", "acceleration")
_UNITS = {"altitude": "m", "vertical_speed": "mps", "acceleration": "mps2"}


def _frozen(a):
    if a is None:
        return None
    a = np.array(a, dtype=float)
    a.setflags(write=False)
    return a


@dataclass(frozen=True)
class FlightLog:
    """A flight log in SI units, time measured from the device's launch detection.

    Attributes
    ----------
    source : str
        File it was read from.
    format : str
        Reader that read it (``altos``, ``perfectflite``, ...).
    device : str
        Device as the file names it (model, serial, flight).
    time : array [s]
        From launch detection (negative on the pad).
    altitude_agl : array [m]
        Altitude above the launch site (barometric unless stated).
    vertical_speed : array [m/s] or None
        Where the device logs one (its estimate; noisy for baro-only devices).
    acceleration : array [m/s^2] or None
        Axial acceleration where logged (accelerometer minus its pad reading).
    events : mapping name -> time [s]
        ``liftoff``, ``burnout``, ``apogee`` and the deployments found.
    resolution : mapping channel -> float
        Quantisation step of each channel [its SI unit].
    ground_elevation : float [m ASL] or None
    device_apogee_agl : float [m] or None
        Apogee as the device reports it (header / event), when it does.
    gaps : tuple of (start, end) [s]
        Intervals with no samples longer than 5 median sample periods.
    notes : tuple of str
        What the reader did (scaled columns, dropped duplicates, ...).
    """

    source: str
    format: str
    device: str
    time: np.ndarray = field(repr=False)
    altitude_agl: np.ndarray = field(repr=False)
    vertical_speed: np.ndarray | None = field(repr=False)
    acceleration: np.ndarray | None = field(repr=False)
    events: Mapping[str, float]
    resolution: Mapping[str, float]
    ground_elevation: float | None = None
    device_apogee_agl: float | None = None
    gaps: tuple = ()
    notes: tuple = ()

    def __repr__(self) -> str:
        return (f"FlightLog({self.format}: {self.device!r}, {self.time.size} samples, apogee "
                f"{self.apogee_agl:.1f} m AGL at {self.apogee_time:.2f} s)")

    @property
    def apogee_agl(self) -> float:
        """Highest logged altitude [m AGL]."""
        return float(self.altitude_agl[int(np.argmax(self.altitude_agl))])

    @property
    def apogee_time(self) -> float:
        """Time of the highest logged altitude [s]."""
        return float(self.time[int(np.argmax(self.altitude_agl))])

    def channels(self) -> tuple[str, ...]:
        """Names of the channels this log has (of ``CHANNELS``)."""
        return tuple(c for c in CHANNELS if self.channel(c) is not None)

    def channel(self, name: str) -> np.ndarray | None:
        """Samples of channel ``name`` (``altitude``, ``vertical_speed``, ``acceleration``)."""
        if name not in CHANNELS:
            raise InputError(f"unknown channel '{name}'; channels: {', '.join(CHANNELS)}", field="channel")
        return {"altitude": self.altitude_agl, "vertical_speed": self.vertical_speed,
                "acceleration": self.acceleration}[name]

    def noise(self, name: str, t_max: float | None = None) -> float:
        """Noise standard deviation of channel ``name`` [SI] (see the module docstring)."""
        y = self.channel(name)
        if y is None:
            raise InputError(f"the log has no {name} channel", source=self.source, field=name)
        t_end = self.apogee_time if t_max is None else t_max
        m = (self.time >= 0) & (self.time <= t_end)
        d2 = np.diff(y[m], 2)
        sigma = 1.4826 * float(np.median(np.abs(d2 - np.median(d2)))) / math.sqrt(6.0) if d2.size else 0.0
        return max(sigma, self.resolution.get(name, 0.0) / math.sqrt(12.0), 1e-6)

    def to_dataframe(self):
        """Samples as a DataFrame with unit-suffixed columns (a copy)."""
        data = {"time_s": self.time, "altitude_agl_m": self.altitude_agl}
        if self.vertical_speed is not None:
            data["vertical_speed_mps"] = self.vertical_speed
        if self.acceleration is not None:
            data["acceleration_mps2"] = self.acceleration
        import pandas as pd                # only here: simulate's start-up stays lean
        return pd.DataFrame(data)

    def to_dict(self) -> dict:
        """Summary with unit-suffixed keys."""
        out = {"source": self.source, "format": self.format, "device": self.device,
               "samples": int(self.time.size), "duration_s": float(self.time[-1] - self.time[0]),
               "apogee_agl_m": self.apogee_agl, "apogee_time_s": self.apogee_time,
               "device_apogee_agl_m": self.device_apogee_agl, "ground_elevation_m": self.ground_elevation,
               "channels": list(self.channels()),
               "events_s": {k: float(v) for k, v in self.events.items()},
               "gaps_s": [[float(a), float(b)] for a, b in self.gaps], "notes": list(self.notes)}
        for c in self.channels():
            out[f"noise_{c}_{_UNITS[c]}"] = self.noise(c)
        return out

    def summary(self) -> str:
        """Human-readable summary (a string; nothing is printed)."""
        lines = [f"Flight log {self.source}", f"  format             {self.format} ({self.device})",
                 f"  samples            {self.time.size} over {self.time[0]:.2f} .. {self.time[-1]:.2f} s",
                 f"  apogee             {self.apogee_agl:10.1f} m AGL ({self.apogee_agl / 0.3048:.0f} ft) "
                 f"at {self.apogee_time:.2f} s"]
        if self.device_apogee_agl is not None:
            lines.append(f"  device apogee      {self.device_apogee_agl:10.1f} m AGL "
                         f"({self.device_apogee_agl / 0.3048:.0f} ft)")
        for name, t in sorted(self.events.items(), key=lambda kv: kv[1]):
            lines.append(f"  {name:<18} {t:10.2f} s")
        lines.append(f"  channels           {', '.join(self.channels())}")
        if self.gaps:
            lines.append(f"  gaps               {len(self.gaps)} (longest {max(b - a for a, b in self.gaps):.2f} s)")
        for note in self.notes:
            lines.append(f"  note: {note}")
        return "\n".join(lines)


#: A log whose highest sample is its last is taken to end at apogee when its own vertical
#: speed channel reads at most this there [m/s] (a simulation exported to apogee, e.g.
#: ``ironbark simulate --csv F --csv-format openrocket`` without ``--descent``: 1 m/s is
#: v^2 / 2g = 5 cm of climb left); without that channel it is refused as truncated
APOGEE_END_SPEED = 1.0


def detect_liftoff(t: np.ndarray, h: np.ndarray) -> float | None:
    """Liftoff time [s] from the early boost: zero of the line through sqrt(h)."""
    i_apo = int(np.argmax(h))
    apo = h[i_apo]
    if apo <= 20.0:
        return None
    up = np.arange(i_apo + 1)
    first = up[h[up] > 0.15 * apo]
    if first.size == 0:
        return None
    sel = up[: first[0]]
    sel = sel[(h[sel] > max(5.0, 0.03 * apo)) & (t[sel] >= t[0])]
    if sel.size < 3:
        return None
    A = np.column_stack([t[sel], np.ones(sel.size)])
    (slope, icpt), *_ = np.linalg.lstsq(A, np.sqrt(h[sel]), rcond=None)
    return float(-icpt / slope) if slope > 0 else None


def _smooth_speed(t, h):
    dt = float(np.median(np.diff(t)))
    w = max(1, int(round(0.25 / dt)))
    hs = np.convolve(h, np.ones(w) / w, mode="same") if w > 1 else h
    return np.gradient(hs, t)


def build_log(source: str, fmt: str, device: str, t, h, *, v=None, a=None, events=None, resolution=None,
              ground_elevation=None, device_apogee=None, notes=(), line_numbers=None) -> FlightLog:
    """Assemble a :class:`FlightLog` from raw SI columns (sorted, deduplicated, events).

    Parameters
    ----------
    t : array [s] from launch detection; h : array [m AGL]; v : [m/s]; a : [m/s^2]
    events : mapping name -> time [s] from the device (deployments, burnout)
    """
    t = np.asarray(t, dtype=float)
    h = np.asarray(h, dtype=float)
    notes = list(notes)
    if t.size < 10:
        raise InputError(f"only {t.size} samples: too short for a flight log", source=source)
    cols = [c for c in (h, v, a) if c is not None]
    bad = ~np.isfinite(t)
    for c in cols:
        bad |= ~np.isfinite(np.asarray(c, dtype=float))
    if bad.all():
        raise InputError("no sample has finite time and altitude", source=source)
    order = np.argsort(t, kind="stable")
    if np.any(np.diff(t[~bad]) < 0):
        notes.append("rows were out of time order; sorted numerically")
    keep = order[~bad[order]]
    ts = t[keep]
    dup = np.concatenate([[False], np.diff(ts) <= 0])
    if dup.any():
        notes.append(f"{int(dup.sum())} samples with a repeated time dropped (first one kept)")
    keep = keep[~dup]
    t, h = t[keep], h[keep]
    v = None if v is None else np.asarray(v, dtype=float)[keep]
    a = None if a is None else np.asarray(a, dtype=float)[keep]
    dts = np.diff(t)
    med = float(np.median(dts))
    gaps = tuple((float(t[i]), float(t[i + 1])) for i in np.nonzero(dts > max(5 * med, 0.5))[0])
    i_apo = int(np.argmax(h))
    if not h[i_apo] - h[0] > 1.0:        # [m] a flight climbs; noise on the pad does not
        raise InputError(f"the altitude never rises more than 1 m above its first sample "
                         f"(max {h[i_apo]:.2f} m): no liftoff in this log", source=source, field="altitude")
    if i_apo == t.size - 1 and not (v is not None and np.isfinite(v[-1])
                                    and abs(float(v[-1])) <= APOGEE_END_SPEED):
        raise InputError("the log ends while the rocket is still climbing (truncated log?)", source=source,
                         line=None if line_numbers is None else int(np.max(line_numbers)))
    ev = {k: float(val) for k, val in (events or {}).items() if val is not None}
    ev["apogee"] = float(t[i_apo])
    t0 = detect_liftoff(t, h)
    if t0 is not None:
        ev["liftoff"] = t0
    if "burnout" not in ev:
        t_lo = ev.get("liftoff", 0.0)
        up = (t > t_lo) & (t < t[i_apo])
        if a is not None and np.any(up & (a < 0)):
            ev["burnout"] = float(t[np.nonzero(up & (a < 0))[0][0]])
        else:
            vs = v if v is not None else _smooth_speed(t, h)
            if np.any(up):
                idx = np.nonzero(up)[0]
                ev["burnout"] = float(t[idx[int(np.argmax(vs[idx]))]])
    res = {"altitude": 0.0, "vertical_speed": 0.0, "acceleration": 0.0}
    res.update(resolution or {})
    return FlightLog(source=str(source), format=fmt, device=device, time=_frozen(t), altitude_agl=_frozen(h),
                     vertical_speed=_frozen(v), acceleration=_frozen(a), events=dict(ev), resolution=res,
                     ground_elevation=ground_elevation, device_apogee_agl=device_apogee, gaps=gaps,
                     notes=tuple(notes))


def transitions(t: np.ndarray, flag: np.ndarray) -> float | None:
    """Time [s] of the first sample where ``flag`` becomes true after being false."""
    f = np.asarray(flag, dtype=bool)
    rise = np.nonzero(f[1:] & ~f[:-1])[0]
    return float(t[rise[0] + 1]) if rise.size else None
