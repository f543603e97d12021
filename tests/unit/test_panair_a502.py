"""A502 deck writer (against a deck PANIN wrote for a real run) and the
external-PANAIR runner (with fake executables replaying recorded outputs)."""
import stat
from pathlib import Path

import pytest

from ironbark_opt.errors import SolverError
from panair.a502 import find_panair, run_panair, write_a502
from panair.lawgs import read_lawgs

DATA = Path(__file__).parents[1] / "data" / "panair"


def _ogive():
    _, nets = read_lawgs(DATA / "ogive_m0.6_a2" / "ogive.wgs")
    base = nets[1].with_kind("base")
    wake = nets[2].with_kind("wake")
    wake.meta["kt"] = -18
    return [nets[0], base, wake]


def test_deck_matches_panin(tmp_path):
    deck = write_a502(tmp_path / "a502.in", _ogive(), mach=0.6, alpha_deg=2.0, alpc_deg=2.0,
                      sref=0.785398, cref=1.0, bref=1.0, xref=0.0, symmetric=True)
    ours = deck.read_text().splitlines()
    ref = (DATA / "ogive_m0.6_a2" / "a502.in").read_text().splitlines()
    assert len(ours) == len(ref)
    # line 1-3: titles; everything else identical to PANIN's deck (trailing blanks aside)
    diff = [(i + 1, a, b) for i, (a, b) in enumerate(zip(ours, ref))
            if i >= 3 and a.rstrip() != b.rstrip()]
    assert diff == []


def test_deck_multi_case_and_wide_numbers(tmp_path):
    deck = write_a502(tmp_path / "a.in", _ogive(), mach=1.6, alpha_deg=[0, 2, 4], alpc_deg=2.0,
                      sref=60000.0, cref=100.0, bref=600.0, xref=25.0)
    text = deck.read_text().splitlines()
    i = text.index("$ANGLES OF ATTACK")
    assert text[i + 1] == "    2.0000" and text[i + 2] == "    0.0000    2.0000    4.0000"
    assert text[text.index("$CASES") + 1] == "    3.0000"
    assert text[text.index("$REFERENCE DATA FOR 3-D FORCES AND MOMENTS") + 2] == \
        "60000.0000600.000000100.000000600.000000"


def _fake(tmp_path, name, body):
    exe = tmp_path / name
    exe.write_text("#!/bin/sh\n" + body)
    exe.chmod(exe.stat().st_mode | stat.S_IEXEC)
    return str(exe)


def test_runner_with_recorded_outputs(tmp_path):
    rec = DATA / "ogive_m0.6_a2"
    exe = _fake(tmp_path, "panair_ok",
                f"read deck\ntest -f \"$deck\" || exit 9\n"
                f"cp {rec}/ffmf {rec}/agps {rec}/panair.err .\n")
    run = run_panair(_ogive(), mach=0.6, alpha_deg=2.0, executable=exe, workdir=tmp_path / "runs",
                     sref=0.785398, cref=1.0)
    assert run.forces[0].CN == 0.06955 and run.forces[0].Cm == -0.10899
    assert run.cp[1][0].shape == (53, 4)
    assert (run.directory / "a502.in").exists() and run.directory.parent == tmp_path / "runs"
    run2 = run_panair(_ogive(), mach=0.6, alpha_deg=2.0, executable=exe, workdir=tmp_path / "runs",
                      sref=0.785398, cref=1.0)
    assert run2.directory != run.directory        # a fresh directory per case


def test_runner_reports_panair_errors(tmp_path):
    stop = _fake(tmp_path, "panair_stop",
                 "echo ' PanAir is stopping.' > panair.err\necho stale > ffmf\nexit 0\n")
    with pytest.raises(SolverError, match="stopping"):
        run_panair(_ogive(), mach=0.6, alpha_deg=2.0, executable=stop, workdir=tmp_path,
                   sref=0.785398, cref=1.0)
    rec = DATA / "ogive_m0.6_a2"
    garbage = _fake(tmp_path, "panair_garbage",
                    f"cp {rec}/panair.err .\nsed 's/0.06955/289.00000/' {rec}/ffmf > ffmf\n")
    with pytest.raises(SolverError, match="not physical"):
        run_panair(_ogive(), mach=3.5, alpha_deg=2.0, executable=garbage, workdir=tmp_path,
                   sref=0.785398, cref=1.0)
    with pytest.raises(SolverError, match="not found"):
        run_panair(_ogive(), mach=0.6, alpha_deg=2.0, executable=str(tmp_path / "nope"),
                   workdir=tmp_path, sref=0.785398, cref=1.0)


def test_find_panair(monkeypatch, tmp_path):
    monkeypatch.setenv("IRONBARK_PANAIR", "/opt/panair/bin/panair")
    assert find_panair() == "/opt/panair/bin/panair"
    monkeypatch.delenv("IRONBARK_PANAIR")
    monkeypatch.setenv("PATH", str(tmp_path))
    assert find_panair() is None
    with pytest.raises(SolverError, match="no PANAIR executable"):
        run_panair(_ogive(), mach=0.6, alpha_deg=2.0, sref=1.0, cref=1.0)
