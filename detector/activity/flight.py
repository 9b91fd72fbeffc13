"""Seed 001's (in)activity detectors as flight-mode detectors: seed 000's decision rule on top of an
activity marker, scored exactly as the moving-variance detector is.

- **Checks**: every W_s (``window_s``), a check closes a period of ``W_s fs`` samples; it is
  *temporarily static* when the detector marked every sample of the period inactive (marker 0).
  Seed 000's eq. 8 then makes it *final static* after ``T_th / W_s`` temporary statics in a row
  (:func:`~flightmode.detector.flight_mode.final_static`), so transmission needs the same sustained
  evidence whatever the detector. The checks' ``mv`` columns hold the detector's figure of merit at
  the closing sample (the same value on the three columns: these detectors give one merit per sample).
- **Window**: the detectors that have one use ``W_s fs`` samples (a 1 s window at 100 Hz is 100
  samples; the memory detectors cost O(N^2) and O(N^3) per sample in it: give them short windows).
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
        return int(round(self.window_s * self.fs_hz))

    @property
    def checks_needed(self) -> int:
        return max(1, int(round(self.time_threshold_s / self.window_s)))

    def validate(self) -> None:
        from flightmode.detector.activity import registry

        d = registry.get(self.name)  # an unknown name: DetectorError with the nearest
        if not self.window >= 2:
            raise DetectorError(f"--window-s {self.window_s:g}: {self.window} sample(s) at {self.fs_hz:g} Hz; "
                                "a window needs at least 2")
        if not (self.k > 0 and math.isfinite(self.k)):
            raise DetectorError(f"--k {self.k!r}: the threshold is k times the rest level, k > 0")
        if not self.time_threshold_s >= self.window_s:
            raise DetectorError(f"--time-threshold-s {self.time_threshold_s:g}: at least one check period "
                                f"(W_s {self.window_s:g} s)")
        if d.signals and self.signal not in d.signals:
            raise DetectorError(f"--signal {self.signal!r}: {self.name} takes {', '.join(d.signals)}")


def _kwargs(p: ActivityParams, rest: dict) -> dict:
    """The detector's own keyword parameters for these flight-mode parameters and rest figures."""
    from flightmode.detector.activity import registry

    d = registry.get(p.name)
    kw: dict = {"fs_hz": p.fs_hz}
    if p.name != "frd":
        kw["window"] = p.window
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
        raise DetectorError(f"{what} needs a gyroscope: sense the flight with one (flightmode sense RUN --gyro)")
    x = flexible_signal(p.signal, acc, bench_gyr_dps) if d.signals else None
    if p.name == "mbcd":
        rest["bandwidth"] = 1.06 * float(np.std(x)) * p.window ** -0.2  # Silverman (1986) eq. 3.28
    if p.name in DB_DETECTORS:
        rest["noise_spectrum"] = _rest_spectrum(x, p.window, max(1, p.window // 2))
    merit = d.detect(t, acc, bench_gyr_dps, threshold=0.0, **_kwargs(p, rest)).merit
    merit = merit[np.isfinite(merit)]
    if merit.size == 0:
        raise DetectorError(f"{p.name}: the bench recording ({n} samples) is shorter than one window ({p.window})")
    rest["merit_median"] = float(np.median(merit))
    if p.name in DB_DETECTORS:
        rest["threshold"] = rest["merit_median"] + 10.0 * math.log10(p.k)
    else:
        rest["threshold"] = p.k * rest["merit_median"]
    return rest


def _rest_spectrum(x: np.ndarray, window: int, shift: int) -> np.ndarray:
    """N(l): the mean magnitude spectrum of the rest signal's frames (the spectrum detectors' framing)."""
    from flightmode.detector.activity.spectrum import amplitude_spectra

    return amplitude_spectra(np.lib.stride_tricks.sliding_window_view(x, window)[::shift]).mean(axis=0)


def activity_checks(t_s: np.ndarray, acc_g: np.ndarray, gyr_dps: np.ndarray | None, p: ActivityParams,
                    rest: dict) -> Checks:
    """Every check of a whole stream (module docstring); ``rest`` from :func:`rest_figures`."""
    from flightmode.detector.activity import registry

    p.validate()
    d = registry.get(p.name)
    res = d.detect(t_s, acc_g, gyr_dps, threshold=rest["threshold"], **_kwargs(p, rest))
    n = p.window
    k = res.marker.shape[0] // n
    if k == 0:
        raise DetectorError(f"the stream ({res.marker.shape[0]} samples) is shorter than one check ({n})")
    periods = res.marker[: k * n].reshape(k, n)
    temp = ~periods.astype(bool).any(axis=1)  # every sample of the period inactive
    index = np.arange(k) * n + n - 1
    after_reset = np.zeros(k, bool)
    after_reset[0] = True
    merit = np.repeat(res.merit[index][:, None], 3, axis=1)
    return Checks(index, np.asarray(t_s, float)[index], merit, temp, final_static(temp, after_reset, p.checks_needed),
                  after_reset)


def evaluate_activity(t_s, acc_g, gyr_dps, labels: dict, p: ActivityParams, rest: dict):
    """The detector over a labelled stream, scored as :func:`~flightmode.detector.evaluation.evaluate`
    scores the moving variance (false statics in the window, response, missed static, accuracy)."""
    import dataclasses

    from flightmode.detector.evaluation import _check_labels, score
    from flightmode.detector.flight_mode import DetectorParams

    _check_labels(t_s, acc_g, labels)
    c = activity_checks(t_s, acc_g, gyr_dps, p, rest)
    dp = dataclasses.replace(DetectorParams(fs_hz=p.fs_hz), window_s=p.window_s, k_sigma=p.k,
                             time_threshold_s=p.time_threshold_s, method=p.name)
    return score(c, t_s, labels, dp, np.full(3, rest["threshold"]))


__all__ = ["ActivityParams", "rest_figures", "activity_checks", "evaluate_activity", "DB_DETECTORS"]
