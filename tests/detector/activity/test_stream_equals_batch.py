"""Every detector, every allowed signal: the streaming class pushed in chunks of 1, 7, 100 samples or
the whole stream gives exactly the batch result (seed 001's detectors have one set of maths; the batch
front end is the stream fed one chunk). Exact means np.array_equal on the marker and on the merit
(NaN where the batch has NaN), not a tolerance: every operation inside a window is elementwise or an
accumulation in a fixed order (flightmode.detector.activity.common)."""

from __future__ import annotations

from functools import cache, lru_cache
from itertools import pairwise

import numpy as np
import pytest

from flightmode.detector.activity import registry

from ._synthetic import FS_HZ, cases, params, stream

CHUNKS = (1, 7, 100, None)  # None: the whole stream in one push


@lru_cache(maxsize=1)
def _data():
    # 10 s still then 10 s moving: 2,000 samples (warm-up, transition and motion all inside)
    t, a, g, _ = stream([(10.0, False), (10.0, True)], np.random.default_rng(1234))
    return t, a, g


def _small(name, signal):
    """The burst parameters with short windows: the equality does not depend on the window's length,
    and short windows keep the 1-sample pushes of the O(N^3) MBCD quick."""
    p = params(name, signal)
    if "window" in p:
        p["window"] = 8
        if "shift" in p:
            p["shift"] = 3
    return p


@cache
def _batch(name, signal):
    t, a, g = _data()
    return registry.get(name).detect(t, a, g, fs_hz=FS_HZ, **_small(name, signal))


def _pushed(name, signal, cuts):
    t, a, g = _data()
    det = registry.get(name).stream(fs_hz=FS_HZ, **_small(name, signal))
    parts = [det.push(t[i:j], a[i:j], g[i:j]) for i, j in pairwise(cuts)]
    return np.concatenate([p.marker for p in parts]), np.concatenate([p.merit for p in parts])


@pytest.mark.parametrize("chunk", CHUNKS, ids=lambda c: f"chunk{c or 'all'}")
@pytest.mark.parametrize(("name", "signal"), cases())
def test_stream_equals_batch_exactly(name, signal, chunk):
    n = _data()[0].shape[0]
    cuts = list(range(0, n, chunk or n)) + [n]
    marker, merit = _pushed(name, signal, cuts)
    whole = _batch(name, signal)
    assert marker.dtype == np.int8 and merit.dtype == np.float64
    np.testing.assert_array_equal(marker, whole.marker)
    np.testing.assert_array_equal(merit, whole.merit)  # NaN == NaN here: the warm-up agrees too
    assert np.isfinite(whole.merit[-1000:]).all()  # the merit exists once the detector is warm


@pytest.mark.parametrize("name", registry.NAMES)
def test_uneven_chunks_with_empty_pushes_equal_batch(name):
    d = registry.get(name)
    signal = "product" if d.signals else None
    n = _data()[0].shape[0]
    rng = np.random.default_rng(7)
    cuts = np.unique(np.concatenate([[0, n], rng.integers(0, n, 60)]))
    cuts = sorted([*cuts, *cuts[:10]])  # a repeated cut is an empty push
    marker, merit = _pushed(name, signal, cuts)
    whole = _batch(name, signal)
    np.testing.assert_array_equal(marker, whole.marker)
    np.testing.assert_array_equal(merit, whole.merit)


@pytest.mark.parametrize("name", registry.NAMES)
def test_warm_up_is_nan_and_active(name):
    """Before the first figure of merit: NaN merit and marker 1 (seed 001 step IV on a missing value),
    the same in batch and stream (checked above); here, where it ends."""
    whole = _batch(name, "acc" if registry.get(name).signals else None)
    nan = np.isnan(whole.merit)
    assert (whole.marker[nan] == 1).all()
    first = int(np.flatnonzero(~nan)[0])
    assert not nan[first:].any()  # once warm, always warm
    p = _small(name, "acc")
    expected = {
        "frd": 0,  # a filter: a merit from the first sample
        # the noise spectrum's 20 frames (shift 3, window 8): the 20th frame ends at 19*3 + 7
        "fsd": 19 * 3 + 7,
        # and the envelope's 6 frames ahead (already inside the 20)
        "ltsd": 19 * 3 + 7,
    }.get(name, p.get("window", 0) - 1)
    assert first == expected
