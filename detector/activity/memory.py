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

Cost: O(N^2) per sample for both (N^2 / 2 splits; the splits themselves are what eq. 10 and 14
maximise over, so no exact form is cheaper), computed incrementally along the stream. The memory is
the buffer of the last N readings (section 2.3.1, "a buffer which is filled with the last N sensor
readings"); nothing older enters a merit. Write a split of the buffer ending at sample e by h = N - j
(the second window is x_{e-h} .. x_e) and g = j - i (the first window's length). Both numerators
are sums over the second window's samples l of a term that depends on l and on the first window only:

    eq. (9)   sum_{l=j}^{N} R_l,  R_l = sum_{k=i}^{j-1} d_kl
    eq. (13)  sum_{l=j}^{N} log sum_{k=i}^{j-1} w_lk   (the denominator's part)

and R_l, for the sample l and the first window g samples long ending h - (e - l) + 1 samples before l,
does not depend on where the buffer ends. So each sample's R (or log R) is computed once, for every
(h, g) with h + g <= N - 1, as running sums over the samples before it (m = h first), and the
numerator of split (h, g) at sample e is the diagonal sum R[e - h, 0, g] + R[e - h + 1, 1, g] + ... +
R[e, h, g], accumulated oldest first, row after row (:func:`_diagonal_sums`). The numerator's part of
eq. (13), sum_{l=j}^{N} log sum_{k=j}^{N} w_lk, depends on j and e only: for each l its kernel sum
over the second window is 1 (w_ll) + a running sum backwards + a running sum forwards, N^2 / 2 logs
per sample. Every sum is accumulated in one fixed order whatever the block, so a merit is a function
of its window's samples only, to the bit. Arrays are laid out window-last, (g, h, samples): the loops
run over the offsets inside a window (N), each step one vector operation over the block's samples,
never over samples; blocks of windows (BLOCK_ELEMENTS) bound the memory.
Written as printed, both cost O(N^4) per window; the previous vectorised form here was O(N^2)
(MBGTD) and O(N^3) (MBCD) per sample.

MBCD's first-window sums are taken in the plain domain and, where one falls below TINY (its terms
may have underflowed: with a narrow kernel the weights of distant samples are 0 in double precision,
d > 38 lambda, and log(0) = -inf), again in the log domain as a running ``np.logaddexp``: S_ij stays
finite and exact. The second window's sums contain w_ll = 1 and never underflow.

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

BLOCK_ELEMENTS = (
    1 << 20
)  # windows per block x N^2: 8 MiB arrays (on a flight 1 << 16 is 2.3x slower, 1 << 21 alike)
TINY = 1e-280  # a kernel range sum below this is taken again in the log domain (see _log_ranges)


def _band(x: np.ndarray, n: int, s: int, e: int) -> np.ndarray:
    """The differences x_l - x_{l-1-m}, m = 0 .. n - 2, of every sample l that the windows ending at
    s .. e - 1 (0-based, s >= n - 1) need, window-last: (n - 1, e - s + n - 2), column r is sample
    l = s - n + 2 + r. Samples before x's start are NaN (they only ever reach splits outside a window)."""
    lo = s - (2 * n - 3)
    xb = x[max(0, lo) : e]
    if lo < 0:
        xb = np.concatenate([np.full(-lo, np.nan), xb])
    sw = np.lib.stride_tricks.sliding_window_view(xb, n)
    return np.ascontiguousarray((sw[:, -1:] - sw[:, -2::-1]).T)


def _running_sums(v: np.ndarray, n: int) -> np.ndarray:
    """q[g-1, h, r] = sum_{m=h}^{h+g-1} v[m, r], added from m = h on (np.cumsum's order), for the
    splits h + g <= n - 1 (the other entries are left unset and never read): (n - 1, n - 1, R)."""
    q = np.empty((n - 1, n - 1, v.shape[1]))
    q[0] = v
    for gi in range(1, n - 1):
        k = n - 1 - gi
        np.add(q[gi - 1, :k], v[gi : gi + k], out=q[gi, :k])
    return q


def _diagonal_sums(q: np.ndarray, n: int) -> np.ndarray:
    """In place: q[g-1, h, r] += q[g-1, h - 1, r - 1], h = 1 .. n - 2 in turn, so that q[g-1, h, r]
    becomes the sum q[g-1, 0, r - h] + q[g-1, 1, r - h + 1] + ... + q[g-1, h, r] of one split's range
    terms over the samples l = e - h .. e, oldest first (module docstring). Columns whose chain would
    start before the block are dropped: (n - 1, n - 1, R - n + 2)."""
    for h in range(1, n - 1):
        k = n - 1 - h
        np.add(q[:k, h, 1:], q[:k, h - 1, :-1], out=q[:k, h, 1:])
    return q[:, :, n - 2 :]


def _blocks(m: int, n: int):
    """(s, e): the windows ending at samples s .. e - 1, B x N^2 at most BLOCK_ELEMENTS."""
    b = max(1, BLOCK_ELEMENTS // (n * n))
    for s in range(n - 1, m, b):
        yield s, min(m, s + b)


# ---------------------------------------------------------------- MBGTD, eq. (9)-(10)
def mbgtd_merits(x: np.ndarray, window: int) -> np.ndarray:
    """V of every full window of a 1-D signal: (len(x) - window + 1,), O(N^2) per sample (module
    docstring): R[l, h, g] = sum_{k = l-h-g}^{l-h-1} |x_l - x_k| as running sums, their diagonal sums
    eq. (9)'s numerators, each divided by (j - i)(N - j + 1) = g (h + 1)."""
    n = window
    out = np.empty(max(0, x.shape[0] - n + 1))
    for s, e in _blocks(x.shape[0], n):
        num = _diagonal_sums(_running_sums(np.abs(_band(x, n, s, e)), n), n)  # d_kl = |x_k - x_l|
        best = np.full(num.shape[2], -np.inf)
        for gi in range(n - 1):
            k = n - 1 - gi
            count = ((gi + 1) * np.arange(1, k + 1, dtype=float))[:, None]  # (j - i)(N - j + 1)
            c = num[gi, :k] / count  # C_ij, seed 001, eq. (9)
            np.maximum(best, c.max(axis=0), out=best)  # seed 001, eq. (10)
        out[s - n + 1 : e - n + 1] = best
    return out


# ---------------------------------------------------------------- MBCD, eq. (12)-(14)
def _log_ranges(logw: np.ndarray, w: np.ndarray, n: int) -> tuple[np.ndarray, np.ndarray]:
    """(Q, back): Q[g-1, h, r] = log sum_{m=h}^{h+g-1} w[m, r] (the first window's kernel sum of eq.
    13 for the sample of column r; h + g <= n - 1), and back[g, r] = sum_{m=0}^{g-1} w[m, r]
    (back[0] = 0).

    The sums run in the plain domain; a sum below TINY, where terms may have underflowed
    (d > 38 lambda), is taken again as a running np.logaddexp of the log weights, so Q stays finite
    and exact. The choice is made per entry from that entry's own sum, so a merit depends on its
    window's samples only (batch and stream agree bit for bit). A running sum of terms >= 0 never
    decreases, so where a sum is below TINY so is the one before it, already in the log domain."""
    q = _running_sums(w, n)
    back = np.zeros_like(w)
    back[1:] = q[: n - 2, 0]
    with np.errstate(divide="ignore", invalid="ignore"):
        for gi in range(n - 1):
            k = n - 1 - gi
            low = q[gi, :k] < TINY
            np.log(q[gi, :k], out=q[gi, :k])
            if low.any():
                if gi == 0:
                    np.copyto(q[0], logw, where=low)
                else:
                    np.logaddexp(q[gi - 1, :k], logw[gi : gi + k], out=q[gi, :k], where=low)
    return q, back


def mbcd_merits(x: np.ndarray, window: int, bandwidth: float) -> np.ndarray:
    """V of every full window of a 1-D signal: (len(x) - window + 1,), O(N^2) per sample (module
    docstring): S_ij = A_j - D_ij + (N - j + 1)(log(j - i) - log(N - j + 1)), eq. (13), with A_j the
    second window's log kernel sums and D_ij the diagonal sums of the first window's."""
    n = window
    h = np.arange(n - 1)
    out = np.empty(max(0, x.shape[0] - n + 1))
    for s, e in _blocks(x.shape[0], n):
        z = _band(x, n, s, e) / bandwidth
        logw = -0.5 * z * z  # log w_lk, seed 001, eq. (12) (decaying; its constant cancels in eq. 13)
        w = np.exp(logw)
        cols = w.shape[1]
        q, back = _log_ranges(logw, w, n)
        d = _diagonal_sums(q, n)  # sum_{l=j}^{N} log sum_{k=i}^{j-1} w_lk, (g - 1, h, E)
        # fwd[u, r] = sum_{t=1}^{u} w_{l, l+t} for the sample l of column r (the kernel is symmetric)
        ahead = np.zeros_like(w)
        for t in range(1, n - 1):
            ahead[t, : cols - t] = w[t - 1, t:]
        fwd = np.cumsum(ahead, axis=0)
        # a[h, E] = sum_{l=j}^{N} log sum_{k=j}^{N} w_lk, j = N - h: l = e - u (u = 0 .. h) and its sum
        # over k = e - h .. e = (w_ll = 1 + the h - u samples before l) + the u samples after l
        back += 1.0
        a = np.zeros((n - 1, cols - n + 2))
        for u in range(n - 1):
            ll = slice(n - 2 - u, cols - u)
            a[u:] += np.log(back[: n - 1 - u, ll] + fwd[u, ll])
        best = np.full(a.shape[1], -np.inf)
        for gi in range(n - 1):
            k = n - 1 - gi
            # the constant part of eq. (13): N - j + 1 = h + 1 terms of log(1/(h + 1)) - log(1/g)
            const = ((h[:k] + 1) * (np.log(gi + 1) - np.log(h[:k] + 1)))[:, None]
            sij = np.subtract(a[:k], d[gi, :k])
            sij += const  # S_ij, seed 001, eq. (13)
            np.maximum(best, sij.max(axis=0), out=best)  # seed 001, eq. (14)
        out[s - n + 1 : e - n + 1] = best
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
