"""Profile: validation, log-pressure interpolation, outside-range policy, DataFrames."""
from __future__ import annotations

import math
import pickle
import warnings
from datetime import datetime, timezone

import casadi as ca
import numpy as np
import pandas as pd
import pytest

from ironbark_opt.atmosphere import (
    ISA, Profile, wind_from_speed_direction, wind_to_speed_direction)
from ironbark_opt.errors import InputError, OutOfRangeWarning

Z = [1200.0, 2000.0, 3500.0, 6000.0]
T = [300.0, 292.0, 284.0, 265.0]        # an inversion-free hot-day column
P = [87800.0, 79800.0, 66400.0, 47600.0]
E = [2.0, 5.0, 9.0, 15.0]
N = [-1.0, 0.0, 3.0, -4.0]


def _profile(**kw):
    return Profile(Z, T, P, E, N, source="test sounding", **kw)


def test_levels_reproduced_and_linear_between():
    prof = _profile()
    for i, z in enumerate(Z):
        assert prof.temperature(z) == pytest.approx(T[i], rel=1e-15)
        assert prof.pressure(z) == pytest.approx(P[i], rel=1e-14)
        assert prof.wind_l(z) == pytest.approx((E[i], N[i]), rel=1e-15)
    mid = 0.5 * (Z[1] + Z[2])
    assert prof.temperature(mid) == pytest.approx(0.5 * (T[1] + T[2]), rel=1e-15)
    assert prof.wind_l(mid)[0] == pytest.approx(0.5 * (E[1] + E[2]), rel=1e-15)


def test_pressure_is_exponential_between_levels():
    """p(mid) is the geometric mean of the neighbours; ln p linear in z."""
    prof = _profile()
    for f in (0.25, 0.5, 0.9):
        z = Z[2] + f * (Z[3] - Z[2])
        expected = P[2] * (P[3] / P[2]) ** f
        assert prof.pressure(z) == pytest.approx(expected, rel=1e-14)


def test_from_isa_interpolation_error():
    """A 250 m-level profile of the ISA 0..10 km reproduces it within the analytic
    bound of linear interpolation of ln p: max|d2 ln p/dz2| dz^2 / 8 with
    d2 ln p/dz2 = g |dT/dz| / (R T^2) (largest at the cold top), +2 % for
    the variation of g and dH/dz."""
    isa = ISA(temperature_offset=5.0)
    prof = Profile.from_atmosphere(isa, np.arange(0.0, 10001.0, 250.0))
    z = np.linspace(0.0, 10000.0, 1001)
    ep = np.max(np.abs(prof.pressure(z) / isa.pressure(z) - 1.0))
    et = np.max(np.abs(prof.temperature(z) - isa.temperature(z)))
    print(f"250 m ISA profile: max rel. pressure error {ep:.2e}, temperature {et:.1e} K")
    bound = 9.80665 * 0.0065 / (287.05287 * float(isa.temperature(10000.0)) ** 2) * 250.0 ** 2 / 8
    print(f"analytic bound {bound:.2e}")
    assert ep < 1.02 * bound
    assert et < 1e-4   # T is linear within a troposphere layer in z up to curvature of H(z)


def test_above_top_is_isa_matched_to_top_and_continuous():
    prof = _profile()
    top = Z[-1]
    for fn in (prof.temperature, prof.pressure, prof.density):
        assert fn(top + 1e-6) == pytest.approx(fn(top), rel=1e-9)
    # Above the top: the ISA lapse (-6.5 K/km in geopotential) and hydrostatic decay.
    isa_top = ISA.from_site(top, T[-1], P[-1])
    for z in (7000.0, 15000.0, 40000.0):
        assert prof.temperature(z) == pytest.approx(float(isa_top.temperature(z)), rel=1e-14)
        assert prof.pressure(z) == pytest.approx(float(isa_top.pressure(z)), rel=1e-13)
    assert prof.wind_l(20000.0) == (E[-1], N[-1])
    assert 0.0 < prof.pressure(40000.0) < P[-1]


def test_below_bottom_clamps_and_warns():
    prof = _profile()
    with pytest.warns(OutOfRangeWarning, match="below the profile"):
        t = prof.temperature(1000.0)
    assert t == T[0]
    with pytest.warns(OutOfRangeWarning):
        assert prof.pressure(np.array([0.0, 1500.0]))[0] == pytest.approx(P[0])
    s = ca.SX.sym("h")
    f = ca.Function("f", [s], [prof.pressure(s)])
    assert float(f(0.0)) == pytest.approx(P[0], rel=1e-14)   # never 0


def test_dT_at_constant_pressure_and_state():
    prof = _profile()
    z = 2600.0
    st = prof.state(z, 4.0)
    assert st["pressure"] == pytest.approx(prof.pressure(z))
    assert st["temperature"] == pytest.approx(prof.temperature(z) + 4.0)
    assert st["density"] == pytest.approx(prof.density(z, 4.0), rel=1e-15)
    assert st["speed_of_sound"] == pytest.approx(prof.speed_of_sound(z, 4.0), rel=1e-15)
    assert st["dynamic_viscosity"] == pytest.approx(prof.dynamic_viscosity(z, 4.0), rel=1e-15)
    assert (st["wind_east"], st["wind_north"]) == prof.wind_l(z)


@pytest.mark.parametrize("change, field, match", [
    ({"altitude": [1200.0, 2000.0, 2000.0, 6000.0]}, "altitude", "strictly increasing"),
    ({"altitude": [1200.0, 3000.0, 2000.0, 6000.0]}, "altitude", "level 2"),
    ({"temperature": [27.0, 19.0, 11.0, -8.0]}, "temperature", "kelvin"),
    ({"pressure": [87800.0, 79800.0, 80000.0, 47600.0]}, "pressure", "decrease"),
    ({"pressure": [878.0, 798.0, 664.0, -1.0]}, "pressure", "positive"),
    ({"wind_east": [1.0, float("nan"), 2.0, 3.0]}, "wind_east", "non-finite"),
    ({"wind_north": [1.0, 2.0]}, "wind_north", "levels"),
    ({"altitude": [[1.0, 2.0]] * 2}, "altitude", "1-D"),
    ({"temperature": ["a", "b", "c", "d"]}, "temperature", "numbers"),
])
def test_bad_data_raises_input_error(change, field, match):
    args = {"altitude": Z, "temperature": T, "pressure": P, "wind_east": E, "wind_north": N}
    args.update(change)
    with pytest.raises(InputError, match=match) as err:
        Profile(**args, source="bad.csv")
    assert err.value.field == field and err.value.source == "bad.csv"


def test_single_level_rejected():
    with pytest.raises(InputError, match="at least 2"):
        Profile([0.0], [288.0], [101325.0], [0.0], [0.0], source="x")


def test_wind_convention_round_trip():
    # A westerly (from 270 deg) blows towards the east; from north blows south.
    e, n = wind_from_speed_direction(10.0, math.radians(270.0))
    assert (e, n) == pytest.approx((10.0, 0.0), abs=1e-12)
    e, n = wind_from_speed_direction(10.0, 0.0)
    assert (e, n) == pytest.approx((0.0, -10.0), abs=1e-12)
    rng = np.random.default_rng(1)
    speed, direc = rng.uniform(0.1, 30, 50), rng.uniform(0, 2 * np.pi, 50)
    s2, d2 = wind_to_speed_direction(*wind_from_speed_direction(speed, direc))
    np.testing.assert_allclose(s2, speed, rtol=1e-12)
    np.testing.assert_allclose(d2, direc, atol=1e-12)


def test_dataframe_round_trip(tmp_path):
    t0 = datetime(2026, 6, 20, 12, tzinfo=timezone.utc)
    prof = _profile(valid_time=t0, run_time="2026-06-20T06Z", latitude_deg=32.99)
    df = prof.to_dataframe()
    assert list(df.columns) == ["altitude_m", "temperature_K", "pressure_Pa",
                                "wind_east_mps", "wind_north_mps"]
    path = tmp_path / "profile.csv"
    df.to_csv(path, index=False)
    back = Profile.from_dataframe(pd.read_csv(path), source=str(path))
    for a, b in ((back.altitude, Z), (back.temperature_levels, T), (back.pressure_levels, P),
                 (back.wind_east_levels, E), (back.wind_north_levels, N)):
        np.testing.assert_allclose(a, b, rtol=1e-15)
    again = Profile.from_dataframe(df)      # attrs carry the metadata
    d = again.describe()
    assert d["source"] == "test sounding" and d["valid_time"] == t0.isoformat()
    assert d["latitude_deg"] == 32.99 and d["levels"] == 4


def test_dataframe_variants_speed_direction_celsius_hpa_top_down():
    speed = np.hypot(E, N)
    direction = np.degrees(wind_to_speed_direction(E, N)[1])
    df = pd.DataFrame({
        "Altitude_m": Z[::-1], "temperature_C": np.array(T[::-1]) - 273.15,
        "pressure_hPa": np.array(P[::-1]) / 100.0,
        "wind_speed_kt": speed[::-1] / (1852.0 / 3600.0), "wind_direction_deg": direction[::-1],
        "dewpoint_C": 0.0,
    })
    prof = Profile.from_dataframe(df, source="sounding.csv")
    np.testing.assert_allclose(prof.altitude, Z)
    np.testing.assert_allclose(prof.temperature_levels, T, rtol=1e-14)
    np.testing.assert_allclose(prof.pressure_levels, P, rtol=1e-14)
    np.testing.assert_allclose(prof.wind_east_levels, E, atol=1e-12)
    np.testing.assert_allclose(prof.wind_north_levels, N, atol=1e-12)


def test_dataframe_errors_name_the_column():
    df = pd.DataFrame({"altitude_m": Z, "temperature_K": T, "pressure_Pa": P})
    with pytest.raises(InputError, match="wind_speed_mps") as err:
        Profile.from_dataframe(df, source="f.csv")
    assert err.value.field == "wind" and err.value.source == "f.csv"
    df = pd.DataFrame({"altitude_m": Z, "temperature_K": ["300", "x", "284", "265"],
                       "pressure_Pa": P, "wind_east_mps": E, "wind_north_mps": N})
    with pytest.raises(InputError, match="row 1") as err:
        Profile.from_dataframe(df)
    assert err.value.field == "temperature_K"
    with pytest.raises(InputError, match="altitude_m"):
        Profile.from_dataframe(pd.DataFrame({"height": Z}))


def test_pickle_and_repr():
    prof = _profile()
    s = ca.SX.sym("h")
    prof.pressure(s)                       # builds the CasADi interpolant
    back = pickle.loads(pickle.dumps(prof))
    assert back.pressure(2500.0) == prof.pressure(2500.0)
    assert repr(prof) == "Profile('test sounding', 4 levels, 1200..6000 m)"
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        assert float(ca.Function("f", [s], [back.pressure(s)])(2500.0)) == pytest.approx(
            prof.pressure(2500.0), rel=1e-14)
