"""Motor configurations of an .ork file and the motor files they need (numeric-only).

Lookup order for a configuration's motor (designation such as ``M1670`` or
``M1670-BS``, and the manufacturer when the file names one):

1. motor files (``.eng``, ``.rse``) next to the .ork file;
2. the directories in ``IRONBARK_MOTOR_PATH`` (``os.pathsep``-separated);
3. ThrustCurve.org through :mod:`ironbark_opt.motors.thrustcurve` (its
   on-disk cache first; online unless ``IRONBARK_OFFLINE`` is set), saved
   into ``<cache>/ork-motors``;

and otherwise an InputError naming the motor and every place searched.
"""
from __future__ import annotations

import os
import re
import warnings
from dataclasses import dataclass
from pathlib import Path

from ironbark_opt.errors import InputError, IronbarkError
from ironbark_opt.openrocket.xmlread import Element

#: manufacturer abbreviations used in RASP files -> canonical name
MAKERS = {"A": "AEROTECH", "AT": "AEROTECH", "AEROTECH": "AEROTECH", "RCS": "AEROTECH",
          "C": "CESARONI", "CTI": "CESARONI", "CESARONI": "CESARONI", "CESARONITECHNOLOGY": "CESARONI",
          "E": "ESTES", "ES": "ESTES", "ESTES": "ESTES", "LOKI": "LOKI", "LOKIRESEARCH": "LOKI",
          "AMW": "AMW", "ANIMALMOTORWORKS": "AMW", "WECO": "WECO", "SF": "WECO",
          "SACHSENFEUERWERK": "WECO", "Q": "QUEST", "QUEST": "QUEST", "KS": "KOSDON",
          "KOSDON": "KOSDON", "PRO38": "CESARONI", "PRO54": "CESARONI"}


@dataclass(frozen=True)
class MotorConfig:
    """One ``<motorconfiguration>``: id, name, default flag, motors per mount.

    ``motors`` is a tuple of ``(mount OrkComponent, MotorEntry)``.
    """

    config_id: str
    name: str
    default: bool
    motors: tuple

    def label(self) -> str:
        """The name, or OpenRocket's ``[designation-delay; ...]`` description."""
        if self.name:
            return self.name
        parts = []
        for _, m in self.motors:
            delay = "P" if m.delay is None else f"{m.delay:g}"
            parts.append(f"{m.designation}-{delay}")
        return "[" + "; ".join(parts) + "]" if parts else "[no motors]"


def configurations(root: Element, ork_rocket) -> list[MotorConfig]:
    """All motor configurations, in file order (ids that only appear on motors last)."""
    rocket = root.require("rocket")
    mounts = ork_rocket.motor_mounts()
    out, seen = [], set()
    for mc in rocket.children("motorconfiguration"):
        cid = mc.attr("configid")
        if not cid:
            raise mc.error("a <motorconfiguration> needs a configid attribute")
        seen.add(cid)
        motors = tuple((mt, mt.motors[cid]) for mt in mounts if cid in mt.motors)
        name = mc.text("name") or ""
        out.append(MotorConfig(cid, name, (mc.attr("default") or "").lower() == "true", motors))
    extra = []
    for mt in mounts:
        for cid in mt.motors:
            if cid not in seen and cid not in extra:
                extra.append(cid)
    for cid in extra:
        out.append(MotorConfig(cid, "", False, tuple((mt, mt.motors[cid]) for mt in mounts
                                                     if cid in mt.motors)))
    return out


def select_config(configs: list[MotorConfig], wanted: str | None, source) -> MotorConfig:
    """The configuration named ``wanted`` (id, id prefix, name or label), else the default."""
    usable = [c for c in configs if c.motors]
    if not usable:
        raise InputError("the design has no motor configuration with a motor", source=source,
                         field="rocket/motorconfiguration")
    if wanted is None:
        for c in usable:
            if c.default:
                return c
        return usable[0]
    w = wanted.strip().lower()
    if not w:
        raise InputError("an empty --config; give a configuration id, name or motor designation",
                         source=source, field="config")
    bare = w.strip("[] ")       # "[L1940X]" as a person types the label of "[L1940X-P]"

    def designations(c):
        return [m.designation.lower() for _, m in c.motors]

    for test in (lambda c: c.config_id.lower() == w, lambda c: c.name.lower() == w,
                 lambda c: c.label().lower() == w, lambda c: c.config_id.lower().startswith(w),
                 lambda c: any(d == w or d == bare for d in designations(c)),
                 lambda c: c.label().lower().strip("[] ") == bare,
                 # the designation without its suffix: L1940X for L1940X-P, L1940 for L1940X
                 lambda c: any(d.startswith(bare) for d in designations(c))):
        found = [c for c in usable if test(c)]
        if len(found) == 1:
            return found[0]
        if len(found) > 1:
            break
    import difflib
    labels = {c.label(): c for c in usable}
    near = difflib.get_close_matches(wanted.strip(), list(labels), n=3, cutoff=0.4)
    listing = "; ".join(f"{c.config_id[:8]} {c.label()}" for c in usable[:8])
    hint = f"did you mean {', '.join(near)}? " if near else ""
    raise InputError(f"no single motor configuration matches {wanted!r}; {hint}available: {listing}"
                     + (f" (and {len(usable) - 8} more)" if len(usable) > 8 else ""),
                     source=source, field="config")


def _norm(text: str) -> str:
    return re.sub(r"[^A-Z0-9]", "", (text or "").upper())


def _maker(text: str) -> str:
    n = _norm(text)
    return MAKERS.get(n, n)


def _common(designation: str) -> str:
    m = re.search(r"(?<![A-Z])([A-O])(\d+)", designation.upper())
    return m.group(1) + m.group(2) if m else ""


def matches(motor, designation: str, manufacturer: str) -> bool:
    """Does a loaded motor match an .ork designation (full or common name) and maker?"""
    have = getattr(motor, "designation", "") or ""
    # A file's designation may carry the delay ('I59WN-P', 'H148R-14'); the .ork gives it apart.
    bare = re.sub(r"-(P|\d+[A-Z]?)$", "", have.strip(), flags=re.I)
    ok = _norm(have) == _norm(designation) or _norm(bare) == _norm(designation) or (
        _common(designation) != "" and _common(have) == _common(designation)
        and (_norm(designation) == _common(designation) or _norm(have) == _common(have)))
    if not ok:
        return False
    if manufacturer and getattr(motor, "manufacturer", ""):
        return _maker(motor.manufacturer) == _maker(manufacturer)
    return True


def search_dirs(ork_path: Path) -> list[Path]:
    """Directories searched for motor files: the .ork's folder, then IRONBARK_MOTOR_PATH."""
    dirs = [Path(ork_path).resolve().parent]
    for part in os.environ.get("IRONBARK_MOTOR_PATH", "").split(os.pathsep):
        if part.strip():
            d = Path(part.strip())
            if d.exists() and not d.is_dir():
                raise InputError(f"entry {d} is a file; expected directories holding .eng/.rse files, "
                                 f"separated by '{os.pathsep}'", field="IRONBARK_MOTOR_PATH")
            dirs.append(d)
    return dirs


@dataclass(frozen=True)
class MotorMatch:
    """A motor file found for an .ork motor.

    ``verified``: True when OpenRocket's digest in the .ork equals the file's
    (:mod:`.digest`), False when it differs, None when it cannot be checked
    (no digest in the .ork, or a .rse file).
    """

    path: Path
    motor: object
    verified: bool | None


def _verify(path: Path, motor, digest: str | None) -> bool | None:
    if not digest or path.suffix.lower() != ".eng":
        return None
    value = _digest_of(path, motor)
    return None if value is None else value == digest.lower()


def _local(designation: str, manufacturer: str, dirs: list[Path], digest: str | None = None):
    """The best local match: digest-verified first, then unverifiable, then mismatching.

    A RASP file whose OpenRocket digest equals the .ork's is the motor the design was
    made with whatever its header calls it: OpenRocket identifies a thrust curve by
    that digest (``MotorDigest``) and names it from ThrustCurve.org's metadata, so the
    136 N s AeroTech G80 file it lists as ``G80T`` has the header name ``G78``.
    """
    found = [MotorMatch(p, m, _verify(p, m, digest))
             for p, m in _candidates(designation, manufacturer, dirs, digest)]
    for want in (True, None, False):
        for hit in found:
            if hit.verified is want:
                return hit
    return None


def _digest_of(path: Path, motor) -> str | None:
    from ironbark_opt.openrocket.digest import eng_digests
    found = eng_digests(path)
    return found.get(getattr(motor, "designation", "")) or (
        next(iter(found.values())) if len(found) == 1 else None)


def _candidates(designation: str, manufacturer: str, dirs: list[Path], digest: str | None = None):
    from ironbark_opt.motors import read_eng, read_rse
    for d in dirs:
        if not d.is_dir():
            continue
        for path in sorted(d.iterdir()):
            ext = path.suffix.lower()
            if ext not in (".eng", ".rse"):
                continue
            try:
                motors = read_eng(path) if ext == ".eng" else read_rse(path)
            except (InputError, OSError, ValueError):
                continue
            for m in (motors if isinstance(motors, (list, tuple)) else [motors]):
                if matches(m, designation, manufacturer) or (
                        digest and ext == ".eng" and _digest_of(path, m) == digest.lower()):
                    yield path, m


def _thrustcurve(designation: str, manufacturer: str, digest: str | None = None):
    try:
        from ironbark_opt import net
        from ironbark_opt.motors import thrustcurve as tc
    except ImportError:
        return None, "ThrustCurve.org client not installed"
    try:
        info, simfile = tc.fetch_motor_file(designation, manufacturer=manufacturer or None)
        path = tc.save_file(info, simfile, net.cache_dir() / "ork-motors")
        from ironbark_opt.motors import load_motor
        motor = load_motor(path)
        return MotorMatch(path, motor, _verify(path, motor, digest)), ""
    except (IronbarkError, OSError) as err:
        return None, str(err)


def find_motor_file(designation: str, manufacturer: str, ork_path,
                    digest: str | None = None) -> MotorMatch:
    """The motor file (and its SolidMotor) an .ork configuration names.

    A local file whose OpenRocket digest equals ``digest`` wins over other
    files with the same designation; a file that cannot be checked (.rse) or
    whose digest differs is used only when nothing better exists, with a
    warning (when the .ork has a digest).

    Raises
    ------
    InputError
        Naming the designation, the manufacturer and every place searched.
    """
    dirs = search_dirs(Path(ork_path))
    hit = _local(designation, manufacturer, dirs, digest)
    if hit is not None:
        if hit.verified is None and digest:
            # a .rse has no OpenRocket digest here: the design's motor may be another
            # variant of the designation (AeroTech's 100 N s and 136 N s G80T both exist)
            warnings.warn(f"motor {designation}: {hit.path} cannot be checked against the motor "
                          f"the .ork was designed with (OpenRocket digest {digest}; only .eng files "
                          f"are checked); its total impulse is {hit.motor.total_impulse:.4g} N s; if "
                          f"OpenRocket's differs, put that motor's .eng next to the .ork",
                          UserWarning, stacklevel=2)
        if hit.verified is False:
            warnings.warn(f"motor {designation}: {hit.path} differs from the motor the .ork was "
                          f"designed with (OpenRocket digest {digest}); using it anyway",
                          UserWarning, stacklevel=2)
        return hit
    hit, why = _thrustcurve(designation, manufacturer, digest)
    if hit is not None:
        if hit.verified is False:
            warnings.warn(f"motor {designation}: ThrustCurve.org's file {hit.path.name} differs from the motor "
                          f"the .ork was designed with (OpenRocket digest {digest}); using it anyway",
                          UserWarning, stacklevel=2)
        return hit
    where = ", ".join(str(d) for d in dirs)
    why = str(why).split(": connection failed")[0][:120] + (": no network" if ": connection failed" in str(why) else "")
    raise InputError(f"motor {manufacturer + ' ' if manufacturer else ''}{designation} not found: "
                     f"searched motor files (.eng/.rse) in {where}; {why}. Put its .eng/.rse file "
                     f"next to the .ork or in a directory listed in IRONBARK_MOTOR_PATH",
                     source=ork_path, field="motor")
