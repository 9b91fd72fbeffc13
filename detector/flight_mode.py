"""The flight-mode detector of seed 000 (section 5, eq. 6-9, Fig. 9).

Every ``W_s`` seconds (every ``N = W_s fs`` samples, at fixed global positions) the moving variance
of each axis is compared with its threshold ``T_sigma = k sigma^2`` (eq. 7, 12): all axes below it
gives a *temporary static* check. The sensor is declared *final static* (a GSM transmission is
allowed) when the last ``ceil(T_th / W_s)`` checks were all temporarily static (eq. 8).

One set of maths, two front ends: :class:`FlightModeDetector` (streaming: push chunks of any size)
and :func:`detect` (batch: one push). A time gap in the stream (consecutive samples more than 1.5
sample periods apart) resets the detector: the moving variance restarts and no check is static
until ``T_th`` of clean data has been seen again (documented behaviour, never silent).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from flightmode.detector.moving_variance import MovingVariance
from flightmode.detector.recommended_point import POINT
from flightmode.errors import DetectorError


@dataclass(frozen=True, slots=True)
class DetectorParams:
    """The detector's parameters; the defaults are seed 000's recommended point (Table 9:
    :data:`flightmode.detector.recommended_point.POINT`)."""

    fs_hz: float = 100.0
    window_s: float = POINT.window_s
    k_sigma: float = POINT.k_sigma
    time_threshold_s: float = POINT.time_threshold_s
    method: str = POINT.method
    weight: float = POINT.weight  # EMV weighting factor
    emv_initial_k: float = 10.0  # EMV starts from 10 sigma^2 (Fig. 18)
    # "per-axis": T^i = k sigma_i^2 on each axis (ours, the default); "common": one T_sigma for the
    # three axes, as seed 000 eq. (12) writes it (T^x = T^y = T^z = T_sigma, the axes' static
    # variances being "approximately equal"), here k times the mean of the three sigma_i^2
    threshold: str = "per-axis"

    @property
    def window(self) -> int:
        return int(round(self.window_s * self.fs_hz))

    @property
    def checks_needed(self) -> int:
        return max(1, math.ceil(self.time_threshold_s / self.window_s - 1e-9))

    def validate(self) -> None:
        if not self.fs_hz > 0:
            raise DetectorError(f"sampling rate {self.fs_hz}: must be > 0 Hz")
        if self.window < 2:
            raise DetectorError(
                f"window {self.window_s} s at {self.fs_hz:g} Hz is {self.window} sample(s): a variance needs >= 2"
            )
        if not self.k_sigma > 0:
            raise DetectorError(f"k = {self.k_sigma}: the threshold k sigma^2 needs k > 0")
        if not self.time_threshold_s > 0:
            raise DetectorError(f"time threshold {self.time_threshold_s} s: must be > 0")
        if self.threshold not in THRESHOLD_MODES:
            raise DetectorError(
                f"threshold {self.threshold!r}: one of {', '.join(THRESHOLD_MODES)} (seed 000 eq. 12 is 'common')"
            )


THRESHOLD_MODES = ("per-axis", "common")


def axis_thresholds(params: DetectorParams, sigma2: np.ndarray) -> np.ndarray:
    """T_sigma per axis (g^2): k sigma_i^2 ("per-axis"), or seed 000 eq. (12)'s one common threshold
    k mean(sigma_i^2) on all three axes ("common")."""
    s2 = np.asarray(sigma2, float).reshape(-1)
    if params.threshold == "common":
        return np.full(s2.shape, params.k_sigma * float(s2.mean()))  # seed 000, eq. (12)
    return params.k_sigma * s2  # eq. (7) with T^i = k sigma_i^2


@dataclass(frozen=True, slots=True)
class Checks:
    """One row per check (every W_s): the sample index and time it closes, the MV per axis, and the
    decisions."""

    index: np.ndarray  # (K,) global sample index of the window end
    t_s: np.ndarray  # (K,)
    mv: np.ndarray  # (K, 3)
    temporary_static: np.ndarray  # (K,) bool, eq. 7
    final_static: np.ndarray  # (K,) bool, eq. 8: transmission allowed
    after_reset: np.ndarray  # (K,) bool: the first check after the detector (re)started


def final_static(temporary: np.ndarray, after_reset: np.ndarray, need: int, carry: int = 0) -> np.ndarray:
    """Eq. 8: a check is final static when it and the ``need - 1`` checks before it (since the last
    reset) were all temporarily static. ``carry``: temporary statics in a row just before the first
    check (the streaming detector's state). Vectorised: the length of the run of temporary statics
    ending at each check."""
    temp = np.asarray(temporary, bool)
    k = np.arange(temp.shape[0])
    # the last check that breaks a run: a dynamic check, or the check before a reset
    breaks = np.where(~temp, k, -1)
    breaks = np.where(np.asarray(after_reset, bool), np.maximum(breaks, k - 1), breaks)
    last = np.maximum.accumulate(breaks) if k.size else breaks
    run = np.where(last < 0, k + 1 + carry, k - last)
    return temp & (run >= need)


# calibration blocks: 10 windows (10 s at the recommended 1 s window). A block's own mean takes only
# 1/N of sigma^2 (0.1 % for the LIS302DL's white noise at 100 Hz) and averages the noise's wandering
# amplitude over ten windows, and one knock or a bag set down differently loses one block, not the estimate
CALIBRATION_BLOCK_WINDOWS = 10
# a quiet block's variance is within a few per cent of the median block's; 5 times it is a knock or
# a change of orientation inside the block, never noise
DISTURBED_OVER_MEDIAN = 5.0


def calibrate_sigma2(acc_g: np.ndarray, window: int, lsb_g: float | None = None) -> np.ndarray:
    """Per-axis static noise variance from a (mostly) static recording, as seed 000 section 5.1
    step (1) asks: "measure the noise variance on each axis". The record is cut into blocks of
    ``CALIBRATION_BLOCK_WINDOWS`` windows (fewer if it is shorter, at least one window); a block whose
    variance about its own mean exceeds ``DISTURBED_OVER_MEDIAN`` times the median block's on any
    axis is dropped (a disturbance: somebody knocked the bench, the bag was set down differently),
    and sigma^2 is the mean variance of the blocks kept.

    Not the median of 1 s window variances: the static noise's amplitude wanders
    (:mod:`~flightmode.sim.sensor.accelerometer`), so the 1 s variances are skewed (spread 0.37
    sigma^2) and their median sits at 0.94 sigma^2, while the thresholds k sigma^2 of Table 2 are
    multiples of the noise variance itself.

    Quantised output: a native 8-bit LIS302DL at rest can output a constant count, so the measured
    variance may be (nearly) zero and a threshold k sigma^2 would then be zero too (every check
    dynamic, never a transmission). The variance is therefore floored at the quantisation noise
    ``lsb^2 / 12`` when ``lsb_g`` is given, and at 1e-12 g^2 otherwise (never zero).
    """
    x = np.asarray(acc_g, float)
    if x.shape[0] < window:
        raise DetectorError(
            f"calibration needs at least one {window}-sample window, got {x.shape[0]} samples"
        )
    n = window * max(1, min(CALIBRATION_BLOCK_WINDOWS, x.shape[0] // window))
    m = x.shape[0] // n
    v = x[: m * n].reshape(m, n, -1).var(axis=1)
    quiet = np.all(v <= DISTURBED_OVER_MEDIAN * np.median(v, axis=0), axis=1)
    s2 = v[quiet].mean(axis=0)
    floor = lsb_g**2 / 12.0 if lsb_g else 1e-12
    return np.maximum(s2, floor)


class FlightModeDetector:
    """Streaming detector. ``push(t_s, acc_g)`` returns the checks completed by that chunk."""

    def __init__(self, params: DetectorParams, sigma2: np.ndarray):
        params.validate()
        sigma2 = np.asarray(sigma2, float).reshape(-1)
        if sigma2.shape != (3,) or not np.all(sigma2 > 0):
            raise DetectorError(f"sigma^2 must be three positive per-axis variances, got {sigma2}")
        self.p = params
        self.sigma2 = sigma2
        self.thresholds = axis_thresholds(params, sigma2)  # eq. 7, 12: T_sigma = k sigma^2
        self._new_engine()
        self._t_last: float | None = None
        self._n = 0  # samples seen (global index of the next one)

    def _new_engine(self) -> None:
        p = self.p
        self._mv = MovingVariance(p.window, p.method, p.weight, p.emv_initial_k * self.sigma2)
        self._since_reset = 0
        self._run_len = 0  # temporary statics in a row so far (eq. 8's state)

    def push(self, t_s: np.ndarray, acc_g: np.ndarray) -> Checks:
        t = np.asarray(t_s, float)
        a = np.asarray(acc_g, float)
        if a.ndim != 2 or a.shape[1] != 3 or t.shape != (a.shape[0],):
            raise DetectorError(f"need t_s (n,) and acc_g (n, 3); got {t.shape} and {a.shape}")
        period = 1.0 / self.p.fs_hz
        if t.shape[0] > 1:
            dt = np.diff(t)
            if np.any(dt <= 0):
                i = int(np.flatnonzero(dt <= 0)[0])
                raise DetectorError(
                    f"time is not increasing at sample {self._n + i + 1} (t = {t[i + 1]:.4f} s)"
                )
            med = float(np.median(dt))
            if abs(med - period) > 0.01 * period:
                raise DetectorError(
                    f"the stream is sampled at {1 / med:.2f} Hz but the detector expects {self.p.fs_hz:g} Hz: "
                    "set fs_hz to the stream's rate"
                )
        out = []
        start = 0
        # split at gaps (including one against the previous chunk): each gap resets the detector
        t_prev = self._t_last
        gaps = []
        if t_prev is not None and t.shape[0] and t[0] - t_prev > 1.5 * period:
            gaps.append(0)
        if t.shape[0] > 1:
            gaps += list(np.flatnonzero(np.diff(t) > 1.5 * period) + 1)
        for g in [*gaps, t.shape[0]]:
            if g > start:
                out.append(self._run(t[start:g], a[start:g]))
            if g < t.shape[0]:
                self._new_engine()
            start = g
        if t.shape[0]:
            self._t_last = float(t[-1])
        return _cat(out)

    def _run(self, t: np.ndarray, a: np.ndarray) -> Checks:
        n0 = self._since_reset
        mv = self._mv.push(a)
        w = self.p.window
        k = np.arange(a.shape[0])
        at_check = ((n0 + k + 1) % w == 0) & (n0 + k + 1 >= w)  # every W_s, windows full
        idx = np.flatnonzero(at_check)
        m = mv[idx]
        temp = np.all(m < self.thresholds, axis=1)  # eq. 7
        first = (n0 + idx + 1) == w  # the first check of this engine (after a start or a reset)
        final = final_static(temp, first, self.p.checks_needed, self._run_len)  # eq. 8
        if temp.size:
            last_dyn = np.flatnonzero(~temp)
            self._run_len = temp.size - 1 - int(last_dyn[-1]) if last_dyn.size else self._run_len + temp.size
        self._since_reset += a.shape[0]
        res = Checks(self._n + idx, t[idx], m, temp, final, first)
        self._n += a.shape[0]
        return res


def _cat(parts: list[Checks]) -> Checks:
    if not parts:
        z = np.zeros(0)
        return Checks(z.astype(int), z, np.zeros((0, 3)), z.astype(bool), z.astype(bool), z.astype(bool))
    return Checks(*(np.concatenate([getattr(p, f) for p in parts]) for f in Checks.__slots__))


def detect(t_s: np.ndarray, acc_g: np.ndarray, params: DetectorParams, sigma2: np.ndarray) -> Checks:
    """Batch front end: every check of a whole stream."""
    return FlightModeDetector(params, sigma2).push(t_s, acc_g)
