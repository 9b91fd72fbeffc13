"""Seed 001's magnitude-based (in)activity detectors (section 2.1, eq. 1-5): AMVD, AMD, ARED, SHOD
and FRD, each a streaming class (``push`` chunks of any length) and a batch function (the whole
stream as one chunk through the same class: bit-identical for any chunking).

The figure of merit V(n) of sample n uses the window of the last N = ``window`` samples
k = n - N + 1 ... n (causal; see :mod:`~flightmode.detector.activity.common` for the conventions:
units g and deg/s, NaN merit and marker 1 before the first full window). A sample is static (marker
0) when V(n) < threshold, active (1) otherwise.

    AMVD  V = 1/N sum_k ||a_k - mean(a)||^2                                   seed 001, eq. (1)
    AMD   V = 1/(sigma_a^2 N) sum_k (||a_k|| - g)^2                           seed 001, eq. (2)
    ARED  V = 1/(sigma_w^2 N) sum_k ||w_k||^2                                 seed 001, eq. (3)
    SHOD  V = 1/N sum_k (||a_k - g mean(a)/||mean(a)||||^2 / sigma_a^2
                          + ||w_k||^2 / sigma_w^2)                            seed 001, eq. (4)
    FRD   V = LPF{ |HPF{x}| }                                                 seed 001, eq. (5)

Choices where the seed is silent:

- sigma_a, sigma_w (eq. 2-4) are the accelerometer's and gyroscope's noise standard deviations, given
  as ``sigma_acc_g`` and ``sigma_gyr_dps`` (required: there is no neutral default; pass 1.0 for an
  unscaled merit in g^2 or (deg/s)^2). The seed's own Table 1 thresholds (AMD 0.0008, SHOD 1.34)
  suggest it did not scale AMD by the noise variance (a merit scaled by it is ~1 at rest).
- g (eq. 2, 4) is 1 g: accelerations are in g. A sensor whose mean |a| at rest is not 1 g (scale-
  factor error) raises AMD's rest merit; calibrate first.
- SHOD with a zero window mean (free fall): the gravity direction is undefined; V = +inf (active).
- FRD (eq. 5; Veltink et al., the seed's ref. [17]) has no window in the seed (its inputs list,
  section 2.3.3, and Table 6 give FRD a threshold only) and no filters. Ours: a 2nd-order Butterworth
  high-pass at ``hp_cutoff_hz`` = 0.3 Hz (removes gravity and slow posture changes), rectification,
  and a 1st-order Butterworth low-pass at ``lp_cutoff_hz`` = 1 Hz (an RC-like envelope: its impulse
  response is positive, so V >= 0 and the threshold is >= 0). The high-pass starts in its steady
  state for the first sample (no start-up transient: a still stream gives V ~ 0 from sample 0), the
  low-pass at rest. FRD therefore has a merit from the first sample.
"""

from __future__ import annotations

import numpy as np

from flightmode.detector.activity.common import (
    GRAVITY_G,
    ActivityResult,
    StreamInput,
    WindowedStream,
    batch_rate,
    check_positive,
    check_signal,
    check_threshold,
    decide,
    flexible_signal,
    norm3,
    run_batch,
    signal_needs_gyro,
    sq_norm3,
    window_sums,
)
from flightmode.errors import DetectorError

SIGMA_ACC_UNIT = "the accelerometer noise standard deviation in g"
SIGMA_GYR_UNIT = "the gyroscope noise standard deviation in deg/s"


# ---------------------------------------------------------------- AMVD, eq. (1)
def amvd_merits(acc_g: np.ndarray, window: int) -> np.ndarray:
    """V of every full window of an (L, 3) array: the trace of the window's (population) covariance."""
    mean = window_sums(acc_g, window) / window  # a-bar_n
    m = mean.shape[0]
    s = sq_norm3(acc_g[0:m] - mean)
    for j in range(1, window):
        s += sq_norm3(acc_g[j : j + m] - mean)
    return s / window  # seed 001, eq. (1)


class AMVDStream(WindowedStream):
    """Acceleration Moving Variance Detector (seed 001, section 2.1.1). Merit in g^2."""

    name, unit = "AMVD", "g^2"

    def __init__(self, *, window: int, threshold: float, fs_hz: float):
        super().__init__(window=window, threshold=threshold, fs_hz=fs_hz, need_gyro=False)

    def _features(self, acc_g, gyr_dps):
        return acc_g

    def _merits(self, f):
        return amvd_merits(f, self.window)


def detect_amvd(
    t_s, acc_g, gyr_dps=None, *, window: int, threshold: float, fs_hz: float | None = None
) -> ActivityResult:
    """AMVD over a whole stream. ``window`` in samples, ``threshold`` in g^2 (the seed's Tables 1
    and 7: 0.017-0.019 g^2 at 16-26 samples); ``gyr_dps`` is not used."""
    fs = batch_rate(t_s, fs_hz, AMVDStream.name)
    return run_batch(AMVDStream(window=window, threshold=threshold, fs_hz=fs), t_s, acc_g, None, window)


# ---------------------------------------------------------------- AMD, eq. (2)
class AMDStream(WindowedStream):
    """Acceleration Magnitude Detector (seed 001, section 2.1.2). Merit dimensionless (in units of
    the noise variance sigma_acc_g^2)."""

    name, unit = "AMD", "(||a|| - g)^2 / sigma_a^2"

    def __init__(self, *, window: int, threshold: float, fs_hz: float, sigma_acc_g: float):
        super().__init__(window=window, threshold=threshold, fs_hz=fs_hz, need_gyro=False)
        self.sigma_acc_g = check_positive(sigma_acc_g, "sigma_acc_g", SIGMA_ACC_UNIT)

    def _features(self, acc_g, gyr_dps):
        d = norm3(acc_g) - GRAVITY_G
        return (d * d)[:, None]

    def _merits(self, f):
        return window_sums(f[:, 0], self.window) / (self.sigma_acc_g**2 * self.window)  # seed 001, eq. (2)


def detect_amd(
    t_s, acc_g, gyr_dps=None, *, window: int, threshold: float, sigma_acc_g: float, fs_hz: float | None = None
) -> ActivityResult:
    """AMD over a whole stream. ``sigma_acc_g``: accelerometer noise standard deviation (g);
    ``gyr_dps`` is not used."""
    fs = batch_rate(t_s, fs_hz, AMDStream.name)
    det = AMDStream(window=window, threshold=threshold, fs_hz=fs, sigma_acc_g=sigma_acc_g)
    return run_batch(det, t_s, acc_g, None, window)


# ---------------------------------------------------------------- ARED, eq. (3)
class AREDStream(WindowedStream):
    """Angular Rate Energy Detector (seed 001, section 2.1.3). Needs ``gyr_dps``."""

    name, unit = "ARED", "||w||^2 / sigma_w^2"

    def __init__(self, *, window: int, threshold: float, fs_hz: float, sigma_gyr_dps: float):
        super().__init__(window=window, threshold=threshold, fs_hz=fs_hz, need_gyro=True)
        self.sigma_gyr_dps = check_positive(sigma_gyr_dps, "sigma_gyr_dps", SIGMA_GYR_UNIT)

    def _features(self, acc_g, gyr_dps):
        return sq_norm3(gyr_dps)[:, None]

    def _merits(self, f):
        return window_sums(f[:, 0], self.window) / (self.sigma_gyr_dps**2 * self.window)  # seed 001, eq. (3)


def detect_ared(
    t_s,
    acc_g,
    gyr_dps=None,
    *,
    window: int,
    threshold: float,
    sigma_gyr_dps: float,
    fs_hz: float | None = None,
) -> ActivityResult:
    """ARED over a whole stream. ``sigma_gyr_dps``: gyroscope noise standard deviation (deg/s)."""
    fs = batch_rate(t_s, fs_hz, AREDStream.name)
    det = AREDStream(window=window, threshold=threshold, fs_hz=fs, sigma_gyr_dps=sigma_gyr_dps)
    return run_batch(det, t_s, acc_g, gyr_dps, window)


# ---------------------------------------------------------------- SHOD, eq. (4)
def shod_merits(f: np.ndarray, window: int, sigma_acc_g: float, sigma_gyr_dps: float) -> np.ndarray:
    """V of every full window of an (L, 4) array: acceleration (3 columns, g), ||w||^2 ((deg/s)^2)."""
    acc, w2 = f[:, :3], f[:, 3]
    mean = window_sums(acc, window) / window
    size = norm3(mean)
    with np.errstate(divide="ignore", invalid="ignore"):
        g_dir = GRAVITY_G * mean / size[:, None]  # g a-bar_n / ||a-bar_n||
    m = mean.shape[0]
    s_acc = sq_norm3(acc[0:m] - g_dir)
    for j in range(1, window):
        s_acc += sq_norm3(acc[j : j + m] - g_dir)
    s_gyr = window_sums(w2, window)
    v = (s_acc / sigma_acc_g**2 + s_gyr / sigma_gyr_dps**2) / window  # seed 001, eq. (4)
    return np.where(size > 0, v, np.inf)  # free fall: no gravity direction, certainly not still


class SHODStream(WindowedStream):
    """Stance Hypothesis Optimal Detector (seed 001, section 2.1.4). Needs ``gyr_dps``. Merit
    dimensionless."""

    name, unit = "SHOD", "dimensionless (noise-variance units)"

    def __init__(
        self, *, window: int, threshold: float, fs_hz: float, sigma_acc_g: float, sigma_gyr_dps: float
    ):
        super().__init__(window=window, threshold=threshold, fs_hz=fs_hz, need_gyro=True)
        self.sigma_acc_g = check_positive(sigma_acc_g, "sigma_acc_g", SIGMA_ACC_UNIT)
        self.sigma_gyr_dps = check_positive(sigma_gyr_dps, "sigma_gyr_dps", SIGMA_GYR_UNIT)

    def _features(self, acc_g, gyr_dps):
        return np.column_stack([acc_g, sq_norm3(gyr_dps)])

    def _merits(self, f):
        return shod_merits(f, self.window, self.sigma_acc_g, self.sigma_gyr_dps)


def detect_shod(
    t_s,
    acc_g,
    gyr_dps=None,
    *,
    window: int,
    threshold: float,
    sigma_acc_g: float,
    sigma_gyr_dps: float,
    fs_hz: float | None = None,
) -> ActivityResult:
    """SHOD over a whole stream (noise standard deviations in g and deg/s)."""
    fs = batch_rate(t_s, fs_hz, SHODStream.name)
    det = SHODStream(
        window=window, threshold=threshold, fs_hz=fs, sigma_acc_g=sigma_acc_g, sigma_gyr_dps=sigma_gyr_dps
    )
    return run_batch(det, t_s, acc_g, gyr_dps, window)


# ---------------------------------------------------------------- FRD, eq. (5)
FRD_HP_ORDER = 2  # Butterworth high-pass order (our choice; the seed gives no filter)
FRD_LP_ORDER = 1  # first order: a positive impulse response keeps V >= 0


class FRDStream:
    """Filtered Rectifier Detector (seed 001, section 2.1.5): V = LPF{|HPF{x}|} of the flexible input
    ``signal``; the merit is in the signal's unit (g for "acc", deg/s for "gyr"). Filter state is
    carried between pushes (``scipy.signal.lfilter`` with ``zi``: bit-identical for any chunking; at
    these low orders the transfer-function form is well conditioned)."""

    name = "FRD"

    def __init__(
        self,
        *,
        threshold: float,
        fs_hz: float,
        signal: str = "acc",
        hp_cutoff_hz: float = 0.3,
        lp_cutoff_hz: float = 1.0,
    ):
        from scipy.signal import butter

        self.signal = check_signal(signal)
        self.threshold = check_threshold(threshold, True, "the unit of the input signal")
        self._input = StreamInput(fs_hz, signal_needs_gyro(signal), self.name)
        fs = self._input.fs_hz
        for name, f in (("hp_cutoff_hz", hp_cutoff_hz), ("lp_cutoff_hz", lp_cutoff_hz)):
            check_positive(f, name, "Hz")
            if f >= fs / 4:  # below a quarter of the rate the first-order low-pass stays positive
                raise DetectorError(
                    f"FRD: {name} = {f} Hz must be below a quarter of the sampling rate ({fs / 4:g} Hz)"
                )
        self.hp_cutoff_hz, self.lp_cutoff_hz = float(hp_cutoff_hz), float(lp_cutoff_hz)
        self._hp = butter(FRD_HP_ORDER, hp_cutoff_hz, "highpass", fs=fs)  # (b, a)
        self._lp = butter(FRD_LP_ORDER, lp_cutoff_hz, "lowpass", fs=fs)
        self._zi_hp: np.ndarray | None = None
        self._zi_lp = np.zeros(FRD_LP_ORDER)

    @property
    def n_samples(self) -> int:
        return self._input.n

    def push(self, t_s, acc_g, gyr_dps=None) -> ActivityResult:
        from scipy.signal import lfilter, lfilter_zi

        _, a, g = self._input.take(t_s, acc_g, gyr_dps)
        x = flexible_signal(self.signal, a, g)
        self._input.commit()
        if x.shape[0] == 0:
            return ActivityResult(np.zeros(0, np.int8), np.zeros(0))
        if self._zi_hp is None:  # the high-pass in its steady state for the first sample
            self._zi_hp = lfilter_zi(*self._hp) * x[0]
        y, self._zi_hp = lfilter(*self._hp, x, zi=self._zi_hp)  # HPF
        v, self._zi_lp = lfilter(*self._lp, np.abs(y), zi=self._zi_lp)  # RECT, LPF: seed 001, eq. (5)
        return ActivityResult(decide(v, self.threshold), v)


def detect_frd(
    t_s,
    acc_g,
    gyr_dps=None,
    *,
    threshold: float,
    signal: str = "acc",
    hp_cutoff_hz: float = 0.3,
    lp_cutoff_hz: float = 1.0,
    fs_hz: float | None = None,
) -> ActivityResult:
    """FRD over a whole stream (no window: the seed gives FRD none). ``threshold`` in the signal's
    unit (g for "acc")."""
    fs = batch_rate(t_s, fs_hz, FRDStream.name)
    det = FRDStream(
        threshold=threshold, fs_hz=fs, signal=signal, hp_cutoff_hz=hp_cutoff_hz, lp_cutoff_hz=lp_cutoff_hz
    )
    return run_batch(det, t_s, acc_g, gyr_dps, None)
