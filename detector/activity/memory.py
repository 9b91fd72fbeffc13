"""Seed 001's memory-based (in)activity detectors (section 2.3, eq. 9-14; Nikovski and Jain, the
seed's ref. [25]): the Memory-Based Graph Theoretic Detector (MBGTD) and the Memory-Based CUSUM
Detector (MBCD), batch and streaming.

Both look at the last N = ``window`` values x_1 .. x_N of the flexible input (``signal``: |a|, |w|,
their sum or product; a scalar per sample), and at every split of that buffer by a pair
1 <= i < j <= N into a first window x_i .. x_{j-1} and a second window x_j .. x_N:

    MBGTD  C_ij = sum_{k=i}^{j-1} sum_{l=j}^{N} d_kl / ((j - i)(N - j + 1))     seed 001, eq. (9)
           V = max_{i<j} C_ij                                                  seed 001, eq. (10)
    MBCD   S_ij = sum_{l=j}^{N} log( mean_{k=j..N} w_lk / mean_{k=i..j-1} w_lk )  seed 001, eq. (13)
           V = max_{i<j} S_ij                                                  seed 001, eq. (14)

with d_kl = |x_k - x_l| (the Euclidean distance of two scalars) and the Parzen (Gaussian) kernel
weight w_lk = exp(-(x_l - x_k)^2 / (2 lambda^2)) of eq. (12) (its normalising constant
1 / (N sqrt(2 pi) lambda) cancels in the ratio of eq. (13)). Both merits are >= 0 (MBCD: the split
j = N alone gives -log(mean w) >= 0 since w <= 1), so the threshold is >= 0.

Cost. Per window, MBGTD is O(N^2): two cumulative sums over the N x N distance matrix give every
C_ij. MBCD is O(N^3): N^2 splits times N log terms, each a range sum of kernel weights read from a
cumulative sum (the log of a range sum does not factor further); the seed's naive form is O(N^4).
Everything is vectorised over all windows (``sliding_window_view`` and broadcasting), in blocks of
windows that bound the memory; the only Python loops run over offsets inside one window.

MBCD works in the log domain (``np.logaddexp.accumulate``): with a narrow kernel the weights of
distant samples underflow to 0 in double precision (d > 38 lambda), and a range sum of them would
give log(0) = -inf. In the log domain S_ij stays finite and exact.

Where the seed is garbled or silent:

- "alpha_{a,b} = {x_a, x_b}" (section 2.3.1) reads {x_a, ..., x_b}: all samples from a to b.
- Eq. (12) prints the kernel as e^{+1/2 (||x_i - x_k|| / lambda)^2}; a Parzen (Gaussian) kernel
  decays, so the exponent is negative (as implemented).
- lambda "stands for the standard deviation of the distribution": we take it as a fixed kernel
  bandwidth ``bandwidth`` in the signal's unit (required). A bandwidth re-estimated from each window
  would make the merit scale-free, and a still window of noise would then score like an active one.
  (The seed's Table 5 MBCD thresholds, 1.7e-6 for |a| in g, are consistent with a bandwidth of
  order 1 g, where every weight is close to 1.)
- Eq. (11)'s "the change point will be detected when g_k <= h" is CUSUM's g_k >= h; only eq. (13)-(14)
  are used here.
- The sums in eq. (13) keep the k = l term (w_ll = 1) as printed (no leave-one-out).
"""

from __future__ import annotations

import numpy as np
from numpy.lib.stride_tricks import sliding_window_view

from flightmode.detector.activity.common import (
    ActivityResult,
    WindowedStream,
    batch_rate,
    check_positive,
    check_signal,
    flexible_signal,
    run_batch,
    signal_needs_gyro,
)

BLOCK_ELEMENTS = 1 << 20  # windows per block x N^2 (8 MiB per float array)


def _split_masks(n: int):
    """For 0-based splits (i, j), 0 <= i < j <= n - 1: the valid-split mask (n, n), the sizes of the
    first window (j - i) and of the second (n - j)."""
    i = np.arange(n)[:, None]
    j = np.arange(n)[None, :]
    valid = i < j
    return valid, np.where(valid, j - i, 1), np.broadcast_to(n - j, (n, n))


def _upper(n: int) -> np.ndarray:
    """(n, n) mask of k >= i (row i, column k)."""
    return np.arange(n)[None, :] >= np.arange(n)[:, None]


def _blocks(m: int, n: int):
    b = max(1, BLOCK_ELEMENTS // (n * n))
    return [(s, min(m, s + b)) for s in range(0, m, b)]


# ---------------------------------------------------------------- MBGTD, eq. (9)-(10)
def mbgtd_merits(x: np.ndarray, window: int) -> np.ndarray:
    """V of every full window of a 1-D signal: (len(x) - window + 1,)."""
    n = window
    win = sliding_window_view(x, n)  # (M, N): window m holds x[m .. m + N - 1]
    valid, size1, size2 = _split_masks(n)
    count = (size1 * size2).astype(float)  # (j - i)(N - j + 1) in the seed's 1-based indices
    out = np.empty(win.shape[0])
    for s, e in _blocks(win.shape[0], n):
        w = win[s:e]
        d = np.abs(w[:, :, None] - w[:, None, :])  # d_kl
        # r[k, j] = sum_{l >= j} d_kl ; then only k < j counts
        r = np.cumsum(d[:, :, ::-1], axis=2)[:, :, ::-1]
        r = np.where(valid, r, 0.0)
        # t[i, j] = sum_{k >= i} r[k, j] = sum_{k=i}^{j-1} sum_{l=j}^{N-1} d_kl
        t = np.cumsum(r[:, ::-1, :], axis=1)[:, ::-1, :]
        c = np.where(valid, t / count, -np.inf)  # seed 001, eq. (9)
        out[s:e] = c.max(axis=(1, 2))  # seed 001, eq. (10)
    return out


# ---------------------------------------------------------------- MBCD, eq. (12)-(14)
def mbcd_merits(x: np.ndarray, window: int, bandwidth: float) -> np.ndarray:
    """V of every full window of a 1-D signal: (len(x) - window + 1,)."""
    n = window
    win = sliding_window_view(x, n)
    valid, size1, size2 = _split_masks(n)
    # the constant part of eq. (13): sum over the N - j terms l of log(1/(N-j)) - log(1/(j-i))
    const = np.where(valid, size2 * (np.log(size1) - np.log(size2)), 0.0)
    out = np.empty(win.shape[0])
    for s, e in _blocks(win.shape[0], n):
        w = win[s:e]
        z = (w[:, :, None] - w[:, None, :]) / bandwidth
        logw = -0.5 * z * z  # log w_lk, seed 001, eq. (12) (decaying; constant dropped)
        # num[l, j] = log sum_{k=j}^{N-1} w_lk (reverse accumulation over k)
        num = np.logaddexp.accumulate(logw[:, :, ::-1], axis=2)[:, :, ::-1]
        acc = np.zeros((e - s, n, n))  # sum over l of (num - den), per split (i, j)
        for l in range(1, n):  # l >= j >= 1
            # den[i, k] = log sum_{k'=i}^{k} w_lk' for i <= k <= l - 1 (forward from each i)
            row = np.where(_upper(l), logw[:, l, None, :l], -np.inf)  # row[i, k] = log w_lk for k >= i
            den = np.logaddexp.accumulate(row, axis=2)  # den[i, j - 1]: the first window i .. j-1
            term = num[:, l, None, 1 : l + 1] - den  # (., i = 0..l-1, j = 1..l)
            acc[:, :l, 1 : l + 1] += np.where(valid[:l, 1 : l + 1], term, 0.0)
        sij = np.where(valid, acc + const, -np.inf)  # seed 001, eq. (13)
        out[s:e] = sij.max(axis=(1, 2))  # seed 001, eq. (14)
    return out


# ---------------------------------------------------------------- streams and batch front ends
class _FlexibleWindowed(WindowedStream):
    def __init__(self, *, window: int, threshold: float, fs_hz: float, signal: str):
        self.signal = check_signal(signal)
        super().__init__(window=window, threshold=threshold, fs_hz=fs_hz, need_gyro=signal_needs_gyro(signal))

    def _features(self, acc_g, gyr_dps):
        return flexible_signal(self.signal, acc_g, gyr_dps)[:, None]


class MBGTDStream(_FlexibleWindowed):
    """Memory-Based Graph Theoretic Detector (seed 001, section 2.3.1): streaming. Merit in the
    signal's unit (g for "acc", deg/s for "gyr")."""

    name, unit = "MBGTD", "the unit of the input signal"

    def __init__(self, *, window: int, threshold: float, fs_hz: float, signal: str = "acc"):
        super().__init__(window=window, threshold=threshold, fs_hz=fs_hz, signal=signal)

    def _merits(self, f):
        return mbgtd_merits(f[:, 0], self.window)


class MBCDStream(_FlexibleWindowed):
    """Memory-Based CUSUM Detector (seed 001, section 2.3.2): streaming. Merit: a log-likelihood
    ratio (nats). ``bandwidth``: the Parzen kernel's lambda, in the signal's unit."""

    name, unit = "MBCD", "a log-likelihood ratio"

    def __init__(self, *, window: int, threshold: float, fs_hz: float, bandwidth: float, signal: str = "acc"):
        super().__init__(window=window, threshold=threshold, fs_hz=fs_hz, signal=signal)
        self.bandwidth = check_positive(bandwidth, "bandwidth", "the Parzen kernel width in the signal's unit")

    def _merits(self, f):
        return mbcd_merits(f[:, 0], self.window, self.bandwidth)


def detect_mbgtd(t_s, acc_g, gyr_dps=None, *, window: int, threshold: float, signal: str = "acc",
                 fs_hz: float | None = None) -> ActivityResult:
    """MBGTD over a whole stream: ``window`` in samples, ``threshold`` in the signal's unit."""
    fs = batch_rate(t_s, fs_hz, MBGTDStream.name)
    det = MBGTDStream(window=window, threshold=threshold, fs_hz=fs, signal=signal)
    return run_batch(det, t_s, acc_g, gyr_dps, window)


def detect_mbcd(t_s, acc_g, gyr_dps=None, *, window: int, threshold: float, bandwidth: float,
                signal: str = "acc", fs_hz: float | None = None) -> ActivityResult:
    """MBCD over a whole stream: ``window`` in samples, ``threshold`` >= 0 (nats), ``bandwidth`` the
    kernel width in the signal's unit."""
    fs = batch_rate(t_s, fs_hz, MBCDStream.name)
    det = MBCDStream(window=window, threshold=threshold, fs_hz=fs, bandwidth=bandwidth, signal=signal)
    return run_batch(det, t_s, acc_g, gyr_dps, window)
