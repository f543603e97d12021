"""The cross-body Mach-cone coincidence of a supersonic body mesh: detector and a
per-Mach mesh free of it.

A constant-strength source panel's transverse (leading / trailing) edge sends a Mach
wave whose normal mass flux is singular like 1 / sqrt(s) where a receiver's upstream
Mach cone is tangent to the edge (the step in source strength at the edge).  On a
body meshed with a constant axial panel length L, a collocation point's Mach cone is
tangent to the edge of the panel diametrically opposite it when B d = (n + 1/2) L (B =
sqrt(M^2 - 1), d the transverse distance between the collocation point and the
opposite panel: r_c + r_c' the two flat-panel centroid radii, r_c = r cos(pi /
n_theta)), for every receiver of the run at once; the causal solution then amplifies
an odd-even sawtooth of source strength along the run (session 16;
tests/unit/test_panair_supersonic_coincidence.py).  Close to it the solution passes
every check but is off (TR R-100 body, 18 rows of 0.389 cal: CN(2 deg) -6 % at Mach
1.39 and 1.405, Cm -85 % at 2.015).

The measure here is the phase ``delta`` of a run: the distance, in panel lengths,
from the tangency point x_c - B d of its receivers (panel centroids) to the nearest
panel edge of the run (0: the coincidence; 0.5: the tangency at a panel's centroid,
as far from both edges as it gets).  Only runs of equal-length near-cylindrical
panels count (the nose's cosine-clustered stations and the fin roots' clustered
chordwise stations have no common phase: no sawtooth builds up there), and in a run
only the receivers whose Mach cone reaches across the body and back inside it: the
edges of two smooth rows cancel but for their step in strength, so one crossing adds
little; the alternating strength sent across and back is what grows.  The opposite
panel is on the station the Mach cone reaches (d = r_c(x_c) + r_c(x_c - B d)), so every
radius of a rocket with several tubes has its own phase.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np

__all__ = ["CoincidenceRun", "coincidence_runs", "coincidence_phase", "coincidence_free_options",
           "COINCIDENCE_BAND", "RUN_SLOPE_MAX"]

#: A near-cylindrical row: |dr/dx| at most this [-] (a boattail or transition steeper
#: than this is not a run: its centroid radius, and so B d, changes along it)
RUN_SLOPE_MAX = 0.05
#: Runs of fewer rows than this carry no sawtooth
RUN_ROWS_MIN = 3
#: A supersonic Mach number whose shared mesh has a run with phase ``delta`` below this
#: [panel lengths] is solved on its own mesh (see :func:`coincidence_free_options`):
#: B d / L within 0.25 of a half-integer.  Measured (session 17; CN, Cm at 2 deg on the
#: shared mesh against the same Mach number on a mesh of phase >= 0.4; Cm about the nose
#: tip, so 1 % of Cm is 0.01-0.02 cal of centre of pressure):
#: TR R-100 body (18 rows of 0.389 cal), n = 2 (Mach 1.33-1.46): CN -5.4 % / Cm -35 % at
#: 0.029, Cm +2.8 % at 0.085, +1.2 % at 0.116, within 0.8 % from 0.134 on (CN 0.15 %)
#: but for a dip of the shared mesh alone at Mach 1.355 (0.160: Cm -2.5 %, CN -0.3 %);
#: n = 4 (Mach 1.88-2.14): CN -12 % / Cm -86 % at 0.023, Cm -4.3 % at 0.138, -2.5 % at
#: 0.226, -2.2 % at 0.255, -1.5 % at 0.28-0.31, -0.7 % at 0.34 (CN at most 0.25 % from
#: 0.25 on); Defiance (76 rows of 0.396 cal, with fins), n = 2: CN +4.3 % / Cm +5.8 % at
#: 0.144, -0.19 % / -0.22 % at 0.181, 0.01 % from 0.218 on.  The error grows with n and
#: with the run's rows; from 0.25 on it is at most 0.25 % in CN and 2.2 % in Cm
#: (0.03 cal) in all three, the mesh-to-mesh spread of these solutions (1-2 % in Cm).
COINCIDENCE_BAND = 0.25
#: The per-Mach mesh aims at a phase at least this in every run [panel lengths]
TARGET_PHASE = 0.4


@dataclass(frozen=True)
class CoincidenceRun:
    """A run of equal-length near-cylindrical body rows: ``x0``, ``x1`` [m] its ends,
    ``length`` [m] the panel length, ``radius`` [m] the mean station radius, ``rows``,
    and ``delta`` [panel lengths] the smallest phase over its receivers whose Mach cone
    reaches across the body and back inside the run (None: none does)."""

    x0: float
    x1: float
    length: float
    radius: float
    rows: int
    delta: float | None


def _runs(xs, rs):
    """Index ranges [a, b) of maximal runs of equal-length (1e-6) near-cylindrical rows."""
    L = np.diff(xs)
    slope = np.abs(np.diff(rs)) / np.maximum(L, 1e-300)
    ok = (slope <= RUN_SLOPE_MAX) & (L > 0)
    out, a = [], 0
    n = len(L)
    while a < n:
        if not ok[a]:
            a += 1
            continue
        b = a + 1
        while b < n and ok[b] and abs(L[b] - L[a]) <= 1e-6 * L[a]:
            b += 1
        if b - a >= RUN_ROWS_MIN:
            out.append((a, b))
        a = b
    return out


def coincidence_runs(xs, rs, mach: float, n_theta: int) -> list[CoincidenceRun]:
    """The runs of a body's axial stations ``xs`` [m] (radii ``rs`` [m]) at Mach
    ``mach`` [-] on ``n_theta`` meridians, with their phases (module docstring)."""
    xs, rs = np.asarray(xs, float), np.asarray(rs, float)
    B = math.sqrt(max(mach * mach - 1.0, 0.0))
    c = math.cos(math.pi / n_theta)
    out = []
    for a, b in _runs(xs, rs):
        L = float(xs[a + 1] - xs[a])
        xc = 0.5 * (xs[a:b] + xs[a + 1:b + 1])
        rc = c * 0.5 * (rs[a:b] + rs[a + 1:b + 1])
        # the tangency point x_t = x_c - B (r_c(x_c) + r_c(x_t)): one fixed-point step
        xt = xc - 2.0 * B * rc
        xt = xc - B * (rc + c * np.interp(xt, xs, rs))
        # receivers whose tangency row is itself such a receiver: the sawtooth is sent
        # across the body and back (a single crossing multiplies the step in source
        # strength between two smooth rows, small; it amplifies an alternating one)
        inside = xc - 2.0 * (xc - xt) >= xs[a]
        delta = None
        if np.any(inside):
            phase = (xt[inside] - xs[a]) / L
            delta = float(np.min(np.abs(phase - np.round(phase))))
        out.append(CoincidenceRun(float(xs[a]), float(xs[b]), L, float(np.mean(rs[a:b + 1])),
                                  b - a, delta))
    return out


def _stations(geometry, options):
    from .mesh import _axial_stations
    xs = _axial_stations(geometry.body, geometry.fins, options)
    return xs, geometry.body.radius_at(xs)


def coincidence_phase(geometry, options, mach: float) -> float | None:
    """The smallest phase [panel lengths] over the runs of ``geometry``'s body meshed
    with ``options`` at Mach ``mach`` (None: no run the Mach cone crosses there and back)."""
    xs, rs = _stations(geometry, options)
    d = [r.delta for r in coincidence_runs(xs, rs, mach, options.scaled("n_theta"))
         if r.delta is not None]
    return min(d) if d else None


def coincidence_free_options(geometry, options, mach: float, band: float | None = None):
    """``options`` when every run of its body mesh has a phase of at least ``band``
    at Mach ``mach``; else the options with the body panel length nearest the
    original (the finer first on a tie) whose smallest phase is at least
    ``TARGET_PHASE`` or that has no run the Mach cone crosses twice (the largest
    smallest phase of the candidates when none is):
    candidates 0.70 ... 1.15 x ``body_spacing`` in steps of 0.5 %.  ``band`` [panel
    lengths]: None for :data:`COINCIDENCE_BAND`; ``math.inf`` always searches."""
    band = COINCIDENCE_BAND if band is None else band
    delta = coincidence_phase(geometry, options, mach)
    if delta is None or delta >= band:
        return options
    s0 = options.body_spacing
    factors = sorted(np.round(np.arange(0.70, 1.1501, 0.005), 6),
                     key=lambda f: (round(abs(math.log(f)), 9), f > 1))
    best, best_delta = options, delta
    for f in factors:
        opt = replace(options, body_spacing=s0 * float(f))
        d = coincidence_phase(geometry, opt, mach)
        if d is None or d >= TARGET_PHASE:      # None: no run the Mach cone crosses twice
            return opt
        if d > best_delta:
            best, best_delta = opt, d
    return best
