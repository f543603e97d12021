"""ThrustCurve.org API v1 client: search motors, download RASP/RockSim data.

The API (Swagger 2.0, version 1.0.3; ``../shared/fixtures/thrustcurve``) has
three calls under the base URL ``endpoint("thrustcurve")`` (default
``https://www.thrustcurve.org/api/v1``, override with
``IRONBARK_THRUSTCURVE_URL``): ``metadata.json``, ``search.json`` and
``download.json``.  The service speaks millimetres and grams; this module
converts to SI at the boundary.  Downloads carry base64-encoded ``.eng`` /
``.rse`` files; they are decoded and parsed with the package's own readers.

Responses are cached (:mod:`ironbark_opt.net`): searches fall back to the
cache when the service is down, downloads are immutable per motor and come
from the cache when present.  Numeric-only (I/O).
"""
from __future__ import annotations

import base64
import binascii
import math
import re
import tempfile
from dataclasses import dataclass
from pathlib import Path

from ironbark_opt import net
from ironbark_opt.errors import InputError

SOURCE = "ThrustCurve.org"
#: Data-file sources, best first: certification-body test data, then the
#: manufacturer's, then user contributions.
SOURCE_RANK = {"cert": 0, "mfr": 1, "user": 2}
FORMAT_SUFFIX = {"RASP": ".eng", "RockSim": ".rse"}


@dataclass(frozen=True)
class MotorInfo:
    """One search result, in SI units.

    ``diameter`` and ``length`` [m], ``total_impulse`` [N s], ``burn_time``
    [s], ``average_thrust`` and ``max_thrust`` [N], ``propellant_mass`` [kg]
    (None if unknown); ``motor_id`` is ThrustCurve's identifier.
    """
    motor_id: str
    manufacturer: str
    manufacturer_abbrev: str
    designation: str
    common_name: str
    impulse_class: str
    diameter: float
    length: float | None
    type: str
    cert_org: str
    total_impulse: float | None
    burn_time: float | None
    average_thrust: float | None
    max_thrust: float | None
    propellant_mass: float | None
    data_files: int
    delays: str
    availability: str

    def to_dict(self) -> dict:
        """JSON-friendly dict with unit-suffixed keys."""
        return {"motor_id": self.motor_id, "manufacturer": self.manufacturer,
                "designation": self.designation, "common_name": self.common_name,
                "impulse_class": self.impulse_class, "diameter_mm": _mm(self.diameter),
                "length_mm": _mm(self.length), "type": self.type, "cert_org": self.cert_org,
                "total_impulse_Ns": self.total_impulse, "burn_time_s": self.burn_time,
                "average_thrust_N": self.average_thrust, "max_thrust_N": self.max_thrust,
                "propellant_mass_kg": self.propellant_mass, "data_files": self.data_files,
                "delays": self.delays, "availability": self.availability}

    def summary(self) -> str:
        """One line: manufacturer, designation, size, impulse, burn time."""
        def f(x, fmt):
            return "?" if x is None else format(x, fmt)
        return (f"{self.manufacturer_abbrev or self.manufacturer} {self.designation} "
                f"({self.impulse_class}, {f(_mm(self.diameter), '.0f')} x "
                f"{f(_mm(self.length), '.0f')} mm, {self.type}): "
                f"I = {f(self.total_impulse, '.1f')} N s, t_b = {f(self.burn_time, '.2f')} s, "
                f"F_avg = {f(self.average_thrust, '.1f')} N, {self.data_files} data file(s)")


@dataclass(frozen=True)
class SimFile:
    """One downloaded simulator file (text already decoded from base64)."""
    motor_id: str
    simfile_id: str
    format: str
    source: str
    license: str
    text: str
    data_url: str

    @property
    def suffix(self) -> str:
        """File suffix for the format (``.eng`` or ``.rse``)."""
        return FORMAT_SUFFIX.get(self.format, ".txt")


def _mm(x):
    return None if x is None else x * 1000.0


def _num(d: dict, key: str, scale: float = 1.0):
    v = d.get(key)
    if isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(v):
        return None
    return float(v) * scale


def _url(call: str) -> str:
    return f"{net.endpoint('thrustcurve')}/{call}"


def _parse_response(kind: str):
    decode = net.parse_json(f"{SOURCE} {kind}")

    def parse(content: bytes):
        data = decode(content)
        if not isinstance(data, dict):
            raise InputError("expected a JSON object", source=f"{SOURCE} {kind}")
        if kind != "metadata" and not isinstance(data.get("results", []), list):
            raise InputError("'results' is not a list", source=f"{SOURCE} {kind}",
                             field="results")
        return data
    return parse


def metadata(**criteria) -> dict:
    """Manufacturers, certification bodies, types, diameters [mm] and impulse classes.

    ``criteria`` are passed through (``manufacturer=``, ``impulseClass=``,
    ``availability=``, ...).
    """
    return net.fetch(SOURCE, _url("metadata.json"), params=criteria or None,
                     parse=_parse_response("metadata")).data


def search(*, designation: str | None = None, common_name: str | None = None,
           manufacturer: str | None = None, impulse_class: str | None = None,
           diameter: float | None = None, type: str | None = None,
           cert_org: str | None = None, availability: str | None = None,
           max_results: int = 20) -> list[MotorInfo]:
    """Search ThrustCurve.org; an empty list when nothing matches.

    Parameters
    ----------
    designation, common_name, manufacturer, impulse_class, type, cert_org, availability : str
        Search criteria (ThrustCurve names: ``K550W``, ``K550``, ``AeroTech``,
        ``K``, ``SU``/``reload``/``hybrid``, ``NAR``/``TRA``, ``available``).
    diameter : float [m], optional
        Motor diameter (sent in whole millimetres).
    max_results : int
        The service returns 20 unless asked for more.

    Raises
    ------
    InputError
        No criterion given, or the service rejected a criterion.
    NetworkError
        Service down and nothing cached.
    """
    crit = {"designation": designation, "commonName": common_name,
            "manufacturer": manufacturer, "impulseClass": impulse_class,
            "type": type, "certOrg": cert_org, "availability": availability}
    crit = {k: v for k, v in crit.items() if v not in (None, "")}
    if diameter is not None:
        if not 0.005 < diameter < 0.5:
            raise InputError(f"diameter must be in metres (0.005-0.5), got {diameter!r}",
                             field="diameter")
        crit["diameter"] = int(round(diameter * 1000.0))
    if not crit:
        raise InputError("give at least one search criterion (designation, common name, "
                         "manufacturer, impulse class, diameter, ...)", field="search")
    crit["maxResults"] = int(max_results)
    data = net.fetch(SOURCE, _url("search.json"), params=crit,
                     parse=_parse_response("search")).data
    if data.get("error"):
        raise InputError(f"{SOURCE} rejected the search: {data['error']}", source=SOURCE,
                         field="search")
    return [_motor_info(r, i) for i, r in enumerate(data.get("results", []))]


def _motor_info(r: dict, i: int) -> MotorInfo:
    if not isinstance(r, dict) or not r.get("motorId") or not r.get("designation"):
        raise InputError("search result without motorId/designation", source=SOURCE,
                         field=f"results[{i}]")
    prop_g = _num(r, "propWeightG", 1e-3)
    return MotorInfo(
        motor_id=str(r["motorId"]), manufacturer=str(r.get("manufacturer", "")),
        manufacturer_abbrev=str(r.get("manufacturerAbbrev", "")),
        designation=str(r["designation"]), common_name=str(r.get("commonName", "")),
        impulse_class=str(r.get("impulseClass", "")),
        diameter=_num(r, "diameter", 1e-3), length=_num(r, "length", 1e-3),
        type=str(r.get("type", "")), cert_org=str(r.get("certOrg", "")),
        total_impulse=_num(r, "totImpulseNs"), burn_time=_num(r, "burnTimeS"),
        average_thrust=_num(r, "avgThrustN"), max_thrust=_num(r, "maxThrustN"),
        propellant_mass=prop_g, data_files=int(r.get("dataFiles") or 0),
        delays=str(r.get("delays", "")), availability=str(r.get("availability", "")))


def download(motor_id: str, *, format: str | None = None) -> list[SimFile]:
    """All data files of one motor (base64 decoded); may be empty.

    Parameters
    ----------
    motor_id : str
        ThrustCurve motor identifier (from :func:`search`).
    format : {"RASP", "RockSim"}, optional
        Only files of this format.
    """
    if format is not None and format not in FORMAT_SUFFIX:
        raise InputError(f"format must be one of {sorted(FORMAT_SUFFIX)}, got {format!r}",
                         field="format")
    body = {"motorIds": [motor_id], "data": "file"}
    if format:
        body["format"] = format
    data = net.fetch(SOURCE, _url("download.json"), json_body=body, prefer_cache=True,
                     parse=_parse_download).data
    return [f for f in data if f.motor_id == motor_id]


def _parse_download(content: bytes) -> list[SimFile]:
    data = _parse_response("download")(content)
    if data.get("error"):
        raise InputError(f"download refused: {data['error']}", source=f"{SOURCE} download")
    files = []
    for i, r in enumerate(data.get("results", [])):
        where = f"results[{i}]"
        if not isinstance(r, dict) or "data" not in r:
            raise InputError("file entry without 'data'", source=f"{SOURCE} download",
                             field=where)
        try:
            text = base64.b64decode(r["data"], validate=True).decode("utf-8", "replace")
        except (binascii.Error, TypeError, ValueError):
            raise InputError("'data' is not valid base64", source=f"{SOURCE} download",
                             field=f"{where}.data") from None
        files.append(SimFile(str(r.get("motorId", "")), str(r.get("simfileId", "")),
                             str(r.get("format", "")), str(r.get("source", "")),
                             str(r.get("license", "")), text, str(r.get("dataUrl", ""))))
    return files


def choose_file(files: list[SimFile], prefer_format: str | None = None) -> SimFile:
    """The best of several data files for one motor.

    Order: certification data, then manufacturer, then user files; within a
    source the preferred format (``prefer_format``, else RASP, which every
    simulator reads), then the file with more data lines (finer curve).
    """
    usable = [f for f in files if f.format in FORMAT_SUFFIX and f.text.strip()]
    if not usable:
        raise InputError("no RASP or RockSim data file for this motor", source=SOURCE)
    prefer = prefer_format or "RASP"

    def rank(f: SimFile):
        return (SOURCE_RANK.get(f.source, 3), f.format != prefer, -f.text.count("\n"))
    return min(usable, key=rank)


def find_motor(designation: str, *, manufacturer: str | None = None) -> MotorInfo:
    """The one motor whose designation (or common name) is ``designation``.

    Raises
    ------
    InputError
        Nothing matches (with a hint), or several manufacturers make a motor
        of that name and ``manufacturer`` was not given.
    """
    results = search(designation=designation, manufacturer=manufacturer)
    if not results:
        results = search(common_name=designation, manufacturer=manufacturer)
    if not results:
        raise InputError(
            f"no motor called {designation!r} at {SOURCE}"
            + (f" from {manufacturer}" if manufacturer else "")
            + "; try `ironbark motor search --common-name` or check the spelling",
            source=SOURCE, field="designation")
    key = _norm(designation)
    exact = [m for m in results if _norm(m.designation) == key] or \
            [m for m in results if _norm(m.common_name) == key] or results
    makers = {m.manufacturer for m in exact}
    if len(exact) > 1 and len(makers) > 1:
        raise InputError(
            f"{designation!r} is ambiguous: "
            + ", ".join(f"{m.manufacturer_abbrev or m.manufacturer} {m.designation}" for m in exact)
            + "; give the manufacturer", source=SOURCE, field="designation")
    return max(exact, key=lambda m: m.data_files)


def _norm(name: str) -> str:
    return re.sub(r"[\s\-_]", "", name).upper()


def fetch_motor_file(designation: str, *, manufacturer: str | None = None,
                     format: str | None = None) -> tuple[MotorInfo, SimFile]:
    """Search, download and choose the best data file for a motor."""
    info = find_motor(designation, manufacturer=manufacturer)
    files = download(info.motor_id)
    if format is not None:
        files = [f for f in files if f.format == format] or files
    if not files:
        raise InputError(f"{SOURCE} has no data file for {info.designation} "
                         f"(motor id {info.motor_id})", source=SOURCE, field="designation")
    return info, choose_file(files, prefer_format=format)


def file_name(info: MotorInfo, simfile: SimFile) -> str:
    """A file name such as ``AeroTech_K550W.eng``."""
    maker = re.sub(r"[^A-Za-z0-9]+", "", info.manufacturer_abbrev or info.manufacturer)
    desig = re.sub(r"[^A-Za-z0-9.\-]+", "_", info.designation)
    return f"{maker}_{desig}{simfile.suffix}"


def save_file(info: MotorInfo, simfile: SimFile, directory: str | Path = ".") -> Path:
    """Write the data file (atomically) into ``directory``; returns its path."""
    path = Path(directory) / file_name(info, simfile)
    net.write_atomic(path, simfile.text.encode("utf-8"))
    return path


def load_motor(designation: str, *, manufacturer: str | None = None,
               format: str | None = None):
    """A ``SolidMotor`` from ThrustCurve.org data, parsed by the package's readers.

    The decoded file is written to a temporary file and read with
    ``ironbark_opt.motors.rasp.read_eng`` or ``ironbark_opt.motors.rse.read_rse``.
    """
    info, simfile = fetch_motor_file(designation, manufacturer=manufacturer, format=format)
    return motor_from_text(simfile.text, simfile.format, designation=info.designation)


def motor_from_text(text: str, format: str, *, designation: str | None = None):
    """Parse ``.eng`` (``format="RASP"``) or ``.rse`` (``"RockSim"``) text to a ``SolidMotor``."""
    if format == "RASP":
        from ironbark_opt.motors.rasp import read_eng as reader
    elif format == "RockSim":
        from ironbark_opt.motors.rse import read_rse as reader
    else:
        raise InputError(f"unknown data-file format {format!r}", field="format")
    with tempfile.TemporaryDirectory(prefix="ironbark-tc-") as tmp:
        path = Path(tmp) / f"thrustcurve{FORMAT_SUFFIX[format]}"
        path.write_text(text, encoding="utf-8")
        motors = reader(path)
    motors = motors if isinstance(motors, (list, tuple)) else [motors]
    if not motors:
        raise InputError("the data file holds no motor", source=SOURCE)
    if designation:
        key = _norm(designation)
        for m in motors:
            if _norm(getattr(m, "designation", "")) == key:
                return m
    return motors[0]
