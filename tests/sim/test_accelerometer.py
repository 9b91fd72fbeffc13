"""Accelerometer presets and the measurement chain (sim.accelerometer)."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest
from scipy.signal import welch

from flightmode.sim.sensor.accelerometer import (
    PRESETS,
    SensorError,
    UnitDraw,
    draw_unit,
    get_preset,
    measure,
    noise_psd_g2_per_hz,
)

SIGMA_G = 2.23e-3  # seed 000 Table 1


def _static(preset, hours, rng, g_vec=(0.0, 0.0, 1.0), unit=None):
    n = int(hours * 3600 * preset.odr_hz)
    f = np.broadcast_to(np.asarray(g_vec, float), (n, 3))
    return measure(f, preset.odr_hz, 0.0, preset, unit or UnitDraw(), rng)


@pytest.mark.slow
def test_logged16_static_noise_is_white_with_uncorrelated_axes_and_5e_6_g2():
    from flightmode.sim.sensor.accelerometer import noise_variance_spread_factor

    p = get_preset("lis302dl-logged16")
    m = _static(p, 10.0, np.random.default_rng(7))  # 10 simulated hours, 3.6 million samples/axis
    x = m.acc_g - m.acc_g.mean(axis=0)
    var = x.var(axis=0)
    # within 3 % of (2.23 mg)^2: the estimator's own spread is sqrt(F / N) for the modulated noise
    # (noise_variance_spread_factor, F = 15: its squares correlate through the amplitude), 0.2 %,
    # and the 0.07 mg quantisation adds lsb^2/12 = 4e-10 g^2 (0.01 %)
    assert np.sqrt(noise_variance_spread_factor(p) / x.shape[0]) < 0.003
    np.testing.assert_allclose(var, SIGMA_G**2, rtol=0.03)
    # independent axes (and white): the cross-correlation at lags -20..20 samples has the standard
    # error 1 / sqrt(N) = 0.0005; 0.01 is 19 of them
    n = x.shape[0]
    for i, j in [(0, 1), (0, 2), (1, 2)]:
        for lag in range(-20, 21):
            a, b = (x[lag:, i], x[: n - lag, j]) if lag >= 0 else (x[: n + lag, i], x[-lag:, j])
            assert abs(np.dot(a, b) / (a.size * np.sqrt(var[i] * var[j]))) < 0.01, (i, j, lag)
    # the spectrum is the model's: flat at 2 sigma^2 / ODR (seed 000 section 4.1, Fig. 4)
    fr, pxx = welch(x[:, 0], fs=p.odr_hz, nperseg=1024)
    model = noise_psd_g2_per_hz(p, fr)
    rel = pxx[2:512] / model[2:512] - 1.0  # bins 0, 1 (segment mean removal) and Nyquist excluded
    # Welch's own spread: K = 7030 Hann segments at 50 % overlap; overlapping segments' periodograms
    # correlate by c^2 = (sum_{n<L/2} w_n w_n+L/2 / sum w_n^2)^2 = 1/36, so var/PSD^2 = (1 + 2 c^2) / K
    # (Welch 1967): 1.2 % per bin. Tolerance 5 of them per bin (510 bins: a chance failure ~3e-4);
    # the amplitude's slow wander adds a little (a white process's periodogram bins stay unbiased)
    w = np.hanning(1025)[:-1]
    k_seg = (x.shape[0] - 1024) // 512 + 1
    c2 = (np.dot(w[:512], w[512:]) / np.dot(w, w)) ** 2
    sd_bin = np.sqrt((1.0 + 2.0 * c2) / k_seg)
    assert 0.012 < sd_bin < 0.014
    assert np.abs(rel).max() < 5 * sd_bin + 0.0025, np.abs(rel).max()
    # ten bands of 51 bins: adjacent Hann bins correlate by 4/9, the next by 1/36, so a band mean
    # has var (1 + 2 (4/9 + 1/36)) / 51 of a bin's: 0.26 %; 5 of them plus a margin
    band_sd = sd_bin * np.sqrt((1.0 + 2.0 * (4 / 9 + 1 / 36)) / 51)
    assert np.abs(rel[:510].reshape(10, 51).mean(axis=1)).max() < 5 * band_sd + 0.0025
    # the lowest and highest fifths of the band are equal (white); each is a mean of ~100 bins (sd
    # 0.18 %), so the ratio is known to 0.26 %: 2 % is 5 of them plus a margin (the Gauss-Markov
    # model before issue 53 had 14 here)
    lo, hi = pxx[2:103].mean(), pxx[410:512].mean()
    assert lo / hi == pytest.approx(1.0, rel=0.02)
    # it integrates to the variance: sum S df = sigma^2 (the PSD's own normalisation)
    assert pxx.sum() * (fr[1] - fr[0]) == pytest.approx(SIGMA_G**2, rel=0.03)


def test_native_8bit_static_variance_is_far_below_the_noise():
    """An 18 mg step is 8 sigma: most samples round to the same count (LIS302DL datasheet step, seed
    000 Table 1 noise). x and y sit at 0 g, mid-step between two thresholds at +-9 mg = 4.04 sigma, so
    a sample flips by one step with the probability E_g[2 Phi(-4.04 sqrt(1 + d^2) / |1 + d g|)] =
    0.19 % for the modulated noise (sim.sensor.accelerometer: the amplitude's peaks make it 36 times
    the Gaussian 5.3e-5), and the variance is that times (18 mg)^2: 6.2e-7 g^2, 0.12 sigma^2. Half an
    hour holds ~340 flips per axis, clustered by the amplitude's 0.1 s memory (its standard error
    about twice Poisson's 5 %): 35 % is more than 3 of them."""
    from scipy.integrate import quad
    from scipy.stats import norm

    p = get_preset("lis302dl")
    m = _static(p, 0.5, np.random.default_rng(1))
    var = m.acc_g.var(axis=0)
    d = p.noise_am_depth
    h = (p.lsb_g / 2) / p.noise_g

    def flip(g):
        return norm.pdf(g) * 2 * norm.sf(h * np.sqrt(1 + d * d) / max(abs(1 + d * g), 1e-12))

    p_flip = quad(flip, -12, 12, points=[-1 / d], limit=200)[0]
    assert p_flip == pytest.approx(1.9e-3, rel=0.01)
    np.testing.assert_allclose(var[:2], p_flip * p.lsb_g**2, rtol=0.35)
    assert np.all(var[:2] < 0.2 * SIGMA_G**2)
    print(f"\nlis302dl 8-bit static variance per axis (g^2): {var}")


def test_unit_draws_are_within_tolerance_and_seeded():
    p = get_preset("lis302dl")
    a = draw_unit(p, np.random.default_rng(5))
    b = draw_unit(p, np.random.default_rng(5))
    c = draw_unit(p, np.random.default_rng(6))
    np.testing.assert_array_equal(a.offset_g, b.offset_g)
    assert not np.array_equal(a.offset_g, c.offset_g)
    assert np.all(np.abs(a.offset_g) <= p.offset_tol_g)
    assert np.all(np.abs(a.sensitivity_err) <= p.sensitivity_tol)
    assert np.all(np.diag(a.cross_axis) == 0) and np.all(np.abs(a.cross_axis) <= p.cross_axis_tol)


def test_resting_norm_is_one_g_up_to_the_offsets_and_counts_carry_the_gain_error():
    p = get_preset("lis302dl-logged16")
    rng = np.random.default_rng(11)
    unit = draw_unit(p, rng)
    g = np.array([0.3, -0.5, 0.81240384])  # a tilted bag; |g| = 1
    m = _static(p, 0.1, rng, g, unit)
    mean = m.acc_g.mean(axis=0)
    expected = (np.eye(3) + unit.cross_axis) @ g + unit.offset_g
    np.testing.assert_allclose(mean, expected, atol=1e-4)  # noise / sqrt(36000) ~ 1e-5 g
    # with a perfect unit the norm is 1 g to the quantisation
    m0 = _static(p, 0.1, rng, g)
    assert np.linalg.norm(m0.acc_g.mean(axis=0)) == pytest.approx(1.0, abs=2e-4)
    # the raw counts are divided by the unit's own sensitivity
    lsb_unit = p.lsb_g * (1 + unit.sensitivity_err)
    np.testing.assert_allclose(m.counts.mean(axis=0) * lsb_unit, mean, atol=1e-6)


def test_saturation_never_exceeds_the_range():
    p = get_preset("lis302dl")
    f = np.zeros((1000, 3))
    f[:, 2] = 1.0
    f[500:505] = [6.0, -7.0, 9.0]  # a dropped bag hitting the floor
    m = measure(f, p.odr_hz, 0.0, p, UnitDraw(), np.random.default_rng(0))
    assert m.counts.max() == 127 and m.counts.min() == -128
    assert np.all(np.abs(m.acc_g) <= p.range_g + p.lsb_g)
    assert m.clipped[500:505].all() and not m.clipped[:400].any()


def test_eobs_counts_are_offset_binary_12_bit():
    p = get_preset("eobs")
    f = np.tile([0.0, 0.0, 1.0], (100, 1))
    m = measure(f, p.odr_hz, 0.0, p, UnitDraw(), np.random.default_rng(0))
    # seed 003 section 6: a = (n - 2048) * 0.0022 g, so 1 g is about 455 counts above 2048
    assert np.all((m.counts >= 0) & (m.counts <= 4095))
    assert abs(np.median(m.counts[:, 2]) - (2048 + 1 / 0.0022)) <= 1
    assert abs(np.median(m.counts[:, 0]) - 2048) <= 1


def test_ideal_preset_is_exact():
    p = get_preset("ideal")
    f = np.random.default_rng(2).normal(0, 0.3, (400, 3))
    m = measure(f, 400.0, 0.0, p, UnitDraw(), np.random.default_rng(0))
    np.testing.assert_array_equal(m.acc_g, f[::4])


def test_bad_input_is_named():
    with pytest.raises(SensorError, match=r"unknown sensor preset 'lis302d'.*did you mean \"lis302dl\""):
        get_preset("lis302d")
    p = dataclasses.replace(get_preset("lis302dl"), odr_hz=200.0)
    with pytest.raises(SensorError, match=r"200 Hz is not one the part has; allowed: 100, 400"):
        measure(np.zeros((10, 3)), 200.0, 0.0, p, UnitDraw(), np.random.default_rng(0))
    f = np.zeros((10, 3))
    f[4, 1] = np.nan
    with pytest.raises(SensorError, match="NaN or inf \\(first at sample 4\\)"):
        measure(f, 100.0, 0.0, get_preset("lis302dl"), UnitDraw(), np.random.default_rng(0))
    with pytest.raises(SensorError, match="not an integer multiple"):
        measure(np.zeros((10, 3)), 150.0, 0.0, get_preset("lis302dl"), UnitDraw(), np.random.default_rng(0))


# Datasheet facts per preset: (bits, zero-g count, count range, g per count, ODRs, anti-alias
# bandwidth as a fraction of the ODR or None, noise g, +-sensitivity tolerance).
# LIS302DL datasheet, Table 3: FS = 0 sensitivity 16.2 / 18 / 19.8 mg/digit (+-10 %), measurement
# range +-2.3 g typ.; FS = 1 64.8 / 72 / 79.2 mg/digit, +-9.2 g typ.; 8-bit two's complement output (OUT_X/Y/Z), ODR 100 or 400 Hz, bandwidth ODR / 2. Noise:
# seed 000 Table 1 (2.23 mg). logged16: seed 000 section 2, the +-2.3 g span stored in 16 bits.
# e-obs: seed 003 section 6, readings 0...4095 (12 bits), zero-g 2048 nominal, 0.0022 g per count
# (tags > 2241); section 1, no anti-alias filter; per-axis rates: the 10 and 100 Hz totals over 1-3 axes
# (sections 4.1, 4.2, 10; sim.sensor.accelerometer.EOBS_PER_AXIS_RATES_HZ).
DATASHEET = {
    "lis302dl": (8, 0, (-128, 127), 0.018, (100.0, 400.0), 0.5, 2.23e-3, 0.10),
    "lis302dl-8g": (8, 0, (-128, 127), 0.072, (100.0, 400.0), 0.5, 2.23e-3, 0.10),
    "lis302dl-logged16": (16, 0, (-32768, 32767), 4.6 / 2**16, (100.0, 400.0), 0.5, 2.23e-3, 0.10),
    "eobs": (12, 2048, (0, 4095), 0.0022, (3.33, 5.0, 10.0, 33.33, 50.0, 100.0), None, None, None),
}


def test_every_preset_validates():
    """Each preset carries its part's published numbers, its range is what its counts can hold, and
    the chain saturates exactly at the extreme counts. The published ranges are rounded: +-2.3 g
    against 128 x 18 mg = 2.304 g, +-9.2 g against 128 x 72 mg = 9.216 g, +-4.5 g against
    2048 x 2.2 mg = 4.506 g; so range_g must be the count span times the step within half a step
    (the rounding of the printed figure), and within 0.5 % of the printed range."""
    assert set(PRESETS) == set(DATASHEET) | {"ideal"}
    published_range_g = {"lis302dl": 2.3, "lis302dl-8g": 9.2, "lis302dl-logged16": 2.3, "eobs": 4.5}
    for name, (bits, zero, crange, lsb, odrs, bw, noise, sens) in DATASHEET.items():
        p = PRESETS[name]
        p.validate()
        assert p.bits == bits and p.zero_count == zero and p.count_range == crange, name
        assert crange[1] - crange[0] + 1 == 2**bits  # the word holds exactly 2^bits codes
        assert p.lsb_g == pytest.approx(lsb, rel=1e-12), name
        assert set(odrs) == set(p.allowed_odr_hz), name
        # negative full scale: the counts below zero-g times the step
        span_g = (zero - crange[0]) * lsb
        assert abs(p.range_g - span_g) <= lsb / 2, (name, p.range_g, span_g)
        assert p.range_g == pytest.approx(published_range_g[name], rel=0.005), name
        if bw is None:
            assert p.bandwidth_hz is None, name
        else:
            assert p.bandwidth_hz == pytest.approx(bw * p.odr_hz), name
        if noise is not None:
            assert p.noise_g == noise and p.sensitivity_tol == sens, name
        # a +-100 g shock pins the output at the extreme counts, which read (count - zero) x step:
        # one step less on the positive side (2^bits codes, zero-g among them)
        f = np.zeros((40, 3))
        f[:20] = 100.0
        f[20:] = -100.0
        m = measure(
            f,
            p.odr_hz,
            0.0,
            dataclasses.replace(p, bandwidth_hz=None, noise_g=0.0),
            UnitDraw(),
            np.random.default_rng(0),
        )
        assert (m.counts[:20] == crange[1]).all() and (m.counts[20:] == crange[0]).all(), name
        assert m.acc_g.min() == pytest.approx(-span_g, rel=1e-12) and m.clipped.all(), name
        assert m.acc_g.max() == pytest.approx((crange[1] - zero) * lsb, rel=1e-12), name
    # logged16: 0.07 mg steps, 32 times finer than the 2.23 mg noise (the noise survives)
    assert PRESETS["lis302dl-logged16"].lsb_g == pytest.approx(7.02e-5, rel=1e-3)
    # ideal: a float output, no noise, no filter, no tolerances
    ideal = PRESETS["ideal"]
    ideal.validate()
    assert ideal.lsb_g is None and ideal.bits is None and ideal.bandwidth_hz is None
    assert ideal.noise_g == ideal.offset_tol_g == ideal.sensitivity_tol == ideal.cross_axis_tol == 0.0


def test_chunked_sensing_equals_one_piece():
    from flightmode.sim.sensor.accelerometer import SensorChain

    p = get_preset("lis302dl")
    f = np.random.default_rng(3).normal(0, 0.05, (12000, 3)) + [0, 0, 1]
    unit = draw_unit(p, np.random.default_rng(4))
    whole = SensorChain(p, unit, 1200.0)(f, 0.0, np.random.default_rng(9))
    chain, rng = SensorChain(p, unit, 1200.0), np.random.default_rng(9)
    parts = [chain(f[a:b], 0.0, rng) for a, b in [(0, 1000), (1000, 1001), (1001, 7777), (7777, 12000)]]
    np.testing.assert_array_equal(np.concatenate([m.counts for m in parts]), whole.counts)
    np.testing.assert_array_equal(np.concatenate([m.t_s for m in parts]), whole.t_s)


def test_eobs_burst_table_and_worked_examples():
    """Seed 003 section 9: byte count 800 on firmware up to rv4_s1 gives 747 data bytes, 768 bytes of
    memory and 498 samples, 249 per axis with two axes; section 10: 1197 on newer firmware gives
    792 samples, 7.92 s at 100 Hz in total."""
    from flightmode.sim.sensor.accelerometer import eobs_burst, eobs_preset

    assert eobs_burst(800, 2, newer_firmware=False) == (249, 747, 768)
    per_axis, data, mem = eobs_burst(1197, 3, newer_firmware=True)
    assert (data, mem) == (1188, 1216) and per_axis * 3 == 792
    # a few rows of the table: setting -> data bytes, samples (all axes)
    for setting, data_bytes, samples in [
        (1, 54, 36),
        (63, 54, 36),
        (64, 117, 78),
        (442, 495, 330),
        (693, 684, 456),
    ]:
        got = eobs_burst(setting, 1)
        assert got[1] == data_bytes and got[0] == samples
    p = eobs_preset(acc_interval_s=1.0, byte_count=1197, odr_per_axis_hz=33.33)
    assert p.burst_samples == 264 and p.burst_samples / p.odr_hz == pytest.approx(7.92, abs=0.01)
    # section 10: an interval shorter than the burst samples (nearly) continuously
    assert p.burst_interval_s < p.burst_samples / p.odr_hz
    with pytest.raises(SensorError, match="byte count must be >= 0"):
        eobs_burst(-1, 3)
