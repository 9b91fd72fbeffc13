"""The interface shared by seed 001's nine (in)activity detectors (section 2.3.3, "Workflow of the
Algorithms"): the result, the decision rule, the input checks, the flexible input signal, and the
sliding-window stream that six of the nine detectors run on.

Conventions (the same for every detector, batch and streaming):

- Inputs: ``t_s`` (n,) seconds; ``acc_g`` (n, 3) specific force in g; ``gyr_dps`` (n, 3) angular rate
  in deg/s, or None. These are the seed's own units: its synthesizer sets the static acceleration
  magnitude to 1 g (section 3.1.1), and its MBGTD thresholds (Table 4: acceleration 1.13, angular
  rate 85.0, sum 84.9) only make sense for an angular rate in deg/s (85 rad/s would be 4,900 deg/s,
  ten times the +-500 deg/s range of its gyroscopes, section 3.2). No conversion is made.
- Windows are counted in samples. Every detector is *causal*: the figure of merit of sample k uses
  samples <= k only (the window ends at k), so a stream can be decided as it arrives.
- Before a detector has its first figure of merit (the first ``window - 1`` samples; longer for the
  spectrum detectors) the merit is NaN and the marker is 1 (activity). This is the seed's decision
  rule (step IV: "lower than the threshold -> static 0, otherwise active 1") applied to a missing
  value, and the safe side for flightmode: "static" is what allows a transmission, so it is never
  claimed without evidence.
- The flexible input (FRD, LTSD, FSD, MBGTD, MBCD; section 3.1.2): ``signal`` is ``"acc"`` (|a| in
  g), ``"gyr"`` (|w| in deg/s), ``"sum"`` (|a| + |w|) or ``"product"`` (|a| |w|), the seed's four
  combinations; the sum adds g to deg/s numerically, as the seed does.
- A time gap (a step over 1.5 sample periods) or a step back in time is an error, never silently
  bridged: the windows would mix samples from either side of it.

Exactness of batch against stream: the batch front ends push the whole stream as one chunk through
the streaming class, and every operation on a window is either elementwise or an accumulation in a
fixed order (:func:`window_sums`, running sums written as loops over the offsets inside a window,
``np.cumsum``), never a reduction whose order could depend on how many windows are computed together
(the maxima are exact in any order). Results are bit-identical for any chunking.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Protocol, runtime_checkable

import numpy as np

from flightmode.errors import DetectorError, did_you_mean, first_nonfinite

SIGNALS = ("acc", "gyr", "sum", "product")  # the flexible input (seed 001, section 3.1.2)
GRAVITY_G = 1.0  # g in eq. (2) and (4), in the unit of acc_g ("1 g or 9.8 m/s^2", section 2.1.2)
GAP_PERIODS = 1.5  # a step longer than this many sample periods is a gap
RATE_TOLERANCE = 0.01  # a given fs_hz must match the stream's median step to 1 %


@dataclass(frozen=True, slots=True)
class ActivityResult:
    """Per sample: ``marker`` (n,) int8, 1 = activity, 0 = inactivity (static); ``merit`` (n,) float64,
    the figure of merit (NaN where the detector has none yet)."""

    marker: np.ndarray
    merit: np.ndarray


@runtime_checkable
class ActivityStream(Protocol):
    """What every streaming detector of seed 001 offers (the batch function ``detect_<name>`` is one
    ``push`` of the whole stream)."""

    @property
    def n_samples(self) -> int: ...

    def push(self, t_s, acc_g, gyr_dps=None) -> ActivityResult: ...


def decide(merit: np.ndarray, threshold: float) -> np.ndarray:
    """Seed 001, section 2.3.3 step (IV): merit < threshold -> 0 (static), else 1 (active); a NaN merit
    is not lower than the threshold, so it is active."""
    return (~(merit < threshold)).astype(np.int8)


# ---------------------------------------------------------------- parameter checks
def check_window(window, name: str = "window") -> int:
    if isinstance(window, bool) or not isinstance(window, (int, np.integer, float)) or int(window) != window:
        raise DetectorError(f"{name} = {window!r}: must be a whole number of samples")
    if window < 2:
        raise DetectorError(f"{name} = {window} samples: a window needs at least 2 samples")
    return int(window)


def check_threshold(threshold, nonnegative: bool, unit: str) -> float:
    try:
        thr = float(threshold)
    except (TypeError, ValueError):
        raise DetectorError(f"threshold = {threshold!r}: must be a number ({unit})") from None
    if not math.isfinite(thr):
        raise DetectorError(f"threshold = {threshold}: must be finite ({unit})")
    if nonnegative and thr < 0:
        raise DetectorError(
            f"threshold = {thr:g}: this figure of merit is never negative ({unit}), so a negative "
            "threshold marks every sample active; use a threshold >= 0"
        )
    return thr


def check_positive(value, name: str, unit: str) -> float:
    try:
        v = float(value)
    except (TypeError, ValueError):
        raise DetectorError(f"{name} = {value!r}: must be a number ({unit})") from None
    if not (math.isfinite(v) and v > 0):
        raise DetectorError(f"{name} = {value}: must be finite and > 0 ({unit})")
    return v


def check_signal(signal: str) -> str:
    if signal not in SIGNALS:
        raise DetectorError(
            f"signal = {signal!r}: use one of {', '.join(SIGNALS)}{did_you_mean(signal, SIGNALS)}"
        )
    return signal


def signal_needs_gyro(signal: str) -> bool:
    return signal != "acc"


# ---------------------------------------------------------------- elementwise maths
def norm3(v: np.ndarray) -> np.ndarray:
    """Euclidean norm of the rows of an (n, 3) array, written out (a fixed order of operations)."""
    return np.sqrt(sq_norm3(v))


def sq_norm3(v: np.ndarray) -> np.ndarray:
    return v[:, 0] * v[:, 0] + v[:, 1] * v[:, 1] + v[:, 2] * v[:, 2]


def flexible_signal(signal: str, acc_g: np.ndarray, gyr_dps: np.ndarray | None) -> np.ndarray:
    """The seed's four inputs of the flexible detectors (section 3.1.2), one value per sample."""
    if signal == "acc":
        return norm3(acc_g)
    assert gyr_dps is not None  # the callers refuse a stream without gyr_dps for the other signals
    w = norm3(gyr_dps)
    if signal == "gyr":
        return w
    a = norm3(acc_g)
    return a + w if signal == "sum" else a * w


def window_sums(v: np.ndarray, window: int) -> np.ndarray:
    """``s[m] = v[m] + v[m + 1] + ... + v[m + window - 1]`` along axis 0, added in that order for every
    m: the same bits for a window whatever else is computed with it (a loop over the window's
    offsets, each step a vector operation over all windows)."""
    m = v.shape[0] - window + 1
    s = v[0:m].copy()
    for j in range(1, window):
        s += v[j : j + m]
    return s


# ---------------------------------------------------------------- the input stream
class StreamInput:
    """Checks chunks of (t_s, acc_g, gyr_dps) and the time axis across chunks; counts samples. A
    detector calls :meth:`take` first and :meth:`commit` once it has processed the chunk, so a chunk
    that is refused (here or by the detector) leaves the stream as it was."""

    def __init__(self, fs_hz: float, need_gyro: bool, who: str):
        self.fs_hz = check_positive(fs_hz, "fs_hz", "the sampling rate in Hz")
        self.need_gyro = need_gyro
        self.who = who
        self.n = 0  # samples accepted so far: the global index of the next one
        self._t_last: float | None = None
        self._pending: tuple[int, float | None] = (0, None)

    def take(self, t_s, acc_g, gyr_dps) -> tuple[np.ndarray, np.ndarray, np.ndarray | None]:
        """The chunk as float arrays, or DetectorError naming the first thing wrong with it."""
        t = np.asarray(t_s, dtype=float)
        a = np.asarray(acc_g, dtype=float)
        if t.ndim != 1:
            raise DetectorError(f"{self.who}: t_s must be a 1-D array of seconds, got shape {t.shape}")
        if a.shape != (t.shape[0], 3):
            raise DetectorError(
                f"{self.who}: acc_g must be an ({t.shape[0]}, 3) array (one row per t_s), got shape {a.shape}"
            )
        g = None
        if self.need_gyro:
            if gyr_dps is None:
                raise DetectorError(
                    f"{self.who} needs the angular rate: provide gyr_dps (a sensor preset with a gyroscope)"
                )
            g = np.asarray(gyr_dps, dtype=float)
            if g.shape != (t.shape[0], 3):
                raise DetectorError(
                    f"{self.who}: gyr_dps must be an ({t.shape[0]}, 3) array (one row per t_s), "
                    f"got shape {g.shape}"
                )
        for name, x in (("t_s", t), ("acc_g", a), ("gyr_dps", g)):
            if x is not None and (i := first_nonfinite(x)) is not None:
                raise DetectorError(
                    f"{self.who}: NaN or inf in {name} at sample {self.n + i}: clean the stream"
                )
        if t.shape[0]:
            tt = t if self._t_last is None else np.concatenate([[self._t_last], t])
            if tt.shape[0] > 1:
                dt = np.diff(tt)
                period = 1.0 / self.fs_hz
                if dt.min() <= 0 or dt.max() > GAP_PERIODS * period:
                    self._bad_step(tt, dt, period, self.n - (tt.shape[0] - t.shape[0]))
        self._pending = (t.shape[0], float(t[-1]) if t.shape[0] else self._t_last)
        return t, a, g

    def commit(self) -> None:
        """The chunk last taken is processed: count it."""
        self.n += self._pending[0]
        self._t_last = self._pending[1]
        self._pending = (0, self._t_last)

    def _bad_step(self, tt: np.ndarray, dt: np.ndarray, period: float, off: int) -> None:
        """Raise for the first step back in time or gap (``off``: the global index of ``tt[0]``)."""
        back = np.flatnonzero(dt <= 0)
        gap = np.flatnonzero(dt > GAP_PERIODS * period)
        if back.size and (not gap.size or back[0] < gap[0]):
            i = int(back[0])
            raise DetectorError(
                f"{self.who}: time is not increasing at sample {off + i + 1} (t = {tt[i + 1]:.6g} s "
                f"after {tt[i]:.6g} s)"
            )
        i = int(gap[0])
        raise DetectorError(
            f"{self.who}: a gap of {dt[i]:.6g} s before sample {off + i + 1} (t = {tt[i + 1]:.6g} s; "
            f"the sample period is {period:.6g} s): split the stream at the gap and start a new detector"
        )


def batch_rate(t_s, fs_hz: float | None, who: str) -> float:
    """The sampling rate of a whole stream: 1 / median step when ``fs_hz`` is None, else ``fs_hz``
    checked against the median step (1 %). Gaps are then steps over 1.5 / rate."""
    t = np.asarray(t_s, dtype=float)
    if t.ndim != 1:
        raise DetectorError(f"{who}: t_s must be a 1-D array of seconds, got shape {t.shape}")
    if (i := first_nonfinite(t)) is not None:
        raise DetectorError(f"{who}: NaN or inf in t_s at sample {i}: clean the stream")
    if t.shape[0] < 2:
        raise DetectorError(f"{who}: {t.shape[0]} sample(s): a stream needs at least 2 samples")
    dt = np.diff(t)
    if np.any(dt <= 0):
        i = int(np.flatnonzero(dt <= 0)[0])
        raise DetectorError(
            f"{who}: time is not increasing at sample {i + 1} (t = {t[i + 1]:.6g} s after {t[i]:.6g} s)"
        )
    med = float(np.median(dt))
    if fs_hz is None:
        return 1.0 / med
    fs = check_positive(fs_hz, "fs_hz", "the sampling rate in Hz")
    if abs(med * fs - 1.0) > RATE_TOLERANCE:
        raise DetectorError(
            f"{who}: the stream is sampled at {1.0 / med:.6g} Hz but fs_hz = {fs:g}: "
            "give the stream's rate, or None"
        )
    return fs


def check_length(n: int, window: int, who: str) -> None:
    if window > n:
        raise DetectorError(f"{who}: window = {window} samples is longer than the signal ({n} samples)")


# ---------------------------------------------------------------- the sliding-window stream
class WindowedStream:
    """Base of the detectors whose figure of merit at sample k is a function of the last ``window``
    samples (AMVD, AMD, ARED, SHOD, MBGTD, MBCD). A subclass gives ``_features`` (per-sample values,
    (n, F)) and ``_merits`` (the merit of every full window of an (L, F) array, (L - window + 1,));
    the stream keeps the last ``window - 1`` feature rows between pushes."""

    name = "detector"
    unit = ""
    nonnegative = True

    def __init__(self, *, window: int, threshold: float, fs_hz: float, need_gyro: bool):
        self.window = check_window(window)
        self.threshold = check_threshold(threshold, self.nonnegative, self.unit)
        self._input = StreamInput(fs_hz, need_gyro, self.name)
        self._tail: np.ndarray | None = None

    @property
    def n_samples(self) -> int:
        """Samples pushed so far."""
        return self._input.n

    def push(self, t_s, acc_g, gyr_dps=None) -> ActivityResult:
        """The marker and merit of every sample of the chunk (any length, even 0)."""
        _, a, g = self._input.take(t_s, acc_g, gyr_dps)
        f = self._features(a, g)
        n = f.shape[0]
        buf = f if self._tail is None else np.concatenate([self._tail, f])
        merit = np.full(n, np.nan)
        if buf.shape[0] >= self.window:
            m = self._merits(buf)
            merit[n - m.shape[0] :] = m
        self._tail = buf[max(0, buf.shape[0] - (self.window - 1)) :].copy()
        self._input.commit()
        return ActivityResult(decide(merit, self.threshold), merit)

    def _features(self, acc_g: np.ndarray, gyr_dps: np.ndarray | None) -> np.ndarray:
        raise NotImplementedError

    def _merits(self, f: np.ndarray) -> np.ndarray:
        raise NotImplementedError


# ---------------------------------------------------------------- causal or centred
ALIGNMENTS = ("causal", "centred")


def centre_merit(merit: np.ndarray, lag: int) -> np.ndarray:
    """A causal merit moved ``lag`` samples earlier: ``out[k] = merit[k + lag]``, NaN (active) for
    the last ``lag`` samples, whose centred window runs past the end of the stream.

    The detectors here are causal (module docstring): the merit of sample k is that of the window
    ending at k. Seed 001 writes V(n) as a function of "the frame at instant n" (section 2.1.1, eq.
    1) without saying where n sits in its frame, and its one explicit window is symmetric: the
    long-term envelope of eq. (6) takes the frames n - N .. n + N. The centred reading gives sample
    k the merit of the window centred on it, which is the causal merit ``lag`` samples later (a
    batch operation: a stream can only have it ``lag`` samples late). ``lag`` per detector is
    :func:`flightmode.detector.activity.montecarlo.merit_lag`."""
    m = np.asarray(merit, dtype=float)
    lag = int(lag)
    if lag < 0:
        raise DetectorError(f"lag = {lag}: a causal merit is centred by moving it earlier (lag >= 0)")
    if lag == 0:
        return m.copy()
    out = np.full(m.shape, np.nan)
    if lag < m.shape[0]:
        out[: m.shape[0] - lag] = m[lag:]
    return out


def run_batch(stream, t_s, acc_g, gyr_dps, window: int | None) -> ActivityResult:
    """The batch front end: the whole stream pushed as one chunk (``window`` checked against its
    length first)."""
    if window is not None:
        check_length(np.asarray(t_s).shape[0], window, stream.name)
    return stream.push(t_s, acc_g, gyr_dps)
