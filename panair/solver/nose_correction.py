"""Tangent-cone pressures for forward-facing body panels at supersonic speed.

Linearised theory over-predicts the load on a nose once B tan(delta)
approaches ~0.5 (the reference README: the Basic Finner's cone from Mach
~2.5), and the second-order pressure rule turns that into non-physical
pressures.  The tangent-cone method takes the pressure on a body panel from
the exact conical flow (Taylor-Maccoll) at the panel's local inclination to
the free stream: it is exact on a cone at zero incidence and a standard,
physical engineering model for pointed noses at incidence (e.g. Anderson,
*Hypersonic and High-Temperature Gas Dynamics*, 2nd ed., 2006, sec. 6.2 and
eq. 6.13 ff. for local-inclination methods; Taylor & Maccoll, Proc. R. Soc.
A 139, 1933).  Leeward panels (negative inclination) expand from the free
stream by a Prandtl-Meyer turn (Anderson, *Modern Compressible Flow*, 3rd
ed., 2003, eqs. 4.44 and 3.30).

Numeric-only.
"""
from __future__ import annotations

import numpy as np
from scipy.integrate import solve_ivp

__all__ = ["TangentCone"]

G = 1.4


def _oblique(mach, beta):
    """Downstream Mach, deflection and p2/p1 of an oblique shock (NACA Report
    1135, 1953, eqs. 128, 132, 138)."""
    mn2 = (mach * np.sin(beta)) ** 2
    p21 = 1 + 2 * G / (G + 1) * (mn2 - 1)
    tan_d = 2 / np.tan(beta) * (mn2 - 1) / (mach**2 * (G + np.cos(2 * beta)) + 2)
    d = np.arctan(tan_d)
    m2n2 = (1 + 0.5 * (G - 1) * mn2) / (G * mn2 - 0.5 * (G - 1))
    m2 = np.sqrt(m2n2) / np.sin(beta - d)
    return m2, d, p21


def _cone_from_shock(mach, beta):
    """Cone half-angle [rad] and surface Cp [-] behind a conical shock of
    angle ``beta`` (Taylor-Maccoll equation integrated from the shock)."""
    m2, d, p21 = _oblique(mach, beta)
    vp = (2 / ((G - 1) * m2**2) + 1) ** -0.5               # V / V_max behind the shock

    def rhs(theta, y):
        vr, vt = y
        a = 0.5 * (G - 1) * (1 - vr**2 - vt**2)
        return [vt, (vt**2 * vr - a * (2 * vr + vt / np.tan(theta))) / (a - vt**2)]

    def hit(theta, y):
        return y[1]
    hit.terminal = True
    sol = solve_ivp(rhs, (beta, 1e-4), [vp * np.cos(beta - d), -vp * np.sin(beta - d)],
                    events=hit, rtol=1e-9, atol=1e-12)
    if not sol.t_events[0].size:
        return np.nan, np.nan
    theta_c = float(sol.t_events[0][0])
    vc = float(sol.y_events[0][0][0])
    mc2 = 2 / ((G - 1) * (1 / vc**2 - 1))
    pc_p2 = ((1 + 0.5 * (G - 1) * m2**2) / (1 + 0.5 * (G - 1) * mc2)) ** (G / (G - 1))
    return theta_c, (p21 * pc_p2 - 1) / (0.5 * G * mach**2)


def _pm(m):
    """Prandtl-Meyer function [rad] (Anderson 2003, eq. 4.44)."""
    k = np.sqrt((G + 1) / (G - 1))
    return k * np.arctan(np.sqrt((m**2 - 1) / k**2)) - np.arctan(np.sqrt(m**2 - 1))


def _pm_inverse(nu, m_lo: float, m_hi: float):
    """Mach numbers [-] in [m_lo, m_hi] whose Prandtl-Meyer angle is ``nu`` [rad] (array,
    _pm(m_lo) <= nu < _pm(m_hi)): Newton's method on the monotone _pm, kept inside a
    bisection bracket, to machine precision (vectorised; the former scalar Brent
    root-finder per panel, to 2e-12, cost seconds per Mach number)."""
    nu = np.asarray(nu, float)
    lo = np.full(nu.shape, float(m_lo))
    hi = np.full(nu.shape, float(m_hi))
    m = np.minimum(2.0 * lo, 0.5 * (lo + hi))
    for _ in range(200):
        f = _pm(m) - nu
        lo = np.where(f < 0, m, lo)
        hi = np.where(f > 0, m, hi)
        # d nu / dM (Anderson 2003, eq. 4.44 differentiated)
        dfdm = np.sqrt(m * m - 1) / (m * (1 + 0.5 * (G - 1) * m * m))
        step = m - f / np.where(dfdm > 0, dfdm, 1e-300)
        nxt = np.where((step > lo) & (step < hi), step, 0.5 * (lo + hi))
        done = (np.abs(nxt - m) <= 4 * np.finfo(float).eps * m) | (f == 0)
        m = np.where(f == 0, m, nxt)
        if np.all(done):
            break
    return m


class TangentCone:
    """Surface Cp of a cone as a function of its half-angle, for one Mach number.

    Parameters
    ----------
    mach : float [-] (> 1)
    n : int
        Shock angles tabulated between the Mach angle and detachment.
    """

    def __init__(self, mach: float, n: int = 40):
        self.mach = float(mach)
        mu = np.arcsin(1 / mach)
        betas = mu + (np.linspace(0.0, 1.0, n) ** 1.5) * (np.radians(80.0) - mu)
        pts = [(0.0, 0.0)]
        for b in betas[1:]:
            th, cp = _cone_from_shock(mach, b)
            if not np.isfinite(th) or th <= pts[-1][0]:
                break                                   # past the maximum cone angle
            pts.append((th, cp))
        tab = np.array(pts)
        self.delta_max = float(tab[-1, 0])
        self._delta, self._cp = tab[:, 0], tab[:, 1]

    def cp(self, delta):
        """Cp [-] at local inclination ``delta`` [rad] (array).

        delta > 0: tangent cone (held at the detachment value beyond it);
        delta < 0: Prandtl-Meyer expansion from the free stream.
        """
        delta = np.asarray(delta, float)
        out = np.interp(np.clip(delta, 0.0, self.delta_max), self._delta, self._cp)
        neg = delta < 0
        if np.any(neg):
            nu_inf = _pm(self.mach)
            k = np.sqrt((G + 1) / (G - 1))
            nu_max = 0.5 * np.pi * (k - 1)
            nu = nu_inf - delta[neg]
            vac = nu >= nu_max * 0.999
            res = np.full(nu.shape, -2 / (G * self.mach**2))
            if np.any(~vac):
                m2 = _pm_inverse(nu[~vac], self.mach, 1e3)
                ratio = ((1 + 0.5 * (G - 1) * self.mach**2)
                         / (1 + 0.5 * (G - 1) * m2**2)) ** (G / (G - 1))
                res[~vac] = (ratio - 1) / (0.5 * G * self.mach**2)
            out[neg] = res
        return out
