"""University of Wyoming soundings: recorded CSV and TEXT:LIST responses on loopback."""
from __future__ import annotations

import math
from datetime import datetime, timezone
from pathlib import Path

import numpy as np
import pytest

from ironbark_opt.atmosphere.sounding import KNOT, fetch_sounding, read_sounding, \
    read_uwyo_csv, read_uwyo_text_list
from ironbark_opt.errors import InputError, NetworkError

W = Path(__file__).resolve().parents[1] / "data" / "weather"
CSV = W / "uwyo_wsgi_wyoming_sounding.csv"
HTML = W / "uwyo_cgi_TEXT_LIST_OUN_1999050400.html"


@pytest.fixture
def server(loopback, net_env, monkeypatch):
    monkeypatch.setenv("IRONBARK_UWYO_URL", loopback.url)
    return loopback


def test_csv_service(server):
    server.route("/wsgi/sounding", CSV, content_type="text/csv")
    col = fetch_sounding(72357, datetime(1999, 5, 4, 0))
    q = server.requests[0]["query"]
    assert q["id"] == ["72357"] and q["datetime"] == ["1999-05-04 00:00:00"]
    assert q["type"] == ["TEXT:CSV"]
    assert col.valid_time == datetime(1999, 5, 3, 23, 2, tzinfo=timezone.utc)
    assert math.degrees(col.latitude) == pytest.approx(35.18)
    # Recorded first (surface) row: 959.0 hPa, 345 m, 22.2 C, 160 deg, 9.3 m/s.
    assert col.pressure[0] == pytest.approx(95900.0)
    assert col.temperature[0] == pytest.approx(295.35)
    assert col.altitude[0] == pytest.approx(345.0, abs=0.5)     # geopotential -> geometric
    assert col.wind_east[0] == pytest.approx(-9.3 * math.sin(math.radians(160)))
    assert col.wind_north[0] == pytest.approx(-9.3 * math.cos(math.radians(160)))
    # 500 hPa row: 5670 m, -14.9 C.
    i = int(np.argmin(abs(col.pressure - 50000.0)))
    assert col.temperature[i] == pytest.approx(258.25)
    # Top row (251 hPa) has no wind and is dropped; 30 levels remain.
    assert col.pressure.size == 30 and col.pressure[-1] == pytest.approx(26860.0)


def test_falls_back_to_legacy_page_on_404(server):
    server.route("/wsgi/sounding", W / "uwyo_wsgi_wyoming_no_data.txt", status=404)
    server.route("/cgi-bin/sounding", HTML, content_type="text/html")
    col = fetch_sounding("72357", datetime(1999, 5, 4, 0))
    assert server.paths() == ["/wsgi/sounding", "/cgi-bin/sounding"]
    q = server.requests[1]["query"]
    assert q["TYPE"] == ["TEXT:LIST"] and q["FROM"] == ["0400"] and q["STNM"] == ["72357"]
    assert col.valid_time == datetime(1999, 5, 4, 0, tzinfo=timezone.utc)
    # 1000 hPa lies below the station (-7 m) and is dropped; ground = station 345 m.
    assert col.pressure[0] == pytest.approx(95900.0)
    assert col.altitude[0] == pytest.approx(345.0, abs=0.5)
    # 931.3 hPa: 165 deg, 40 knots.
    speed = math.hypot(col.wind_east[1], col.wind_north[1])
    assert speed == pytest.approx(40 * KNOT)


def test_both_services_fail(server):
    server.route("/wsgi/sounding", W / "uwyo_wsgi_wyoming_no_data.txt", status=404)
    with pytest.raises(NetworkError) as err:
        fetch_sounding("BOI", datetime(2010, 12, 9, 1))
    msg = str(err.value)
    assert "Unable to retrieve the data for BOI" in msg
    assert "/wsgi/sounding" in msg and "/cgi-bin/sounding" in msg


def test_truncated_csv_falls_back(server):
    text = CSV.read_text()
    server.route("/wsgi/sounding", text[: len(text) // 2].rsplit(",", 3)[0])
    server.route("/cgi-bin/sounding", HTML)
    col = fetch_sounding(72357, datetime(1999, 5, 4))
    assert col.source.startswith(server.url + "/cgi-bin/sounding")


def test_csv_and_text_list_agree():
    """Independent paths: the same sounding from the two services (CSV in m/s,
    TEXT:LIST in knots) agrees to the recording's rounding."""
    a, b = read_sounding(CSV), read_sounding(HTML)
    assert a.pressure.size == b.pressure.size
    np.testing.assert_allclose(a.altitude, b.altitude, atol=1e-6)
    dT = np.max(abs(a.temperature - b.temperature))
    sa = np.hypot(a.wind_east, a.wind_north)
    sb = np.hypot(b.wind_east, b.wind_north)
    dV = np.max(abs(sa - sb))
    print(f"CSV vs TEXT:LIST: max |dT| = {dT:.2f} K, max |dV| = {dV:.2f} m/s")
    assert dT <= 0.1 + 1e-9
    assert dV <= 0.5 * KNOT + 0.05 + 1e-9     # knots rounded to 1, m/s to 0.1


def test_deep_sounding_reaches_35_km():
    col = read_sounding(W / "uwyo_wsgi_wyoming_sounding_heights.csv")
    assert col.altitude[-1] > 34900.0
    assert col.pressure[-1] == pytest.approx(600.0)
    assert np.all(np.diff(col.altitude) > 0)


def test_missing_column_named():
    text = CSV.read_text().replace("temperature_C", "temp")
    with pytest.raises(InputError, match="missing column 'temperature_c'"):
        read_uwyo_csv(text, source="x.csv")


def test_bad_number_names_line_and_field():
    lines = CSV.read_text().splitlines()
    lines[3] = lines[3].replace(" 19.8,", " abc,", 1)
    with pytest.raises(InputError, match=r"x.csv:4: field 'temperature_C'"):
        read_uwyo_csv("\n".join(lines), source="x.csv")


def test_text_list_without_table():
    with pytest.raises(InputError, match="no sounding table"):
        read_uwyo_text_list("<HTML>Can't get 72357 OUN Observations</HTML>")
