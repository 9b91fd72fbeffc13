"""NMV and EMV (seed 000 eq. 1-5): exact against direct computations, chunk-invariant."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from flightmode.detector.moving_variance import DetectorError, MovingVariance, moving_variance


def _two_pass_nmv(x, n):
    from numpy.lib.stride_tricks import sliding_window_view

    w = sliding_window_view(x, n, axis=0)  # (M - n + 1, axes, n)
    return w.var(axis=-1)  # numpy's two-pass variance: mean((x - mean)^2)


def _direct_emv(x, n, weight, v0):
    a = weight / n
    m = x[0].copy()
    v = np.full(x.shape[1], v0, float)
    out = np.empty_like(x)
    for k in range(x.shape[0]):
        m = (1 - a) * m + a * x[k]  # eq. 4
        v = (1 - a) * v + a * (x[k] - m) ** 2  # eq. 5
        out[k] = v
    return out


def test_nmv_equals_two_pass_on_an_accelerometer_like_signal():
    # 1 g of gravity on z plus 2.23 mg noise: the worst case for mean(x^2) - mean(x)^2
    rng = np.random.default_rng(0)
    x = rng.normal(0.0, 2.23e-3, (50_000, 3)) + [0.02, -0.5, 0.86]
    mv = moving_variance(x, 100)
    assert np.isnan(mv[:99]).all()
    np.testing.assert_allclose(mv[99:], _two_pass_nmv(x, 100), rtol=1e-12, atol=0)


@pytest.mark.slow
def test_nmv_stays_exact_after_ten_million_samples():
    """10^7 samples of running sums: the periodic re-anchoring keeps the error at the 1e-12 level
    where plain running sums of raw values would have drifted (they reach ~1e-9 here)."""
    rng = np.random.default_rng(1)
    n = 10_000_000
    x = rng.normal(0.0, 2.23e-3, (n, 1)) + 1.0
    mv = MovingVariance(100, "nmv", n_axes=1)
    for k in range(0, n, 1_000_000):  # pushed in chunks, as a logger would
        last = mv.push(x[k : k + 1_000_000])
    ref = _two_pass_nmv(x[-(1_000_000 + 99) :], 100)  # the windows ending in the last chunk
    np.testing.assert_allclose(last, ref, rtol=1e-12)


def test_emv_equals_the_direct_recursion():
    rng = np.random.default_rng(2)
    x = rng.normal(0.0, 0.01, (5000, 3)) + 1.0
    for weight in (1, 5, 10):
        got = moving_variance(x, 100, "emv", weight, initial_variance=10 * 2.23e-3**2)
        np.testing.assert_allclose(got, _direct_emv(x, 100, weight, 10 * 2.23e-3**2), rtol=1e-12)


@settings(max_examples=60, deadline=None, derandomize=True)  # CI sees the same examples every run
@given(
    cuts=st.lists(st.integers(min_value=0, max_value=3000), max_size=12),
    method=st.sampled_from(["nmv", "emv"]),
    window=st.sampled_from([2, 7, 100]),
    seed=st.integers(0, 2**16),
)
def test_any_chunking_gives_identical_values(cuts, method, window, seed):
    x = np.random.default_rng(seed).normal(0.0, 0.05, (3000, 3)) + [0.0, 0.0, 1.0]
    engine = dict(window=window, method=method, weight=min(5, window), block=max(window, 256))
    mv = MovingVariance(**engine)
    bounds = [0, *sorted(cuts), 3000]
    got = np.concatenate([mv.push(x[a:b]) for a, b in zip(bounds, bounds[1:])])
    # bit-identical to one push (NaN where no full window yet)
    np.testing.assert_array_equal(got, MovingVariance(**engine).push(x))
    # and the batch front end (its own re-anchoring block, 4096) agrees to 1e-12 relative or 1e-13
    # g^2 absolute: the running sums' rounding is bounded by (block + N) x eps x max(y^2) =
    # 4196 x 2.2e-16 x (0.2 g)^2 ~ 4e-14 g^2, y being the deviation from the block's anchor; a
    # 2-sample window of nearly equal values can have a variance far below that, so relative
    # agreement alone cannot be asked of it
    batch = moving_variance(x, window, method, weight=min(5, window))
    np.testing.assert_allclose(got, batch, rtol=1e-12, atol=1e-13)


def test_bad_input_is_named():
    with pytest.raises(DetectorError, match="at least 2 samples"):
        MovingVariance(1)
    with pytest.raises(DetectorError, match="use 'nmv' or 'emv'"):
        MovingVariance(10, "ema")
    with pytest.raises(DetectorError, match="EMV weight 0"):
        MovingVariance(10, "emv", weight=0)
    mv = MovingVariance(10)
    mv.push(np.zeros((25, 3)))
    bad = np.zeros((5, 3))
    bad[3, 1] = np.nan
    with pytest.raises(DetectorError, match="NaN or inf in the stream at sample 28"):
        mv.push(bad)
