"""The gyroscope presets (sim.sensor.gyroscope) in a sensed flight: the datasheet's noise density at
rest, the output word's step, the unit's offset within its bound; and the sweep's comparison of
methods (its ROC area) on a table whose answer is known."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.stats import chi2

from flightmode.errors import SensorError
from flightmode.sim.sensor.accelerometer import get_preset as accel_preset
from flightmode.sim.sensor.carrier import CarrierSpec
from flightmode.sim.sensor.gyroscope import GyroSpec, get_preset
from flightmode.sim.sensor.sensing import sense


@pytest.fixture(scope="module")
def gyro_rec(fly_cached):
    _, tr = fly_cached("pattern")
    return sense(
        tr,
        CarrierSpec(handled_in_cruise=0),
        accel_preset("lis302dl"),
        np.random.default_rng(3),
        gyro=get_preset("bmi270"),
    )


def test_bmi270_at_rest_has_its_datasheet_noise_step_and_offset(gyro_rec):
    g, rec = get_preset("bmi270"), gyro_rec
    rest = rec.gyro_dps[rec.phase == "terminal_rest"]
    assert rest.shape[0] > 10_000
    # the output word: +-250 deg/s in 16 bits at 131.072 LSB/(deg/s)
    steps = rest / g.lsb_dps
    assert np.allclose(steps, np.rint(steps), atol=1e-6)
    # the noise: 0.007 deg/s/sqrt(Hz) over ODR / 2 = 50 Hz, 0.0495 deg/s RMS; quantisation adds
    # lsb^2 / 12 (the step is 0.0076 deg/s: 1 % of the variance). Sample variance of n white samples:
    # (n - 1) s^2 / sigma^2 ~ chi2(n - 1), two-sided 1e-6 per axis
    sigma = math.hypot(0.007 * math.sqrt(100.0 / 2.0), g.lsb_dps / math.sqrt(12.0))
    n = rest.shape[0]
    for ax in range(3):
        stat = (n - 1) * rest[:, ax].var(ddof=1) / sigma**2
        assert chi2.ppf(5e-7, n - 1) < stat < chi2.ppf(1 - 5e-7, n - 1)
    # the unit's zero-rate offset: within +-0.5 deg/s (the mean of n samples is good to 4e-4 deg/s)
    assert np.all(np.abs(rest.mean(axis=0)) <= g.bias_tol_dps + 0.002)
    # a turn beyond the range saturates at it
    assert g.range_dps == 250.0 and np.abs(rec.gyro_dps).max() <= 250.0


def test_the_rest_before_the_flight_calibrates_both_sensors(gyro_rec):
    """stream_rest("rest"): the longest run of truly static samples before the in-flight window, the
    accelerometer's and the gyroscope's rows of it (what the gyroscope detectors calibrate on)."""
    from flightmode.runs.pipeline import stream_rest

    rec = gyro_rec
    cols = {
        "acc_g": rec.acc_g,
        "gyro_dps": rec.gyro_dps,
        "sensor_static": rec.sensor_static,
        "in_flight_window": rec.in_flight_window,
    }
    acc, gyr, said = stream_rest("rest", cols, None)
    assert gyr.shape == acc.shape and said == f"{acc.shape[0]} truly static samples before the flight"
    # the runs of truly static samples before the window, found here independently
    t_push = rec.t_s[np.flatnonzero(rec.in_flight_window)[0]]
    st = rec.sensor_static & (rec.t_s < t_push)
    edges = np.flatnonzero(np.diff(np.concatenate([[0], st.astype(np.int8), [0]])))
    lengths = edges[1::2] - edges[::2]
    a = int(edges[::2][np.argmax(lengths)])
    assert acc.shape[0] == lengths.max()  # the longest run
    assert np.array_equal(acc, rec.acc_g[a : a + acc.shape[0]]) and np.array_equal(
        gyr, rec.gyro_dps[a : a + acc.shape[0]]
    )


def test_presets_and_bad_input():
    assert get_preset("generic") == GyroSpec()
    assert get_preset("bmi270").noise_rms_dps(200.0) == pytest.approx(0.07)
    with pytest.raises(SensorError, match="bmi270"):
        get_preset("bmi27")
    with pytest.raises(SensorError, match="range"):
        GyroSpec(range_dps=0.0).validate()


def test_compare_methods_auc_is_the_area_under_the_k_sweep():
    """One flight, one method, two thresholds with known rates: the ROC through (0, 0), (0.1, 0.5),
    (0.3, 0.9), (1, 1) has the trapezoid area 0.025 + 0.14 + 0.665 = 0.83."""
    import pyarrow as pa

    from flightmode.studies.sweep import compare_methods

    base = {
        "dataset": "d",
        "family": "f",
        "flight_id": "0",
        "sensor_preset": "p",
        "method": "nmv",
        "weight": 1.0,
        "window_s": 1.0,
        "time_threshold_s": 4.0,
        "in_window_h": 1.0,
        "in_flight_checks": 1000,
        "static_s": 100.0,
        "suspend_s": 1.0,
        "response_s": 2.0,
        "checks": 2000,
    }
    rows = [
        base
        | {
            "k": 2.0,
            "false_static_count": 3,
            "false_static_s": 100.0,
            "missed_static_s": 50.0,
            "accuracy": 0.9,
        },
        base
        | {
            "k": 4.0,
            "false_static_count": 9,
            "false_static_s": 300.0,
            "missed_static_s": 10.0,
            "accuracy": 0.8,
        },
    ]
    (r,) = compare_methods(pa.Table.from_pylist(rows))
    assert r["auc"] == pytest.approx(0.83)
    # the best point: the lower bound on false statics (k 2), its accuracy
    assert r["k"] == 2.0 and r["accuracy"] == pytest.approx(0.9) and r["roc_points"] == 2
