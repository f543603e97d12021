"""On-disk cache of built flight models (the symbolic Functions and their grid).

Building a :class:`~ironbark_opt.dynamics.model.FlightModel` (right-hand sides,
RK4 steps with common-subexpression elimination, the nominal flight that fixes
the RK4 grid) costs ~0.35 s; loading its serialised CasADi Functions ~0.06 s.
A model is stored under a key that changes whenever anything it depends on
changes: the pickled setup (vehicle, motor, aero tables, atmosphere, site),
the discretisation settings, the CasADi version and the source of every
``ironbark_opt`` module.  The key also names the model's compiled libraries
(:func:`~ironbark_opt.dynamics.integrator.compile_function`), so a cached
compiled model is found without generating its C code again.

Files: ``$IRONBARK_CACHE_DIR/models/<key>.pkl`` (written atomically; a file
that cannot be read is ignored and rebuilt); models and compiled libraries
together are kept under ``IRONBARK_CACHE_MAX_MB`` (least recently used deleted
first, :mod:`~ironbark_opt.dynamics.cache_limit`).  ``IRONBARK_MODEL_CACHE=0``
switches the cache off.
"""
from __future__ import annotations

import hashlib
import os
import pickle
import pickletools
from pathlib import Path
from typing import Mapping

import casadi as ca

from ironbark_opt.dynamics import cache_limit
from ironbark_opt.dynamics.integrator import cache_root

_FORMAT = 1
_SOURCE_DIGEST: list[str] = []


def source_digest() -> str:
    """SHA-256 of every ``ironbark_opt`` source file (computed once per process)."""
    if not _SOURCE_DIGEST:
        root = Path(__file__).resolve().parents[1]
        h = hashlib.sha256()
        for path in sorted(root.rglob("*.py")):
            h.update(str(path.relative_to(root)).encode())
            h.update(path.read_bytes())
        _SOURCE_DIGEST.append(h.hexdigest())
    return _SOURCE_DIGEST[0]


def library_key(model, *names) -> str | None:
    """Name (24 hex digits) of a compiled library of ``model`` on its current RK4 grid:
    a hash of the model's key, its discretisation and ``names`` (what tells its
    libraries apart: nothing for the model's own, else the Function's name and
    options); None when the model has no key (not cacheable)."""
    if model._key is None:
        return None
    return hashlib.sha256(repr((model._key, model.discretisation(), *names)).encode()).hexdigest()[:24]


def model_key(setup, steps) -> str | None:
    """The cache key of ``setup`` flown with ``steps``, or None (not cacheable)."""
    if os.environ.get("IRONBARK_MODEL_CACHE", "1") == "0":
        return None
    try:
        # optimize(): drop the pickle's memo bookkeeping, which depends on which
        # objects happen to be shared in memory, not on the data
        data = pickletools.optimize(pickle.dumps(setup, protocol=pickle.HIGHEST_PROTOCOL))
    except (pickle.PicklingError, TypeError, AttributeError):
        return None
    h = hashlib.sha256(data)
    h.update(repr((_FORMAT, steps, ca.__version__, source_digest())).encode())
    return h.hexdigest()[:24]


def _path(key: str) -> Path:
    return cache_root() / "models" / f"{key}.pkl"


def load(key: str | None, *, lazy: bool = False) -> Mapping | None:
    """The stored model ``{name: Function or value}``, or None.  ``lazy``: a
    :class:`LazyFunctions` (each Function deserialised when first read)."""
    if key is None:
        return None
    try:
        with open(_path(key), "rb") as fh:
            doc = pickle.load(fh)
        cache_limit.touch(_path(key))              # used now: the last the size limit deletes
        if lazy:
            return LazyFunctions(doc)
        return {k: ca.Function.deserialize(v) if isinstance(v, str) else v for k, v in doc.items()}
    except Exception:          # noqa: BLE001 - missing, truncated or foreign file: rebuild
        return None


class LazyFunctions(Mapping):
    """A stored model whose Functions are deserialised on first access (each once)."""

    def __init__(self, doc: dict):
        self._doc, self._done = doc, {}

    def __getitem__(self, name):
        if name not in self._done:
            value = self._doc[name]
            self._done[name] = ca.Function.deserialize(value) if isinstance(value, str) else value
        return self._done[name]

    def __iter__(self):
        return iter(self._doc)

    def __len__(self) -> int:
        return len(self._doc)


class PhaseView(Mapping):
    """``{phase: model[prefix + phase]}`` for rail, boost and coast, read when asked for."""

    PHASES = ("rail", "boost", "coast")

    def __init__(self, model: Mapping, prefix: str):
        self._model, self._prefix = model, prefix

    def __getitem__(self, phase):
        if phase not in self.PHASES:
            raise KeyError(phase)
        return self._model[self._prefix + phase]

    def __contains__(self, phase) -> bool:
        return phase in self.PHASES

    def __iter__(self):
        return iter(self.PHASES)

    def __len__(self) -> int:
        return len(self.PHASES)


def store(key: str | None, items: dict) -> None:
    """Write ``items`` (Functions serialised, other values pickled) atomically."""
    if key is None:
        return
    path = _path(key)
    try:
        path.parent.mkdir(parents=True, exist_ok=True)
        doc = {k: v.serialize() if isinstance(v, ca.Function) else v for k, v in items.items()}
        tmp = path.with_name(f".{path.name}.{os.getpid()}.tmp")
        with open(tmp, "wb") as fh:
            pickle.dump(doc, fh, protocol=pickle.HIGHEST_PROTOCOL)
        os.replace(tmp, path)
    except OSError:
        return                 # a read-only cache only costs the next build
    cache_limit.prune(cache_root(), keep=path)


def compile_detached(model) -> None:
    """Compile ``model``'s libraries for the next run in a detached, lowest-priority
    process (:func:`~ironbark_opt.dynamics.integrator.run_detached`) that rebuilds the
    model from its pickled constructor arguments (the built Functions come from this
    cache) and generates and compiles there: the process that asks pays ~1 ms (the
    pickle), not the C code generation (~0.1 s) nor the compiler.  At most one such
    compile per model library key runs at a time, within the machine-wide cap on
    background compiles (no free slot: it gives up, the next run starts another;
    :func:`~ironbark_opt.dynamics.integrator.run_detached`); without a compiler, nothing."""
    from ironbark_opt.dynamics.integrator import _claim, compiler_available, default_cache_dir, run_detached
    key = model._library_key()
    if key is None or not compiler_available():
        return
    pending = default_cache_dir() / f".model_{key}.c"            # the marker benchmarks wait for
    if not _claim(pending):
        return
    spec = pending.with_name(f".model_{key}.{os.getpid()}.pkl")
    try:
        with open(spec, "wb") as fh:
            pickle.dump((type(model).__module__, type(model).__qualname__, model._rebuild_args(), model._key,
                         model.discretisation()), fh, protocol=pickle.HIGHEST_PROTOCOL)
    except (OSError, pickle.PicklingError, TypeError, AttributeError):
        spec.unlink(missing_ok=True)
        pending.unlink(missing_ok=True)
        return
    run_detached("ironbark_opt.dynamics.model_cache:_compile_model", [str(spec)], [spec, pending])


def _compile_model(spec: str) -> None:
    """:func:`compile_detached`'s child: rebuild the model (VM), give it the asking
    process's key (the libraries' names) and compile its libraries."""
    import importlib
    with open(spec, "rb") as fh:
        module, name, args, key, discretisation = pickle.load(fh)
    model = getattr(importlib.import_module(module), name)(*args, jit=False)
    model._key = key
    model._compile_libraries(discretisation)
