"""Geodesy and KML of :mod:`ironbark_opt.report` against published numbers and
the Monte Carlo covariance (no flights: a Dispersion built from known samples)."""
import math

import numpy as np
import pytest

from ironbark_opt.analysis.montecarlo import Dispersion
from ironbark_opt.report.geodesy import local_to_geodetic, radii_of_curvature
from ironbark_opt.report.kml import dispersion_kml
from kml_check import K, ellipse_covariances, parse_kml


@pytest.mark.parametrize("lat_deg", [0.0, 30.0, 45.0, 60.0])
def test_degree_lengths_match_bowditch(lat_deg):
    """Length of one degree of latitude and of longitude, from the radii of
    curvature, against the series of Bowditch, *The American Practical
    Navigator* (NGA Pub. 9), "length of a degree": 111132.92 - 559.82 cos 2p +
    1.175 cos 4p - 0.0023 cos 6p and 111412.84 cos p - 93.5 cos 3p + 0.118 cos 5p
    [m]; tolerance 0.1 m (1e-6, the series' rounding)."""
    p = math.radians(lat_deg)
    m, n = radii_of_curvature(p)
    lat_len, lon_len = math.pi / 180 * m, math.pi / 180 * n * math.cos(p)
    ref_lat = 111132.92 - 559.82 * math.cos(2 * p) + 1.175 * math.cos(4 * p) - 0.0023 * math.cos(6 * p)
    ref_lon = 111412.84 * math.cos(p) - 93.5 * math.cos(3 * p) + 0.118 * math.cos(5 * p)
    print(f"{lat_deg:g} deg: 1 deg latitude {lat_len:.3f} m (Bowditch {ref_lat:.3f}), "
          f"1 deg longitude {lon_len:.3f} m (Bowditch {ref_lon:.3f})")
    assert lat_len == pytest.approx(ref_lat, abs=0.1) and lon_len == pytest.approx(ref_lon, abs=0.1)
    lat, lon = local_to_geodetic(ref_lon, ref_lat, p, math.radians(-106.0))
    assert lat == pytest.approx(lat_deg + 1.0, abs=2e-3) and lon == pytest.approx(-105.0, abs=2e-6)


def test_equator_radii():
    """At the equator N = a and M = a (1 - e^2) (WGS-84: a = 6378137 m, 1/f = 298.257223563)."""
    m0, n0 = radii_of_curvature(0.0)
    assert n0 == pytest.approx(6378137.0, abs=1e-6) and m0 == pytest.approx(6335439.327, abs=1e-3)


def _dispersion(east, north):
    n = len(east)
    table = {"sample": np.arange(n), "apogee_east_m": east * 0.5, "apogee_north_m": north * 0.5,
             "landing_east_m": east, "landing_north_m": north}
    return Dispersion(name="TestRocket", samples=n, seed=7, descent=True, dispersed=(), distributions={},
                      stats={}, extra={}, _table=table)


def test_ellipse_polygons_recover_the_monte_carlo_covariance():
    rng = np.random.default_rng(3)
    sigma = np.array([[250.0 ** 2, 0.6 * 250 * 120], [0.6 * 250 * 120, 120.0 ** 2]])
    pts = rng.multivariate_normal([800.0, -600.0], sigma, size=400)
    disp = _dispersion(pts[:, 0], pts[:, 1])
    lat0, lon0 = 39.3897, -8.288964
    text = dispersion_kml(disp, math.radians(lat0), math.radians(lon0), 140.0)
    cov = np.cov(pts.T)                       # the Dispersion's (sample) covariance
    got = ellipse_covariances(text, lat0, lon0, 140.0)
    assert sorted(got) == [1.0, 2.0, 3.0]
    for k, c in got.items():
        err = np.abs(c - cov).max() / np.abs(cov).max()
        print(f"{k:g} sigma: covariance from the polygon {c.ravel().round(1)} vs samples {cov.ravel().round(1)}, "
              f"max rel. error {err:.2e}")
        assert err < 1e-5               # coordinates printed to 1e-7 deg (1 cm)
    names = [pm.find(K + "name").text for pm in parse_kml(text).findall(K + "Placemark")]
    assert "1 sigma landing ellipse (39.3 %)" in names and "3 sigma landing ellipse (98.9 %)" in names
