"""Per-sample decisions against the truth labels: how any detector made by the interface
(:mod:`flightmode.detector.interface`: one bool per sample, True = at rest, the radio may transmit) is
scored, with the definitions of :mod:`flightmode.detector.evaluation` (seed 000 sections 5.1.2, 5.3
and 7.1) taken from checks every W_s to samples.

Inputs are plain arrays: the stream's times ``t_s``, the decisions ``static`` and the labels
``in_flight_window``, ``sensor_static`` and ``phase`` (one row per sample). Durations are samples x
dt, dt the median sample interval.

- **False-static events**: runs of rest decisions inside the in-flight window (pushback to engines
  off), each with its start time, duration and phase (the phase of its first sample). A run that
  continues into the window from before pushback is the suspension latency (``suspend_s``); it is
  also a false static when it lasts ``grace_s`` or longer (0, the default: always). A detector
  that decides every W_s (the built-ins' checks, judged at their closing sample) with its decisions
  held until the next check gives the same events as :class:`~flightmode.detector.evaluation.
  Evaluation` with ``grace_s = W_s``: a held decision from before pushback covers less than one
  window of the in-flight window before the first check inside it decides.
- **Missed static**: outside the window, samples truly static where the detector does not allow
  transmission, in seconds; ``static_s`` is all truly static time outside the window and
  ``availability`` the share of it reported static.
- **Suspension latency**: from the window's first sample to the first sample inside it that forbids
  transmission (NaN: the window never forbade it, or there is no window).
- **Response**: from the first truly static sample after the window ends to the first rest decision
  at or after it (None: the bag never came to rest, or the detector never answered).
- **Accuracy and correlation**: per sample, the decision against ``sensor_static`` (fraction equal,
  and the phi coefficient of the two 0/1 series).

This module imports NumPy only inside its functions.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

from flightmode.errors import DetectorError


@dataclass(frozen=True, slots=True)
class DecisionEvaluation:
    """The figures of one stream's decisions (module docstring)."""

    samples: int
    dt_s: float
    false_static_events: list[dict]  # {"t_s", "duration_s", "phase"}
    in_flight_samples: int
    static_s: float  # truly static time outside the in-flight window
    missed_static_s: float
    suspend_s: float  # NaN: never suspended inside the window, or no window
    response_s: float | None
    accuracy: float
    correlation: float
    rest_after: bool  # the bag was truly at rest after the window (a response was due)

    @property
    def false_static_count(self) -> int:
        return len(self.false_static_events)

    @property
    def false_static_s(self) -> float:
        return float(sum(e["duration_s"] for e in self.false_static_events))

    @property
    def longest_false_static_s(self) -> float:
        return max((e["duration_s"] for e in self.false_static_events), default=0.0)

    @property
    def in_window_h(self) -> float:
        return self.in_flight_samples * self.dt_s / 3600.0

    @property
    def availability(self) -> float:
        """The share of truly static time outside the window reported static (NaN: none)."""
        return (self.static_s - self.missed_static_s) / self.static_s if self.static_s > 0 else math.nan

    def summary(self) -> dict:
        return {
            "samples": self.samples,
            "dt_s": self.dt_s,
            "in_flight_samples": self.in_flight_samples,
            "in_window_h": self.in_window_h,
            "false_static_events": self.false_static_events,
            "false_static_count": self.false_static_count,
            "false_static_s": self.false_static_s,
            "longest_false_static_s": self.longest_false_static_s,
            "false_static_phases": ",".join(e["phase"] for e in self.false_static_events),
            "suspend_s": self.suspend_s,
            "response_s": self.response_s,
            "static_s": self.static_s,
            "missed_static_s": self.missed_static_s,
            "availability": self.availability,
            "accuracy": self.accuracy,
            "correlation": self.correlation,
        }


def check(t_s: Any, static: Any, labels: dict) -> None:
    """A DetectorError unless ``static`` and the three labels have one row per sample of ``t_s``
    (the labels by :func:`flightmode.detector.evaluation.check_labels`)."""
    import numpy as np

    from flightmode.detector.evaluation import check_labels

    n = np.asarray(t_s).shape[0]
    if np.asarray(static).shape != (n,):
        raise DetectorError(
            f"decisions have shape {np.asarray(static).shape}, the stream {n} samples: one per sample"
        )
    check_labels(t_s, labels)


def score(t_s: Any, static: Any, labels: dict, *, grace_s: float = 0.0) -> DecisionEvaluation:
    """Score per-sample decisions ``static`` (True: at rest) over a labelled stream (module
    docstring). ``grace_s``: a rest decision carried into the in-flight window from before it counts
    as a false static only when it lasts this long or longer."""
    import numpy as np

    from flightmode.detector.evaluation import phi_coefficient
    from flightmode.intervals import true_runs

    check(t_s, static, labels)
    t = np.asarray(t_s, float)
    dec = np.asarray(static, bool)
    window = np.asarray(labels["in_flight_window"], bool)
    truth = np.asarray(labels["sensor_static"], bool)
    phase = np.asarray(labels["phase"], dtype=object)
    n = t.shape[0]
    dt = float(np.median(np.diff(t))) if n > 1 else math.nan
    events = []
    for s, e in true_runs(dec & window):
        carried = s > 0 and bool(dec[s - 1]) and not bool(window[s - 1])
        dur = (e - s) * dt
        if carried and dur < grace_s - 1e-9 * max(1.0, grace_s):
            continue  # the suspension latency, shorter than the grace
        events.append({"t_s": float(t[s]), "duration_s": dur, "phase": str(phase[s])})
    outside = truth & ~window
    static_s = float(outside.sum()) * dt
    missed = float((outside & ~dec).sum()) * dt
    suspend = math.nan
    response = None
    rest_after = False
    if window.any():
        w = np.flatnonzero(window)
        off = np.flatnonzero(window & ~dec)
        if off.size:
            suspend = float(t[off[0]] - t[w[0]])
        end = int(w[-1])
        after = np.flatnonzero(truth[end:])
        if after.size:
            rest_after = True
            i_rest = end + int(after[0])
            hit = np.flatnonzero(dec[i_rest:])
            if hit.size:
                response = float(t[i_rest + hit[0]] - t[i_rest])
    acc = float(np.mean(dec == truth)) if n else math.nan
    return DecisionEvaluation(
        n,
        dt,
        events,
        int(window.sum()),
        static_s,
        missed,
        suspend,
        response,
        acc,
        phi_coefficient(dec, truth),
        rest_after,
    )


def held(n: int, index: Any, decided: Any) -> Any:
    """Decisions made at samples ``index`` (increasing), each held until the next: one bool per
    sample of a stream of ``n`` (False before the first), as a streaming detector that decides every
    W_s reports between its checks."""
    import numpy as np

    idx = np.asarray(index, np.int64)
    out = np.zeros(n, bool)
    if idx.size:
        pos = np.searchsorted(idx, np.arange(n), side="right") - 1
        ok = pos >= 0
        out[ok] = np.asarray(decided, bool)[pos[ok]]
    return out


__all__ = ["DecisionEvaluation", "check", "held", "score"]
