"""Local-inclination pressures: the supersonic fallback where linear theory
has no solution.

Linearised supersonic theory fails on panels steeper than the Mach cone
(a short nose's tip at Mach 2, a blunt shoulder): the influence
coefficients do not exist there.  For such a Mach number the table takes
every panel's pressure from its own inclination delta to the free stream
(sin delta = -n . V/|V|, positive facing the flow), the classical
local-inclination method (Anderson, *Hypersonic and High-Temperature Gas
Dynamics*, 2nd ed., 2006, sec. 6.2-6.4):

* body panels: the tangent cone (exact conical flow, Taylor & Maccoll 1933;
  :class:`panair.solver.nose_correction.TangentCone`),
* fin panels: the tangent wedge (the exact oblique shock, NACA Report 1135,
  1953, eqs. 128-150),
* both expand through a Prandtl-Meyer turn from the free stream when they
  face away from it (Anderson, *Modern Compressible Flow*, 3rd ed., eq. 4.44).

Body panels parallel to the axis (a cylinder's, normal with no axial
component) keep their zero-incidence pressure at every angle of attack:
applied to them the local-inclination rule gives a lift linear in alpha
along the whole cylinder (Ackeret's 2 delta / beta on each strip), where
slender-body theory has none on a constant cross-section, dN/dx = 2 q alpha
dS/dx (Munk, NACA Report 184, 1924; Nielsen, *Missile Aerodynamics*, 1960,
ch. 3); the non-linear cylinder lift is the table's viscous cross-flow term.
(APEX I at Mach 1.2: CN-alpha 70 /rad with the cylinder's strips, about six
times its subsonic value, and the centre of pressure forward of the CG.)

It has no interference (no fin-body carry-over, no upwash) and is less
accurate than linear theory where that solves; :func:`panair.sweep` uses it
only for the Mach numbers linear theory refuses and records them in the
table metadata (``mach_local_inclination``).

Numeric-only.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .nose_correction import G, TangentCone, _oblique
from .pressure import integrate_forces

__all__ = ["LocalInclinationSolver", "TangentWedge"]


class TangentWedge:
    """Surface Cp behind the weak oblique shock of a wedge vs its deflection
    (Cp at the detachment angle held beyond it); Prandtl-Meyer for negative
    deflections (shared with :class:`TangentCone`)."""

    def __init__(self, mach: float, n: int = 200):
        self.mach = float(mach)
        mu = np.arcsin(1.0 / mach)
        betas = np.linspace(mu, np.radians(89.0), n)
        pts = [(0.0, 0.0)]
        for b in betas[1:]:
            _, d, p21 = _oblique(mach, b)
            if not np.isfinite(d) or d <= pts[-1][0]:
                break                                   # past the maximum deflection (weak branch)
            pts.append((float(d), float((p21 - 1.0) / (0.5 * G * mach ** 2))))
        tab = np.array(pts)
        self.delta_max = float(tab[-1, 0])
        self._d, self._cp = tab[:, 0], tab[:, 1]
        self._expansion = TangentCone(mach, n=2)        # its Prandtl-Meyer branch

    def cp(self, delta):
        """Cp [-] at deflection ``delta`` [rad] (array)."""
        delta = np.asarray(delta, float)
        out = np.interp(np.clip(delta, 0.0, self.delta_max), self._d, self._cp)
        neg = delta < 0
        if np.any(neg):
            out[neg] = self._expansion.cp(delta[neg])
        return out


@dataclass(frozen=True)
class InclinationResult:
    """Pressure coefficients for one angle of attack (as :class:`PanelResult`)."""

    mach: float
    alpha: float
    CA: float
    CN: float
    Cm: float
    cp: np.ndarray


class LocalInclinationSolver:
    """Local-inclination pressures on a :class:`PanelSet` at one Mach number.

    Parameters
    ----------
    panels : PanelSet
    mach : float [-] (> 1)
    sref : float [m^2]; lref : float [m]; xref : float [m]
    """

    def __init__(self, panels, mach: float, *, sref: float, lref: float, xref: float = 0.0):
        self.panels, self.mach = panels, float(mach)
        #: (n,) bool: the panels whose pressure is in the forces
        self.integrated = panels.integrate
        self.sref, self.lref, self.xref = float(sref), float(lref), float(xref)
        _, self._cen, nrm, self._area = panels.geometry(1.0)
        self._nrm = nrm
        self._nrm_f = panels.force_normals(nrm)
        self._fin = panels.fin_mask()
        #: body panels parallel to the axis: no incidence pressure (see the module docstring)
        self._axial = ~self._fin & (np.abs(nrm[:, 0]) < 1e-6)
        self._cone, self._wedge = TangentCone(mach), TangentWedge(mach)

    def solve(self, alpha, beta=0.0) -> list[InclinationResult]:
        """Pressure forces at the angles ``alpha`` [rad] (zero sideslip)."""
        out = []
        sel = self.integrated
        for a in np.atleast_1d(np.asarray(alpha, float)):
            v = np.array([np.cos(a), 0.0, np.sin(a)])
            delta = np.arcsin(np.clip(-(self._nrm @ v), -1.0, 1.0))
            delta[self._axial] = 0.0
            cp = np.where(self._fin, self._wedge.cp(delta), self._cone.cp(delta))
            c = integrate_forces(cp[sel], self._cen[sel], self._nrm_f[sel], self._area[sel],
                                 sref=self.sref, lref=self.lref, xref=self.xref,
                                 symmetric=self.panels.symmetric)
            out.append(InclinationResult(self.mach, float(a), c["CA"], c["CN"], c["Cm"], cp))
        return out
