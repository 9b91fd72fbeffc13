"""Seed 002's two cubic-spline path methods: the worked example, exactness on cubics, streaming."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from flightmode.nav.spline_path import NavError, RecurrencePath, recurrence_path, tridiagonal_path


def test_free_fall_example_of_section_iv_both_methods():
    """Seed 002 section IV: released from 400 ft, -32 ft/s^2 measured every second for 5 s.
    The paper writes the end condition as "f(4) = 0", but its samples run t = 0..5 and its own
    matrix and solution end with a_5 = 0: it is f(5) = 0 (and its "n = 6" counts samples)."""
    t = np.arange(6.0)
    acc = np.full(6, -32.0)
    for pp in (tridiagonal_path(t, acc, 400.0, 0.0), recurrence_path(t, acc, 400.0, 0.0)):
        d, c, b, a = pp.c
        # the paper's numbers, to double rounding (the banded LU leaves ~1e-13 on values of ~400)
        exact = dict(rtol=0, atol=1e-12)
        np.testing.assert_allclose(a, [400, 384, 336, 256, 144], **exact)
        np.testing.assert_allclose(b, [0, -32, -64, -96, -128], **exact)
        np.testing.assert_allclose(c, -16.0, **exact)
        np.testing.assert_allclose(d, 0.0, **exact)
        assert pp(5.0) == pytest.approx(0.0, abs=1e-12)  # a_5 = f(5) = 0
        tt = np.linspace(0, 5, 51)
        np.testing.assert_allclose(pp(tt), 400 - 16 * tt**2, rtol=0, atol=1e-12)  # "400 - 16 t^2"


@st.composite
def cubic_case(draw):
    n = draw(st.integers(3, 400))
    uniform = draw(st.booleans())
    seed = draw(st.integers(0, 2**32 - 1))
    rng = np.random.default_rng(seed)
    if uniform:
        t = draw(st.floats(-100, 100)) + np.arange(n) * draw(st.floats(1e-3, 10.0))
    else:
        t = np.cumsum(rng.uniform(0.01, 1.0, n)) + draw(st.floats(-100, 100))
    coef = rng.normal(size=(4, 3)) * np.array([[1e3], [10.0], [1.0], [0.1]])
    return t, coef


@settings(max_examples=150, deadline=None, derandomize=True)
@given(cubic_case())
def test_both_methods_are_exact_on_cubics_and_agree(case):
    """A cubic position has a linear acceleration, which the spline (eq. 1-6) represents exactly:
    both methods must recover it to 1e-9 relative (double rounding through n steps, n <= 400)."""
    t, k = case
    tc = t - t[0]
    f = lambda x: k[0] + k[1] * x[:, None] + k[2] * x[:, None] ** 2 + k[3] * x[:, None] ** 3  # noqa: E731
    v0 = k[1]
    acc = 2 * k[2] + 6 * k[3] * tc[:, None]
    pos = f(tc)
    scale = np.abs(pos).max()
    tri = tridiagonal_path(t, acc, pos[0], pos[-1])
    rec = recurrence_path(t, acc, pos[0], v0)
    tt = np.linspace(t[0], t[-1], 97)
    for pp in (tri, rec):
        assert np.abs(pp(t) - pos).max() <= 1e-9 * scale
        assert np.abs(pp(tt) - f(tt - t[0])).max() <= 1e-9 * scale
    # consistent boundary conditions: the recurrence's end position fed to the tridiagonal method
    # gives the same spline, velocity and acceleration included
    tri2 = tridiagonal_path(t, acc, pos[0], rec(t[-1]))
    assert np.abs(tri2(tt) - rec(tt)).max() <= 1e-9 * scale
    vs = np.abs(k[1:]).sum() * max(1.0, float(tc[-1])) ** 2
    assert np.abs(tri2.derivative()(tt) - rec.derivative()(tt)).max() <= 1e-7 * vs
    np.testing.assert_allclose(rec.derivative(2)(t), acc, rtol=1e-9, atol=1e-9 * np.abs(acc).max())


@settings(max_examples=60, deadline=None, derandomize=True)
@given(st.lists(st.integers(1, 200), min_size=1, max_size=8), st.integers(0, 2**32 - 1))
def test_streaming_recurrence_is_bit_identical_for_any_chunking(cuts, seed):
    rng = np.random.default_rng(seed)
    n = 500
    t = np.cumsum(rng.uniform(0.005, 0.02, n))
    acc = rng.normal(size=(n, 3))
    batch = recurrence_path(t, acc, [1.0, 2.0, 3.0], [0.1, -0.2, 0.3])
    r = RecurrencePath([1.0, 2.0, 3.0], [0.1, -0.2, 0.3])
    i = 0
    for c in cuts * 10:
        if i >= n:
            break
        r.push(t[i : i + c], acc[i : i + c])
        i += c
    r.push(t[i:], acc[i:])
    pp = r.ppoly()
    np.testing.assert_array_equal(pp.c, batch.c)
    np.testing.assert_array_equal(pp.x, batch.x)


def test_bad_input_is_named():
    t = np.arange(10.0)
    a = np.zeros(10)
    with pytest.raises(NavError, match="not increasing at sample 5"):
        tridiagonal_path(np.r_[t[:5], t[4], t[6:]], a, 0, 0)
    with pytest.raises(NavError, match="not increasing"):
        recurrence_path(t[::-1], a, 0, 0)
    with pytest.raises(NavError, match="2 sample\\(s\\): a cubic-spline path needs at least 3"):
        tridiagonal_path(t[:2], a[:2], 0, 0)
    with pytest.raises(NavError, match="at least 3"):
        recurrence_path(t[:2], a[:2], 0, 0)
    bad = a.copy()
    bad[7] = np.nan
    with pytest.raises(NavError, match="NaN or inf at sample 7"):
        tridiagonal_path(t, bad, 0, 0)
    with pytest.raises(NavError, match="NaN or inf at sample 7"):
        recurrence_path(t, bad, 0, 0)
    with pytest.raises(NavError, match="time has NaN"):
        recurrence_path(np.r_[t[:3], np.nan, t[4:]], a, 0, 0)
    with pytest.raises(NavError, match="rows"):
        recurrence_path(t, a[:5], 0, 0)
