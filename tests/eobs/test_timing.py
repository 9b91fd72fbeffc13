"""Sample timing within a burst (seed 003 sections 4.2, 5.4)."""

from __future__ import annotations

import numpy as np
import pytest

from flightmode.eobs.burst import AccBurst
from flightmode.eobs.timing import draw_start_delay_s, max_start_delay_s, sample_offsets_s, sample_times
from flightmode.errors import SensorError


def test_samples_follow_at_the_period_of_one_axis():
    # section 4.2: "a sampling frequency f of 10 Hz ... T = 0.1 s"; 13 arrows in its Drawing 1
    off = sample_offsets_s(13, 10.0)
    np.testing.assert_array_equal(off[:, 0], np.arange(13) / 10.0)  # exact: k / f computed the same way
    # three axes: all axes of a set at the set's time unless staggered by 1 / (3 f)
    off3 = sample_offsets_s(4, 10.0, 0.25, n_axes=3)
    np.testing.assert_array_equal(off3, 0.25 + np.repeat(np.arange(4)[:, None] / 10.0, 3, axis=1))
    st = sample_offsets_s(2, 10.0, n_axes=3, stagger_axes=True)
    np.testing.assert_allclose(
        st, [[0, 1 / 30, 2 / 30], [0.1, 0.1 + 1 / 30, 0.1 + 2 / 30]], rtol=0, atol=1e-15
    )


def test_a_real_burst_spans_twelve_seconds_from_its_timestamp():
    """The albatross bursts: 60 samples per axis at 5 Hz: the last at 59 / 5 = 11.8 s."""
    b = AccBurst("1163", np.datetime64("2008-07-27T00:15:00"), "XY", 5.0, np.full((60, 2), 2048), 0)
    t = sample_times(b)
    assert t.shape == (60, 2) and t.dtype == np.dtype("datetime64[ns]")
    assert t[0, 0] == b.start_time and t[-1, 1] == np.datetime64("2008-07-27T00:15:11.800")
    t_old = sample_times(b, start_delay_s=0.731)
    assert t_old[0, 0] == np.datetime64("2008-07-27T00:15:00.731")  # rounded to the ns: exact here


def test_start_delay_is_a_per_tag_draw_up_to_one_second_for_old_tags():
    rng = np.random.default_rng(7)
    old = [draw_start_delay_s(n, rng) for n in range(1, 2242, 7)]
    assert all(0.0 <= d < 1.0 for d in old) and max(old) > 0.9 and min(old) < 0.1  # 321 uniforms span [0, 1)
    assert max_start_delay_s(2241) == 1.0 and max_start_delay_s(2242) == 0.0
    # newer tags: no delay, but the stream advances one draw per tag whatever the generation
    a, b = np.random.default_rng(1), np.random.default_rng(1)
    assert draw_start_delay_s(5000, a) == 0.0
    draw_start_delay_s(100, b)
    assert a.random() == b.random()
    # the same generator state gives the same delay
    assert draw_start_delay_s(100, np.random.default_rng(5)) == draw_start_delay_s(
        100, np.random.default_rng(5)
    )
    with pytest.raises(SensorError, match="bounds it to 0-1.0 s"):
        sample_offsets_s(3, 10.0, start_delay_s=1.5)
