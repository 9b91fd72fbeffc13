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

Cost. Per window, MBGTD is O(N^2): two running sums over the N x N distance matrix give every
C_ij. MBCD is O(N^3): N^2 splits times N log terms, each a range sum of kernel weights extended one
sample at a time (the log of a range sum does not factor further); the seed's naive form is O(N^4).
Everything is vectorised over the windows: a block of windows is laid out window-last, (N, N, B),
and every step is one NumPy operation over the B windows; the Python loops run over the indices
inside one window only (N for MBGTD, N (N - 1) / 2 for MBCD), never over samples. Blocks bound the
memory (and keep the arrays cache-sized).

MBCD works in the log domain (``np.logaddexp``): with a narrow kernel the weights of
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

from functools import lru_cache

import numpy as np

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

BLOCK_ELEMENTS = 1 << 16  # windows per block x N^2: 512 KiB float arrays, cache-sized (2x faster than 8 MiB)


@lru_cache(maxsize=16)
def _split_masks(n: int):
    """For 0-based splits (i, j), 0 <= i < j <= n - 1: the valid-split mask (n, n), the sizes of the
    first window (j - i) and of the second (n - j)."""
    i = np.arange(n)[:, None]
    j = np.arange(n)[None, :]
    valid = i < j
    out = (valid, np.where(valid, j - i, 1), np.broadcast_to(n - j, (n, n)).copy())
    for a in out:
        a.flags.writeable = False  # cached: shared by every call
    return out


def _windows(x: np.ndarray, n: int):
    """Blocks of full windows of a 1-D array, window-last: (index of the block's first window, (n, B)
    array w with w[k, m] = x[first + m + k]), B x n^2 at most BLOCK_ELEMENTS."""
    m = x.shape[0] - n + 1
    b = max(1, BLOCK_ELEMENTS // (n * n))
    for s in range(0, m, b):
        e = min(m, s + b)
        yield s, x[np.arange(n)[:, None] + np.arange(s, e)]


# ---------------------------------------------------------------- MBGTD, eq. (9)-(10)
def mbgtd_merits(x: np.ndarray, window: int) -> np.ndarray:
    """V of every full window of a 1-D signal: (len(x) - window + 1,). Window-last layout, as
    :func:`mbcd_merits`."""
    n = window
    valid, size1, size2 = _split_masks(n)
    count = (size1 * size2).astype(float)[:, :, None]  # (j - i)(N - j + 1) in the seed's 1-based indices
    for_split = valid[:, :, None]
    out = np.empty(x.shape[0] - n + 1)
    for s, w in _windows(x, n):
        d = np.abs(w[:, None, :] - w[None, :, :])  # d[k, l] = |x_k - x_l|
        # r[k, j] = sum_{l=j}^{N-1} d_kl, accumulated from l = N-1 down
        r = np.empty_like(d)
        r[:, n - 1] = d[:, n - 1]
        for j in range(n - 2, -1, -1):
            np.add(r[:, j + 1], d[:, j], out=r[:, j])
        # t[i, j] = sum_{k=i}^{j-1} r[k, j] (for j > i), accumulated from k = j-1 down
        t = np.zeros_like(d)
        for i in range(n - 2, -1, -1):
            np.add(r[i, i + 1 :], t[i + 1, i + 1 :], out=t[i, i + 1 :])
        c = np.where(for_split, t / count, -np.inf)  # seed 001, eq. (9)
        out[s : s + w.shape[1]] = c.max(axis=(0, 1))  # seed 001, eq. (10)
    return out


# ---------------------------------------------------------------- MBCD, eq. (12)-(14)
def mbcd_merits(x: np.ndarray, window: int, bandwidth: float) -> np.ndarray:
    """V of every full window of a 1-D signal: (len(x) - window + 1,).

    Arrays are laid out window-last, (N, N, B), so that every step is one vector operation over the B
    windows of a block: the loops run over the indices inside a window only."""
    n = window
    valid, size1, size2 = _split_masks(n)
    # the constant part of eq. (13): sum over the N - j terms l of log(1/(N-j)) - log(1/(j-i))
    const = np.where(valid, size2 * (np.log(size1) - np.log(size2)), 0.0)[:, :, None]
    m_win = x.shape[0] - n + 1
    out = np.empty(m_win)
    for s, w in _windows(x, n):
        e = s + w.shape[1]
        z = (w[:, None, :] - w[None, :, :]) / bandwidth
        logw = -0.5 * z * z  # log w_lk, seed 001, eq. (12) (decaying; its constant cancels in eq. 13)
        # num[l, j] = log sum_{k=j}^{N-1} w_lk: the second window's kernel sum, accumulated from k = N-1 down
        num = np.empty_like(logw)
        num[:, n - 1] = logw[:, n - 1]
        for k in range(n - 2, -1, -1):
            np.logaddexp(num[:, k + 1], logw[:, k], out=num[:, k])
        acc = np.zeros((n, n, e - s))  # acc[i, j] = sum over l >= j of (num - den), l in increasing order
        den = np.empty((n, e - s))
        for l in range(1, n):
            for k in range(l):  # extend the first window to end at k: den[i] = log sum_{k'=i}^{k} w_lk'
                if k:
                    np.logaddexp(den[:k], logw[l, k], out=den[:k])
                den[k] = logw[l, k]
                acc[: k + 1, k + 1] += num[l, k + 1] - den[: k + 1]  # the term l of S_{i, j = k + 1}
        sij = np.where(valid[:, :, None], acc + const, -np.inf)  # seed 001, eq. (13)
        out[s:e] = sij.max(axis=(0, 1))  # seed 001, eq. (14)
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
        self.bandwidth = check_positive(bandwidth, "bandwidth", "Parzen kernel width in the signal's unit")

    def _merits(self, f):
        return mbcd_merits(f[:, 0], self.window, self.bandwidth)


def detect_mbgtd(
    t_s,
    acc_g,
    gyr_dps=None,
    *,
    window: int,
    threshold: float,
    signal: str = "acc",
    fs_hz: float | None = None,
) -> ActivityResult:
    """MBGTD over a whole stream: ``window`` in samples, ``threshold`` in the signal's unit."""
    fs = batch_rate(t_s, fs_hz, MBGTDStream.name)
    det = MBGTDStream(window=window, threshold=threshold, fs_hz=fs, signal=signal)
    return run_batch(det, t_s, acc_g, gyr_dps, window)


def detect_mbcd(
    t_s,
    acc_g,
    gyr_dps=None,
    *,
    window: int,
    threshold: float,
    bandwidth: float,
    signal: str = "acc",
    fs_hz: float | None = None,
) -> ActivityResult:
    """MBCD over a whole stream: ``window`` in samples, ``threshold`` >= 0 (nats), ``bandwidth`` the
    kernel width in the signal's unit."""
    fs = batch_rate(t_s, fs_hz, MBCDStream.name)
    det = MBCDStream(window=window, threshold=threshold, fs_hz=fs, bandwidth=bandwidth, signal=signal)
    return run_batch(det, t_s, acc_g, gyr_dps, window)
