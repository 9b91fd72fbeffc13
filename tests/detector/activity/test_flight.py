"""Seed 001's detectors under seed 000's decision rule (detector.activity.flight): the checks on a
stream whose answer is known, the monotonicity every threshold rule must have on a real flight, and
`flightmode detect --method` with its one-line refusals."""

from __future__ import annotations

import numpy as np
import pytest

from flightmode.detector.activity.flight import (
    ActivityParams,
    activity_checks,
    evaluate_activity,
    rest_figures,
)
from flightmode.errors import DetectorError

FS = 100.0


def _still_burst_still(rng, still_s=30.0, burst_s=20.0):
    """Rest (1 g on z, 2.2 mg white noise as the LIS302DL's), a 2 Hz 0.5 g swing, rest again."""
    n0, n1 = int(still_s * FS), int(burst_s * FS)
    n = 2 * n0 + n1
    t = np.arange(n) / FS
    a = np.zeros((n, 3))
    a[:, 2] = 1.0
    a[n0 : n0 + n1, 0] = 0.5 * np.sin(2 * np.pi * 2.0 * t[n0 : n0 + n1])
    a += rng.normal(0.0, 2.2e-3, a.shape)
    static = np.ones(n, bool)
    static[n0 : n0 + n1] = False
    return t, a, static, (n0, n0 + n1)


@pytest.mark.parametrize("name", ["amvd", "amd", "frd", "fsd", "mbgtd"])
def test_checks_follow_the_marker_and_eq_8(name):
    rng = np.random.default_rng(7)
    t, a, static, (b0, b1) = _still_burst_still(rng)
    bench = np.column_stack(
        [rng.normal(0, 2.2e-3, 6000), rng.normal(0, 2.2e-3, 6000), 1 + rng.normal(0, 2.2e-3, 6000)]
    )
    # FSD frames keep their mean (seed 001 removes none): the 1 g of |a| leaks over every band of a 1 s
    # frame and hides a 0.06 g change in |a|; 0.32 s frames (32 samples, as seed 001's own) see it
    w = {"mbgtd": 0.5, "fsd": 0.32}.get(name, 1.0)
    p = ActivityParams(name, fs_hz=FS, window_s=w, k=4.0, time_threshold_s=4.0)
    rest = rest_figures(p, bench)
    c = activity_checks(t, a, None, p, rest)
    n = p.window
    # a check closes every W_s, at the last sample of its period
    assert np.array_equal(c.index, np.arange(len(c.index)) * n + n - 1)
    # no check inside the swing is static, temporarily or finally (0.5 g against a 2.2 mg rest level)
    inside = (c.index >= b0) & (c.index < b1)
    assert not c.temporary_static[inside].any() and not c.final_static[inside].any()
    # eq. 8: a final static needs checks_needed temporary statics in a row, so the first one after
    # the swing comes no sooner than T_th after it (plus the detector's own window and filter memory)
    after = np.flatnonzero(c.final_static & (c.index >= b1))
    assert after.size and (c.t_s[after[0]] - t[b1]) >= p.time_threshold_s - p.window_s
    # and at rest, far from the swing, the detector lets the tracker transmit most of the time (a 4x
    # threshold over the rest median still leaves the noise's tail: FSD's 6 dB lets 80 % through)
    quiet = c.index < b0 - 10 * FS
    assert c.final_static[quiet][p.checks_needed + 5 :].mean() > 0.75


def test_a_higher_threshold_never_removes_a_static_check_on_a_real_flight(pattern_run):
    """Eq. 7's comparison is monotone in the threshold and eq. 8's run length in its input: every check
    final static at k is final static at any larger k (here on the pattern flight's real recording)."""
    from flightmode.runs.pipeline import stream_rest
    from flightmode.runs.run_io import read_samples

    run, _ = pattern_run
    cols, info = read_samples(run)
    bench, _, _ = stream_rest("preset", cols, info)
    labels = {k: cols[k] for k in ("in_flight_window", "sensor_static", "phase")}
    prev = None
    for k in (2.0, 4.0, 8.0):
        p = ActivityParams(
            "amvd", fs_hz=float(info["sensor"]["odr_hz"]), window_s=1.0, k=k, time_threshold_s=4.0
        )
        e = evaluate_activity(cols["t_s"], cols["acc_g"], None, labels, p, rest_figures(p, bench))
        if prev is not None:
            assert not (prev & ~e.checks.final_static).any()
        prev = e.checks.final_static
    # the pattern flight rests on the ground before and after: some checks are static
    assert prev.any()


def test_detect_cli_runs_every_accelerometer_detector_and_refuses_in_one_line(pattern_run):
    from typer.testing import CliRunner

    from flightmode.cli.main import app

    run, _ = pattern_run
    r = CliRunner().invoke(app, ["detect", str(run), "--method", "frd"])
    assert r.exit_code == 0, r.output
    assert (
        "Filtered Rectifier Detector (seed 001, eq. (5))" in r.output
        and "false-static events in flight" in r.output
    )
    for args, msg in (
        (["--method", "mvcd"], "--method 'mvcd': use 'nmv' or 'emv' (seed 000) or one of seed 001's"),
        (["--method", "shod"], "shod needs a gyroscope"),
        (["--method", "frd", "--signal", "sum"], "frd with --signal sum needs a gyroscope"),
        (["--method", "amvd", "--k", "-1"], "--k -1.0: the threshold is k times the rest level"),
    ):
        r = CliRunner().invoke(app, ["detect", str(run), *args])
        assert r.exit_code == 2 and msg in r.output and len(r.output.strip().splitlines()) == 1, (
            args,
            r.output,
        )
    with pytest.raises(DetectorError, match="a window needs at least 2"):
        ActivityParams("amvd", fs_hz=100.0, window_s=0.01).validate()


@pytest.mark.parametrize("name", ["amvd", "frd", "ltsd", "mbgtd"])
def test_the_grid_runs_the_detector_once_per_window_and_decides_as_alone(name):
    """evaluate_activity_grid: each point's checks and scores equal the detector run alone with those
    parameters (its merit does not depend on the threshold, so one run per window serves every k)."""
    from flightmode.detector.activity.flight import evaluate_activity_grid

    rng = np.random.default_rng(11)
    t, a, static, _ = _still_burst_still(rng)
    labels = {
        "in_flight_window": ~static,
        "sensor_static": static,
        "phase": np.where(static, "terminal_rest", "cruise"),
    }
    bench = np.column_stack(
        [rng.normal(0, 2.2e-3, 6000), rng.normal(0, 2.2e-3, 6000), 1 + rng.normal(0, 2.2e-3, 6000)]
    )
    windows, ks, tths = (0.32, 0.5), (2.0, 4.0, 8.0), (1.0, 3.0)
    got = list(evaluate_activity_grid(t, a, None, labels, name, windows, ks, tths, FS, bench))
    assert len(got) == len(windows) * len(ks) * len(tths)
    for dp, e in got:
        p = ActivityParams(
            name, fs_hz=FS, window_s=dp.window_s, k=dp.k_sigma, time_threshold_s=dp.time_threshold_s
        )
        alone = evaluate_activity(t, a, None, labels, p, rest_figures(p, bench))
        assert np.array_equal(e.checks.final_static, alone.checks.final_static), dp
        assert e.false_static_events == alone.false_static_events and e.response_s == alone.response_s
