"""Seed 001's Monte Carlo evaluation of the nine (in)activity detectors on synthesized signals
(section 3.1.2, Tables 1-6 and 13, Figures 3, 4 and 9).

Per run i (a recording from :func:`~flightmode.detector.activity.synth.synthesize`), per detector and
per input signal (|a|, |w|, their sum and product for the flexible detectors FRD, LTSD, FSD, MBGTD,
MBCD; the fixed input for AMVD, AMD, ARED, SHOD): a grid search over the window (and the frame shift
for LTSD and FSD; FRD has neither, Table 6) and the threshold, keeping the point of maximum accuracy
(fraction of samples whose marker equals the truth) and the Pearson correlation coefficient of the
marker with the truth there; then the ROC curve of the threshold swept at that run's best window
(and shift), and its area by the trapezoid rule over (FPR, TPR). Over N runs: mean +/- std of each
statistic and of the best parameters (Tables 1-6), the mean AUC and its rank (Table 13), and the
vertically averaged ROC curves (Figure 9; TPR averaged at fixed FPR: Fawcett 2006, "An introduction
to ROC analysis", Pattern Recognit. Lett. 27:861, section 8.1).

Choices where the seed is silent:

- The threshold "grid" is exact by default: the figure of merit does not depend on the threshold,
  so the detector runs once per (window, shift) and every distinct partition of its merits (every
  threshold between two consecutive distinct merit values) is scored from sorted counts. That is the
  limit of any threshold grid, and no slower than a coarse one. A reported threshold is the midpoint
  between the two merit values it separates (geometric for positive merits, :func:`exact_thresholds`).
  An explicit grid can be given per detector and signal (:class:`Grid`).
- The correlation of two binary vectors is the phi coefficient (TP TN - FP FN) / sqrt(...); when the
  marker is constant it is undefined and counted as 0. ``correlation`` is taken at the accuracy-best
  point; ``correlation_max`` is its own maximum over the grid (the seed's "we extract the maximum
  values of the statistics" reads either way).
- The first samples, before a detector has a merit, are marked active (the detectors' rule) and are
  scored like every other sample. In the ROC the NaN merit counts as +inf; the curve is anchored at
  (0, 0) and (1, 1).
- Ties: the first best point in grid order (windows, then shifts, ascending; thresholds ascending).
- Noise figures come from a bench recording of the same sensor lying still (``bench_s``, its own
  random stream), as they would on a real unit: sigma_a, sigma_w (AMD, ARED, SHOD) are the RMS of the
  per-axis standard deviations; LTSD/FSD's noise spectrum N(l) is the mean frame spectrum of the rest
  signal at the same window and shift; MBCD's kernel width is Silverman's rule of thumb
  1.06 s n^(-1/5) (Silverman 1986, "Density Estimation", eq. 3.28) with s the rest signal's standard
  deviation and n the window. LTSD's envelope order is the detector's default (6 frames).
- Standard deviations are sample standard deviations (ddof = 1).

Windows (issue 53): the detectors are causal (a stream's merit of sample k is the window ending at
k); ``MonteCarloConfig.alignment = "centred"`` scores each sample with the window centred on it
(:func:`merit_lag`, :func:`~flightmode.detector.activity.common.centre_merit`). The seed does not
say which it used for eq. (1)-(5) ("the frame at instant n", section 2.1.1); its LTSD envelope,
eq. (6), spans frames n - N .. n + N (centred); its memory detectors fill "a buffer ... with the last
N sensor readings" (section 2.3.1: causal, though a buffer's split marks a change wherever the
evaluation places it). Both are run and compared in docs/seed001_tables_n50.txt.

Cost, per 120 s run at 50 Hz with the default (wide) grid: 8-12 s of one core, most of it LTSD and
FSD at shift 1 and MBCD at 22-32 samples; :meth:`Grid.narrow` (the N = 500 study's grid) about 3 s.

Where each case errs: every run row also holds ``err_<kind>``, the share of the record's samples that the
case's marker gets wrong inside periods of each kind (synth.PERIOD_KINDS), at its best point; they sum to
1 - accuracy. ``err_jumping_flight`` is the part of ``err_jumping`` in a jump's flight (|a| below
``JUMP_FLIGHT_G``): there |a| |w| is near 0 whatever the rotation, so the Prod input loses the jump
(:func:`errors_by_kind`; docs/seed001_tables_n50.txt section 6).

Reproducibility: run i uses the generator of ``SeedSequence(seed, spawn_key=(i,))`` (the i-th child
of ``SeedSequence(seed)``), whatever the order or the worker it runs on; the recording and the bench
each take a named stream of it (:func:`~flightmode.streams.as_streams`).
"""

from __future__ import annotations

import math
import os
from dataclasses import asdict, dataclass, field
from typing import Any

import numpy as np
import numpy.typing as npt

from flightmode.detector.activity.synth import ACTIVITIES, DEFAULT_RANGES, PERIOD_KINDS, Ranges
from flightmode.errors import DetectorError, did_you_mean

SIGNALS = ("acc", "gyr", "sum", "product")
SIGNAL_LABEL = {"acc": "Acc.", "gyr": "Ang.", "sum": "Sum", "product": "Prod"}  # the seed's Table 13 labels
TABLE_OF = {"amvd": 1, "amd": 1, "ared": 1, "shod": 1, "fsd": 2, "ltsd": 3, "mbgtd": 4, "mbcd": 5, "frd": 6}
MAGNITUDE = ("amvd", "amd", "ared", "shod")
SPECTRUM = ("ltsd", "fsd")
MEMORY = ("mbgtd", "mbcd")
# a jump's flight: the sensor in free fall reads |a| near 0 (our jumps: synth._jumps); 0.5 g splits the
# flight from the contact push (which peaks at 2-3 g) at any noise level the study uses
JUMP_FLIGHT_G = 0.5
ERROR_KINDS = (*PERIOD_KINDS, "jumping_flight")


# ---------------------------------------------------------------- configuration
@dataclass(frozen=True, slots=True)
class Grid:
    """The parameter grid. Windows and shifts in samples. ``thresholds``: ((key, values), ...) with
    key "amvd" or "ltsd/acc"; a detector/signal not listed gets the exact sweep (module docstring)."""

    detectors: tuple[str, ...] = ("amvd", "amd", "ared", "shod", "frd", "ltsd", "fsd", "mbgtd", "mbcd")
    signals: tuple[str, ...] = SIGNALS
    # Wide enough that the seed's best windows (Tables 1-5, in samples at its 50 Hz: 3.4 for LTSD-Sum
    # up to 97 +- 10 for AMD) and the shifts (1.3 for LTSD-Sum up to 17 for FSD-Ang) lie inside, with
    # room beyond them (steps of about sqrt 2). The previous, narrower grid is :meth:`narrow`: its edges
    # held the best window of ARED, SHOD (3, the minimum) and FSD, LTSD (8-32, shift 1) in most runs.
    magnitude_windows: tuple[int, ...] = (2, 3, 4, 6, 8, 11, 16, 22, 32, 45, 64, 90, 128, 181, 256)
    spectrum_windows: tuple[int, ...] = (2, 3, 4, 6, 8, 11, 16, 22, 32)  # LTSD, FSD frame length
    spectrum_shifts: tuple[int, ...] = (1, 2, 3, 4, 6, 8, 12, 16, 24, 32)  # only shift <= window is used
    memory_windows: tuple[int, ...] = (3, 4, 6, 8, 11, 16, 22, 32)  # MBGTD, MBCD: O(N^2) per sample
    thresholds: tuple[tuple[str, tuple[float, ...]], ...] = ()

    @classmethod
    def narrow(cls, **kw) -> Grid:
        """The grid of the N = 500 study in docs/seed001_tables_n500.txt (before issue 53)."""
        return cls(
            magnitude_windows=(3, 5, 10, 20, 40, 80, 120),
            spectrum_windows=(8, 16, 32),
            spectrum_shifts=(1, 2, 4, 8, 16),
            memory_windows=(4, 8, 12, 16, 20),
            **kw,
        )

    def edges(self, detector: str) -> dict:
        """The grid's extremes for a detector: {"window": (lo, hi), "shift": (lo, hi) or None}; FRD
        has neither (None, None)."""
        if detector == "frd":
            return {"window": None, "shift": None}
        pts = self.points(detector)
        ws = [w for w, _ in pts if w is not None]
        ss = [s for _, s in pts if s is not None]
        return {"window": (min(ws), max(ws)), "shift": (min(ss), max(ss)) if ss else None}

    def check(self) -> None:
        from flightmode.detector.activity import registry

        for d in self.detectors:
            registry.get(d)  # an unknown name raises, with the nearest
        for s in self.signals:
            if s not in SIGNALS:
                raise DetectorError(
                    f"signal {s!r}: use one of {', '.join(SIGNALS)}{did_you_mean(s, SIGNALS)}"
                )
        for name, ws, least in (
            ("magnitude_windows", self.magnitude_windows, 2),
            ("spectrum_windows", self.spectrum_windows, 2),
            ("spectrum_shifts", self.spectrum_shifts, 1),
            ("memory_windows", self.memory_windows, 2),
        ):
            if not ws or any(isinstance(w, bool) or int(w) != w or w < least for w in ws):
                raise DetectorError(
                    f"Grid.{name} = {ws!r}: give one or more whole numbers of samples >= {least}"
                )
        if not any(s <= w for w in self.spectrum_windows for s in self.spectrum_shifts):
            raise DetectorError("Grid: no spectrum shift is <= a spectrum window")
        keys = {k for k, _ in self.thresholds}
        valid = {d for d in self.detectors} | {f"{d}/{s}" for d in self.detectors for s in SIGNALS}
        for k in keys - valid:
            raise DetectorError(
                f"Grid.thresholds key {k!r}: use a detector or detector/signal of the grid"
                f"{did_you_mean(k, sorted(valid))}"
            )

    def thresholds_for(self, detector: str, signal: str | None) -> np.ndarray | None:
        table = dict(self.thresholds)
        v = table.get(f"{detector}/{signal}") if signal else None
        if v is None and detector in table:
            v = table[detector]
        return None if v is None else np.asarray(sorted(v), float)

    def points(self, detector: str) -> list[tuple[int | None, int | None]]:
        """(window, shift) pairs of a detector, in grid order."""
        if detector == "frd":
            return [(None, None)]
        if detector in SPECTRUM:
            return [
                (w, s) for w in sorted(self.spectrum_windows) for s in sorted(self.spectrum_shifts) if s <= w
            ]
        ws = self.memory_windows if detector in MEMORY else self.magnitude_windows
        return [(w, None) for w in sorted(ws)]

    def cases(self) -> list[tuple[str, str | None]]:
        """(detector, signal) in the seed's table order; signal None for the fixed-input detectors."""
        from flightmode.detector.activity import registry

        out: list[tuple[str, str | None]] = []
        for d in sorted(self.detectors, key=lambda n: (TABLE_OF[n], registry.NAMES.index(n))):
            sigs = registry.get(d).signals
            out += [(d, s) for s in self.signals if s in sigs] if sigs else [(d, None)]
        return out


@dataclass(frozen=True, slots=True)
class MonteCarloConfig:
    """One Monte Carlo study: the recordings (synthesizer settings), the bench, the grid."""

    duration_s: float = 120.0
    fs_hz: float = 50.0  # the seed's IMU rate (section 4.1)
    gravity_axis: str = "z"
    sigma_acc_g: float = 2.23e-3
    sigma_gyr_dps: float = 0.05
    acc_range_g: float = 3.0
    gyr_range_dps: float = 500.0
    ranges: Ranges = DEFAULT_RANGES
    activities: tuple[str, ...] = ACTIVITIES  # the synthesizer's mix (drawn uniformly)
    sequence: bool = False  # True: the activities in their order, cycling (synth.FIGURE2_SEQUENCE)
    bench_s: float = 20.0  # the still recording the noise figures come from
    grid: Grid = field(default_factory=Grid)
    roc_points: int = 101  # FPR grid of the averaged ROC curves
    # "causal": the merit of sample k is that of the window ending at k (the detectors' own, a stream's);
    # "centred": that of the window centred on k (common.centre_merit, merit_lag).
    alignment: str = "causal"
    # MBCD's Parzen width lambda (eq. 12): None = Silverman's rule on the bench (module docstring), or
    # one fixed value in the signal's unit for every input (a sensitivity option: section 2.3.2 calls
    # lambda "the standard deviation of the distribution" without saying which distribution)
    mbcd_bandwidth: float | None = None

    def check(self) -> None:
        from flightmode.detector.activity.common import ALIGNMENTS

        self.grid.check()
        if self.alignment not in ALIGNMENTS:
            raise DetectorError(
                f"alignment = {self.alignment!r}: use one of {', '.join(ALIGNMENTS)}"
                f"{did_you_mean(str(self.alignment), ALIGNMENTS)}"
            )
        if self.mbcd_bandwidth is not None and not (
            math.isfinite(self.mbcd_bandwidth) and self.mbcd_bandwidth > 0
        ):
            raise DetectorError(f"mbcd_bandwidth = {self.mbcd_bandwidth!r}: must be finite and > 0 (or None)")
        bad = [a for a in self.activities if a not in ACTIVITIES]
        if not self.activities or bad:
            raise DetectorError(
                f"activities = {self.activities!r}: give one or more of {', '.join(ACTIVITIES)}"
            )
        if not (isinstance(self.roc_points, int) and self.roc_points >= 2):
            raise DetectorError(f"roc_points = {self.roc_points!r}: need an integer >= 2")
        longest = max(
            max(self.grid.magnitude_windows), max(self.grid.spectrum_windows), max(self.grid.memory_windows)
        )
        for name, s in (("duration_s", self.duration_s), ("bench_s", self.bench_s)):
            if not s * self.fs_hz > 2 * longest:
                raise DetectorError(
                    f"{name} = {s:g} s is {s * self.fs_hz:g} samples at {self.fs_hz:g} Hz: "
                    f"need more than twice the longest window ({longest})"
                )


# ---------------------------------------------------------------- one merit vector against the truth
@dataclass(frozen=True, slots=True)
class Sweep:
    """Counts at each candidate threshold (ascending): marker = merit >= threshold (NaN: active)."""

    thresholds: np.ndarray
    tp: np.ndarray
    fp: np.ndarray
    tn: np.ndarray
    fn: np.ndarray

    @property
    def accuracy(self) -> np.ndarray:
        return (self.tp + self.tn) / (self.tp + self.fp + self.tn + self.fn)

    @property
    def correlation(self) -> np.ndarray:
        """Pearson's r of the marker and the truth (the phi coefficient); 0 where undefined."""
        tp, fp, tn, fn = (x.astype(float) for x in (self.tp, self.fp, self.tn, self.fn))
        den = np.sqrt((tp + fp) * (tn + fn) * (tp + fn) * (fp + tn))
        with np.errstate(invalid="ignore", divide="ignore"):
            r = (tp * tn - fp * fn) / den
        return np.where(den > 0, r, 0.0)

    @property
    def tpr(self) -> np.ndarray:
        p = self.tp + self.fn
        return self.tp / p if p[0] else np.full(self.tp.shape, np.nan)

    @property
    def fpr(self) -> np.ndarray:
        n = self.fp + self.tn
        return self.fp / n if n[0] else np.full(self.fp.shape, np.nan)


def exact_thresholds(merit: np.ndarray) -> np.ndarray:
    """One threshold per distinct partition of the finite merits (ascending): the lowest value (all
    active), the midpoints between consecutive distinct values, and just above the highest (all
    finite merits static). A midpoint is geometric between two positive values (the merits of most
    detectors span decades: 6 and 3e4 give 420, not 15,000) and arithmetic otherwise (the dB merits
    of LTSD and FSD, already logarithmic, can be negative)."""
    u = np.unique(merit[np.isfinite(merit)])
    if u.size == 0:
        return np.zeros(1)
    lo, hi = u[:-1], u[1:]
    with np.errstate(invalid="ignore"):
        mid = np.where(lo > 0, np.sqrt(lo * hi), 0.5 * (lo + hi))
    mid = np.clip(mid, np.nextafter(lo, np.inf), hi)  # strictly above lo, at most hi (rounding)
    return np.concatenate([u[:1], mid, [np.nextafter(u[-1], np.inf)]])


def sweep(merit, truth, thresholds=None) -> Sweep:
    """The confusion counts of the decision ``marker = ~(merit < threshold)`` (seed 001, section
    2.3.3 step IV) at every threshold (exact sweep when None) against the boolean ``truth``."""
    m = np.asarray(merit, float)
    y = np.asarray(truth).astype(bool)
    if m.shape != y.shape or m.ndim != 1:
        raise DetectorError(f"merit {m.shape} and truth {y.shape} must be 1-D arrays of one length")
    thr = exact_thresholds(m) if thresholds is None else np.asarray(thresholds, float)
    key = np.where(np.isnan(m), np.inf, m)  # a NaN merit is never below a threshold: active
    pos, neg = np.sort(key[y]), np.sort(key[~y])
    fn = np.searchsorted(pos, thr, side="left")  # positives marked static (merit < threshold)
    tn = np.searchsorted(neg, thr, side="left")
    return Sweep(thr, pos.size - fn, neg.size - tn, tn, fn)


def roc_curve(merit, truth, thresholds=None) -> tuple[np.ndarray, np.ndarray]:
    """(FPR, TPR) of the threshold swept from high to low, anchored at (0, 0) and (1, 1)."""
    s = sweep(merit, truth, thresholds)
    fpr, tpr = s.fpr[::-1], s.tpr[::-1]
    return np.concatenate([[0.0], fpr, [1.0]]), np.concatenate([[0.0], tpr, [1.0]])


def auc(fpr: np.ndarray, tpr: np.ndarray) -> float:
    """Area under a ROC curve by the trapezoid rule (FPR non-decreasing)."""
    return float(np.sum(np.diff(fpr) * 0.5 * (tpr[1:] + tpr[:-1])))


def roc_on_grid(fpr: np.ndarray, tpr: np.ndarray, grid: np.ndarray) -> np.ndarray:
    """TPR of a ROC curve at fixed FPR values (linear between points; at a vertical step, the top)."""
    uf, first = np.unique(fpr[::-1], return_index=True)  # the last point of each FPR: its highest TPR
    top = tpr[::-1][first]
    return np.interp(grid, uf, top)


# ---------------------------------------------------------------- one run
def _run_generator(seed: int, index: int) -> np.random.Generator:
    """Run ``index``'s generator: the index-th child of SeedSequence(seed), built directly."""
    return np.random.Generator(np.random.PCG64(np.random.SeedSequence(int(seed), spawn_key=(int(index),))))


def _bench_figures(bench, d, signal, window, shift, bandwidth=None) -> dict:
    """The detector's noise figures from the still bench recording (module docstring)."""
    from flightmode.detector.activity.common import flexible_signal
    from flightmode.detector.activity.spectrum import amplitude_spectra

    kw: dict = {}
    if d.name in ("amd", "shod"):
        kw["sigma_acc_g"] = float(np.sqrt(np.mean(np.var(bench.acc_g, axis=0))))
    if d.name in ("ared", "shod"):
        kw["sigma_gyr_dps"] = float(np.sqrt(np.mean(np.var(bench.gyr_dps, axis=0))))
    if d.name in SPECTRUM:
        x = flexible_signal(signal, bench.acc_g, bench.gyr_dps)
        frames = np.lib.stride_tricks.sliding_window_view(x, window)[::shift]
        kw["noise_spectrum"] = amplitude_spectra(frames).mean(axis=0)
    if d.name == "mbcd":
        if bandwidth is not None:
            kw["bandwidth"] = float(bandwidth)
        else:
            x = flexible_signal(signal, bench.acc_g, bench.gyr_dps)
            kw["bandwidth"] = 1.06 * float(np.std(x)) * window**-0.2  # Silverman (1986) eq. 3.28
    return kw


LTSD_ORDER = 6  # the LTSE order the study runs LTSD at (spectrum.detect_ltsd's default)


def merit_lag(detector: str, window: int | None, shift: int | None, order: int = LTSD_ORDER) -> int:
    """How many samples the causal merit of ``detector`` lags the centre of the data it describes,
    rounded down (the ``lag`` of :func:`~flightmode.detector.activity.common.centre_merit`):

    - AMVD, AMD, ARED, SHOD, MBGTD, MBCD: the window ends at k, its centre is (window - 1) / 2
      samples earlier (seed 001, eq. 1-4, 9-14: V(n) of "the frame at instant n").
    - LTSD, FSD: the merit held at sample k is that of frame m - order, m the last frame ending at
      or before k (spectrum module docstring); frame n's centre is n shift + (window - 1) / 2, and the
      hold adds (shift - 1) / 2 on average: order shift + (window + shift - 2) / 2. Centred, the
      envelope spans frames n - order .. n + order about the sample's own frame, as eq. (6) writes it.
    - FRD: 0. It has no window (Table 6); its filters' delay is not a window's (left causal).
    """
    if detector == "frd" or window is None:
        return 0
    if detector in SPECTRUM:
        s = int(shift or 1)
        o = order if detector == "ltsd" else 0
        return int(o * s + (int(window) + s - 2) // 2)
    return int((int(window) - 1) // 2)


@dataclass(frozen=True, slots=True)
class GridBest:
    """The grid search of one detector and signal over one recording: the accuracy-best point
    (accuracy, correlation there, threshold, window, shift; None where the detector has none), the
    correlation's own maximum, the merit at the best (window, shift), and the ``surface``: per
    (window, shift) in grid order, the best accuracy over thresholds (the seed's Figure 4)."""

    accuracy: float
    correlation: float
    correlation_max: float
    threshold: float
    window: int | None
    shift: int | None
    merit: np.ndarray
    surface: tuple[tuple[int | None, int | None, float], ...]


def grid_search(
    name: str,
    signal: str | None,
    t_s,
    acc_g,
    gyr_dps,
    truth,
    points,
    *,
    fs_hz: float,
    thresholds=None,
    figures=None,
    alignment: str = "causal",
) -> GridBest:
    """Detector ``name`` (input ``signal``, None for a fixed-input detector) at every (window, shift)
    of ``points`` (None where it takes none), run once per point with ``figures(window, shift)`` (its
    noise figures: a dict of keyword arguments) and scored at every threshold (exact when
    ``thresholds`` is None) against the boolean ``truth`` (seed 001, section 3.1.2). ``alignment``
    "centred" scores the merit of the window centred on each sample (:func:`merit_lag`)."""
    from flightmode.detector.activity import registry
    from flightmode.detector.activity.common import centre_merit

    d = registry.get(name)
    y = np.asarray(truth).astype(bool)
    best, corr_max, surface = None, -np.inf, []
    for window, shift in points:
        kw = {"fs_hz": fs_hz, **(figures(window, shift) if figures else {})}
        for key, v in (("window", window), ("shift", shift), ("signal", signal)):
            if v is not None:
                kw[key] = v
        merit = d.detect(t_s, acc_g, gyr_dps, threshold=0.0, **kw).merit
        if alignment == "centred":
            merit = centre_merit(merit, merit_lag(name, window, shift))
        s = sweep(merit, y, thresholds)
        acc, corr = s.accuracy, s.correlation
        k = int(np.argmax(acc))  # the first best: the lowest threshold
        corr_max = max(corr_max, float(corr.max()))
        surface.append((window, shift, float(acc[k])))
        if best is None or acc[k] > best[0]:  # strictly better: ties keep the earlier grid point
            best = (float(acc[k]), float(corr[k]), float(s.thresholds[k]), window, shift, merit)
    if best is None:
        raise DetectorError(f"grid_search {name}: points is empty: give one or more (window, shift) pairs")
    return GridBest(best[0], best[1], corr_max, best[2], best[3], best[4], best[5], tuple(surface))


def period_index(periods, n: int) -> np.ndarray:
    """(n,) index into synth.PERIOD_KINDS of every sample's period."""
    kind = np.zeros(n, np.int64)
    for p in periods:
        kind[p.start : p.stop] = PERIOD_KINDS.index(p.kind)
    return kind


def errors_by_kind(merit, threshold: float, truth, kind: np.ndarray, flight: np.ndarray) -> dict[str, float]:
    """{"err_<kind>": share of all samples that the marker ``merit >= threshold`` (NaN: active) gets
    wrong in periods of each synth.PERIOD_KINDS kind, ..., "err_jumping_flight": the part of
    err_jumping where ``flight`` holds}. The shares sum to 1 - accuracy."""
    from flightmode.detector.activity.common import decide

    y = np.asarray(truth).astype(bool)
    wrong = decide(np.asarray(merit, float), threshold).astype(bool) != y
    counts = np.bincount(kind[wrong], minlength=len(PERIOD_KINDS)) / y.size
    out = {f"err_{k}": float(c) for k, c in zip(PERIOD_KINDS, counts)}
    out["err_jumping_flight"] = float((wrong & flight).sum() / y.size)
    return out


def evaluate_run(index: int, seed: int, config: MonteCarloConfig) -> dict:
    """Run ``index`` of the study: {"index", "rows": [one dict per (detector, signal)], "roc":
    {(detector, signal): TPR at the config's FPR grid}}. Pure: the same (index, seed, config) give the
    same result in any process."""
    from flightmode.detector.activity import registry
    from flightmode.detector.activity.scales import to_paper_scale
    from flightmode.detector.activity.synth import still_recording, synthesize
    from flightmode.streams import as_streams

    streams = as_streams(_run_generator(seed, index))
    sensor: dict[str, Any] = {
        "fs_hz": config.fs_hz,
        "gravity_axis": config.gravity_axis,
        "sigma_acc_g": config.sigma_acc_g,
        "sigma_gyr_dps": config.sigma_gyr_dps,
        "acc_range_g": config.acc_range_g,
        "gyr_range_dps": config.gyr_range_dps,
    }
    rec = synthesize(
        streams.rng("recording"),
        config.duration_s,
        ranges=config.ranges,
        activities=tuple(config.activities),
        sequence=config.sequence,
        **sensor,
    )
    bench = still_recording(streams.rng("bench"), config.bench_s, **sensor)
    truth = rec.marker.astype(bool)
    from flightmode.detector.activity.common import norm3

    kind = period_index(rec.periods, truth.size)
    flight = (kind == PERIOD_KINDS.index("jumping")) & (norm3(rec.acc_g) < JUMP_FLIGHT_G)
    fpr_grid = np.linspace(0.0, 1.0, config.roc_points)
    sigma_acc_g = float(np.sqrt(np.mean(np.var(bench.acc_g, axis=0))))  # as _bench_figures has it
    rows, roc = [], {}
    for name, signal in config.grid.cases():
        d = registry.get(name)
        thresholds = config.grid.thresholds_for(name, signal)
        b = grid_search(
            name,
            signal,
            rec.t_s,
            rec.acc_g,
            rec.gyr_dps,
            truth,
            config.grid.points(name),
            fs_hz=config.fs_hz,
            thresholds=thresholds,
            figures=lambda w, s, d=d, sig=signal: _bench_figures(bench, d, sig, w, s, config.mbcd_bandwidth),
            alignment=config.alignment,
        )
        fpr, tpr = roc_curve(b.merit, truth, thresholds)  # the threshold swept at the best window (and shift)
        roc[(name, signal)] = roc_on_grid(fpr, tpr, fpr_grid)
        rows.append(
            {
                "run": int(index),
                "detector": name,
                "signal": signal,
                "accuracy": b.accuracy,
                "correlation": b.correlation,
                "correlation_max": b.correlation_max,
                "threshold": b.threshold,
                "threshold_paper": to_paper_scale(name, signal, b.threshold, sigma_acc_g),
                "window": math.nan if b.window is None else float(b.window),
                "shift": math.nan if b.shift is None else float(b.shift),
                "auc": auc(fpr, tpr),
                "activity_fraction": float(truth.mean()),
                **errors_by_kind(b.merit, b.threshold, truth, kind, flight),
            }
        )
    return {"index": int(index), "rows": rows, "roc": roc}


# ---------------------------------------------------------------- the study
@dataclass(frozen=True, slots=True)
class MonteCarloResult:
    """Every run's rows (in run order), the FPR grid and each case's per-run TPR (n_runs, K)."""

    seed: int
    n_runs: int
    config: MonteCarloConfig
    rows: tuple[dict, ...]
    roc_fpr: np.ndarray
    roc_tpr: dict


def run_montecarlo(
    n_runs: int,
    *,
    seed: int = 0,
    config: MonteCarloConfig | None = None,
    client=None,
    order=None,
    on_run=None,
    workers: int = 1,
    scheduler: str | None = None,
) -> MonteCarloResult:
    """The study over runs 0 .. n_runs - 1, one task per run (:func:`flightmode.cluster.map_flights`):
    on ``client`` (a ``dask.distributed.Client``) when given, else on the Dask ``scheduler`` at that
    address, else on a local cluster of ``workers`` processes (:func:`flightmode.cluster.open_client`)
    when ``workers`` > 1, else in this process. ``order``: the order to run them in (a permutation
    of 0 .. n_runs - 1; the result does not depend on it). ``on_run(index)`` after each run."""
    cfg = MonteCarloConfig() if config is None else config
    if isinstance(n_runs, bool) or not isinstance(n_runs, (int, np.integer)) or n_runs < 1:
        raise DetectorError(f"n_runs = {n_runs!r}: must be a positive integer")
    if isinstance(seed, bool) or not isinstance(seed, (int, np.integer)) or seed < 0:
        raise DetectorError(f"seed = {seed!r}: must be an integer >= 0")
    cfg.check()
    idx = list(range(n_runs)) if order is None else [int(i) for i in order]
    if sorted(idx) != list(range(n_runs)):
        raise DetectorError(f"order must be a permutation of 0 .. {n_runs - 1}")
    if isinstance(workers, bool) or not isinstance(workers, (int, np.integer)) or workers < 1:
        raise DetectorError(f"workers = {workers!r}: must be a positive integer")
    import hashlib

    from flightmode.cluster import map_flights

    # task keys unique to this study: two studies on one scheduler never share a task
    token = hashlib.sha256(repr((seed, n_runs, cfg)).encode()).hexdigest()[:12]
    results = map_flights(
        evaluate_run,
        [(i, seed, cfg) for i in idx],
        int(workers),
        (lambda n: on_run(idx[n])) if on_run else None,
        client=client,
        scheduler=scheduler,
        keys=[f"activity-mc-{token}-{i}" for i in idx],
    )
    done = {r["index"]: r for r in results}
    runs = [done[i] for i in range(n_runs)]  # run order, whatever the completion order
    rows = tuple(row for r in runs for row in r["rows"])
    roc = {k: np.stack([r["roc"][k] for r in runs]) for k in runs[0]["roc"]}
    return MonteCarloResult(int(seed), int(n_runs), cfg, rows, np.linspace(0.0, 1.0, cfg.roc_points), roc)


# ---------------------------------------------------------------- the paper's numbers
@dataclass(frozen=True, slots=True)
class PaperRow:
    """One case of seed 001's Monte Carlo on synthesized signals (N = 500): (mean, std) per statistic
    as printed in Tables 1-6 (None where the table has no row: FRD has no window, only LTSD and FSD a
    shift), and the AUC with its overall rank from Table 13."""

    table: int
    detector: str
    signal: str | None
    accuracy: tuple[float, float]
    correlation: tuple[float, float]
    window: tuple[float, float] | None
    threshold: tuple[float, float]
    shift: tuple[float, float] | None
    auc: float
    auc_rank: int


def _p(table, det, sig, acc, corr, win, thr, shift, auc_value, rank):
    return PaperRow(table, det, sig, acc, corr, win, thr, shift, auc_value, rank)


# Seed 001, Tables 1-6 (accuracy, correlation coefficient, window length, threshold, shift: mean +-
# std over N = 500 synthesized runs) and Table 13 (AUC, overall rank), transcribed from the seed text.
PAPER_TABLES: tuple[PaperRow, ...] = (
    # Table 1: magnitude methods without flexible input
    _p(
        1,
        "amvd",
        None,
        (0.8741, 0.0181),
        (0.7137, 0.0360),
        (26.065, 1.1011),
        (0.0188, 0.0049),
        None,
        0.8778,
        12,
    ),
    _p(
        1,
        "amd",
        None,
        (0.9641, 0.0087),
        (0.9205, 0.0175),
        (96.9560, 9.8260),
        (0.0008, 0.0002),
        None,
        0.9576,
        2,
    ),
    _p(
        1,
        "ared",
        None,
        (0.9431, 0.0136),
        (0.8752, 0.0270),
        (21.9300, 1.5849),
        (2.3712, 2.1621),
        None,
        0.9256,
        3,
    ),
    _p(
        1,
        "shod",
        None,
        (0.9817, 0.0124),
        (0.9592, 0.0269),
        (10.7556, 1.3007),
        (1.3426, 0.2898),
        None,
        0.9880,
        1,
    ),
    # Table 2: FSD
    _p(
        2,
        "fsd",
        "acc",
        (0.9395, 0.0155),
        (0.8639, 0.0331),
        (18.0836, 1.8278),
        (2.6441, 0.6272),
        (15.1304, 2.2318),
        0.8897,
        11,
    ),
    _p(
        2,
        "fsd",
        "gyr",
        (0.9344, 0.0153),
        (0.8534, 0.0311),
        (17.3496, 1.8112),
        (13.8640, 3.0741),
        (16.9824, 0.9055),
        0.7909,
        18,
    ),
    _p(
        2,
        "fsd",
        "sum",
        (0.9330, 0.0351),
        (0.8520, 0.058906),
        (13.0636, 0.9983),
        (10.4764, 2.6726),
        (13.1048, 0.4916),
        0.7722,
        21,
    ),
    _p(
        2,
        "fsd",
        "product",
        (0.9470, 0.0441),
        (0.8835, 0.0788),
        (9.5292, 1.7607),
        (8.3344, 2.8890),
        (7.2364, 2.9423),
        0.7422,
        24,
    ),
    # Table 3: LTSD
    _p(
        3,
        "ltsd",
        "acc",
        (0.9252, 0.0179),
        (0.8328, 0.0388),
        (14.6012, 0.7580),
        (4.9140, 1.7976),
        (1.6348, 0.7648),
        0.9127,
        7,
    ),
    _p(
        3,
        "ltsd",
        "gyr",
        (0.9150, 0.0926),
        (0.8209, 0.15256),
        (5.2376, 0.8156),
        (17.3252, 3.0170),
        (1.3936, 0.5699),
        0.7468,
        23,
    ),
    _p(
        3,
        "ltsd",
        "sum",
        (0.9355, 0.0138),
        (0.8556, 0.0282),
        (3.3848, 0.2816),
        (16.1172, 3.6251),
        (1.2744, 0.5312),
        0.8940,
        10,
    ),
    _p(
        3,
        "ltsd",
        "product",
        (0.9318, 0.0884),
        (0.8585, 0.1266),
        (11.3200, 0.3639),
        (8.7112, 1.7633),
        (1.7776, 0.7616),
        0.8959,
        9,
    ),
    # Table 4: MBGTD
    _p(
        4,
        "mbgtd",
        "acc",
        (0.9243, 0.0139),
        (0.8295, 0.02813),
        (12.8088, 3.4643),
        (1.1286, 0.7215),
        None,
        0.9090,
        8,
    ),
    _p(
        4,
        "mbgtd",
        "gyr",
        (0.9114, 0.0179),
        (0.8040, 0.0345),
        (5.9932, 3.4687),
        (84.9760, 79.7386),
        None,
        0.7478,
        22,
    ),
    _p(
        4,
        "mbgtd",
        "sum",
        (0.9115, 0.0179),
        (0.8041, 0.0345),
        (5.9900, 3.4701),
        (84.8680, 79.275),
        None,
        0.8648,
        15,
    ),
    _p(
        4,
        "mbgtd",
        "product",
        (0.9349, 0.0159),
        (0.85312, 0.03532),
        (9.7260, 3.7743),
        (151.8720, 81.4212),
        None,
        0.9250,
        4,
    ),
    # Table 5: MBCD
    _p(
        5,
        "mbcd",
        "acc",
        (0.9257, 0.0145),
        (0.8339, 0.0289),
        (8.4584, 3.1602),
        (1.749e-6, 5.389e-7),
        None,
        0.9133,
        6,
    ),
    _p(
        5,
        "mbcd",
        "gyr",
        (0.9098, 0.0180),
        (0.80002, 0.034774),
        (7.6108, 2.4729),
        (0.1117, 0.0179),
        None,
        0.8655,
        13,
    ),
    _p(
        5,
        "mbcd",
        "sum",
        (0.9100, 0.0180),
        (0.80066, 0.034845),
        (6.0644, 2.1265),
        (0.0925, 0.0182),
        None,
        0.8650,
        14,
    ),
    _p(
        5,
        "mbcd",
        "product",
        (0.9373, 0.0168),
        (0.85877, 0.037214),
        (11.1192, 3.2323),
        (0.1068, 0.0267),
        None,
        0.9172,
        5,
    ),
    # Table 6: FRD (no window length row: the seed gives FRD a threshold only)
    _p(6, "frd", "acc", (0.7921, 0.0178), (0.5228, 0.0389), None, (0.0100, 0.0070), None, 0.8451, 16),
    _p(6, "frd", "gyr", (0.7608, 0.0207), (0.4823, 0.0464), None, (0.1720, 0.2862), None, 0.7787, 19),
    _p(6, "frd", "sum", (0.7610, 0.0207), (0.4825, 0.0463), None, (0.1780, 0.2990), None, 0.7786, 20),
    _p(6, "frd", "product", (0.7944, 0.0223), (0.5362, 0.0509), None, (0.1680, 0.2777), None, 0.8177, 17),
)

# What in the seed text is odd, as transcribed (the values above are as printed):
PAPER_NOTES = (
    "Table 2, FSD-Sum correlation std is printed 0.058906 (six decimals where the others have four).",
    "Tables 4-5 print some values with 5-6 decimals (0.02813, 0.85312, 0.80002 +- 0.034774, ...); kept as printed.",
    "Table 3 sets LTSD-Sum's correlation (0.8556) in bold although LTSD-Prod's (0.8585) is higher.",
    (
        "Section 3.1.2 speaks of 'the eight methods' and Table 13 of 24 cases: nine detectors, four of them "
        "with fixed input (4 + 5 x 4 = 24 cases)."
    ),
    (
        "Table 6 (FRD) has no window-length row; the thresholds' units are not stated anywhere (AMD's 0.0008 "
        "and MBCD-Acc's 1.7e-6 suggest unscaled merits; see the detectors' module docstrings)."
    ),
    (
        "Tables 1-6 and 13 read cleanly otherwise: every value has a mean and a std, and Table 13's ranks "
        "order its AUCs without a tie or a gap."
    ),
    (
        "Table 13 does not follow Tables 2-4's accuracies: FSD-Prod has Table 2's best accuracy (0.947) and "
        "the lowest AUC of all 24 cases (0.742); FSD-Ang./Sum, LTSD-Ang. and MBGTD-Ang. (accuracies 0.91-0.93) "
        "rank 18-23 by AUC. How the paper's ROC curves were taken is not stated (section 4.1)."
    ),
)


def paper_row(detector: str, signal: str | None) -> PaperRow | None:
    """The paper's row for a case, or None when the paper has none."""
    for p in PAPER_TABLES:
        if p.detector == detector and p.signal == signal:
            return p
    return None


# ---------------------------------------------------------------- the paper's form
def label(detector: str, signal: str | None) -> str:
    """The seed's name of a case: "SHOD", "FSD-Acc.", "MBCD-Prod"."""
    return detector.upper() if signal is None else f"{detector.upper()}-{SIGNAL_LABEL[signal]}"


def _ms(v: npt.ArrayLike) -> tuple[float, float]:
    v = np.asarray(v, float)
    if np.all(np.isnan(v)):
        return math.nan, math.nan
    return float(np.nanmean(v)), float(np.nanstd(v, ddof=1)) if np.sum(~np.isnan(v)) > 1 else math.nan


def summary(result: MonteCarloResult) -> list[dict]:
    """One row per (detector, signal), in the seed's table order: the table number, mean and std of
    accuracy, correlation, correlation_max, window, shift, threshold and AUC over the runs, the AUC
    rank (1 = highest mean AUC), and the paper's values beside them (NaN where it has none)."""
    rows = []
    for name, signal in result.config.grid.cases():
        mine = [r for r in result.rows if r["detector"] == name and r["signal"] == signal]
        row: dict[str, Any] = {
            "table": TABLE_OF[name],
            "detector": name,
            "signal": signal,
            "label": label(name, signal),
            "n_runs": len(mine),
        }
        for stat in ("accuracy", "correlation", "correlation_max", "window", "shift", "threshold", "auc"):
            row[f"{stat}_mean"], row[f"{stat}_std"] = _ms([r[stat] for r in mine])
        # the best threshold is often flat over decades (any value in a wide gap between the merits of
        # still and active samples is best): the median is the steadier summary beside the mean
        row["threshold_median"] = float(np.median([r["threshold"] for r in mine]))
        tp = [r.get("threshold_paper", math.nan) for r in mine]
        row["threshold_paper_mean"], row["threshold_paper_std"] = _ms(tp)
        row["threshold_paper_median"] = float(np.median(tp)) if not np.all(np.isnan(tp)) else math.nan
        rows.append(row)
    order = sorted(
        range(len(rows)), key=lambda i: -rows[i]["auc_mean"] if np.isfinite(rows[i]["auc_mean"]) else np.inf
    )
    for rank, i in enumerate(order, 1):
        rows[i]["auc_rank"] = rank
    for row in rows:
        p = paper_row(row["detector"], row["signal"])
        for stat in ("accuracy", "correlation", "window", "threshold", "shift"):
            v = getattr(p, stat) if p else None
            row[f"paper_{stat}_mean"], row[f"paper_{stat}_std"] = v if v else (math.nan, math.nan)
        row["paper_auc"] = p.auc if p else math.nan
        row["paper_auc_rank"] = p.auc_rank if p else -1
    return rows


def _pm(m: float, s: float, fmt: str) -> str:
    if not np.isfinite(m):
        return "-"
    return f"{m:{fmt}} +- {s:{fmt}}" if np.isfinite(s) else f"{m:{fmt}}"


def format_tables(result_or_rows) -> str:
    """Tables 1-6 and 13, ours beside the paper's, as text (one line per case)."""
    rows = summary(result_or_rows) if isinstance(result_or_rows, MonteCarloResult) else list(result_or_rows)
    out = []
    head = (
        f"{'case':<11} {'accuracy':>17} {'paper':>17} {'d acc':>6}  {'correlation':>17} {'paper':>17}  "
        f"{'window':>13} {'paper':>15}  {'shift':>11} {'paper':>13}  {'threshold':>19} {'paper':>19}"
    )
    for table in sorted({r["table"] for r in rows}):
        out += [f"Table {table}", head]
        for r in (r for r in rows if r["table"] == table):
            d = r["accuracy_mean"] - r["paper_accuracy_mean"]
            out.append(
                f"{r['label']:<11} {_pm(r['accuracy_mean'], r['accuracy_std'], '.4f'):>17} "
                f"{_pm(r['paper_accuracy_mean'], r['paper_accuracy_std'], '.4f'):>17} "
                f"{(f'{d:+.3f}' if np.isfinite(d) else '-'):>6}  "
                f"{_pm(r['correlation_mean'], r['correlation_std'], '.4f'):>17} "
                f"{_pm(r['paper_correlation_mean'], r['paper_correlation_std'], '.4f'):>17}  "
                f"{_pm(r['window_mean'], r['window_std'], '.1f'):>13} "
                f"{_pm(r['paper_window_mean'], r['paper_window_std'], '.1f'):>15}  "
                f"{_pm(r['shift_mean'], r['shift_std'], '.1f'):>11} "
                f"{_pm(r['paper_shift_mean'], r['paper_shift_std'], '.1f'):>13}  "
                f"{_pm(r['threshold_mean'], r['threshold_std'], '.4g'):>19} "
                f"{_pm(r['paper_threshold_mean'], r['paper_threshold_std'], '.4g'):>19}"
            )
        out.append("")
    out += ["Table 13 (AUC; rank)", f"{'case':<11} {'AUC':>17} {'rank':>5} {'paper AUC':>10} {'rank':>5}"]
    for r in sorted(rows, key=lambda r: r["auc_rank"]):
        paper = (
            f"{r['paper_auc']:>10.4f} {r['paper_auc_rank']:>5d}"
            if np.isfinite(r["paper_auc"])
            else f"{'-':>10} {'-':>5}"
        )
        out.append(
            f"{r['label']:<11} {_pm(r['auc_mean'], r['auc_std'], '.4f'):>17} {r['auc_rank']:>5d} {paper}"
        )
    return "\n".join(out)


# ---------------------------------------------------------------- writing
def _config_dict(cfg: MonteCarloConfig) -> dict:
    return asdict(cfg)


def write_results(results: MonteCarloResult, out_dir) -> dict:
    """Write the study to ``out_dir`` (created): ``runs.parquet`` (every run's best point),
    ``tables.parquet`` (Tables 1-6 and 13 with the paper's values), ``roc.parquet`` (the averaged ROC
    curves), ``roc_best8.png`` (Figure 9: the eight best by AUC, complete and zoomed),
    ``roc_table<k>.png`` (one per table), and ``results.json`` (seed, runs, configuration) last: a
    folder without it is incomplete. Each file is written to a temporary name and renamed. Returns
    {name: path}."""
    import json

    import pyarrow as pa

    from flightmode.atomic import write_parquet, write_with

    out = os.fspath(out_dir)
    os.makedirs(out, exist_ok=True)
    paths = {}
    meta_path = os.path.join(out, "results.json")
    if os.path.exists(meta_path):
        os.remove(meta_path)  # incomplete until rewritten last
    rows = summary(results)
    tables = {
        "runs": pa.Table.from_pylist(list(results.rows)),
        "tables": pa.Table.from_pylist(rows),
        "roc": pa.Table.from_pylist(
            [
                {
                    "detector": k[0],
                    "signal": k[1],
                    "label": label(*k),
                    "fpr": float(f),
                    "tpr_mean": float(m),
                    "tpr_std": float(s) if np.isfinite(s) else None,
                }
                for k, v in results.roc_tpr.items()
                for f, m, s in zip(
                    results.roc_fpr,
                    v.mean(axis=0),
                    v.std(axis=0, ddof=1) if v.shape[0] > 1 else np.full(v.shape[1], np.nan),
                )
            ]
        ),
    }
    for name, table in tables.items():
        p = os.path.join(out, f"{name}.parquet")
        write_parquet(table, p)  # zstd, page checksums
        paths[name] = p
    best8 = [(r["detector"], r["signal"]) for r in sorted(rows, key=lambda r: r["auc_rank"])[:8]]
    figures = {"roc_best8": (best8, "The eight best by mean AUC (cf. seed 001, Figure 9)")}
    for t in sorted({r["table"] for r in rows}):
        figures[f"roc_table{t}"] = (
            [(r["detector"], r["signal"]) for r in rows if r["table"] == t],
            f"Table {t} cases",
        )
    for name, (cases, title) in figures.items():
        p = os.path.join(out, f"{name}.png")
        # mypy cannot infer the type of a lambda with default arguments (python/mypy#12557)
        write_with(p, lambda tmp, c=cases, ti=title: _roc_figure(results, c, ti, tmp), mkdir=False)  # type: ignore[misc]
        paths[name] = p
    meta = {
        "seed": results.seed,
        "n_runs": results.n_runs,
        "config": _config_dict(results.config),
        "source": "seed 001 section 3.1 (flightmode.detector.activity.montecarlo)",
    }
    write_with(meta_path, lambda tmp: _write_text(tmp, json.dumps(meta, indent=2, default=list)), mkdir=False)
    paths["results"] = meta_path
    return paths


def _write_text(path: str | os.PathLike, text: str) -> None:
    with open(path, "w") as f:
        f.write(text)


def _roc_figure(results: MonteCarloResult, cases, title: str, path: str | os.PathLike) -> None:
    """Averaged ROC curves of ``cases``: complete (left) and zoomed to FPR <= 0.2, TPR >= 0.8 (right)."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure

    fig = Figure(figsize=(11, 4.8))
    FigureCanvasAgg(fig)
    axes = fig.subplots(1, 2)
    for k in cases:
        tpr = results.roc_tpr[k].mean(axis=0)
        a = float(np.mean([r["auc"] for r in results.rows if (r["detector"], r["signal"]) == k]))
        for ax in axes:
            ax.plot(results.roc_fpr, tpr, label=f"{label(*k)} (AUC {a:.3f})")
    for ax, (lo, hi) in zip(axes, ((0.0, 1.0), (0.8, 1.0))):
        ax.plot([0, 1], [0, 1], color="0.7", lw=0.8, ls="--")
        ax.set_xlabel("false positive rate")
        ax.set_ylabel("true positive rate")
        ax.set_xlim(0.0, 1.0 - lo if lo else 1.0)
        ax.set_ylim(lo, hi)
        ax.grid(alpha=0.3)
    axes[1].set_xlim(0.0, 0.2)
    axes[0].legend(fontsize=7, loc="lower right")
    fig.suptitle(f"{title}: {results.n_runs} synthesized runs, seed {results.seed}")
    fig.tight_layout()
    fig.savefig(path, format="png", dpi=110)


__all__ = [
    "PAPER_NOTES",
    "PAPER_TABLES",
    "Grid",
    "GridBest",
    "MonteCarloConfig",
    "MonteCarloResult",
    "PaperRow",
    "Sweep",
    "auc",
    "evaluate_run",
    "exact_thresholds",
    "format_tables",
    "grid_search",
    "label",
    "paper_row",
    "roc_curve",
    "roc_on_grid",
    "run_montecarlo",
    "summary",
    "sweep",
    "write_results",
]
