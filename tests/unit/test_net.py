"""net.py (endpoints, settings, cache, atomic writes), config.py and site presets."""
from __future__ import annotations

import math
import os

import pytest

from ironbark_opt import config, net
from ironbark_opt.atmosphere import sites
from ironbark_opt.errors import InputError


@pytest.fixture
def cfg(tmp_path, monkeypatch):
    path = tmp_path / "config.toml"
    monkeypatch.setenv("IRONBARK_CONFIG", str(path))
    for env, _ in net.ENDPOINTS.values():
        monkeypatch.delenv(env, raising=False)
    for var in ("IRONBARK_HTTP_TIMEOUT", "IRONBARK_HTTP_RETRIES", "IRONBARK_HTTP_BACKOFF",
                "IRONBARK_OFFLINE"):
        monkeypatch.delenv(var, raising=False)
    return path


def test_endpoint_precedence(cfg, monkeypatch):
    assert net.endpoint("thrustcurve") == "https://www.thrustcurve.org/api/v1"
    cfg.write_text('[endpoints]\nthrustcurve = "http://mirror.example/api/v1/"\n')
    assert net.endpoint("thrustcurve") == "http://mirror.example/api/v1"
    monkeypatch.setenv("IRONBARK_THRUSTCURVE_URL", "http://127.0.0.1:1/x")
    assert net.endpoint("thrustcurve") == "http://127.0.0.1:1/x"
    with pytest.raises(InputError, match="unknown endpoint"):
        net.endpoint("nope")


def test_every_endpoint_has_an_env_variable():
    envs = [env for env, _ in net.ENDPOINTS.values()]
    for required in ("IRONBARK_THRUSTCURVE_URL", "IRONBARK_THREDDS_URL", "IRONBARK_NOMADS_URL",
                     "IRONBARK_UWYO_URL"):
        assert required in envs


def test_failure_hint_names_the_endpoints_variable(cfg, monkeypatch):
    """A failed request names the variable of the endpoint it went to (the longest
    matching base); with several variables on that base none is named (a THREDDS failure
    behind one local mirror said 'set IRONBARK_THRUSTCURVE_URL', the first in the table)."""
    monkeypatch.setenv("IRONBARK_THRUSTCURVE_URL", "http://127.0.0.1:9")
    monkeypatch.setenv("IRONBARK_THREDDS_URL", "http://127.0.0.1:9")
    assert net._env_hint("http://127.0.0.1:9/ncss/x") == \
        "the IRONBARK_*_URL variable of this source (2 point at this server)"
    monkeypatch.setenv("IRONBARK_THREDDS_URL", "http://127.0.0.1:9/thredds")
    assert net._env_hint("http://127.0.0.1:9/thredds/ncss/x") == "IRONBARK_THREDDS_URL"
    assert net._env_hint("https://elsewhere.example/x") == "the IRONBARK_*_URL variables"


def test_settings_from_config_and_env(cfg, monkeypatch):
    assert net.settings() == net.NetSettings()
    cfg.write_text("[network]\ntimeout_s = 5\nretries = 4\nbackoff_s = 0.5\noffline = true\n")
    assert net.settings() == net.NetSettings(5.0, 4, 0.5, True)
    monkeypatch.setenv("IRONBARK_OFFLINE", "0")
    monkeypatch.setenv("IRONBARK_HTTP_TIMEOUT", "1.5")
    s = net.settings()
    assert s.offline is False and s.timeout == 1.5
    monkeypatch.setenv("IRONBARK_HTTP_RETRIES", "many")
    with pytest.raises(InputError, match="network"):
        net.settings()


def test_invalid_config_names_file_and_line(cfg):
    cfg.write_text('[network]\ntimeout_s = 5\nretries = = 2\n')
    with pytest.raises(InputError) as err:
        config.load()
    assert str(cfg) in str(err.value) and err.value.line == 3
    cfg.write_text('sites = 3\n')
    with pytest.raises(InputError, match="expected a table"):
        config.load()


def test_cache_dir(monkeypatch, tmp_path):
    monkeypatch.setenv("IRONBARK_CACHE_DIR", str(tmp_path / "c"))
    assert net.cache_dir() == tmp_path / "c"
    monkeypatch.delenv("IRONBARK_CACHE_DIR")
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path / "xdg"))
    if os.name == "posix" and not os.uname().sysname == "Darwin":
        assert net.cache_dir() == tmp_path / "xdg" / "ironbark"


def test_cache_key_is_stable_and_distinguishes_requests():
    a = net.cache_key("http://h/x", {"b": 2, "a": 1})
    assert a == net.cache_key("http://h/x", {"a": 1, "b": 2})
    assert a != net.cache_key("http://h/x", {"a": 1, "b": 3})
    assert a != net.cache_key("http://h/x", {"a": 1, "b": 2}, byte_range=(0, 9))
    assert net.cache_key("http://h/x", json_body={"m": [1]}) != net.cache_key("http://h/x")
    # NCSS does not care about the order of repeated var= parameters:
    assert net.cache_key("u", {"var": ["a", "b"]}) == net.cache_key("u", {"var": ["b", "a"]})
    assert net.cache_key("u", {"var": ["a"]}) != net.cache_key("u", {"var": ["a", "b"]})


def test_write_atomic_replaces_whole_file_and_cleans_up(tmp_path):
    path = tmp_path / "d" / "f.bin"
    net.write_atomic(path, b"old")
    net.write_atomic(path, b"new contents")
    assert path.read_bytes() == b"new contents"
    assert [p.name for p in path.parent.iterdir()] == ["f.bin"]


def test_write_atomic_failure_leaves_old_file(tmp_path, monkeypatch):
    path = tmp_path / "f.bin"
    net.write_atomic(path, b"old")

    def boom(src, dst):
        raise OSError("disk full")
    monkeypatch.setattr(os, "replace", boom)
    with pytest.raises(OSError):
        net.write_atomic(path, b"new")
    assert path.read_bytes() == b"old"
    assert [p.name for p in tmp_path.iterdir()] == ["f.bin"]


def test_offline_without_cache(cfg, monkeypatch, tmp_path):
    monkeypatch.setenv("IRONBARK_CACHE_DIR", str(tmp_path / "c"))
    from ironbark_opt.errors import NetworkError
    with pytest.raises(NetworkError, match="offline mode and no cached copy of http://h/x"):
        net.fetch("Test", "http://h/x", offline=True)


def test_parse_json():
    assert net.parse_json("s")(b'{"a": 1}') == {"a": 1}
    with pytest.raises(InputError, match="not valid JSON"):
        net.parse_json("s")(b"{")


def test_spaceport_america_preset_and_aliases(cfg):
    sac = sites.get_site("Spaceport America")
    assert sites.get_site("sac") == sac
    assert sac.latitude_deg == pytest.approx(32.990254)
    assert sac.longitude_deg == pytest.approx(-106.974998)
    assert sac.elevation == pytest.approx(1400.0)
    assert sac.to_dict()["elevation_m"] == 1400.0


def test_site_from_user_config(cfg):
    cfg.write_text('[sites.home_field]\nlatitude_deg = 43.1\nlongitude_deg = 270.6\n'
                   'elevation_m = 260\ndescription = "Club field"\n')
    s = sites.get_site("home-field")
    assert s.latitude == pytest.approx(math.radians(43.1))
    assert s.longitude_deg == pytest.approx(-89.4)
    assert s.description == "Club field"
    cfg.write_text('[sites.bad]\nlatitude_deg = 95\nlongitude_deg = 0\nelevation_m = 0\n')
    with pytest.raises(InputError, match=r"sites.bad.latitude_deg"):
        sites.get_site("bad")
    cfg.write_text('[sites.bad]\nlatitude_deg = 45\nelevation_m = 0\n')
    with pytest.raises(InputError, match="missing longitude_deg"):
        sites.all_sites()


def test_unknown_site_says_how_to_add_one(cfg):
    with pytest.raises(InputError) as err:
        sites.get_site("atlantis")
    assert "[sites.atlantis]" in str(err.value) and str(cfg) in str(err.value)
