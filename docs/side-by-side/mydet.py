"""A plugin detector for the demonstration: at rest when the acceleration magnitude's spread over the
last window_s is under threshold_mg (a tracker maker's first idea)."""

import numpy as np


class Spread:
    def __init__(self, fs_hz, threshold_mg, window_s):
        self.n = max(2, int(round(window_s * fs_hz)))
        self.thr = threshold_mg / 1000.0
        self.buf = np.zeros(0)

    def push(self, t_s, x):
        mag = np.sqrt((np.asarray(x) ** 2).sum(axis=1))
        allv = np.concatenate([self.buf, mag])
        out = np.zeros(mag.shape[0], bool)
        k = self.buf.shape[0]
        from numpy.lib.stride_tricks import sliding_window_view

        if allv.shape[0] >= self.n:
            w = sliding_window_view(allv, self.n)
            spread = w.max(axis=1) - w.min(axis=1)  # window ending at sample i + n - 1
            ends = np.arange(self.n - 1, allv.shape[0])
            keep = ends >= k
            out[ends[keep] - k] = spread[keep] < self.thr
        self.buf = allv[-(self.n - 1) :] if self.n > 1 else np.zeros(0)
        return out


def make(fs_hz, channels, threshold_mg=20.0, window_s=2.0):
    return Spread(fs_hz, threshold_mg, window_s)
