"""Network faults on the ThrustCurve.org path: each gives a clear message,
falls back to the cache where one exists, never leaves a half-written cache."""
from __future__ import annotations

import warnings
from pathlib import Path

import pytest

from ironbark_opt.errors import InputError, NetworkError
from ironbark_opt.motors import thrustcurve as tc

TC = Path(__file__).resolve().parents[1] / "data" / "thrustcurve"
API = "/api/v1"
SEARCH = f"{API}/search.json"


def _cache_files(cache: Path) -> list[Path]:
    return sorted(p for p in cache.rglob("*") if p.is_file()) if cache.exists() else []


def _no_temp_files(cache: Path):
    assert not [p for p in _cache_files(cache) if p.name.startswith(".tmp")]


def test_http_404_names_url_and_is_not_retried(tc_server, net_env):
    with pytest.raises(NetworkError) as err:
        tc.search(manufacturer="Estes")
    msg = str(err.value)
    assert "ThrustCurve.org" in msg and "HTTP 404" in msg and "/api/v1/search.json" in msg
    assert "--offline" in msg
    assert tc_server.paths().count(SEARCH) == 1          # 4xx: no retry
    assert _cache_files(net_env) == []


def test_http_500_is_retried_then_succeeds(tc_server):
    tc_server.route(SEARCH, TC / "search-GET-manufacturer.json", fail_first=1)
    assert len(tc.search(manufacturer="Estes")) == 20
    assert tc_server.paths().count(SEARCH) == 2


def test_http_500_persistent(tc_server, net_env):
    tc_server.route(SEARCH, b"oops", status=500)
    with pytest.raises(NetworkError, match="HTTP 500"):
        tc.search(manufacturer="Estes")
    assert tc_server.paths().count(SEARCH) == 2          # first try + 1 retry
    assert _cache_files(net_env) == []


def test_timeout(tc_server, monkeypatch, net_env):
    monkeypatch.setenv("IRONBARK_HTTP_TIMEOUT", "0.3")
    monkeypatch.setenv("IRONBARK_HTTP_RETRIES", "0")
    tc_server.route(SEARCH, TC / "search-GET-manufacturer.json", delay=1.0)
    with pytest.raises(NetworkError, match=r"no answer within 0.3 s \(timeout\)"):
        tc.search(manufacturer="Estes")
    _no_temp_files(net_env)


def test_connection_refused(net_env, monkeypatch, closed_port_url):
    monkeypatch.setenv("IRONBARK_THRUSTCURVE_URL", closed_port_url + API)
    with pytest.raises(NetworkError, match="connection refused") as err:
        tc.search(manufacturer="Estes")
    assert "IRONBARK_THRUSTCURVE_URL" in str(err.value)


def test_truncated_body_is_not_cached(tc_server, net_env):
    tc_server.route(SEARCH, TC / "search-GET-manufacturer.json", truncate=True)
    with pytest.raises(NetworkError) as err:
        tc.search(manufacturer="Estes")
    assert "truncated" in str(err.value) or "malformed" in str(err.value)
    assert _cache_files(net_env) == []


def test_malformed_json(tc_server, net_env):
    tc_server.route(SEARCH, b'{"results": [ {"motorId": ')
    with pytest.raises(NetworkError, match="malformed response: not valid JSON"):
        tc.search(manufacturer="Estes")
    assert _cache_files(net_env) == []


def test_malformed_base64_in_download(tc_server, net_env):
    tc_server.route(f"{API}/download.json",
                 b'{"results": [{"motorId": "m", "format": "RASP", "source": "cert", "data": "%%%"}]}')
    with pytest.raises(NetworkError, match="not valid base64"):
        tc.download("m")
    assert _cache_files(net_env) == []


def test_falls_back_to_cache_when_service_fails(tc_server, net_env):
    route = tc_server.route(SEARCH, TC / "search-GET-manufacturer.json")
    fresh = tc.search(manufacturer="Estes")
    files = _cache_files(net_env)
    assert len(files) == 1
    before = files[0].read_bytes()
    route.status, route.body = 500, b"down"
    with pytest.warns(UserWarning, match="using the cached copy"):
        cached = tc.search(manufacturer="Estes")
    assert cached == fresh
    assert files[0].read_bytes() == before            # failure did not touch the cache
    _no_temp_files(net_env)


def test_offline_mode_uses_only_the_cache(tc_server, net_env, monkeypatch):
    tc_server.route(SEARCH, TC / "search-GET-manufacturer.json")
    tc.search(manufacturer="Estes")
    n = len(tc_server.requests)
    monkeypatch.setenv("IRONBARK_OFFLINE", "1")
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        assert len(tc.search(manufacturer="Estes")) == 20
    assert len(tc_server.requests) == n                  # no request in offline mode
    with pytest.raises(NetworkError, match="offline mode and no cached copy"):
        tc.search(manufacturer="AeroTech")


def test_bad_endpoint_setting(net_env, monkeypatch):
    monkeypatch.setenv("IRONBARK_THRUSTCURVE_URL", "ftp://example")
    with pytest.raises(InputError, match="http"):
        tc.search(manufacturer="Estes")
