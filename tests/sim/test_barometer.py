"""Barometer presets and the measurement chain (sim.sensor.barometer): the datasheet noise at rest,
quantisation, the unit's offset and TCO, ODR sampling, saturation, bad input."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest
from scipy.stats import chi2

from flightmode.errors import SensorError
from flightmode.sim.sensor.barometer import (
    BMP581_TABLE9,
    PRESETS,
    BaroUnit,
    draw_unit,
    get_preset,
    measure,
    with_odr,
)
from flightmode.units import HPA_PA

NOISY = [name for name, p in PRESETS.items() if p.noise_pa > 0]


def _at_rest(preset, seconds, seed, p_pa=100_000.0):
    # the BMP581's Table 9 is "at 100 kPa"; a perfect unit (no offset) on a bench
    t = np.arange(0.0, seconds + 1e-9, 0.01)
    return measure(t, np.full(t.shape, p_pa), preset, np.random.default_rng(seed), unit=BaroUnit())


@pytest.mark.parametrize("name", NOISY)
def test_noise_at_rest_reproduces_the_datasheet_rms(name):
    p = get_preset(name)
    _, y = _at_rest(p, 120.0, seed=17)
    n = y.size
    # white noise sigma plus the quantisation's lsb^2 / 12 (Sheppard: the step is below sigma / 4)
    var = p.noise_pa**2 + (p.lsb_pa**2 / 12.0 if p.lsb_pa else 0.0)
    stat = (n - 1) * y.var(ddof=1) / var  # chi-square with n - 1 degrees of freedom
    assert chi2.ppf(0.0005, n - 1) < stat < chi2.ppf(0.9995, n - 1)  # a 99.9 % two-sided interval
    # and white: lag-1 autocorrelation within 4 standard errors of zero
    d = y - y.mean()
    assert abs(np.dot(d[1:], d[:-1]) / np.dot(d, d)) < 4.0 / np.sqrt(n)


@pytest.mark.parametrize("odr", [1.0, 25.0, 200.0])
def test_lps22hh_noise_per_odr(odr):
    p = with_odr("lps22hh", odr)
    t_out, y = _at_rest(p, 3000.0 / odr, seed=int(odr))  # 3000 samples whatever the rate
    assert np.allclose(np.diff(t_out), 1.0 / odr)
    n = y.size
    stat = (n - 1) * y.var(ddof=1) / (p.noise_pa**2 + p.lsb_pa**2 / 12.0)
    assert chi2.ppf(0.0005, n - 1) < stat < chi2.ppf(0.9995, n - 1)


def test_the_bmp581_presets_are_its_table_9():
    for osr, (noise, odr_max) in BMP581_TABLE9.items():
        p = get_preset(f"bmp581-osr{osr}")
        assert p.noise_pa == noise and max(p.allowed_odr_hz) <= odr_max and p.lsb_pa == 1 / 64
    assert get_preset("bmp581").noise_pa == 0.21  # x16, the tracker default


def test_quantisation_step():
    for name in ("bmp581", "lps22hh"):
        p = get_preset(name)
        quiet = dataclasses.replace(p, noise_pa=0.0)
        t = np.linspace(0.0, 100.0, 10001)
        truth = 95_000.0 + 0.05 * t  # a slow ramp: 0.05 Pa/s
        t_out, y = measure(t, truth, quiet, np.random.default_rng(0), unit=BaroUnit())
        k = y / p.lsb_pa
        np.testing.assert_array_equal(k, np.rint(k))  # every reading a whole number of steps
        steps = np.unique(np.rint(np.diff(k)))
        assert set(steps) <= {0.0, 1.0}  # a ramp slower than a step per sample: 0 or one step
        assert np.abs(y - np.interp(t_out, t, truth)).max() <= p.lsb_pa / 2 + 1e-9


def test_the_unit_offset_and_temperature_coefficient():
    p = get_preset("bmp581")
    units = [draw_unit(p, np.random.default_rng(i)) for i in range(2000)]
    off = np.array([u.offset_pa for u in units])
    assert np.abs(off).max() <= 0.5 * HPA_PA  # within the absolute accuracy
    assert off.std() == pytest.approx(0.5 * HPA_PA / np.sqrt(3), rel=0.06)  # uniform in +-50 Pa
    ideal = get_preset("ideal")
    t = np.linspace(0.0, 10.0, 1001)
    unit = BaroUnit(offset_pa=12.0, tco_pa_per_k=0.4)
    _, y = measure(
        t,
        np.full(t.shape, 1e5),
        ideal,
        np.random.default_rng(0),
        unit=unit,
        temperature_c=np.full(t.shape, 35.0),
    )
    np.testing.assert_allclose(y, 1e5 + 12.0 + 0.4 * 10.0, rtol=0, atol=1e-9)


def test_the_ideal_barometer_samples_the_truth_at_the_odr():
    t = np.arange(0.0, 60.0, 1 / 120)
    truth = 101_325.0 - 12.0 * t
    t_out, y = measure(t, truth, "ideal", np.random.default_rng(0))
    assert t_out[0] == 0.0 and np.allclose(np.diff(t_out), 1 / 25) and t_out[-1] <= t[-1]
    np.testing.assert_allclose(y, 101_325.0 - 12.0 * t_out, rtol=0, atol=1e-8)


def test_saturation_below_the_range_in_an_unpressurised_hold():
    t = np.arange(0.0, 10.0, 0.1)
    fl350 = np.full(t.shape, 238.4 * HPA_PA)  # FL350 ambient, below the LPS22HH's 260 hPa
    _, y = measure(t, fl350, "lps22hh", np.random.default_rng(0), unit=BaroUnit())
    lo = get_preset("lps22hh").range_pa[0]
    assert np.all(np.abs(y - lo) <= get_preset("lps22hh").lsb_pa)


def test_same_seed_same_output_and_the_unit_is_drawn_first():
    t = np.arange(0.0, 20.0, 0.01)
    p = np.full(t.shape, 9.9e4)
    a = measure(t, p, "bmp581", np.random.default_rng(5))
    b = measure(t, p, "bmp581", np.random.default_rng(5))
    assert np.array_equal(a[1], b[1])
    rng = np.random.default_rng(5)
    unit = draw_unit(get_preset("bmp581"), rng)
    c = measure(t, p, "bmp581", rng, unit=unit)
    assert np.array_equal(a[1], c[1])


def test_bad_input_raises_typed_one_line_errors():
    t = np.arange(0.0, 10.0, 0.1)
    p = np.full(t.shape, 1e5)
    cases = [
        ('did you mean "bmp581"', lambda: measure(t, p, "bmp58", np.random.default_rng(0))),
        ("NaN", lambda: measure(t, np.where(t == t[20], np.nan, p), "bmp581", np.random.default_rng(0))),
        ("not increasing", lambda: measure(t[::-1], p, "bmp581", np.random.default_rng(0))),
        ("allowed: 1, 10, 25, 50, 75, 100, 200 Hz", lambda: with_odr("lps22hh", 30.0)),
        ("allowed", lambda: with_odr("bmp581-osr128", 25.0)),  # x128 runs at 12 Hz at most
    ]
    for text, call in cases:
        with pytest.raises(SensorError) as e:
            call()
        assert text in str(e.value) and "\n" not in str(e.value)
