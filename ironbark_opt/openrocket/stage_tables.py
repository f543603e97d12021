"""The flight configurations of a serial multi-stage OpenRocket design and
their aerodynamic tables (numeric-only).

A serial stack of N stages flies N configurations: the whole stack before the
first separation, then after each separation the stages still above it, down to
the top stage alone (the sustainer).  Each has its own outer shape, so each
gets its own panel table (``ironbark aero build``, :func:`configurations`),
named and tagged by its role: ``stack`` (every stage), ``sustainer`` (the top
stage alone) and ``upper<n>`` (the top ``n`` stages, for N > 2).  A staged
flight (:func:`ironbark_opt.openrocket.staging.staged_setup`) flies the table
whose metadata names its configuration (:func:`tables_by_configuration`).  A
separated lower stage falling on its own keeps the empirical estimate of its
geometry (no table is built for it).  A rocket TOML with a ``[[stage]]`` table
has the same two configurations
(:func:`ironbark_opt.staged_vehicle.stage_configurations_from_toml`).
"""
from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

from ironbark_opt.errors import InputError

#: metadata keys an ``aero build`` table of one configuration carries
CONFIG_KEY = "stage_configuration"
STAGES_KEY = "stage_names"
LENGTH_KEY = "stage_configuration_length_m"
#: a table's configuration length must match the design's to this [m]
LENGTH_TOL_M = 1e-3


@dataclass(frozen=True)
class StageConfiguration:
    """One flight configuration of a serial multi-stage rocket.

    Parameters
    ----------
    key : str
        ``stack``, ``sustainer`` or ``upper<n>`` (see the module docstring).
    stages : tuple of str
        The names of its stages, top first.
    rocket : Rocket
        Its geometry, x from the stack's nose tip (the top stage's).
    """

    key: str
    stages: tuple
    rocket: object

    def metadata(self) -> dict:
        """What a table of this configuration records about it."""
        return {CONFIG_KEY: self.key, STAGES_KEY: list(self.stages),
                LENGTH_KEY: float(self.rocket.length())}


def configuration_key(n_stages: int, n_total: int) -> str:
    """The role of the configuration of the top ``n_stages`` of ``n_total`` stages."""
    if n_stages == n_total:
        return "stack"
    return "sustainer" if n_stages == 1 else f"upper{n_stages}"


def configurations(doc) -> list[StageConfiguration]:
    """Every flight configuration of a serial multi-stage :class:`OrkDocument`,
    the stack first, then one per separation (top ``n`` stages, ``n`` falling)."""
    from ironbark_opt.openrocket.build import geometry
    from ironbark_opt.openrocket.staging import _stage_doc

    n = len(doc.rocket.stages)
    out = []
    for k in range(n, 0, -1):
        sub = _stage_doc(doc, range(k))
        out.append(StageConfiguration(configuration_key(k, n), tuple(s.name for s in sub.rocket.stages),
                                      geometry(sub)))
    return out


def tables_by_configuration(doc, tables, known=None) -> dict[str, Path]:
    """Each table of ``tables`` (paths of ``aero build`` tables, any order) keyed
    by the configuration of ``doc`` (an OrkDocument, or with ``known`` the
    configurations of another file and ``doc`` its path) its metadata names.  A
    configuration without a table given takes the one ``aero build`` wrote beside a
    given one (``STEM-stack.csv`` -> ``STEM-sustainer.csv``), checked the same way.

    Raises InputError for a table built for no configuration of this design
    (a single-stage table, another rocket's stages), two tables of one
    configuration, or a configuration of the staged flight without a table.
    """
    from ironbark_opt.aero.table import AeroTable

    if known is None:
        known, doc = configurations(doc), doc.path
    known = {c.key: c for c in known}
    doc = Path(doc)
    found: dict[str, Path] = {}

    def check(path) -> str:
        meta = AeroTable.load(path).metadata
        key, names = meta.get(CONFIG_KEY), meta.get(STAGES_KEY)
        if key is None:
            raise InputError(f"not the table of a stage configuration (no '{CONFIG_KEY}' in its metadata): "
                             f"'ironbark aero build {doc.name}' writes one table per configuration "
                             f"({', '.join(known)}); give each with --table", source=path, field="table")
        conf = known.get(key)
        if conf is None or list(conf.stages) != list(names or []):
            raise InputError(f"built for configuration '{key}' (stages {', '.join(names or [])}), which "
                             f"{doc.name} does not have; its configurations: "
                             + "; ".join(f"{c.key} ({', '.join(c.stages)})" for c in known.values()),
                             source=path, field="table")
        length = meta.get(LENGTH_KEY)
        if length is None or abs(float(length) - conf.rocket.length()) > LENGTH_TOL_M:
            raise InputError(f"built for a '{key}' {length} m long; {doc.name}'s is "
                             f"{conf.rocket.length():.4f} m (the design changed? build its tables again)",
                             source=path, field="table")
        if key in found:
            raise InputError(f"two tables of configuration '{key}': {found[key]} and {path}", source=path,
                             field="table")
        found[key] = Path(path)
        return key

    given = [(Path(p), check(p)) for p in tables]
    # a configuration not given: the table 'aero build' wrote for it beside a given one
    # (STEM-stack.csv -> STEM-sustainer.csv), as a parallel-booster stack's table finds its own
    for path, key in given:
        stem = path.name[:-len(path.suffix)] if path.suffix else path.name
        if not stem.endswith(f"-{key}"):
            continue
        for other in known:
            sibling = path.with_name(f"{stem[:-len(key)]}{other}{path.suffix}")
            if other not in found and sibling.is_file():
                check(sibling)
    missing = [k for k in ("stack", "sustainer") if k in known and k not in found]
    if missing:
        raise InputError(f"no table for configuration {' and '.join(repr(k) for k in missing)}: a staged "
                         f"flight flies the table of each configuration (or none: the empirical estimate); "
                         f"give each with --table", source=doc, field="table")
    return found
