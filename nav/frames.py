"""From what the accelerometer measured to world-frame kinematic acceleration (and the truth to
compare with).

The world frame is the FlightTrack's: ``pos_ned_m``, north/east/down of the tangent plane at the
origin airport, fixed to the Earth (ECEF). In that rotating frame the kinematic acceleration of a
point is

    a = C_w<-ned(lat, lon) (C_ned<-body f_body + g_n(lat, lon, h)) - 2 Omega_w x v

with ``f`` the specific force (what an accelerometer measures), ``g_n`` the effective gravity (J2
gravitation plus the centrifugal term, :func:`gravity_ned_mps2`), and the Coriolis
term from the Earth's rotation ``Omega`` (at 230 m/s it is 0.03 m/s^2: 220 km of position after an
hour if ignored).

Modes (issue: nav frames):

- :class:`TruthPath` (``acceleration``): the exact kinematic acceleration of the truth path, sampled as
  a perfect *integrating* accelerometer would (the mean over each sample period, from the exact
  velocity change). Point samples of JSBSim's 120 Hz acceleration alias the wheel spin-up and
  gear impulses (touchdown: 45 m/s^2 for one FDM step) and leave 20-80 m of error after a flight;
  the period means leave millimetres (tests/nav).
- :func:`truth_aided_acceleration`: a Recording's sensor-frame specific force rotated with the
  truth (the bag's orientation, the FlightTrack's attitude and position), plus gravity, minus
  Coriolis, over the time the bag is stowed on board. What remains is the sensor's own error
  (noise, offsets, gain, cross-axis, quantisation) and vibration.
- :func:`tilt_only_acceleration`: no truth at all, only the gravity direction seen during each of
  the detector's static periods. An accelerometer cannot see heading (seed 003 section 1): this
  gives the vertical kinematic acceleration and the magnitude of the horizontal one, valid only
  while the sensor keeps the attitude it had at the last static period. A 10 degree climb attitude
  leaks g (1 - cos 10 deg) = 0.15 m/s^2 into the vertical and g sin 10 deg = 1.7 m/s^2 into the
  horizontal: it cannot rebuild an airliner's path, and the module says so by returning only these
  two quantities.
"""

from __future__ import annotations

import numpy as np

from flightmode.nav.spline_path import NavError

OMEGA_E_RADPS = 7.292115e-5  # WGS84 Earth rotation rate
G0_MPS2 = 9.80665  # the g in which accelerometer samples are expressed


GM_M3PS2 = 3.986004418e14  # WGS84 gravitational parameter
J2 = 1.08262982e-3  # the Earth's second zonal harmonic (JSBSim's value)
A_M = 6378137.0  # WGS84 equatorial radius


def gravity_ned_mps2(lat_deg, lon_deg, alt_m) -> np.ndarray:
    """(n, 3) effective gravity in local north/east/down: the J2 gravitation plus the centrifugal
    term of the Earth's rotation, the model JSBSim's FGInertial uses (it matches the FDM's own
    specific force at rest to 1e-8 m/s^2, tests/nav). WGS84 *normal* gravity (Somigliana with the
    free-air gradient) differs from it by about 5e-5 m/s^2 (5 micro-g) here, which a double
    integration turns into ~600 m after 85 minutes: the gravity model matters at this level."""
    from flightmode.sim.flight.geodesy import geodetic_to_ecef

    e = geodetic_to_ecef(lat_deg, lon_deg, alt_m)
    x, y, z = e[..., 0], e[..., 1], e[..., 2]
    r = np.sqrt(x * x + y * y + z * z)
    s2 = (z / r) ** 2
    pc = 1.5 * J2 * (A_M / r) ** 2
    k = GM_M3PS2 / (r * r)
    g = -k[..., None] * np.stack([(1 + pc * (1 - 5 * s2)) * x / r, (1 + pc * (1 - 5 * s2)) * y / r,
                                  (1 + pc * (3 - 5 * s2)) * z / r], axis=-1)
    om = np.array([0.0, 0.0, OMEGA_E_RADPS])
    g = g - np.cross(om, np.cross(om, e))  # centrifugal
    return np.einsum("...ij,...j->...i", _ecef_to_ned(lat_deg, lon_deg), g)


def _ecef_to_ned(lat_deg, lon_deg) -> np.ndarray:
    """(..., 3, 3) rotation matrices taking ECEF vectors into local north/east/down."""
    la, lo = np.radians(lat_deg), np.radians(lon_deg)
    sl, cl, so, co = np.sin(la), np.cos(la), np.sin(lo), np.cos(lo)
    r = np.empty(np.shape(la) + (3, 3))
    r[..., 0, :] = np.stack([-sl * co, -sl * so, cl], axis=-1)
    r[..., 1, :] = np.stack([-so, co, np.zeros_like(so)], axis=-1)
    r[..., 2, :] = np.stack([-cl * co, -cl * so, -sl], axis=-1)
    return r


def world_from_local(track, lat_deg, lon_deg) -> np.ndarray:
    """(n, 3, 3): local NED at (lat, lon) -> the track's world frame (tangent NED at its origin)."""
    r0 = _ecef_to_ned(track.origin_lat_deg, track.origin_lon_deg)
    return np.einsum("ij,nkj->nik", r0, _ecef_to_ned(lat_deg, lon_deg))


class TruthPath:
    """The truth path of a point fixed in the aircraft (the CG, or a bag at a body-axis lever arm
    from it), in the world frame: one cubic interpolant of its 120 Hz positions, built once and
    asked for position, velocity and acceleration."""

    def __init__(self, track, lever_arm_body_m=None):
        from scipy.interpolate import CubicSpline

        pos = track.pos_ned_m
        if lever_arm_body_m is not None:
            r = np.asarray(lever_arm_body_m, float)
            pos = pos + np.einsum("nij,j->ni", _world_from_body(track, track.t_s), r)
        self.t0_s, self.t1_s = float(track.t_s[0]), float(track.t_s[-1])
        self.spline = CubicSpline(track.t_s, pos)

    def position(self, t_s) -> np.ndarray:
        return self.spline(np.asarray(t_s, float))

    def velocity(self, t_s) -> np.ndarray:
        return self.spline(np.asarray(t_s, float), 1)

    def acceleration(self, t_s, integrating: bool = True) -> np.ndarray:
        """Kinematic acceleration (m/s^2) at ``t_s`` (uniform). ``integrating``: the mean over each
        sample period [t - h/2, t + h/2] (the exact velocity change of the interpolant over h,
        divided by h), as a perfect integrating accelerometer; else point samples."""
        t = np.asarray(t_s, float)
        if t.shape[0] < 2:
            raise NavError("need at least two sample times")
        if not integrating:
            return self.spline(t, 2)
        h = float(np.median(np.diff(t)))
        lo = np.maximum(t - h / 2, self.t0_s)
        hi = np.minimum(t + h / 2, self.t1_s)
        return (self.spline(hi, 1) - self.spline(lo, 1)) / (hi - lo)[:, None]


def truth_position(track, t_s, lever_arm_body_m=None) -> np.ndarray:
    """The truth position (world frame, m) at ``t_s`` (one-off use of :class:`TruthPath`)."""
    return TruthPath(track, lever_arm_body_m).position(t_s)


def truth_world_acceleration(track, t_s, integrating: bool = True, lever_arm_body_m=None) -> np.ndarray:
    """Kinematic acceleration of the truth path (one-off use of :class:`TruthPath`)."""
    return TruthPath(track, lever_arm_body_m).acceleration(t_s, integrating)


def _world_from_body(track, t_s) -> np.ndarray:
    from scipy.spatial.transform import Rotation, Slerp

    t = np.clip(np.asarray(t_s, float), track.t_s[0], track.t_s[-1])
    att = Slerp(track.t_s, Rotation.from_quat(track.quat_wxyz, scalar_first=True))(t)  # body -> local NED
    lat = np.interp(t, track.t_s, track.lat_deg)
    lon = np.interp(t, track.t_s, track.lon_deg)
    return np.einsum("nij,njk->nik", world_from_local(track, lat, lon), att.as_matrix())


def truth_aided_acceleration(rec, track, t_s=None, acc_g=None, truth: TruthPath | None = None) -> np.ndarray:
    """World-frame kinematic acceleration (m/s^2) from a Recording's samples with the truth's help:
    sensor -> body by the bag's orientation in its stowed segment, body -> local NED -> world by the
    track, plus gravity (J2 and centrifugal), minus Coriolis (module docstring). Only for samples
    while the bag is on board and not carried (stowed, in the hold, or handled in its seat; raises
    otherwise). ``t_s``/``acc_g`` default to the whole Recording; ``truth`` (the bag's TruthPath,
    for the Coriolis term's velocity) is built if not given."""
    t = rec.t_s if t_s is None else np.asarray(t_s, float)
    a = rec.acc_g if acc_g is None else np.asarray(acc_g, float)
    seg_t0 = np.array([s.t0_s for s in rec.segments])
    si = np.searchsorted(seg_t0, t, side="right") - 1
    if np.any(si < 0) or not all(rec.segments[k].on_board and rec.segments[k].state != "carried"
                                 for k in np.unique(si)):
        raise NavError("truth-aided frames need samples while the bag is on board and not carried")
    if t[0] < track.t_s[0] or t[-1] > track.t_s[-1]:
        raise NavError("samples outside the FlightTrack's time span")
    f_body = np.empty_like(a)
    for k in np.unique(si):
        sel = si == k
        f_body[sel] = a[sel] @ rec.segments[k].orientation.T * G0_MPS2  # body <- sensor
    c_wb = _world_from_body(track, t)
    lat = np.interp(t, track.t_s, track.lat_deg)
    lon = np.interp(t, track.t_s, track.lon_deg)
    alt = np.interp(t, track.t_s, track.alt_m)
    g_w = np.einsum("nij,nj->ni", world_from_local(track, lat, lon), gravity_ned_mps2(lat, lon, alt))
    # Earth rate in world axes: ECEF z axis expressed in the origin's NED
    r0 = _ecef_to_ned(track.origin_lat_deg, track.origin_lon_deg)
    omega_w = r0 @ np.array([0.0, 0.0, OMEGA_E_RADPS])
    v_w = (truth or TruthPath(track)).velocity(t)
    return np.einsum("nij,nj->ni", c_wb, f_body) + g_w - 2.0 * np.cross(omega_w, v_w)


def static_periods(checks, window: int, n: int) -> np.ndarray:
    """Per-sample mask of the detector's final-static periods: every sample of each window whose
    check was final static (the detector's own view, no truth)."""
    ends = np.asarray(checks.index)[checks.final_static]
    edges = np.zeros(n + 1, np.int64)  # +1 where a window starts, -1 after it ends
    np.add.at(edges, np.maximum(ends - window + 1, 0), 1)
    np.add.at(edges, np.minimum(ends + 1, n), -1)
    return np.cumsum(edges)[:n] > 0


def tilt_only_acceleration(acc_g, static_mask) -> tuple[np.ndarray, np.ndarray]:
    """(vertical kinematic acceleration, down positive, m/s^2; horizontal magnitude, m/s^2) from the
    gravity direction of the most recent static period (module docstring). Before the first static
    period there is no estimate (NaN)."""
    a = np.asarray(acc_g, float)
    st = np.asarray(static_mask, bool)
    if not st.any():
        raise NavError("tilt-only frames need at least one static period (none was detected)")
    # the mean specific force over each static run; carried forward to the next run
    runs_start = np.flatnonzero(np.diff(np.concatenate([[0], st.astype(np.int8)])) == 1)
    runs_end = np.flatnonzero(np.diff(np.concatenate([st.astype(np.int8), [0]])) == -1) + 1
    up = np.full(a.shape, np.nan)  # unit vector of the specific force at rest: "up", sensor axes
    mag = np.full(a.shape[0], np.nan)
    for s, e in zip(runs_start, runs_end):
        m = a[s:e].mean(axis=0)
        nxt = runs_start[runs_start > s]
        stop = nxt[0] if nxt.size else a.shape[0]
        up[s:stop] = m / np.linalg.norm(m)
        mag[s:stop] = np.linalg.norm(m)
    f_up = np.einsum("ni,ni->n", a, up)
    vertical_down = (f_up - mag) * -G0_MPS2  # a_down = -(f.up - |g|)
    horizontal = np.linalg.norm(a - f_up[:, None] * up, axis=1) * G0_MPS2
    return vertical_down, horizontal
