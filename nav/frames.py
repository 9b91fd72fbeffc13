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

from flightmode.errors import NavError
from flightmode.intervals import true_runs_array
from flightmode.sim.flight.geodesy import ecef_to_ned_matrix, geodetic_to_ecef, ned_to_ecef
from flightmode.units import G0_MPS2  # the g in which accelerometer samples are expressed

OMEGA_E_RADPS = 7.292115e-5  # WGS84 Earth rotation rate

GM_M3PS2 = 3.986004418e14  # WGS84 gravitational parameter
J2 = 1.08262982e-3  # the Earth's second zonal harmonic (JSBSim's value)
A_M = 6378137.0  # WGS84 equatorial radius


def gravity_ecef_mps2(lat_deg, lon_deg, alt_m) -> np.ndarray:
    """(n, 3) effective gravity in ECEF: the J2 gravitation plus the centrifugal term of the Earth's
    rotation, the model JSBSim's FGInertial uses (it matches the FDM's own specific force at rest to
    1e-6 m/s^2 vertically, tests/nav). WGS84 *normal* gravity (Somigliana with the free-air
    gradient) differs from it by about 5e-5 m/s^2 (5 micro-g) here, which a double integration turns
    into ~600 m after 85 minutes: the gravity model matters at this level."""
    e = geodetic_to_ecef(lat_deg, lon_deg, alt_m)
    x, y, z = e[..., 0], e[..., 1], e[..., 2]
    r2 = x * x + y * y + z * z
    r = np.sqrt(r2)
    s2 = z * z / r2
    pc = 1.5 * J2 * (A_M * A_M / r2)
    k = -GM_M3PS2 / (r2 * r)
    w2 = OMEGA_E_RADPS**2  # centrifugal: + w^2 (x, y, 0)
    fxy = k * (1 + pc * (1 - 5 * s2)) + w2
    return np.stack([fxy * x, fxy * y, k * (1 + pc * (3 - 5 * s2)) * z], axis=-1)


def gravity_ned_mps2(lat_deg, lon_deg, alt_m) -> np.ndarray:
    """:func:`gravity_ecef_mps2` in local north/east/down."""
    return np.einsum(
        "...ij,...j->...i", ecef_to_ned_matrix(lat_deg, lon_deg), gravity_ecef_mps2(lat_deg, lon_deg, alt_m)
    )


def _world_rotation(track) -> np.ndarray:
    """ECEF -> the track's world frame (the tangent NED at its origin)."""
    return ecef_to_ned_matrix(track.origin_lat_deg, track.origin_lon_deg)


def attitude_at(track, t_s):
    """The body -> local NED attitude at times ``t_s`` (a scipy Rotation): the track's quaternions
    interpolated linearly and renormalised (nlerp). Between two FDM steps (1/120 s) an airliner turns
    by at most a few milliradians, where nlerp and slerp differ by under 1e-9 rad."""
    from scipy.spatial.transform import Rotation

    t = np.clip(np.asarray(t_s, float), track.t_s[0], track.t_s[-1])
    pos = (t - track.t_s[0]) * track.fs_hz
    i0 = np.clip(pos.astype(np.int64), 0, track.n - 2)
    w = (pos - i0)[:, None]
    q0, q1 = track.quat_wxyz[i0], track.quat_wxyz[i0 + 1]
    q1 = np.where(np.sum(q0 * q1, axis=1)[:, None] < 0.0, -q1, q1)  # the shorter way round
    return Rotation.from_quat(q0 + w * (q1 - q0), scalar_first=True)


def body_to_world(track, t_s, v_body) -> np.ndarray:
    """Body-axis vectors (n, 3) (or one (3,)) at times ``t_s`` (None: at the track's own samples, no
    interpolation), in the track's world frame: body -> local NED by the attitude, local NED -> ECEF
    at the track's position, ECEF -> world."""
    if t_s is None:
        from scipy.spatial.transform import Rotation

        att, lat, lon = Rotation.from_quat(track.quat_wxyz, scalar_first=True), track.lat_deg, track.lon_deg
    else:
        t = np.asarray(t_s, float)
        att = attitude_at(track, t)
        lat = np.interp(t, track.t_s, track.lat_deg)
        lon = np.interp(t, track.t_s, track.lon_deg)
    return ned_to_ecef(lat, lon, att.apply(v_body)) @ _world_rotation(track).T


class TruthPath:
    """The truth path of a point fixed in the aircraft (the CG, or a bag at a body-axis lever arm
    from it), in the world frame: one cubic interpolant of its 120 Hz positions, built once and
    asked for position, velocity and acceleration."""

    def __init__(self, track, lever_arm_body_m=None):
        from scipy.interpolate import make_interp_spline

        pos = track.pos_ned_m
        if lever_arm_body_m is not None:
            pos = pos + body_to_world(track, None, np.asarray(lever_arm_body_m, float))
        self.t0_s, self.t1_s = float(track.t_s[0]), float(track.t_s[-1])
        # the not-a-knot cubic interpolant (scipy's CubicSpline's), as a B-spline: built five times
        # faster on a whole flight's 120 Hz samples (0.14 s against 0.73 s for 666,000; the two agree
        # to 1e-10 of the values, the solvers' rounding)
        self.spline = make_interp_spline(track.t_s, pos, k=3)

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
    if np.any(si < 0) or not all(
        rec.segments[k].on_board and rec.segments[k].state != "carried" for k in np.unique(si)
    ):
        raise NavError("truth-aided frames need samples while the bag is on board and not carried")
    if t[0] < track.t_s[0] or t[-1] > track.t_s[-1]:
        raise NavError("samples outside the FlightTrack's time span")
    f_body = np.empty_like(a)
    for k in np.unique(si):
        sel = si == k
        f_body[sel] = a[sel] @ rec.segments[k].orientation.T * G0_MPS2  # body <- sensor
    lat = np.interp(t, track.t_s, track.lat_deg)
    lon = np.interp(t, track.t_s, track.lon_deg)
    alt = np.interp(t, track.t_s, track.alt_m)
    # specific force body -> local NED -> ECEF, plus gravity (in ECEF), then ECEF -> world once
    f_ecef = ned_to_ecef(lat, lon, attitude_at(track, t).apply(f_body))
    r0 = _world_rotation(track)
    omega_w = r0 @ np.array([0.0, 0.0, OMEGA_E_RADPS])  # Earth rate: the ECEF z axis in world axes
    v_w = (truth or TruthPath(track)).velocity(t)
    return (f_ecef + gravity_ecef_mps2(lat, lon, alt)) @ r0.T - 2.0 * np.cross(omega_w, v_w)


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
    runs = true_runs_array(st)
    runs_start, runs_end = runs[:, 0], runs[:, 1]
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
