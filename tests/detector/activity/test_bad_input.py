"""Bad input to any of seed 001's detectors raises DetectorError with one line that names the problem:
the window, the threshold's sign, NaN/inf, time going back or jumping (a gap), shapes, a missing
gyroscope, an unknown signal; in batch and across the chunks of a stream."""

from __future__ import annotations

import numpy as np
import pytest

from flightmode.detector.activity import registry
from flightmode.errors import DetectorError

from ._synthetic import FS_HZ, params, stream

NAMES = registry.NAMES
WINDOWED = [n for n in NAMES if "window" in registry.get(n).parameters]
NONNEGATIVE = [n for n in NAMES if registry.get(n).nonnegative]


def _data(n=300):
    t, a, g, _ = stream([(n / FS_HZ, False)], np.random.default_rng(5))
    return t, a, g


def _p(name, **change):
    d = registry.get(name)
    p = params(name, "acc" if d.signals else None)
    if "window" in p:
        p["window"] = 8
        if "shift" in p:
            p["shift"] = 3
    p.update(change)
    return p


def _raises(match, f, *args, **kw):
    with pytest.raises(DetectorError, match=match) as e:
        f(*args, **kw)
    assert "\n" not in str(e.value)
    return str(e.value)


@pytest.mark.parametrize("name", NAMES)
def test_good_input_runs(name):
    t, a, g = _data()
    r = registry.get(name).detect(t, a, g, **_p(name))
    assert r.marker.shape == r.merit.shape == t.shape


@pytest.mark.parametrize("name", WINDOWED)
def test_window_longer_than_the_signal(name):
    t, a, g = _data(50)
    _raises("longer than the signal", registry.get(name).detect, t, a, g, **_p(name, window=51))


@pytest.mark.parametrize("name", WINDOWED)
@pytest.mark.parametrize("window", [1, 0, -3, 2.5, "8"])
def test_window_too_short_or_not_a_count(name, window):
    t, a, g = _data()
    _raises("window", registry.get(name).detect, t, a, g, **_p(name, window=window))
    _raises("window", registry.get(name).stream, fs_hz=FS_HZ, **_p(name, window=window))


@pytest.mark.parametrize("name", NONNEGATIVE)
def test_negative_threshold_for_a_nonnegative_merit(name):
    t, a, g = _data()
    msg = _raises("never negative", registry.get(name).detect, t, a, g, **_p(name, threshold=-0.1))
    assert "-0.1" in msg


@pytest.mark.parametrize("name", ["ltsd", "fsd"])
def test_a_negative_threshold_in_db_is_allowed_but_not_nan(name):
    t, a, g = _data()
    registry.get(name).detect(t, a, g, **_p(name, threshold=-3.0))
    _raises("finite", registry.get(name).detect, t, a, g, **_p(name, threshold=float("nan")))


@pytest.mark.parametrize("name", NAMES)
@pytest.mark.parametrize("where", ["t_s", "acc_g", "gyr_dps"])
def test_nan_or_inf(name, where):
    t, a, g = _data()
    p = _p(name, signal="sum") if registry.get(name).signals else _p(name)
    t, a, g = t.copy(), a.copy(), g.copy()
    {"t_s": t, "acc_g": a, "gyr_dps": g}[where][123] = np.inf if where == "gyr_dps" else np.nan
    uses_gyro = registry.get(name).needs_gyro or "signal" in p
    if where == "gyr_dps" and not uses_gyro:
        registry.get(name).detect(t, a, g, **p)  # an input the detector does not read is not checked
        return
    _raises(r"NaN or inf in " + where + " at sample 123", registry.get(name).detect, t, a, g, **p)


@pytest.mark.parametrize("name", NAMES)
def test_time_not_increasing(name):
    t, a, g = _data()
    t = t.copy()
    t[100] = t[99]
    _raises("not increasing at sample 100", registry.get(name).detect, t, a, g, **_p(name))


@pytest.mark.parametrize("name", NAMES)
def test_a_gap(name):
    t, a, g = _data()
    t = np.where(np.arange(t.shape[0]) >= 200, t + 0.02, t)  # two missing samples: a 3-period step
    _raises("gap .* before sample 200", registry.get(name).detect, t, a, g, **_p(name))


@pytest.mark.parametrize("name", NAMES)
def test_gap_and_step_back_across_chunks_of_a_stream(name):
    t, a, g = _data()
    det = registry.get(name).stream(fs_hz=FS_HZ, **_p(name))
    det.push(t[:100], a[:100], g[:100])
    _raises("gap .* before sample 100", det.push, t[101:150], a[101:150], g[101:150])
    _raises("not increasing at sample 100", det.push, t[99:150], a[99:150], g[99:150])
    det.push(t[100:150], a[100:150], g[100:150])  # a rejected chunk leaves the state as it was
    assert det.n_samples == 150


@pytest.mark.parametrize("name", NAMES)
def test_shapes_that_do_not_match(name):
    t, a, g = _data()
    det = registry.get(name).detect
    p = _p(name, signal="product") if registry.get(name).signals else _p(name)
    _raises(r"acc_g must be an \(300, 3\)", det, t, a[:, :2], g, **p)
    _raises(r"acc_g must be an \(300, 3\)", det, t, a[:-1], g, **p)
    _raises("t_s must be a 1-D", det, t[:, None], a, g, **p)
    if registry.get(name).needs_gyro or "signal" in p:
        _raises(r"gyr_dps must be an \(300, 3\)", det, t, a, g[:-1], **p)


@pytest.mark.parametrize("name", NAMES)
def test_fs_hz_that_is_not_the_stream_rate(name):
    t, a, g = _data()
    _raises("sampled at 100 Hz but fs_hz = 50", registry.get(name).detect, t, a, g, fs_hz=50.0, **_p(name))


@pytest.mark.parametrize(
    ("name", "signal"),
    [("ared", None), ("shod", None)] + [(n, s) for n in NAMES for s in registry.get(n).signals if s != "acc"],
)
def test_a_gyroscope_detector_without_gyroscope(name, signal):
    t, a, _ = _data()
    p = _p(name, signal=signal) if signal else _p(name)
    fix = r"provide gyr_dps \(a sensor preset with a gyroscope\)"
    msg = _raises(fix, registry.get(name).detect, t, a, None, **p)
    assert msg.startswith(name.upper())


@pytest.mark.parametrize("name", [n for n in NAMES if registry.get(n).signals])
def test_unknown_signal_suggests_the_nearest(name):
    t, a, g = _data()
    _raises('did you mean "product"', registry.get(name).detect, t, a, g, **_p(name, signal="prod"))


def test_spectrum_specific_parameters():
    t, a, g = _data()
    d = registry.get("ltsd").detect
    _raises("longer than the FFT", d, t, a, g, **_p("ltsd", window=513))
    _raises("shift = 0", d, t, a, g, **_p("ltsd", shift=0))
    _raises("order = -1", d, t, a, g, **_p("ltsd", order=-1))
    _raises("noise_spectrum must hold the 257", d, t, a, g, **_p("ltsd", noise_spectrum=np.ones(512)))
    hole = np.r_[1, 1, 1, 0, np.ones(253)]
    _raises("zero or not finite in band 3", d, t, a, g, **_p("ltsd", noise_spectrum=hole))
    # an exactly constant input has no noise to learn: the bands where its spectrum is zero
    const = np.tile([0.0, 0.0, 1.0], (t.shape[0], 1))
    _raises("noiseless", d, t, const, g, **_p("ltsd", window=16))
    # in a stream it is the push that completes the noise frames, and that push changes nothing
    det = registry.get("ltsd").stream(fs_hz=FS_HZ, **_p("ltsd", window=16))
    det.push(t[:50], const[:50], g[:50])
    _raises("noiseless", det.push, t[50:], const[50:], g[50:])
    assert det.n_samples == 50


def test_memory_and_noise_scales_must_be_positive():
    t, a, g = _data()
    _raises("bandwidth = 0", registry.get("mbcd").detect, t, a, g, **_p("mbcd", bandwidth=0.0))
    _raises("sigma_acc_g = -1", registry.get("amd").detect, t, a, g, **_p("amd", sigma_acc_g=-1))
    _raises(
        "sigma_gyr_dps = nan", registry.get("ared").detect, t, a, g, **_p("ared", sigma_gyr_dps=float("nan"))
    )
    _raises("lp_cutoff_hz = 30", registry.get("frd").detect, t, a, g, **_p("frd", lp_cutoff_hz=30.0))
