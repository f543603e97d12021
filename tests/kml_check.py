"""Reading back the KML of :mod:`ironbark_opt.report.kml` in tests: the OGC KML 2.2
structure (xml.etree) and the covariance behind an ellipse polygon."""
import math
import xml.etree.ElementTree as ET

import numpy as np

from ironbark_opt.report.geodesy import radii_of_curvature
from ironbark_opt.report.kml import KML_NS

K = f"{{{KML_NS}}}"


def parse_kml(text):
    """Root of a KML document after checking the OGC KML 2.2 structure used here."""
    root = ET.fromstring(text.encode("utf-8"))
    assert root.tag == K + "kml"
    docs = root.findall(K + "Document")
    assert len(docs) == 1
    doc = docs[0]
    children = [c.tag for c in doc]
    # schema order: name, description, then Styles, then the Placemarks
    assert children[:2] == [K + "name", K + "description"]
    first_pm = children.index(K + "Placemark")
    assert all(t == K + "Style" for t in children[2:first_pm])
    assert all(t == K + "Placemark" for t in children[first_pm:])
    for pm in doc.findall(K + "Placemark"):
        tags = [c.tag.replace(K, "") for c in pm]
        assert tags[0] == "name" and tags[-1] in ("Point", "LineString", "Polygon")
        if "styleUrl" in tags:
            assert doc.find(f"{K}Style[@id='{pm.find(K + 'styleUrl').text[1:]}']") is not None
    return doc


def coordinates(element):
    """(lon, lat, alt) array of a geometry's coordinates, checking the lon,lat,alt ranges."""
    text = element.find(f".//{K}coordinates").text
    xyz = np.array([[float(v) for v in tup.split(",")] for tup in text.split()])
    assert xyz.shape[1] == 3
    assert np.all(np.abs(xyz[:, 0]) <= 180) and np.all(np.abs(xyz[:, 1]) <= 90)
    return xyz


def local_from_geodetic(lon, lat, lat0_deg, lon0_deg, height):
    """Inverse of the flat-Earth map (test side): east/north [m] at ``height`` [m]."""
    m, n = radii_of_curvature(math.radians(lat0_deg))
    return (np.radians(lon - lon0_deg) * (n + height) * math.cos(math.radians(lat0_deg)),
            np.radians(lat - lat0_deg) * (m + height))


def ellipse_covariances(kml_text, lat0_deg, lon0_deg, height):
    """{k: covariance recovered from the k-sigma polygon}: points equally spaced in
    the ellipse's parameter have second moments k^2/2 * Sigma."""
    doc = parse_kml(kml_text)
    out = {}
    for pm in doc.findall(K + "Placemark"):
        poly = pm.find(K + "Polygon")
        if poly is None:
            continue
        assert poly.find(K + "altitudeMode").text == "clampToGround"
        ring = poly.find(f"{K}outerBoundaryIs/{K}LinearRing")
        xyz = coordinates(ring)
        assert np.array_equal(xyz[0], xyz[-1]), "a LinearRing is closed"
        e, n = local_from_geodetic(xyz[:-1, 0], xyz[:-1, 1], lat0_deg, lon0_deg, height)
        k = float(pm.find(K + "name").text.split()[0])
        out[k] = 2.0 / k ** 2 * np.cov(np.vstack([e, n]), bias=True)
    return out
