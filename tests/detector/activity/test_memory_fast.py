"""The memory detectors' O(N^2)-per-sample kernels (flightmode.detector.activity.memory: running sums
per sample, diagonal sums along the stream) against seed 001's eq. (9)-(10) and (12)-(14) written
straight from the page, per window and per split, in exact-as-possible scalar arithmetic
(math.fsum; eq. 13's kernel sums as a max-shifted log-sum-exp, so they stay finite where the weights
underflow); batch against streaming with the study's window length; and the flight wrapper's windows
(the study's, in samples at the stream's rate)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from flightmode.detector.activity import memory
from flightmode.detector.activity.common import decide
from flightmode.detector.activity.memory import MBCDStream, MBGTDStream, mbcd_merits, mbgtd_merits


def _reference_mbgtd(x: list[float], n: int) -> np.ndarray:
    """Eq. (9)-(10), 1-based i < j <= N, the double sum of distances fsum'd."""
    out = []
    for e in range(n - 1, len(x)):
        w = [0.0, *x[e - n + 1 : e + 1]]  # w[1] .. w[N]
        best = -math.inf
        for i in range(1, n + 1):
            for j in range(i + 1, n + 1):
                s = math.fsum(abs(w[k] - w[l]) for k in range(i, j) for l in range(j, n + 1))
                best = max(best, s / ((j - i) * (n - j + 1)))  # seed 001, eq. (9)
        out.append(best)  # seed 001, eq. (10)
    return np.array(out)


def _log_sum(logs: list[float]) -> float:
    m = max(logs)
    return m + math.log(math.fsum(math.exp(v - m) for v in logs))


def _reference_mbcd(x: list[float], n: int, lam: float) -> np.ndarray:
    """Eq. (12)-(14), 1-based i < j <= N: log w_lk = -(x_l - x_k)^2 / (2 lambda^2) (eq. 12, its
    constant cancels in eq. 13), each mean of eq. (13) as a log-sum-exp, the terms fsum'd."""
    out = []
    for e in range(n - 1, len(x)):
        w = [0.0, *x[e - n + 1 : e + 1]]
        lw = [[-0.5 * ((w[a] - w[b]) / lam) ** 2 for b in range(n + 1)] for a in range(n + 1)]
        best = -math.inf
        for i in range(1, n + 1):
            for j in range(i + 1, n + 1):
                terms = []
                for l in range(j, n + 1):
                    post = _log_sum([lw[l][k] for k in range(j, n + 1)]) - math.log(n - j + 1)
                    pre = _log_sum([lw[l][k] for k in range(i, j)]) - math.log(j - i)
                    terms.append(post - pre)  # seed 001, eq. (13)
                best = max(best, math.fsum(terms))
        out.append(best)  # seed 001, eq. (14)
    return np.array(out)


def _inputs(seed: int, m: int = 60) -> np.ndarray:
    """A still stretch, a step, a swing: |a|-like values around 1 g."""
    rng = np.random.default_rng(seed)
    x = 1.0 + rng.normal(0.0, 0.005, m)
    x[m // 3 :] += 0.2
    x[2 * m // 3 :] += 0.4 * np.sin(np.arange(m - 2 * m // 3))
    return x


@pytest.mark.parametrize("n", [2, 3, 5, 8, 13])
@pytest.mark.parametrize("seed", [0, 1])
def test_mbgtd_equals_eq_9_10(n, seed):
    x = _inputs(seed)
    # a sum of non-negative terms: the fast running sums and the fsum differ by rounding only, a few
    # ulps times the N^2 / 4 terms: 1e-12 relative is a 100x margin at N = 13
    np.testing.assert_allclose(mbgtd_merits(x, n), _reference_mbgtd(list(x), n), rtol=1e-12, atol=0)


@pytest.mark.parametrize("n", [2, 3, 5, 8, 13])
@pytest.mark.parametrize("lam", [0.5, 0.004])
def test_mbcd_equals_eq_12_14(n, lam):
    """lambda 0.5 (every weight near 1, merits ~1e-3..1) and 0.004 (the noise's width: across the
    step every weight underflows, d up to 150 lambda, merits ~1e4, the log-domain path)."""
    x = _inputs(3)
    fast = mbcd_merits(x, n, lam)
    ref = _reference_mbcd(list(x), n, lam)
    assert np.isfinite(fast).all()
    # eq. (13) is a difference of sums of logs (A - D + const): the rounding of each log term,
    # eps x |term| <= 2.2e-16 x |log w|max, is not relative to the difference. Bound: 1e-12 of the
    # merit plus 1e-13 of the largest |log w| in the window (N terms of a few ulps each, 10x margin)
    lw_max = 0.5 * ((np.max(x) - np.min(x)) / lam) ** 2
    np.testing.assert_allclose(fast, ref, rtol=1e-12, atol=1e-13 * (1.0 + lw_max))
    if lam < 0.01:  # the underflow path ran
        assert (ref > 1e3).any()


@pytest.mark.parametrize("n", [4, 13])
def test_decisions_equal_the_equations_exactly(n):
    """Seed 001 step IV on the fast merits and on the reference's: the same marker for every
    threshold (the thresholds sit half-way between consecutive distinct merits, far above rounding)."""
    x = _inputs(5)
    for fast, ref in (
        (mbgtd_merits(x, n), _reference_mbgtd(list(x), n)),
        (mbcd_merits(x, n, 0.05), _reference_mbcd(list(x), n, 0.05)),
    ):
        levels = np.unique(ref)
        for thr in 0.5 * (levels[1:] + levels[:-1]):
            np.testing.assert_array_equal(decide(fast, thr), decide(ref, thr))


def test_the_block_does_not_change_a_bit(monkeypatch):
    """A merit is a function of its window's samples only: blocks of 1, 3 or 1,000 windows give the
    same bits (what batch = stream rests on)."""
    x = _inputs(7, 400)
    want = (mbgtd_merits(x, 26), mbcd_merits(x, 25, 0.004))
    for elements in (1, 3 * 26 * 26, 1000 * 26 * 26):
        monkeypatch.setattr(memory, "BLOCK_ELEMENTS", elements)
        np.testing.assert_array_equal(mbgtd_merits(x, 26), want[0])
        np.testing.assert_array_equal(mbcd_merits(x, 25, 0.004), want[1])


@pytest.mark.parametrize("chunk", [1, 7, None], ids=lambda c: f"chunk{c or 'all'}")
@pytest.mark.parametrize("name", ["mbgtd", "mbcd"])
def test_stream_equals_batch_at_the_study_window(name, chunk):
    """The study's window at 100 Hz (26 and 25 samples) on a still-step-swing stream with a kernel of
    the noise's width (MBCD's log-domain sums run): pushes of 1, 7 and all samples, the same bits."""
    fs = 100.0
    x = _inputs(11, 600)
    t = np.arange(x.shape[0]) / fs
    acc = np.column_stack([np.zeros_like(x), np.zeros_like(x), x])
    kw = {"window": 26, "threshold": 0.05, "fs_hz": fs}
    if name == "mbcd":
        kw = {"window": 25, "threshold": 20.0, "fs_hz": fs, "bandwidth": 0.004}
    cls = MBGTDStream if name == "mbgtd" else MBCDStream
    whole = cls(**kw).push(t, acc)
    det = cls(**kw)
    step = chunk or x.shape[0]
    parts = [det.push(t[i : i + step], acc[i : i + step]) for i in range(0, x.shape[0], step)]
    np.testing.assert_array_equal(np.concatenate([p.merit for p in parts]), whole.merit)
    np.testing.assert_array_equal(np.concatenate([p.marker for p in parts]), whole.marker)
    assert np.isfinite(whole.merit[kw["window"] - 1 :]).all()


def test_the_flight_wrapper_uses_the_study_windows():
    """MBGTD and MBCD run with seed 001's windows (Tables 10-11, samples at its IMU's 50 Hz) in
    samples at the stream's rate; W_s stays the check period; the other detectors keep W_s fs."""
    from flightmode.detector.activity.flight import STUDY_WINDOW_S, ActivityParams, detector_kwargs

    assert ActivityParams("mbgtd", fs_hz=50.0).detector_window == 13  # Table 10: 13.18 samples
    assert ActivityParams("mbcd", fs_hz=50.0).detector_window == 13  # Table 11: 12.62 samples
    assert ActivityParams("mbgtd", fs_hz=100.0).detector_window == 26
    assert ActivityParams("mbcd", fs_hz=100.0, signal="gyr").detector_window == 30  # 15.25 at 50 Hz
    p = ActivityParams("mbcd", fs_hz=100.0, window_s=2.0)
    assert (p.window, detector_kwargs(p, {"bandwidth": 1.0})["window"]) == (200, 25)
    assert ActivityParams("amvd", fs_hz=100.0, window_s=0.5).detector_window == 50
    assert set(STUDY_WINDOW_S) == {"mbgtd", "mbcd"}
    assert all(0.2 < s < 0.35 for v in STUDY_WINDOW_S.values() for s in v.values())
