"""Build the constructed forecast test files (run by hand; needs eccodes).

There are no recorded GRIB2 messages and no recorded NCSS response with all
four isobaric variables in ../shared/fixtures/weather, so these files are
built in the recorded formats from recorded numbers:

- ``gfs_constructed.t06z.f006.grib2`` + ``.idx``: GFS-like GRIB2 (regular
  0.5 deg lat/lon, 5 x 5 points around 40 N 105 W, run 2017-09-05 06Z,
  +6 h).  TMP on the 26 pressure levels is the *recorded* temperature of
  ``ncss_gfs0p5_point_csv_2015-06-12T15Z_40N_105W.csv`` at 40 N 105 W;
  HGT is the hypsometric integral of that temperature (dry air, from
  1000 hPa at 120 gpm); UGRD = 2 + 0.001 z, VGRD = -1 - 0.0005 z (m/s,
  z in gpm).  One RH message per level is added so that selecting from the
  index matters.  The ``.idx`` is written in wgrib2's inventory format.
- ``rap_constructed.t19z.awp130pgrbf02.grib2`` + ``.idx``: RAP-like GRIB2
  on a 5 x 5 piece of a Lambert conformal grid (LoV 265 deg, tangent at
  25 deg, 13.545 km) around Spaceport America, run 2024-12-11 19Z, +2 h,
  19 levels 1000-100 hPa, U.S. Standard Atmosphere 1976 T and heights, and
  *grid-relative* winds (uvRelativeToGrid = 1) of an earth-relative wind
  east 5 m/s, north 8 m/s, rotated at each grid point's longitude.
- ``ncss_rap_point_csv_constructed.csv``: a THREDDS NCSS point CSV in the
  recorded header format with the four variables of the RAP dataset on its
  37 levels (100-1000 hPa), grid point 32.99 N 106.97 W, 2024-12-11T21:00Z:
  U.S. Standard Atmosphere 1976 temperature and geopotential height, and
  *grid-relative* winds of an earth-relative 12 m/s westerly, rotated into
  the RAP Lambert grid (LoV 265 deg, tangent latitude 25 deg).

    python tests/data/weather/make_constructed.py
"""
from __future__ import annotations

import csv
import math
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
G0, R = 9.80665, 287.05287


def gfs_column(dT=0.0):
    """The recorded GFS temperature column at 40 N 105 W (plus ``dT`` [K]) from 1000 hPa up, and
    its hypsometric geopotential heights (dry air, 1000 hPa at 120 gpm): ``p [Pa], T [K], H [gpm]``."""
    rows = list(csv.reader(open(HERE / "ncss_gfs0p5_point_csv_2015-06-12T15Z_40N_105W.csv")))
    p = np.array([float(r[3]) for r in rows[1:]])           # Pa, increasing
    T = np.array([float(r[4]) for r in rows[1:]]) + dT
    order = np.argsort(-p)                                    # from 1000 hPa upwards
    p, T = p[order], T[order]
    H = [120.0]
    for i in range(1, p.size):
        H.append(H[-1] + R * 0.5 * (T[i] + T[i - 1]) / G0 * math.log(p[i - 1] / p[i]))
    return p, T, np.array(H)


def gfs_grib():
    from eccodes import (codes_get_message, codes_grib_new_from_samples, codes_release,
                         codes_set, codes_set_values)
    p, T, H = gfs_column()
    u, v = 2.0 + 0.001 * H, -1.0 - 0.0005 * H
    fields = {"gh": H, "t": T, "r": np.full_like(T, 50.0), "u": u, "v": v}
    names = {"gh": "HGT", "t": "TMP", "r": "RH", "u": "UGRD", "v": "VGRD"}
    out, idx, offset, n = bytearray(), [], 0, 0
    for i in range(p.size):
        for short in ("gh", "t", "r", "u", "v"):
            g = codes_grib_new_from_samples("regular_ll_pl_grib2")
            codes_set(g, "centre", "kwbc")
            codes_set(g, "dataDate", 20170905)
            codes_set(g, "dataTime", 600)
            codes_set(g, "forecastTime", 6)
            codes_set(g, "Ni", 5)
            codes_set(g, "Nj", 5)
            codes_set(g, "latitudeOfFirstGridPointInDegrees", 41.0)
            codes_set(g, "longitudeOfFirstGridPointInDegrees", 254.0)
            codes_set(g, "latitudeOfLastGridPointInDegrees", 39.0)
            codes_set(g, "longitudeOfLastGridPointInDegrees", 256.0)
            codes_set(g, "iDirectionIncrementInDegrees", 0.5)
            codes_set(g, "jDirectionIncrementInDegrees", 0.5)
            codes_set(g, "shortName", short)
            codes_set(g, "typeOfLevel", "isobaricInhPa")
            codes_set(g, "level", int(round(p[i] / 100.0)))
            codes_set(g, "bitsPerValue", 24)
            # constant value plus a small gradient, exact at the centre node
            ramp = np.linspace(-1.0, 1.0, 25) * 0.01 * max(1.0, abs(fields[short][i]))
            ramp[12] = 0.0
            codes_set_values(g, fields[short][i] + ramp)
            msg = codes_get_message(g)
            codes_release(g)
            n += 1
            level = f"{int(round(p[i] / 100.0))} mb"
            idx.append(f"{n}:{offset}:d=2017090506:{names[short]}:{level}:6 hour fcst:")
            out += msg
            offset += len(msg)
    (HERE / "gfs_constructed.t06z.f006.grib2").write_bytes(bytes(out))
    (HERE / "gfs_constructed.t06z.f006.grib2.idx").write_text("\n".join(idx) + "\n")


def isa(H):
    """U.S. Standard Atmosphere 1976 below 20 km: T [K], p [Pa] at geopotential H [m']."""
    if H <= 11000.0:
        T = 288.15 - 0.0065 * H
        return T, 101325.0 * (T / 288.15) ** (G0 / (R * 0.0065))
    return 216.65, 22632.06 * math.exp(-G0 * (H - 11000.0) / (R * 216.65))


def isa_height(p):
    lo, hi = -1000.0, 20000.0
    for _ in range(100):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if isa(mid)[1] > p else (lo, mid)
    return 0.5 * (lo + hi)


def rap_grib():
    from eccodes import (codes_get_array, codes_get_message, codes_grib_new_from_samples,
                         codes_release, codes_set, codes_set_values)
    out, idx, offset, n = bytearray(), [], 0, 0
    for hpa in range(1000, 99, -50):
        H = isa_height(hpa * 100.0)
        T = isa(H)[0]
        for short, name in (("gh", "HGT"), ("t", "TMP"), ("u", "UGRD"), ("v", "VGRD")):
            g = codes_grib_new_from_samples("GRIB2")
            codes_set(g, "gridType", "lambert")
            for k, val in (("Nx", 5), ("Ny", 5), ("latitudeOfFirstGridPointInDegrees", 32.7),
                           ("longitudeOfFirstGridPointInDegrees", 252.75),
                           ("LaDInDegrees", 25.0), ("LoVInDegrees", 265.0),
                           ("Latin1InDegrees", 25.0), ("Latin2InDegrees", 25.0),
                           ("DxInMetres", 13545), ("DyInMetres", 13545), ("shapeOfTheEarth", 6),
                           ("centre", "kwbc"), ("dataDate", 20241211), ("dataTime", 1900),
                           ("forecastTime", 2), ("typeOfLevel", "isobaricInhPa"),
                           ("level", hpa), ("shortName", short), ("bitsPerValue", 24)):
                codes_set(g, k, val)
            codes_set(g, "uvRelativeToGrid", 1)
            codes_set_values(g, np.zeros(25))
            lons = codes_get_array(g, "longitudes")
            theta = math.sin(math.radians(25.0)) * np.radians(lons - 265.0)
            east, north = 5.0, 8.0
            ug = np.cos(theta) * east - np.sin(theta) * north
            vg = np.sin(theta) * east + np.cos(theta) * north
            values = {"gh": np.full(25, H), "t": np.full(25, T), "u": ug, "v": vg}[short]
            codes_set_values(g, values)
            msg = codes_get_message(g)
            codes_release(g)
            n += 1
            idx.append(f"{n}:{offset}:d=2024121119:{name}:{hpa} mb:2 hour fcst:")
            out += msg
            offset += len(msg)
    (HERE / "rap_constructed.t19z.awp130pgrbf02.grib2").write_bytes(bytes(out))
    (HERE / "rap_constructed.t19z.awp130pgrbf02.grib2.idx").write_text("\n".join(idx) + "\n")


def rap_csv():
    lat, lon = 32.99, -106.97
    theta = math.sin(math.radians(25.0)) * math.radians(lon - (265.0 - 360.0))
    east, north = 12.0, 0.0
    # inverse of east = c u + s v, north = -s u + c v
    c, s = math.cos(theta), math.sin(theta)
    ug, vg = c * east - s * north, s * east + c * north
    lines = ['date,lat[unit="degrees_north"],lon[unit="degrees_east"],vertCoord[unit="Pa"],'
             'Geopotential_height_isobaric[unit="gpm"],Temperature_isobaric[unit="K"],'
             'u-component_of_wind_isobaric[unit="m/s"],v-component_of_wind_isobaric[unit="m/s"]']
    for p in np.arange(10000.0, 100001.0, 2500.0):
        H = isa_height(p)
        T = isa(H)[0]
        lines.append(f"2024-12-11T21:00:00Z,{lat},{lon},{p:.1f},{H:.1f},{T:.2f},{ug:.4f},{vg:.4f}")
    (HERE / "ncss_rap_point_csv_constructed.csv").write_text("\n".join(lines) + "\n")


if __name__ == "__main__":
    gfs_grib()
    rap_grib()
    rap_csv()
