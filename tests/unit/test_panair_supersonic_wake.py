"""Supersonic fin wakes behind which the body continues (panair.solver.supersonic_wake).

Linear theory's wake (Ward, *Linearized Theory of Steady High-Speed Flow*, 1955, ch. 8;
Epton & Magnus, NASA CR-3251, 1990, the wake networks): it carries no load and the
potential jump of the fin's trailing edge is carried aft unchanged.  Checked on a coarse
cone-cylinder with a fin pair in the lifting plane and 2.5 cal of body behind it, Mach 1.6:
the jump across the wake's root line on the body keeps its trailing-edge value to the
base within 15 % (without the sheets it decays: the case the sheets fix), and the
afterbody carries lift, not a download; and the mirror-folded solve of a 3-fin full
model with sheets equals the unfolded one.
"""
import math
from dataclasses import replace

import numpy as np
import pytest

from panair.mesh import BodyGeometry, FinGeometry, MeshOptions, RocketGeometry, mesh_rocket
from panair.solver import build_panels, make_solver
from panair.solver.pressure import integrate_forces

MACH = 1.6
X_TE = 7.5                      # fin root trailing edge [cal]; body to 10 cal


def _opt(**kw):
    base = MeshOptions(**{"n_theta": 16, "n_nose": 8, "body_spacing": 0.5, "n_chord": 10,
                          "n_span": 3, "supersonic_span_factor": 2.0, "supersonic_chord_factor": 1.0, **kw})
    return replace(base.for_mach(1.2), tip_mach=(MACH,))


def _pair_model():
    body = BodyGeometry(np.array([0.0, 2.84, 10.0]), np.array([0.0, 0.5, 0.5]))
    fins = (FinGeometry(2, 1.0, 0.6, 0.6, 0.4, X_TE - 1.0, 0.04, roll=np.pi / 2),)
    return build_panels(mesh_rocket(RocketGeometry(body, fins), symmetric=True, options=_opt()),
                        symmetric=True)


def _jump_along_wake(p, res):
    """(x, potential jump) across the wake's root line (theta = 90 deg, fin at +y) on the
    body panels aft of the trailing edge, alpha 2 minus alpha 0."""
    _, c, n, a = p.geometry()
    body = np.array([p.names[k] == "body" for k in p.network]) & p.integrate
    mu = res[1].mu - res[0].mu
    th = np.degrees(np.arctan2(c[:, 1], -c[:, 2]))
    out = []
    for x in np.unique(np.round(c[body & (c[:, 0] > X_TE), 0], 9)):
        ring = body & (np.abs(c[:, 0] - x) < 1e-6)
        below = ring & (th < 90)
        above = ring & (th > 90)
        i = np.nonzero(below)[0][np.argmax(th[below])]
        j = np.nonzero(above)[0][np.argmin(th[above])]
        out.append((x, mu[j] - mu[i]))
    return np.array(out)


@pytest.fixture(scope="module")
def pair():
    p = _pair_model()
    s = make_solver(p, MACH, sref=np.pi / 4, lref=1.0, xref=0.0)
    return p, s, s.solve(np.radians([0.0, 2.0]))


def test_wake_keeps_the_trailing_edge_potential_jump(pair):
    p, s, res = pair
    assert s.wake_cells > 0
    j = _jump_along_wake(p, res)
    print(f"\npotential jump across the wake line, x = {j[0, 0]:.2f} ... {j[-1, 0]:.2f} cal: "
          f"{j[0, 1]:.5f} ... {j[-1, 1]:.5f}")
    assert abs(j[0, 1]) > 1e-4
    assert np.all(np.abs(j[:, 1] / j[0, 1] - 1) < 0.15)


def test_without_the_sheets_the_jump_dies_out(monkeypatch):
    """The solver as it was before the sheets (a wall-less wake): the jump decays
    behind the trailing edge, the failure the sheets remove."""
    import panair.solver.supersonic as sup
    monkeypatch.setattr(sup, "WAKE_SHEETS", False)
    p = _pair_model()
    s = make_solver(p, MACH, sref=np.pi / 4, lref=1.0, xref=0.0)
    j = _jump_along_wake(p, s.solve(np.radians([0.0, 2.0])))
    print(f"\nwithout sheets: jump {j[0, 1]:.5f} ... {j[-1, 1]:.5f}")
    assert s.wake_cells == 0 and j[-1, 1] / j[0, 1] < 0.6


def test_afterbody_carries_lift_not_a_download(pair):
    p, s, res = pair
    _, c, n, a = p.geometry()
    body = np.array([p.names[k] == "body" for k in p.network]) & p.integrate
    aft = body & (c[:, 0] > X_TE)
    cn = [integrate_forces(r.cp[aft], c[aft], n[aft], a[aft], sref=np.pi / 4, lref=1.0, xref=0.0,
                           symmetric=True)["CN"] for r in res]
    cna_aft = (cn[1] - cn[0]) / math.radians(2.0)
    cna = (res[1].CN - res[0].CN) / math.radians(2.0)
    print(f"\nafterbody CN-alpha {cna_aft:.3f} of {cna:.3f} /rad")
    assert 0.0 < cna_aft < 0.3 * cna


def test_mirror_fold_with_wake_sheets_is_the_full_solve():
    body = BodyGeometry(np.array([0.0, 2.84, 10.0]), np.array([0.0, 0.5, 0.5]))
    fins = (FinGeometry(3, 1.0, 0.6, 0.6, 0.4, X_TE - 1.0, 0.04, roll=0.0),)
    p = build_panels(mesh_rocket(RocketGeometry(body, fins), symmetric=False,
                                 options=_opt(n_span=2, n_chord=8)), symmetric=False)
    out = []
    for mirror in (False, True):
        s = make_solver(p, MACH, sref=np.pi / 4, lref=1.0, xref=0.0, mirror=mirror)
        assert s.wake_cells > 0 and (s._fold is not None) == mirror
        out.append([(r.CN, r.Cm) for r in s.solve(np.radians([0.0, 2.0]))])
    np.testing.assert_allclose(out[1], out[0], rtol=1e-8, atol=1e-10)


@pytest.mark.parametrize("roll_deg", [90.0, 30.0])
def test_fold_in_another_plane_with_wake_sheets_is_the_full_solve(roll_deg):
    """3 fins rolled 90 deg (OpenRocket's default) or 30 deg have no x-z mirror plane but
    one through a fin: its even and odd systems, each with the wake conditions
    (supersonic_wake.folded_wake_systems), give the full solve; a fin lies in the
    plane, so its cells are their own mirror images."""
    body = BodyGeometry(np.array([0.0, 2.84, 10.0]), np.array([0.0, 0.5, 0.5]))
    fins = (FinGeometry(3, 1.0, 0.6, 0.6, 0.4, X_TE - 1.0, 0.04, roll=np.radians(roll_deg)),)
    p = build_panels(mesh_rocket(RocketGeometry(body, fins), symmetric=False,
                                 options=_opt(n_span=2, n_chord=8)), symmetric=False)
    out = []
    for mirror in (False, True):
        s = make_solver(p, MACH, sref=np.pi / 4, lref=1.0, xref=0.0, mirror=mirror)
        assert s.wake_cells > 0
        if mirror:
            assert s._fold is not None and s._fold.odd
        out.append([(r.CN, r.Cm, r.CY, r.Cn) for r in s.solve(np.radians([0.0, 2.0, 5.0]))])
    np.testing.assert_allclose(out[1], out[0], rtol=1e-8, atol=1e-10)


def test_sheet_stops_where_the_body_grows_past_it():
    """A flare behind the fins (radius 0.5 -> 0.6 cal from 8 to 9 cal) would put the
    sheet's root inside the body: its innermost strip ends where the body reaches it
    and no cell lies inside the body; on a cylinder it runs to the body's end."""
    from panair.solver.supersonic_wake import wake_sheets
    fins = (FinGeometry(2, 1.0, 0.6, 0.6, 0.4, X_TE - 1.0, 0.04, roll=np.pi / 2),)
    ends = {}
    for name, x, r in (("cylinder", [0.0, 2.84, 10.0], [0.0, 0.5, 0.5]),
                       ("flare", [0.0, 2.84, 8.0, 9.0, 10.0], [0.0, 0.5, 0.5, 0.6, 0.6])):
        p = build_panels(mesh_rocket(RocketGeometry(BodyGeometry(np.array(x), np.array(r)), fins),
                                     symmetric=True, options=_opt()), symmetric=True)
        lifting = ~p.wake_at_base
        sh = wake_sheets(p, p.integrate.copy(), np.unique(p.network[p.wake_upper[lifting]]))
        c = sh.corners[:sh.n_cells]
        r_in = np.linalg.norm(c[..., 1:], axis=2).min(axis=1)
        inner = r_in < r_in.min() + 1e-9
        ends[name] = float(c[inner][..., 0].max())
        assert np.all(r_in >= np.interp(c[..., 0].max(axis=1), x, r) - 1e-9)
    print(f"\ninnermost strip of the sheet ends at: {ends}")
    assert ends["cylinder"] == pytest.approx(10.0)
    assert X_TE < ends["flare"] <= 8.5


def test_sheet_behind_a_swept_trailing_edge_runs_to_the_body_end():
    """A parallelogram fin (trailing edge swept back, the tip's trailing edge 0.4 cal
    aft of the root's): every strip's sheet runs from its trailing edge to the body's
    end.  Before session 19 the guard above took the tip cap alongside the tip chord for
    the body (its radius the tip's) and stopped each strip's sheet at the first body
    station beside the tip chord: 14 cells instead of 100+ on a slender wing, whose
    Mach 1.2 thin-wing lift was then -31 % of the Mach box, -22 % with the sheets."""
    from panair.solver.supersonic_wake import wake_sheets
    fins = (FinGeometry(2, 1.0, 1.0, 0.6, 0.4, X_TE - 1.0, 0.04, roll=np.pi / 2),)
    p = build_panels(mesh_rocket(RocketGeometry(BodyGeometry(np.array([0.0, 2.84, 10.0]),
                                                             np.array([0.0, 0.5, 0.5])), fins),
                                 symmetric=True, options=_opt()), symmetric=True)
    lifting = ~p.wake_at_base
    sh = wake_sheets(p, p.integrate.copy(), np.unique(p.network[p.wake_upper[lifting]]))
    c = sh.corners[:sh.n_cells]
    r_mid = np.round(np.linalg.norm(c.mean(axis=1)[:, 1:], axis=1), 6)
    ends = [float(c[r_mid == r][..., 0].max()) for r in np.unique(r_mid)]
    print(f"\nstrips {len(ends)}, ends {np.round(ends, 3)}")
    assert len(ends) >= 6
    np.testing.assert_allclose(ends, 10.0, atol=1e-9)


@pytest.mark.parametrize("count, roll_deg", [(3, 0.0), (4, 0.0), (3, 17.0), (4, 45.0)])
def test_sheet_faces_are_sided_as_their_fins(count, roll_deg):
    """A wake face looks to the side ``sheets.side`` of its fin's plane (physical space,
    where the sheets are built) and the solver sides the panels by the same plane in its
    scaled space (x / B): both must be one orientation.  fin_plane orients the normal by
    the geometry; with LAPACK's sign (before session 17) the two disagreed for one fin in
    three or four (3 and 4 fins rolled 0 deg, 3 rolled 17 deg) at some of these Mach
    numbers (4 rolled 0 deg, Mach 2.5: all four), and the faces took sources from the side
    they do not face."""
    from panair.solver import supersonic as sup
    from panair.solver.supersonic_wake import sheet_geometry, wake_sheets
    body = BodyGeometry(np.array([0.0, 2.84, 12.0]), np.array([0.0, 0.5, 0.5]))
    geom = RocketGeometry(body, (FinGeometry(count, 1.0, 1.0, 1.0, 0.0, 9.0, 0.08,
                                             roll=np.radians(roll_deg)),))
    opt = MeshOptions(n_theta=16, n_nose=4, body_spacing=2.0, n_chord=4, n_span=2)
    for mach in (1.2, 1.6, 2.0, 2.5, 3.0):
        p = build_panels(mesh_rocket(geom, options=opt.for_mach(mach)))
        keep = p.integrate.copy()
        b = math.sqrt(mach**2 - 1.0)
        _, cen, _, _ = p.geometry(1.0 / b)
        fins = np.unique(p.network[p.wake_upper[~p.wake_at_base]])
        sheets = wake_sheets(p, keep, fins)
        _, cen_w, nrm_w, _ = sheet_geometry(sheets, b)
        planes, x0, tol = sup._fin_planes(p, keep, cen[keep], fins)
        own = np.eye(len(fins), dtype=bool)
        recv = sup._receiver_sides(planes, x0, tol, own, cen_w, nrm_w, sheets.fin,
                                   np.zeros(len(fins), bool))
        np.testing.assert_array_equal(recv[sheets.fin, np.arange(len(sheets.fin))], sheets.side)
