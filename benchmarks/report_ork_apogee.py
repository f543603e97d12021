"""Report: OpenRocket's stored apogee next to Ironbark-Opt's, per .ork file and simulation.

A report, not a test.  Run ``python benchmarks/report_ork_apogee.py`` (add
``--offline`` to skip ThrustCurve.org).  Motors are looked up as ``load_ork``
does (next to the .ork, ``IRONBARK_MOTOR_PATH``, ThrustCurve.org); rows whose
motor cannot be found or whose features cannot be flown yet say why.  Our
drag comes from the interim empirical pressure-drag table
(``ironbark_opt.aero.empirical_drag``) plus friction and base drag, an
interim model until the panel solver lands.
"""
from __future__ import annotations

import os
import re
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
DATA = ROOT / "tests" / "data" / "ork"


def main() -> None:
    if "--offline" in sys.argv:
        os.environ["IRONBARK_OFFLINE"] = "1"
    os.environ.setdefault("IRONBARK_MOTOR_PATH", str(DATA / "motors"))
    from ironbark_opt.errors import IronbarkError
    from ironbark_opt.flight import simulate
    from ironbark_opt.openrocket import read_ork
    from ironbark_opt.openrocket.build import rocket_file
    from ironbark_opt.vehicle import setup_from_file

    print(f"{'file':<34} {'simulation':<32} {'config':<14} {'OR apogee':>10} {'ours':>10} {'diff':>7}")
    for path in sorted(DATA.glob("*.ork")):
        try:
            doc = read_ork(path)
        except IronbarkError as err:
            print(f"{path.name[:34]:<34} {'(not read)':<32} {'':<14} {'':>10} {'':>10}  {err.message}")
            continue
        for sim in doc.simulations:
            or_apogee = sim.summary.get("apogee_m")
            label, ours, note = "", None, ""
            try:
                cfg = doc.config(sim.config_id or None)
                label = cfg.label()
                rf = rocket_file(doc, cfg.config_id)
                flight = simulate(setup_from_file(rf, rail_exit="travel"))
                ours = flight.to_dict()["apogee_agl_m"]
            except IronbarkError as err:
                note = getattr(err, "message", str(err)).split(";")[0][:70]
            o = f"{or_apogee:10.1f}" if or_apogee is not None else f"{'-':>10}"
            u = f"{ours:10.1f}" if ours is not None else f"{'-':>10}"
            d = f"{(ours - or_apogee) / or_apogee:+7.1%}" if (ours and or_apogee) else f"{'':>7}"
            print(f"{path.name[:34]:<34} {sim.name[:32]:<32} {label[:14]:<14} {o} {u} {d}  {note}")
    _substituted(simulate, setup_from_file, read_ork, rocket_file)


def _substituted(simulate, setup_from_file, read_ork, rocket_file) -> None:
    """Designs flown on the WECO C6 we have a file for, in place of their Estes C6-5
    (a different motor: these rows check plausibility only)."""
    import tempfile

    from ironbark_opt.openrocket.xmlread import read_bytes
    for name in ("A simple model rocket.ork", "Clustered motors.ork"):
        xml = read_bytes(DATA / name).replace(
            b"<manufacturer>Estes</manufacturer>", b"<manufacturer>WECO</manufacturer>")
        xml = re.sub(rb"<digest>[0-9a-f]*</digest>", b"", xml)
        with tempfile.TemporaryDirectory() as tmp:
            path = Path(tmp) / "weco.ork"
            path.write_bytes(xml)
            doc = read_ork(path)
            cfg = doc.config("[C6-5]")
            sim = doc.simulation_for(cfg)
            flight = simulate(setup_from_file(rocket_file(doc, cfg.config_id), rail_exit="travel"))
            ours = flight.to_dict()["apogee_agl_m"]
            ref = sim.summary["apogee_m"]
            label = name.replace(".ork", "")[:24] + " (WECO)"
            print(f"{label:<34} {sim.name[:32]:<32} {'[C6-5]':<14} {ref:10.1f} {ours:10.1f} "
                  f"{(ours - ref) / ref:+7.1%}  motor substituted: WECO C6 for Estes C6")


if __name__ == "__main__":
    main()
