"""A saved one-column atmosphere profile flown far from where it was taken is said so.

A JSON profile ('ironbark weather get --json') carries the latitude and longitude it was
taken at; flown at another launch site its winds and temperatures are another place's.
Found in session 21's README audit: a Kaltbrunn (Switzerland) profile flew at Spaceport
America without a word, while a reanalysis file at the wrong place is refused.
"""
import json
import math
import warnings

import numpy as np
import pytest

from ironbark_opt.atmosphere.files import (EARTH_RADIUS_KM, PROFILE_SITE_WARN_KM,
                                           load_atmosphere_file, site_distance_km)

KALTBRUNN = (47.2131, 9.0245)                 # [deg]
SPACEPORT = (32.9904, -106.9750)              # [deg]


def _profile_json(tmp_path, lat_deg, lon_deg):
    z = np.linspace(0.0, 5000.0, 11)
    levels = {"altitude_m": z.tolist(), "temperature_K": (288.15 - 0.0065 * z).tolist(),
              "pressure_Pa": (101325.0 * (1 - 2.25577e-5 * z) ** 5.25588).tolist(),
              "wind_east_mps": [3.0] * 11, "wind_north_mps": [0.0] * 11}
    path = tmp_path / "profile.json"
    path.write_text(json.dumps({"source": "test", "latitude_deg": lat_deg,
                                "longitude_deg": lon_deg, "levels": levels}))
    return path


def test_great_circle_distance_analytic():
    # a degree of longitude on the equator and of latitude on a meridian: 2 pi R / 360
    arc = 2.0 * math.pi * EARTH_RADIUS_KM / 360.0
    assert site_distance_km(0.0, 0.0, 0.0, 1.0) == pytest.approx(arc, rel=1e-12)
    assert site_distance_km(10.0, 20.0, 11.0, 20.0) == pytest.approx(arc, rel=1e-12)
    assert site_distance_km(45.0, 0.0, -45.0, 180.0) == pytest.approx(math.pi * EARTH_RADIUS_KM, rel=1e-12)


def test_profile_far_from_the_site_warns_with_the_distance(tmp_path):
    path = _profile_json(tmp_path, *KALTBRUNN)
    d = site_distance_km(*KALTBRUNN, *SPACEPORT)
    with pytest.warns(UserWarning, match=rf"{d:.0f} km from the launch site") as rec:
        prof = load_atmosphere_file(path, latitude=math.radians(SPACEPORT[0]),
                                    longitude=math.radians(SPACEPORT[1]))
    assert str(path) in str(rec[0].message) and d > 8000.0
    assert prof.latitude_deg == pytest.approx(KALTBRUNN[0])


def test_profile_at_or_near_the_site_or_without_a_site_is_silent(tmp_path):
    path = _profile_json(tmp_path, *KALTBRUNN)
    near = (KALTBRUNN[0] + 0.9 * PROFILE_SITE_WARN_KM / 111.2, KALTBRUNN[1])   # ~270 km north
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        load_atmosphere_file(path, latitude=math.radians(near[0]), longitude=math.radians(near[1]))
        load_atmosphere_file(path)                    # no site given: nothing to compare
