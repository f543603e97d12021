"""The size limit on cached models and libraries (ironbark_opt.dynamics.cache_limit):
least recently used deleted first, in-flight files and the file just written kept,
a bad limit named, and a stored / loaded model marked as used."""
import os

import pytest

from ironbark_opt.dynamics import cache_limit, model_cache
from ironbark_opt.errors import InputError

MIB = 2 ** 20


def _file(path, size, mtime):
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_bytes(b"x" * size)
    os.utime(path, (mtime, mtime))
    return path


@pytest.fixture
def root(tmp_path, monkeypatch):
    monkeypatch.setenv("IRONBARK_CACHE_DIR", str(tmp_path))
    return tmp_path


def test_least_recently_used_go_first_until_under_the_limit(root, monkeypatch):
    monkeypatch.setenv(cache_limit.ENV, "2.5")                     # 2.5 MiB
    a = _file(root / "models" / "a.pkl", MIB, 1000)
    b = _file(root / "jit" / "model_b.so", MIB, 2000)
    c = _file(root / "models" / "c.pkl", MIB, 3000)
    d = _file(root / "jit" / "model_d.so", MIB, 4000)
    marker = _file(root / "jit" / ".model_e.c", 3 * MIB, 500)       # a pending compile: never counted
    tmp = _file(root / "models" / ".f.pkl.12.tmp", 3 * MIB, 500)    # being written
    other = _file(root / "ork-aero" / "x.csv", 3 * MIB, 500)        # not a limited kind
    deleted = cache_limit.prune(root)
    # 4 MiB counted, limit 2.5 MiB: the two oldest go, 2 MiB stay
    assert deleted == [a, b]
    assert not a.exists() and not b.exists()
    assert c.exists() and d.exists() and marker.exists() and tmp.exists() and other.exists()


def test_the_file_just_written_is_kept(root, monkeypatch):
    monkeypatch.setenv(cache_limit.ENV, "1.5")
    new = _file(root / "models" / "new.pkl", 2 * MIB, 1000)          # oldest mtime, alone above the limit
    old = _file(root / "models" / "old.pkl", MIB, 2000)
    assert cache_limit.prune(root, keep=new) == [old]
    assert new.exists()


def test_no_limit_and_default(root, monkeypatch):
    _file(root / "models" / "a.pkl", MIB, 1000)
    monkeypatch.setenv(cache_limit.ENV, "0")
    assert cache_limit.max_bytes() is None and cache_limit.prune(root) == []
    monkeypatch.delenv(cache_limit.ENV)
    assert cache_limit.max_bytes() == 2048 * MIB


@pytest.mark.parametrize("raw", ["lots", "-1", "nan", "inf"])
def test_bad_limit_is_named(root, monkeypatch, raw):
    monkeypatch.setenv(cache_limit.ENV, raw)
    with pytest.raises(InputError, match="IRONBARK_CACHE_MAX_MB.*MiB >= 0"):
        cache_limit.max_bytes()


def test_store_prunes_and_load_marks_used(root, monkeypatch):
    monkeypatch.setenv(cache_limit.ENV, "0.001")                   # ~1 kB: every store evicts the rest
    old = _file(root / "models" / "0123456789abcdef01234567.pkl", 4096, 1000)
    model_cache.store("aaaaaaaaaaaaaaaaaaaaaaaa", {"n": 1})
    assert not old.exists()
    path = root / "models" / "aaaaaaaaaaaaaaaaaaaaaaaa.pkl"
    assert path.exists()
    os.utime(path, (1000, 1000))
    assert model_cache.load("aaaaaaaaaaaaaaaaaaaaaaaa") == {"n": 1}
    assert path.stat().st_mtime > 1e9                               # touched on load
