"""Per-burst DFT (seed 003 section 11) and std after the high-pass (section 12), by hand."""

from __future__ import annotations

import numpy as np
import pytest

from flightmode.eobs.burst import AccBurst
from flightmode.eobs.spectrum import (
    bessel_sos,
    burst_dft,
    burst_hp_std,
    dft_frequencies_hz,
    dft_magnitudes,
    hp_std,
    lowpass_forward_backward,
    n_dft_values,
)
from flightmode.errors import SensorError


def _note_formula(a) -> np.ndarray:
    """Section 11.1 written out: r_n = (1/N) |sum_k exp(-2 pi i n k / N) a_k|, 0 <= n <= N/2."""
    a = np.asarray(a, float)
    N = a.size
    k = np.arange(N)
    return np.array([abs(np.sum(np.exp(-2j * np.pi * n * k / N) * a)) / N for n in range(N // 2 + 1)])


def test_number_of_dft_values_is_the_notes():
    # 11.2: "if N=6 you will get four real numbers r_0, r_1, r_2, r_3 ... if N=7 you will also get only four"
    assert n_dft_values(6) == 4 and n_dft_values(7) == 4
    assert len(dft_magnitudes(np.arange(6))) == 4 and len(dft_magnitudes(np.arange(7))) == 4
    # the DFT example of 5.3 is a Z burst with "166" values: N = 330 samples (330 for 442-504 bytes, section 9)
    assert n_dft_values(330) == 166


def test_dft_is_the_notes_sum_divided_by_n():
    rng = np.random.default_rng(11)
    for N in (1, 2, 6, 7, 60, 331):
        a = rng.integers(0, 4096, N)
        # the FFT and the O(N^2) sum differ by float rounding only: about N eps x sum|a| <= 331 x 2.2e-16 x 4095
        np.testing.assert_allclose(dft_magnitudes(a), _note_formula(a), rtol=0, atol=1e-9)


def test_dft_of_a_cosine_by_hand():
    """a_k = D + A cos(2 pi m k / N): r_0 = D, r_m = A / 2 (half the amplitude in +m and half in N-m),
    every other r_n = 0; at n = N/2 a (-1)^k sequence gives r = A. Float rounding ~1e-12 of 2048."""
    N, D, A, m, fs = 120, 2048.0, 300.0, 7, 5.0
    k = np.arange(N)
    r = dft_magnitudes(D + A * np.cos(2 * np.pi * m * k / N))
    expect = np.zeros(N // 2 + 1)
    expect[0], expect[m] = D, A / 2
    np.testing.assert_allclose(r, expect, rtol=0, atol=1e-9)
    np.testing.assert_allclose(dft_magnitudes(A * (-1.0) ** k)[N // 2], A, rtol=1e-12)
    # 11.3: f_n = n / N f_s, f_s per axis: the cosine's m = 7 at 7 / 120 * 5 Hz
    f = dft_frequencies_hz(N, fs)
    assert f[m] == pytest.approx(7 / 24, rel=1e-15) and f[-1] == fs / 2 and len(f) == N // 2 + 1


def test_burst_dft_is_per_axis():
    rng = np.random.default_rng(2)
    raw = rng.integers(1500, 2500, (60, 2))
    f, mags = burst_dft(AccBurst("1", np.datetime64("2008-07-27"), "XY", 5.0, raw, 0))
    assert mags.shape == (31, 2) and f[1] == pytest.approx(5.0 / 60)
    for j in range(2):
        np.testing.assert_allclose(mags[:, j], _note_formula(raw[:, j]), rtol=0, atol=1e-9)


def test_hp_std_of_a_sine_is_the_filter_response_by_hand():
    """Forward-backward filtering is zero-phase with gain |H(f)|^2, so after subtracting the low-pass
    a sine of amplitude A on any offset leaves (1 - |H(f)|^2) A sin(...): std A / sqrt(2) |1 - |H|^2|.
    |H| comes from the filter's frequency response (sosfreqz), not from running it. The ends differ
    (the filter's start-up over the odd-extended edges), a share of the burst that halves as N doubles:
    measured 5.0e-4 A at N = 2000, 2.5e-4 A at N = 4000 (f = 2 f_c, the worst of 1-4 f_c); tolerance
    1e-3 A at N = 2000 and the halving checked to 10 %."""
    from scipy.signal import sosfreqz

    fs, fc, A = 100.0, 5.0, 100.0
    sos = bessel_sos(fs, fc)
    err = {}
    for N in (2000, 4000):
        k = np.arange(N)
        for f in (5.0, 10.0, 20.0):  # whole periods in the burst
            _, h = sosfreqz(sos, worN=[f], fs=fs)
            expect = A / np.sqrt(2) * abs(1 - abs(h[0]) ** 2)
            err[N, f] = hp_std(2048 + A * np.sin(2 * np.pi * f * k / fs), fs, fc) - expect
            assert abs(err[N, f]) <= 1e-3 * A, (N, f, err[N, f])
    assert err[4000, 10.0] / err[2000, 10.0] == pytest.approx(0.5, rel=0.1)
    # 10th order, -3 dB per pass at f_c ('mag' normalisation): the residual at f_c is 1 - 1/2 of the sine
    _, h = sosfreqz(sos, worN=[fc], fs=fs)
    assert abs(h[0]) ** 2 == pytest.approx(0.5, rel=1e-9)


def test_hp_std_edge_cases():
    # a constant burst has no high-frequency part (the low-pass keeps DC exactly, to float rounding)
    assert hp_std(np.full(60, 2048.0), 5.0, 1.0) == pytest.approx(0.0, abs=1e-9)
    # section 12's std is the population one (1/N) of the residual
    rng = np.random.default_rng(4)
    a = rng.integers(1800, 2300, 330).astype(float)
    r = a - lowpass_forward_backward(a, 10.0, 1.0)
    assert hp_std(a, 10.0, 1.0) == pytest.approx(np.sqrt(np.sum((r - r.mean()) ** 2) / 330), rel=1e-12)
    # a short burst (12 samples per axis: 36 samples over 3 axes, the smallest byte count of section 9)
    b = AccBurst("1", np.datetime64("2014-05-11"), "XYZ", 3.33, rng.integers(0, 4096, (12, 3)), 0)
    assert burst_hp_std(b, 0.5).shape == (3,) and np.all(burst_hp_std(b, 0.5) > 0)
    with pytest.raises(SensorError, match=r"cut-off 5 Hz must lie in \(0, f_s/2 = 5 Hz\)"):
        hp_std(a, 10.0, 5.0)
