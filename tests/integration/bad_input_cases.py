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
    env: tuple = ()                 # (NAME, value) pairs set for the run ({T}, {C}... expanded)


CASES: list[Case] = []


def case(id, argv, needles=(), status=2, edits=(), outputs=(), net=None, env=()):
    CASES.append(Case(id, tuple(argv.split()) if isinstance(argv, str) else tuple(argv),
                      tuple(needles), status, tuple(edits), tuple(outputs), net, tuple(env)))


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
case("toml-motor-kind-unknown", sim_c, ["calisto.toml", "motor.kind", "hybrid"],
     edits=[edit(CT, 'designation = "M1670"', 'designation = "M1670"\nkind = "nuclear"')])
case("toml-hybrid-with-solid-overrides", sim_c, ["calisto.toml", "propellant_cg", "tanks"],
     edits=[edit(CT, 'designation = "M1670"', 'designation = "M1670"\nkind = "hybrid"')])
case("toml-ejection-delay-negative", sim_c, ["calisto.toml", "ejection_delay", ">= 0"],
     edits=[edit(CT, 'designation = "M1670"', 'designation = "M1670"\nejection_delay = -2.0')])
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
# --site/--time without --forecast were ignored by simulate, sensitivity and montecarlo (ballast
# refused them): `simulate --site euroc --kml F` drew the file's site, not EuRoC's
case("simulate-site-without-forecast", sim_c + " --site euroc --kml {T}/f.kml", ["--site", "--forecast"],
     outputs=["f.kml"])
case("sensitivity-time-without-forecast", "sensitivity {C} --time 2025-06-20T15:00Z", ["--time", "--forecast"])
case("mc-site-without-forecast", "montecarlo {C} --spec {CD}/dispersions.toml --no-progress --samples 10"
     " --site euroc", ["--site", "--forecast"])
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
case("ballast-robust-card-spec", rob_c + " --card {T}/card.png --card-spec {CD}/dispersions.toml",
     ["--robust", "--card-spec"], outputs=["card.png"])
case("ballast-robust-select-samples-negative", rob_c + " --select-samples -1", ["select_samples"])
case("ballast-robust-min-gain-t-nan", rob_c + " --min-gain-t nan", ["--min-gain-t", "finite"])
case("ballast-robust-min-rail-speed-text", rob_c + " --min-rail-speed fast", ["--min-rail-speed"])
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
GEFS = "window {C} --forecast gefs --site spaceport --from 2025-06-20T15:00Z"
case("window-gefs-members-zero", GEFS + " --members 0", ["--members"])
case("window-gefs-go-fraction", GEFS + " --min-go-fraction 1.5", ["--min-go-fraction"])
case("window-rap-members", WIN + " --members 3", ["--members", "deterministic"])
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
case("out-sim-kml-ext", sim_c + " --kml {T}/x.kmz", ["--kml", ".kml"], outputs=["x.kmz"])
case("out-sim-csv-format", sim_c + " --csv {T}/x.csv --csv-format excel", ["--csv-format"], outputs=["x.csv"])
case("out-ballast-card-missing-folder", ball_c + " --card {T}/no/c.pdf", ["--card", "no"], outputs=["no"])
case("out-ballast-card-ext", ball_c + " --card {T}/c.doc", ["--card", ".pdf"], outputs=["c.doc"])
case("out-ballast-card-spec-missing", ball_c + " --card {T}/c.pdf --card-spec {T}/none.toml", ["none.toml"],
     outputs=["c.pdf"])
case("out-ballast-card-spec-alone", ball_c + " --card-spec {CD}/dispersions.toml", ["--card-spec", "--card"])
case("out-mc-samples-out-ext", MC + " --samples 4 --samples-out {T}/x.xlsx", ["--samples-out", ".parquet"],
     outputs=["x.xlsx"])
case("out-mc-kml-missing-folder", MC + " --samples 4 --kml {T}/no/x.kml", ["--kml"], outputs=["no"])
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
case("net-window-gefs-closed-port", GEFS + " --members 3 --plot {T}/w.png", ["gefs", "dataset.xml"], status=3,
     net="closed", outputs=["w.png"])


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


# =========================================================================== second batch
# Kinds the first 234 rows did not cover: flight logs and their options, calibration
# files, [airbrakes], [[airstart]], atmosphere files, aero build/plot options, weather
# and motor outputs, environment variables, dispersion specs, NaN/inf in numeric options.
TEL = "{D}/telemetry"
RRC3 = DATA / "telemetry/euroc21-sta-carl2-rrc3.csv"
ALTOS = DATA / "telemetry/issuiuc-2021-endurance-telemetrum.csv"
LOG = "log.csv"
cmp_c = "flight compare {C} {T}/" + LOG
cal_c = "calibrate {C} {T}/" + LOG


def _head(src: Path, lines: int):
    """The first ``lines`` lines of a log (a file cut short by a dying battery)."""
    return "".join(src.read_text(errors="replace").splitlines(keepends=True)[:lines])


def _rrc3(replace_row: int | None = None, value: str = "abc"):
    """The RRC3 log with the altitude of data row ``replace_row`` replaced."""
    rows = RRC3.read_text().splitlines(keepends=True)
    if replace_row is not None:
        cells = rows[replace_row].split(";")
        cells[1] = value
        rows[replace_row] = ";".join(cells)
    return "".join(rows)


def _gzip_cut(tmp: Path):
    blob = gzip.compress(RRC3.read_bytes())
    (tmp / "log.csv.gz").write_bytes(blob[: len(blob) // 2])


GENERIC = "t_s,alt_m\n" + "".join(f"{0.1 * i:.1f},{max(0.0, 50 * (0.1 * i) - 2.0 * (0.1 * i) ** 2):.2f}\n"
                                  for i in range(200))

# --- flight logs (flight compare / calibrate)
case("b2-log-missing", cmp_c.replace(LOG, "nope.csv"), ["nope.csv", "not found"])
case("b2-log-directory", "flight compare {C} {T}/ex", ["ex", "directory"])
case("b2-log-empty", cmp_c, ["log.csv"], edits=[write(LOG, "")])
case("b2-log-binary", cmp_c, ["log.csv"], edits=[write(LOG, bytes(range(256)) * 8)])
case("b2-log-foreign-motor", "flight compare {C} {CD}/Cesaroni_M1670.eng", ["cesaroni_m1670.eng", "flight log"])
case("b2-log-foreign-toml", "calibrate {C} {C}", ["calisto.toml", "flight log"])
case("b2-log-truncated-altos", cmp_c, ["log.csv"], edits=[write(LOG, _head(ALTOS, 4))])
case("b2-log-truncated-rrc3", cal_c, ["log.csv"], edits=[write(LOG, _head(RRC3, 3))])
case("b2-log-truncated-gzip", "flight compare {C} {T}/log.csv.gz", ["log.csv.gz"], edits=[_gzip_cut])
case("b2-log-text-altitude", cmp_c, ["log.csv:41", "altitude"], edits=[write(LOG, _rrc3(40))])
case("b2-log-inf-altitude", cmp_c, ["log.csv:41", "finite"], edits=[write(LOG, _rrc3(40, "inf"))])
case("b2-log-no-liftoff", cmp_c + " --columns time=t_s:s,altitude=alt_m:m", ["log.csv", "liftoff"],
     edits=[write(LOG, "t_s,alt_m\n" + "".join(f"{0.1 * i:.1f},0.0\n" for i in range(100)))])
case("b2-columns-no-equals", cmp_c + " --columns time", ["--columns", "time"], edits=[write(LOG, GENERIC)])
case("b2-columns-unknown-channel", cmp_c + " --columns time=t_s:s,height=alt_m:m", ["--columns", "height"],
     edits=[write(LOG, GENERIC)])
case("b2-columns-unknown-unit", cmp_c + " --columns time=t_s:s,altitude=alt_m:furlong",
     ["--columns", "furlong"], edits=[write(LOG, GENERIC)])
case("b2-columns-missing-column", cmp_c + " --columns time=Time:s,altitude=alt_m:m", ["log.csv", "time"],
     edits=[write(LOG, GENERIC)])
case("b2-columns-no-time", cmp_c + " --columns altitude=alt_m:m", ["--columns", "time"],
     edits=[write(LOG, GENERIC)])
case("b2-log-format-unknown", cmp_c + " --format nosuch", ["--format", "nosuch"], edits=[write(LOG, GENERIC)])
case("b2-calibrate-until-negative", cal_c + " --until -5", ["--until"], edits=[write(LOG, _rrc3())])
case("b2-calibrate-until-nan", cal_c + " --until nan", ["--until"], edits=[write(LOG, _rrc3())])
case("b2-calibrate-until-fraction-nan", cal_c + " --until-fraction nan", ["--until-fraction"],
     edits=[write(LOG, _rrc3())])
case("b2-calibrate-param-unknown", cal_c + " --param wings", ["wings"], edits=[write(LOG, _rrc3())])
case("b2-calibrate-output-ext", cal_c + " -o {T}/cal.xyz", ["--output", ".xyz"], edits=[write(LOG, _rrc3())],
     outputs=["cal.xyz"])
case("b2-calibrate-output-missing-folder", cal_c + " -o {T}/no/cal.toml", ["--output", "folder"],
     edits=[write(LOG, _rrc3())])
case("b2-compare-plot-under-file", cmp_c + " --plot {C}/cmp.png", ["--plot"], edits=[write(LOG, _rrc3())])

# --- calibration files (--calibration)
sim_cal = "simulate {C} --calibration {T}/cal.toml"
case("b2-cal-missing", "simulate {C} --calibration {T}/nope.toml", ["nope.toml", "not found"])
case("b2-cal-syntax", sim_cal, ["cal.toml"], edits=[write("cal.toml", "[parameters\ndrag_scale = 1\n")])
case("b2-cal-nan", sim_cal, ["cal.toml", "drag_scale"], edits=[write("cal.toml", "[parameters]\ndrag_scale = nan\n")])
case("b2-cal-negative", sim_cal, ["cal.toml", "thrust_scale"],
     edits=[write("cal.toml", "[parameters]\nthrust_scale = -1.0\n")])
case("b2-cal-string", sim_cal, ["cal.toml", "drag_scale"],
     edits=[write("cal.toml", "[parameters]\ndrag_scale = \"big\"\n")])
case("b2-cal-json-garbage", "simulate {C} --calibration {T}/cal.json", ["cal.json"], edits=[write("cal.json", "{")])
case("b2-cal-no-parameters", sim_cal, ["cal.toml", "parameters"], edits=[write("cal.toml", "x = 1\n")])
case("b2-cal-wrong-ext", "simulate {C} --calibration {T}/cal.txt", ["cal.txt"],
     edits=[write("cal.txt", "[parameters]\ndrag_scale = 1.0\n")])
case("b2-cal-on-montecarlo-inf", "montecarlo {C} --spec {CD}/dispersions.toml --calibration {T}/cal.toml",
     ["cal.toml", "drag_scale"], edits=[write("cal.toml", "[parameters]\ndrag_scale = inf\n")])


# --- [airbrakes]
def _brakes(extra: str, table: bool = True):
    def go(tmp: Path):
        root = Path(__file__).resolve().parents[2]
        if table:
            (tmp / "ex/c/drag_airbrakes.csv").write_bytes(
                (root / "examples/calisto_airbrakes/drag_airbrakes.csv").read_bytes())
        toml = tmp / CT
        toml.write_text(toml.read_text() + "\n[airbrakes]\n" + extra + "\n")
    return go


AB = 'drag = "drag_airbrakes.csv"\ndrag_is = "total"\n'
case("b2-ab-drag-missing", sim_c, ["calisto.toml", "nope.csv"],
     edits=[_brakes('drag = "nope.csv"\ntrigger = "time"\nstart = 5.4\nrate = 2.0', table=False)])
case("b2-ab-trigger-unknown", sim_c, ["calisto.toml", "trigger"],
     edits=[_brakes(AB + 'trigger = "sound"\nstart = 5.4\nrate = 2.0')])
case("b2-ab-level-over-1", sim_c, ["calisto.toml", "level"],
     edits=[_brakes(AB + 'trigger = "time"\nstart = 5.4\nrate = 2.0\nlevel = 1.5')])
case("b2-ab-rate-negative", sim_c, ["calisto.toml", "rate"],
     edits=[_brakes(AB + 'trigger = "time"\nstart = 5.4\nrate = -2.0')])
case("b2-ab-time-without-rate", sim_c, ["calisto.toml", "rate"],
     edits=[_brakes(AB + 'trigger = "time"\nstart = 5.4')])
case("b2-ab-altitude-without-ramp", sim_c, ["calisto.toml", "ramp"],
     edits=[_brakes(AB + 'trigger = "altitude"\nstart = 1000.0')])
case("b2-ab-drag-is-bad", sim_c, ["calisto.toml", "drag_is"],
     edits=[_brakes('drag = "drag_airbrakes.csv"\ndrag_is = "half"\ntrigger = "time"\nstart = 5.4\nrate = 2.0')])
case("b2-ab-start-nan", sim_c, ["calisto.toml", "start"],
     edits=[_brakes(AB + 'trigger = "time"\nstart = nan\nrate = 2.0')])
case("b2-ab-unknown-key", sim_c, ["calisto.toml", "colour"],
     edits=[_brakes(AB + 'trigger = "time"\nstart = 5.4\nrate = 2.0\ncolour = "red"')])
case("b2-ab-table-negative-cd", sim_c, ["drag_airbrakes.csv", "cd"],
     edits=[_brakes(AB + 'trigger = "time"\nstart = 5.4\nrate = 2.0'),
            edit("ex/c/drag_airbrakes.csv", "0.1, 0.1, 0.7663", "0.1, 0.1, -0.7663")])
case("b2-ab-table-nan", sim_c, ["drag_airbrakes.csv"],
     edits=[_brakes(AB + 'trigger = "time"\nstart = 5.4\nrate = 2.0'),
            edit("ex/c/drag_airbrakes.csv", "0.1, 0.1, 0.7663", "0.1, 0.1, nan")])
case("b2-ab-table-not-a-grid", sim_c, ["drag_airbrakes.csv", "grid"],
     edits=[_brakes(AB + 'trigger = "time"\nstart = 5.4\nrate = 2.0'),
            edit("ex/c/drag_airbrakes.csv", "0.1, 0.1, 0.7663\n", "")])
case("b2-ab-controller-file-missing", sim_c, ["calisto.toml", "nope.py"],
     edits=[_brakes(AB + 'trigger = "controller"\ncontroller = "nope.py:ctl"\nsampling_rate = 10.0\nrate = 2.0')])
case("b2-ab-controller-no-function", sim_c, ["ctl.py", "missing"],
     edits=[_brakes(AB + 'trigger = "controller"\ncontroller = "ctl.py:missing"\nsampling_rate = 10.0\nrate = 2.0'),
            write("ex/c/ctl.py", "def ctl(time_s, state):\n    return 0.0\n")])
case("b2-ab-sampling-rate-zero", sim_c, ["calisto.toml", "sampling_rate"],
     edits=[_brakes(AB + 'trigger = "controller"\ncontroller = "ctl.py:ctl"\nsampling_rate = 0.0\nrate = 2.0'),
            write("ex/c/ctl.py", "def ctl(time_s, state):\n    return 0.0\n")])


# --- [[airstart]]
def _airstart(body: str, motor: bool = True):
    def go(tmp: Path):
        if motor:
            (tmp / "ex/c/AeroTech_I211W.eng").write_bytes((DATA / "motors/AeroTech_I211W.eng").read_bytes())
        toml = tmp / CT
        toml.write_text(toml.read_text() + "\n[[airstart]]\n" + body + "\n")
    return go


case("b2-as-file-missing", sim_c, ["calisto.toml", "nope.eng"],
     edits=[_airstart('file = "nope.eng"\nnozzle_x = 2.5\nignition_time = 4.0', motor=False)])
case("b2-as-ignition-negative", sim_c, ["calisto.toml", "ignition_time"],
     edits=[_airstart('file = "AeroTech_I211W.eng"\nnozzle_x = 2.5\nignition_time = -1.0')])
case("b2-as-ignition-nan", sim_c, ["calisto.toml", "ignition_time"],
     edits=[_airstart('file = "AeroTech_I211W.eng"\nnozzle_x = 2.5\nignition_time = nan')])
case("b2-as-no-nozzle", sim_c, ["calisto.toml", "nozzle_x"],
     edits=[_airstart('file = "AeroTech_I211W.eng"\nignition_time = 4.0')])
case("b2-as-unknown-key", sim_c, ["calisto.toml", "delay"],
     edits=[_airstart('file = "AeroTech_I211W.eng"\nnozzle_x = 2.5\nignition_time = 4.0\ndelay = 3')])
case("b2-as-nozzle-outside-body", sim_c, ["nozzle"],
     edits=[_airstart('file = "AeroTech_I211W.eng"\nnozzle_x = 9.0\nignition_time = 4.0')])

# --- atmosphere files ([launch] atmosphere, --atmosphere)
REAN = "{D}/weather/reanalysis/euroc_2022_all_windows.nc"
case("b2-atm-missing", "simulate {C} --atmosphere {T}/nope.nc", ["nope.nc", "not found"])
case("b2-atm-corrupt-nc", "simulate {C} --atmosphere {T}/bad.nc", ["bad.nc"],
     edits=[write("bad.nc", b"CDF\x01" + bytes(range(200)))])
case("b2-atm-truncated-nc", "simulate {C} --atmosphere {T}/cut.nc", ["cut.nc"],
     edits=[lambda tmp: (tmp / "cut.nc").write_bytes(
         (DATA / "weather/reanalysis/bella_lui_weather_data_ERA5.nc").read_bytes()[:5000])])
case("b2-atm-multi-time-no-time", "simulate {C} --atmosphere " + REAN, ["euroc_2022_all_windows.nc", "time"])
case("b2-atm-time-not-iso", "simulate {C} --atmosphere " + REAN + " --atmosphere-time yesterday",
     ["yesterday"])
case("b2-atm-time-outside-file", "simulate {C} --atmosphere " + REAN + " --atmosphere-time 1999-01-01T00:00Z",
     ["euroc_2022_all_windows.nc", "1999"])
case("b2-atm-wrong-variables-nc", "simulate {C} --atmosphere {T}/vars.nc", ["vars.nc"],
     edits=[lambda tmp: _netcdf_without_temperature(tmp / "vars.nc")])
case("b2-atm-json-not-monotone", "simulate {C} --atmosphere {T}/p.json", ["p.json", "altitude"],
     edits=[write("p.json", '{"levels": {"altitude_m": [0, 2000, 1000], "temperature_K": [288.0, 275.0, 281.5],'
                            ' "pressure_Pa": [101325, 79500, 89880]}}')])
case("b2-atm-csv-not-monotone", "simulate {C} --atmosphere {T}/p.csv", ["p.csv", "altitude"],
     edits=[write("p.csv", "altitude_m,temperature_K,pressure_Pa\n0,288.0,101325\n2000,275.0,79500\n"
                           "1000,281.5,89880\n")])
case("b2-atm-csv-negative-pressure", "simulate {C} --atmosphere {T}/p.csv", ["p.csv", "pressure"],
     edits=[write("p.csv", "altitude_m,temperature_K,pressure_Pa\n0,288.0,101325\n1000,281.5,-89880\n"
                           "2000,275.0,79500\n")])
case("b2-atm-json-garbage", "simulate {C} --atmosphere {T}/p.json", ["p.json"], edits=[write("p.json", "[1, 2")])
case("b2-atm-toml-missing-file", sim_c, ["calisto.toml", "nope.nc"],
     edits=[edit(CT, "[launch]", '[launch]\natmosphere = "nope.nc"')])
case("b2-atm-toml-unknown-key", sim_c, ["calisto.toml", "when"],
     edits=[edit(CT, "[launch]", '[launch]\natmosphere = {file = "x.nc", when = "2022-10-13T12:00Z"}')])


def _netcdf_without_temperature(path: Path):
    """A valid netCDF3 file with the grid but no temperature (``t``) variable."""
    import numpy as np
    from scipy.io import netcdf_file
    with netcdf_file(path, "w") as nc:
        nc.createDimension("latitude", 2)
        nc.createDimension("longitude", 2)
        nc.createDimension("level", 3)
        for name, values in (("latitude", [39.0, 40.0]), ("longitude", [-8.5, -7.5]),
                             ("level", [1000.0, 850.0, 700.0])):
            var = nc.createVariable(name, "f4", (name,))
            var[:] = np.array(values, dtype="f4")
        var = nc.createVariable("u", "f4", ("level", "latitude", "longitude"))
        var[:] = np.zeros((3, 2, 2), dtype="f4")


# --- aero build / aero plot
case("b2-aero-build-mach-descending", "aero build {C} --mach 0.5,0.3 --out {T}/tables/x", ["--mach"],
     outputs=["tables/x.csv"])
case("b2-aero-build-mach-nan", "aero build {C} --mach 0.3,nan --out {T}/tables/x", ["--mach"])
case("b2-aero-build-mach-negative", "aero build {C} --mach -0.3,0.5 --out {T}/tables/x", ["--mach"])
case("b2-aero-build-mach-huge", "aero build {C} --mach 0.3,50 --out {T}/tables/x", ["--mach"])
case("b2-aero-build-alpha-over-90", "aero build {C} --alpha-deg 0,95 --out {T}/tables/x", ["--alpha-deg"])
case("b2-aero-build-alpha-nan", "aero build {C} --alpha-deg 0,nan --out {T}/tables/x", ["--alpha-deg"])
case("b2-aero-build-refine-nan", "aero build {C} --refine nan --out {T}/tables/x", ["--refine"])
case("b2-aero-build-refine-huge", "aero build {C} --refine 1e9 --out {T}/tables/x", ["--refine"])
case("b2-aero-build-workers-huge", "aero build {C} --workers 1000000 --out {T}/tables/x", ["--workers"])
case("b2-aero-build-out-is-dir", "aero build {C} --out {T}/ex", ["--out"])
case("b2-aero-plot-json-garbage", "aero plot {T}/tables/Kestrel.csv --out {T}/p.png", ["kestrel.json"],
     edits=[write("tables/Kestrel.json", "{not json")], outputs=["p.png"])
case("b2-aero-plot-csv-nan", "aero plot {T}/tables/Kestrel.csv --out {T}/p.png", ["kestrel.csv"],
     edits=[lambda tmp: _nan_in_table(tmp / "tables/Kestrel.csv")], outputs=["p.png"])
case("b2-table-option-csv-inf", sim_k + " --table {T}/tables/Kestrel.csv", ["kestrel.csv"],
     edits=[lambda tmp: _nan_in_table(tmp / "tables/Kestrel.csv", "inf")])


def _nan_in_table(path: Path, value: str = "nan"):
    rows = path.read_text().splitlines(keepends=True)
    cells = rows[5].split(",")
    cells[-1] = value + ("\n" if cells[-1].endswith("\n") else "")
    rows[5] = ",".join(cells)
    path.write_text("".join(rows))


# --- weather get --out, motor get, motor search
W_REAN = "weather get --model reanalysis --file {D}/weather/reanalysis/bella_lui_weather_data_ERA5.nc " \
         "--lat 46.9 --lon 9.0 "
case("b2-weather-out-ext", W_REAN + "--out {T}/p.xyz", ["--out", ".xyz", ".json"], outputs=["p.xyz"])
case("b2-weather-out-missing-folder", W_REAN + "--out {T}/no/p.json", ["--out", "folder"])
case("b2-weather-out-is-dir", W_REAN + "--out {T}/ex", ["--out"])
case("b2-weather-top-nan", W_REAN + "--top-m nan", ["--top-m"])
case("b2-weather-lon-inf", "weather get --model reanalysis --file {D}/weather/reanalysis/bella_lui_weather_data_ERA5.nc "
                           "--lat 46.9 --lon inf", ["--lon"])
case("b2-motor-get-empty", ["motor", "get", "", "--offline"], ["designation"])
case("b2-motor-get-path-like", "motor get {T}/x.eng --offline", ["x.eng"])
case("b2-motor-get-symbols", ["motor", "get", "%%%", "--offline"], ["designation", "%%%"])
case("b2-motor-search-diameter-nan", "motor search --diameter-mm nan --offline", ["--diameter-mm"])
case("b2-motor-search-max-results-huge", "motor search --manufacturer AeroTech --max-results 1000000000 --offline",
     ["--max-results"])

# --- .ork configurations, finishes and the motor search path
ORK_AS = "{ORK:Airstart timing.ork}"
case("b2-ork-config-nonexistent-id", ["simulate", ORK1, "--config", "deadbeef"], ["config", "deadbeef"])
case("b2-ork-config-nonexistent-motor", ["simulate", ORK1, "--config", "[Z9000]"], ["config", "z9000"])
case("b2-ork-config-whitespace", ["simulate", ORK1, "--config", "   "], ["config"])


def _ork_finish(tmp: Path):
    path = tmp / "ork" / "01.One-stage_OR22.02.ork"
    with zipfile.ZipFile(path) as z:
        xml = z.read("rocket.ork").decode()
    xml = xml.replace("<finish>smooth</finish>", "<finish>glossy</finish>", 1)
    buf = io.BytesIO()
    with zipfile.ZipFile(buf, "w") as z:
        z.writestr("rocket.ork", xml)
    path.write_bytes(buf.getvalue())


case("b2-ork-unknown-finish", ["simulate", ORK1], ["finish", "glossy"], edits=[_ork_finish])

case("b2-env-motor-path-is-file", ["simulate", ORK1], ["ironbark_motor_path", "calisto.toml", "director"],
     env=[("IRONBARK_MOTOR_PATH", "{C}")])
case("b2-env-offline-garbage", ["simulate", ORK1], ["ironbark_offline"], env=[("IRONBARK_OFFLINE", "maybe")])

# --- dispersion specs
mc_spec = "montecarlo {C} --spec {T}/spec.toml --samples 4 --no-progress"
case("b2-spec-negative-std", mc_spec, ["spec.toml", "std"],
     edits=[write("spec.toml", '[parameters.drag_scale]\ndistribution = "normal"\nstd = -0.05\n')])
case("b2-spec-nan-std", mc_spec, ["spec.toml", "std"],
     edits=[write("spec.toml", '[parameters.drag_scale]\ndistribution = "normal"\nstd = nan\n')])
case("b2-spec-inf-mean", mc_spec, ["spec.toml", "mean"],
     edits=[write("spec.toml", '[parameters.drag_scale]\ndistribution = "normal"\nmean = inf\nstd = 0.05\n')])
case("b2-spec-uniform-low-above-high", mc_spec, ["spec.toml", "low"],
     edits=[write("spec.toml", '[parameters.drag_scale]\ndistribution = "uniform"\nlow = 1.2\nhigh = 0.8\n')])
case("b2-spec-unknown-distribution", mc_spec, ["spec.toml", "distribution"],
     edits=[write("spec.toml", '[parameters.drag_scale]\ndistribution = "lognormal"\nstd = 0.05\n')])
case("b2-spec-sample-file-missing", mc_spec, ["spec.toml", "nope.csv"],
     edits=[write("spec.toml", '[parameters.drag_scale]\ndistribution = "file"\nfile = "nope.csv"\n'
                               'column = "drag_scale"\n')])
case("b2-spec-sample-file-nan", mc_spec, ["s.csv"],
     edits=[write("spec.toml", '[parameters.drag_scale]\ndistribution = "file"\nfile = "s.csv"\n'
                               'column = "drag_scale"\n'),
            write("s.csv", "drag_scale\n1.0\nnan\n0.98\n")])
case("b2-spec-sample-file-column-missing", mc_spec, ["s.csv", "drag"],
     edits=[write("spec.toml", '[parameters.drag_scale]\ndistribution = "file"\nfile = "s.csv"\n'
                               'column = "drag"\n'),
            write("s.csv", "drag_scale\n1.0\n0.98\n")])
case("b2-spec-seed-negative", mc_spec, ["spec.toml", "seed"],
     edits=[write("spec.toml", 'seed = -1\n[parameters.drag_scale]\ndistribution = "normal"\nstd = 0.05\n')])
case("b2-spec-seed-float", mc_spec, ["spec.toml", "seed"],
     edits=[write("spec.toml", 'seed = 1.5\n[parameters.drag_scale]\ndistribution = "normal"\nstd = 0.05\n')])
case("b2-spec-is-directory", "montecarlo {C} --spec {T}/ex --samples 4", ["ex", "directory"])

# --- NaN / inf in numeric options
case("b2-opt-elevation-inf", sim_c + " --elevation inf", ["--elevation"])
case("b2-opt-rail-inf", sim_c + " --rail-length inf", ["--rail-length"])
case("b2-opt-ballast-inf", sim_c + " --ballast inf", ["--ballast"])
case("b2-sens-ballast-x-inf", "sensitivity {C} --ballast 0.5 --ballast-x inf", ["--ballast-x"])
case("b2-mc-band-inf", "montecarlo {C} --spec {CD}/dispersions.toml --target 3000m --band inf", ["--band"])
case("b2-mc-ballast-nan", "montecarlo {C} --spec {CD}/dispersions.toml --ballast nan", ["--ballast"])
case("b2-ballast-min-margin-inf", "ballast {C} --target 3000m --min-margin inf", ["--min-margin"])
case("b2-ballast-min-rail-speed-nan", "ballast {C} --target 3000m --min-rail-speed nan", ["--min-rail-speed"])
case("b2-ballast-max-inf", "ballast {C} --target 3000m --max-ballast inf", ["--max-ballast"])
case("b2-ballast-target-inf", "ballast {C} --target inf", ["target"])
case("b2-sens-target-nan", "sensitivity {C} --target nanm", ["target"])
case("b2-mc-target-inf", "montecarlo {C} --spec {CD}/dispersions.toml --target infm", ["target"])


# --- found by a mutation fuzz of the example TOMLs (each flew, hung or named no file before)
case("fuzz-ab-controller-raises", sim_c, ["ctl.py:3", "airbrakes.controller", "raised runtimeerror"],
     edits=[_brakes(AB + 'trigger = "controller"\ncontroller = "ctl.py:ctl"\nsampling_rate = 10.0\nrate = 2.0'),
            write("ex/c/ctl.py", "def ctl(time_s, state):\n    x = 1\n    raise RuntimeError('boom')\n")])
case("fuzz-ab-controller-nan", sim_c, ["ctl.py:1", "airbrakes.controller", "returned nan"],
     edits=[_brakes(AB + 'trigger = "controller"\ncontroller = "ctl.py:ctl"\nsampling_rate = 10.0\nrate = 2.0'),
            write("ex/c/ctl.py", "def ctl(time_s, state):\n    return float('nan')\n")])
case("fuzz-ab-start-negative", sim_c, ["calisto.toml", "airbrakes.start", ">= 0 s"],
     edits=[_brakes(AB + 'trigger = "time"\nstart = -5.4\nrate = 2.0')])
case("fuzz-fin-bevel-longer-than-fin", sim_k, ["kestrel.toml", "le_bevel", "longer than the fin"],
     edits=[edit(KT, "le_bevel = 0.020", "le_bevel = 0.5")])
case("fuzz-motor-mount-wider-than-body", sim_k, ["kestrel.toml", "outer_radius", "does not fit"],
     edits=[edit(KT, "outer_radius = 0.0400", "outer_radius = 0.0600")])
case("fuzz-point-mass-off-the-body", sim_k, ["kestrel.toml", "component[6].x", "off the body"],
     edits=[edit(KT, "x = 1.05", "x = 9.05")])
case("fuzz-recovery-negative-diameter", "simulate {K} --descent", ["kestrel.toml", "recovery[0].diameter"],
     edits=[edit(KT, "diameter = 0.61", "diameter = -0.61")])
case("fuzz-site-temperature-celsius", sim_c, ["calisto.toml", "launch.site_temperature", "kelvin"],
     edits=[edit(CT, "wind_speed = 0.0", "site_temperature = 25.0")])
case("fuzz-longitude-out-of-range", sim_c, ["calisto.toml", "launch.longitude_deg"],
     edits=[edit(CT, "longitude_deg = -106.974998", "longitude_deg = -400.0")])
case("fuzz-fin-set-duplicated", sim_c, ["calisto.toml:53", "component[4].x", "roll_deg"],
     edits=[edit(CT, "[[component]]\ntype = \"rail_buttons\"",
                 "[[component]]\ntype = \"trapezoidal_fins\"\nx = 2.32756\nroot_chord = 0.120\ntip_chord = 0.060\n"
                 "span = 0.110\nsweep_length = 0.060\nthickness = 0.0112\n\n[[component]]\ntype = \"rail_buttons\"")])
case("fuzz-fin-count-100", sim_c, ["calisto.toml", "component[3].count", "do not fit"],
     edits=[edit(CT, "count = 4", "count = 100")])
case("fuzz-sweep-angle-90", sim_c, ["calisto.toml", "sweep_angle_deg"],
     edits=[edit(CT, "sweep_length = 0.060", "sweep_angle_deg = 90.0")])
case("fuzz-motor-ahead-of-nose", sim_c, ["calisto.toml", "motor.nozzle_x", "ahead of the nose tip"],
     edits=[edit(CT, "nozzle_x = 2.533", "nozzle_x = 0.2")])
case("fuzz-eng-header-negative-propellant", sim_c, ["cesaroni_m1670.eng:1", "propellant_kg"],
     edits=[edit(CE, "3.101 5.231", "-3.101 5.231")])
