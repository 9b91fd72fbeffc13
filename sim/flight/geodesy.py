"""Geodesy: WGS-84 geodetic <-> ECEF <-> local NED, and great-circle navigation on a sphere.

Vectorised over NumPy arrays. Angles in degrees at the boundary (``lat_deg``), radians inside.
Great-circle formulas are the standard spherical ones (mean Earth radius), which is how route
courses and distances to go are flown; truth positions use the WGS-84 ellipsoid.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

import numpy as np

if TYPE_CHECKING:
    from flightmode.sim.flight.plan import Runway

WGS84_A_M = 6378137.0
WGS84_F = 1.0 / 298.257223563
WGS84_E2 = WGS84_F * (2.0 - WGS84_F)
EARTH_MEAN_RADIUS_M = 6371008.8


def geodetic_to_ecef(lat_deg, lon_deg, alt_m):
    """WGS-84 geodetic to Earth-centred Earth-fixed coordinates (m); arrays broadcast."""
    lat = np.radians(lat_deg)
    lon = np.radians(lon_deg)
    sin_lat = np.sin(lat)
    n = WGS84_A_M / np.sqrt(1.0 - WGS84_E2 * sin_lat**2)
    x = (n + alt_m) * np.cos(lat) * np.cos(lon)
    y = (n + alt_m) * np.cos(lat) * np.sin(lon)
    z = (n * (1.0 - WGS84_E2) + alt_m) * sin_lat
    return np.stack(np.broadcast_arrays(x, y, z), axis=-1)


def ecef_to_ned_matrix(lat_deg, lon_deg) -> np.ndarray:
    """Rotation matrices (..., 3, 3) taking ECEF vectors into the local NED frame at (lat, lon);
    (3, 3) for scalars. The one ECEF <-> NED rotation of flightmode (its transpose goes back)."""
    la, lo = np.radians(lat_deg), np.radians(lon_deg)
    sl, cl, so, co = np.sin(la), np.cos(la), np.sin(lo), np.cos(lo)
    r = np.empty(np.shape(la) + (3, 3))
    r[..., 0, :] = np.stack([-sl * co, -sl * so, cl], axis=-1)
    r[..., 1, :] = np.stack([-so, co, np.zeros_like(so)], axis=-1)
    r[..., 2, :] = np.stack([-cl * co, -cl * so, -sl], axis=-1)
    return r


def ned_to_ecef(lat_deg, lon_deg, v_ned) -> np.ndarray:
    """NED vectors (n, 3) at (lat, lon) (n,) rotated into ECEF: ``ecef_to_ned_matrix(lat, lon)^T v``,
    without building the (n, 3, 3) matrices."""
    la, lo = np.radians(lat_deg), np.radians(lon_deg)
    sl, cl, so, co = np.sin(la), np.cos(la), np.sin(lo), np.cos(lo)
    v = np.asarray(v_ned, float)
    n, e, d = v[..., 0], v[..., 1], v[..., 2]
    return np.stack(
        [-sl * co * n - so * e - cl * co * d, -sl * so * n + co * e - cl * so * d, cl * n - sl * d], axis=-1
    )


def geodetic_to_ned(lat_deg, lon_deg, alt_m, lat0_deg: float, lon0_deg: float, alt0_m: float):
    """Position (N x 3, m) in the local NED frame whose origin is (lat0, lon0, alt0)."""
    ecef = geodetic_to_ecef(lat_deg, lon_deg, alt_m)
    ecef0 = geodetic_to_ecef(lat0_deg, lon0_deg, alt0_m)
    return (ecef - ecef0) @ ecef_to_ned_matrix(lat0_deg, lon0_deg).T


def great_circle_distance_m(lat1_deg, lon1_deg, lat2_deg, lon2_deg):
    """Haversine distance on the mean-radius sphere (m)."""
    p1, p2 = np.radians(lat1_deg), np.radians(lat2_deg)
    dp = p2 - p1
    dl = np.radians(np.asarray(lon2_deg) - np.asarray(lon1_deg))
    h = np.sin(dp / 2) ** 2 + np.cos(p1) * np.cos(p2) * np.sin(dl / 2) ** 2
    return 2.0 * EARTH_MEAN_RADIUS_M * np.arcsin(np.sqrt(np.clip(h, 0.0, 1.0)))


def initial_course_deg(lat1_deg, lon1_deg, lat2_deg, lon2_deg):
    """Initial great-circle course from point 1 to point 2, degrees true in [0, 360)."""
    p1, p2 = np.radians(lat1_deg), np.radians(lat2_deg)
    dl = np.radians(np.asarray(lon2_deg) - np.asarray(lon1_deg))
    y = np.sin(dl) * np.cos(p2)
    x = np.cos(p1) * np.sin(p2) - np.sin(p1) * np.cos(p2) * np.cos(dl)
    return np.degrees(np.arctan2(y, x)) % 360.0


def gc_distance_m(lat1_deg: float, lon1_deg: float, lat2_deg: float, lon2_deg: float) -> float:
    """Scalar :func:`great_circle_distance_m` (plain math: the pilot calls it every tick)."""
    p1, p2 = math.radians(lat1_deg), math.radians(lat2_deg)
    h = (
        math.sin((p2 - p1) / 2) ** 2
        + math.cos(p1) * math.cos(p2) * math.sin(math.radians(lon2_deg - lon1_deg) / 2) ** 2
    )
    return 2.0 * EARTH_MEAN_RADIUS_M * math.asin(math.sqrt(min(1.0, max(0.0, h))))


def gc_course_rad(lat1_deg: float, lon1_deg: float, lat2_deg: float, lon2_deg: float) -> float:
    """Scalar initial great-circle course (rad, -pi..pi) from point 1 to point 2."""
    p1, p2 = math.radians(lat1_deg), math.radians(lat2_deg)
    dl = math.radians(lon2_deg - lon1_deg)
    return math.atan2(
        math.sin(dl) * math.cos(p2), math.cos(p1) * math.sin(p2) - math.sin(p1) * math.cos(p2) * math.cos(dl)
    )


def destination_point(lat_deg: float, lon_deg: float, course_deg: float, distance_m: float):
    """Point reached from (lat, lon) along a great circle with the given initial course."""
    p1, l1 = np.radians(lat_deg), np.radians(lon_deg)
    c = np.radians(course_deg)
    d = distance_m / EARTH_MEAN_RADIUS_M
    p2 = np.arcsin(np.sin(p1) * np.cos(d) + np.cos(p1) * np.sin(d) * np.cos(c))
    l2 = l1 + np.arctan2(np.sin(c) * np.sin(d) * np.cos(p1), np.cos(d) - np.sin(p1) * np.sin(p2))
    return float(np.degrees(p2)), float((np.degrees(l2) + 540.0) % 360.0 - 180.0)


class RunwayFrame:
    """The tangent plane at a runway threshold, rotated to the runway: x along the runway heading,
    y to the right (m). Exact WGS-84 ECEF -> NED of the point taken at the threshold elevation
    (scalar math: the pilot calls it every tick; an aircraft's height only scales the horizontal
    distance by 1 + h/R, i.e. along the approach path, not across it)."""

    def __init__(self, rwy: Runway):
        self.rwy = rwy
        lat0, lon0 = math.radians(rwy.lat_deg), math.radians(rwy.lon_deg)
        self._h = rwy.elevation_m  # points are taken at the threshold elevation
        self._ecef0 = self._ecef(lat0, lon0, self._h)
        sl, cl = math.sin(lat0), math.cos(lat0)
        h = math.radians(rwy.heading_deg)
        ch, sh = math.cos(h), math.sin(h)
        # rows: runway x = N cos h + E sin h; runway y = -N sin h + E cos h (plain floats: the pilot
        # calls to_xy every tick)
        n_row, e_row, _ = ecef_to_ned_matrix(rwy.lat_deg, rwy.lon_deg).tolist()
        self._rx = tuple(ch * a + sh * b for a, b in zip(n_row, e_row))
        self._ry = tuple(-sh * a + ch * b for a, b in zip(n_row, e_row))
        s = sl
        rn = WGS84_A_M / math.sqrt(1.0 - WGS84_E2 * s * s)
        self._m_per_deg_n = math.radians(1.0) * rn * (1.0 - WGS84_E2) / (1.0 - WGS84_E2 * s * s)
        self._m_per_deg_e = math.radians(1.0) * rn * cl
        self._ch, self._sh = ch, sh
        self.heading_rad = h

    @staticmethod
    def _ecef(lat: float, lon: float, h: float) -> tuple[float, float, float]:
        s, c = math.sin(lat), math.cos(lat)
        n = WGS84_A_M / math.sqrt(1.0 - WGS84_E2 * s * s)
        return (n + h) * c * math.cos(lon), (n + h) * c * math.sin(lon), (n * (1.0 - WGS84_E2) + h) * s

    def to_xy(self, lat_deg: float, lon_deg: float) -> tuple[float, float]:
        px, py, pz = self._ecef(math.radians(lat_deg), math.radians(lon_deg), self._h)
        dx, dy, dz = px - self._ecef0[0], py - self._ecef0[1], pz - self._ecef0[2]
        rx, ry = self._rx, self._ry
        return rx[0] * dx + rx[1] * dy + rx[2] * dz, ry[0] * dx + ry[1] * dy + ry[2] * dz

    def to_latlon(self, x: float, y: float) -> tuple[float, float]:
        """Inverse of :meth:`to_xy` (fixed-point iteration from the flat guess; sub-millimetre)."""
        lat, lon = self.rwy.lat_deg, self.rwy.lon_deg
        tx, ty = x, y
        for _ in range(6):
            n = tx * self._ch - ty * self._sh
            e = tx * self._sh + ty * self._ch
            lat, lon = lat + n / self._m_per_deg_n, lon + e / self._m_per_deg_e
            gx, gy = self.to_xy(lat, lon)
            tx, ty = x - gx, y - gy
            if abs(tx) + abs(ty) < 1e-6:
                break
        return lat, lon

    def heading_in_frame(self, psi_rad: float) -> float:
        return psi_rad - self.heading_rad
