"""LaWGS reader/writer and PANAIR output parsers, on real PANAIR files
(tests/data/panair, copied from ../shared/fixtures/panair)."""
from pathlib import Path

import numpy as np
import pytest

from ironbark_opt.errors import InputError, SolverError
from panair.a502_output import (check_panair_err, read_agps, read_ffmf,
                                read_panair_out_summary)
from panair.lawgs import Network, read_lawgs, write_lawgs

DATA = Path(__file__).parents[1] / "data" / "panair"


def test_read_ogive_lawgs_geometry():
    title, nets = read_lawgs(DATA / "ogive_m0.6_a2" / "ogive.wgs")
    assert "ogive" in title
    assert [n.name for n in nets] == ["body", "base", "basewake"]
    assert [n.shape for n in nets] == [(25, 53), (3, 25), (25, 2)]
    body = nets[0].points
    # D = 1 body: every point of the cylinder part is on radius 0.5 (to the 8 digits printed)
    r = np.hypot(body[..., 1], body[..., 2])
    cyl = body[..., 0] >= 3.0
    assert np.allclose(r[cyl], 0.5, atol=1e-7)
    # tangent ogive 3 cal, R = 0.5: radius of curvature rho = (R^2 + L^2)/(2R) = 9.25
    rho = (0.25 + 9.0) / 1.0
    x = body[0, :25, 0]
    r_exact = np.sqrt(rho**2 - (3.0 - x) ** 2) - (rho - 0.5)
    assert np.allclose(r[0, :25], r_exact, atol=1e-7)
    assert nets[2].points[0, 1, 0] == 60.0  # wake 50 cal long


def test_lawgs_crlf_and_round_trip(tmp_path):
    title, nets = read_lawgs(DATA / "naca0012" / "naca0012.wgs")
    assert title == "NACA0012 created by wgs_creator"
    assert [n.shape for n in nets] == [(20, 49), (5, 25), (20, 2)]
    out = write_lawgs(tmp_path / "rt.wgs", nets, title=title)
    title2, nets2 = read_lawgs(out)
    assert title2 == title
    for a, b in zip(nets, nets2):
        assert a.name == b.name
        np.testing.assert_allclose(a.points, b.points, rtol=1e-9, atol=1e-12)


def test_lawgs_scale_translate_and_errors(tmp_path):
    f = tmp_path / "t.wgs"
    f.write_text("t\nnet\n1 2 2 0 0 0 0 1 0 0 2 2 2 0\n0 0 0 1 0 0\n0 1 0\n1 1 0\n")
    _, (net,) = read_lawgs(f)
    np.testing.assert_allclose(net.points[1, 1], [3.0, 2.0, 0.0])
    f.write_text("t\nnet\n1 2 2 0 0 0 0 0 0 0 1 1 1 0\n0 0 0 1 0 0\n0 1 x\n")
    with pytest.raises(InputError, match=r"t.wgs:5.*coordinate"):
        read_lawgs(f)
    f.write_text("t\nnet\n1 2 2 0 0 0 0 0 0 0 1 1 1 0\n0 0 0 1 0 0\n")
    with pytest.raises(InputError, match="2 of 4 points"):
        read_lawgs(f)
    f.write_text("t\nnet\n1 2 2 0 0 0 30 0 0 0 1 1 1 0\n" + "0 0 0\n" * 4)
    with pytest.raises(InputError, match="rotations"):
        read_lawgs(f)
    with pytest.raises(InputError, match="shape"):
        Network("bad", np.zeros((1, 3, 3)))


def test_ffmf_single_and_multi_solution():
    (s,) = read_ffmf(DATA / "ogive_m0.6_a2" / "ffmf")
    assert (s.alpha_deg, s.CN, s.CA, s.Cm, s.cl, s.cdi, s.area) == (
        2.0, 0.06955, -0.00145, -0.10899, 0.06956, 0.00097, 28.35324)
    sols = read_ffmf(DATA / "ogive_m1.6_alpc2" / "ffmf")
    assert [x.alpha_deg for x in sols] == [0.0, 2.0, 4.0]
    assert [x.CN for x in sols] == [0.00172, 0.09268, 0.18488]
    assert sols[2].Cm == -0.21847
    # CRLF file from pyPanair, wing case
    (w,) = read_ffmf(DATA / "naca0012" / "ffmf")
    assert w.alpha_deg == 6.0 and w.cl == 0.47895 and w.area == 123954.39335
    # body-axis and wind-axis forces are the same vector: cl = fz cos a - fx sin a
    a = np.radians(s.alpha_deg)
    assert abs(s.cl - (s.fz * np.cos(a) - s.fx * np.sin(a))) < 2e-5


def test_panair_out_summary_matches_ffmf():
    (a,) = read_panair_out_summary(DATA / "ogive_m0.6_a2" / "panair.out")
    (b,) = read_ffmf(DATA / "ogive_m0.6_a2" / "ffmf")
    assert a == b


def test_agps_cp():
    cp = read_agps(DATA / "ogive_m0.6_a2" / "agps")
    assert sorted(cp) == [1, 2, 3]
    assert len(cp[1]) == 25 and cp[1][0].shape == (53, 4)
    assert cp[1][0][0, 3] == pytest.approx(0.665751)  # stagnation at the tip, row 1
    # geometry of agps = geometry of the LaWGS grid
    _, nets = read_lawgs(DATA / "ogive_m0.6_a2" / "ogive.wgs")
    np.testing.assert_allclose(cp[1][3][:, :3], nets[0].points[3], atol=6e-6)
    multi = read_agps(DATA / "ogive_m1.6_alpc2" / "agps")
    assert multi[1][0].shape == (53, 6)
    assert multi[1][0][0, 3:].tolist() == [0.429325, 0.525149, 0.637799]


def test_panair_err(tmp_path):
    assert check_panair_err(DATA / "ogive_m0.6_a2" / "panair.err") == []
    assert check_panair_err(DATA / "batch_case1" / "panair.err") == []
    bad = tmp_path / "panair.err"
    bad.write_text(" geometry   cpu time:     0.033\n PanAir is stopping.\n")
    with pytest.raises(SolverError, match="stopping"):
        check_panair_err(bad)
    with pytest.raises(SolverError, match="did not run"):
        check_panair_err(tmp_path / "nothing" / "panair.err")


def test_ffmf_garbage_is_an_input_error(tmp_path):
    f = tmp_path / "ffmf"
    f.write_text(" sol-no alpha\n ------\n      1    2.0000    0.0000  ****** 0 0 0 0 0\n 0 0 0 1\n")
    with pytest.raises(InputError, match=r"ffmf:3"):
        read_ffmf(f)
    f.write_text("nothing here\n")
    with pytest.raises(InputError, match="not a PANAIR force summary"):
        read_ffmf(f)
