"""Build the CONSTRUCTED ThrustCurve.org API v1 responses for the AeroTech M1315W and
the Cesaroni I216 (the motors of the NUSTARS FT2 and Imperial College APEX I flights).

Not recorded: no network was available. The data files are byte-for-byte the blobs of
``core/resources-src/datafiles/thrustcurves/thrustcurve.org/`` in openrocket/openrocket at
commit 13dc5289ffc99184b06282029ee82421238543b6 (tag release-15.03), copied into
``openrocket-15.03/``; their OpenRocket digests equal the ones the two teams' .ork files
store for their motors. The responses follow the recorded format of
``download-POST-motorId.json`` and ``search-GET-designation-K550W.json``; every number in
the search result is computed from the RASP file (header and curve), ids and URLs are
placeholders marked ``constructed``, and fields the files do not give are left out.

Run from this folder: ``python construct.py`` (rewrites the four JSON files).
"""
import base64
import json
from pathlib import Path

HERE = Path(__file__).resolve().parent
SRC = HERE / "openrocket-15.03"
#: response name: (manufacturer, abbreviation, source files, ThrustCurve data source). The
#: M1315W file says it is TMT (Tripoli Motor Testing) stand data: "cert"; the I216 file
#: names no origin: "user" (what ThrustCurve calls any other contributed file).
MOTORS = {
    "M1315W": ("AeroTech", "AeroTech", "AeroTech_M1315", "cert"),
    "I216": ("Cesaroni Technology", "Cesaroni", "Cesaroni_I216", "user"),
}


def _rasp(text: str):
    rows = [ln.split(";")[0].split() for ln in text.splitlines()]
    rows = [r for r in rows if r]
    head, pts = rows[0], [(float(a), float(b)) for a, b in rows[1:]]
    if pts[0][0] > 0:
        pts.insert(0, (0.0, 0.0))
    impulse = sum(0.5 * (f0 + f1) * (t1 - t0) for (t0, f0), (t1, f1) in zip(pts, pts[1:]))
    return head, pts, impulse


def build(key: str, maker: str, abbrev: str, stem: str, source: str) -> tuple[dict, dict]:
    eng = (SRC / f"{stem}.eng").read_bytes()
    rse = (SRC / f"{stem}.rse").read_bytes()
    head, pts, impulse = _rasp(eng.decode("ascii"))
    burn = pts[-1][0]
    motor_id = f"constructed-{abbrev}-{key}"
    files = []
    for fmt, suffix, data in (("RASP", "eng", eng), ("RockSim", "rse", rse)):
        sid = f"{motor_id}-{suffix}"
        files.append({"motorId": motor_id, "simfileId": sid, "format": fmt, "source": source,
                      "data": base64.b64encode(data).decode("ascii"),
                      "infoUrl": f"/simfiles/{sid}/", "dataUrl": f"/simfiles/{sid}/download/data.{suffix}",
                      "source_url": f"http://localhost:3000/simfiles/{sid}/"})
    common = key[0] + "".join(ch for ch in key[1:] if ch.isdigit())
    result = {"motorId": motor_id, "manufacturer": maker, "manufacturerAbbrev": abbrev,
              "designation": head[0], "commonName": common, "impulseClass": key[0],
              "diameter": float(head[1]), "length": float(head[2]),
              "avgThrustN": round(impulse / burn, 3), "maxThrustN": max(f for _, f in pts),
              "totImpulseNs": round(impulse, 2), "burnTimeS": burn, "dataFiles": 2,
              "propWeightG": round(1000 * float(head[4]), 1), "delays": head[3].replace("-", ","),
              "source_url": f"http://localhost:3000/motors/{abbrev}/{key}/"}
    search = {"criteria": [{"name": "designation", "value": key, "matches": 1}], "matches": 1,
              "results": [result], "source_url": "http://localhost:3000/motors/search.html"}
    return search, {"results": files}


if __name__ == "__main__":
    for key, spec in MOTORS.items():
        search, download = build(key, *spec)
        (HERE / f"search-GET-designation-{key}-constructed.json").write_text(json.dumps(search, indent=2) + "\n")
        (HERE / f"download-POST-motorId-{key}-constructed.json").write_text(json.dumps(download, indent=2) + "\n")
