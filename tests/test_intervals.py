"""flightmode.intervals: runs of True and change points, against a plain loop over the samples."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from flightmode.intervals import change_points, segment_starts, true_runs, true_runs_array


def _loop_runs(mask):
    runs, start = [], None
    for i, v in enumerate(mask):
        if v and start is None:
            start = i
        if not v and start is not None:
            runs.append((start, i))
            start = None
    if start is not None:
        runs.append((start, len(mask)))
    return runs


@given(st.lists(st.booleans(), max_size=60))
def test_runs_are_the_stretches_of_true_found_by_a_loop(mask):
    assert true_runs(mask) == _loop_runs(mask)
    a = true_runs_array(np.array(mask, dtype=bool))
    assert a.shape == (len(_loop_runs(mask)), 2) and a.dtype == np.int64
    assert all(type(v) is int for r in true_runs(mask) for v in r)


@given(st.lists(st.sampled_from(["gate", "taxi_out", "cruise"]), max_size=40))
def test_change_points_and_segment_starts_are_where_the_value_differs(labels):
    x = np.array(labels, dtype=object)
    want = [i for i in range(1, len(labels)) if labels[i] != labels[i - 1]]
    assert change_points(x).tolist() == want
    assert segment_starts(x).tolist() == ([0, *want] if labels else [])


def test_edges_and_bad_shapes():
    assert true_runs([True, True]) == [(0, 2)] and true_runs([]) == [] and true_runs([False]) == []
    assert change_points(np.array([0, 0, 1, 1, 0], np.int8)).tolist() == [2, 4]
    with pytest.raises(ValueError, match="1-D"):
        true_runs(np.zeros((2, 2), bool))
    with pytest.raises(ValueError, match="1-D"):
        change_points(np.zeros((2, 2)))
