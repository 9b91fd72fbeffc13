"""The e-obs duty-cycled rule as a detector of the interface (:mod:`flightmode.detector.interface`):
entry point ``eobs-duty``, so that ``detect``, ``sweep`` and ``certify`` run it beside the built-ins.

A tag that records acceleration in bursts (seed 003 section 4.1: ``N`` samples per axis every ACC
interval, asleep in between) decides once per burst (:mod:`flightmode.eobs.duty_cycle`: seed 000
eq. (1) over the burst, eq. (7) with T_sigma = k sigma^2, eq. (8) with bursts in place of checks).
On a continuous stream the tag's bursts are its samples: burst ``j`` starts at sample
``round(j x interval_s x fs_hz)`` (the stream's first sample is burst 0's first) and takes
``burst_samples`` samples, one every ``round(fs_hz / odr_hz)`` (the tag's per-axis rate, seed 003
section 4.2; at most the stream's). The decision of a burst is made at its last sample and held until
the next burst's last sample: False (the radio stays off) before the first.

sigma^2: the ``sigma2`` parameter (g^2, one per channel), or calibrated on the unit's rest recording
(``rest``, passed by the harness) cut into bursts of the same shape
(:func:`~flightmode.eobs.duty_cycle.calibrate_sigma2_bursts`), floored at the quantisation noise
``lsb_g^2 / 12`` (``sensor_lsb_g`` from the harness, else the recording's smallest step).

``push`` takes chunks of any size and ``decide`` the whole stream; both run the same bursts through
:class:`~flightmode.eobs.duty_cycle.BurstDetector`, so they agree exactly.
"""

from __future__ import annotations

import math
from typing import Any

from flightmode.errors import DetectorError

CHANNELS = ("acc_x_g", "acc_y_g", "acc_z_g")
# seed 003 section 4.2's usual per-axis rate of the newer tags, and eobs_preset's default
ODR_HZ = 10.0
# seed 000 Table 9's threshold; two quiet bursts in a row for final static (eq. 8 with T_th / W_s = 2)
K = 4.0
M = 2


class EobsDutyDetector:
    """The duty-cycled rule over a continuous stream (module docstring)."""

    def __init__(
        self, fs_hz: float, sigma2: Any, interval_s: float, burst_samples: int, step: int, k: float, m: int
    ):
        from flightmode.eobs.duty_cycle import BurstDetector

        self.period = int(round(interval_s * fs_hz))
        self.n, self.step = int(burst_samples), int(step)
        self.span = (self.n - 1) * self.step  # offset of a burst's last sample from its first
        self.det = BurstDetector(sigma2, k, m)
        self.decision = False
        self.g0 = 0  # global index of the next pushed sample
        self.pending: list = []  # the current burst's samples from earlier chunks

    def push(self, t_s: Any, x: Any) -> Any:
        import numpy as np

        t = np.asarray(t_s, float)
        x = np.asarray(x, float)
        n = t.shape[0]
        g = self.g0 + np.arange(n)
        off = g % self.period
        member = (off % self.step == 0) & (off <= self.span)
        out = np.empty(n, bool)
        last = 0
        ends = np.flatnonzero(member & (off == self.span))
        start = 0
        for e in ends.tolist():
            take = np.flatnonzero(member[start : e + 1]) + start
            burst = np.concatenate([*self.pending, x[take]]) if self.pending else x[take]
            self.pending = []
            out[last:e] = self.decision
            self.decision = bool(self.det.push(t[e], burst).final_static[0])
            last, start = e, e + 1
        out[last:] = self.decision
        rest = np.flatnonzero(member[start:]) + start
        if rest.size:
            self.pending.append(x[rest])
        self.g0 += n
        return out

    def decide(self, t_s: Any, x: Any) -> Any:
        return self.push(t_s, x)


def make(
    fs_hz: float,
    channels: list[str],
    *,
    interval_s: float = 10.0,
    burst_samples: int = 20,
    odr_hz: float = ODR_HZ,
    k: float = K,
    m: int = M,
    sigma2: Any = None,
    rest: Any = None,
    sensor_lsb_g: float | None = None,
) -> EobsDutyDetector:
    """The duty-cycled rule at ``fs_hz`` on ``channels`` (acceleration, g): a burst of
    ``burst_samples`` samples at ``odr_hz`` every ``interval_s`` seconds; quiet when every channel's
    burst variance is under ``k sigma^2``; final static after ``m`` quiet bursts in a row."""
    import numpy as np

    for c in channels:
        if c not in CHANNELS:
            raise DetectorError(
                f"eobs-duty: channel {c!r}: the e-obs rule reads acceleration ({', '.join(CHANNELS)})"
            )
    if not (isinstance(burst_samples, int) and burst_samples >= 2):
        raise DetectorError(f"eobs-duty: burst_samples = {burst_samples!r}: an integer >= 2 (a variance)")
    if not (odr_hz > 0 and math.isfinite(odr_hz)):
        raise DetectorError(f"eobs-duty: odr_hz = {odr_hz!r}: a rate > 0 Hz")
    step = max(1, int(round(fs_hz / odr_hz)))
    span_s = (burst_samples - 1) * step / fs_hz
    if not (interval_s > 0 and int(round(interval_s * fs_hz)) > (burst_samples - 1) * step):
        raise DetectorError(
            f"eobs-duty: interval_s = {interval_s!r}: the ACC interval must exceed the burst ({span_s:g} s)"
        )
    if sigma2 is None:
        if rest is None:
            raise DetectorError(
                "eobs-duty: give sigma2 (g^2 per channel) or run it where a rest recording is passed"
            )
        from flightmode.eobs.duty_cycle import calibrate_sigma2_bursts

        r = np.asarray(rest, float)[::step]
        nb = r.shape[0] // burst_samples
        if nb < 1:
            raise DetectorError(
                f"eobs-duty: the rest recording ({np.asarray(rest).shape[0]} samples) is shorter than one burst"
            )
        sigma2 = calibrate_sigma2_bursts(
            list(r[: nb * burst_samples].reshape(nb, burst_samples, -1)), lsb_g=sensor_lsb_g or _lsb(r)
        )
    s2 = np.asarray(sigma2, float).reshape(-1)
    if s2.size != len(channels):
        raise DetectorError(f"eobs-duty: sigma2 has {s2.size} values for {len(channels)} channels")
    return EobsDutyDetector(fs_hz, s2, interval_s, burst_samples, step, k, m)


def _lsb(rest: Any) -> float | None:
    """The recording's resolution: the smallest step between two of its values on any channel (the
    calibration's floor is then the quantisation noise lsb^2 / 12: a unit whose counts do not move
    at rest would otherwise give sigma^2 = 0, and every later LSB flip a moving burst)."""
    import numpy as np

    steps = [np.diff(np.unique(c)) for c in np.asarray(rest, float).T]
    steps = [d[d > 0].min() for d in steps if (d > 0).any()]
    return float(min(steps)) if steps else None


make.channels = CHANNELS  # type: ignore[attr-defined]

__all__ = ["EobsDutyDetector", "make"]
