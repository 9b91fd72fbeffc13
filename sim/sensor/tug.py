"""The tug's jolts during the pushback, as the cabin floor feels them.

The flight's pushback (:class:`flightmode.sim.flight.pilot.ground.Pushback`) is a smooth speed
profile: JSBSim's tug force on a PI loop ramps the aircraft to ``pushback_mps`` (1.2 m/s) and back at
0.2 m/s^2, with no jolt. A real push is not smooth: the tow bar has free play and a shock absorber
(tow bars "incorporate a shock absorber system, normally a large spring, to avoid snatching
movements being transmitted to the aircraft structure": an aircraft-maintenance course text), the
tug's driver starts and stops it, and the slack is taken up and given back as the push goes on.
Those jolts reach the floor along the fuselage axis. They are added here to the floor's specific
force (before the mounts, so every placement feels them through its own support) as prescribed
accelerations (:func:`tug_accel_mps2`), not in the flight: each is a :func:`bump_accel` pulse, a
smooth out-and-back surge that leaves no net velocity or displacement, so the flight's own path and
speed (the FlightTrack, its digest) are unchanged and a path estimator integrates no drift from them.

- the start: a surge rearward (the push's direction) of peak ``pushback.start_peak_mps2`` over
  ``pushback.jolt_duration_s`` from the pushback's first instant;
- the stop: a surge forward of peak ``pushback.stop_peak_mps2`` ending when the aircraft comes to
  rest (ground speed below 0.1 m/s for the last time before the tug is disconnected);
- the slack: Poisson events at ``pushback.slack_rate_per_min`` between the two, each a pulse of
  either sign of peak ``pushback.slack_peak_mps2`` over ``pushback.slack_duration_s``.

Sources. Speed: "about 2-5 km/h" for the traditional tow (Applied Sciences 13(6), 3636, 2023, on
towed-taxi lateral stability; read in docs/research/fleet_loads/OTHER_SOURCES.md); the flight's
1.2 m/s lies in it. Jolt magnitudes: none were found for normal operations; a tow-bar failure
analysis in an accident report (Hong Kong CAD, Aircraft Accident Investigation Report ACCID01/06,
appendix "Failure analysis of a towbar", City University of Hong Kong) computes 3.3 m/s^2 as the
sudden deceleration that would break the tow-bar head: the ranges below stay well under it. All
magnitudes, durations and the slack rate are assumptions (:data:`UNCERTAIN`); per flight each is
drawn log-uniformly within ``pushback.flight_spread`` of its declared value, per slack pulse the
peak and duration again.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass

import numpy as np

from flightmode.labels import PHASE_CODE
from flightmode.sim.sensor.passenger import BUMP_PEAK, bump_accel
from flightmode.uncertain import Uncertain, value_of

START_PEAK_MPS2 = Uncertain(
    "pushback.start_peak_mps2",
    0.3,
    0.05,
    1.0,
    "m/s^2",
    "assumption: a tug's start through the tow bar's free play and spring; well under the 3.3 m/s^2 "
    "of a tow-bar head's failure case (HK CAD report ACCID01/06, tow-bar failure analysis)",
    "the pushback's start: the surge's peak acceleration along the fuselage (median)",
)
STOP_PEAK_MPS2 = Uncertain(
    "pushback.stop_peak_mps2",
    0.3,
    0.05,
    1.0,
    "m/s^2",
    "assumption: as the start (the tug brakes the aircraft to rest through the same bar)",
    "the pushback's stop: the surge's peak acceleration along the fuselage (median)",
)
JOLT_DURATION_S = Uncertain(
    "pushback.jolt_duration_s",
    0.8,
    0.3,
    2.0,
    "s",
    "assumption: the tow bar's spring and the nose-gear strut take up the jolt over a fraction of a "
    "second to two seconds",
    "the pushback's start and stop: the surges' duration (median)",
)
SLACK_RATE_PER_MIN = Uncertain(
    "pushback.slack_rate_per_min",
    2.0,
    0.2,
    6.0,
    "1/min",
    "assumption: the driver's throttle corrections and the bar's slack taken up in the turn",
    "the pushback: how often a tow-bar slack pulse reaches the floor (median)",
)
SLACK_PEAK_MPS2 = Uncertain(
    "pushback.slack_peak_mps2",
    0.1,
    0.02,
    0.3,
    "m/s^2",
    "assumption: smaller than the start and stop surges",
    "the pushback: a tow-bar slack pulse's peak acceleration along the fuselage (median)",
)
SLACK_DURATION_S = Uncertain(
    "pushback.slack_duration_s",
    0.5,
    0.2,
    1.5,
    "s",
    "assumption: as the start and stop, shorter",
    "the pushback: a tow-bar slack pulse's duration (median)",
)
FLIGHT_SPREAD = Uncertain(
    "pushback.flight_spread",
    1.5,
    1.0,
    2.5,
    "1",
    "assumption: tugs, drivers and tow bars differ; each flight's values lie within this factor of the "
    "medians (log-uniform)",
    "the pushback: the spread of the jolts between flights and between slack pulses",
)
UNCERTAIN = (
    START_PEAK_MPS2,
    STOP_PEAK_MPS2,
    JOLT_DURATION_S,
    SLACK_RATE_PER_MIN,
    SLACK_PEAK_MPS2,
    SLACK_DURATION_S,
    FLIGHT_SPREAD,
)
AT_REST_MPS = 0.1  # the push has stopped below this ground speed


@dataclass(frozen=True, slots=True)
class TugDraw:
    """One flight's tug jolts (:func:`draw_tug`): each pulse's start time, signed peak acceleration
    along body x (forward; negative: rearward) and duration; the first is the start, the last the
    stop, the rest the slack pulses in time order."""

    t_s: np.ndarray  # (m,)
    peak_mps2: np.ndarray  # (m,)
    duration_s: np.ndarray  # (m,)
    slack_rate_per_s: float

    def as_dict(self) -> dict:
        return {
            "start_peak_mps2": float(self.peak_mps2[0]),
            "stop_peak_mps2": float(self.peak_mps2[-1]),
            "jolt_duration_s": float(self.duration_s[0]),
            "slack_rate_per_min": self.slack_rate_per_s * 60.0,
            "slack_pulses": int(self.t_s.shape[0] - 2),
        }


def push_span(
    t_s: np.ndarray, phase_code: np.ndarray, ground_speed_mps: np.ndarray
) -> tuple[float, float] | None:
    """The push's (start, stop) in track time: the pushback phase's first sample, and the last
    sample in it moving at :data:`AT_REST_MPS` or more (the aircraft at rest after it); None
    without a pushback."""
    idx = np.flatnonzero(phase_code == PHASE_CODE["pushback"])
    if idx.size == 0:
        return None
    moving = idx[ground_speed_mps[idx] >= AT_REST_MPS]
    t_end = t_s[moving[-1]] if moving.size else t_s[idx[-1]]
    return float(t_s[idx[0]]), float(t_end)


def draw_tug(
    span: tuple[float, float], rng: np.random.Generator, overrides: Mapping[str, float] | None = None
) -> TugDraw:
    """The jolts of the push over ``span`` (:func:`push_span`). Draws, in this order: the start's
    and the stop's peaks, the jolt duration, the slack rate, the number of slack pulses (Poisson),
    their times (uniform between the start's end and the stop's beginning), peaks, durations and
    signs."""
    k = value_of(FLIGHT_SPREAD, overrides)

    def spread(size=None):
        return np.exp(rng.uniform(-np.log(k), np.log(k), size))

    a0 = value_of(START_PEAK_MPS2, overrides) * float(spread())
    a1 = value_of(STOP_PEAK_MPS2, overrides) * float(spread())
    dur = value_of(JOLT_DURATION_S, overrides) * float(spread())
    rate = value_of(SLACK_RATE_PER_MIN, overrides) / 60.0 * float(spread())
    t0, t1 = span[0], max(span[0], span[1] - dur)
    lo, hi = t0 + dur, t1
    m = int(rng.poisson(rate * max(hi - lo, 0.0)))
    ts = np.sort(rng.uniform(lo, hi, m)) if hi > lo else np.zeros(0)
    m = ts.shape[0]
    pk = value_of(SLACK_PEAK_MPS2, overrides) * spread(m)
    du = value_of(SLACK_DURATION_S, overrides) * spread(m)
    sign = np.where(rng.uniform(size=m) < 0.5, -1.0, 1.0)
    # the start surges rearward (the push's direction), the stop forward
    return TugDraw(
        np.concatenate([[t0], ts, [t1]]),
        np.concatenate([[-a0], sign * pk, [a1]]),
        np.concatenate([[dur], du, [dur]]),
        rate,
    )


def tug_accel_mps2(t_s: np.ndarray, d: TugDraw) -> np.ndarray | None:
    """The jolts' acceleration (3, n), body axes, m/s^2, at times ``t_s`` (sorted), or None when no
    pulse touches them. Each pulse is :func:`bump_accel` scaled so that its peak magnitude (mid-pulse)
    is the drawn one, with the drawn sign at that peak."""
    t = np.asarray(t_s, float)
    if t.shape[0] == 0:
        return None
    live = np.flatnonzero((d.t_s <= t[-1]) & (d.t_s + d.duration_s >= t[0]))
    if live.size == 0:
        return None
    out = np.zeros((3, t.shape[0]))
    for i in live:  # the few pulses of this stretch; each vectorised over its samples
        a, b = np.searchsorted(t, [d.t_s[i], d.t_s[i] + d.duration_s[i]])
        # bump_accel peaks at -BUMP_PEAK mid-pulse: the sign flip puts the drawn sign there
        out[0, a:b] += -d.peak_mps2[i] / BUMP_PEAK * bump_accel((t[a:b] - d.t_s[i]) / d.duration_s[i])
    return out


__all__ = ["UNCERTAIN", "TugDraw", "draw_tug", "push_span", "tug_accel_mps2"]
