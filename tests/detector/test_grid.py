"""The parameter grid (detector.grid) and the confidence bounds (detector.confidence)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from flightmode.detector.confidence import hours_needed, proportion_upper_bound, rate_upper_bound
from flightmode.detector.evaluation import evaluate
from flightmode.detector.flight_mode import DetectorError, detect
from flightmode.detector.grid import Grid, evaluate_grid


def test_rate_bounds_against_known_values():
    # zero events in 30,000 h: the 95 % bound is -ln(0.05)/30,000 = 2.9957/30,000 (rule of three)
    assert rate_upper_bound(0, 30_000.0) == pytest.approx(-math.log(0.05) / 30_000.0, rel=1e-12)
    assert rate_upper_bound(0, 30_000.0) == pytest.approx(1e-4, rel=2e-3)
    # 3 events: the tabulated exact one-sided 95 % Poisson upper limit on the mean is 7.754 (Garwood)
    assert rate_upper_bound(3, 1_000.0) * 1_000.0 == pytest.approx(7.754, abs=5e-4)
    assert hours_needed(1e-4) == pytest.approx(29_957.3, abs=0.1)
    assert hours_needed(1e-4, events=3) == pytest.approx(77_537, rel=1e-4)
    # Clopper-Pearson, 0 of 100: the bound solves (1 - p)^100 = 0.05
    assert proportion_upper_bound(0, 100) == pytest.approx(1.0 - 0.05 ** (1 / 100), rel=1e-9)
    with pytest.raises(DetectorError, match="confidence 1.0"):
        rate_upper_bound(0, 10.0, 1.0)
    with pytest.raises(DetectorError, match="target rate 0"):
        hours_needed(0.0)


@pytest.mark.parametrize(
    "grid, message",
    [
        (Grid(ks=()), r"--k: the grid axis is empty"),
        (Grid(windows_s=(0.01,)), r"window 0.01 s at 100 Hz is 1 sample"),
        (Grid(ks=(0.0,)), r"--k 0.0: the threshold k sigma\^2 needs k > 0"),
        (Grid(time_thresholds_s=(-1.0,)), r"--time-threshold-s -1.0"),
        (
            Grid(methods=(("rms", 1.0),)),
            r"--method 'rms': use nmv, emv, nmv\+baro, emv\+baro or one of seed 001's detectors",
        ),
        (Grid(methods=(("mbdc", 1.0),)), r"did you mean \"mbcd\"\?"),
        (
            Grid(methods=(("amvd:sum", 1.0),)),
            r"--method 'amvd:sum': Acceleration Moving Variance Detector takes no input choice",
        ),
        (Grid(methods=(("fsd:gyro", 1.0),)), r"--method 'fsd:gyro': fsd takes acc, gyr, sum, product"),
        (Grid(methods=(("nmv", 1.0), ("nmv", 1.0))), r"--method: a value is given twice"),
    ],
)
def test_bad_grids_are_one_line_errors(grid, message):
    with pytest.raises(DetectorError, match=message):
        grid.validate(100.0)


def test_grid_decisions_equal_the_detector_run_alone(run_cached):
    # the pattern flight's own recording; sigma^2 from its first static minute
    rec = run_cached("pattern").recording
    labels = {
        "in_flight_window": rec.in_flight_window,
        "sensor_static": rec.sensor_static,
        "phase": rec.phase,
    }
    s2 = {}

    def sigma2_of(window):
        s2[window] = np.var(rec.acc_g[:6000], axis=0) * (1.0 + 0.1 * window / 100.0)  # differs by window
        return s2[window]

    grid = Grid(
        methods=(("nmv", 1.0), ("emv", 5.0), ("emv", 1.0)),
        windows_s=(0.5, 1.0, 2.0),
        ks=(3.0, 4.0, 6.0),
        time_thresholds_s=(2.0, 3.0, 4.0),
    )
    got = list(evaluate_grid(rec.t_s, rec.acc_g, labels, grid, rec.odr_hz, sigma2_of))
    assert len(got) == len(grid) == 81
    for p, e in got[::7]:  # every seventh point: NMV and EMV, each window, k and time threshold
        alone = detect(rec.t_s, rec.acc_g, p, s2[p.window])
        for f in ("index", "t_s", "mv", "temporary_static", "final_static", "after_reset"):
            assert np.array_equal(getattr(e.checks, f), getattr(alone, f)), (
                p,
                f,
            )  # exactly, not approximately
        ref = evaluate(rec.t_s, rec.acc_g, labels, p, s2[p.window])
        assert (e.false_static_events, e.missed_static_s, e.response_s) == (
            ref.false_static_events,
            ref.missed_static_s,
            ref.response_s,
        )
