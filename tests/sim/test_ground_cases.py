"""The ground cases' motions (sim/sensor/passenger.py, sim/sensor/tug.py): each model's statistics
match its drawn parameters, the same seed gives the same numbers, and they act only where they
should (the lap's on a lap, the tug's in the push)."""

from __future__ import annotations

import numpy as np
import pytest

from flightmode.sim.sensor import passenger as pax
from flightmode.sim.sensor import tug
from flightmode.uncertain import value_of

FS_HZ = 800.0  # the sensing stage's internal rate (sim.sensor.sensing.FS_INTERNAL_HZ)


def test_bump_leaves_no_net_velocity_or_displacement_and_peaks_mid_pulse():
    u = (np.arange(100_000) + 0.5) / 100_000
    a = pax.bump_accel(u)
    du = 1.0 / u.shape[0]
    v = np.cumsum(a) * du
    # midpoint sums of smooth periodic integrands are exact to rounding (1e-9 of the 4 pi^2 scale)
    assert abs(v[-1]) < 1e-9 * pax.BUMP_PEAK
    assert abs(np.sum(v) * du) < 1e-9 * pax.BUMP_PEAK
    assert pax.bump_accel(np.array([0.5]))[0] == pytest.approx(-pax.BUMP_PEAK, rel=1e-12)
    assert pax.bump_accel(np.array([-0.1, 0.0, 1.0, 1.1])) == pytest.approx(0.0, abs=1e-12)


def test_breathing_spectral_peak_at_the_drawn_rate_within_one_bin():
    # the low end of the breathing's wander (2 %): its phase modulation index stays below 0.6, so
    # the carrier (J0 > 0.9) dominates the spectrum and sits at the drawn rate; over 1200 s a bin is
    # 1/1200 Hz
    d = pax.draw_lap(0.0, 1200.0, np.random.default_rng(3), {"passenger.breath_variability": 0.02})
    fs = 20.0
    t = np.arange(int(1200.0 * fs)) / fs
    a = pax.breathing_accel_mps2(t, d)
    x = d.breath_dir @ a  # along the breathing's direction
    spec = np.abs(np.fft.rfft(x * np.hanning(x.shape[0])))
    f = np.fft.rfftfreq(x.shape[0], 1.0 / fs)
    assert abs(f[np.argmax(spec)] - d.breath_rate_hz) <= 1.0 / 1200.0
    # its size: the displacement amplitude times (2 pi f)^2 to within the wander's +-2 % in rate
    # (squared: +-4 %, plus the modulation's own second derivative: 10 % in all)
    peak = d.breath_amplitude_m * (2 * np.pi * d.breath_rate_hz) ** 2
    assert np.sqrt(2.0) * x.std() == pytest.approx(peak, rel=0.1)


def test_breathing_rate_and_amplitude_lie_within_the_spread_of_their_medians():
    k = value_of(pax.FLIGHT_SPREAD)
    for seed in range(50):
        d = pax.draw_lap(0.0, 10.0, np.random.default_rng(seed))
        assert value_of(pax.BREATH_RATE_HZ) / k <= d.breath_rate_hz <= value_of(pax.BREATH_RATE_HZ) * k
        assert (
            value_of(pax.BREATH_AMPLITUDE_M) / k
            <= d.breath_amplitude_m
            <= value_of(pax.BREATH_AMPLITUDE_M) * k
        )
        assert np.linalg.norm(d.breath_dir) == pytest.approx(1.0)
        assert d.breath_dir[1] == 0.0 and d.breath_dir[0] >= 0.0 and d.breath_dir[2] <= 0.0


def test_posture_shift_count_within_three_poisson_sigma_of_rate_times_time():
    span = 10 * 3600.0
    for seed in range(5):
        d = pax.draw_lap(0.0, span, np.random.default_rng(seed))
        mu = d.shift_rate_per_s * span
        assert abs(d.shift_t_s.shape[0] - mu) <= 3.0 * np.sqrt(mu), seed
        assert np.all((d.shift_t_s >= 0.0) & (d.shift_t_s <= span))


def test_each_posture_shift_peaks_at_its_drawn_size_over_its_duration_squared():
    d = pax.draw_lap(0.0, 600.0, np.random.default_rng(5), {"passenger.shift_rate_per_min": 3.0})
    assert d.shift_t_s.shape[0] > 10
    t = np.arange(int(600.0 * FS_HZ)) / FS_HZ
    a = pax.shifts_accel_mps2(t, d)
    for t0, dur, disp, u in zip(d.shift_t_s, d.shift_duration_s, d.shift_displacement_m, d.shift_dir):
        sel = (t >= t0) & (t <= t0 + dur)
        # overlapping shifts add: check the isolated ones
        others = np.abs(d.shift_t_s - t0) < d.shift_duration_s.max() + dur
        if others.sum() > 1:
            continue
        peak = pax.BUMP_PEAK * disp / dur**2
        # on the 800 Hz grid the sampled peak is within 5 pi^2 (dt / 2T)^2 of the true one (the
        # pulse's curvature at its peak, relative: d''(0.5 + e) = -4 pi^2 (1 - 5 pi^2 e^2 + ...))
        tol = 5 * np.pi**2 * (0.5 / FS_HZ / dur) ** 2
        along = u @ a[:, sel]
        assert np.min(along) == pytest.approx(-peak, rel=tol)
        # the pulse acts along its direction only
        np.testing.assert_allclose(a[:, sel], np.outer(u, along), atol=1e-12)


def test_lap_motion_is_deterministic_and_seamless_across_chunks():
    d1 = pax.draw_lap(0.0, 3600.0, np.random.default_rng(11))
    d2 = pax.draw_lap(0.0, 3600.0, np.random.default_rng(11))
    t = np.arange(int(120.0 * FS_HZ)) / FS_HZ + 1000.0
    whole = pax.lap_accel_mps2(t, d1)
    assert np.array_equal(whole, pax.lap_accel_mps2(t, d2))
    # a closed form of t: any chunking gives the same samples, bit for bit
    parts = np.hstack([pax.lap_accel_mps2(t[i : i + 7001], d1) for i in range(0, t.shape[0], 7001)])
    assert np.array_equal(whole, parts)
    other = pax.draw_lap(0.0, 3600.0, np.random.default_rng(12))
    assert not np.array_equal(whole, pax.lap_accel_mps2(t, other))


def _push(seed: int, overrides=None):
    return tug.draw_tug((100.0, 190.0), np.random.default_rng(seed), overrides)


def test_tug_start_and_stop_peak_at_their_drawn_values_rearward_then_forward():
    t = 90.0 + np.arange(int(110.0 * FS_HZ)) / FS_HZ
    for seed in range(10):
        d = _push(seed)
        a = tug.tug_accel_mps2(t, d)
        assert a is not None and not a[1:].any()  # along the fuselage only
        for i in (0, -1):
            t0, dur, pk = d.t_s[i], d.duration_s[i], d.peak_mps2[i]
            sel = (t >= t0) & (t <= t0 + dur)
            # the start or stop alone in its stretch? (a slack pulse may overlap it)
            if np.sum((d.t_s < t0 + dur) & (d.t_s + d.duration_s > t0)) > 1:
                continue
            tol = 5 * np.pi**2 * (0.5 / FS_HZ / dur) ** 2  # as for the shifts: the grid's peak error
            extreme = a[0, sel][np.argmax(np.abs(a[0, sel]))]
            assert extreme == pytest.approx(pk, rel=tol)
        assert d.peak_mps2[0] < 0.0 < d.peak_mps2[-1]
        assert d.t_s[0] == 100.0 and d.t_s[-1] + d.duration_s[-1] == pytest.approx(190.0)


def test_tug_jolts_leave_no_velocity_and_act_only_in_the_push():
    dt = 1.0 / FS_HZ
    t = 50.0 + np.arange(int(200.0 * FS_HZ)) * dt
    d = _push(2)
    a = tug.tug_accel_mps2(t, d)
    assert a is not None
    outside = (t < 100.0) | (t > 190.0 + dt)
    assert not a[:, outside].any()
    # each pulse's velocity change sums to zero: on the grid to within one sample's worth of the
    # largest pulse (the pulse edges fall between samples)
    assert abs(a[0].sum() * dt) <= np.abs(d.peak_mps2).max() * dt
    assert tug.tug_accel_mps2(np.arange(0.0, 90.0, dt), d) is None


def test_tug_slack_count_within_three_poisson_sigma_and_determinism():
    span = 10 * 3600.0
    for seed in range(5):
        d = tug.draw_tug((0.0, span), np.random.default_rng(seed))
        mu = d.slack_rate_per_s * (span - 2 * d.duration_s[0])
        assert abs(d.t_s.shape[0] - 2 - mu) <= 3.0 * np.sqrt(mu), seed
    a, b = _push(7), _push(7)
    for name in ("t_s", "peak_mps2", "duration_s"):
        assert np.array_equal(getattr(a, name), getattr(b, name))


def test_push_span_from_the_track_phase_and_speed():
    from flightmode.labels import PHASE_CODE

    t = np.arange(0.0, 100.0, 0.5)
    ph = np.full(t.shape, PHASE_CODE["gate"])
    ph[(t >= 20.0) & (t < 80.0)] = PHASE_CODE["pushback"]
    gs = np.where((t >= 25.0) & (t < 70.0), 1.0, 0.02)
    assert tug.push_span(t, ph, gs) == (20.0, 69.5)
    assert tug.push_span(t, np.full(t.shape, PHASE_CODE["gate"]), gs) is None


def test_overrides_outside_the_declared_range_are_refused():
    from flightmode.errors import ScenarioError

    with pytest.raises(ScenarioError, match="pushback.start_peak_mps2"):
        _push(1, {"pushback.start_peak_mps2": 5.0})
    with pytest.raises(ScenarioError, match="passenger.shift_rate_per_min"):
        pax.draw_lap(0.0, 10.0, np.random.default_rng(1), {"passenger.shift_rate_per_min": 0.0})


@pytest.fixture(scope="module")
def pattern_track(fly_cached):
    return fly_cached("pattern")[1]


def _sense(track, placement, monkeypatch=None):
    from flightmode.sim.sensor.accelerometer import UnitDraw, get_preset
    from flightmode.sim.sensor.carrier import CarrierSpec
    from flightmode.sim.sensor.sensing import sense

    spec = CarrierSpec(placement=placement, handled_in_cruise=0)
    return sense(track, spec, get_preset("lis302dl-logged16"), 4, unit=UnitDraw())


def test_sensing_adds_the_jolts_only_in_the_push_and_the_passenger_only_on_a_lap(pattern_track, monkeypatch):
    tr = pattern_track
    with_cases = {p: _sense(tr, p) for p in ("under_seat", "lap")}
    monkeypatch.setattr(tug, "tug_accel_mps2", lambda t, d: None)
    monkeypatch.setattr(pax, "lap_accel_mps2", lambda t, d: np.zeros((3, np.asarray(t).shape[0])))
    without = {p: _sense(tr, p) for p in ("under_seat", "lap")}
    span = tug.push_span(tr.t_s, tr.phase_code, tr.ground_speed_mps)
    assert span is not None
    # every other draw is untouched (the cases draw from their own streams): outside the push the
    # under-seat bag's samples are the same bit for bit; after it, once the mounts' ringing has
    # decayed below a double's rounding (zeta omega >= 0.1 x 2 pi x 3 Hz: e^-1.9t < 1e-17 after 20 s;
    # 60 s kept)
    a, b = with_cases["under_seat"], without["under_seat"]
    assert np.array_equal(a.t_s, b.t_s)
    t = a.t_s
    out = (t < span[0]) | (t > span[1] + 60.0)
    assert np.array_equal(a.acc_g[out], b.acc_g[out])
    inside = (t >= span[0]) & (t <= span[1])
    assert not np.array_equal(a.acc_g[inside], b.acc_g[inside])
    assert a.stowage["ground"]["tug"]["slack_pulses"] >= 0 and "lap" not in a.stowage["ground"]
    # the lap: the passenger acts wherever the bag lies on the lap, and nowhere else (off board the
    # bag is in the terminal: the same samples)
    a, b = with_cases["lap"], without["lap"]
    on_lap = np.zeros(t.shape, bool)
    for seg in a.segments:
        if seg.on_board and seg.placement == "lap" and seg.state == "stowed":
            on_lap |= (t >= seg.t0_s) & (t < seg.t1_s)
    # (from 1 s after the bag leaves the aircraft: the accelerometer's own filter carries the last
    # on-board samples over for a few of its periods, 0.2 s at the 100 Hz part's anti-alias filter)
    off_board = np.zeros(t.shape, bool)
    for seg in a.segments:
        if not seg.on_board:
            off_board |= (t >= seg.t0_s + 1.0) & (t < seg.t1_s)
    assert np.array_equal(a.acc_g[off_board], b.acc_g[off_board])
    assert not np.array_equal(a.acc_g[on_lap & ~inside], b.acc_g[on_lap & ~inside])
    assert "lap" in a.stowage["ground"]
    # the same seed: the same recording, bit for bit
    monkeypatch.undo()
    again = _sense(tr, "lap")
    assert np.array_equal(again.acc_g, with_cases["lap"].acc_g)


def test_the_pushback_speed_profile_is_declared_and_overridden_only_when_named():
    from flightmode.errors import ScenarioError
    from flightmode.sim.flight.aircraft.registry import get_profile
    from flightmode.sim.flight.pilot import ground

    tu = get_profile("A320").tuning
    # the declared nominal values are the profiles' own: a flight without overrides is unchanged
    assert ground.PUSHBACK_SPEED_MPS.value == tu.pushback_mps
    assert ground.PUSHBACK_RAMP_MPS2.value == tu.pushback_decel_mps2
    assert ground.pushback_tuning(tu) is tu
    assert ground.pushback_tuning(tu, {"mount.seat.fn_v_scale": 2.0}) is tu
    slow = ground.pushback_tuning(tu, {"pushback.speed_mps": 0.6})
    assert (slow.pushback_mps, slow.pushback_decel_mps2) == (0.6, tu.pushback_decel_mps2)
    with pytest.raises(ScenarioError, match="pushback.ramp_mps2"):
        ground.pushback_tuning(tu, {"pushback.ramp_mps2": 2.0})


def test_an_overridden_pushback_speed_reaches_the_flight(fly_cached):
    # the first 15 minutes of the pattern flight hold its gate wait, engine start and pushback;
    # the push's top speed is the tug's speed to its PI loop's settling, 5 %
    from flightmode.labels import PHASE_CODE

    for speed in (0.6, None):
        changes = {} if speed is None else {"model": {"pushback.speed_mps": speed}}
        _, tr = fly_cached("pattern", stop_after_s=900.0, **changes)
        push = tr.phase_code == PHASE_CODE["pushback"]
        assert push.any()
        top = float(tr.ground_speed_mps[push].max())
        assert top == pytest.approx(1.2 if speed is None else speed, rel=0.05)
