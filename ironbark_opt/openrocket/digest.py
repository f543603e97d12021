"""OpenRocket's motor digest of RASP (.eng) files, to verify a motor an .ork names (numeric-only).

The digest (OpenRocket ``MotorDigest``) is an MD5 over blocks, each fed as
big-endian 32-bit integers: the block's type order, its number of values,
then every value v rounded as round((v + eps sign v) * k + eps sign)
with eps = 1e-11 and k = 1000 for times [ms] and forces [mN], 10000 for
masses [0.1 g].  For a RASP motor (``RASPMotorLoader.createRASPMotor``)
the blocks are the time points (order 0), the loaded and empty masses
(``MASS_SPECIFIC``, order 1) and the thrust points (order 5), after the
curve is sorted by time and given a (0, 0) start point and a zero-thrust
end point (``AbstractMotorLoader.finalizeThrustCurve``).

RockSim (.rse) digests also depend on OpenRocket's treatment of the file's
mass/CG columns and are not reproduced: :func:`eng_digests` covers .eng only.
"""
from __future__ import annotations

import hashlib
import math
from pathlib import Path

from ironbark_opt.validate import is_float

_EPS = 1e-11
_TIME, _MASS_SPECIFIC, _FORCE = (0, 1000), (1, 10000), (5, 1000)


def _next(v: float) -> float:
    return v + math.copysign(_EPS, v) if v != 0.0 else v


def _java_round(v: float) -> int:
    return int(math.floor(v + 0.5))


def digest(blocks) -> str:
    """MD5 hex digest of ``[((order, multiplier), values), ...]`` (OpenRocket ``MotorDigest``)."""
    md = hashlib.md5()
    for (order, mult), values in blocks:
        ints = [_java_round(_next(_next(float(v)) * mult)) for v in values]
        md.update(order.to_bytes(4, "big"))
        md.update(len(ints).to_bytes(4, "big"))
        for x in ints:
            md.update((x & 0xFFFFFFFF).to_bytes(4, "big"))
    return md.hexdigest()


def rasp_digest(time, thrust, total_mass: float, propellant_mass: float) -> str:
    """Digest of one RASP motor: ``time`` [s], ``thrust`` [N], masses [kg] from its header."""
    pts = sorted(zip((float(t) for t in time), (float(f) for f in thrust)), key=lambda p: p[0])
    t = [p[0] for p in pts]
    f = [p[1] for p in pts]
    if abs(t[0]) > 1e-8:
        t.insert(0, 0.0)
        f.insert(0, 0.0)
    if len(t) > 1 and abs(t[0]) <= 1e-8 and abs(t[1]) <= 1e-8:
        del t[0], f[0]
    if abs(f[-1]) > 1e-8:
        t.append(t[-1])
        f.append(0.0)
    return digest([(_TIME, t), (_MASS_SPECIFIC, (total_mass, total_mass - propellant_mass)),
                   (_FORCE, f)])


def eng_digests(path) -> dict[str, str]:
    """``{designation: digest}`` of every motor in a RASP ``.eng`` file ({} if unreadable)."""
    try:
        lines = Path(path).read_text(encoding="latin-1").lstrip("\ufeff\u00ef\u00bb\u00bf").splitlines()
    except OSError:
        return {}
    out: dict[str, str] = {}
    header, time, thrust = None, [], []

    def flush():
        if header is not None and len(time) >= 2:
            try:
                out[header[0]] = rasp_digest(time, thrust, float(header[5]), float(header[4]))
            except (ValueError, IndexError):
                pass

    for raw in lines:
        line = raw.split(";")[0].strip()
        if not line:
            continue
        parts = line.split()
        if len(parts) == 7 and not is_float(parts[0]):
            flush()
            header, time, thrust = parts, [], []
        elif len(parts) == 2 and header is not None and all(is_float(p) for p in parts):
            time.append(float(parts[0]))
            thrust.append(float(parts[1]))
    flush()
    return out
