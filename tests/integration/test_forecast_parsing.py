"""Parsing of the recorded THREDDS responses, and the RAP wind rotation checked
against an independent computation with Snyder's Lambert projection formulas."""
from __future__ import annotations

import math
from datetime import datetime, timezone
from pathlib import Path

import numpy as np
import pytest

from ironbark_opt.atmosphere import grib
from ironbark_opt.atmosphere.ncss import parse_dataset_xml, parse_point_csv, rotate_grid_winds
from ironbark_opt.errors import InputError

W = Path(__file__).resolve().parents[1] / "data" / "weather"
RAP_PROJ = {"grid_mapping_name": "lambert_conformal_conic", "standard_parallel": "25.0",
            "longitude_of_central_meridian": "265.0"}


def test_dataset_descriptions_axis_names_differ():
    rap = parse_dataset_xml((W / "ncss_RAP_CONUS_13km_20241211_1900_dataset.xml").read_bytes())
    gfs = parse_dataset_xml((W / "ncss_GFS_Global_0p5deg_20170903_1200_dataset.xml").read_bytes())
    assert rap.vertical_axis["Temperature_isobaric"] == "isobaric"
    assert gfs.vertical_axis["Temperature_isobaric"] == "isobaric3"
    assert rap.time_begin == datetime(2024, 12, 11, 19, tzinfo=timezone.utc)
    assert rap.time_end == datetime(2024, 12, 12, 16, tzinfo=timezone.utc)
    assert rap.run_time == datetime(2024, 12, 11, 19, tzinfo=timezone.utc)
    assert rap.projection["grid_mapping_name"] == "lambert_conformal_conic"
    assert gfs.projection == {}
    with pytest.raises(InputError, match="not valid XML"):
        parse_dataset_xml(b"<gridDataset><axis")


def test_ensemble_axis_of_the_built_gefs_description():
    """The Ensemble axis (regular: values from start + i * resolution; irregular: listed), and
    none in the recorded deterministic descriptions."""
    text = (W / "ncss_GEFS_members_built_dataset.xml").read_text()
    gefs = parse_dataset_xml(text.encode())
    assert gefs.vertical_axis["Temperature_isobaric_ens"] == "isobaric"
    assert gefs.ensemble["u-component_of_wind_isobaric_ens"] == ("ens", tuple(float(m) for m in range(21)))
    assert gefs.run_time == datetime(2024, 12, 11, 12, tzinfo=timezone.utc)
    listed = text.replace('<values spacing="regularPoint" npts="21" start="0.0" end="20.0" resolution="1.0" />',
                          '<values spacing="irregularPoint" npts="4" start="0.0" end="7.0">0.0 1.0 2.0 7.0</values>')
    assert parse_dataset_xml(listed.encode()).ensemble["Temperature_isobaric_ens"][1] == (0.0, 1.0, 2.0, 7.0)
    broken = text.replace('npts="21" start="0.0" end="20.0" resolution="1.0"', 'npts="21" start="0.0"')
    with pytest.raises(InputError, match="axis 'ens'.*21 points with resolution 0") as err:
        parse_dataset_xml(broken.encode(), "gefs.xml")
    assert err.value.field == "ens" and err.value.source == "gefs.xml"
    gfs = parse_dataset_xml((W / "ncss_GFS_Global_0p5deg_20170903_1200_dataset.xml").read_bytes())
    assert gfs.ensemble == {}


def test_recorded_point_csv_columns_by_name():
    table = parse_point_csv((W / "ncss_gfs0p5_point_csv_2015-06-12T15Z_40N_105W.csv").read_bytes())
    unit, p = table["vertCoord"]
    assert unit == "Pa" and p[0] == 1000.0 and p[-1] == 100000.0 and p.size == 26
    assert table["Temperature_isobaric"][1][list(p).index(50000.0)] == pytest.approx(263.3999938964844)
    one = parse_point_csv((W / "ncss_gfs0p5_point_csv_vertCoord50000.csv").read_bytes())
    assert one["Temperature_isobaric"][1].tolist() == pytest.approx([263.3999938964844])
    # Column order does not matter: swap two columns.
    lines = (W / "ncss_gfs0p5_point_csv_vertCoord50000.csv").read_text().splitlines()
    swapped = []
    for line in lines:
        c = line.split(",")
        c[3], c[4] = c[4], c[3]
        swapped.append(",".join(c))
    again = parse_point_csv("\n".join(swapped).encode())
    assert again["Temperature_isobaric"][1][0] == pytest.approx(263.3999938964844)
    assert again["vertCoord"][1][0] == 50000.0


def test_truncated_point_csv_names_line():
    text = (W / "ncss_gfs0p5_point_csv_2015-06-12T15Z_40N_105W.csv").read_text()
    cut = text[: text.index("5000.0,214.0") + 8]
    with pytest.raises(InputError, match=r":5: expected 6 fields"):
        parse_point_csv(cut.encode(), "x")


def _snyder_xy(lat, lon, phi1=math.radians(25.0), lam0=math.radians(265.0 - 360.0)):
    """Lambert conformal conic, sphere, one standard parallel (Snyder 1987, eqs. 15-1..15-3, 14-1..14-2)."""
    n = math.sin(phi1)
    F = math.cos(phi1) * math.tan(math.pi / 4 + phi1 / 2) ** n / n
    rho = F / math.tan(math.pi / 4 + lat / 2) ** n
    rho0 = F / math.tan(math.pi / 4 + phi1 / 2) ** n
    th = n * (lon - lam0)
    return np.array([rho * math.sin(th), rho0 - rho * math.cos(th)])


@pytest.mark.parametrize("lat_deg, lon_deg", [(32.99, -106.97), (47.0, -70.0), (25.0, -95.0)])
def test_rotation_matches_projected_meridians(lat_deg, lon_deg):
    lat, lon, eps = math.radians(lat_deg), math.radians(lon_deg), 1e-6
    p0 = _snyder_xy(lat, lon)
    north = _snyder_xy(lat + eps, lon) - p0
    east = _snyder_xy(lat, lon + eps) - p0
    north, east = north / np.linalg.norm(north), east / np.linalg.norm(east)
    E, N = 7.0, -3.0                           # earth-relative wind
    ug, vg = E * east + N * north              # its grid components
    e, n = rotate_grid_winds(ug, vg, lon, RAP_PROJ)
    err = max(abs(e - E), abs(n - N))
    print(f"rotation at {lat_deg}, {lon_deg}: error {err:.1e} m/s")
    assert err < 1e-5


def test_idx_parsing_and_range_selection():
    text = (Path(__file__).resolve().parents[1] / "data" / "weather"
            / "gfs_constructed.t06z.f006.grib2.idx").read_text()
    entries = grib.parse_idx(text)
    assert entries[0] == grib.IdxEntry(1, 0, "2017090506", "HGT", "1000 mb", "6 hour fcst")
    # The excerpt documented in ../shared (HRRR inventory) parses too:
    excerpt = (W / "herbie_docs_grib2_idx_excerpt.md").read_text()
    hrrr = "\n".join(ln for ln in excerpt.splitlines() if ln[:1].isdigit())
    entries = grib.parse_idx(hrrr)
    assert len(entries) == 18 and entries[9].variable == "UGRD" and entries[9].offset == 4522696
    ranges = grib.select_ranges(entries)
    # 10-15 (UGRD/VGRD 250, 300 mb, HGT/TMP 500 mb) are adjacent; DPT 500 mb is
    # skipped; UGRD/VGRD 500 mb run to the end of the file.
    assert ranges == [(4522696, 8898144), (9954184, None)]
    with pytest.raises(InputError, match=":2: not an index line"):
        grib.parse_idx("1:0:d=1:HGT:500 mb:anl:\ngarbage\n", "x.idx")


def test_candidate_runs():
    gfs = grib.MODELS["gfs"]
    t = datetime(2024, 6, 1, 18, tzinfo=timezone.utc)
    runs = grib.candidate_runs(gfs, t, now=datetime(2024, 6, 1, 9, tzinfo=timezone.utc))
    # newest published run: 09Z - 5 h latency -> 00Z run; lead 18 h
    assert runs[0] == (datetime(2024, 6, 1, 0, tzinfo=timezone.utc), 18)
    assert runs[1] == (datetime(2024, 5, 31, 18, tzinfo=timezone.utc), 24)
    rap = grib.MODELS["rap"]
    runs = grib.candidate_runs(rap, datetime(2024, 6, 1, 18, 40, tzinfo=timezone.utc),
                               now=datetime(2024, 6, 2, tzinfo=timezone.utc))
    assert runs[0] == (datetime(2024, 6, 1, 18, tzinfo=timezone.utc), 1)   # nearest hour
