"""Mesher: network layout, orientation, enclosed volume, fin sections,
half-model rules; VTK and picture export."""
import numpy as np
import pytest

from ironbark_opt.errors import InputError
from panair.lawgs import read_lawgs, write_lawgs
from panair.mesh import BodyGeometry, FinGeometry, MeshOptions, RocketGeometry, mesh_rocket
from panair.solver import build_panels
from panair.solver.influence import planar_corners
from panair.vtk import write_vtk


def _rocket(section="double_wedge", roll=np.pi / 4, **kw):
    body = BodyGeometry(np.array([0.0, 2.84, 10.0]), np.array([0.0, 0.5, 0.5]))
    fins = (FinGeometry(4, 1.0, 1.0, 1.0, 0.0, 9.0, 0.08, roll=roll, section=section, **kw),)
    return RocketGeometry(body, fins)


def _volume(panels):
    """Divergence theorem, F = (0, y, z)/2 (bases and y = 0 caps add nothing)."""
    _, c, n, a = planar_corners(panels.corners)
    return 0.5 * np.sum((c[:, 1] * n[:, 1] + c[:, 2] * n[:, 2]) * a)


def test_body_only_volume_and_layout():
    body = BodyGeometry(np.array([0.0, 3.0, 10.0]), np.array([0.0, 0.5, 0.5]))
    nets = mesh_rocket(RocketGeometry(body), options=MeshOptions(n_theta=64))
    assert [n.name for n in nets] == ["body", "base", "basewake"]
    panels = build_panels([n for n in nets if n.kind != "wake"])
    exact = np.pi * 0.25 * (3.0 / 3 + 7.0)           # cone + cylinder
    # inscribed 64-gon: area factor sin(2pi/64)/(2pi/64)
    poly = exact * np.sin(2 * np.pi / 64) / (2 * np.pi / 64)
    print(f"volume {_volume(panels):.5f}, polygon {poly:.5f}, exact {exact:.5f}")
    assert _volume(panels) == pytest.approx(poly, rel=2e-3)


def test_half_model_fins_and_orientation():
    nets = mesh_rocket(_rocket(), symmetric=True)
    names = [n.name for n in nets]
    assert names.count("fin0") == 1 and "fin1" in names and "fin2" not in names
    panels = build_panels(nets, symmetric=True)        # checks orientation
    assert len(panels.wake_corners) > 0 and np.all(panels.wake_upper >= 0)
    full = build_panels(mesh_rocket(_rocket()), symmetric=False)
    assert full.n == pytest.approx(2 * panels.n, rel=0.02)
    # fin normals: outward from the fin mid-plane
    fin = next(n for n in nets if n.name == "fin0")
    _, c, nrm, _ = planar_corners(np.stack([fin.points[:-1, :-1], fin.points[:-1, 1:],
                                            fin.points[1:, 1:], fin.points[1:, :-1]],
                                           axis=2).reshape(-1, 4, 3))
    e_t = np.array([0.0, np.cos(np.pi / 4), -np.sin(np.pi / 4)])
    side = (c - np.array([0, 0, 0])) @ e_t
    assert np.all(np.sign(nrm @ e_t)[np.abs(side) > 1e-6] == np.sign(side[np.abs(side) > 1e-6]))


def test_fin_in_symmetry_plane_is_refused():
    with pytest.raises(InputError, match="symmetry plane"):
        mesh_rocket(_rocket(roll=0.0), symmetric=True)
    mesh_rocket(_rocket(roll=0.0), symmetric=False)    # fine as a full model


@pytest.mark.parametrize("section,area", [
    ("double_wedge", 0.5 * 1.0 * 0.08),                 # diamond
    # square and rounded: LE rounded with radius t/2 (two quarter circles), TE closed over t
    ("square", 1.0 * 0.08 - 0.5 * 0.08 * 0.08 - (1 - np.pi / 4) * 0.08 * 0.08 / 2),
    ("rounded", 1.0 * 0.08 - 0.5 * 0.08 * 0.08 - (1 - np.pi / 4) * 0.08 * 0.08 / 2),
])
def test_fin_section_area(section, area):
    f = _rocket(section).fins[0]
    xi = np.linspace(0, 1, 20001)
    a = np.trapezoid(2 * f.half_thickness(xi, 1.0), xi)
    assert a == pytest.approx(area, rel=1e-3)


def test_hexagonal_section():
    f = _rocket("double_wedge", le_bevel=0.2, te_bevel=0.1).fins[0]
    h = f.half_thickness(np.array([0.0, 0.1, 0.2, 0.5, 0.9, 0.95, 1.0]), 1.0)
    np.testing.assert_allclose(h, [0, 0.02, 0.04, 0.04, 0.04, 0.02, 0.0], atol=1e-12)


def test_mesh_lawgs_round_trip_and_vtk(tmp_path):
    nets = mesh_rocket(_rocket(), symmetric=True)
    write_lawgs(tmp_path / "bf.wgs", nets, title="basic finner")
    _, back = read_lawgs(tmp_path / "bf.wgs")
    assert [n.shape for n in back] == [n.shape for n in nets]
    panels = build_panels(nets, symmetric=True)
    out = write_vtk(tmp_path / "bf.vtk", panels.corners, cp=np.zeros(panels.n),
                    network=panels.network)
    text = out.read_text().splitlines()
    assert text[0].startswith("# vtk DataFile") and f"CELLS {panels.n} {5 * panels.n}" in text
    with pytest.raises(InputError, match="cp has"):
        write_vtk(tmp_path / "x.vtk", panels.corners, cp=np.zeros(3))


def test_plots(tmp_path):
    import matplotlib
    matplotlib.use("Agg")
    from panair.plots import plot_cp, plot_mesh
    nets = mesh_rocket(_rocket(), symmetric=True, options=MeshOptions(n_chord=4, n_span=2))
    panels = build_panels(nets, symmetric=True)
    fig = plot_mesh(panels.corners, wake_corners=panels.wake_corners, filename=tmp_path / "m.png")
    fig2 = plot_cp(panels.corners, panels.corners[:, 0, 0], filename=tmp_path / "cp.png")
    assert (tmp_path / "m.png").stat().st_size > 1000 and (tmp_path / "cp.png").exists()
    assert fig is not fig2


@pytest.mark.parametrize("section, kw, expect", [
    ("square", {}, "last thickness"), ("rounded", {}, "last thickness"),
    ("double_wedge", {"le_bevel": 0.2, "te_bevel": 0.0}, "last thickness"),
    ("double_wedge", {}, "none"), ("airfoil", {}, "none")])
def test_blunt_trailing_edge_closure_carries_no_force(section, kw, expect):
    """The wedge closing a blunt trailing edge (chord stations centred in the
    last thickness of chord; an LE-only bevel's square trailing edge too, since
    session 19: before, a step over the last panel) is no-force; sharp trailing
    edges have none."""
    opt = MeshOptions(n_theta=16, n_nose=6, body_spacing=1.0, n_chord=20, n_span=3)
    nets = mesh_rocket(_rocket(section, **kw), symmetric=True, options=opt)
    fin = next(n for n in nets if n.name == "fin0")
    mask = fin.meta.get("separated", np.zeros((3, 40), bool))
    assert mask.shape == (3, 40)
    pts = fin.points
    xc = 0.25 * (pts[:-1, :-1, 0] + pts[1:, :-1, 0] + pts[:-1, 1:, 0] + pts[1:, 1:, 0])
    if expect == "none":
        assert not mask.any()
        return
    if expect == "last thickness":     # t = 0.08 of chord 1 before the trailing edge at x = 10
        np.testing.assert_array_equal(mask, xc > 10.0 - 0.08)
    panels = build_panels(nets, symmetric=True)
    assert (~panels.integrate[panels.network == 3]).sum() == mask.sum()


def test_elliptical_and_freeform_fins_are_meshed():
    """Fins meshed from their outline: the meshed elliptical fin's planform (its
    leading- and trailing-edge points in the fin plane) has the half ellipse's
    area pi c_r s / 4 (within 1 %: polygonal strips); a free-form copy of a
    trapezoid meshes as the trapezoid (subsonic strips share the outline's length:
    on straight edges the trapezoid's equal strips; CN-alpha at Mach 0.5 equal to
    1e-6; on the former sine strips within 2 %)."""
    from ironbark_opt.rocket import (BodyTube, EllipticalFins, FreeformFins, NoseCone, Rocket,
                                     TrapezoidalFins)
    from ironbark_opt.rocket.fin_sections import FinSection
    from panair.geometry_adapter import from_rocket
    from panair.solver import make_solver
    sec = FinSection(kind="double_wedge")
    body = [NoseCone(shape="tangent_ogive", length=0.3, radius=0.05),
            BodyTube(x=0.3, length=1.0, radius=0.05)]
    opt = MeshOptions(n_theta=32, n_nose=8, body_spacing=1.0, n_chord=12, n_span=8)

    ell = EllipticalFins(count=4, x=1.1, thickness=0.004, root_chord=0.16, span=0.1, section=sec)
    nets = mesh_rocket(from_rocket(Rocket("t", body + [ell])), symmetric=True, options=opt)
    fin = next(n for n in nets if n.name == "fin0").points
    n_c = (fin.shape[1] - 1) // 2
    le, te = fin[:, n_c], 0.5 * (fin[:, 0] + fin[:, -1])
    rad = lambda q: np.hypot(q[:, 1], q[:, 2]) - 0.05                    # noqa: E731
    poly = np.vstack([np.column_stack([le[:, 0], rad(le)]),
                      np.column_stack([te[::-1, 0], rad(te[::-1])])])
    x, y = poly[:, 0], poly[:, 1]
    area = 0.5 * abs(np.dot(x, np.roll(y, -1)) - np.dot(y, np.roll(x, -1)))
    assert rad(le)[-1] == pytest.approx(0.1, abs=1e-9)
    print(f"\nmeshed elliptical planform {area:.6g} vs pi c s / 4 = {ell.planform_area():.6g}")
    assert area == pytest.approx(ell.planform_area(), rel=0.01)
    trap = TrapezoidalFins(count=4, x=1.1, thickness=0.004, root_chord=0.16, tip_chord=0.08,
                           span=0.1, sweep_length=0.04, section=sec)
    free = FreeformFins(count=4, x=1.1, thickness=0.004, section=sec,
                        points=[(0, 0), (0.04, 0.1), (0.12, 0.1), (0.16, 0)])
    cna = []
    for fins in ([trap], [free]):
        p = build_panels(mesh_rocket(from_rocket(Rocket("t", body + fins)), symmetric=True,
                                     options=opt), symmetric=True)
        r = make_solver(p, 0.5, sref=np.pi * 0.05**2, lref=0.1).solve(np.radians([0.0, 2.0]))
        cna.append((r[1].CN - r[0].CN) / np.radians(2.0))
    print(f"\nCN-alpha trapezoid {cna[0]:.6f}, its free-form copy {cna[1]:.6f}")
    assert cna[1] == pytest.approx(cna[0], rel=1e-6)


def test_freeform_fins_with_a_pointed_tip_mesh_cleanly():
    """OpenRocket free-form fins ending in a point (chord 0 at the tip), square
    section: meshed without NumPy warnings, tip line collapsed to the point (the file's
    'base drag hack' transition is left out by the .ork reader)."""
    import warnings
    from pathlib import Path
    from ironbark_opt.vehicle import load_rocket_geometry
    from panair.geometry_adapter import from_rocket
    ork = Path(__file__).parents[1] / "data" / "ork" / "Base drag hack (short-wide).ork"
    with pytest.warns(UserWarning, match="base drag hack"):
        rocket, _ = load_rocket_geometry(ork)
    with warnings.catch_warnings():
        warnings.simplefilter("error", RuntimeWarning)
        nets = mesh_rocket(from_rocket(rocket), symmetric=True,
                           options=MeshOptions(n_theta=16, n_nose=6, n_chord=8, n_span=4))
    fin = next(n for n in nets if n.name == "fin0").points
    assert np.ptp(fin[-1], axis=0).max() < 1e-12            # the tip is a point
    assert not any(n.name.startswith("cap") for n in nets)  # so no tip cap


def _body_thetas(nets):
    """Meridian angles [rad] of the body network (from the bottom through +y)."""
    body = next(n for n in nets if n.name == "body")
    p = body.points[:, -1]                       # the last station: on the cylinder
    return np.unwrap(np.arctan2(p[:, 1], -p[:, 2]))


def test_three_fin_roots_lie_on_meridians_without_slivers():
    """3 fins on a 32-line circle: every gap between fin roots is split evenly, so
    no body panel is narrower than 0.6 of the nominal 2 pi / 32 (the old even
    spacing left 1.5 deg slivers beside two roots); fin-root pairs (+-eps) excepted."""
    body = BodyGeometry(np.array([0.0, 0.3, 2.5]), np.array([0.0, 0.075, 0.075]))
    fins = (FinGeometry(3, 0.23, 0.11, 0.185, 0.12, 2.145, 0.0058, roll=np.pi / 2,
                        section="rounded"),)
    nets = mesh_rocket(RocketGeometry(body, fins), symmetric=False, options=MeshOptions())
    th = _body_thetas(nets)
    d = np.diff(th)
    wide = d[d > 1e-6]
    assert wide.min() >= 0.6 * 2 * np.pi / 32
    # each root: its line of the even split with the +-eps lines opening the fin
    # footprint beside it (two tiny gaps per fin)
    assert int(np.sum(d <= 1e-6)) == 2 * 3


def test_four_fins_rolled_45_keep_the_even_circle():
    """Fins on the even spacing: the meridians are np.linspace's (tables unchanged)."""
    nets = mesh_rocket(_rocket(), symmetric=True, options=MeshOptions(n_theta=32))
    th = _body_thetas(nets)
    lines = th[np.concatenate([[True], np.diff(th) > 1e-6])]
    np.testing.assert_allclose(np.sort(lines), np.linspace(0.0, np.pi, 17), atol=1e-8)


def _haack(fineness, n=400):
    """Von Karman (Haack C = 0) nose of radius 1 and length 2 * fineness, then a cylinder."""
    L = 2.0 * fineness
    th = np.linspace(0.0, np.pi, n)
    x = 0.5 * L * (1 - np.cos(th))
    r = np.sqrt((th - 0.5 * np.sin(2 * th)) / np.pi)
    return BodyGeometry(np.append(x, 4 * L), np.append(r, 1.0))


@pytest.mark.parametrize("mach", [1.2, 1.5, 2.0])
def test_haack_tip_is_meshed_subinclined(mach):
    """A 2-calibre von Karman nose: the cosine-clustered first panel is steeper
    than the Mach cone (B tan > 0.951: the solver refuses it); with tip_mach the
    first panel's secant obeys B tan <= 0.93 when a tip of at most TIP_MAX_FRACTION
    of the nose does it, and the stations are unchanged otherwise."""
    from dataclasses import replace

    from panair.mesh import TIP_BT_MAX, TIP_MAX_FRACTION, _axial_stations
    g = _haack(2.0)
    b = np.sqrt(mach**2 - 1)
    plain = _axial_stations(g, (), MeshOptions())
    tipped = _axial_stations(g, (), replace(MeshOptions(), tip_mach=(mach,)))
    sec = lambda xs: float(np.interp(xs[1], g.x, g.r) / xs[1])
    if b * sec(plain) <= TIP_BT_MAX:                 # the solver takes the tip as it is
        np.testing.assert_array_equal(tipped, plain)
    elif len(tipped) < len(plain):
        assert b * sec(tipped) <= TIP_BT_MAX and tipped[1] <= TIP_MAX_FRACTION * 4.0
        np.testing.assert_array_equal(tipped[1:], plain[len(plain) - len(tipped) + 1:])
    else:                                            # no tip within the limit does it
        near = plain[1:][plain[1:] <= TIP_MAX_FRACTION * 4.0]
        assert np.all(b * np.interp(near, g.x, g.r) / near > TIP_BT_MAX)
        np.testing.assert_array_equal(tipped, plain)
    # a cone within the limit is never cut
    cone = BodyGeometry(np.array([0.0, 2.84, 10.0]), np.array([0.0, 0.5, 0.5]))
    np.testing.assert_array_equal(_axial_stations(cone, (), replace(MeshOptions(), tip_mach=(mach,))),
                                  _axial_stations(cone, (), MeshOptions()))


def test_fins_in_line_a_wake_ends_on_the_fin_behind():
    """Two 4-fin sets in line (a booster's behind a sustainer's): the body's root lines
    open along both roots (a watertight junction: the enclosed volume is the body's
    plus both fin sets'), and the forward fins' wakes stop at the aft fins' leading
    edge (a wake through the thick aft fin put its control points on the sheet)."""
    body = BodyGeometry(np.array([0.0, 2.84, 20.0]), np.array([0.0, 0.5, 0.5]))
    fore = FinGeometry(4, 1.0, 1.0, 1.0, 0.0, 9.0, 0.08, roll=np.pi / 4)
    aft = FinGeometry(4, 1.0, 1.0, 1.2, 0.0, 18.0, 0.08, roll=np.pi / 4)
    opt = MeshOptions(n_theta=16, n_chord=6, n_span=3)
    nets = mesh_rocket(RocketGeometry(body, (fore, aft)), symmetric=True, options=opt)
    panels = build_panels(nets, symmetric=True)
    one = build_panels(mesh_rocket(RocketGeometry(body, (fore,)), symmetric=True, options=opt), symmetric=True)
    two = build_panels(mesh_rocket(RocketGeometry(body, (aft,)), symmetric=True, options=opt), symmetric=True)
    bare = build_panels(mesh_rocket(RocketGeometry(body), symmetric=True, options=opt), symmetric=True)
    fins_fore, fins_aft = _volume(one) - _volume(bare), _volume(two) - _volume(bare)
    print(f"volume {_volume(panels):.5f} = body {_volume(bare):.5f} + fins {fins_fore:.5f} + {fins_aft:.5f}")
    assert _volume(panels) == pytest.approx(_volume(bare) + fins_fore + fins_aft, rel=1e-9)
    fore_wakes = [n for n in nets if n.kind == "wake" and "interior" in n.meta]
    assert len(fore_wakes) == 2                                   # the half model's two forward fins
    for w in fore_wakes:
        assert np.allclose(w.points[:, 1, 0], 18.0)               # ends on the aft leading edge
    # no wake panel between the aft fins' leading and trailing edges
    xw = panels.wake_corners[:, :, 0]
    assert not np.any((xw.max(axis=1) > 18.0 + 1e-9) & (xw.min(axis=1) < 19.0 - 1e-9))


def test_fins_in_line_a_wake_ends_on_the_first_fin_it_meets():
    """Three 4-fin sets in line, the middle one narrower (a two-stage stack whose
    booster has a small forward set): the forward fins' wake stations inside the middle
    set's span end on its leading edge, those beside it on the aft set's.  Until session
    20 only the first fin behind was looked at, so the outer stations ran on through
    the aft fin in its plane (a fuzzed two-stage stack: |Cp| 3.5e4 at Mach 0.05)."""
    body = BodyGeometry(np.array([0.0, 2.84, 20.0]), np.array([0.0, 0.5, 0.5]))
    fore = FinGeometry(4, 1.0, 1.0, 1.0, 0.0, 9.0, 0.08, roll=np.pi / 4)
    mid = FinGeometry(4, 1.0, 1.0, 0.5, 0.0, 13.0, 0.08, roll=np.pi / 4)
    aft = FinGeometry(4, 1.0, 1.0, 1.2, 0.0, 18.0, 0.08, roll=np.pi / 4)
    opt = MeshOptions(n_theta=16, n_chord=6, n_span=4)
    nets = mesh_rocket(RocketGeometry(body, (fore, mid, aft)), symmetric=True, options=opt)
    fore_wakes = [n for n in nets if n.kind == "wake" and n.name in ("wake0", "wake1")]
    assert len(fore_wakes) == 2
    for w in fore_wakes:
        r = np.hypot(w.points[:, 0, 1], w.points[:, 0, 2])
        ends = w.points[:, 1, 0]
        np.testing.assert_allclose(ends[r <= 0.5 + 0.5 + 1e-9], 13.0)     # on the middle fin
        np.testing.assert_allclose(ends[r > 0.5 + 0.5 + 1e-9], 18.0)      # beside it, on the aft fin
        assert np.all(w.meta["interior"][:, 1])                           # nothing shed past them
    panels = build_panels(nets, symmetric=True)
    xw = panels.wake_corners[:, :, 0]
    rw = np.hypot(panels.wake_corners[:, :, 1], panels.wake_corners[:, :, 2])
    through_aft = (xw.max(axis=1) > 18.0 + 1e-9) & (xw.min(axis=1) < 19.0 - 1e-9) & (rw.min(axis=1) < 1.7)
    assert not np.any(through_aft)


def test_fins_in_line_no_wake_through_the_tip_of_a_shorter_fin_behind():
    """A forward fin wider than the fin in line behind it: the wake strip reaching over
    the aft fin's tip (one station inside its span, one beside it) ends at its leading
    edge instead of running on through the aft fin's tip panels (a fuzzed two-stage
    stack, sustainer fins 0.39 m ahead of the booster's 0.35 m: |Cp| 1.3e6 at Mach
    0.05, build refused); the strips wholly beside it keep their wake."""
    body = BodyGeometry(np.array([0.0, 2.84, 20.0]), np.array([0.0, 0.5, 0.5]))
    fore = FinGeometry(4, 1.0, 1.0, 1.0, 0.0, 9.0, 0.08, roll=np.pi / 4)
    aft = FinGeometry(4, 1.0, 1.0, 0.63, 0.0, 18.0, 0.08, roll=np.pi / 4)
    opt = MeshOptions(n_theta=16, n_chord=6, n_span=4)
    panels = build_panels(mesh_rocket(RocketGeometry(body, (fore, aft)), symmetric=True, options=opt),
                          symmetric=True)
    w = panels.wake_corners
    xw, rw = w[:, :, 0], np.hypot(w[:, :, 1], w[:, :, 2])
    over_aft = (xw.max(axis=1) > 18.0 + 1e-9) & (xw.min(axis=1) < 19.0 - 1e-9) & (rw.min(axis=1) < 0.5 + 0.63)
    assert not np.any(over_aft)
    beside = (xw.min(axis=1) >= 18.0 - 1e-9) & (rw.min(axis=1) > 0.5 + 0.63)
    assert np.any(beside)                         # the outer strips' wake runs on
