"""Build the GEFS ensemble test files (run by hand; numpy only).

No recorded GEFS response exists in ../shared/fixtures/weather, so these files
are BUILT in the formats of the real service (see ironbark_opt/atmosphere/
ensemble.py for the sources) from recorded numbers:

- ``ncss_GEFS_members_built_dataset.xml``: a THREDDS NCSS ``dataset.xml``
  written like netCDF-Java's ``CoverageDatasetCapabilities`` (the element and
  attribute layout of the recorded GFS description next to it): 1-degree
  lat/lon axes, a scalar ``reftime`` (run 2024-12-11T12Z), a 3-hourly ``time``
  axis (0-72 h), the 26 pressure levels of the recorded GFS point CSV on
  ``isobaric``, an ``ens`` axis of ``axisType="Ensemble"`` with 21 members
  (GRIB2 perturbation numbers 0..20, regular: no listed values) and one
  gridSet with the four ``*_isobaric_ens`` variables.
- ``ncss_gefs_member{0,1,2}_point_csv_built.csv``: TDS 5 grid-as-point CSV
  (``StationProfileSubsetWriterCSV`` header: ``time,alt[unit="Pa"],station,
  latitude,longitude,<vars>``) of members 0, 1, 2 at the 1-degree grid point
  33 N 253 E, 2024-12-11T18:00Z.  Temperature: the *recorded* GFS column of
  ``ncss_gfs0p5_point_csv_2015-06-12T15Z_40N_105W.csv`` plus 0, +2, -2 K;
  geopotential height: its hypsometric integral (``make_constructed.gfs_column``);
  wind: a uniform westerly of 8, 10, 6 m/s (v = 0) at every level.

    python tests/data/weather/make_gefs.py
"""
from __future__ import annotations

import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))
from make_constructed import gfs_column  # noqa: E402

NS = 'xmlns="http://www.unidata.ucar.edu/namespaces/netcdf/ncml-2.2"'
MEMBERS = {0: (0.0, 8.0), 1: (2.0, 10.0), 2: (-2.0, 6.0)}      # member: (dT [K], westerly [m/s])
VARS = (("Geopotential_height_isobaric_ens", "gpm", "Geopotential height @ Isobaric surface"),
        ("Temperature_isobaric_ens", "K", "Temperature @ Isobaric surface"),
        ("u-component_of_wind_isobaric_ens", "m/s", "u-component of wind @ Isobaric surface"),
        ("v-component_of_wind_isobaric_ens", "m/s", "v-component of wind @ Isobaric surface"))


def _axis(name, axis_type, attrs, values, shape=None):
    lines = [f'  <axis name="{name}" shape="{shape if shape is not None else ""}" type="double" '
             f'axisType="{axis_type}">']
    lines += [f'    <attribute {NS} name="{k}" value="{v}" />' for k, v in attrs]
    lines.append(f"    {values}")
    lines.append("  </axis>")
    return lines


def dataset_xml():
    p, _, _ = gfs_column()
    levels = " ".join(f"{x:.1f}" for x in sorted(p))
    times = " ".join(f"{3.0 * i:.1f}" for i in range(25))
    out = ['<?xml version="1.0" encoding="UTF-8"?>',
           '<gridDataset location="/thredds/ncss/grid/grib/NCEP/GEFS/Global_1p0deg_Ensemble/members/Best" '
           'path="path">']
    out += _axis("latitude", "Lat", [("units", "degrees_north")],
                 '<values spacing="regularPoint" npts="181" start="90.0" end="-90.0" resolution="-1.0" />', "181,")
    out += _axis("longitude", "Lon", [("units", "degrees_east")],
                 '<values spacing="regularPoint" npts="360" start="0.0" end="359.0" resolution="1.0" />', "360,")
    out += _axis("reftime", "RunTime", [("units", "Hour since 2024-12-11T12:00:00Z"),
                                         ("standard_name", "forecast_reference_time")],
                 '<values spacing="regularPoint" npts="1" start="0.0" end="0.0" />')
    out += _axis("time", "Time", [("units", "Hour since 2024-12-11T12:00:00Z"), ("standard_name", "time")],
                 f'<values spacing="regularPoint" npts="25" start="0.0" end="72.0" resolution="3.0">{times}</values>',
                 "25,")
    out += _axis("ens", "Ensemble", [("units", "")],
                 '<values spacing="regularPoint" npts="21" start="0.0" end="20.0" resolution="1.0" />', "21,")
    out += _axis("isobaric", "Pressure", [("units", "Pa"), ("positive", "down")],
                 f'<values spacing="irregularPoint" npts="{p.size}" start="{min(p):.1f}" end="{max(p):.1f}">'
                 f'{levels}</values>', f"{p.size},")
    out += ['  <gridSet name="reftime time ens isobaric latitude longitude">']
    out += [f'    <axisRef name="{a}" />' for a in ("reftime", "time", "ens", "isobaric", "latitude", "longitude")]
    for name, unit, desc in VARS:
        out += [f'    <grid name="{name}" desc="{desc}" type="float">',
                f'      <attribute {NS} name="units" value="{unit}" />', "    </grid>"]
    out += ["  </gridSet>",
            '  <coordTransform name="LatLon_Projection" transformType="Projection">',
            f'    <parameter {NS} name="grid_mapping_name" value="latitude_longitude" />',
            "  </coordTransform>",
            "  <LatLonBox>", "    <west>0.0000</west>", "    <east>359.0000</east>",
            "    <south>-90.0000</south>", "    <north>90.0000</north>", "  </LatLonBox>",
            "  <TimeSpan>", "    <begin>2024-12-11T12:00:00Z</begin>", "    <end>2024-12-14T12:00:00Z</end>",
            "  </TimeSpan>", "</gridDataset>"]
    (HERE / "ncss_GEFS_members_built_dataset.xml").write_text("\n".join(out) + "\n")


def member_csv(member):
    dT, wind = MEMBERS[member]
    p, T, H = gfs_column(dT)
    head = ('time,alt[unit="Pa"],station,latitude[unit="degrees_north"],longitude[unit="degrees_east"],'
            + ",".join(f'{name}[unit="{unit}"]' for name, unit, _ in VARS))
    rows = [f"2024-12-11T18:00:00Z,{pi:.1f},GridPointRequestedAt[32.990N_106.975W],33.000,253.000,"
            f"{Hi:.2f},{Ti:.2f},{wind:.4f},0.0000" for pi, Ti, Hi in zip(p, T, H)]
    (HERE / f"ncss_gefs_member{member}_point_csv_built.csv").write_text("\n".join([head] + rows) + "\n")


if __name__ == "__main__":
    dataset_xml()
    for m in MEMBERS:
        member_csv(m)
