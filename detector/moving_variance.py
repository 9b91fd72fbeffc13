"""Moving variance of accelerometer axes: NMV and EMV of seed 000 (section 3, eq. 1-5).

One set of maths, two front ends: :class:`MovingVariance` is the streaming engine (push chunks of
any length; the state is kept between pushes) and :func:`moving_variance` the batch front end, which
feeds the whole array as one chunk. Both give bit-identical results for any chunking, because
every operation is either elementwise or a sequential recursion continued exactly across chunks
(``np.cumsum`` on an array that starts with the carried value; ``scipy.signal.lfilter`` with its
carried state).

NMV (eq. 1-3): the variance of the last ``N`` samples, ``mean(x^2) - mean(x)^2``, from running sums
(eq. 2-3). Running sums of raw values lose precision two ways: the sums drift as rounding errors
accumulate over millions of samples, and ``mean(x^2) - mean(x)^2`` cancels catastrophically when
the mean (1 g of gravity) is large against the spread (2 mg of noise). Both are handled by
*periodic re-anchoring*: every ``block`` samples (at fixed global positions) the sums restart,
taken relative to an anchor (the block's first sample), from the last ``N - 1`` samples. Rounding
then never accumulates over more than ``block + N`` samples and the summed values are deviations
from a nearby level, not 1 g.

EMV (eq. 4-5), with ``alpha = weight / N`` (seed 000: N is the window in samples, the weighting
factor 1, 5 or 10):

    m(n) = (1 - alpha) m(n-1) + alpha x(n)                          (eq. 4)
    v(n) = (1 - alpha) v(n-1) + alpha (x(n) - m(n))^2               (eq. 5)

starting from ``m = x(0)`` and ``v = initial_variance`` (10 sigma^2 in seed 000's Fig. 18).

The seed's typesetting of eq. 2-5 is garbled in our copy (symbols lost); the forms above are the
ones consistent with its text ("the old average and variance are weighted and a new average and
variance are computed taking in consideration the new sample") and its reference [17].
"""

from __future__ import annotations

import numpy as np
from scipy.signal import lfilter

from flightmode.errors import DetectorError, first_nonfinite


class MovingVariance:
    """Streaming NMV or EMV over (n, n_axes) chunks. ``push`` returns the MV of every pushed sample
    (NaN for NMV until the first window is full)."""

    def __init__(
        self,
        window: int,
        method: str = "nmv",
        weight: float = 1.0,
        initial_variance: float | np.ndarray = 0.0,
        n_axes: int = 3,
        block: int = 4096,
    ):
        if method not in ("nmv", "emv"):
            raise DetectorError(f"moving-variance method '{method}': use 'nmv' or 'emv'")
        if int(window) != window or window < 2:
            raise DetectorError(f"window of {window} samples: a variance needs at least 2 samples")
        if method == "emv" and not 0 < weight <= window:
            raise DetectorError(f"EMV weight {weight}: must be in (0, window = {window}]")
        if block < window:
            raise DetectorError(f"re-anchoring block {block} shorter than the window {window}")
        self.window, self.method, self.weight, self.n_axes, self.block = (
            int(window),
            method,
            weight,
            n_axes,
            block,
        )
        self.n = 0  # samples pushed so far
        # NMV state: the last N - 1 samples, and the running sums (relative to the anchor) of the
        # last N samples' prefix values
        self._tail = np.zeros((0, n_axes))
        self._anchor = np.zeros(n_axes)
        self._c1 = np.zeros((0, n_axes))  # cumulative sums over the block's span, last N values
        self._c2 = np.zeros((0, n_axes))
        # EMV state
        a = weight / window
        self._b, self._a = np.array([a]), np.array([1.0, -(1.0 - a)])
        self._zm: np.ndarray | None = None
        self._zv = np.atleast_1d(np.asarray(initial_variance, float)) * np.ones(n_axes) * (1.0 - a)

    def push(self, x: np.ndarray) -> np.ndarray:
        x = np.asarray(x, dtype=float)
        if x.ndim != 2 or x.shape[1] != self.n_axes:
            raise DetectorError(f"samples must be an (n, {self.n_axes}) array, got shape {x.shape}")
        if x.shape[0] == 0:
            return np.zeros((0, self.n_axes))
        if (bad := first_nonfinite(x)) is not None:
            raise DetectorError(
                f"NaN or inf in the stream at sample {self.n + bad}: clean the stream, or start a new "
                "detector after the gap (a gap resets the detector)"
            )
        out = self._emv(x) if self.method == "emv" else self._nmv(x)
        self.n += x.shape[0]
        return out

    # ---------------------------------------------------------------- EMV, eq. 4-5
    def _emv(self, x: np.ndarray) -> np.ndarray:
        if self._zm is None:  # start the mean at the first sample (m(0) = x(0))
            self._zm = x[0] * (1.0 - self._b[0])
        m, zm = lfilter(self._b, self._a, x, axis=0, zi=self._zm[None, :])
        self._zm = zm[0]
        d2 = (x - m) ** 2
        v, zv = lfilter(self._b, self._a, d2, axis=0, zi=self._zv[None, :])
        self._zv = zv[0]
        return v

    # ---------------------------------------------------------------- NMV, eq. 1-3
    def _nmv(self, x: np.ndarray) -> np.ndarray:
        n_win, blk = self.window, self.block
        out = np.empty_like(x)
        i = 0
        while i < x.shape[0]:
            g = self.n + i  # global index of x[i]
            if g % blk == 0:
                self._reanchor(x[i])
            end = min(x.shape[0], i + blk - g % blk)  # up to the next block boundary
            seg = x[i:end]
            y = seg - self._anchor
            # sequential sums continued from the carried value (bit-identical for any chunking)
            last1 = self._c1[-1] if self._c1.shape[0] else np.zeros(self.n_axes)
            last2 = self._c2[-1] if self._c2.shape[0] else np.zeros(self.n_axes)
            c1 = np.cumsum(np.vstack([last1, y]), axis=0)[1:]
            c2 = np.cumsum(np.vstack([last2, y * y]), axis=0)[1:]
            h1 = np.vstack([self._c1, c1])
            h2 = np.vstack([self._c2, c2])
            k0 = self._c1.shape[0]  # index in h of the first new sample
            idx = np.arange(k0, k0 + seg.shape[0])
            back = idx - n_win
            # sums over the window: C(n) - C(n - N); C before the span start is 0
            s1 = h1[idx] - np.where((back >= 0)[:, None], h1[np.maximum(back, 0)], 0.0)
            s2 = h2[idx] - np.where((back >= 0)[:, None], h2[np.maximum(back, 0)], 0.0)
            var = np.maximum((s2 - s1 * s1 / n_win) / n_win, 0.0)  # eq. 1: mean(x^2) - mean(x)^2
            have = (g + np.arange(seg.shape[0]) + 1) >= n_win
            var[~have] = np.nan
            out[i:end] = var
            self._c1, self._c2 = h1[-n_win:], h2[-n_win:]
            self._tail = np.vstack([self._tail, seg])[-(n_win - 1) :]
            i = end
        return out

    def _reanchor(self, first: np.ndarray) -> None:
        """Restart the sums at a block boundary: anchor at the block's first sample, and rebuild the
        prefix sums of the last N - 1 samples relative to it (periodic re-anchoring)."""
        self._anchor = first.copy()
        y = self._tail - self._anchor
        zero = np.zeros((1, self.n_axes))
        self._c1 = np.cumsum(np.vstack([zero, y]), axis=0)[1:]
        self._c2 = np.cumsum(np.vstack([zero, y * y]), axis=0)[1:]


def moving_variance(
    x: np.ndarray,
    window: int,
    method: str = "nmv",
    weight: float = 1.0,
    initial_variance: float | np.ndarray = 0.0,
) -> np.ndarray:
    """Batch front end: the MV of every sample of an (n, n_axes) array."""
    x = np.asarray(x, dtype=float)
    if x.ndim == 1:
        x = x[:, None]
    mv = MovingVariance(window, method, weight, initial_variance, n_axes=x.shape[1])
    return mv.push(x)
