"""Rendering of a :class:`FlightCard` (no flights: the numbers are given)."""
import xml.etree.ElementTree as ET

import matplotlib.image as mpimg
import pytest

from ironbark_opt.errors import InputError
from ironbark_opt.report.card import FlightCard, write_flight_card

CARD = FlightCard(rocket="Kestrel", motor="CTI L1350", site="euroc, 39.38970 N, 8.28896 W, 140.0 m ASL",
                  launch_time="2022-10-13T12:00Z",
                  atmosphere="ERA5 reanalysis: euroc_2022_all_windows.nc at 39.3897 N 8.2890 W, valid "
                             "2022-10-13T12:00:00+00:00, a long source line that must wrap on the page",
                  rail="12.00 m, 84.0 deg above horizontal, heading 0.0 deg", ballast_kg=0.4321,
                  ballast_x_m=0.355, apogee_agl_m=3000.04, rail_exit_speed_mps=31.234,
                  static_margin_rail_exit_cal=1.87, static_margin_min_cal=1.52, max_mach=0.91234,
                  max_dynamic_pressure_Pa=48123.0, apogee_east_m=-120.3, apogee_north_m=310.4,
                  target_agl_m=3000.0, apogee_per_100g_m=-14.26, landing_east_m=-400.1, landing_north_m=900.2,
                  landing_distance_m=985.1)


def test_lines_carry_the_numbers():
    text = "\n".join(CARD.text_lines())
    for snippet in ("ballast mass       0.432 kg", "predicted apogee   3000.0 m AGL (9843 ft)",
                    "apogee per 100 g   -14.3 m", "max q              48.12 kPa", "max Mach           0.912",
                    "apogee 5-95 %      no dispersion spec given", "launch time (UTC)  2022-10-13T12:00Z"):
        assert snippet in text
    assert all(len(line) <= 19 + 62 for line in CARD.text_lines())    # the atmosphere line wraps
    import dataclasses
    banded = dataclasses.replace(CARD, apogee_p05_m=2950.0, apogee_p95_m=3050.0, samples=400, band_m=50.0,
                                 probability_in_band=0.8125)
    assert "P(+-50 m)          0.812 of the Monte Carlo flights within 50.0 m of the target" in banded.text_lines()
    assert "apogee 5-95 %      2950.0 to 3050.0 m AGL (400 Monte Carlo flights)" in banded.text_lines()
    d = CARD.to_dict()
    assert d["lines"] == CARD.text_lines() and d["ballast_kg"] == 0.4321 and d["landing_ellipse"] is None


@pytest.mark.parametrize("suffix", [".png", ".pdf", ".svg"])
def test_one_a4_page(tmp_path, suffix):
    path = tmp_path / f"card{suffix}"
    write_flight_card(path, CARD)
    data = path.read_bytes()
    if suffix == ".png":
        h, w = mpimg.imread(path).shape[:2]
        assert (w, h) == (int(8.27 * 150), int(11.69 * 150))              # A4 at 150 dpi (truncated)
    elif suffix == ".pdf":
        assert data.startswith(b"%PDF") and data.count(b"/Type /Page\n") + data.count(b"/Type /Page ") <= 1
    else:
        texts = [e.text for e in ET.fromstring(data).iter("{http://www.w3.org/2000/svg}text")]
        assert set(CARD.text_lines()) <= set(texts)
        assert "Kestrel: nominal flight" in texts


def test_unknown_type_refused(tmp_path):
    with pytest.raises(InputError, match=r"\.pdf"):
        write_flight_card(tmp_path / "card.docx", CARD)
