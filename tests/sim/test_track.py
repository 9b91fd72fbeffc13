"""FlightTrack helpers: lever-arm specific force and attitude quaternions."""

import numpy as np
from scipy.spatial.transform import Rotation

from flightmode.sim.flight.track import euler_to_quat_wxyz


def _track_like(f, w, wdot):
    from flightmode.sim.flight.track import FlightTrack

    n = f.shape[0]
    z = np.zeros(n)
    z3 = np.zeros((n, 3))
    return FlightTrack(
        aircraft="x",
        fs_hz=1.0,
        origin_lat_deg=0.0,
        origin_lon_deg=0.0,
        origin_alt_m=0.0,
        t_s=np.arange(n, dtype=float),
        lat_deg=z,
        lon_deg=z,
        alt_m=z,
        agl_m=z,
        pos_ned_m=z3,
        vel_ned_mps=z3,
        euler_rad=z3,
        quat_wxyz=np.tile([1.0, 0, 0, 0], (n, 1)),
        rates_radps=w,
        ang_acc_radps2=wdot,
        specific_force_body_mps2=f,
        n1_pct=z[:, None],
        n2_pct=z[:, None],
        thrust_n=z[:, None],
        wow=z.astype(bool),
        flap_norm=z,
        gear_norm=z,
        speedbrake_norm=z,
        ias_mps=z,
        tas_mps=z,
        mach=z,
        alpha_rad=z,
        ground_speed_mps=z,
        vertical_speed_mps=z,
        phase_code=z.astype(np.uint8),
        in_flight_window=z.astype(bool),
        airborne=z.astype(bool),
        turbulence_code=z.astype(np.uint8),
        events=(),
    )


def test_specific_force_at_lever_arm_is_rigid_body_kinematics():
    # steady yaw at 0.1 rad/s: a point 10 m ahead of the CG feels the centripetal -w^2 r = -0.1 m/s^2
    # along x; an angular acceleration of 0.2 rad/s^2 about z adds wdot x r = +2 m/s^2 along y
    n = 4
    f = np.tile([0.0, 0.0, -9.81], (n, 1))
    w = np.tile([0.0, 0.0, 0.1], (n, 1))
    wdot = np.tile([0.0, 0.0, 0.2], (n, 1))
    tr = _track_like(f, w, wdot)
    fp = tr.specific_force_at([10.0, 0.0, 0.0])
    np.testing.assert_allclose(fp, np.tile([-0.1, 2.0, -9.81], (n, 1)), atol=1e-12)
    np.testing.assert_allclose(tr.specific_force_at([0.0, 0.0, 0.0]), f, atol=0)


def test_euler_quaternion_matches_scipy():
    rng = np.random.default_rng(3)
    eul = rng.uniform([-1, -1.2, -3], [1, 1.2, 3], size=(50, 3))
    q = euler_to_quat_wxyz(eul)
    ref = Rotation.from_euler("ZYX", eul[:, ::-1]).as_quat()  # xyzw, body->NED
    ref_wxyz = ref[:, [3, 0, 1, 2]]
    sign = np.sign(np.sum(q * ref_wxyz, axis=1))[:, None]
    np.testing.assert_allclose(q, ref_wxyz * sign, atol=1e-12)


def test_named_bag_locations_exist_for_every_profile():
    from flightmode.sim.flight.aircraft.registry import PROFILES

    for prof in PROFILES.values():
        loc = prof.locations_m
        assert {"cabin_seat_mid", "overhead_bin_mid", "forward_hold", "aft_hold"} <= set(loc)
        # holds are below the cabin floor (z down), bins above the seats, all inside the fuselage
        assert loc["forward_hold"][2] > loc["cabin_seat_mid"][2] > loc["overhead_bin_mid"][2]
        assert all(abs(v[0]) < prof.length_m / 2 for v in loc.values())
