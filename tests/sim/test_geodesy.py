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


def _geodesic(lat1, lon1, lat2, lon2):
    """The WGS-84 geodesic (m) and its initial azimuth (deg), by pyproj (PROJ's geodesic library,
    Karney's algorithm, accurate to 15 nm): the field's reference, independent of flightmode."""
    from pyproj import Geod

    az, _, s = Geod(ellps="WGS84").inv(lon1, lat1, lon2, lat2)
    return s, az % 360.0


def _sphere_unit(lat_deg, lon_deg):
    p, lam = math.radians(lat_deg), math.radians(lon_deg)
    return np.array([math.cos(p) * math.cos(lam), math.cos(p) * math.sin(lam), math.sin(p)])


def test_geodesic_reference_reproduces_its_published_example():
    # Flinders Peak to Buninyong (Vincenty 1975; Geoscience Australia's worked example): 54,972.271 m,
    # azimuth 306 deg 52' 05.37"; the printed figures are good to 1 mm / 0.01"
    s, az = _geodesic(
        -(37 + 57 / 60 + 3.72030 / 3600),
        144 + 25 / 60 + 29.52440 / 3600,
        -(37 + 39 / 60 + 10.15610 / 3600),
        143 + 55 / 60 + 35.38390 / 3600,
    )
    assert s == pytest.approx(54_972.271, abs=1e-3)
    assert az == pytest.approx(306 + 52 / 60 + 5.37 / 3600, abs=0.01 / 3600)


def test_great_circle_gva_lhr():
    """Geneva to Heathrow (coordinates to 1e-4 deg, ~10 m: the same
    coordinates go into every reference, so their rounding does not enter the comparison)."""
    p1, p2 = (46.2500, 6.1275), (51.4648, -0.4341)
    d = float(geodesy.great_circle_distance_m(*p1, *p2))
    c = float(geodesy.initial_course_deg(*p1, *p2))
    # 1. On the sphere, exactly: the central angle from the unit vectors (atan2 of |u x v| and
    # u . v, a different formula from the haversine) times the IUGG mean radius R1 = a (1 - f/3)
    # = 6,371,008.77 m. Tolerance rel 1e-8: the module rounds R1 to 0.1 m (4.5e-9); float round-off
    # is ~1e-15.
    u, v = _sphere_unit(*p1), _sphere_unit(*p2)
    r1 = geodesy.WGS84_A_M * (1.0 - geodesy.WGS84_F / 3.0)
    assert r1 == pytest.approx(6_371_008.77, abs=0.01)
    ang = math.atan2(np.linalg.norm(np.cross(u, v)), u @ v)
    assert d == pytest.approx(r1 * ang, rel=1e-8)
    # and the initial course: the tangent at point 1 towards point 2, v - (u . v) u, resolved on
    # the local north and east unit vectors (round-off only: 1e-9 deg)
    tdir = v - (u @ v) * u
    lat, lon = map(math.radians, p1)
    north = np.array([-math.sin(lat) * math.cos(lon), -math.sin(lat) * math.sin(lon), math.cos(lat)])
    east = np.array([-math.sin(lon), math.cos(lon), 0.0])
    assert c == pytest.approx(math.degrees(math.atan2(tdir @ east, tdir @ north)) % 360.0, abs=1e-9)
    # 2. Against the true WGS-84 geodesic: a sphere of radius R1 replaces the ellipsoid's
    # radius of curvature, which along this route lies between the meridian radius M at 46.25 N
    # (6,368.8 km) and the prime-vertical radius N at 51.46 N (6,391.2 km); so the geodesic over the
    # spherical distance must lie in [M / R1, N / R1] = [0.99965, 1.00318] (0.35 % wide: the
    # sphere's modelling error, not a test tolerance that hides anything finer than it).
    s_geo, az_geo = _geodesic(*p1, *p2)
    e2 = geodesy.WGS84_E2
    m_lo = geodesy.WGS84_A_M * (1 - e2) / (1 - e2 * math.sin(math.radians(p1[0])) ** 2) ** 1.5
    n_hi = geodesy.WGS84_A_M / math.sqrt(1 - e2 * math.sin(math.radians(p2[0])) ** 2)
    assert m_lo / r1 <= s_geo / d <= n_hi / r1, (s_geo, d)
    # the geodesic's azimuth differs from the great circle's by O(f) rad = 0.19 deg at most
    assert abs(c - az_geo) < math.degrees(geodesy.WGS84_F)


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
