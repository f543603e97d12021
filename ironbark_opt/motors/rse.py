"""RockSim ``.rse`` thrust-curve files (XML; numeric-only file I/O).

``<engine-database><engine-list><engine code= mfg= dia= len= delays=
propWt= initWt= exitDia= ...><data><eng-data t= f= m= cg=/>...`` with
lengths in mm, masses in g, time in s, thrust in N.  Several engines per file
are allowed.

The mass column ``m`` is ambiguous: ThrustCurve.org writes (and reads) it as
the *propellant* mass, OpenRocket reads it as the *total* motor mass when
``auto-calc-mass="0"``.  Decision: the first row decides.  If ``m[0]`` is
within 1 % of ``propWt`` it is propellant mass; if within 1 % of ``initWt``
it is total mass (then propellant = m[0] - m[-1], dry = m[-1]); a column of
zeros is ignored; anything else is an error naming the row.  Either way the
mass *history* is not used: propellant burns in proportion to delivered
impulse (see :mod:`ironbark_opt.motors.solid`), which is also how
ThrustCurve.org fills the column.

The ``cg`` column [mm from the motor's forward end, RockSim convention] is
used only when ``auto-calc-cg="0"``: the first row is the loaded motor's CG,
the last row the empty motor's CG, from which the dry and propellant CGs
forward of the nozzle exit follow.  ``exitDia`` > 0 gives the nozzle exit
area.  Delays are comma-separated (``P`` = plugged, >= 100 s placeholders
dropped, as for ``.eng``).
"""
from __future__ import annotations

import math
import xml.parsers.expat
from os import PathLike
from pathlib import Path

import numpy as np

from ironbark_opt.errors import InputError
from ironbark_opt.motors.rasp import build_motor, parse_delays, parse_number, read_text
from ironbark_opt.motors.solid import SolidMotor

#: Relative tolerance for recognising what the first ``m`` value is.
MASS_MATCH_TOLERANCE = 0.01


def _parse_xml(text: str, src: Path) -> list[dict]:
    """Engines as dicts: attrs, line, rows [(line, attrs)]."""
    engines: list[dict] = []
    stack: list[str] = []
    parser = xml.parsers.expat.ParserCreate()

    def start(name, attrs):
        line = parser.CurrentLineNumber
        if name == "engine":
            engines.append({"attrs": attrs, "line": line, "rows": []})
        elif name == "eng-data":
            if not engines or "engine" not in stack:
                raise InputError("<eng-data> outside an <engine>", source=src, line=line)
            engines[-1]["rows"].append((line, attrs))
        stack.append(name)

    def end(name):
        stack.pop()

    parser.StartElementHandler = start
    parser.EndElementHandler = end
    try:
        parser.Parse(text, True)
    except xml.parsers.expat.ExpatError as exc:
        raise InputError(f"not well-formed XML: {xml.parsers.expat.ErrorString(exc.code)}",
                         source=src, line=exc.lineno) from None
    return engines


def _attr(attrs, key, *, src, line, required=True, default=None):
    if key not in attrs or attrs[key].strip() == "":
        if required:
            raise InputError(f"missing attribute '{key}'", source=src, line=line, field=key)
        return default
    return parse_number(attrs[key], source=src, line=line, field=key)


def read_rse(path: str | PathLike, **overrides) -> list[SolidMotor]:
    """All engines of a RockSim ``.rse`` file. Numeric-only.

    Parameters
    ----------
    path : str or path-like
    **overrides
        ``SolidMotor`` fields (SI units) applied to every engine.

    Returns
    -------
    list of SolidMotor, in file order.

    Raises
    ------
    InputError
        Naming file, line and attribute: malformed XML, missing attributes,
        non-numeric values, decreasing times, an ambiguous mass column.
    """
    src = Path(path)
    engines = _parse_xml(read_text(path), src)
    if not engines:
        raise InputError("no <engine> element in file", source=src)
    return [_engine(src, e, overrides) for e in engines]


def _engine(src: Path, eng: dict, overrides: dict) -> SolidMotor:
    a, hline = eng["attrs"], eng["line"]
    code = a.get("code", "").strip()
    if not code:
        raise InputError("missing attribute 'code'", source=src, line=hline, field="code")
    rows = []
    for line, r in eng["rows"]:
        t = _attr(r, "t", src=src, line=line)
        f = _attr(r, "f", src=src, line=line)
        m = _attr(r, "m", src=src, line=line, required=False, default=0.0)
        cg = _attr(r, "cg", src=src, line=line, required=False, default=math.nan)
        if rows and t < rows[-1][1]:
            raise InputError(f"time decreases: t={t} s after {rows[-1][1]} s", source=src,
                             line=line, field="t")
        if t < 0 or f < 0:
            raise InputError("negative time or thrust", source=src, line=line,
                             field="t" if t < 0 else "f")
        rows.append((line, t, f, m, cg))
    if not rows:
        raise InputError(f"engine {code!r} has no <eng-data> rows", source=src, line=hline,
                         field="data")
    t = np.array([r[1] for r in rows])
    F = np.array([r[2] for r in rows])
    m_g = np.array([r[3] for r in rows])
    length = _attr(a, "len", src=src, line=hline) / 1000.0
    fields = dict(designation=code, manufacturer=a.get("mfg", "").strip(),
                  diameter=_attr(a, "dia", src=src, line=hline) / 1000.0, length=length,
                  delays=parse_delays(a.get("delays", ""), source=src, line=hline,
                                      separators=",-"))
    fields.update(_masses(src, hline, a, rows, m_g, overrides))
    exit_dia = _attr(a, "exitDia", src=src, line=hline, required=False, default=0.0)
    if exit_dia > 0:
        fields["nozzle_exit_area"] = math.pi * (exit_dia / 2000.0) ** 2
    if a.get("auto-calc-cg", "1").strip() == "0":
        fields.update(_cgs(src, rows, fields, length))
    return build_motor(t, F, fields, overrides, source=src, line=hline)


def _masses(src, hline, a, rows, m_g, overrides) -> dict:
    prop = _attr(a, "propWt", src=src, line=hline, required=False, default=0.0)
    init = _attr(a, "initWt", src=src, line=hline, required=False, default=0.0)
    m0 = m_g[0]

    def near(x, ref):
        return ref > 0 and abs(x - ref) <= MASS_MATCH_TOLERANCE * ref

    if np.all(m_g == 0) or near(m0, prop):      # ThrustCurve.org: propellant mass
        if prop <= 0 or init <= prop:
            if {"propellant_mass", "dry_mass"} <= set(overrides):
                return {}
            raise InputError(f"need propWt > 0 and initWt > propWt, got propWt={prop:g} g, "
                             f"initWt={init:g} g", source=src, line=hline, field="propWt")
        return dict(propellant_mass=prop / 1000.0, dry_mass=(init - prop) / 1000.0)
    if near(m0, init):                           # OpenRocket: total mass
        dry, mp = m_g[-1], m0 - m_g[-1]
        if dry <= 0 or mp <= 0:
            raise InputError(f"mass column read as total mass (m[0] = initWt = {init:g} g) "
                             f"must fall to the dry mass, but ends at {dry:g} g",
                             source=src, line=rows[-1][0], field="m")
        return dict(propellant_mass=mp / 1000.0, dry_mass=dry / 1000.0)
    raise InputError(f"mass column starts at m = {m0:g} g, which is neither propWt "
                     f"({prop:g} g, propellant mass) nor initWt ({init:g} g, total mass)",
                     source=src, line=rows[0][0], field="m")


def _cgs(src, rows, fields, length) -> dict:
    cg0, cg1 = rows[0][4], rows[-1][4]
    if not (math.isfinite(cg0) and math.isfinite(cg1)):
        raise InputError("auto-calc-cg=\"0\" but the cg column is missing", source=src,
                         line=rows[0][0], field="cg")
    md, mp = fields.get("dry_mass"), fields.get("propellant_mass")
    x_total = length - cg0 / 1000.0     # forward of the nozzle exit
    x_dry = length - cg1 / 1000.0
    out = {"dry_cg": x_dry}
    if md and mp:
        out["propellant_cg"] = ((md + mp) * x_total - md * x_dry) / mp
    return out
