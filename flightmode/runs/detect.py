"""A detector over one recorded stream (a run folder's samples, a samples file, a dataset flight),
scored against its truth labels: what ``flightmode detect`` prints.

Every detector goes through the detector interface (:mod:`flightmode.detector.interface`): loaded by
name (the entry-point group ``flightmode.detectors``: the built-ins and plugins) or by
``package.module:make``, made with the stream's rate, the channels it reads and its parameters, fed
the stream and scored from its per-sample decisions (:func:`flightmode.detector.decisions.score`).
This module gives the factory what the harness knows of the stream and its run.json (``info``):

- ``rest``: the unit's rest recording in the detector's channels (:func:`rest_recording`), the same
  calibration data ``stream_sigma2`` and ``stream_rest`` of :mod:`flightmode.runs.pipeline` use;
- ``sensor_lsb_g``: the accelerometer's resolution (the variance floor of a quantised unit);
- ``baro_fs_hz``: the barometer's reading rate; ``arrival_ground_pa``: the destination's expected
  ground pressure when the run's scenario is known (:func:`flightmode.runs.pipeline.pressure_params`).

A built-in detector with checks also gives its check-based evaluation (``evaluation``), which the
rich report prints (seed 000's tables, the redundant rule's sources).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

from flightmode.errors import DetectorError, did_you_mean


@dataclass(frozen=True, slots=True)
class DetectSettings:
    """What the command line sets: the detector's ``params`` (``--param``, and the named options
    ``--k`` ...), where its rest recording comes from (``sigma2_from``: preset or rest), the
    ``channels`` it reads (None: the detector's own) and the ``chunk`` size it is pushed in (None:
    the whole stream at once, by its ``decide`` when it has one)."""

    params: dict = field(default_factory=dict)
    sigma2_from: str = "preset"
    channels: tuple[str, ...] | None = None
    chunk: int | None = None


@dataclass(frozen=True, slots=True)
class Detection:
    """One detector's outcome on a stream. ``method``: its name; ``kind``: the built-in's kind
    (``moving_variance``, ``activity``, ``redundant``, ``pressure``, ``two_source``) or ``plugin``;
    ``evaluation``: the built-in's check-based evaluation (an
    :class:`~flightmode.detector.evaluation.Evaluation` or a
    :class:`~flightmode.detector.pressure.RedundantEvaluation`), else the per-sample one;
    ``decision_evaluation``: the per-sample :class:`~flightmode.detector.decisions.DecisionEvaluation`
    of every detector, ``decisions`` the decisions themselves; ``calibration_source``: where the
    rest recording came from; ``params``: the moving variance's DetectorParams; ``rest``: an activity
    detector's rest figures; ``source``, ``channels``, ``detector_params``, ``title``: what was run."""

    method: str
    kind: str
    fs_hz: float
    evaluation: Any
    calibration_source: str
    params: Any = None
    rest: dict = field(default_factory=dict)
    decision_evaluation: Any = None
    decisions: Any = None
    source: str = ""
    channels: tuple[str, ...] = ()
    detector_params: dict = field(default_factory=dict)
    title: str = ""
    detector: Any = None  # the detector object (its internals: checks, rest figures, registry row)


def stream_rate_hz(cols: dict, info: dict | None) -> float:
    """The stream's output rate: run.json's sensor rate, or the median spacing of the first samples."""
    import numpy as np

    if info and info.get("sensor"):
        return float(info["sensor"]["odr_hz"])
    t = cols["t_s"]
    return 1.0 / float(np.median(np.diff(t[: min(len(t), 10_000)])))


def baro_rate_hz(cols: dict, info: dict | None) -> float:
    """The barometer's reading rate: run.json's, or the spacing of its readings (``baro_new``)."""
    import numpy as np

    baro = ((info or {}).get("sensor") or {}).get("baro")
    if baro:
        return float(baro["odr_hz"])
    tb = cols["t_s"][cols["baro_new"]]
    return round(1.0 / float(np.median(np.diff(tb))), 3) if tb.shape[0] > 2 else math.nan


def _lsb_g(info: dict | None) -> float | None:
    from flightmode.sim.sensor.accelerometer import get_preset

    return get_preset(info["sensor"]["preset"]).lsb_g if info is not None and info.get("sensor") else None


def _arrival_ground_pa(info: dict | None, source) -> float | None:
    """The destination's expected ground pressure from the run's scenario (None: not known)."""
    if info is None or "scenario_toml" not in info:
        return None
    from flightmode.runs.pipeline import pressure_params
    from flightmode.runs.run_io import run_scenario

    return pressure_params(run_scenario(info, str(source)), 25.0).arrival_ground_pa


def _check_source(source: str) -> None:
    from flightmode.runs.pipeline import SIGMA2_SOURCES

    if source not in SIGMA2_SOURCES:
        raise DetectorError(
            f"--sigma2-from {source!r}: use one of {', '.join(SIGMA2_SOURCES)}"
            f"{did_you_mean(source, SIGMA2_SOURCES)}"
        )


def rest_recording(source: str, cols: dict, info: dict | None, channels, x) -> tuple[Any, str]:
    """The unit's rest recording in ``channels`` (rows of the stream matrix ``x``'s columns) and where
    it came from. ``preset``: the accelerometer's 60 s bench recording of the recording's own unit
    (:func:`flightmode.runs.pipeline.stream_rest`, needs run.json), the channels the bench does not
    record (gyroscope, pressure) from the longest truly static run before the flight, as a tracker
    zeroes its gyroscope at rest (a gyroscope cuts the bench to that run's length, as stream_rest
    does; the pressure holds its last value beyond it); ``rest``: every truly static sample before the
    flight, all channels (every static sample when those are fewer than one second), as
    :func:`flightmode.detector.recommended.sigma2_from_rest` selects them."""
    import numpy as np

    from flightmode.detector.evaluation import longest_static_run
    from flightmode.detector.interface import ACC_CHANNELS, GYRO_CHANNELS
    from flightmode.runs.pipeline import stream_rest

    _check_source(source)
    for name in ("sensor_static", "in_flight_window"):
        if name not in cols:
            raise DetectorError(f"--sigma2-from {source}: the samples have no {name} column")
    static = np.asarray(cols["sensor_static"], bool)
    window = np.asarray(cols["in_flight_window"], bool)
    before = static.copy()
    if window.any():
        before[int(np.flatnonzero(window)[0]) :] = False  # only what a tracker saw before the flight
    ch = list(channels)
    if source == "rest":
        if not static.any():
            raise DetectorError("--sigma2-from rest: the stream has no truly static samples")
        sel = before if before.sum() >= stream_rate_hz(cols, info) else static
        return x[sel], f"{int(sel.sum())} truly static samples before the flight"
    if info is None or "sensor" not in info:
        raise DetectorError(
            "--sigma2-from preset needs the run.json beside samples.parquet; "
            "use --sigma2-from rest for a bare samples file"
        )
    gyro = any(c in GYRO_CHANNELS for c in ch)
    view = cols if gyro else {k: v for k, v in cols.items() if k != "gyro_dps"}
    acc, gyr, where = stream_rest("preset", view, info)
    a, b = longest_static_run(before) if before.any() else longest_static_run(static)
    rest = np.empty((acc.shape[0], len(ch)))
    for j, c in enumerate(ch):
        if c in ACC_CHANNELS:
            rest[:, j] = acc[:, ACC_CHANNELS.index(c)]
        elif c in GYRO_CHANNELS and gyr is not None:
            rest[:, j] = gyr[:, GYRO_CHANNELS.index(c)]
        else:  # pressure (and a gyroscope channel asked of a stream without one: stream_matrix refused it)
            run = x[a:b, j]
            rest[:, j] = np.concatenate([run, np.full(max(0, acc.shape[0] - run.shape[0]), run[-1])])[
                : acc.shape[0]
            ]
    if "pressure_pa" in ch:
        where += "; the pressure at rest before the flight"
    return rest, f"bench calibration: the {where}"


def compare_fixed_float(cols: dict, info: dict | None, source, settings: DetectSettings) -> dict:
    """``nmv-fixed`` against the floating NMV on this stream's 8-bit samples
    (:func:`flightmode.detector.fixed_point.compare_fixed_float`): sigma^2 in counts^2 from the unit's
    rest recording as ``--sigma2-from`` picks it, the window, k and T_th from ``settings.params``."""
    import numpy as np

    from flightmode.detector import fixed_point
    from flightmode.detector.interface import ACC_CHANNELS, stream_matrix
    from flightmode.detector.recommended_point import POINT

    p = dict(settings.params)
    unknown = sorted(set(p) - {"window_s", "k", "time_threshold_s"})
    if unknown:
        raise DetectorError(
            f"--compare-float: nmv-fixed's comparison takes window_s, k, time_threshold_s, not {unknown}"
        )
    fs = stream_rate_hz(cols, info)
    t, x = stream_matrix(cols, ACC_CHANNELS, str(source))
    rest, _ = rest_recording(settings.sigma2_from, cols, info, ACC_CHANNELS, x)
    window_s = float(p.get("window_s", POINT.window_s))
    window = int(round(window_s * fs))
    return fixed_point.compare_fixed_float(
        t,
        x,
        fs,
        window_s=window_s,
        k=float(p.get("k", POINT.k_sigma)),
        time_threshold_s=float(p.get("time_threshold_s", POINT.time_threshold_s)),
        sigma2_counts=fixed_point.sigma2_counts_of_rest(np.asarray(rest), window),
    )


def _describe(loaded, params: dict) -> str:
    """``frd with --signal sum``: the detector and the parameters that change its channels."""
    base = loaded.channels_for({})
    given = [k for k in params if loaded.channels_for({k: params[k]}) != base]
    return loaded.name + (
        " with " + ", ".join(f"--{k.replace('_', '-')} {params[k]}" for k in given) if given else ""
    )


def _check_streams(loaded, params: dict, channels, cols: dict, source) -> None:
    """A DetectorError when the stream lacks a sensor the detector reads."""
    from flightmode.detector.interface import GYRO_CHANNELS

    if any(c in GYRO_CHANNELS for c in channels) and cols.get("gyro_dps") is None:
        raise DetectorError(
            f"{_describe(loaded, params)} needs a gyroscope: sense the flight with one (flightmode sense RUN --gyro)"
        )
    if "pressure_pa" in channels and ("baro_pa" not in cols or "baro_new" not in cols):
        raise DetectorError(
            f"{source}: the samples have no barometer (baro_pa) for {_describe(loaded, params)}: fly with "
            '[sensor].baro = "bmp581" (or `flightmode fly --baro bmp581`)'
        )


def detect_stream(
    cols: dict,
    info: dict | None,
    source,
    detector: Any = "nmv",
    settings: DetectSettings | None = None,
    what: str = "--detector",
) -> Detection:
    """Run ``detector`` (a registered name, ``package.module:make``, or an
    :class:`~flightmode.detector.interface.Loaded`) over a stream's columns
    (:func:`flightmode.runs.run_io.read_samples`, or :func:`flightmode.datasets.flight.flight_stream`)
    with its run.json ``info`` (None: a bare samples file), scored against the stream's truth labels.
    ``source`` names the stream in errors; ``what`` the option that named the detector."""
    from flightmode.detector import decisions as dec
    from flightmode.detector import interface
    from flightmode.detector.recommended import labels_of

    s = settings or DetectSettings()
    _check_source(s.sigma2_from)
    loaded = detector if isinstance(detector, interface.Loaded) else interface.load(str(detector), what)
    params = {**loaded.params, **s.params}
    interface.check_params(loaded, params)
    channels = tuple(s.channels) if s.channels else loaded.channels_for(params)
    interface.check_channels(channels, f"detector {loaded.name}")
    _check_streams(loaded, params, channels, cols, source)
    labels = labels_of(cols)
    t, x = interface.stream_matrix(cols, channels, str(source))
    fs = stream_rate_hz(cols, info)
    rest, where = (None, "")
    if loaded.takes_rest:
        rest, where = rest_recording(s.sigma2_from, cols, info, channels, x)
    f = loaded.factory
    context: dict = {}
    if interface.accepts(f, "sensor_lsb_g"):
        context["sensor_lsb_g"] = _lsb_g(info)
    if "pressure_pa" in channels and interface.accepts(f, "baro_fs_hz"):
        context["baro_fs_hz"] = baro_rate_hz(cols, info)
    if "pressure_pa" in channels and interface.accepts(f, "arrival_ground_pa"):
        context["arrival_ground_pa"] = _arrival_ground_pa(info, source)
    det = interface.build(loaded, fs, channels, params, rest, **context)
    static = interface.decisions(loaded.name, det, t, x, s.chunk)
    per_sample = dec.score(t, static, labels)
    rich = getattr(det, "evaluation", None)
    kind = str(getattr(det, "kind", "plugin"))
    return Detection(
        method=loaded.name,
        kind=kind,
        fs_hz=fs,
        evaluation=rich(t, x, labels) if callable(rich) and kind != "plugin" else per_sample,
        calibration_source=where,
        params=getattr(det, "params", None) if kind in ("moving_variance", "redundant") else None,
        rest=dict(getattr(det, "rest_figures", {}) or {}),
        decision_evaluation=per_sample,
        decisions=static,
        source=loaded.source,
        channels=tuple(channels),
        detector_params=params,
        title=str(getattr(loaded.factory, "title", "") or ""),
        detector=det,
    )


__all__ = [
    "DetectSettings",
    "Detection",
    "baro_rate_hz",
    "detect_stream",
    "rest_recording",
    "stream_rate_hz",
]
