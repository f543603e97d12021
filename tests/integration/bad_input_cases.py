"""The bad-input corpus: one row per input a user might get wrong (issue 15).

Every case is built from the project's own examples (``examples/calisto``,
``examples/kestrel``, ``tests/data``), copied into the test's ``tmp_path``:

- ``{C}`` -> ``<tmp>/ex/c/calisto.toml`` (its motor and drag curves beside it)
- ``{K}`` -> ``<tmp>/ex/k/kestrel.toml`` (its table at ``<tmp>/tables``)
- ``{T}`` -> ``<tmp>``;  ``{D}`` -> ``tests/data`` (read-only)
- ``{ORK:name}`` -> a copy of ``tests/data/ork/name`` in ``<tmp>/ork``

``edits`` change the copies before the run: ``(relpath, old, new)`` replaces
the text ``old`` (which must be there: the corpus fails loudly when an
example changes under it), ``(relpath, None, content)`` writes a file (str or
bytes), and a callable ``f(tmp)`` does anything else.  ``needles`` are
lower-case words the one-line error must contain (the file, field or option
and what was expected).  ``outputs`` are paths (relative to ``<tmp>``) that
must not exist afterwards: no partial output file.

Extend the corpus by appending a ``Case``; nothing else needs to change.
"""
from __future__ import annotations

import gzip
import io
import zipfile
from dataclasses import dataclass
from pathlib import Path

DATA = Path(__file__).resolve().parents[1] / "data"


@dataclass(frozen=True)
class Case:
    id: str
    argv: tuple
    needles: tuple = ()
    status: int = 2
    edits: tuple = ()
    outputs: tuple = ()
    net: str | None = None          # "closed": ThrustCurve URL on a closed port; "loopback:<fault>"


CASES: list[Case] = []


def case(id, argv, needles=(), status=2, edits=(), outputs=(), net=None):
    CASES.append(Case(id, tuple(argv.split()) if isinstance(argv, str) else tuple(argv),
                      tuple(needles), status, tuple(edits), tuple(outputs), net))


CT = "ex/c/calisto.toml"
CD_SPEC = "ex/c/dispersions.toml"
KT = "ex/k/kestrel.toml"
CE = "ex/c/Cesaroni_M1670.eng"
KE = "ex/k/Cesaroni_4263L1350-P.eng"
DRAG = "ex/c/powerOffDragCurve.csv"
DRAG_ON = "ex/c/powerOnDragCurve.csv"


def edit(path, old, new):
    return (path, old, new)


def write(path, content):
    return (path, None, content)


# --------------------------------------------------------------------------- broken TOML
sim_c = "simulate {C}"
sim_k = "simulate {K}"
case("toml-missing-file", "simulate {T}/nope.toml", ["nope.toml", "not found"])
case("toml-directory", "simulate {T}/ex", ["ex", "directory"])
case("toml-syntax-unclosed-string", sim_c, ["calisto.toml:", "syntax"],
     edits=[edit(CT, 'name = "Calisto"', 'name = "Calisto')])
case("toml-syntax-bad-value", sim_c, ["calisto.toml:", "syntax"],
     edits=[edit(CT, "mass = 14.426", "mass = 14.426.1")])
case("toml-duplicate-key", sim_c, ["calisto.toml:", "mass"],
     edits=[edit(CT, "mass = 14.426", "mass = 14.426\nmass = 15.0")])
case("toml-duplicate-table", sim_c, ["calisto.toml:", "launch"],
     edits=[edit(CT, "[launch]", "[launch]\nrail_length = 5.2\n[launch]")])
case("toml-empty-file", sim_c, ["calisto.toml", "rocket"], edits=[write(CT, "")])
case("toml-binary-garbage", sim_c, ["calisto.toml"], edits=[write(CT, b"\x00\xff\xfe garbage")])
case("toml-unknown-top-table", sim_c, ["calisto.toml", "rokcet"],
     edits=[edit(CT, "[rocket]\n", "[rokcet]\nx = 1\n[rocket]\n")])
case("toml-unknown-launch-key", sim_c, ["calisto.toml", "rail_lenght"],
     edits=[edit(CT, "rail_length = 5.2", "rail_lenght = 5.2")])
case("toml-missing-motor-table", sim_c, ["calisto.toml", "motor"],
     edits=[edit(CT, "[motor]\n", "[motor_x]\n")])
case("toml-negative-nose-length", sim_c, ["calisto.toml:", "length"],
     edits=[edit(CT, "length = 0.55829", "length = -0.55829")])
case("toml-string-for-number", sim_c, ["calisto.toml", "rail_length"],
     edits=[edit(CT, "rail_length = 5.2", 'rail_length = "long"')])
case("toml-bool-for-number", sim_c, ["calisto.toml", "rail_length"],
     edits=[edit(CT, "rail_length = 5.2", "rail_length = true")])
case("toml-nan-rail-length", sim_c, ["calisto.toml", "rail_length"],
     edits=[edit(CT, "rail_length = 5.2", "rail_length = nan")])
case("toml-inf-elevation", sim_c, ["calisto.toml", "site_elevation"],
     edits=[edit(CT, "site_elevation = 1400.0", "site_elevation = inf")])
case("toml-negative-rail-length", sim_c, ["calisto.toml", "rail_length", "> 0"],
     edits=[edit(CT, "rail_length = 5.2", "rail_length = -5.2")])
case("toml-zero-rail-length", sim_c, ["calisto.toml", "rail_length"],
     edits=[edit(CT, "rail_length = 5.2", "rail_length = 0")])
case("toml-inclination-120", sim_c, ["calisto.toml", "inclination"],
     edits=[edit(CT, "inclination_deg = 84.0", "inclination_deg = 120.0")])
case("toml-inclination-0", sim_c, ["calisto.toml", "inclination"],
     edits=[edit(CT, "inclination_deg = 84.0", "inclination_deg = 0.0")])
case("toml-inclination-1.5", sim_c, ["inclination"],
     edits=[edit(CT, "inclination_deg = 84.0", "inclination_deg = 1.5")])
case("toml-latitude-95", sim_c, ["calisto.toml", "latitude"],
     edits=[edit(CT, "latitude_deg = 32.990254", "latitude_deg = 95.0")])
case("toml-negative-wind", sim_c, ["calisto.toml", "wind_speed"],
     edits=[edit(CT, "wind_speed = 0.0", "wind_speed = -3.0")])
case("toml-wind-80", sim_c, ["wind_speed"],
     edits=[edit(CT, "wind_speed = 0.0", "wind_speed = 80.0")])
case("toml-unknown-component-type", sim_c, ["calisto.toml", "type"],
     edits=[edit(CT, 'type = "body_tube"', 'type = "body_tub"')])
case("toml-unknown-nose-shape", sim_c, ["calisto.toml", "shape"],
     edits=[edit(CT, 'shape = "von_karman"', 'shape = "pointy"')])
case("toml-fin-count-zero", sim_c, ["calisto.toml", "count"],
     edits=[edit(CT, "count = 4", "count = 0")])
case("toml-fin-negative-span", sim_c, ["calisto.toml", "span"],
     edits=[edit(CT, "span = 0.110", "span = -0.110")])
case("toml-transition-negative-radius", sim_c, ["calisto.toml", "radius"],
     edits=[edit(CT, "aft_radius = 0.0435", "aft_radius = -0.0435")])
case("toml-motor-file-missing", sim_c, ["nope.eng", "not found"],
     edits=[edit(CT, 'file = "Cesaroni_M1670.eng"', 'file = "nope.eng"')])
case("toml-motor-file-directory", sim_c, ["directory"],
     edits=[edit(CT, 'file = "Cesaroni_M1670.eng"', 'file = "."')])
case("toml-motor-unknown-designation", sim_c, ["m9999"],
     edits=[edit(CT, 'designation = "M1670"', 'designation = "M9999"')])
case("toml-motor-unknown-override", sim_c, ["calisto.toml", "dry_mas"],
     edits=[edit(CT, "dry_mass = 1.815", "dry_mas = 1.815")])
case("toml-motor-negative-dry-mass", sim_c, ["dry_mass"],
     edits=[edit(CT, "dry_mass = 1.815", "dry_mass = -1.815")])
case("toml-motor-nozzle-negative", sim_c, ["nozzle_x"],
     edits=[edit(CT, "nozzle_x = 2.533", "nozzle_x = -2.533")])
case("toml-grain-inner-gt-outer", sim_c, ["radius"],
     edits=[edit(CT, "inner_radius = 0.015", "inner_radius = 0.040")])
case("toml-grain-negative-density", sim_c, ["density"],
     edits=[edit(CT, "density = 1815.0", "density = -1815.0")])
case("toml-drag-file-missing", sim_c, ["nodrag.csv", "not found"],
     edits=[edit(CT, 'drag_power_off = "powerOffDragCurve.csv"', 'drag_power_off = "nodrag.csv"')])
case("toml-table-missing", sim_k, ["nope", "not found"],
     edits=[edit(KT, 'table = "../../tables/Kestrel.csv"', 'table = "nope.csv"')])
case("toml-recovery-negative-cd", sim_k, ["kestrel.toml", "cd"],
     edits=[edit(KT, "cd = 1.5", "cd = -1.5")])
case("toml-recovery-bad-deploy", sim_k, ["kestrel.toml", "deploy"],
     edits=[edit(KT, 'deploy = "apogee"', 'deploy = "later"')])
case("toml-ballast-xmax-fwd-of-xmin", sim_k, ["kestrel.toml", "x_max"],
     edits=[edit(KT, "x_max = 0.58", "x_max = 0.40")])
case("toml-ballast-negative-capacity", sim_k, ["kestrel.toml", "mass_max"],
     edits=[edit(KT, "mass_max = 3.0", "mass_max = -3.0")])
case("toml-ballast-over-capacity", sim_k, ["kestrel.toml", "mass"],
     edits=[edit(KT, "mass_max = 3.0", "mass_max = 3.0\nmass = 4.0")])
case("toml-ballast-outside-bay", sim_k, ["kestrel.toml", "x"],
     edits=[edit(KT, "mass_max = 3.0", "mass_max = 3.0\nmass = 1.0\nx = 1.5")])
case("toml-ballast-bay-outside-body", sim_k, ["ballast", "aft of the rocket"],
     edits=[edit(KT, "x_min = 0.46", "x_min = 3.46"), edit(KT, "x_max = 0.58", "x_max = 3.58")])
case("toml-component-negative-mass", sim_k, ["kestrel.toml", "mass"],
     edits=[edit(KT, "mass = 0.95", "mass = -0.95")])
case("toml-unknown-material", sim_k, ["kestrel.toml", "material"],
     edits=[edit(KT, 'material = "plywood"', 'material = "unobtainium"')])
case("toml-inner-tube-radius-swap", sim_k, ["kestrel.toml", "radius"],
     edits=[edit(KT, "inner_radius = 0.0385", "inner_radius = 0.0450")])
case("toml-rail-buttons-outside", sim_k, ["x_aft"],
     edits=[edit(KT, "x_aft = 2.20", "x_aft = 9.20")])

# --------------------------------------------------------------------------- impossible physics
case("phys-zero-dry-mass", sim_c, ["mass", "> 0"],
     edits=[edit(CT, "mass = 14.426", "mass = 0.0")])
case("phys-cg-aft-of-tail", sim_c, ["cg_x", "outside the body"],
     edits=[edit(CT, "cg_x = 1.278", "cg_x = 5.0")])
case("phys-cg-ahead-of-nose", sim_c, ["cg_x", "outside the body"],
     edits=[edit(CT, "cg_x = 1.278", "cg_x = -0.5")])
case("phys-axial-gt-twice-transverse", sim_c, ["i_axial", "triangle"],
     edits=[edit(CT, "I_axial = 0.034", "I_axial = 70.0"),
            edit(CT, "I_transverse = 6.321", "I_transverse = 25.0")])
case("phys-zero-transverse-inertia", sim_c, ["i_transverse"],
     edits=[edit(CT, "I_transverse = 6.321", "I_transverse = 0.0")])
case("phys-negative-axial-inertia", sim_c, ["inertia", ">= 0"],
     edits=[edit(CT, "I_axial = 0.034", "I_axial = -0.034")])
case("phys-tensor-not-positive-definite", sim_c, ["inertia", "positive definite"],
     edits=[edit(CT, "I_axial = 0.034", "# I_axial = 0.034"), edit(CT, "I_transverse = 6.321",
                 "inertia = [[0.034, 9.0, 0.0], [9.0, 6.321, 0.0], [0.0, 0.0, 6.321]]")])
case("phys-tensor-asymmetric", sim_c, ["inertia", "symmetric"],
     edits=[edit(CT, "I_axial = 0.034", "# I_axial = 0.034"), edit(CT, "I_transverse = 6.321",
                 "inertia = [[0.034, 0.1, 0.0], [0.0, 6.321, 0.0], [0.0, 0.0, 6.321]]")])
case("phys-tensor-triangle", sim_c, ["i_axial", "triangle"],
     edits=[edit(CT, "I_axial = 0.034", "# I_axial = 0.034"), edit(CT, "I_transverse = 6.321",
                 "inertia = [[20.0, 0.0, 0.0], [0.0, 6.321, 0.0], [0.0, 0.0, 6.321]]")])
case("phys-tensor-wrong-shape", sim_c, ["inertia", "3x3"],
     edits=[edit(CT, "I_axial = 0.034", "# I_axial = 0.034"), edit(CT, "I_transverse = 6.321",
                 "inertia = [[0.034, 0.0], [0.0, 6.321]]")])
case("phys-motor-dry-inertia-triangle", sim_c, ["dry_inertia", "triangle"],
     edits=[edit(CT, "dry_inertia = [0.125, 0.002]", "dry_inertia = [0.125, 0.9]")])
case("phys-motor-dry-cg-outside-motor", sim_c, ["dry_cg"],
     edits=[edit(CT, "dry_cg = 0.317", "dry_cg = 3.0")])
case("phys-propellant-heavier-than-motor", sim_c, ["propellant_mass"],
     edits=[edit(CT, "dry_cg = 0.317", "dry_cg = 0.317\npropellant_mass = 40.0")])
case("phys-propellant-zero", sim_c, ["propellant_mass"],
     edits=[edit(CT, "dry_cg = 0.317", "dry_cg = 0.317\npropellant_mass = 0.0")])
case("phys-grains-ten-times-motor", sim_c, ["propellant_mass"],
     edits=[edit(CT, "count = 5", "count = 50")])
case("phys-nozzle-outside-body", sim_c, ["nozzle_x", "body"],
     edits=[edit(CT, "nozzle_x = 2.533", "nozzle_x = 7.0")])
case("phys-unstable-cg-aft", sim_c, ["static margin", "--allow-unstable"],
     edits=[edit(CT, "cg_x = 1.278", "cg_x = 2.40")])
case("phys-unstable-no-fins", sim_k, ["static margin", "--allow-unstable"],
     edits=[edit(KT, "x = 1.05", "x = 2.35"), edit(KT, "mass = 0.95", "mass = 30.0")])
case("phys-motor-too-weak", sim_c, ["thrust", "weight"],
     edits=[edit(CT, "mass = 14.426", "mass = 250.0"),
            edit(CT, "I_transverse = 6.321", "I_transverse = 110.0")])
case("phys-motor-table-inverted", sim_c, ["cesaroni_m1670.eng"],
     edits=[edit(CE, "0.055 100", "0.055 -100")])

# --------------------------------------------------------------------------- motor files
case("eng-empty", sim_c, ["cesaroni_m1670.eng"], edits=[write(CE, "")])
case("eng-comments-only", sim_c, ["cesaroni_m1670.eng"], edits=[write(CE, "; nothing\n; here\n")])
case("eng-header-short", sim_c, ["cesaroni_m1670.eng"],
     edits=[edit(CE, "M1670-BS 75 757 0 3.101 5.231 CTI", "M1670-BS 75 757 0")])
case("eng-header-text-mass", sim_c, ["cesaroni_m1670.eng"],
     edits=[edit(CE, "M1670-BS 75 757 0 3.101 5.231 CTI", "M1670-BS 75 757 0 heavy 5.231 CTI")])
case("eng-negative-diameter", sim_c, ["cesaroni_m1670.eng"],
     edits=[edit(CE, "M1670-BS 75 757", "M1670-BS -75 757")])
case("eng-prop-gt-total", sim_c, ["cesaroni_m1670.eng"],
     edits=[edit(CE, "3.101 5.231", "6.101 5.231")])
case("eng-time-not-increasing", sim_c, ["cesaroni_m1670.eng"],
     edits=[edit(CE, "0.2 1800", "0.12 1800")])
case("eng-negative-thrust", sim_c, ["cesaroni_m1670.eng"],
     edits=[edit(CE, "1 2034", "1 -2034")])
case("eng-text-thrust", sim_c, ["cesaroni_m1670.eng"],
     edits=[edit(CE, "1 2034", "1 lots")])
case("eng-nan-thrust", sim_c, ["cesaroni_m1670.eng"],
     edits=[edit(CE, "1 2034", "1 nan")])
case("eng-one-column", sim_c, ["cesaroni_m1670.eng"],
     edits=[edit(CE, "1 2034", "1")])
case("eng-no-data", sim_c, ["cesaroni_m1670.eng"],
     edits=[write(CE, "M1670-BS 75 757 0 3.101 5.231 CTI\n")])
case("eng-all-zero-thrust", sim_c, ["cesaroni_m1670.eng"],
     edits=[write(CE, "M1670-BS 75 757 0 3.101 5.231 CTI\n0.5 0\n1.0 0\n")])
case("eng-binary", sim_c, ["cesaroni_m1670.eng"], edits=[write(CE, b"\x89PNG\r\n\x1a\n\x00\x00")])
case("eng-kestrel-negative-time", sim_k, ["cesaroni_4263l1350-p.eng"],
     edits=[edit(KE, "   0.016 1421.724", "   -0.016 1421.724")])
case("motor-wrong-suffix", sim_c, ["motor.txt"],
     edits=[write("ex/c/motor.txt", "hello"), edit(CT, 'file = "Cesaroni_M1670.eng"', 'file = "motor.txt"')])
case("motor-csv-bad", sim_c, ["motor.csv"],
     edits=[write("ex/c/motor.csv", "time_s,thrust_N\n0,1\nx,y\n"),
            edit(CT, 'file = "Cesaroni_M1670.eng"', 'file = "motor.csv"')])
case("motor-rse-bad-xml", sim_c, ["motor.rse"],
     edits=[write("ex/c/motor.rse", "<engine-database><eng"),
            edit(CT, 'file = "Cesaroni_M1670.eng"', 'file = "motor.rse"')])

# --------------------------------------------------------------------------- drag curves
case("drag-mach-not-increasing", sim_c, ["powerOffDragCurve.csv".lower(), "mach"],
     edits=[edit(DRAG, "0.02,0.394981721", "0.005,0.394981721")])
case("drag-negative-cd", sim_c, ["poweroffdragcurve.csv", "cd"],
     edits=[edit(DRAG, "0.02,0.394981721", "0.02,-0.394981721")])
case("drag-single-row", sim_c, ["poweroffdragcurve.csv"],
     edits=[write(DRAG, "0.5,0.4\n")])
case("drag-empty", sim_c, ["poweroffdragcurve.csv"], edits=[write(DRAG, "")])
case("drag-text", sim_c, ["poweroffdragcurve.csv"],
     edits=[edit(DRAG, "0.02,0.394981721", "0.02,high")])
case("drag-nan", sim_c, ["poweroffdragcurve.csv"],
     edits=[edit(DRAG, "0.02,0.394981721", "0.02,nan")])
case("drag-one-column", sim_c, ["poweroffdragcurve.csv"],
     edits=[write(DRAG, "0.1\n0.2\n0.3\n")])
case("drag-negative-mach", sim_c, ["poweroffdragcurve.csv", "mach"],
     edits=[edit(DRAG, "0.01,0.333865758", "-0.01,0.333865758")])
case("drag-cd-absurd", sim_c, ["poweroffdragcurve.csv", "cd"],
     edits=[edit(DRAG, "0.02,0.394981721", "0.02,250.0")])
case("drag-power-on-negative", sim_c, ["powerondragcurve.csv", "cd"],
     edits=[lambda tmp: _replace_line(tmp / DRAG_ON, 1, "0.02,-0.4")])
case("drag-binary", sim_c, ["poweroffdragcurve.csv"], edits=[write(DRAG, b"\x00\x01\x02\xff")])

# --------------------------------------------------------------------------- aero tables
table_opt = "simulate {C} --table {T}/tables/Kestrel.csv"
case("table-option-missing", "simulate {C} --table {T}/none.csv", ["none", "not found"])
case("table-json-missing", sim_k, ["kestrel"], edits=[lambda tmp: (tmp / "tables/Kestrel.json").unlink()])
case("table-json-garbage", sim_k, ["kestrel.json"], edits=[write("tables/Kestrel.json", "{not json")])
case("table-json-wrong-format", sim_k, ["kestrel.json", "format"],
     edits=[edit("tables/Kestrel.json", '"format": "ironbark-aerotable"', '"format": "other"')])
case("table-json-negative-area", sim_k, ["kestrel", "reference_area"],
     edits=[edit("tables/Kestrel.json", '"reference_area_m2": 0.0081', '"reference_area_m2": -0.0081')])
case("table-csv-empty", sim_k, ["kestrel.csv"], edits=[write("tables/Kestrel.csv", "")])
case("table-csv-text-value", sim_k, ["kestrel.csv"],
     edits=[lambda tmp: _replace_field(tmp / "tables/Kestrel.csv", 2, 2, "abc")])
case("table-csv-nan", sim_k, ["kestrel.csv"],
     edits=[lambda tmp: _replace_field(tmp / "tables/Kestrel.csv", 2, 4, "nan")])
case("table-csv-missing-column", sim_k, ["kestrel", "coefficients"],
     edits=[lambda tmp: _drop_column(tmp / "tables/Kestrel.csv", "Cm")])
case("table-csv-missing-row", sim_k, ["kestrel.csv"],
     edits=[lambda tmp: _drop_line(tmp / "tables/Kestrel.csv", 5)])

# --------------------------------------------------------------------------- .ork files
ORK1 = "{ORK:01.One-stage_OR22.02.ork}"
case("ork-not-zip", "simulate {T}/ork/bad.ork", ["bad.ork"], edits=[write("ork/bad.ork", "hello")])
case("ork-empty", "simulate {T}/ork/bad.ork", ["bad.ork"], edits=[write("ork/bad.ork", b"")])
case("ork-truncated-zip", "simulate {T}/ork/bad.ork", ["bad.ork", "damaged"],
     edits=[lambda tmp: _truncated_copy(tmp, "01.One-stage_OR22.02.ork", "bad.ork")])
case("ork-truncated-gzip", "simulate {T}/ork/bad.ork", ["bad.ork", "damaged"],
     edits=[lambda tmp: _truncated_copy(tmp, "simplerocket_v1.2_gzip.ork", "bad.ork")])
case("ork-empty-zip", "simulate {T}/ork/bad.ork", ["bad.ork", "empty"],
     edits=[lambda tmp: _zip(tmp / "ork/bad.ork", {})])
case("ork-zip-bomb", "simulate {T}/ork/bomb.ork", ["bomb.ork", "inflate"],
     edits=[lambda tmp: _zip(tmp / "ork/bomb.ork", {"rocket.ork": _BOMB})])
case("ork-gzip-bomb", "simulate {T}/ork/bomb.ork", ["bomb.ork", "inflate"],
     edits=[lambda tmp: _gzip_bomb(tmp / "ork/bomb.ork")])
case("ork-bad-xml", "simulate {T}/ork/bad.ork", ["bad.ork", "xml"],
     edits=[lambda tmp: _zip(tmp / "ork/bad.ork", {"rocket.ork": b"<openrocket><rocket>"})])
case("ork-wrong-root", "simulate {T}/ork/bad.ork", ["bad.ork", "openrocket"],
     edits=[lambda tmp: _zip(tmp / "ork/bad.ork", {"rocket.ork": b"<html></html>"})])
case("ork-entity-expansion", "simulate {T}/ork/bad.ork", ["bad.ork"],
     edits=[lambda tmp: _zip(tmp / "ork/bad.ork", {"rocket.ork": _ENTITIES})])
case("ork-bad-version", "simulate {T}/ork/bad.ork", ["bad.ork", "version"],
     edits=[lambda tmp: _zip(tmp / "ork/bad.ork", {"rocket.ork": b'<openrocket version="0.1"/>'})])
case("ork-config-unknown", f"simulate {ORK1} --config [Z9999]", ["config", "z9999"])
case("ork-config-on-toml", "simulate {C} --config M1670", ["config", "openrocket"])
case("ork-two-stage", ["simulate", "{ORK:Two stage high power rocket.ork}"], ["stage"])
case("ork-motor-missing", ["simulate", "{ORK:A simple model rocket.ork}"], ["motor"])

# --------------------------------------------------------------------------- CLI options
case("opt-inclination-120", sim_c + " --inclination 120", ["--inclination", "90"])
case("opt-inclination-0", sim_c + " --inclination 0", ["--inclination"])
case("opt-inclination-negative", sim_c + " --inclination -5", ["--inclination"])
case("opt-inclination-nan", sim_c + " --inclination nan", ["--inclination"])
case("opt-inclination-1.5", sim_c + " --inclination 1.5", ["--inclination"])
case("opt-heading-nan", sim_c + " --heading nan", ["--heading"])
case("opt-heading-inf", sim_c + " --heading inf", ["--heading"])
case("opt-elevation-nan", sim_c + " --elevation nan", ["--elevation"])
case("opt-elevation-absurd", sim_c + " --elevation 90000", ["--elevation"])
case("opt-elevation-text", sim_c + " --elevation high", ["--elevation"])
case("opt-rail-negative", sim_c + " --rail-length -1", ["--rail-length", "> 0"])
case("opt-rail-zero", sim_c + " --rail-length 0", ["--rail-length"])
case("opt-rail-nan", sim_c + " --rail-length nan", ["--rail-length"])
case("opt-rail-too-short", sim_c + " --rail-length 0.5", ["--rail-length"])
case("opt-ballast-negative", sim_c + " --ballast -1", ["--ballast", ">= 0"])
case("opt-ballast-nan", sim_c + " --ballast nan", ["--ballast"])
case("opt-ballast-huge", sim_c + " --ballast 1000", ["--ballast"])
case("opt-ballast-x-outside-body", sim_c + " --ballast 1 --ballast-x 10", ["--ballast-x", "body"])
case("opt-ballast-x-negative", sim_c + " --ballast 1 --ballast-x -1", ["--ballast-x"])
case("opt-ballast-x-nan", sim_c + " --ballast 1 --ballast-x nan", ["--ballast-x"])
case("opt-ballast-outside-bay", sim_k + " --ballast 1 --ballast-x 1.5", ["--ballast-x", "bay"])
case("opt-ballast-over-capacity", sim_k + " --ballast 5", ["--ballast", "mass_max"])
case("opt-rail-exit-unknown", sim_c + " --rail-exit sideways", ["--rail-exit"])
case("opt-unknown-option", sim_c + " --frobnicate 3", ["--frobnicate"])
case("opt-inclination-no-value", sim_c + " --inclination", ["--inclination"])
case("opt-config-empty", f"simulate {ORK1} --config ''", ["config"])
ball_c = "ballast {C} --target 3000m"
ball_k = "ballast {K} --target 3000m"
case("ballast-target-text", "ballast {C} --target high", ["target"])
case("ballast-target-negative", "ballast {C} --target -3000m", ["target"])
case("ballast-target-unit", "ballast {C} --target 3000parsec", ["target"])
case("ballast-target-nan", "ballast {C} --target nanm", ["target"])
case("ballast-target-missing", "ballast {C}", ["--target"])
case("ballast-max-negative", ball_c + " --max-ballast -1", ["--max-ballast"])
case("ballast-max-nan", ball_c + " --max-ballast nan", ["--max-ballast"])
case("ballast-x-outside", ball_c + " --ballast-x 10", ["--ballast-x", "body"])
case("ballast-x-outside-bay", ball_k + " --ballast-x 1.5", ["--ballast-x", "bay"])
case("ballast-x-nan", ball_c + " --ballast-x nan", ["--ballast-x"])
case("ballast-min-margin-nan", ball_c + " --min-margin nan", ["--min-margin"])
case("ballast-min-rail-speed-negative", ball_c + " --min-rail-speed -5", ["--min-rail-speed"])
case("ballast-max-over-bay", ball_k + " --max-ballast 10", ["--max-ballast", "mass_max"])
case("ballast-processes-zero", ball_c + " --motor {CD}/Cesaroni_M1670.eng --processes 0", ["--processes"])
case("ballast-executor-bad", ball_c + " --motor {CD}/Cesaroni_M1670.eng --executor ftp://x", ["executor"])
case("ballast-executor-no-motor", ball_c + " --executor local", ["--executor"])
case("ballast-objective-bad", ball_c + " --objective cheapest", ["--objective"])
case("ballast-forecast-no-time", ball_c + " --forecast rap", ["--time"])
case("ballast-motor-missing-path", ball_c + " --motor nope.eng", ["nope.eng", "not found"])
case("ballast-motor-missing-dir-path", ball_c + " --motor {T}/motors/nope.eng", ["nope.eng", "not found"])
case("ballast-motor-empty-dir", ball_c + " --motor {T}/emptydir", ["emptydir", "no motor files"],
     edits=[lambda tmp: (tmp / "emptydir").mkdir()])
case("ballast-motor-bad-file", ball_c + " --motor {T}/bad.eng", ["bad.eng"], edits=[write("bad.eng", "xx\n")])
case("ballast-unstable", ball_c, ["static margin", "--allow-unstable"],
     edits=[edit(CT, "cg_x = 1.278", "cg_x = 2.40")])
case("ballast-toml-broken", ball_c, ["calisto.toml:", "syntax"],
     edits=[edit(CT, 'name = "Calisto"', 'name = "Calisto')])
rob_c = ball_c + " --robust --spec {CD}/dispersions.toml --check-samples 0"
case("ballast-robust-no-spec", ball_c + " --robust", ["--spec"])
case("ballast-robust-spec-missing", ball_c + " --robust --spec {T}/nope.toml", ["nope.toml", "not found"])
case("ballast-robust-objective-motor", rob_c + " --objective least_ballast", ["--robust", "in_band"])
case("ballast-robust-objective-no-flag", ball_c + " --objective in_band", ["--robust"])
case("ballast-robust-band-negative", rob_c + " --band -5", ["band"])
case("ballast-robust-samples-few", rob_c + " --samples 2", ["samples"])
case("ballast-robust-with-motor", rob_c + " --motor {CD}/Cesaroni_M1670.eng", ["--robust", "--motor"])
case("ballast-robust-spec-disperses-ballast", rob_c, ["dispersions.toml", "ballast_mass"],
     edits=[(CD_SPEC, None, '[parameters.ballast_mass]\ndistribution = "normal"\nstd = 0.1\n')])
WIN = "window {C} --forecast rap --site spaceport --from 2025-06-20T15:00Z"
case("window-from-not-a-time", "window {C} --forecast rap --site spaceport --from tomorrow", ["--from", "iso"])
case("window-hours-zero", WIN + " --hours 0", ["--hours"])
case("window-no-site", "window {C} --forecast rap --from 2025-06-20T15:00Z", ["--site"])
case("window-site-unknown", "window {C} --forecast rap --site atlantis --from 2025-06-20T15:00Z", ["atlantis"])
case("window-forecast-unknown", "window {C} --forecast ecmwf --site spaceport --from 2025-06-20T15:00Z",
     ["--forecast"])
case("window-band-zero", WIN + " --band 0", ["--band"])
case("window-plot-suffix", WIN + " --plot {T}/w.txt", ["--plot"], outputs=["w.txt"])
case("window-spec-missing", WIN + " --spec {T}/nope.toml", ["nope.toml", "not found"])
MC = "montecarlo {C} --spec {CD}/dispersions.toml --no-progress"
case("mc-samples-huge", MC + " --samples 1000000000000", ["--samples"])
case("mc-samples-zero", MC + " --samples 0", ["--samples"])
case("mc-samples-negative", MC + " --samples -5", ["--samples"])
case("mc-samples-text", MC + " --samples many", ["--samples"])
case("mc-seed-negative", MC + " --seed -1", ["--seed"])
case("mc-chunk-zero", MC + " --chunk 0", ["--chunk"])
case("mc-band-negative", MC + " --samples 4 --target 3000m --band -5", ["--band"])
case("mc-band-nan", MC + " --samples 4 --target 3000m --band nan", ["--band"])
case("mc-target-bad", MC + " --samples 4 --target tall", ["target"])
case("mc-spec-missing", "montecarlo {C} --spec {T}/nospec.toml --samples 4", ["nospec.toml", "not found"])
case("mc-spec-broken", MC + " --samples 4", ["dispersions.toml:"],
     edits=[write("ex/c/dispersions.toml", "[x\n")])
case("mc-spec-unknown-param", MC + " --samples 4", ["dispersions.toml", "frobnication"],
     edits=[write("ex/c/dispersions.toml", "[parameters.frobnication]\ndistribution = \"normal\"\nstd = 1\n")])
case("mc-executor-bad", MC + " --samples 4 --executor ftp://x", ["executor"])
case("sens-param-unknown", "sensitivity {C} --param frobnication", ["frobnication"])
case("sens-target-bad", "sensitivity {C} --target tall", ["target"])
case("sens-ballast-negative", "sensitivity {C} --ballast -1", ["--ballast"])
case("aero-build-mach-text", "aero build {C} --mach a,b --out {T}/t", ["--mach"])
case("aero-build-alpha-negative", "aero build {C} --alpha-deg -5,0 --out {T}/t", ["alpha"])
case("aero-build-workers-zero", "aero build {C} --workers 0 --out {T}/t", ["--workers"])
case("aero-build-refine-negative", "aero build {C} --refine -1 --out {T}/t", ["--refine"])
case("aero-plot-missing-table", "aero plot {T}/none.csv --out {T}/p.png", ["none", "not found"], outputs=["p.png"])
case("motor-get-offline-format", "motor get K550W --format XYZ --offline", ["--format"])
case("motor-get-dir-is-file", "motor get K550W --offline -o {C}", ["-o"])
case("motor-search-max-results-zero", "motor search --designation K550W --max-results 0 --offline", ["--max-results"])
case("motor-search-diameter-negative", "motor search --diameter-mm -5 --offline", ["--diameter-mm"])
case("ork-info-missing", "ork info {T}/none.ork", ["none.ork", "no such file"])
case("weather-lat-out", "weather get --model rap --lat 95 --lon 0 --time 2025-06-20T15:00Z --offline", ["lat"])
case("weather-file-missing", "weather get --model sounding --file {T}/none.txt", ["none.txt"])

# --------------------------------------------------------------------------- output paths
case("out-plot-missing-folder", sim_c + " --plot {T}/nofolder/x.png", ["--plot", "nofolder"],
     outputs=["nofolder"])
case("out-plot-unknown-ext", sim_c + " --plot {T}/x.bmpx", ["--plot", "png"], outputs=["x.bmpx"])
case("out-plot-is-dir", sim_c + " --plot {T}/ex", ["--plot", "directory"])
case("out-csv-missing-folder", sim_c + " --csv {T}/nofolder/x.csv", ["--csv", "nofolder"],
     outputs=["nofolder"])
case("out-csv-under-a-file", sim_c + " --csv {T}/ex/c/calisto.toml/x.csv", ["--csv"])
case("out-csv-is-dir", sim_c + " --csv {T}/ex", ["--csv", "directory"])
case("out-csv-full-disk", sim_c + " --csv /dev/full", ["--csv", "/dev/full"])
case("out-csv-readonly-dir", sim_c + " --csv /proc/x.csv", ["--csv"])
case("out-csv-bad-input-no-file", sim_c + " --csv {T}/x.csv --rail-length -1", ["--rail-length"],
     outputs=["x.csv"])
case("out-plot-bad-input-no-file", sim_c + " --plot {T}/x.png --inclination 120", ["--inclination"],
     outputs=["x.png"])
case("out-ballast-plot-missing-folder", ball_c + " --plot {T}/nofolder/x.png", ["--plot"], outputs=["nofolder"])
case("out-ballast-plot-ext", ball_c + " --plot {T}/x.txt", ["--plot"], outputs=["x.txt"])
case("out-mc-csv-missing-folder", MC + " --samples 4 --csv {T}/nofolder/x.csv", ["--csv"])
case("out-mc-histogram-ext", MC + " --samples 4 --histogram {T}/x.doc", ["--histogram"], outputs=["x.doc"])
case("out-mc-ellipse-missing", MC + " --samples 4 --descent --ellipse {T}/no/x.png", ["--ellipse"])
case("out-mc-results-dir-is-file", MC + " --samples 4 --results-dir {C}", ["--results-dir"])
case("out-sens-csv-missing", "sensitivity {C} --csv {T}/no/x.csv", ["--csv"])
case("out-sens-plot-ext", "sensitivity {C} --plot {T}/x.gif", ["--plot"], outputs=["x.gif"])
case("out-aero-build-under-file", "aero build {C} --out {C}/sub/t", ["--out"])
case("out-aero-build-missing-folder", "aero build {C} --out {T}/no/where/t", ["--out"])
case("out-aero-plot-ext", "aero plot {T}/tables/Kestrel.csv --out {T}/p.xyz", ["--out"], outputs=["p.xyz"])
case("out-aero-plot-under-file", "aero plot {T}/tables/Kestrel.csv --out {C}/p.png", ["--out"])
case("out-motor-download-dir-is-file", "motor get K550W --offline -o {CD}/calisto.toml/x", ["output-dir"])
case("out-weather-csv-missing", "weather get --model sounding --file {T}/x.txt --csv {T}/no/x.csv",
     ["--csv"], edits=[write("x.txt", "x")])

# --------------------------------------------------------------------------- network faults (exit 3)
case("net-search-closed-port", "motor search --designation K550W", ["thrustcurve", "cache"], status=3, net="closed")
case("net-download-closed-port", "motor get K550W -o {T}", ["thrustcurve", "cache"], status=3, net="closed")
case("net-search-500", "motor search --designation K550W", ["thrustcurve", "500"], status=3,
     net="loopback:500")
case("net-search-garbage", "motor search --designation K550W", ["thrustcurve"], status=3,
     net="loopback:garbage")
case("net-search-truncated", "motor search --designation K550W", ["thrustcurve"], status=3,
     net="loopback:truncate")
case("net-offline-not-cached", "motor get K550W --offline -o {T}", ["cache", "offline"], status=3,
     net="closed")
case("net-ballast-name-closed-port", ball_c + " --motor K550W", ["k550w"], status=3, net="closed")
case("net-forecast-closed-port", ball_c + " --forecast rap --site spaceport --time 2025-06-20T15:00Z",
     ["cache"], status=3, net="closed")
case("net-window-closed-port", WIN + " --hours 2 --plot {T}/w.png", ["cache"], status=3, net="closed",
     outputs=["w.png"])


# --------------------------------------------------------------------------- helpers
_BOMB_SIZE = 300 * 1024 * 1024          # inflates to 300 MB: over the 200 MB cap
_BOMB = None                             # built lazily (zipfile streams it)


def _zip(path: Path, members: dict) -> None:
    path.parent.mkdir(parents=True, exist_ok=True)
    with zipfile.ZipFile(path, "w", compression=zipfile.ZIP_DEFLATED) as zf:
        for name, data in members.items():
            if data is None:             # the bomb: stream zeros
                with zf.open(name, "w", force_zip64=True) as fh:
                    chunk = b"<openrocket>" + b" " * (1024 * 1024 - 12)
                    for _ in range(_BOMB_SIZE // len(chunk)):
                        fh.write(chunk)
            else:
                zf.writestr(name, data)


def _gzip_bomb(path: Path) -> None:
    path.parent.mkdir(parents=True, exist_ok=True)
    with gzip.open(path, "wb", compresslevel=1) as fh:
        chunk = b" " * (1024 * 1024)
        fh.write(b"<openrocket>")
        for _ in range(_BOMB_SIZE // len(chunk)):
            fh.write(chunk)


_ENTITIES = (b'<?xml version="1.0"?><!DOCTYPE r [<!ENTITY a "aaaaaaaaaa">'
             b'<!ENTITY b "&a;&a;&a;&a;&a;&a;&a;&a;&a;&a;"><!ENTITY c "&b;&b;&b;&b;&b;&b;&b;&b;&b;&b;">]>'
             b'<openrocket version="1.9">&c;</openrocket>')


def _truncated_copy(tmp: Path, name: str, out: str) -> None:
    data = (DATA / "ork" / name).read_bytes()
    (tmp / "ork").mkdir(exist_ok=True)
    (tmp / "ork" / out).write_bytes(data[: len(data) // 2])


def _replace_line(path: Path, index: int, text: str) -> None:
    lines = path.read_text().splitlines()
    lines[index] = text
    path.write_text("\n".join(lines) + "\n")


def _drop_line(path: Path, index: int) -> None:
    lines = path.read_text().splitlines()
    del lines[index]
    path.write_text("\n".join(lines) + "\n")


def _replace_field(path: Path, row: int, col: int, text: str) -> None:
    lines = path.read_text().splitlines()
    cells = lines[row].split(",")
    cells[col] = text
    lines[row] = ",".join(cells)
    path.write_text("\n".join(lines) + "\n")


def _drop_column(path: Path, name: str) -> None:
    lines = [ln.split(",") for ln in path.read_text().splitlines()]
    i = lines[0].index(name)
    path.write_text("\n".join(",".join(c[:i] + c[i + 1:]) for c in lines) + "\n")
