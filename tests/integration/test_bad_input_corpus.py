"""Every bad input in the corpus gets a clear one-line error (issue 15).

Each case of :mod:`bad_input_cases` runs the ``ironbark`` CLI in-process and
asserts: the exit status (2 bad input, 3 network/solver), one line on stderr
starting ``error:`` that names the file/field/option (the case's needles), no
traceback, nothing on stdout that looks like a result, and no partial output
file.  A few cases also run as real subprocesses for the exit-code path.
"""
from __future__ import annotations

import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest
from click.testing import CliRunner

from ironbark_opt.cli import main
from bad_input_cases import CASES, DATA
from conftest import isolate_network

ROOT = Path(__file__).resolve().parents[2]


def _prepare(tmp: Path, case) -> list[str]:
    shutil.copytree(ROOT / "examples/calisto", tmp / "ex/c")
    shutil.copytree(ROOT / "examples/kestrel", tmp / "ex/k")
    (tmp / "tables").mkdir()
    for name in ("Kestrel.csv", "Kestrel.json"):
        shutil.copy(ROOT / "tables" / name, tmp / "tables" / name)
    argv = []
    for arg in case.argv:
        if arg.startswith("{ORK:"):
            name = arg[5:-1]
            (tmp / "ork").mkdir(exist_ok=True)
            shutil.copy(DATA / "ork" / name, tmp / "ork" / name)
            argv.append(str(tmp / "ork" / name))
            continue
        argv.append(arg.replace("{C}", str(tmp / "ex/c/calisto.toml"))
                    .replace("{K}", str(tmp / "ex/k/kestrel.toml"))
                    .replace("{CD}", str(tmp / "ex/c")).replace("{T}", str(tmp))
                    .replace("{D}", str(DATA)))
    argv = ["" if a == "''" else a for a in argv]
    for ed in case.edits:
        if callable(ed):
            ed(tmp)
            continue
        rel, old, new = ed
        path = tmp / rel
        path.parent.mkdir(parents=True, exist_ok=True)
        if old is None:
            (path.write_bytes if isinstance(new, bytes) else path.write_text)(new)
        else:
            text = path.read_text()
            assert old in text, f"corpus case {case.id}: {old!r} not in {rel} (example changed?)"
            path.write_text(text.replace(old, new, 1))
    return argv


def _network(case, monkeypatch, tmp: Path, closed_port_url, loopback_factory):
    isolate_network(monkeypatch, tmp, closed_port_url)
    if case.net and case.net.startswith("loopback:"):
        server = loopback_factory()
        fault = case.net.split(":", 1)[1]
        for path in ("/api/v1/search.json", "/api/v1/search"):
            if fault == "500":
                server.route(path, b"oops", status=500)
            elif fault == "garbage":
                server.route(path, b"<html>not json</html>", content_type="application/json")
            elif fault == "truncate":
                server.route(path, DATA / "thrustcurve/search-GET-designation-K550W.json",
                             content_type="application/json", truncate=True)
        monkeypatch.setenv("IRONBARK_THRUSTCURVE_URL", server.url + "/api/v1")


@pytest.fixture
def loopback_factory(request):
    """The loopback server of conftest.py, started only for the cases that need it."""
    return lambda: request.getfixturevalue("loopback")


def _check(case, status, stdout, stderr, tmp):
    lines = [ln for ln in stderr.splitlines() if ln.strip() and not ln.startswith("warning:")]
    assert "Traceback" not in stderr + stdout, f"{case.id}: traceback\n{stderr}"
    assert status == case.status, f"{case.id}: exit {status}, expected {case.status}\n{stderr}\n{stdout}"
    assert len(lines) == 1 and lines[0].startswith("error: "), f"{case.id}: not one error line:\n{stderr}"
    line = lines[0].lower()
    assert len(line) < 500, f"{case.id}: error line too long ({len(line)} chars): {line}"
    missing = [n for n in case.needles if n.lower() not in line]
    assert not missing, f"{case.id}: error does not name {missing}: {lines[0]}"
    assert "apogee" not in stdout.lower(), f"{case.id}: printed a result: {stdout}"
    for rel in case.outputs:
        assert not (tmp / rel).exists(), f"{case.id}: output {rel} was written"
    leftovers = [p.name for p in tmp.rglob("*.tmp*")]
    assert not leftovers, f"{case.id}: temporary files left: {leftovers}"


@pytest.mark.parametrize("case", CASES, ids=[c.id for c in CASES])
def test_bad_input(case, tmp_path, monkeypatch, closed_port_url, loopback_factory):
    argv = _prepare(tmp_path, case)
    _network(case, monkeypatch, tmp_path, closed_port_url, loopback_factory)
    for name, value in case.env:
        monkeypatch.setenv(name, value.replace("{C}", str(tmp_path / "ex/c/calisto.toml"))
                           .replace("{T}", str(tmp_path)))
    monkeypatch.chdir(tmp_path)
    res = CliRunner().invoke(main, argv, catch_exceptions=True)
    if res.exception is not None and not isinstance(res.exception, SystemExit):
        import traceback
        tb = "".join(traceback.format_exception(res.exception))
        pytest.fail(f"{case.id}: uncaught {type(res.exception).__name__}\n{tb}")
    print(f"{case.id}: exit {res.exit_code}: {res.stderr.strip()}")
    _check(case, res.exit_code, res.stdout, res.stderr, tmp_path)


def test_corpus_is_large_and_unique():
    ids = [c.id for c in CASES]
    assert len(ids) == len(set(ids)), "duplicate case ids"
    assert len(ids) >= 150, f"corpus has {len(ids)} cases, expected >= 150"
    print(f"bad-input corpus: {len(ids)} cases")


@pytest.mark.parametrize("case_id", ["toml-duplicate-key", "opt-inclination-120", "net-search-closed-port"])
def test_real_subprocess_exit_status(case_id, tmp_path, closed_port_url):
    """The exit status reaches the shell (a real ``python -m ironbark_opt.cli``)."""
    case = next(c for c in CASES if c.id == case_id)
    argv = _prepare(tmp_path, case)
    env = dict(os.environ, PYTHONPATH=str(ROOT), IRONBARK_CACHE_DIR=str(tmp_path / "cache"),
               IRONBARK_CONFIG=str(tmp_path / "no.toml"), IRONBARK_HTTP_RETRIES="1",
               IRONBARK_HTTP_BACKOFF="0", IRONBARK_THRUSTCURVE_URL=closed_port_url)
    proc = subprocess.run([sys.executable, "-m", "ironbark_opt.cli", *argv], cwd=tmp_path, env=env,
                          capture_output=True, text=True, timeout=300)
    _check(case, proc.returncode, proc.stdout, proc.stderr, tmp_path)
