"""Geodesy: frames and great circles against independent facts."""

import math

import numpy as np
import pytest

from flightmode.sim.flight import geodesy
from flightmode.sim.flight.plan import Runway


def test_ned_of_origin_is_zero_and_up_is_minus_down():
    ned = geodesy.geodetic_to_ned(46.2, 6.1, 1430.0, 46.2, 6.1, 430.0)
    # 1000 m straight up is -1000 m in D, to floating-point accuracy of ECEF differences (~1e-9 m)
    np.testing.assert_allclose(ned, [[0.0, 0.0, -1000.0]][0], atol=1e-6)


def test_ned_north_offset_matches_meridian_arc():
    # 0.01 deg of latitude at 46 deg: meridian radius of curvature gives 1111.4 m; the tangent-plane
    # north coordinate differs from the arc by O(s^3/R^2) < 1 mm
    lat0 = 46.0
    ned = geodesy.geodetic_to_ned(lat0 + 0.01, 6.0, 0.0, lat0, 6.0, 0.0)
    s = math.sin(math.radians(lat0))
    rm = geodesy.WGS84_A_M * (1 - geodesy.WGS84_E2) / (1 - geodesy.WGS84_E2 * s * s) ** 1.5
    assert ned[0] == pytest.approx(rm * math.radians(0.01), abs=1e-3)
    assert abs(ned[1]) < 1e-6


def test_great_circle_gva_lhr():
    # Geneva to Heathrow is about 752 km on the mean sphere (haversine, published route figures
    # 750-760 km); 1 km tolerance covers the rounding of the threshold coordinates
    d = geodesy.great_circle_distance_m(46.2500, 6.1275, 51.4648, -0.4341)
    assert d == pytest.approx(752_000, abs=6_000)
    # the initial course is north-west; on the sphere it is steeper north than the rhumb line
    c = geodesy.initial_course_deg(46.2500, 6.1275, 51.4648, -0.4341)
    assert 315 < c < 330


def test_destination_point_inverts_course_and_distance():
    lat, lon = geodesy.destination_point(60.0, 25.0, 224.0, 500_000.0)
    assert geodesy.great_circle_distance_m(60.0, 25.0, lat, lon) == pytest.approx(500_000.0, rel=1e-9)
    assert geodesy.initial_course_deg(60.0, 25.0, lat, lon) == pytest.approx(224.0, abs=1e-6)


@pytest.mark.parametrize("heading", [0.0, 47.0, 227.0, 315.0])
def test_runway_frame_axes_and_round_trip(heading):
    rwy = Runway("XXXX", "01", 51.0, -0.4, 25.0, heading, 3000.0)
    fr = geodesy.RunwayFrame(rwy)
    # the runway frame is the WGS-84 tangent plane rotated to the runway heading: compare with the
    # exact ECEF->NED transform (it is that transform, so 1 mm at 30 km out on the approach)
    for x, y in [(1000.0, 0.0), (0.0, 200.0), (-1500.0, -300.0), (-30000.0, 40.0)]:
        lat, lon = fr.to_latlon(x, y)
        n, e, _ = geodesy.geodetic_to_ned(lat, lon, 25.0, 51.0, -0.4, 25.0)
        h = math.radians(heading)
        assert n * math.cos(h) + e * math.sin(h) == pytest.approx(x, abs=1e-3)
        assert -n * math.sin(h) + e * math.cos(h) == pytest.approx(y, abs=1e-3)
    # and the frame inverts itself exactly (a linear map)
    lat2, lon2 = fr.to_latlon(123.4, -567.8)
    assert fr.to_xy(lat2, lon2) == pytest.approx((123.4, -567.8), abs=1e-6)
