"""Google Earth maps (OGC KML 2.2): a flight's trajectory and a Monte Carlo's
landing ellipses (numeric-only).

Element order follows the OGC KML 2.2 schema (OGC 07-147r2): a Document's
name, description and Styles before its Placemarks; a Placemark's name,
description and styleUrl before its geometry; ``coordinates`` are
``lon,lat,alt`` tuples in decimal degrees (WGS-84) and metres.  The
trajectory's altitudes are ``absolute`` (above sea level); ellipses are
drawn on the ground (``clampToGround``).

Ellipse convention ("n-sigma"): the k-sigma ellipse has k times the square
roots of the covariance eigenvalues as semi-axes (Mahalanobis distance k),
so a Gaussian scatter has ``1 - exp(-k^2/2)`` of its points inside
(39.3 %, 86.5 %, 98.9 % for k = 1, 2, 3; chi-square with 2 degrees of
freedom, see :data:`ironbark_opt.analysis.montecarlo.ELLIPSE_CONTENT`).
"""
from __future__ import annotations

import math
import xml.etree.ElementTree as ET

import numpy as np

from ironbark_opt.analysis.montecarlo import ELLIPSE_CONTENT, ellipse_points
from ironbark_opt.report.geodesy import local_to_geodetic, position_text

KML_NS = "http://www.opengis.net/kml/2.2"
#: line colours of the 1/2/3-sigma ellipses, KML aabbggrr
_SIGMA_COLOURS = {1: "ff00c000", 2: "ff00c0ff", 3: "ff0000ff"}


def _el(parent, tag, text=None, **attrs):
    e = ET.SubElement(parent, f"{{{KML_NS}}}{tag}", attrs)
    if text is not None:
        e.text = str(text)
    return e


def _coordinates(lon, lat, alt) -> str:
    return " ".join(f"{a:.7f},{b:.7f},{c:.1f}" for a, b, c in zip(lon, lat, alt))


def _document(name: str, description: str):
    ET.register_namespace("", KML_NS)
    root = ET.Element(f"{{{KML_NS}}}kml")
    doc = _el(root, "Document")
    _el(doc, "name", name)
    _el(doc, "description", description)
    return root, doc


def _style(doc, sid, colour, width, fill=None):
    style = _el(doc, "Style", id=sid)
    line = _el(style, "LineStyle")
    _el(line, "color", colour)
    _el(line, "width", width)
    if fill is not None:
        poly = _el(style, "PolyStyle")
        _el(poly, "color", fill)


def _point(doc, name, description, lon, lat, alt, mode="absolute"):
    pm = _el(doc, "Placemark")
    _el(pm, "name", name)
    _el(pm, "description", description)
    pt = _el(pm, "Point")
    _el(pt, "altitudeMode", mode)
    _el(pt, "coordinates", _coordinates([lon], [lat], [alt]))


def _text(root) -> str:
    ET.indent(root, space=" ")
    return '<?xml version="1.0" encoding="UTF-8"?>\n' + ET.tostring(root, encoding="unicode") + "\n"


def flight_kml(flight, latitude: float, longitude: float, *, atmosphere: str = "") -> str:
    """KML text of ``flight``'s trajectory from the rail at ``latitude``/``longitude`` [rad].

    A ``LineString`` through every integrator sample (altitude above sea
    level, ``absolute``) and Points at the rail, apogee and (when flown) the
    landing point.
    """
    df = flight.to_dataframe()
    s = flight.summary_values
    elev = s["site_elevation_m"]
    alt = df["altitude_asl_m"].to_numpy()
    lat, lon = local_to_geodetic(df["x_east_m"].to_numpy(), df["y_north_m"].to_numpy(), latitude, longitude, alt)
    root, doc = _document(f"{flight.name}: trajectory",
                          f"apogee {s['apogee_agl_m']:.1f} m AGL at {s['apogee_time_s']:.2f} s; "
                          f"site elevation {elev:.1f} m ASL. {atmosphere}".strip())
    _style(doc, "trajectory", "ff0055ff", 3)
    lat0, lon0 = math.degrees(latitude), math.degrees(longitude)
    _point(doc, "launch rail", f"{position_text(latitude, longitude, 6)}, {elev:.1f} m ASL", lon0, lat0, elev)
    pm = _el(doc, "Placemark")
    _el(pm, "name", "trajectory")
    _el(pm, "description", "altitude above sea level (absolute), every integrator sample")
    _el(pm, "styleUrl", "#trajectory")
    line = _el(pm, "LineString")
    _el(line, "extrude", 0)
    _el(line, "tessellate", 0)
    _el(line, "altitudeMode", "absolute")
    _el(line, "coordinates", _coordinates(lon, lat, alt))
    for key, label in (("apogee", "apogee"), ("landing", "landing")):
        if f"{key}_east_m" not in s:
            continue
        h = elev + (s["apogee_agl_m"] if key == "apogee" else 0.0)
        la, lo = local_to_geodetic(s[f"{key}_east_m"], s[f"{key}_north_m"], latitude, longitude, h)
        _point(doc, f"{label} ({s[f'{key}_time_s']:.1f} s)",
               f"{s[f'{key}_east_m']:.1f} m east, {s[f'{key}_north_m']:.1f} m north of the rail, "
               f"{h:.1f} m ASL", float(lo), float(la), h)
    return _text(root)


def dispersion_kml(dispersion, latitude: float, longitude: float, site_elevation: float, *,
                   sigmas=(1, 2, 3), atmosphere: str = "", points: int = 181) -> str:
    """KML text of a Monte Carlo's 1/2/3-sigma ellipses (landing points when
    flown to landing, else apogee points projected on the ground), drawn
    around the rail at ``latitude``/``longitude`` [rad], ``site_elevation`` [m ASL]."""
    from ironbark_opt.analysis.montecarlo import error_ellipse

    east, north, which = dispersion.positions("auto")
    el = error_ellipse(east, north)
    root, doc = _document(f"{dispersion.name}: {which} dispersion",
                          f"{dispersion.samples} Monte Carlo samples, seed {dispersion.seed}; k-sigma ellipse: "
                          f"k x the square roots of the covariance eigenvalues. {atmosphere}".strip())
    for k in sigmas:
        colour = _SIGMA_COLOURS.get(k, "ffffffff")
        _style(doc, f"sigma{k:g}", colour, 2, fill="33" + colour[2:])
    lat0, lon0 = math.degrees(latitude), math.degrees(longitude)
    _point(doc, "launch rail", f"{position_text(latitude, longitude, 6)}, {site_elevation:.1f} m ASL", lon0, lat0,
           site_elevation)
    for k in sigmas:
        e, n = ellipse_points(el, k, points)
        lat, lon = local_to_geodetic(e, n, latitude, longitude, site_elevation)
        content = ELLIPSE_CONTENT.get(k, 1.0 - math.exp(-k * k / 2.0))
        pm = _el(doc, "Placemark")
        _el(pm, "name", f"{k:g} sigma {which} ellipse ({100 * content:.1f} %)")
        _el(pm, "description", f"semi-axes {k * el['semi_major_m']:.1f} x {k * el['semi_minor_m']:.1f} m, "
                               f"major axis {el['azimuth_deg']:.1f} deg from north")
        _el(pm, "styleUrl", f"#sigma{k:g}")
        poly = _el(pm, "Polygon")
        _el(poly, "tessellate", 1)
        _el(poly, "altitudeMode", "clampToGround")
        ring = _el(_el(poly, "outerBoundaryIs"), "LinearRing")
        _el(ring, "coordinates", _coordinates(lon, lat, np.full(len(lon), site_elevation)))
    la, lo = local_to_geodetic(el["center_east_m"], el["center_north_m"], latitude, longitude, site_elevation)
    _point(doc, f"mean {which} point", f"{el['center_east_m']:.1f} m east, {el['center_north_m']:.1f} m north",
           float(lo), float(la), site_elevation, mode="clampToGround")
    return _text(root)
