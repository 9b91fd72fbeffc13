"""A simulated flight as an e-obs tag records it: its bursts written as a Movebank file read back
identically, and the duty-cycled detector on them (the battery trade-off on a real flight)."""

from __future__ import annotations

import numpy as np
import pytest


@pytest.fixture(scope="module")
def pattern(fly_cached):
    return fly_cached("pattern")


def test_a_simulated_flights_bursts_round_trip_through_a_movebank_file(pattern, tmp_path):
    from flightmode.eobs.flight import recording_bursts
    from flightmode.eobs.movebank import bursts_to_file, read_movebank, write_movebank
    from flightmode.runs import pipeline
    from flightmode.sim.sensor.accelerometer import eobs_burst, eobs_preset

    sc, track = pattern
    preset = eobs_preset(60.0, 1188, 10.0)  # ACC interval 60 s, the largest burst of newer firmware
    rec = pipeline.sense(track, sc.carrier, preset, pipeline.streams_of(sc.seed).child("sensor"))
    bursts = recording_bursts(rec, tag_id="4321")
    # seed 003 section 9: 1188 bytes, 3 axes -> 19 blocks of 63 (54 in the first) -> 1,188 data bytes
    # -> 792 samples -> 264 per axis; a burst every 60 s over the whole track
    n = eobs_burst(1188, 3)[0]
    assert n == 264
    # one burst every 60 s from the first sample (the bag's day: the terminal before, the arrival after)
    starts = np.array([b.start_time for b in bursts])
    assert np.all(np.diff(starts) == np.timedelta64(60, "s"))
    assert 0 <= rec.t_s[-1] - rec.t_s[0] - 60.0 * (len(bursts) - 1) < 60.0
    assert all(b.raw.shape == (n, 3) for b in bursts[:-1]) and all(b.axes == "XYZ" for b in bursts)
    assert all(0 <= b.raw.min() and b.raw.max() <= 4095 for b in bursts)  # the tag's 12-bit counts
    path = write_movebank(bursts_to_file(bursts), tmp_path / "flight.csv")
    back = [r.burst for r in read_movebank(path).rows if r.burst is not None]
    assert back == bursts  # every field: tag, start to the nanosecond, axes, rate, every count


def test_the_duty_cycled_detector_on_a_flight_trades_samples_for_response(pattern):
    from flightmode.eobs.flight import tradeoff_on_track

    sc, track = pattern
    rows = tradeoff_on_track(track, sc, (30.0, 120.0), 216, (1, 2))
    by = {(r.burst_interval_s, r.m): r for r in rows}
    for interval in (30.0, 120.0):
        one, two = by[(interval, 1)], by[(interval, 2)]
        # 216 bytes -> 4 blocks -> 243 data bytes -> 162 samples -> 54 per axis, every interval
        assert one.burst_samples == 54 and one.samples_per_hour == pytest.approx(54 * 3600 / interval)
        # eq. 8 with bursts: a burst final static at m = 2 is final static at m = 1, so waiting for a
        # second quiet burst never answers sooner and never adds a false static
        assert two.false_statics <= one.false_statics or one.false_statics == 0
        if two.response_s is not None:
            assert one.response_s is not None and two.response_s >= one.response_s
    # four times fewer samples
    assert by[(120.0, 1)].samples_per_hour == pytest.approx(by[(30.0, 1)].samples_per_hour / 4)
    # the response counts from the moment the bag truly came to rest (between bursts): m quiet bursts
    # must begin after it, so at least (m - 1) intervals and one burst (5.4 s at 10 Hz) pass; at m = 1
    # the next burst begins within an interval and is quiet (P_M per burst at k = 4 with 54 samples is
    # below 1e-9: duty_cycle.pm_burst), so at most one interval and one burst pass
    burst_s = 54 / 10.0
    for (interval, m), r in by.items():
        assert r.response_s is not None and r.response_s >= (m - 1) * interval + burst_s - 0.1 - 1e-9
        if m == 1:
            assert r.response_s <= interval + burst_s
