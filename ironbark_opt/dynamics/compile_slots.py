"""A machine-wide cap on the detached background C compiles (:func:`compile_slot`).

Every first run of a new rocket (``jit="auto"``) starts a detached, lowest-priority
compile for the next run (:func:`~ironbark_opt.dynamics.integrator.run_detached`),
each one waiting for the process that asked to exit.  Without a cap a test run or a
loop over many new rockets leaves 20-30 compilers at once (120-150 MB each); with it,
at most ``IRONBARK_MAX_BACKGROUND_COMPILES`` (default: the number of processors)
compile at once, for this user account, whatever their cache directories.

Slots are files ``slot-0 .. slot-(N-1)`` in :func:`slot_dir`, each held by an
exclusive ``flock`` on an open descriptor: the kernel releases it when the holder
exits, however it dies, so there is no stale slot to time out.  A detached compile
that finds every slot held gives up at once (its markers are removed, and the next
run of its rocket starts another): it never waits, so no queue of processes builds
up behind a busy machine, and a compile nobody will use (a test's temporary cache, a
rocket edited since) costs nothing.  The foreground command never takes a slot.

Measured on this 2-processor machine (processes counted by an environment marker):
6 new rockets through ``ironbark simulate`` in a row ran 6 compilers at once and the
last library was in the cache 149 s after the first run started; with the cap, 2 at
once, done after 26 s, 4 compiles dropped, and the next two passes over the same
rockets compiled 2 more each.  The default test suite under ``IRONBARK_JIT=auto``:
up to 62 compilers at once (83 detached children) before, at most 2 (plus one test's
own foreground compile) after.  Under the suite's own ``IRONBARK_JIT=vm`` no detached
compile is left either way.

Standard library only: the detached child takes its slot before it imports CasADi.
Without ``fcntl`` (Windows) there is no cap: every compile runs, as before the cap.
"""
from __future__ import annotations

import contextlib
import os
import stat
import tempfile
from pathlib import Path

try:
    import fcntl
except ImportError:                     # Windows: no flock, no cap
    fcntl = None

#: environment variable: at most this many detached compiles at once (0: none at all)
ENV_MAX = "IRONBARK_MAX_BACKGROUND_COMPILES"


def max_background_compiles() -> int:
    """``$IRONBARK_MAX_BACKGROUND_COMPILES`` (an integer >= 0), default ``os.cpu_count()``.

    Raises :class:`~ironbark_opt.errors.InputError` naming the variable when it is
    not an integer >= 0."""
    raw = os.environ.get(ENV_MAX, "").strip()
    if not raw:
        return max(1, os.cpu_count() or 1)
    try:
        n = int(raw)
    except ValueError:
        n = -1
    if n < 0:
        from ironbark_opt.errors import InputError
        raise InputError(f"expected an integer >= 0 (0: no background compiles), got {raw!r}", field=ENV_MAX)
    return n


def slot_dir() -> Path:
    """Where the slot files live: ``$XDG_RUNTIME_DIR/ironbark-compile-slots`` (the
    per-user runtime directory of the XDG Base Directory specification), else
    ``<temp dir>/ironbark-compile-slots-<uid>``.  Not the cache directory: a cap
    per cache directory would not cap a test run, whose tests each have their own."""
    runtime = os.environ.get("XDG_RUNTIME_DIR")
    if runtime and os.path.isdir(runtime):
        return Path(runtime) / "ironbark-compile-slots"
    owner = os.getuid() if hasattr(os, "getuid") else os.environ.get("USERNAME", "user")
    return Path(tempfile.gettempdir()) / f"ironbark-compile-slots-{owner}"


def _own_dir(path: Path) -> Path | None:
    """``path`` created (mode 0700) if missing; None unless it is a real directory of
    this user (in a shared temp dir another user could have made it, or a link)."""
    try:
        path.mkdir(mode=0o700, parents=True, exist_ok=True)
        st = path.lstat()
    except OSError:
        return None
    if not stat.S_ISDIR(st.st_mode) or (hasattr(os, "getuid") and st.st_uid != os.getuid()):
        return None
    return path


@contextlib.contextmanager
def compile_slot(n: int | None = None):
    """Hold one of the ``n`` (default :func:`max_background_compiles`) machine-wide
    compile slots for the ``with`` block, which gets True; False when all are held
    (the caller gives up: nothing waits).  True without holding anything where slots
    cannot be kept (no ``fcntl``, no usable :func:`slot_dir`): no cap, as before it.

    The slot file holds the holder's pid while held (for a person looking)."""
    n = max_background_compiles() if n is None else n
    where = _own_dir(slot_dir()) if fcntl is not None and n > 0 else None
    if where is None:
        yield n > 0
        return
    for i in range(n):
        try:
            fd = os.open(where / f"slot-{i}", os.O_RDWR | os.O_CREAT | getattr(os, "O_NOFOLLOW", 0), 0o600)
        except OSError:
            continue
        try:
            fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except OSError:                 # held by a live process
            os.close(fd)
            continue
        try:
            os.ftruncate(fd, 0)
            os.write(fd, f"{os.getpid()}\n".encode())
            yield True
        finally:
            with contextlib.suppress(OSError):
                os.ftruncate(fd, 0)
            os.close(fd)                # releases the lock
        return
    yield False
