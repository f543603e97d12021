"""Subsonic linearised-potential panel solver (Prandtl-Glauert).

Method: low-order Morino / Dirichlet formulation (Morino & Kuo, "Subsonic
potential aerodynamics for complex configurations: a general theory",
AIAA J. 12(2), 1974; Katz & Plotkin, *Low-Speed Aerodynamics*, 2001,
sec. 12.3): constant source and doublet on each panel, the perturbation
potential inside the body held at zero, sources sigma = -U'.n from the
free stream, Kutta condition at trailing edges (wake doublet =
mu_upper - mu_lower, K&P eq. 12.27).

Compressibility: the Prandtl-Glauert / Goethert transform x' = x / beta,
beta = sqrt(1 - M^2), with the linearised *mass-flux* boundary condition
(as PANAIR: Epton & Magnus, NASA CR-3251, sec. B.3): in the stretched
space Laplace's equation holds, the free stream becomes U' = (Ux / beta,
Uy, Uz), and the physical perturbation velocity is (phi'_x' / beta,
phi'_y, phi'_z).  The compressibility axis is the body x axis, so the
influence matrix depends on Mach only: it is built and LU-factorised once,
and each (alpha, beta) is one more right-hand side.  (PANAIR's reference
runs use ALPC = alpha, i.e. the compressibility axis along the wind; on the
ogive-cylinder the difference is ~1 % in CN.)

Base: a wake tube shed from a body-base edge is the solid continuation of
the body (sources and the body's trailing-edge doublet, see
``PanelSet.wake_at_base``), so the flow ahead of the base sees a
semi-infinite body, as a separated base flow looks to it.

Numeric-only.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
from scipy.linalg import lu_factor, lu_solve

from ironbark_opt.errors import InputError, SolverError

from .influence import influence_matrices
from .panels import MirrorFold, PanelSet, mirror_plane
from .pressure import integrate_forces, pressure_coefficient, surface_gradient

__all__ = ["SubsonicSolver", "PanelResult", "MACH_SUBSONIC_MAX"]

MACH_SUBSONIC_MAX = 0.9
"""Above this the Prandtl-Glauert model is not trusted (transonic)."""
CP_MAX = 1e4
"""Largest |Cp| [-] of an acceptable subsonic solution.  Attached potential flow over
a rocket's panels stays within tens to a few hundred even at the fin-tip corner
singularities (measured, alpha 20 deg, Mach 0.05 / 0.9: Kestrel 163 / 214, Calisto
76 / 127, GENESIS 147 / 197, NDRT 88 / 139); a singular influence matrix from
degenerate panels gave 1e13 with finite values everywhere (a CN at zero alpha, a CA
of 6e9) and must be reported, not returned."""


@dataclass(frozen=True)
class PanelResult:
    """Pressure forces on the ``surface`` networks for one flow condition.

    Coefficients are body-axis (x aft, z up): ``CA`` positive aft, ``CN``
    positive up, ``Cm`` positive nose-up about (xref, 0, 0); divided by
    q * sref (and lref for moments).  Pressure only (no friction, no base).
    """

    mach: float
    alpha: float
    beta: float
    CA: float
    CY: float
    CN: float
    Cl: float
    Cm: float
    Cn: float
    cp: np.ndarray = field(repr=False)
    mu: np.ndarray = field(repr=False)

    def coefficients(self) -> dict:
        """The six coefficients as a dict."""
        return {k: getattr(self, k) for k in ("CA", "CY", "CN", "Cl", "Cm", "Cn")}


def _refuse_sideslip(beta, mirrored: bool):
    """InputError for a sideslip angle on a solver that assumes flow symmetric in the
    x-z plane (a half model, or a full model folded on its mirror twins)."""
    if mirrored and np.any(beta != 0.0):
        raise InputError("a half model (symmetric=True) or a solver set up with mirror=True "
                         "cannot be solved in sideslip; mesh the full configuration", field="beta")


def _free_stream(alpha, beta):
    """Unit free-stream direction in body axes (x aft, z up), aeroballistic
    angles: alpha [rad] in the x-z plane, beta [rad] sideslip (wind from
    the +y side gives negative CY)."""
    return np.array([np.cos(alpha) * np.cos(beta), -np.sin(beta), np.sin(alpha) * np.cos(beta)])


class RefinedLU:
    """Solution of a dense system A x = b to double precision from a single-precision
    LU factorisation refined iteratively: LAPACK's DSGESV (Buttari, Dongarra, Langou,
    Langou, Luszczek & Kurzak, "Mixed precision iterative refinement techniques for
    the solution of dense linear systems", Int. J. High Perform. Comput. Appl. 21(4),
    2007), with its stopping test (residual <= ||x|| ||A||_inf eps sqrt(n), the
    backward error of a double-precision LU) and its fallback: when the refinement
    does not converge in ITER_MAX steps, or a single-precision pivot is below
    PIVOT_MIN x the largest (a nearly singular matrix, which single precision
    cannot judge), A is factorised in double precision as before.

    The single-precision factorisation takes half the time of the double one
    (measured, n = 4384: 1.07 / 2.19 s CPU); each refinement step is one matrix
    product with the right-hand sides.  The solution is the double-precision one
    to rounding (the tables agree with the double LU's to ~1e-13).

    A (float64, n x n) is kept (not overwritten) for the residuals.
    """

    ITER_MAX = 30
    PIVOT_MIN = 1e-4

    def __init__(self, A: np.ndarray):
        self._A = A
        self._lu64 = None
        self._lu32 = lu_factor(A.astype(np.float32), overwrite_a=True, check_finite=False)
        d = np.abs(np.diag(self._lu32[0])).astype(float)
        if not np.all(np.isfinite(d)) or d.min() < self.PIVOT_MIN * d.max():
            self._factor64()
        self._anrm = float(np.abs(A).sum(axis=1).max())

    def _factor64(self):
        self._lu64 = lu_factor(self._A, check_finite=False)
        self._lu32 = None

    def pivots(self) -> np.ndarray:
        """|diagonal of U| of the (double if computed, else single precision) LU."""
        lu = self._lu64 if self._lu64 is not None else self._lu32
        return np.abs(np.diag(lu[0])).astype(float)

    def _solve32(self, r):
        scale = np.abs(r).max(axis=0)
        scale = np.where(scale > 0, scale, 1.0)          # no underflow in single precision
        return lu_solve(self._lu32, (r / scale).astype(np.float32),
                        check_finite=False).astype(float) * scale

    def solve(self, b: np.ndarray) -> np.ndarray:
        """x with A x = b, b (n,) or (n, k)."""
        b = np.asarray(b, float)
        if self._lu32 is not None:
            x = self._solve32(b)
            tol = self._anrm * np.finfo(float).eps * math.sqrt(len(b))
            for _ in range(self.ITER_MAX):
                r = b - self._A @ x
                if np.all(np.abs(r).max(axis=0) <= tol * np.abs(x).max(axis=0)):
                    return x
                x = x + self._solve32(r)
            self._factor64()                               # did not converge
        return lu_solve(self._lu64, b, check_finite=False)


class SubsonicSolver:
    """Influence matrix for one Mach number, factorised once.

    Parameters
    ----------
    panels : PanelSet
        From :func:`panair.solver.panels.build_panels` (lengths in [m] or
        any consistent unit with ``sref``, ``lref``, ``xref``).
    mach : float [-]
        0 <= mach <= 0.9.
    sref : float [m^2]
    lref : float [m]
    xref : float [m]
        Moment reference, x aft of the nose tip.
    pressure_rule : str
        See :func:`panair.solver.pressure.pressure_coefficient`
        (default second-order, PANAIR's default).
    mirror : bool
        On a full model whose mesh is its own mirror image in a plane through the axis
        (:func:`panair.solver.panels.mirror_plane`) the system is set up and
        factorised for one panel of each mirror pair (half the influence
        coefficients; the same solution to rounding).  In the x-z plane only flows
        without sideslip will be solved (they are symmetric there: one system, an
        eighth of the LU); sideslip then raises InputError, as on a half model.  In
        another plane (3 fins rolled 90 deg) every flow has a part symmetric and a
        part antisymmetric in it: two systems of half the size (a quarter of the LU),
        :class:`panair.solver.panels.MirrorFold`.
    """

    def __init__(self, panels: PanelSet, mach: float, *, sref: float, lref: float,
                 xref: float = 0.0, pressure_rule: str = "second-order", mirror: bool = False):
        if not 0.0 <= mach <= MACH_SUBSONIC_MAX:
            raise InputError(f"subsonic solver needs 0 <= Mach <= {MACH_SUBSONIC_MAX}, got {mach} "
                             "(transonic Mach numbers are bridged, supersonic ones need the "
                             "supersonic solver)", field="mach")
        if sref <= 0 or lref <= 0:
            raise InputError("sref and lref must be positive", field="sref/lref")
        self.panels = panels
        #: (n,) bool: the panels whose pressure is in the forces
        self.integrated = panels.integrate
        self.mach = float(mach)
        self.beta_pg = np.sqrt(1.0 - mach**2)
        self.sref, self.lref, self.xref = float(sref), float(lref), float(xref)
        self.pressure_rule = pressure_rule
        pressure_coefficient(np.zeros((1, 3)), np.array([1.0, 0, 0]), mach, pressure_rule)
        stretch = 1.0 / self.beta_pg
        flat, cen, nrm, area = panels.geometry(stretch)
        self._flat_t, self._cen_t, self._nrm_t = flat, cen, nrm
        n = panels.n
        plane = mirror_plane(panels) if mirror else None
        self._fold = MirrorFold(*plane) if plane is not None else None
        rows = self._fold.reps if self._fold is not None else np.arange(n)
        D, S = influence_matrices(cen[rows], flat, nrm, self_index=rows)
        if panels.symmetric:
            image = cen * np.array([1.0, -1.0, 1.0])
            influence_matrices(image, flat, nrm, out=(D, S))
        self._Sw, self._nrm_w = None, None
        if len(panels.wake_corners):
            wflat, wcen, wnrm, _ = panels.wake_geometry(stretch)
            Dw, Sw = influence_matrices(cen[rows], wflat, wnrm)
            if panels.symmetric:
                influence_matrices(cen * np.array([1.0, -1.0, 1.0]), wflat, wnrm, out=(Dw, Sw))
            low = panels.wake_lower >= 0
            np.add.at(D.T, panels.wake_upper, Dw.T)
            np.add.at(D.T, panels.wake_lower[low], -Dw.T[low])
            base = panels.wake_at_base
            if np.any(base):
                # base wake tubes carry sources too (solid continuation of the body);
                # kept beside S (one matrix product more per solve, no copy of S)
                self._Sw, self._nrm_w = Sw[:, base], wnrm[base]
        self._S = S
        if not np.all(np.isfinite(D)) or not np.all(np.isfinite(S)) or (
                self._Sw is not None and not np.all(np.isfinite(self._Sw))):
            raise SolverError(f"Mach {mach}: non-finite influence coefficients "
                              "(coincident or degenerate panels in the mesh)")
        self._lu = RefinedLU(D if self._fold is None else self._fold.fold(D))
        # a mirror plane other than x-z: the antisymmetric part's system as well
        self._lu_odd = (RefinedLU(self._fold.fold_odd(D))
                        if self._fold is not None and self._fold.odd else None)
        for lu in (self._lu, self._lu_odd):
            diag = lu.pivots() if lu is not None else np.ones(1)
            if diag.min() < 1e-10 * diag.max():
                raise SolverError(f"Mach {mach}: singular influence matrix "
                                  "(duplicated panels or wrongly oriented networks)")
        _, self._cen, self._nrm, self._area = panels.geometry(1.0)
        self._nrm_f = panels.force_normals(self._nrm)      # normals for the force integration

    def _rhs(self, vt, sigma=None):
        """Right-hand sides (rows of the system) of stretched free streams ``vt`` (k, 3):
        minus the sources' potential, sigma = -U'.n on the panels (``sigma`` if given)
        and base wakes."""
        rhs = -(self._S @ (-(self._nrm_t @ vt.T) if sigma is None else sigma))
        if self._Sw is not None:
            rhs -= self._Sw @ -(self._nrm_w @ vt.T)
        return rhs

    def solve(self, alpha, beta=0.0) -> list[PanelResult]:
        """Solve for one or more flow angles.

        Parameters
        ----------
        alpha : float or array [rad]
            Angle(s) of attack.
        beta : float or array [rad]
            Sideslip angle(s) (broadcast with alpha); must be 0 on a half
            model.

        Returns
        -------
        list of PanelResult, one per angle pair.
        """
        alpha, beta = np.broadcast_arrays(np.atleast_1d(np.asarray(alpha, float)),
                                          np.atleast_1d(np.asarray(beta, float)))
        fold = self._fold
        _refuse_sideslip(beta, self.panels.symmetric or (fold is not None and not fold.odd))
        v = np.array([_free_stream(a, b) for a, b in zip(alpha, beta)])     # (k, 3)
        stretch = np.array([self.beta_pg, 1.0, 1.0])
        vt = v / stretch                                                      # stretched free stream
        sigma = -(self._nrm_t @ vt.T)                                         # (n, k)
        if fold is not None and fold.odd:
            # mu is linear in the free stream: solved for three unit streams, the x axis
            # and the plane's cross direction (symmetric in the mirror plane) and its
            # normal (antisymmetric), and combined for every angle
            basis = fold.basis()                                              # (3, 3)
            mu_even = self._lu.solve(self._rhs(basis[:2] / stretch))
            mu_odd = self._lu_odd.solve(self._rhs(basis[2:] / stretch)[fold.paired])
            w = basis @ v.T                                                   # (3, k)
            mu = fold.expand(mu_even @ w[:2]) + fold.expand_odd(mu_odd @ w[2:])
        else:
            mu = self._lu.solve(self._rhs(vt, sigma))
            if fold is not None:
                mu = fold.expand(mu)
        out = []
        for k in range(len(alpha)):
            g = surface_gradient(mu[:, k], self._cen_t, self._nrm_t, self.panels.neighbours,
                                 self._flat_t, self.panels.integrate)
            grad = g + sigma[:, k, None] * self._nrm_t
            u = grad / np.array([self.beta_pg, 1.0, 1.0])
            cp = pressure_coefficient(u, v[k], self.mach, self.pressure_rule)
            if not np.all(np.isfinite(cp)):
                raise SolverError(f"Mach {self.mach}, alpha {np.degrees(alpha[k]):.2f} deg: "
                                  "non-finite surface pressure")
            cp_abs = float(np.max(np.abs(cp)))
            if cp_abs > CP_MAX:
                raise SolverError(f"Mach {self.mach}, alpha {np.degrees(alpha[k]):.2f} deg: "
                                  f"singular surface pressure (|Cp| up to {cp_abs:.3g} > "
                                  f"{CP_MAX:g}): degenerate panels (a body or fin of almost zero "
                                  "size somewhere) make the panel equations singular")
            sel = self.integrated
            c = integrate_forces(cp[sel], self._cen[sel], self._nrm_f[sel], self._area[sel],
                                 sref=self.sref, lref=self.lref, xref=self.xref,
                                 symmetric=self.panels.symmetric)
            out.append(PanelResult(self.mach, float(alpha[k]), float(beta[k]), cp=cp,
                                   mu=mu[:, k], **c))
        return out
