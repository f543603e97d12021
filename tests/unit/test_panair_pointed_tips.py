"""Pointed fin tips (tip chord 0) in the supersonic solver: the slivers by which a
rounded edge wraps onto the tip point are the tip's closure, treated as a tip cap
(solved, not integrated; :func:`panair.solver.supersonic._pointed_tip_closure`).

Checked: which panels are closure (only collapsed, sideways-facing fin panels,
a sliver of the fin's area; none on a trapezoidal pointed fin meshed with equal
strips, none on a fin with a tip chord), and (slow) that ICL APEX's fins, whose closure slivers
had a singular surface gradient (Cp -4e6) and sent Mach 1.5 and 2 to local
inclination, solve by linear theory at Mach 2 with a mesh-converged CN-alpha
(refine 1.0 vs 1.3 within 1 %) close to the local-inclination estimate.

Subsonic meshes (MeshOptions.fin_strips "outline", panair.mesh._span_stations) close
a pointed tip with a strip at least one fin thickness wide instead: a straight
pointed outline meshes as the trapezoid it copies, and ICL APEX's fins solve with a
bounded pressure (on 12 x 20 sine strips their 0.4-mm closing strip gave |Cp| 1.8e4,
past the subsonic solver's CP_MAX: aero build refused) and a CN-alpha converged in
the strip count."""
from pathlib import Path

import numpy as np
import pytest

from panair.mesh import BodyGeometry, FinGeometry, MeshOptions, RocketGeometry, mesh_rocket
from panair.solver import build_panels, make_solver, supersonic

APEX = Path(__file__).parents[1] / "data" / "telemetry" / "icl-apex1-pnut.ork"


def _swept_geometry(tip_chord, freeform=True):
    """A 1-m rocket with a conical nose and three swept fins (APEX-like planform; as
    a free-form outline, meshed with strips narrowing toward the tip as APEX's)."""
    x = np.linspace(0.0, 0.18, 12)
    body = BodyGeometry(np.append(x, 0.99), np.append(0.023 * x / 0.18, 0.023))
    outline = ([0.0, 1.0], [0.0, 0.0744], [0.079, tip_chord]) if freeform else None
    fins = (FinGeometry(3, 0.079, tip_chord, 0.047, 0.0744, 0.891, 0.0025, section="rounded",
                        roll=np.pi / 2, outline=outline),)
    return RocketGeometry(body, fins)


def _swept_rocket(tip_chord, freeform=True):
    opt = MeshOptions(supersonic_span_factor=2.0, supersonic_chord_factor=1.0,
                      n_theta=24, n_nose=10, body_spacing=0.8, n_chord=12, n_span=6)
    return build_panels(mesh_rocket(_swept_geometry(tip_chord, freeform), symmetric=False,
                                    options=opt.for_mach(1.2)), symmetric=False)


def _closure(panels):
    keep = panels.integrate
    lifting = ~panels.wake_at_base
    fins = np.unique(panels.network[panels.wake_upper[lifting]])
    return supersonic._pointed_tip_closure(panels, keep, fins), keep, fins


def test_closure_panels_are_the_pointed_tips_sideways_slivers():
    pointed = _swept_rocket(0.0)
    closure, keep, fins = _closure(pointed)
    assert closure.sum() > 0
    _, cen, nrm, area = pointed.geometry(1.0)
    net = pointed.network[keep]
    assert np.isin(net[closure], fins).all()
    for f in fins:                                   # near each fin's tip point, a sliver
        on = net == f
        tip_y = np.abs(pointed.corners[keep][on][..., 1:]).max()
        assert np.all(np.linalg.norm(cen[keep][closure & on][:, 1:], axis=1) > 0.9 * tip_y)
        assert area[keep][closure & on].sum() < 0.01 * area[keep][on].sum()
    clipped, _, _ = _closure(_swept_rocket(0.008))
    assert not clipped.any()                        # a tip chord: a tip cap, no closure
    equal_strips, _, _ = _closure(_swept_rocket(0.0, freeform=False))
    assert not equal_strips.any()                   # its last strip's triangles face the sides


def _apex():
    """ICL APEX's panel geometry, its symmetry, Sref [m^2] and the calibre [m]."""
    from ironbark_opt.vehicle import load_rocket_geometry
    from panair.geometry_adapter import from_rocket, is_symmetric
    rk, _ = load_rocket_geometry(APEX)
    geom = from_rocket(rk)
    return geom, is_symmetric(geom), rk.reference_area(), 2 * rk.reference_radius()


@pytest.mark.slow
def test_apex_pointed_fins_solve_linear_at_mach_2():
    from dataclasses import replace

    from panair.solver.local_inclination import LocalInclinationSolver
    geom, sym, sref, lref = _apex()
    res = {}
    for refine in (1.0, 1.3):
        opt = replace(MeshOptions(refine=refine).for_mach(1.2), tip_mach=(2.0,))
        panels = build_panels(mesh_rocket(geom, symmetric=sym, options=opt), symmetric=sym)
        a0, a4 = make_solver(panels, 2.0, sref=sref, lref=lref, mirror=True).solve(
            np.radians([0.0, 4.0]))
        res[refine] = ((a4.CN - a0.CN) / np.radians(4.0), -(a4.Cm - a0.Cm) / (a4.CN - a0.CN))
        if refine == 1.0:
            l0, l4 = LocalInclinationSolver(panels, 2.0, sref=sref, lref=lref).solve(
                np.radians([0.0, 4.0]))
            li = (l4.CN - l0.CN) / np.radians(4.0)
    (c1, x1), (c2, x2) = res[1.0], res[1.3]
    print(f"\nAPEX Mach 2: CN-alpha {c1:.3f} (refine 1.3: {c2:.3f}; local inclination {li:.3f}), "
          f"xcp {x1:.3f} / {x2:.3f} cal")
    # xcp: 0.005 cal between the meshes until session 17, 0.050 since the per-panel nose
    # blend (panair.solver.supersonic.NOSE_WEIGHT_PER_PANEL: the linear -> tangent-cone
    # transition, 0.4 < B tan delta < 0.6, falls on the nose panels the mesh has there;
    # CN-alpha 7.207 -> 6.565, xcp 12.40 -> 13.30 cal, local inclination 7.092)
    assert abs(c1 / c2 - 1) < 0.01 and abs(x1 - x2) < 0.08
    assert abs(c1 / li - 1) < 0.1


def _fin_points(geom, opt):
    return next(n for n in mesh_rocket(geom, symmetric=False, options=opt) if n.name == "fin0").points


@pytest.mark.parametrize("n_span", [6, 12, 24])
def test_subsonic_pointed_tip_strip_is_a_thickness_wide(n_span):
    """Subsonic mesh: the strip closing the pointed tip is at least one fin thickness
    wide (on sine strips 24 of them made it 0.1 mm, t = 2.5 mm), and the straight
    pointed outline is meshed exactly as the trapezoid it copies; the supersonic
    mesh keeps its sine strips (the closure slivers above)."""
    opt = MeshOptions(n_theta=24, n_nose=10, body_spacing=0.8, n_chord=12, n_span=n_span)
    free = _fin_points(_swept_geometry(0.0), opt)
    width = np.hypot(*(free[-1, 0, 1:] - free[-2, 0, 1:]).T)     # trailing-edge points, radial
    assert width >= 0.0025 * (1 - 1e-9)
    np.testing.assert_allclose(free, _fin_points(_swept_geometry(0.0, freeform=False), opt), atol=1e-12)
    sup = _fin_points(_swept_geometry(0.0), opt.for_mach(1.2))
    r = np.hypot(sup[:, 0, 1], sup[:, 0, 2]) - 0.023
    s = np.sin(0.5 * np.pi * np.linspace(0.0, 1.0, len(r)))
    np.testing.assert_allclose(r / r[-1], s, atol=1e-9)


def test_apex_pointed_fins_subsonic_pressure_bounded_and_converged():
    """ICL APEX's curved pointed fins on the default-density subsonic fin mesh of 12
    strips x 20 chordwise panels, Mach 0.05, alpha 0 / 4 / 12 deg: largest |Cp| on
    the fins under 100 (attached flow's fin-tip corners stay within tens to a few
    hundred, panair.solver.subsonic.CP_MAX; measured 1.2 / 2.7 / 6.6, the body at the
    fin roots 18.9; sine strips: 1.5e3 / 2.7e3 / 1.8e4, refused), and CN-alpha within
    1 % of 24 strips' (measured 8.342 vs 8.388 /rad, -0.55 %)."""
    geom, sym, sref, lref = _apex()
    cna = {}
    for n_span in (12, 24):
        panels = build_panels(mesh_rocket(geom, symmetric=sym, options=MeshOptions(n_span=n_span, n_chord=20)),
                              symmetric=sym)
        res = make_solver(panels, 0.05, sref=sref, lref=lref, mirror=True).solve(np.radians([0.0, 4.0, 12.0]))
        on_fins = np.isin(panels.network, [k for k, name in enumerate(panels.names) if name.startswith("fin")])
        cp_fin = [float(np.abs(r.cp[on_fins]).max()) for r in res]
        cna[n_span] = (res[1].CN - res[0].CN) / np.radians(4.0)
        print(f"\nAPEX Mach 0.05, {n_span} x 20: fin max |Cp| at 0/4/12 deg "
              f"{cp_fin[0]:.3g} / {cp_fin[1]:.3g} / {cp_fin[2]:.3g}, CN-alpha {cna[n_span]:.4f}")
        assert max(cp_fin) < 100
    assert cna[12] == pytest.approx(cna[24], rel=0.01)
