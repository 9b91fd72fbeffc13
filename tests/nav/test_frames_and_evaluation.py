"""Frames (gravity, truth-aided rotation), the random-walk law, ZUPT, and the flights (slow)."""

from __future__ import annotations

import numpy as np
import pytest

from flightmode.nav import frames
from flightmode.nav.evaluation import predicted_random_walk_m, random_walk_exponent, zupt_path
from flightmode.nav.spline_path import NavError, recurrence_path, tridiagonal_path

SIG_MPS2 = 2.23e-3 * 9.80665  # the LIS302DL noise (seed 000 Table 1) in m/s^2


def test_gravity_model_is_the_fdms_own_at_rest(fly_cached):
    """At the gate the aircraft is at rest in the Earth frame, so its specific force rotated to NED
    plus gravity must vanish: with the J2 + centrifugal model (JSBSim's FGInertial model) to
    2e-5 m/s^2, the size of a 1e-6 rad attitude resolution times g (the vertical, insensitive to
    attitude to first order, agrees to 1e-6 m/s^2), while WGS84 normal gravity misses the vertical by
    ~5e-5 m/s^2 (frames.gravity_ned_mps2's docstring)."""
    from scipy.spatial.transform import Rotation

    _, tr = fly_cached("pattern")
    i = np.arange(100, 1000, 50)
    c = Rotation.from_quat(tr.quat_wxyz[i], scalar_first=True).as_matrix()
    f_ned = np.einsum("nij,nj->ni", c, tr.specific_force_body_mps2[i])
    g = frames.gravity_ned_mps2(tr.lat_deg[i], tr.lon_deg[i], tr.alt_m[i])
    assert np.abs(f_ned + g).max() < 2e-5
    assert np.abs(f_ned + g)[:, 2].max() < 1e-6
    assert 9.78 < np.linalg.norm(g, axis=1).min() and np.linalg.norm(g, axis=1).max() < 9.83


def test_random_walk_law_exponent_and_size():
    """White acceleration noise integrated twice: sigma_x = sigma_a sqrt(dt) t^1.5 / sqrt(3). 200
    Monte Carlo runs estimate an RMS to ~5 % (1/sqrt(2 x 200)); the fitted exponent over 1-600 s is
    1.5 within 0.05."""
    p, t, rms = random_walk_exponent(SIG_MPS2, 100.0, 600.0, 200, np.random.default_rng(0))
    assert p == pytest.approx(1.5, abs=0.05)
    np.testing.assert_allclose(rms[-5:], predicted_random_walk_m(SIG_MPS2, 100.0, t[-5:]), rtol=0.15)


def test_zupt_bounds_the_error_and_end_points_pin_it():
    """A bag moved for 20 s, then set down for 10 s, six times (3 min): with LIS302DL noise and a
    20 mg bias, the plain recurrence drifts quadratically (0.5 b t^2 = 3.2 km at 180 s), while the
    recurrence restarted at zero velocity at each rest only accumulates within one 20-s move
    (0.5 b 20^2 = 39 m per move, about 240 m over six): ZUPT bounds the velocity error."""
    fs = 100.0
    n = int(180 * fs)
    t = np.arange(n) / fs
    rng = np.random.default_rng(1)
    static = (t % 30.0) >= 20.0
    true_acc = np.where(static, 0.0, np.sin(2 * np.pi * t / 20.0))  # returns to rest at each stop
    bias = 0.020 * 9.80665
    meas = true_acc + bias + rng.normal(0, SIG_MPS2, n)
    truth = recurrence_path(t, true_acc, 0.0, 0.0)(t)
    plain = recurrence_path(t, meas, 0.0, 0.0)(t) - truth
    zupt = zupt_path(t, meas[:, None], np.zeros(1), static)[:, 0] - truth
    assert abs(plain[-1]) > 3000.0
    assert np.abs(zupt).max() < 300.0
    # the tridiagonal method with both end positions known pins both ends: error b T^2 / 8 at most
    tri = tridiagonal_path(t, meas, truth[0], truth[-1])(t) - truth
    assert abs(tri[-1]) < 1e-6 and np.abs(tri).max() < bias * 180.0**2 / 8 * 1.05


def test_tilt_only_sees_the_vertical_only_and_needs_a_static_period():
    rng = np.random.default_rng(2)
    n = 1000
    tilt = np.array([0.3, -0.2, -np.sqrt(1 - 0.13)])  # the gravity direction in tilted sensor axes
    acc = np.tile(-tilt, (n, 1)) + rng.normal(0, 1e-4, (n, 3))  # at rest: f = -g
    static = np.zeros(n, bool)
    static[:200] = True
    acc[500:] += 0.1 * tilt  # 0.1 g downward acceleration: specific force falls along "up"
    vert, hor = frames.tilt_only_acceleration(acc, static)
    assert np.abs(vert[:500]).max() < 0.01 and np.abs(hor[:500]).max() < 0.01
    assert vert[500:].mean() == pytest.approx(0.1 * 9.80665, rel=0.01)
    with pytest.raises(NavError, match="at least one static period"):
        frames.tilt_only_acceleration(acc, np.zeros(n, bool))


@pytest.mark.slow
def test_default_flight_ideal_world_acceleration_within_a_metre(fly_cached):
    """Issue acceptance: the default flight, ideal world-frame acceleration at 100 Hz (integrating
    samples), tridiagonal with the gate-to-gate positions: within 1 m of the truth everywhere. The
    recurrence from the gate at rest is reported; point samples are shown to alias the FDM's ground
    impulses into tens of metres."""
    _, tr = fly_cached("gva-lhr-a320")
    t = np.arange(tr.t_s[0], tr.t_s[-1], 0.01)
    truth = frames.truth_position(tr, t)
    a = frames.truth_world_acceleration(tr, t)
    tri = np.linalg.norm(tridiagonal_path(t, a, truth[0], truth[-1])(t) - truth, axis=1)
    rec = np.linalg.norm(recurrence_path(t, a, truth[0], np.zeros(3))(t) - truth, axis=1)
    pt = frames.truth_world_acceleration(tr, t, integrating=False)
    tri_pt = np.linalg.norm(tridiagonal_path(t, pt, truth[0], truth[-1])(t) - truth, axis=1)
    print(
        f"\ndefault flight, {t.shape[0]:,} samples: tridiagonal max {tri.max():.4f} m; recurrence max "
        f"{rec.max():.4f} m, final {rec[-1]:.4f} m; point samples tridiagonal max {tri_pt.max():.1f} m"
    )
    assert tri.max() < 1.0
    assert rec.max() < 1.0
    assert tri_pt.max() > 5.0  # aliasing of the touchdown and gear impulses is real, not noise


@pytest.mark.slow
def test_default_flight_sensor_noise_grows_as_the_random_walk(fly_cached):
    """The same flight sensed twice with a perfect unit (no offsets): the ideal part and the LIS302DL
    logger. Their difference isolates noise and quantisation; its recurrence path error grows as
    t^p with p near 1.5 (one realisation over 80 minutes: +-0.35) and never far above the law."""
    from flightmode.nav.evaluation import span
    from flightmode.sim.sensor.accelerometer import UnitDraw, get_preset
    from flightmode.sim.sensor.carrier import CarrierSpec
    from flightmode.sim.sensor.sensing import sense

    _, tr = fly_cached("gva-lhr-a320")
    recs = [
        sense(tr, CarrierSpec(), get_preset(p), np.random.default_rng(1), unit=UnitDraw())
        for p in ("ideal", "lis302dl-logged16")
    ]
    t0, t1 = span(recs[0], tr)
    s = (recs[0].t_s >= t0) & (recs[0].t_s <= t1)
    t = recs[0].t_s[s] - t0
    d = (recs[1].acc_g[s] - recs[0].acc_g[s]) * 9.80665
    e = np.linalg.norm(recurrence_path(t, d, np.zeros(3), np.zeros(3))(t), axis=1)
    k = np.unique(np.geomspace(10 * 100, t.shape[0] - 1, 40).astype(int))
    p = np.polyfit(np.log(t[k]), np.log(e[k] + 1e-9), 1)[0]
    # the noise's 0 Hz density sets the walk: white, so the 2.23 mg itself
    from flightmode.sim.sensor.accelerometer import noise_random_walk_sigma_g

    sig_rw = noise_random_walk_sigma_g(get_preset("lis302dl-logged16")) * 9.80665
    law = predicted_random_walk_m(sig_rw, 100.0, t[-1]) * np.sqrt(3)  # 3 axes
    print(
        f"\nnoise-only path error after {t[-1] / 60:.0f} min: {e[-1]:.0f} m (law, 1 sigma: {law:.0f} m); "
        f"fitted exponent {p:.2f}"
    )
    assert 1.15 < p < 1.85
    assert e[-1] < 4 * law
