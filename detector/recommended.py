"""Seed 000's recommended detector and where its noise variance sigma^2 comes from.

The paper's recommendation (Table 9 and section 7): the normal moving variance (NMV), a window and
check period W_s of 1 s, an amplitude threshold T_sigma = 4 sigma^2 per axis and a time threshold
T_th of 4 s. sigma^2 is the per-axis variance of the sensor's static noise (section 5.1), which a
tracker learns either on the bench before deployment (:func:`flightmode.detector.flight_mode.
calibrate_sigma2` on a static recording of its own unit) or in place, from what it recorded while
truly at rest before the flight (:func:`sigma2_from_rest`).
"""

from __future__ import annotations

import numpy as np

from flightmode.detector.evaluation import Evaluation, evaluate
from flightmode.detector.flight_mode import DetectorParams, calibrate_sigma2
from flightmode.detector.recommended_point import POINT
from flightmode.errors import DetectorError

# seed 000, Table 9 and section 7 (the numbers: recommended_point.POINT)
RECOMMENDED = DetectorParams(
    window_s=POINT.window_s,
    k_sigma=POINT.k_sigma,
    time_threshold_s=POINT.time_threshold_s,
    method=POINT.method,
    weight=POINT.weight,
)
LABELS = ("in_flight_window", "sensor_static", "phase")


def recommended_params(fs_hz: float) -> DetectorParams:
    """The recommended detector at a stream's sampling rate."""
    import dataclasses

    p = dataclasses.replace(RECOMMENDED, fs_hz=float(fs_hz))
    p.validate()
    return p


def labels_of(columns: dict) -> dict:
    """The truth labels evaluation needs, from a dict of columns (a Recording's or a samples file's)."""
    missing = [k for k in LABELS if k not in columns]
    if missing:
        raise DetectorError(
            f"the samples have no {', '.join(missing)} column(s): evaluation needs the truth labels"
        )
    return {k: columns[k] for k in LABELS}


def sigma2_from_rest(
    acc_g: np.ndarray,
    sensor_static: np.ndarray,
    in_flight_window: np.ndarray,
    window: int,
    lsb_g: float | None = None,
) -> tuple[np.ndarray, int]:
    """sigma^2 per axis from the truly static samples a tracker saw before the flight (the terminal
    and gate rests), as a tracker calibrating in place would; all static samples if those are fewer
    than one window. Returns (sigma^2, samples used)."""
    static = np.asarray(sensor_static, bool)
    if not static.any():
        raise DetectorError("--sigma2-from rest: the stream has no truly static samples")
    window_mask = np.asarray(in_flight_window, bool)
    first = int(np.flatnonzero(window_mask)[0]) if window_mask.any() else static.shape[0]
    sel = static.copy()
    sel[first:] = False  # only what a tracker could see before the flight
    if sel.sum() < window:
        sel = static
    return calibrate_sigma2(np.asarray(acc_g, float)[sel], window, lsb_g), int(sel.sum())


def evaluate_recommended(
    t_s: np.ndarray, acc_g: np.ndarray, labels: dict, fs_hz: float, sigma2: np.ndarray
) -> Evaluation:
    """The recommended detector run over a labelled stream and scored against its labels."""
    return evaluate(t_s, acc_g, labels, recommended_params(fs_hz), sigma2)
