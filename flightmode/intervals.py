"""Runs and change points of sampled labels: the one home of run-length helpers.

A *run* of a boolean mask is a maximal stretch of consecutive True samples, given as ``[start,
stop)`` sample indices (``stop`` exclusive, as Python slices). A *change point* of a label array is
an index ``i`` whose value differs from sample ``i - 1``. Pure NumPy on sample indices: times are the
caller's (``t_s[start]``).
"""

from __future__ import annotations

import numpy as np


def true_runs_array(mask) -> np.ndarray:
    """(k, 2) int64 ``[start, stop)`` of each run of True in the 1-D boolean ``mask``, in order;
    shape (0, 2) when it holds no True."""
    m = np.asarray(mask, dtype=bool)
    if m.ndim != 1:
        raise ValueError(f"true_runs: a 1-D mask is needed, not shape {m.shape}")
    d = np.diff(np.concatenate([[0], m.astype(np.int8), [0]]))
    return np.stack([np.flatnonzero(d == 1), np.flatnonzero(d == -1)], axis=1).astype(np.int64)


def true_runs(mask) -> list[tuple[int, int]]:
    """``[(start, stop), ...]`` (Python ints, ``stop`` exclusive) of each run of True in ``mask``."""
    return [(int(s), int(e)) for s, e in true_runs_array(mask)]


def change_points(labels) -> np.ndarray:
    """int64 indices ``i`` (1 <= i < n) where ``labels[i] != labels[i - 1]``, for a 1-D array of any
    comparable values (booleans, codes, strings)."""
    x = np.asarray(labels)
    if x.ndim != 1:
        raise ValueError(f"change_points: a 1-D array is needed, not shape {x.shape}")
    return (np.flatnonzero(x[1:] != x[:-1]) + 1).astype(np.int64)


def segment_starts(labels) -> np.ndarray:
    """int64 index of the first sample of each stretch of equal values: 0 and every change point
    (empty for an empty array)."""
    x = np.asarray(labels)
    if x.shape[0] == 0:
        return np.zeros(0, dtype=np.int64)
    return np.concatenate([[0], change_points(x)]).astype(np.int64)


__all__ = ["true_runs", "true_runs_array", "change_points", "segment_starts"]
