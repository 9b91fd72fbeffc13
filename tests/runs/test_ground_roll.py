"""runs.ground_roll on a real flight (the `pattern` built-in): the takeoff roll and the rollout rebuilt
from the bag's own samples come within an error budget built from the sensor's figures and the
aircraft's attitude, and the segments are the labelled ones."""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest

from flightmode.errors import NavError
from flightmode.nav.ground_roll import along_track_acceleration, integrate_along_track
from flightmode.runs.ground_roll import ground_rolls
from flightmode.sim.sensor.accelerometer import get_preset, noise_random_walk_sigma_g
from flightmode.units import G0_MPS2

PATH_STAGES = ("fly", "sense", "detect", "path")  # the same cached run as tests/runs/test_pipeline.py


@pytest.fixture(scope="module")
def pattern(run_cached):
    return run_cached("pattern", stages=PATH_STAGES)


def test_the_pipeline_stores_the_rolls_of_the_labelled_segments(pattern):
    r = pattern
    tr, rec = r.track, r.recording
    takeoff, rollout = r.path.ground_rolls
    assert r.path.ground_rolls_note is None
    assert (takeoff.segment, rollout.segment) == ("takeoff roll", "rollout")
    # the function form gives the pipeline's figures exactly
    assert ground_rolls(tr, rec) == r.path.ground_rolls
    # the bag's samples are 10 ms apart: each end is within one of its label (1e-9 s: the rounding
    # of sample times like 333.46000000000004)
    h = 1.0 / rec.odr_hz + 1e-9
    assert 0 <= takeoff.t0_s - tr.event_time("takeoff_roll") < h
    assert 0 <= tr.event_time("liftoff") - takeoff.t1_s < h
    assert 0 <= rollout.t0_s - tr.event_time("touchdown") < h
    # the rollout phase's last FDM sample is one step (1/120 s) before taxi-in starts
    assert 0 <= tr.event_time("taxi_in") - rollout.t1_s < h + 1.0 / tr.fs_hz
    # the takeoff's rest is the line-up hold, ending at brake release; the rollout's the first stop
    # after the runway exit (the pattern's taxi-in has no hold: the stand, engines running then off)
    lineup = next(e for e in tr.events if e.name == "hold" and e.detail.startswith("lineup"))
    assert lineup.t_s <= takeoff.rest_t0_s < takeoff.rest_t1_s <= tr.event_time("takeoff_roll")
    assert tr.event_time("shutdown") - 1.0 <= rollout.rest_t0_s < rollout.rest_t1_s
    # what is given, not estimated: rest at brake release; the truth's speed at the runway exit
    assert takeoff.known_speed_mps == 0.0
    assert rollout.known_speed_mps == float(np.interp(rollout.t1_s, tr.t_s, tr.ground_speed_mps))
    for c in (takeoff, rollout):
        assert c.length_error_m == c.est_length_m - c.true_length_m
        assert c.length_error_pct == 100.0 * c.length_error_m / c.true_length_m
        assert c.speed_error_mps == c.est_speed_mps - c.true_speed_mps


def _budget(track, rec, c) -> tuple[float, float]:
    """(speed m/s, length m) the estimate of roll ``c`` may be off by, from the sensor's figures and the
    aircraft's attitude; each term bounds one error source (module docstring of nav.ground_roll):

    - the offset left after the stop's mean: that mean carries the noise's error, 3 sigma of a mean
      of n samples, sigma at the noise's 0 Hz density (2.23 mg x 4.8 for the LIS302DL's coloured
      noise: sim.sensor.accelerometer), plus half a quantisation step; a residual r moves the speed by
      r T and the length by 0.5 r T^2 (T: the roll's duration);
    - the noise in the roll itself, 3 sigma of its random walk: sigma sqrt(dt T) in speed and
      sigma sqrt(dt) T^1.5 / sqrt(3) in length;
    - the unit's cross-axis coupling (run.json's matrix C): the reading along the travel axis u is
      scaled by 1 + u^T C u to first order (|C_ij| <= 2 %, so at most 2 % for a bag lying flat);
    - the attitude: the stop's mean holds gravity at the stop's pitch theta_0; on the roll the pitch
      changes (the nose rises as the roll starts, the rotation before liftoff; the derotation after
      touchdown), which leaks g (sin theta - sin theta_0) along the aircraft's axis, integrated as
      the estimator integrates (the truth's pitch)."""
    pr = get_preset(rec.preset)
    takeoff = c.segment == "takeoff roll"
    sel = (rec.t_s >= c.t0_s) & (rec.t_s <= c.t1_s)
    rest = (rec.t_s >= c.rest_t0_s) & (rec.t_s <= c.rest_t1_s)
    T = c.t1_s - c.t0_s
    sigma = noise_random_walk_sigma_g(pr) * G0_MPS2
    r = 3.0 * sigma / math.sqrt(rest.sum()) + 0.5 * pr.lsb_g * G0_MPS2
    dt = 1.0 / rec.odr_hz
    noise_v = r * T + 3.0 * sigma * math.sqrt(dt * T)
    noise_x = 0.5 * r * T**2 + 3.0 * sigma * math.sqrt(dt) * T**1.5 / math.sqrt(3.0)
    _, u, _ = along_track_acceleration(rec.acc_g[sel], rec.acc_g[rest], takeoff)
    gain = abs(u @ np.asarray(rec.unit["cross_axis"]) @ u)
    ts = rec.t_s[sel]
    pitch = np.interp(ts, track.t_s, track.euler_rad[:, 1])
    at_rest = (track.t_s >= c.rest_t0_s) & (track.t_s <= c.rest_t1_s)
    leak = G0_MPS2 * (np.sin(pitch) - np.sin(track.euler_rad[at_rest, 1].mean()))
    v, x = integrate_along_track(ts, leak, 0.0, "start" if takeoff else "end")
    att_v, att_x = abs(v[-1] if takeoff else v[0]), abs(x[-1])
    return (
        noise_v + gain * c.true_speed_mps + att_v,
        noise_x + gain * c.true_length_m + att_x,
    )


def test_the_rolls_come_within_the_sensor_budget(pattern):
    r = pattern
    assert r.recording.preset == "lis302dl-logged16"  # the pattern's sensor: the figures below are its
    for c in r.path.ground_rolls:
        budget_v, budget_x = _budget(r.track, r.recording, c)
        # the budget itself: within 4 % of the roll's length (a 1.6-1.8 km roll; the pitch term and
        # the noise's offset residual are the largest) and 3 m/s of its top speed (67-86 m/s)
        assert budget_x < 0.04 * c.true_length_m, (c, budget_x)
        assert budget_v < 3.0, (c, budget_v)
        assert abs(c.length_error_m) <= budget_x, (c, budget_x)
        assert abs(c.speed_error_mps) <= budget_v, (c, budget_v)
        # the truth is the airliner's: a 1.5-2 km roll, 60-90 m/s at liftoff or touchdown
        assert 1000.0 < c.true_length_m < 2500.0 and 55.0 < c.true_speed_mps < 95.0


def test_a_bag_moved_between_the_stop_and_the_roll_is_refused(pattern):
    r = pattern
    rec = r.recording
    # the bag picked up (carried) over the takeoff roll: its offset and tilt at the stop need not hold
    segs = tuple(
        dataclasses.replace(s, state="carried") if s.t0_s <= 340.0 < s.t1_s else s for s in rec.segments
    )
    with pytest.raises(NavError, match="does not lie in one place on board over the takeoff roll"):
        ground_rolls(r.track, dataclasses.replace(rec, segments=segs))
