"""Each figure of merit against the seed's equation worked by hand on a few samples (the numbers in
the comments are the hand computation), and the memory-based ones against the equations written as
plain loops. Tolerances are rounding only (1e-12 relative)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from flightmode.detector.activity.magnitude import (
    detect_amd,
    detect_amvd,
    detect_ared,
    detect_frd,
    detect_shod,
)
from flightmode.detector.activity.memory import detect_mbcd, detect_mbgtd, mbcd_merits, mbgtd_merits
from flightmode.detector.activity.spectrum import N_BANDS, detect_fsd, detect_ltsd

NAN = np.nan
FS = 100.0


def _t(n):
    return np.arange(n) / FS


def _scalar_as_acc(x):
    """An acceleration whose magnitude is x (x >= 0): |(0, 0, x)| = x."""
    x = np.asarray(x, float)
    return np.column_stack([np.zeros_like(x), np.zeros_like(x), x])


def _close(got, want):
    np.testing.assert_allclose(got, want, rtol=1e-12, atol=1e-15, equal_nan=True)


def test_amvd_eq1():
    a = np.array([[0, 0, 1], [0.3, 0, 1], [0, 0.6, 1], [0, 0, 1.3]])
    # window a1..a3: mean (0.1, 0.2, 1); squared deviations 0.05, 0.08, 0.17 -> 0.30 / 3 = 0.1
    # window a2..a4: mean (0.1, 0.2, 1.1); squared deviations 0.09, 0.18, 0.09 -> 0.36 / 3 = 0.12
    r = detect_amvd(_t(4), a, window=3, threshold=0.11, fs_hz=FS)
    _close(r.merit, [NAN, NAN, 0.1, 0.12])
    np.testing.assert_array_equal(r.marker, [1, 1, 0, 1])  # NaN: active; 0.1 < 0.11 static; 0.12 active


def test_amd_eq2():
    a = np.array([[0, 0, 1], [0, 0, 1.2], [0.6, 0, 0.8], [0, 0, 0.7]])
    # |a| - g = 0, 0.2, 0, -0.3 -> squares 0, 0.04, 0, 0.09; sigma^2 N = 0.01 * 2
    r = detect_amd(_t(4), a, window=2, threshold=3.0, sigma_acc_g=0.1, fs_hz=FS)
    _close(r.merit, [NAN, 2.0, 2.0, 4.5])
    np.testing.assert_array_equal(r.marker, [1, 0, 0, 1])


def test_ared_eq3():
    w = np.array([[1, 2, 2], [0, 0, 0], [3, 0, 4], [0, 0, 2]])
    # ||w||^2 = 9, 0, 25, 4; sigma^2 N = 4 * 3 -> 34 / 12, 29 / 12
    r = detect_ared(_t(4), np.zeros((4, 3)), w, window=3, threshold=2.5, sigma_gyr_dps=2.0, fs_hz=FS)
    _close(r.merit, [NAN, NAN, 34 / 12, 29 / 12])
    np.testing.assert_array_equal(r.marker, [1, 1, 1, 0])


def test_shod_eq4():
    a = np.array([[3, 0, 0], [0, 4, 0], [0, 2, 0]])
    w = np.array([[1, 0, 0], [0, 2, 0], [0, 0, 0]])
    # window 1: mean (1.5, 2, 0), |mean| 2.5, g mean/|mean| = (0.6, 0.8, 0);
    #   ||a - u||^2 = 2.4^2 + 0.8^2 = 6.4 and 0.6^2 + 3.2^2 = 10.6 -> 17 / 0.25 = 68; ||w||^2 = 1 + 4 = 5
    #   V = (68 + 5) / 2 = 36.5
    # window 2: mean (0, 3, 0), u = (0, 1, 0); ||a - u||^2 = 9 and 1 -> 10 / 0.25 = 40; ||w||^2 = 4 + 0
    #   V = (40 + 4) / 2 = 22
    r = detect_shod(_t(3), a, w, window=2, threshold=30.0, sigma_acc_g=0.5, sigma_gyr_dps=1.0, fs_hz=FS)
    _close(r.merit, [NAN, 36.5, 22.0])
    np.testing.assert_array_equal(r.marker, [1, 1, 0])


def test_shod_in_free_fall_is_active():
    a = np.array([[0, 0, 0.1], [0, 0, -0.1]])  # the window's mean acceleration is zero
    r = detect_shod(
        _t(2), a, np.zeros((2, 3)), window=2, threshold=1e9, sigma_acc_g=1, sigma_gyr_dps=1, fs_hz=FS
    )
    assert r.merit[1] == np.inf and r.marker[1] == 1


def test_frd_eq5_constant_input_gives_zero():
    """A still sensor: the high-pass starts in its steady state, so there is nothing to rectify."""
    r = detect_frd(_t(500), np.tile([0.1, -0.2, 0.97], (500, 1)), threshold=1e-9, fs_hz=FS)
    assert np.max(np.abs(r.merit)) < 1e-12 and not r.marker.any()


def test_frd_eq5_level_of_a_sinusoid():
    """x = 1 + A sin(2 pi f t). A 2nd-order Butterworth high-pass made by the bilinear transform with
    prewarping has the response H = -W^2 / (-W^2 + sqrt(2) Wc j W + Wc^2) at W = tan(pi f / fs),
    Wc = tan(pi fc / fs): in steady state HPF{x}(t_k) = A |H| sin(2 pi f t_k + arg H) (the 1 g is
    removed). Rectified, then low-passed with DC gain 1: over whole periods the output's mean is the
    mean of |A |H| sin(2 pi f t_k + arg H)| over the samples. Measured from 10 s on, when the start-up
    transients (slowest: the high-pass poles) have decayed below 1e-10 of the level."""
    f, amp, fc = 5.0, 0.2, 0.3
    t = _t(2000)
    r = detect_frd(
        t,
        _scalar_as_acc(1.0 + amp * np.sin(2 * np.pi * f * t)),
        threshold=0.0,
        hp_cutoff_hz=fc,
        lp_cutoff_hz=1.0,
        fs_hz=FS,
    )
    w, wc = math.tan(math.pi * f / FS), math.tan(math.pi * fc / FS)
    h = -(w**2) / (-(w**2) + math.sqrt(2) * wc * 1j * w + wc**2)
    tk = t[1000:2000]  # 10 s: 50 whole periods of the rectified ripple
    want = np.mean(np.abs(amp * abs(h) * np.sin(2 * np.pi * f * tk + np.angle(h))))
    assert want == pytest.approx(2 / math.pi * amp * abs(h), rel=2e-3)  # ~ the continuous mean
    assert np.mean(r.merit[1000:2000]) == pytest.approx(want, rel=1e-9)
    assert (r.merit >= 0).all()  # a first-order low-pass of a rectified signal never goes negative


def test_fsd_eq8_is_the_frame_energy_over_a_flat_noise():
    """Parseval for the zero-padded 512-point DFT: 1/512 sum_l |X(l)|^2 = sum_k x_k^2. With a flat
    noise spectrum N(l) = c, eq. (8) is 10 log10(sum_k x_k^2 / c^2)."""
    x = [1, 2, 3, 6, 2, 4]  # frames (window 2, shift 2): (1, 2), (3, 6), (2, 4): energies 5, 45, 20
    c = 0.5
    r = detect_fsd(
        _t(6),
        _scalar_as_acc(x),
        window=2,
        shift=2,
        threshold=20.0,
        noise_spectrum=np.full(N_BANDS, c),
        fs_hz=FS,
    )
    e = [10 * math.log10(v / c**2) for v in (5, 45, 20)]  # 13.0, 22.6, 19.0 dB
    # sample k has the merit of the last frame ending at or before it (frame n ends at 2n + 1)
    _close(r.merit, [NAN, e[0], e[0], e[1], e[1], e[2]])
    np.testing.assert_array_equal(r.marker, [1, 0, 0, 1, 1, 0])


def test_ltsd_eq6_7_envelope_of_scaled_frames():
    """Frames that are one shape (1, 2) scaled by s_n: X(l, n) = s_n X_1(l) in every band, so the
    envelope over frames n-1..n+1 is max(s) X_1 and eq. (7) is 10 log10(max(s)^2 * 5 / c^2). V(n) is
    known when frame n + 1 ends (sample 2n + 3)."""
    s = [1, 2, 3, 0.5, 0.5, 0.5]
    x = np.concatenate([[v, 2 * v] for v in s])
    c = 1.0
    r = detect_ltsd(
        _t(12),
        _scalar_as_acc(x),
        window=2,
        shift=2,
        threshold=0.0,
        order=1,
        noise_spectrum=np.full(N_BANDS, c),
        fs_hz=FS,
    )
    v = [10 * math.log10(max(s[max(0, n - 1) : n + 2]) ** 2 * 5 / c**2) for n in range(5)]
    # envelopes: frame 0 {1, 2} -> 2; 1 {1, 2, 3} -> 3; 2 {2, 3, .5} -> 3; 3 {3, .5, .5} -> 3; 4 -> 0.5
    assert v[0] == pytest.approx(10 * math.log10(20)) and v[4] == pytest.approx(10 * math.log10(1.25))
    _close(r.merit, [NAN, NAN, NAN, v[0], v[0], v[1], v[1], v[2], v[2], v[3], v[3], v[4]])


@pytest.mark.parametrize("detect", [detect_fsd, detect_ltsd])
def test_spectral_merit_of_the_noise_itself_is_zero_db(detect):
    """Identical frames (a signal periodic with the shift): the noise spectrum learnt on the first
    frames is every frame's spectrum, and the envelope of identical frames is the frame: 0 dB."""
    x = np.tile([1.0, 1.02, 0.97, 1.01, 0.99], 40)  # period 5 = the shift
    r = detect(_t(200), _scalar_as_acc(x), window=7, shift=5, threshold=1.0, noise_frames=4, fs_hz=FS)
    ok = np.isfinite(r.merit)
    assert ok.sum() > 150
    np.testing.assert_allclose(r.merit[ok], 0.0, atol=1e-9)


def test_mbgtd_eq9_10():
    x = [0, 1, 3, 7, 7]
    # buffer (0, 1, 3, 7), splits (first | second): 0|1,3,7 -> 11/3; 0,1|3,7 -> 18/4; 0,1,3|7 -> 17/3;
    #   1|3,7 -> 8/2; 1,3|7 -> 10/2; 3|7 -> 4: max 17/3
    # buffer (1, 3, 7, 7): 1|3,7,7 -> 14/3; 1,3|7,7 -> 20/4; 1,3,7|7 -> 10/3; 3|7,7 -> 8/2; 3,7|7 -> 4/2;
    #   7|7 -> 0: max 5
    r = detect_mbgtd(_t(5), _scalar_as_acc(x), window=4, threshold=5.5, fs_hz=FS)
    _close(r.merit, [NAN, NAN, NAN, 17 / 3, 5.0])
    np.testing.assert_array_equal(r.marker, [1, 1, 1, 1, 0])


def test_mbcd_eq12_14():
    x = [0, 0, 2, 2, 2]
    # kernel w = exp(-d^2 / 2) (lambda 1): w = 1 at d = 0, e^-2 at d = 2.
    # buffer (0, 0, 2, 2): split 0,0 | 2,2: each of the two l has a second-window mean 1 and a
    #   first-window mean e^-2: log e^2 = 2 each, S = 4 (every other split is lower, e.g. 0 | 0,2,2:
    #   log((1 + 2e^-2)/3) + 2 log((2 + e^-2)/(3 e^-2)) = 2.46)
    # buffer (0, 2, 2, 2): split 0 | 2,2,2: three terms of 2, S = 6
    r = detect_mbcd(_t(5), _scalar_as_acc(x), window=4, threshold=5.0, bandwidth=1.0, fs_hz=FS)
    _close(r.merit, [NAN, NAN, NAN, 4.0, 6.0])
    np.testing.assert_array_equal(r.marker, [1, 1, 1, 0, 1])


def _naive_mbgtd(x, n):
    """Eq. (9)-(10) as written: every split (i, j), its double sum of distances."""
    out = []
    for e in range(n - 1, len(x)):
        w = x[e - n + 1 : e + 1]
        best = -math.inf
        for i in range(n):
            for j in range(i + 1, n):
                s = sum(abs(w[k] - w[l]) for k in range(i, j) for l in range(j, n))
                best = max(best, s / ((j - i) * (n - j)))
        out.append(best)
    return np.array(out)


def _naive_mbcd(x, n, lam):
    """Eq. (12)-(14) as written, with plain exp and log."""
    out = []
    for e in range(n - 1, len(x)):
        w = x[e - n + 1 : e + 1]
        k_ = [[math.exp(-0.5 * ((w[a] - w[b]) / lam) ** 2) for b in range(n)] for a in range(n)]
        best = -math.inf
        for i in range(n):
            for j in range(i + 1, n):
                s = 0.0
                for l in range(j, n):
                    post = sum(k_[l][k] for k in range(j, n)) / (n - j)
                    pre = sum(k_[l][k] for k in range(i, j)) / (j - i)
                    s += math.log(post / pre)
                best = max(best, s)
        out.append(best)
    return np.array(out)


@pytest.mark.parametrize("n", [2, 3, 6, 9])
def test_memory_merits_equal_the_equations_written_as_loops(n):
    x = np.random.default_rng(n).normal(1.0, 0.3, 40)
    np.testing.assert_allclose(mbgtd_merits(x, n), _naive_mbgtd(list(x), n), rtol=1e-12)
    # lambda of the data's spread: every kernel weight is far from underflow, so the plain-domain loop
    # is exact enough to compare with (the log-domain sums differ only by rounding)
    np.testing.assert_allclose(mbcd_merits(x, n, 0.4), _naive_mbcd(list(x), n, 0.4), rtol=1e-10, atol=1e-12)


def test_mbcd_stays_finite_where_the_kernel_underflows():
    """Samples 100 bandwidths apart: every weight across the split is exp(-5000) = 0 in double
    precision, and the plain ratio of eq. (13) is log(1/0). In the log domain the split between the
    two levels scores exactly 2 * 100^2 / 2 = 10,000 (two samples, each log(1 / e^-5000))."""
    x = np.array([0.0, 0.0, 100.0, 100.0])
    v = mbcd_merits(x, 4, 1.0)
    assert np.isfinite(v).all()
    _close(v, [10000.0])
