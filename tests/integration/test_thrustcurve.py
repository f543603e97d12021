"""ThrustCurve.org client against recorded API responses on a loopback tc_server."""
from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

from ironbark_opt.errors import InputError
from ironbark_opt.motors import thrustcurve as tc

TC = Path(__file__).resolve().parents[1] / "data" / "thrustcurve"
API = "/api/v1"


def test_search_by_manufacturer_parses_recorded_response(tc_server):
    tc_server.route(f"{API}/search.json", TC / "search-GET-manufacturer.json")
    found = tc.search(manufacturer="Estes")
    # The recorded response says 22 matches but carries 20 (the default maxResults).
    assert len(found) == 20
    first = found[0]
    assert first.designation == "1/4A3" and first.manufacturer_abbrev == "Estes"
    assert first.diameter == pytest.approx(0.013) and first.length == pytest.approx(0.045)
    assert first.total_impulse == pytest.approx(0.59)
    assert first.burn_time == pytest.approx(0.25)
    assert first.propellant_mass == pytest.approx(0.83e-3)
    assert [m.designation for m in found][-1] == "F50"
    query = tc_server.requests[-1]["query"]
    assert query["manufacturer"] == ["Estes"] and query["maxResults"] == ["20"]


def test_search_sends_diameter_in_mm_and_class(tc_server):
    tc_server.route(f"{API}/search.json", TC / "search-GET-empty.json")
    assert tc.search(impulse_class="K", diameter=0.054) == []
    query = tc_server.requests[-1]["query"]
    assert query["impulseClass"] == ["K"] and query["diameter"] == ["54"]


def test_invalid_criterion_reports_service_message(tc_server):
    tc_server.route(f"{API}/search.json", TC / "search-GET-invalid.json")
    with pytest.raises(InputError, match='Invalid search criterion "imaginary"'):
        tc.search(designation="X")


def test_no_criterion_is_input_error(tc_server):
    with pytest.raises(InputError, match="at least one search criterion"):
        tc.search()


def test_metadata(tc_server):
    tc_server.route(f"{API}/metadata.json", TC / "metadata-GET-all.json")
    meta = tc.metadata()
    assert meta["diameters"][0] == 13 and "N" in meta["impulseClasses"]
    assert [m["abbrev"] for m in meta["manufacturers"]] == ["AeroTech", "Estes", "Kosdon"]


def _trapezoid_impulse(eng_text: str) -> float:
    rows = [line.split() for line in eng_text.splitlines()
            if line.strip() and not line.startswith(";")]
    pts = np.array([[float(a), float(b)] for a, b in rows[1:]])
    t = np.concatenate(([0.0], pts[:, 0]))
    f = np.concatenate(([0.0], pts[:, 1]))
    return float(np.sum(0.5 * (f[1:] + f[:-1]) * np.diff(t)))


def test_download_decodes_and_prefers_certification_data(tc_server):
    tc_server.route(f"{API}/download.json", TC / "download-POST-motorIds.json")
    files = tc.download("56a409280002310000000146")
    assert {(f.format, f.source) for f in files} == {("RockSim", "user"), ("RASP", "cert")}
    best = tc.choose_file(files)
    assert best.format == "RASP" and best.source == "cert" and best.suffix == ".eng"
    assert best.text.startswith("; AeroTech K550W")
    # Preferring RockSim does not beat certification data:
    assert tc.choose_file(files, prefer_format="RockSim").source == "cert"
    sent = json.loads(tc_server.requests[-1]["body"])
    assert sent["motorIds"] == ["56a409280002310000000146"]
    # Independent check: the RASP curve's trapezoid impulse vs the RockSim
    # file's Itot (1594.46 N s), two different files of the same motor.
    impulse = _trapezoid_impulse(best.text)
    err = abs(impulse - 1594.46) / 1594.46
    print(f"K550W impulse from .eng {impulse:.1f} N s vs RockSim Itot 1594.46: {err:.2%}")
    assert err < 0.03


def test_choose_file_ranks_sources():
    mk = lambda fmt, src, n: tc.SimFile("m", src + fmt, fmt, src, "", "x\n" * n, "")
    files = [mk("RockSim", "user", 50), mk("RockSim", "mfr", 5), mk("RASP", "mfr", 3)]
    assert tc.choose_file(files).simfile_id == "mfrRASP"
    assert tc.choose_file(files, prefer_format="RockSim").simfile_id == "mfrRockSim"
    with pytest.raises(InputError):
        tc.choose_file([])


def test_download_is_cached_and_not_fetched_again(tc_server):
    tc_server.route(f"{API}/download.json", TC / "download-POST-motorId.json")
    a = tc.download("56a409280002310000000146")
    b = tc.download("56a409280002310000000146")
    assert a == b and tc_server.paths().count(f"{API}/download.json") == 1


def test_fetch_motor_file_and_save(tc_server, tmp_path):
    tc_server.route(f"{API}/search.json", TC / "search-GET-designation-K550W.json")
    tc_server.route(f"{API}/download.json", TC / "download-POST-motorId.json")
    info, simfile = tc.fetch_motor_file("k550w")
    assert info.designation == "K550W" and info.diameter == pytest.approx(0.054)
    assert simfile.source == "cert"
    path = tc.save_file(info, simfile, tmp_path)
    assert path.name == "AeroTech_K550W.eng"
    assert path.read_text().splitlines()[3].startswith("K550W 54 410")
    assert "I = 1594.5 N s" in info.summary()


def test_unknown_designation_gives_clear_error(tc_server):
    tc_server.route(f"{API}/search.json", TC / "search-GET-empty.json")
    with pytest.raises(InputError, match="no motor called 'Z9999'"):
        tc.find_motor("Z9999")


def test_load_motor_with_package_reader(tc_server):
    pytest.importorskip("ironbark_opt.motors.rasp")
    tc_server.route(f"{API}/search.json", TC / "search-GET-designation-K550W.json")
    tc_server.route(f"{API}/download.json", TC / "download-POST-motorId.json")
    motor = tc.load_motor("K550W")
    assert motor.total_impulse == pytest.approx(_trapezoid_impulse(
        tc.choose_file(tc.download("56a409280002310000000146")).text), rel=0.01)
    assert motor.diameter == pytest.approx(0.054)


def test_rocksim_file_parses_and_agrees_with_rasp(tc_server):
    """The two data files of the K550W (RockSim from a user, RASP certification
    data) parsed by the package's readers: total impulse agrees within 3 %."""
    pytest.importorskip("ironbark_opt.motors.rse")
    tc_server.route(f"{API}/download.json", TC / "download-POST-motorId.json")
    files = {f.format: f for f in tc.download("56a409280002310000000146")}
    rse = tc.motor_from_text(files["RockSim"].text, "RockSim", designation="K550W")
    eng = tc.motor_from_text(files["RASP"].text, "RASP", designation="K550W")
    err = abs(rse.total_impulse - eng.total_impulse) / eng.total_impulse
    print(f"K550W total impulse: RockSim {rse.total_impulse:.1f} N s, "
          f"RASP {eng.total_impulse:.1f} N s ({err:.2%})")
    assert err < 0.03
    assert rse.propellant_mass_initial == pytest.approx(0.8804, rel=1e-3)
