"""Seed 001's (in)activity detectors as flight-mode detectors: seed 000's decision rule on top of an
activity marker, scored exactly as the moving-variance detector is.

- **Checks**: every W_s (``window_s``), a check closes a period of ``W_s fs`` samples; it is
  *temporarily static* when the detector marked every sample of the period inactive (marker 0).
  Seed 000's eq. 8 then makes it *final static* after ``T_th / W_s`` temporary statics in a row
  (:func:`~flightmode.detector.flight_mode.final_static`), so transmission needs the same sustained
  evidence whatever the detector. The checks' ``mv`` columns hold the detector's figure of merit at
  the closing sample (the same value on the three columns: these detectors give one merit per sample).
- **Window**: the magnitude and spectrum detectors use ``W_s fs`` samples (a 1 s window at 100 Hz is
  100 samples). The memory detectors (MBGTD, MBCD) use the window the study chose for them, in
  seconds, times the stream's rate (:data:`STUDY_WINDOW_S`; 0.25-0.31 s, 25-31 samples at 100 Hz):
  their buffer of the last N readings is what they compare splits of (seed 001, section 2.3.1), and
  their cost is O(N^2) per sample, so W_s fs (100 samples) would be 16x the study's cost for a
  detector the study never ran that way. W_s stays their check period.
- **Threshold**: ``k`` times the figure of merit's median over the unit's own bench recording at rest
  (the 60 s lying still that calibrates sigma^2 for the moving variance, seed 000 section 5.1), the
  counterpart of ``k sigma^2``; for the spectrum detectors, whose merit is in dB above the rest
  spectrum, ``k`` is a power ratio: the threshold is the rest median plus ``10 log10(k)`` dB.
- **Noise figures** the detectors take, from the same bench recording: ``sigma_acc_g`` (AMD, SHOD),
  the RMS of the per-axis noise standard deviations; the LTSD/FSD noise spectrum N(l) (the mean frame
  spectrum at rest, not the flight's first frames, which on a flight are a walk through the
  terminal); MBCD's kernel width, Silverman's rule of thumb 1.06 s n^(-1/5) (Silverman 1986,
  "Density Estimation", eq. 3.28) with s the rest signal's standard deviation and n the window.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from flightmode.detector.flight_mode import Checks, final_static
from flightmode.errors import DetectorError

DB_DETECTORS = frozenset({"ltsd", "fsd"})
IMU_RATE_HZ = 50.0  # the rate of the study's IMU, whose signals Tables 10-11 optimise (seed 001, section 4.1)
# seed 001's best windows for the memory detectors on its real signals, in samples at IMU_RATE_HZ
# (Table 10, MBGTD; Table 11, MBCD; per input signal), as seconds
STUDY_WINDOW_S: dict[str, dict[str, float]] = {
    "mbgtd": {
        "acc": 13.1833 / IMU_RATE_HZ,
        "gyr": 13.6833 / IMU_RATE_HZ,
        "sum": 13.6167 / IMU_RATE_HZ,
        "product": 13.6500 / IMU_RATE_HZ,
    },
    "mbcd": {
        "acc": 12.6167 / IMU_RATE_HZ,
        "gyr": 15.2500 / IMU_RATE_HZ,
        "sum": 15.0500 / IMU_RATE_HZ,
        "product": 14.5167 / IMU_RATE_HZ,
    },
}


@dataclass(frozen=True, slots=True)
class ActivityParams:
    """A seed 001 detector under seed 000's decision rule (module docstring)."""

    name: str
    fs_hz: float = 100.0
    window_s: float = 1.0
    k: float = 4.0
    time_threshold_s: float = 4.0
    signal: str = "acc"

    @property
    def window(self) -> int:
        """The check period W_s fs, in samples (and the window of the detectors that take W_s)."""
        return int(round(self.window_s * self.fs_hz))

    @property
    def detector_window(self) -> int:
        """The detector's own window in samples: the study's for MBGTD and MBCD (:data:`STUDY_WINDOW_S`
        times the rate), else W_s fs."""
        if self.name in STUDY_WINDOW_S and self.signal in STUDY_WINDOW_S[self.name]:
            return int(round(STUDY_WINDOW_S[self.name][self.signal] * self.fs_hz))
        return self.window

    @property
    def checks_needed(self) -> int:  # as DetectorParams.checks_needed (eq. 8)
        return max(1, math.ceil(self.time_threshold_s / self.window_s - 1e-9))

    def validate(self) -> None:
        from flightmode.detector.activity import registry

        d = registry.get(self.name)  # an unknown name: DetectorError with the nearest
        if not self.window >= 2:
            raise DetectorError(
                f"--window-s {self.window_s:g}: {self.window} sample(s) at {self.fs_hz:g} Hz; "
                "a window needs at least 2"
            )
        if not self.detector_window >= 2:
            raise DetectorError(
                f"{self.name}: the study's window is {STUDY_WINDOW_S[self.name][self.signal]:g} s, "
                f"{self.detector_window} sample(s) at {self.fs_hz:g} Hz; a window needs at least 2"
            )
        if not (self.k > 0 and math.isfinite(self.k)):
            raise DetectorError(f"--k {self.k!r}: the threshold is k times the rest level, k > 0")
        if not self.time_threshold_s > 0:
            raise DetectorError(
                f"--time-threshold-s {self.time_threshold_s:g}: must be > 0 (one check suffices "
                "below W_s, as for the moving variance)"
            )
        if d.signals and self.signal not in d.signals:
            raise DetectorError(f"--signal {self.signal!r}: {self.name} takes {', '.join(d.signals)}")


def detector_kwargs(p: ActivityParams, rest: dict) -> dict:
    """The detector's own keyword parameters for these flight-mode parameters and rest figures (the
    streaming class's and the batch function's, besides ``threshold``)."""
    from flightmode.detector.activity import registry

    d = registry.get(p.name)
    kw: dict = {"fs_hz": p.fs_hz}
    if p.name != "frd":
        kw["window"] = p.detector_window
    if d.signals:
        kw["signal"] = p.signal
    if p.name in ("amd", "shod"):
        kw["sigma_acc_g"] = rest["sigma_acc_g"]
    if p.name in ("ared", "shod"):
        kw["sigma_gyr_dps"] = rest["sigma_gyr_dps"]
    if p.name in DB_DETECTORS:
        kw["shift"] = max(1, p.window // 2)
        if "noise_spectrum" in rest:
            kw["noise_spectrum"] = rest["noise_spectrum"]
    if p.name == "mbcd":
        kw["bandwidth"] = rest["bandwidth"]
    return kw


def rest_figures(p: ActivityParams, bench_acc_g: np.ndarray, bench_gyr_dps: np.ndarray | None = None) -> dict:
    """The noise figures and the rest level of the merit from a static recording of the unit at the
    stream's rate (module docstring)."""
    from flightmode.detector.activity import registry
    from flightmode.detector.activity.common import flexible_signal

    p.validate()
    d = registry.get(p.name)
    acc = np.asarray(bench_acc_g, float)
    n = acc.shape[0]
    t = np.arange(n) / p.fs_hz
    rest: dict = {"sigma_acc_g": float(np.sqrt(np.mean(np.var(acc, axis=0))))}
    if bench_gyr_dps is not None:
        rest["sigma_gyr_dps"] = float(np.sqrt(np.mean(np.var(np.asarray(bench_gyr_dps, float), axis=0))))
    elif d.needs_gyro or p.signal != "acc":
        what = p.name if d.needs_gyro else f"{p.name} with --signal {p.signal}"
        raise DetectorError(
            f"{what} needs a gyroscope: sense the flight with one (flightmode sense RUN --gyro)"
        )
    x = flexible_signal(p.signal, acc, bench_gyr_dps) if d.signals else None
    if p.name == "mbcd":
        assert x is not None  # mbcd and the dB detectors take a signal
        rest["bandwidth"] = 1.06 * float(np.std(x)) * p.detector_window**-0.2  # Silverman (1986) eq. 3.28
    if p.name in DB_DETECTORS:
        assert x is not None
        rest["noise_spectrum"] = _rest_spectrum(x, p.window, max(1, p.window // 2))
    merit = d.detect(t, acc, bench_gyr_dps, threshold=0.0, **detector_kwargs(p, rest)).merit
    merit = merit[np.isfinite(merit)]
    if merit.size == 0:
        raise DetectorError(
            f"{p.name}: the bench recording ({n} samples) is shorter than one window ({p.detector_window})"
        )
    rest["merit_median"] = float(np.median(merit))
    rest["threshold"] = threshold_of(p.name, rest["merit_median"], p.k)
    return rest


def threshold_of(name: str, rest_median: float, k: float) -> float:
    """k times the rest level (a power ratio of k, 10 log10(k) dB, for the dB detectors)."""
    return rest_median + 10.0 * math.log10(k) if name in DB_DETECTORS else k * rest_median


def _rest_spectrum(x: np.ndarray, window: int, shift: int) -> np.ndarray:
    """N(l): the mean magnitude spectrum of the rest signal's frames (the spectrum detectors' framing)."""
    from flightmode.detector.activity.spectrum import amplitude_spectra

    return amplitude_spectra(np.lib.stride_tricks.sliding_window_view(x, window)[::shift]).mean(axis=0)


def activity_checks(
    t_s: np.ndarray, acc_g: np.ndarray, gyr_dps: np.ndarray | None, p: ActivityParams, rest: dict
) -> Checks:
    """Every check of a whole stream (module docstring); ``rest`` from :func:`rest_figures`."""
    from flightmode.detector.activity import registry

    p.validate()
    res = registry.get(p.name).detect(
        t_s, acc_g, gyr_dps, threshold=rest["threshold"], **detector_kwargs(p, rest)
    )
    periods, index, after_reset = _periods(res.marker.shape[0], p.window)
    return _checks(t_s, res.marker, res.merit, periods, index, after_reset, p.checks_needed)


def _periods(n_samples: int, window: int):
    k = n_samples // window
    if k == 0:
        raise DetectorError(f"the stream ({n_samples} samples) is shorter than one check ({window})")
    index = np.arange(k) * window + window - 1
    after_reset = np.zeros(k, bool)
    after_reset[0] = True
    return (k, window), index, after_reset


def _checks(t_s, marker, merit, periods, index, after_reset, need: int) -> Checks:
    k, n = periods
    temp = ~marker[: k * n].reshape(k, n).astype(bool).any(axis=1)  # every sample of the period inactive
    mv = np.repeat(merit[index][:, None], 3, axis=1)
    return Checks(
        index, np.asarray(t_s, float)[index], mv, temp, final_static(temp, after_reset, need), after_reset
    )


def evaluate_activity_grid(
    t_s,
    acc_g,
    gyr_dps,
    labels: dict,
    name: str,
    windows_s,
    ks,
    time_thresholds_s,
    fs_hz: float,
    bench_acc_g: np.ndarray,
    signal: str = "acc",
    bench_gyr_dps: np.ndarray | None = None,
):
    """(parameters, evaluation) for every (window, k, T_th) of one detector over one stream, the
    detector run once per window: its figure of merit does not depend on the threshold, so each k is
    one comparison (seed 001's step IV) and each T_th one run-length pass (seed 000's eq. 8), as the
    moving variance's grid (:func:`~flightmode.detector.grid.evaluate_grid`). The decisions are
    exactly :func:`evaluate_activity`'s."""
    import dataclasses

    from flightmode.detector.activity import registry
    from flightmode.detector.activity.common import decide
    from flightmode.detector.evaluation import score
    from flightmode.detector.flight_mode import DetectorParams

    d = registry.get(name)
    for w in windows_s:
        base = ActivityParams(
            name, fs_hz=fs_hz, window_s=w, k=ks[0], time_threshold_s=time_thresholds_s[0], signal=signal
        )
        rest = rest_figures(base, bench_acc_g, bench_gyr_dps)
        merit = d.detect(
            t_s, acc_g, gyr_dps, threshold=rest["threshold"], **detector_kwargs(base, rest)
        ).merit
        periods, index, after_reset = _periods(merit.shape[0], base.window)
        for k in ks:
            thr = threshold_of(name, rest["merit_median"], k)
            marker = decide(merit, thr)
            for tth in time_thresholds_s:
                p = dataclasses.replace(base, k=k, time_threshold_s=tth)
                c = _checks(t_s, marker, merit, periods, index, after_reset, p.checks_needed)
                dp = DetectorParams(fs_hz=fs_hz, window_s=w, k_sigma=k, time_threshold_s=tth, method=name)
                yield dp, score(c, t_s, labels, dp, np.full(3, thr))


def evaluate_activity(t_s, acc_g, gyr_dps, labels: dict, p: ActivityParams, rest: dict):
    """The detector over a labelled stream, scored as :func:`~flightmode.detector.evaluation.evaluate`
    scores the moving variance (false statics in the window, response, missed static, accuracy)."""
    import dataclasses

    from flightmode.detector.evaluation import check_labels, score
    from flightmode.detector.flight_mode import DetectorParams

    check_labels(t_s, labels)
    c = activity_checks(t_s, acc_g, gyr_dps, p, rest)
    dp = dataclasses.replace(
        DetectorParams(fs_hz=p.fs_hz),
        window_s=p.window_s,
        k_sigma=p.k,
        time_threshold_s=p.time_threshold_s,
        method=p.name,
    )
    return score(c, t_s, labels, dp, np.full(3, rest["threshold"]))


__all__ = [
    "ActivityParams",
    "rest_figures",
    "activity_checks",
    "detector_kwargs",
    "evaluate_activity",
    "evaluate_activity_grid",
    "threshold_of",
    "DB_DETECTORS",
]
