"""The built-in detectors through the detector interface (detector/builtin.py): every one streams
(any chunking gives the decisions of one push, which is ``decide``), each gives the decisions of the
module it wraps (seed 000's checks, seed 001's checks, the redundant rule's) held per sample, and the
two-source combinator is the AND of its parts."""

from __future__ import annotations

import numpy as np
import pytest

from flightmode.detector import interface
from flightmode.detector.interface import ACC_CHANNELS, GYRO_CHANNELS

FS = 100.0
SIG_G = 2.23e-3  # the LIS302DL's static noise (seed 000 section 5.1)
SIG_DPS = 0.05  # a MEMS gyroscope's at rest
BARO_FS = 25.0
P0_PA = 101_325.0


def _stream(seed: int = 0, rest_s=(90.0, 60.0), moving_s: float = 150.0):
    """t, x in every channel (acc, gyro, held pressure): at rest, then moving (vibration; a cabin
    ramp of -12 Pa/s), then at rest again; and a separate 60 s rest recording of the unit."""
    rng = np.random.default_rng(seed)
    n0, n1, n2 = (int(s * FS) for s in (rest_s[0], moving_s, rest_s[1]))
    n = n0 + n1 + n2
    t = np.arange(n) / FS
    acc = rng.normal(0, SIG_G, (n, 3)) + [0.0, 0.0, 1.0]
    acc[n0 : n0 + n1] += (
        rng.normal(0, 0.02, (n1, 3)) + 0.01 * np.sin(2 * np.pi * 3.0 * t[n0 : n0 + n1])[:, None]
    )
    gyr = rng.normal(0, SIG_DPS, (n, 3))
    gyr[n0 : n0 + n1] += rng.normal(0, 2.0, (n1, 3))
    # the barometer's conversions every 4 rows, each held (as sensing.read_barometer stores it)
    p_true = (
        P0_PA
        - 12.0 * np.clip(t - rest_s[0], 0, moving_s / 2)
        + 12.0 * np.clip(t - rest_s[0] - moving_s / 2, 0, moving_s / 2)
    )
    reading = p_true[::4] + rng.normal(0, 0.2, p_true[::4].shape[0])
    pres = np.repeat(reading, 4)[:n]
    x = np.column_stack([acc, gyr, pres])
    rest = np.column_stack(
        [
            rng.normal(0, SIG_G, (6000, 3)) + [0.0, 0.0, 1.0],
            rng.normal(0, SIG_DPS, (6000, 3)),
            np.full(6000, P0_PA) + rng.normal(0, 0.2, 6000),
        ]
    )
    return t, x, rest


CH = (*ACC_CHANNELS, *GYRO_CHANNELS, "pressure_pa")


def _make(name: str, params: dict | None = None):
    loaded = interface.load(name)
    params = params or {}
    ch = loaded.channels_for(params)
    cols = [CH.index(c) for c in ch]
    return loaded, ch, cols, params


def _build(loaded, ch, params, rest, cols):
    return interface.build(loaded, FS, ch, params, rest[:, cols], sensor_lsb_g=None, baro_fs_hz=BARO_FS)


BUILTINS = [
    ("nmv", {}),
    ("emv", {"weight": 5.0}),
    ("nmv+baro", {"baro_hold_s": 30.0}),  # the 120 s default is longer than the stream's rests
    ("emv+baro", {"baro_hold_s": 30.0, "baro_margin_hpa": 0.0}),
    ("two-source", {"second_params": {"baro_hold_s": 30.0}}),
    ("amvd", {}),
    ("amd", {}),
    ("ared", {}),
    ("shod", {}),
    ("frd", {"signal": "sum"}),
    ("ltsd", {}),
    ("fsd", {}),
    ("mbgtd", {}),
    ("mbcd", {"window_s": 0.5}),
]


@pytest.mark.parametrize("name,params", BUILTINS, ids=[b[0] for b in BUILTINS])
def test_every_builtin_streams_in_any_chunking_as_decide_does(name, params):
    t, x, rest = _stream(1)
    loaded, ch, cols, params = _make(name, params)
    whole = interface.decisions(name, _build(loaded, ch, params, rest, cols), t, x[:, cols])
    assert whole.dtype == bool and whole.shape == t.shape
    # the stream is at rest for 90 s, moves, rests again: a detector that never or always allows
    # transmission would pass any chunking trivially
    assert whole.any() and not whole.all(), name
    rng = np.random.default_rng(7)
    for chunking in (1_000, None):
        det = _build(loaded, ch, params, rest, cols)
        if chunking is None:  # random cuts, chunks of 1 sample to thousands
            cuts = np.sort(rng.choice(np.arange(1, t.shape[0]), 60, replace=False))
            cuts = np.concatenate([cuts, cuts[:5] + 1])
            parts = np.split(np.arange(t.shape[0]), np.unique(cuts))
        else:
            parts = np.array_split(np.arange(t.shape[0]), t.shape[0] // chunking)
        got, n0 = [], 0
        for idx in parts:
            got.append(interface.checked_push(name, det, t[idx], x[idx][:, cols], n0))
            n0 += idx.shape[0]
        assert np.array_equal(np.concatenate(got), whole), (name, chunking)


def test_nmv_decisions_are_seed_000s_final_static_held_per_sample_on_a_flight(pattern_run):
    """On the pattern flight's samples: the built-in's decision at every sample is the final static of
    the last check of :func:`flightmode.detector.flight_mode.detect` closed at or before it (False
    before the first), with the same sigma^2 as the run's own detector (the bench calibration)."""
    from flightmode.detector.flight_mode import DetectorParams, detect
    from flightmode.runs.detect import DetectSettings, detect_stream
    from flightmode.runs.run_io import read_samples

    run, _ = pattern_run
    cols, info = read_samples(run)
    d = detect_stream(cols, info, run, "nmv", DetectSettings(chunk=4_999))
    c = detect(cols["t_s"], cols["acc_g"], DetectorParams(fs_hz=100.0), d.evaluation.sigma2)
    j = np.searchsorted(c.index, np.arange(cols["t_s"].shape[0]), side="right") - 1
    expected = np.where(j >= 0, c.final_static[np.maximum(j, 0)], False)
    assert np.array_equal(d.decisions, expected)
    assert expected.any() and not expected.all()
    # and the run's own detector (run.json) had the same sigma^2 and false statics
    import json

    run_det = json.loads((run / "run.json").read_text())["detector"]
    assert d.evaluation.sigma2.tolist() == run_det["sigma2_g2"]
    assert d.evaluation.false_static_count == run_det["false_static_count"]


def test_the_activity_detector_holds_seed_001s_checks():
    """amvd's decisions are :func:`~flightmode.detector.activity.flight.activity_checks`' final
    statics held per sample, with the rest figures of its rest recording."""
    from flightmode.detector.activity.flight import ActivityParams, activity_checks, rest_figures

    t, x, rest = _stream(2)
    loaded, ch, cols, params = _make("amvd")
    det = _build(loaded, ch, params, rest, cols)
    got = interface.decisions("amvd", det, t, x[:, cols])
    p = ActivityParams("amvd", fs_hz=FS)
    figs = rest_figures(p, rest[:, :3])
    assert figs == det.rest_figures
    c = activity_checks(t, x[:, :3], None, p, figs)
    j = np.searchsorted(c.index, np.arange(t.shape[0]), side="right") - 1
    assert np.array_equal(got, np.where(j >= 0, c.final_static[np.maximum(j, 0)], False))


def test_the_redundant_rule_is_detector_pressures_rule_held_per_sample():
    """nmv+baro reads the barometer's conversions back from the held pressure_pa (a new reading at
    every 4th row at 25 Hz in a 100 Hz stream) and allows transmission at an accelerometer check when
    the accelerometer is final static AND the pressure source static as of it, as
    :func:`flightmode.detector.pressure.detect_redundant` decides."""
    from flightmode.detector.flight_mode import DetectorParams, calibrate_sigma2
    from flightmode.detector.pressure import PressureParams, detect_redundant

    t, x, rest = _stream(3)
    loaded, ch, cols, params = _make("nmv+baro", {"baro_hold_s": 20.0})
    det = _build(loaded, ch, params, rest, cols)
    got = interface.decisions("nmv+baro", det, t, x[:, cols])
    s2 = calibrate_sigma2(rest[:, :3], 100)
    pp = PressureParams(fs_hz=BARO_FS, hold_s=20.0)
    rc = detect_redundant(t, x[:, :3], t[::4], x[::4, 6], DetectorParams(fs_hz=FS), s2, pp)
    idx = np.round(rc.t_s * FS).astype(int)  # the checks' closing samples
    j = np.searchsorted(idx, np.arange(t.shape[0]), side="right") - 1
    assert np.array_equal(got, np.where(j >= 0, rc.allowed[np.maximum(j, 0)], False))
    # the ramp suspends the pressure source: the rule allows less than the accelerometer alone
    assert (~rc.allowed & rc.accel_static).any()


def test_the_redundant_rules_evaluation_from_its_pushed_checks_is_the_batch_one():
    """nmv+baro's rich evaluation scores the accelerometer checks it already pushed (in chunks here)
    instead of running the detector again: every figure equals evaluate_redundant's own run."""
    from flightmode.detector.pressure import evaluate_redundant

    t, x, rest = _stream(5)
    loaded, ch, cols, params = _make("nmv+baro", {"baro_hold_s": 20.0})
    det = _build(loaded, ch, params, rest, cols)
    interface.decisions("nmv+baro", det, t, x[:, cols], chunk=333)
    n = t.shape[0]
    labels = {
        "in_flight_window": (t >= 90.0) & (t < 240.0),
        "sensor_static": (t < 90.0) | (t >= 240.0),
        "phase": np.where((t >= 90.0) & (t < 240.0), "taxi_out", "gate").astype(object),
    }
    assert labels["phase"].shape == (n,)
    got = det.evaluation(t, x[:, cols], labels)
    want = evaluate_redundant(
        t, x[:, :3], t[::4], x[::4, 6], labels, det.params, det.sigma2, det.pressure_params
    )
    assert got.summary() == want.summary()


def test_two_source_is_the_and_of_its_two_detectors():
    """Suspend when ANY says flying, resume only when ALL say on the ground: per sample, the AND of
    the first and second detectors run alone (here AMVD and the pressure source)."""
    t, x, rest = _stream(4)
    spec = {
        "first": "amvd",
        "second": "flightmode.detector.builtin:pressure",
        "second_params": {"baro_hold_s": 20.0},
    }
    loaded, ch, cols, params = _make("two-source", spec)
    assert ch == (*ACC_CHANNELS, "pressure_pa")
    both = interface.decisions("two-source", _build(loaded, ch, params, rest, cols), t, x[:, cols])
    alone = []
    for name, p in (("amvd", {}), ("flightmode.detector.builtin:pressure", {"baro_hold_s": 20.0})):
        lo, c2, cols2, p = _make(name, p)
        alone.append(interface.decisions(name, _build(lo, c2, p, rest, cols2), t, x[:, cols2]))
    assert np.array_equal(both, alone[0] & alone[1])
    assert (alone[0] & ~alone[1]).any()  # the pressure source does hold some of the accelerometer's rests


def test_builtin_parameters_and_channels_are_checked_in_one_line():
    from flightmode.errors import DetectorError

    t, x, rest = _stream(5, rest_s=(20.0, 10.0), moving_s=10.0)
    cases = [
        ("nmv", {"weight": 5.0}, "no parameter 'weight'"),
        ("amvd", {"signal": "sum"}, "no parameter 'signal'"),
        ("nmv", {"sigma2": [1e-6, 0.0, 1e-6]}, "three positive variances"),
        ("nmv+baro", {"baro_margin_hpa": -3.0}, "must be >= 0"),
        ("two-source", {"first": "nmvv"}, 'did you mean "nmv"'),
    ]
    for name, params, words in cases:
        loaded = interface.load(name)
        ch = ACC_CHANNELS if name == "two-source" else loaded.channels_for(params)
        cols = [CH.index(c) for c in ch]
        with pytest.raises(DetectorError, match=words) as e:
            loaded = interface.load(name)
            interface.build(loaded, FS, loaded.channels_for(params), params, rest[:, cols])
        assert "\n" not in str(e.value)
    # a built-in given channels without the ones it reads
    with pytest.raises(DetectorError, match="have no acc_z_g"):
        interface.build(interface.load("nmv"), FS, ["acc_x_g", "acc_y_g"], {}, rest[:, :2])


def test_a_time_gap_withdraws_the_permission_until_t_th_of_clean_data():
    """Seed 000's detector resets at a gap (flight_mode: samples more than 1.5 periods apart); the
    per-sample decisions fall to False at the gap's first sample, not at the next check, in any
    chunking, and come back only after T_th (4 s = 4 checks) of clean data."""
    import numpy as np

    from flightmode.detector import interface

    fs = 100.0
    rng = np.random.default_rng(7)
    t = np.arange(3000) / fs
    t[1500:] += 10.0  # ten seconds with no sample
    x = rng.normal(0.0, 0.002, (3000, 3)) + [0.0, 0.0, 1.0]  # a unit at rest, white noise
    rest = rng.normal(0.0, 0.002, (6000, 3)) + [0.0, 0.0, 1.0]
    loaded = interface.load("nmv")
    runs = []
    for chunk in (None, 7, 1000):
        det = interface.build(loaded, fs, loaded.channels, {}, rest=rest)
        runs.append(interface.decisions("nmv", det, t, x, chunk))
    for out in runs[1:]:
        assert np.array_equal(out, runs[0])
    out = runs[0]
    assert out[1499]  # at rest long enough before the gap
    assert not out[1500:1899].any()  # from the gap until the fourth clean check closes
    assert out[1899:].all()
