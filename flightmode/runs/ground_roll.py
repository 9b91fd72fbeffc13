"""The takeoff roll and the rollout of one run rebuilt from the bag's own samples, against the truth
(:func:`ground_rolls`; the maths is :mod:`flightmode.nav.ground_roll`, seed 002's spline recurrence).

Segments, from the track's labels (:mod:`flightmode.labels`):

- **takeoff roll**: the first sample of the ``takeoff_roll`` phase (brake release) to liftoff (the
  first ``airborne`` sample after it). Known speed: 0 m/s at its start (the roll begins from the
  line-up stop). Rest: the last stop before it (the line-up hold).
- **rollout**: touchdown (the first sample of the last ``rollout`` span) to the end of that span
  (the runway exit). It ends at taxi speed, and the turn off the runway follows, which an
  accelerometer cannot follow without heading: its known speed is the truth's ground speed at the
  end of the span (the exit speed), and the rollout is integrated backwards from it. Rest: the first
  stop after it (a hold on the taxiway, or the stand).

A stop is a run of truth samples standing still on the ground (ground speed under :data:`STOP_MPS`,
weight on wheels) at least :data:`MIN_REST_S` long; of a long stop the :data:`MAX_REST_S` nearest the
roll are used. The bag must lie in one place on board over the roll and the stop (one stowed or
in-hold segment of the carrier timeline): its offset and its tilt are then the same in both.

The truth is the FlightTrack's over the bag's own sample times: the ground distance (the integral
of the ground speed) and the ground speed at the end the estimate does not know (liftoff for the
takeoff roll, touchdown for the rollout: each roll's top speed).
"""

from __future__ import annotations

from dataclasses import asdict, dataclass
from typing import TYPE_CHECKING

import numpy as np

from flightmode.errors import NavError
from flightmode.intervals import true_runs_array
from flightmode.labels import PHASE_CODE
from flightmode.nav.ground_roll import estimate_roll

if TYPE_CHECKING:
    from flightmode.sim.flight.track import FlightTrack
    from flightmode.sim.sensor.recording import Recording

STOP_MPS = 0.05  # ground speed under which the aircraft stands (a taxiing airliner: 5-15 m/s)
MIN_REST_S = 2.0  # a shorter stop is no rest (the brakes' settling; 200 samples at 100 Hz)
MAX_REST_S = 30.0  # of a longer stop, the part nearest the roll (the mean of 3,000 samples at 100 Hz)


@dataclass(frozen=True, slots=True)
class GroundRollCheck:
    """One ground roll: the bag's estimate against the truth over the same samples."""

    segment: str  # "takeoff roll" or "rollout"
    t0_s: float  # first and last sample of the roll (FlightTrack time)
    t1_s: float
    rest_t0_s: float  # the stop whose mean gave the offset and the tilt
    rest_t1_s: float
    known_speed_mps: (
        float  # given, not estimated: 0 at the takeoff roll's start, the exit speed at the rollout's end
    )
    est_length_m: float
    true_length_m: float
    est_speed_mps: float  # at liftoff (takeoff roll) or touchdown (rollout): the end not given
    true_speed_mps: float
    length_error_m: float  # estimate - truth
    length_error_pct: float  # of the true length
    speed_error_mps: float  # estimate - truth

    def as_dict(self) -> dict:
        return asdict(self)


def _stops(track: FlightTrack) -> np.ndarray:
    """(k, 2) sample-index runs [start, stop) of the track standing still on the ground, at least
    MIN_REST_S long."""
    still = (np.abs(track.ground_speed_mps) < STOP_MPS) & track.wow.astype(bool) & ~track.airborne
    runs = true_runs_array(still)
    return runs[(runs[:, 1] - runs[:, 0]) >= MIN_REST_S * track.fs_hz]


def _rest_window(track: FlightTrack, t_s: float, before: bool, segment: str) -> tuple[float, float]:
    """The stop nearest the roll on the given side of ``t_s``, clipped at ``t_s`` (a stop may run a
    few samples into the roll: the ground speed grows from 0 at brake release)."""
    runs = _stops(track)
    t = track.t_s
    start, last = t[runs[:, 0]], t[runs[:, 1] - 1]
    if before:
        ok = np.flatnonzero(start < t_s)
        if ok.size:
            t0, t1 = float(start[ok[-1]]), min(float(last[ok[-1]]), t_s)
            t0 = max(t0, t1 - MAX_REST_S)
    else:
        ok = np.flatnonzero(last > t_s)
        if ok.size:
            t0, t1 = max(float(start[ok[0]]), t_s), float(last[ok[0]])
            t1 = min(t1, t0 + MAX_REST_S)
    if not ok.size or t1 - t0 < MIN_REST_S - 1.5 / track.fs_hz:
        side = "before" if before else "after"
        raise NavError(
            f"no stop of {MIN_REST_S:g} s or more {side} the {segment}: no rest to take the offset from"
        )
    return t0, t1


def _segments(track: FlightTrack) -> dict[str, tuple[float, float]]:
    """{segment: (t0, t1)} from the labels (module docstring)."""
    t = track.t_s
    tr = np.flatnonzero(track.phase_code == PHASE_CODE["takeoff_roll"])
    if tr.size == 0:
        raise NavError("the track has no takeoff_roll phase: ground rolls need a whole gate-to-gate flight")
    up = np.flatnonzero(track.airborne[tr[0] :])
    if up.size == 0:
        raise NavError("the track never leaves the ground after its takeoff roll")
    ro = true_runs_array(track.phase_code == PHASE_CODE["rollout"])
    if ro.shape[0] == 0:
        raise NavError("the track has no rollout phase: ground rolls need a whole gate-to-gate flight")
    s, e = ro[-1]  # the last landing's (after a go-around or a touch-and-go)
    return {
        "takeoff roll": (float(t[tr[0]]), float(t[tr[0] + up[0]])),
        "rollout": (float(t[s]), float(t[e - 1])),
    }


def _one_place(rec: Recording, t0_s: float, t1_s: float, what: str) -> None:
    """The bag lies in one place on board (one stowed or in-hold segment) over [t0_s, t1_s]."""
    inside = [s for s in rec.segments if s.t0_s <= t0_s and t1_s <= s.t1_s]
    if not inside or not inside[0].on_board or inside[0].state not in ("stowed", "in_hold"):
        raise NavError(
            f"the bag does not lie in one place on board over the {what} and its stop "
            f"({t0_s:.1f}-{t1_s:.1f} s): its offset and tilt at the stop need not hold in the roll"
        )


def _cumulative_distance_m(track: FlightTrack) -> np.ndarray:
    gs = track.ground_speed_mps
    return np.concatenate([[0.0], np.cumsum(0.5 * (gs[1:] + gs[:-1]) * np.diff(track.t_s))])


def ground_rolls(track: FlightTrack, rec: Recording) -> tuple[GroundRollCheck, GroundRollCheck]:
    """(takeoff roll, rollout) rebuilt from ``rec``'s samples (module docstring); NavError when a
    roll has no stop beside it or the bag moves between the stop and the roll."""
    dist = _cumulative_distance_m(track)
    out = []
    for segment, (t0, t1) in _segments(track).items():
        takeoff = segment == "takeoff roll"
        rest0, rest1 = _rest_window(track, t0 if takeoff else t1, before=takeoff, segment=segment)
        _one_place(rec, min(t0, rest0), max(t1, rest1), segment)
        sel = (rec.t_s >= t0) & (rec.t_s <= t1)
        rest = (rec.t_s >= rest0) & (rec.t_s <= rest1)
        if sel.sum() < 3 or not rest.any():
            raise NavError(f"the {segment} holds {int(sel.sum())} samples and its stop {int(rest.sum())}")
        ts = rec.t_s[sel]
        gs = np.interp(ts, track.t_s, track.ground_speed_mps)
        known = 0.0 if takeoff else float(gs[-1])
        est = estimate_roll(
            ts,
            rec.acc_g[sel],
            rec.acc_g[rest],
            accelerating=takeoff,
            known_speed_mps=known,
            known_at="start" if takeoff else "end",
        )
        d = np.interp(ts[[0, -1]], track.t_s, dist)
        true_len = float(d[1] - d[0])
        true_v = float(gs[-1] if takeoff else gs[0])
        est_v = est.end_speed_mps if takeoff else est.start_speed_mps
        out.append(
            GroundRollCheck(
                segment=segment,
                t0_s=float(ts[0]),
                t1_s=float(ts[-1]),
                rest_t0_s=rest0,
                rest_t1_s=rest1,
                known_speed_mps=known,
                est_length_m=est.length_m,
                true_length_m=true_len,
                est_speed_mps=est_v,
                true_speed_mps=true_v,
                length_error_m=est.length_m - true_len,
                length_error_pct=100.0 * (est.length_m - true_len) / true_len,
                speed_error_mps=est_v - true_v,
            )
        )
    return out[0], out[1]


__all__ = ["GroundRollCheck", "MAX_REST_S", "MIN_REST_S", "STOP_MPS", "ground_rolls"]
