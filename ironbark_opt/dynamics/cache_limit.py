"""A size limit on the on-disk caches of built flight models and compiled libraries.

Every model is stored under a key that includes the source of every ``ironbark_opt``
module (:mod:`~ironbark_opt.dynamics.model_cache`), so each upgrade, and each new
rocket, adds files (a model 0.1-22 MB, a library ~1 MB) and nothing removed them:
a developer's cache reached 4.9 GB in two days.  After each model is stored, the
least recently used models (``models/*.pkl``) and libraries (``jit/*.so``) are
deleted until both together fit in the limit; loading a model or a library marks
it used (its modification time), so what a team flies every day stays.

The limit is ``IRONBARK_CACHE_MAX_MB`` [MiB] (default 2048; ``0`` = no limit).
Files being written (dot files: temporaries, pending-compile markers) are never
counted nor deleted, nor is the file just written.  Deleting a library another
process has loaded is safe on POSIX (its mapping stays valid); where the system
refuses (Windows), the file is skipped.
"""
from __future__ import annotations

import os
from pathlib import Path

from ironbark_opt.errors import InputError

#: default limit [MiB]
DEFAULT_MAX_MB = 2048.0
ENV = "IRONBARK_CACHE_MAX_MB"
#: the cached files the limit applies to: (sub-directory of the cache root, suffix)
KINDS = (("models", ".pkl"), ("jit", ".so"))


def max_bytes() -> float | None:
    """The limit [bytes] from ``IRONBARK_CACHE_MAX_MB``, or None (no limit)."""
    raw = os.environ.get(ENV, "").strip()
    if not raw:
        return DEFAULT_MAX_MB * 2 ** 20
    try:
        mb = float(raw)
    except ValueError:
        mb = float("nan")
    if not mb >= 0 or mb == float("inf"):
        raise InputError(f"expected a size in MiB >= 0 (0 = no limit), got {raw!r}",
                         source="environment", field=ENV)
    return None if mb == 0 else mb * 2 ** 20


def touch(path: Path) -> None:
    """Mark a cached file as used now (its modification time), if it exists."""
    try:
        os.utime(path)
    except OSError:
        pass


def cached_files(root: Path) -> list[tuple[float, int, Path]]:
    """(modification time [s], size [bytes], path) of every limited file under ``root``."""
    out = []
    for sub, suffix in KINDS:
        try:
            entries = list(os.scandir(root / sub))
        except OSError:
            continue
        for e in entries:
            if e.name.startswith(".") or not e.name.endswith(suffix):
                continue
            try:
                st = e.stat()
            except OSError:
                continue
            out.append((st.st_mtime, st.st_size, Path(e.path)))
    return out


def prune(root: Path, keep: Path | None = None) -> list[Path]:
    """Delete the least recently used limited files under ``root`` (never ``keep``) until
    the rest fit in :func:`max_bytes`; returns the deleted paths (oldest first)."""
    limit = max_bytes()
    if limit is None:
        return []
    files = cached_files(root)
    total = sum(size for _, size, _ in files)
    deleted = []
    keep = None if keep is None else Path(keep).resolve()
    for _, size, path in sorted(files, key=lambda f: f[0]):
        if total <= limit:
            break
        if keep is not None and path.resolve() == keep:
            continue
        try:
            path.unlink()
        except OSError:
            continue
        total -= size
        deleted.append(path)
    return deleted
