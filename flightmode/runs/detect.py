"""A detection method, by name, over one recorded stream (a run folder's samples, a samples file, a
dataset flight), scored against its truth labels: what ``flightmode detect`` prints.

The method table is :mod:`flightmode.detector.methods`; this module gives each kind its calibration
from the stream and its run.json (``info``): seed 000's moving variance its sigma^2
(:func:`flightmode.runs.pipeline.stream_sigma2`), the redundant rule that and the pressure detector's
parameters (the destination known from the run's scenario), seed 001's detectors a static recording
of the unit (:func:`flightmode.runs.pipeline.stream_rest`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

from flightmode.errors import DetectorError


@dataclass(frozen=True, slots=True)
class DetectSettings:
    """What the command line sets; ``baro_*`` None take the pressure detector's defaults."""

    window_s: float = 1.0
    k: float = 4.0
    time_threshold_s: float = 4.0
    weight: float = 1.0
    signal: str = "acc"
    sigma2_from: str = "preset"
    baro_rate_pa_s: float | None = None
    baro_margin_hpa: float | None = None
    baro_hold_s: float | None = None


@dataclass(frozen=True, slots=True)
class Detection:
    """One method's outcome on a stream: ``kind`` as in the method table; ``evaluation`` an
    :class:`~flightmode.detector.evaluation.Evaluation` (moving variance, activity) or a
    :class:`~flightmode.detector.pressure.RedundantEvaluation` (redundant); ``calibration_source``:
    where sigma^2 or the rest recording came from; ``params``: the moving variance's DetectorParams
    (None for an activity detector); ``rest``: an activity detector's rest figures."""

    method: str
    kind: str
    fs_hz: float
    evaluation: Any
    calibration_source: str
    params: Any = None
    rest: dict = field(default_factory=dict)


def stream_rate_hz(cols: dict, info: dict | None) -> float:
    """The stream's output rate: run.json's sensor rate, or the median spacing of the first samples."""
    import numpy as np

    if info and info.get("sensor"):
        return float(info["sensor"]["odr_hz"])
    t = cols["t_s"]
    return 1.0 / float(np.median(np.diff(t[: min(len(t), 10_000)])))


def pressure_params_of(cols: dict, info: dict | None, source, settings: DetectSettings):
    """The pressure detector's parameters for a stream's barometer (its rate from run.json, or from
    the spacing of its readings; the destination's ground pressure from the run's scenario)."""
    import numpy as np

    from flightmode.detector.pressure import PressureParams

    if "baro_pa" not in cols or "baro_new" not in cols:
        raise DetectorError(
            f"{source}: the samples have no barometer (baro_pa): fly with [sensor].baro = "
            '"bmp581" (or `flightmode fly --baro bmp581`)'
        )
    baro = ((info or {}).get("sensor") or {}).get("baro")
    if baro:
        fs = float(baro["odr_hz"])
    else:
        tb = cols["t_s"][cols["baro_new"]]
        fs = round(1.0 / float(np.median(np.diff(tb))), 3) if tb.shape[0] > 2 else math.nan
    changes: dict = {}
    margin = settings.baro_margin_hpa
    if margin is not None:
        if margin < 0:
            raise DetectorError(f"--baro-margin-hpa {margin:g}: must be >= 0 (0: no level bound)")
        changes["level_margin_pa"] = margin * 100.0 if margin > 0 else None
    if settings.baro_rate_pa_s is not None:
        changes["rate_threshold_pa_s"] = settings.baro_rate_pa_s
    if settings.baro_hold_s is not None:
        changes["hold_s"] = settings.baro_hold_s
    if info is not None and "scenario_toml" in info:  # the destination known (the run's scenario)
        from flightmode.runs.pipeline import pressure_params
        from flightmode.runs.run_io import run_scenario

        return pressure_params(run_scenario(info, str(source)), fs, **changes)
    pp = PressureParams(fs_hz=fs, **changes)
    pp.validate()
    return pp


def moving_variance_params(m, s: DetectSettings, fs: float):
    """The moving-variance detector's parameters (validated) for method ``m`` at ``fs`` Hz, as the
    settings ``s`` give them: shared by the accelerometer rule and the redundant one."""
    from flightmode.detector.flight_mode import DetectorParams

    p = DetectorParams(
        fs_hz=fs,
        window_s=s.window_s,
        k_sigma=s.k,
        time_threshold_s=s.time_threshold_s,
        method=m.base,
        weight=s.weight,
    )
    p.validate()
    return p


def _moving_variance(cols, info, source, m, s: DetectSettings, fs: float) -> Detection:
    from flightmode.detector.evaluation import evaluate
    from flightmode.detector.recommended import labels_of
    from flightmode.runs.pipeline import stream_sigma2

    p = moving_variance_params(m, s, fs)
    s2, s2_source = stream_sigma2(s.sigma2_from, cols, info, p.window)
    e = evaluate(cols["t_s"], cols["acc_g"], labels_of(cols), p, s2)
    return Detection(m.name, m.kind, fs, e, s2_source, p)


def _redundant(cols, info, source, m, s: DetectSettings, fs: float) -> Detection:
    from flightmode.detector.pressure import evaluate_redundant
    from flightmode.detector.recommended import labels_of
    from flightmode.runs.pipeline import stream_sigma2

    pp = pressure_params_of(cols, info, source, s)
    p = moving_variance_params(m, s, fs)
    s2, s2_source = stream_sigma2(s.sigma2_from, cols, info, p.window)
    t, new = cols["t_s"], cols["baro_new"]
    red = evaluate_redundant(t, cols["acc_g"], t[new], cols["baro_pa"][new], labels_of(cols), p, s2, pp)
    return Detection(m.name, m.kind, fs, red, s2_source, p)


def _activity(cols, info, source, m, s: DetectSettings, fs: float) -> Detection:
    from flightmode.detector.activity.flight import ActivityParams, evaluate_activity, rest_figures
    from flightmode.detector.recommended import labels_of
    from flightmode.runs.pipeline import stream_rest

    p = ActivityParams(
        m.base, fs_hz=fs, window_s=s.window_s, k=s.k, time_threshold_s=s.time_threshold_s, signal=s.signal
    )
    p.validate()
    bench, bench_gyr, bench_source = stream_rest(s.sigma2_from, cols, info)
    rest = rest_figures(p, bench, bench_gyr)
    e = evaluate_activity(cols["t_s"], cols["acc_g"], cols.get("gyro_dps"), labels_of(cols), p, rest)
    return Detection(m.name, m.kind, fs, e, bench_source, None, rest)


EVALUATE_KIND = {"moving_variance": _moving_variance, "redundant": _redundant, "activity": _activity}


def detect_stream(
    cols: dict, info: dict | None, source, method: str = "nmv", settings: DetectSettings | None = None
) -> Detection:
    """Run the method called ``method`` (:func:`flightmode.detector.methods.get`: an unknown name fails
    with the nearest) over a stream's columns (:func:`flightmode.runs.run_io.read_samples`, or
    :func:`flightmode.datasets.flight.flight_stream`) with its run.json ``info`` (None: a bare
    samples file), scored against the stream's truth labels. ``source`` names the stream in errors."""
    from flightmode.detector import methods

    m = methods.get(method)
    return EVALUATE_KIND[m.kind](
        cols, info, source, m, settings or DetectSettings(), stream_rate_hz(cols, info)
    )


__all__ = ["DetectSettings", "Detection", "detect_stream", "pressure_params_of", "stream_rate_hz"]
