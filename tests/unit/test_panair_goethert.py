"""The subsonic solver's compressibility transform against the Goethert rule.

With the linearised mass-flux boundary condition (Epton & Magnus, NASA CR-3251,
sec. B.3) the Prandtl-Glauert equation at Mach M on a configuration is, exactly,
Laplace's equation on the configuration stretched in x by 1/beta (beta =
sqrt(1 - M^2)) with the free stream U' = (cos a / beta, 0, sin a): an
incompressible flow at tan a' = beta tan a (Goethert's rule; e.g. Ashley &
Landahl, *Aerodynamics of Wings and Bodies*, 1965, sec. 6.1; Katz & Plotkin 2001,
sec. 13.7).  With the linear pressure rule Cp = -2 u.e (e the free-stream
direction), the physical perturbation velocity (phi'_x' / beta, phi'_y, phi'_z) =
lambda (u0_x / beta, u0_y, u0_z), lambda = cos a / (beta cos a'), of the
incompressible solution u0 on the stretched panels gives, on every panel and
exactly,

    Cp(M, a) = Cp_0(stretched, a') cos^2 a / (beta^2 cos^2 a'),

and with the panels' x-y projections shrunk by beta and their y-z projections
unchanged, CN(M, a) = CN_0(stretched, a') s / beta and CA(M, a) = CA_0 s / beta^2
(s = cos^2 a / cos^2 a'): to first order CN-alpha at Mach M is the incompressible
CN-alpha of the stretched configuration.

So a solve at Mach 0.9 on the physical panels and a solve at Mach 0 on the same
panels stretched by 1/beta (the same linear system up to the right-hand side's
scale) must agree to rounding and O(a^2): a check that the solver stretches the
geometry, scales the free stream and maps velocities and coefficients back
consistently (issue 13, session 14: the Allen fins 1 and 5 are 20-35 % above the
tunnel at Mach 0.6-0.9; the transform is not the cause).  Configuration: a
tangent-ogive cylinder with two fins in the lifting plane, the layout of Allen's
fin 1 (NASA/TM-2001-210652 via MAPLEAF, tests/data/aero/allen/fin01), coarse mesh.
"""
from dataclasses import replace

import numpy as np
import pytest

from panair.mesh import BodyGeometry, FinGeometry, MeshOptions, RocketGeometry, mesh_rocket
from panair.solver import build_panels, make_solver

OPT = MeshOptions(n_theta=16, n_nose=8, body_spacing=0.8, n_chord=10, n_span=4)


def _ogive_cylinder_with_fins():
    """Allen's body in calibers (3-cal tangent ogive, 12 cal long) and fin 1 (delta,
    root chord 1, span 0.5, root leading edge at 8.4 cal, thickness 0.034)."""
    rho = 9.25                                      # ogive radius [cal]
    x = np.linspace(0.0, 3.0, 13)
    r = np.sqrt(rho**2 - (3.0 - x) ** 2) + 0.5 - rho
    body = BodyGeometry(np.append(x, 12.0), np.append(np.maximum(r, 0.0), 0.5))
    fins = (FinGeometry(2, 1.0, 0.0, 0.5, 1.0, 8.4, 0.034, roll=np.pi / 2, section="rounded"),)
    return build_panels(mesh_rocket(RocketGeometry(body, fins), options=OPT))


def _stretched(panels, k):
    c, w = panels.corners.copy(), panels.wake_corners.copy()
    c[..., 0] *= k
    w[..., 0] *= k
    return replace(panels, corners=c, wake_corners=w)


@pytest.mark.parametrize("mach", [0.6, 0.9])
def test_prandtl_glauert_solve_is_the_incompressible_solve_of_the_stretched_body(mach):
    panels = _ogive_cylinder_with_fins()
    beta = np.sqrt(1.0 - mach**2)
    alpha = np.radians([0.0, 4.0])
    alpha0 = np.arctan(beta * np.tan(alpha))
    kw = dict(sref=np.pi / 4, lref=1.0, xref=0.0, pressure_rule="linear")
    comp = make_solver(panels, mach, **kw).solve(alpha)
    inc = make_solver(_stretched(panels, 1.0 / beta), 0.0, **kw).solve(alpha0)
    for c, i, a, a0 in zip(comp, inc, alpha, alpha0):
        s = np.cos(a) ** 2 / np.cos(a0) ** 2
        scale = np.abs(c.cp).max()
        np.testing.assert_allclose(c.cp, i.cp * s / beta**2, rtol=0, atol=1e-9 * scale)
        assert c.CN == pytest.approx(i.CN * s / beta, rel=1e-9, abs=1e-12)
        assert c.CA == pytest.approx(i.CA * s / beta**2, rel=1e-9, abs=1e-12)
    cna = (comp[1].CN - comp[0].CN) / alpha[1]
    assert cna > 4.0                                  # the fins lift (nose alone: 2)
    # the same to first order in alpha (s and a'/(beta a) differ from 1 by O(a^2): 0.3 %)
    assert cna == pytest.approx((inc[1].CN - inc[0].CN) / alpha0[1], rel=1e-2)
