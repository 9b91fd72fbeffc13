"""A grid of detector parameters over one labelled stream, each moving variance computed once.

The moving variance depends on the method, its weight and the window, not on the amplitude threshold
``k`` (eq. 7 compares it with ``k sigma^2``) nor on the time threshold (eq. 8 counts checks in a row).
So :func:`evaluate_grid` runs the detector once per (method, weight, window), then for every ``k``
one comparison and for every time threshold one run-length pass (:func:`final_static`), and scores
each point with :func:`~flightmode.detector.evaluation.score`. Its decisions are exactly
:func:`~flightmode.detector.flight_mode.detect`'s for the same parameters (the EMV's start value,
``emv_initial_k sigma^2``, does not depend on ``k`` either).
"""

from __future__ import annotations

import dataclasses
import itertools
from collections.abc import Callable, Iterator
from dataclasses import dataclass

import numpy as np

from flightmode.detector.evaluation import Evaluation, score
from flightmode.detector.flight_mode import DetectorParams, detect, final_static
from flightmode.detector.moving_variance import DetectorError

# the kinds of registered detector (flightmode.detectors entry points, detector/builtin.py) whose grid
# a sweep evaluates on its fast path: seed 000's moving variance, the redundant rule, seed 001's
GRID_KINDS = ("moving_variance", "redundant", "activity")


def grid_kind(name: str) -> str | None:
    """The registered detector ``name``'s kind when the grid can sweep it, else None."""
    from flightmode.detector import interface

    if ":" in name:
        return None  # a module path is a detector of the interface (--detector), not a grid method
    try:
        loaded = interface.load(name)
    except DetectorError:
        return None
    kind = getattr(loaded.factory, "kind", None)
    return kind if kind in GRID_KINDS else None


@dataclass(frozen=True, slots=True)
class Grid:
    """The axes of a sweep: (method, weight) pairs, windows (s), k, time thresholds (s)."""

    methods: tuple[tuple[str, float], ...] = (("nmv", 1.0),)
    windows_s: tuple[float, ...] = (1.0,)
    ks: tuple[float, ...] = (4.0,)
    time_thresholds_s: tuple[float, ...] = (4.0,)

    def __len__(self) -> int:
        return len(self.methods) * len(self.windows_s) * len(self.ks) * len(self.time_thresholds_s)

    def validate(self, fs_hz: float) -> None:
        """Every axis non-empty and every value usable at ``fs_hz``; a DetectorError naming the axis."""
        self.check_axes()
        for w in self.windows_s:
            DetectorParams(fs_hz=fs_hz, window_s=w).validate()  # a window of >= 2 samples

    def check_axes(self) -> None:
        """What can be checked before the stream's rate is known (every check of :meth:`validate` but
        the window's length in samples)."""
        for name, axis in (
            ("--method", self.methods),
            ("--window-s", self.windows_s),
            ("--k", self.ks),
            ("--time-threshold-s", self.time_thresholds_s),
        ):
            if not axis:
                raise DetectorError(f"{name}: the grid axis is empty; give at least one value")
            if len(set(axis)) != len(axis):  # a point twice would count its flights' hours twice
                raise DetectorError(f"{name}: a value is given twice; give each once")
        from flightmode.detector.activity import registry

        for method, weight in self.methods:
            name, _, signal = method.partition(":")
            kind = grid_kind(name)  # the registry says which names the grid sweeps
            if kind is None or (signal and kind != "activity"):
                from flightmode.detector.interface import names as registered
                from flightmode.errors import did_you_mean

                raise DetectorError(
                    f"--method {method!r}: use nmv, emv, nmv+baro, emv+baro or one of seed 001's detectors "
                    f"({', '.join(registry.NAMES)}, a flexible one with :acc, :gyr, :sum or "
                    f":product){did_you_mean(name, tuple(n for n in registered() if grid_kind(n)))}"
                )
            if signal:
                d = registry.get(name)
                if signal not in d.signals:
                    raise DetectorError(
                        f"--method {method!r}: {d.title} takes no input choice"
                        if not d.signals
                        else f"--method {method!r}: {name} takes {', '.join(d.signals)}"
                    )
            if not weight > 0:
                raise DetectorError(f"--weight {weight!r}: an EMV weighting factor must be > 0")
        for w in self.windows_s:
            if not w > 0:
                raise DetectorError(f"--window-s {w!r}: a window must be > 0 s")
        for k in self.ks:
            if not k > 0:
                raise DetectorError(f"--k {k!r}: the threshold k sigma^2 needs k > 0")
        for t in self.time_thresholds_s:
            if not t > 0:
                raise DetectorError(f"--time-threshold-s {t!r}: must be > 0")

    def points(self, fs_hz: float) -> Iterator[DetectorParams]:
        for (m, wt), w, k, t in itertools.product(
            self.methods, self.windows_s, self.ks, self.time_thresholds_s
        ):
            yield DetectorParams(fs_hz=fs_hz, window_s=w, k_sigma=k, time_threshold_s=t, method=m, weight=wt)


def parse_axis(text: str, option: str) -> tuple[float, ...]:
    """One grid axis written as ``2,3,4`` or ``start:stop:step`` (stop included) as floats; a
    DetectorError naming ``option`` (the command-line option, e.g. ``--k``) for anything else."""
    try:
        if ":" in text:
            a, b, c = (float(x) for x in text.split(":"))
            if not c > 0 or b < a:
                raise ValueError
            return tuple(round(float(v), 10) for v in np.arange(a, b + c / 2, c))
        return tuple(float(x) for x in text.split(",") if x.strip())
    except ValueError:
        raise DetectorError(f"{option} {text!r}: give values as 2,3,4 or a range start:stop:step") from None


def grid_of(
    methods: str | tuple[str, ...],
    weights: tuple[float, ...] = (1.0,),
    windows_s: tuple[float, ...] = (1.0,),
    ks: tuple[float, ...] = (4.0,),
    time_thresholds_s: tuple[float, ...] = (4.0,),
) -> Grid:
    """The grid of a sweep request: every EMV method (``emv``, ``emv+baro``) paired with each weight
    of ``weights``, every other method with weight 1 (its weight is unused); ``methods`` a tuple or a
    comma list (``nmv,emv``). Checks the axes (:meth:`Grid.check_axes`)."""
    if isinstance(methods, str):
        methods = tuple(m.strip() for m in methods.split(",") if m.strip())
    pairs = tuple((m, w) for m in methods for w in (weights if m in ("emv", "emv+baro") else (1.0,)))
    grid = Grid(pairs, tuple(windows_s), tuple(ks), tuple(time_thresholds_s))
    grid.check_axes()
    return grid


def grid_from_text(method: str, weight: str, window_s: str, k: str, time_threshold_s: str) -> Grid:
    """:func:`grid_of` from the command line's text axes (:func:`parse_axis`), e.g.
    ``grid_from_text("nmv,emv", "5", "0.5,1,2", "2:8:0.5", "1:8:1")``, the default 624-point grid."""
    return grid_of(
        method,
        parse_axis(weight, "--weight"),
        parse_axis(window_s, "--window-s"),
        parse_axis(k, "--k"),
        parse_axis(time_threshold_s, "--time-threshold-s"),
    )


def evaluate_grid(
    t_s: np.ndarray,
    acc_g: np.ndarray,
    labels: dict,
    grid: Grid,
    fs_hz: float,
    sigma2_of: Callable[[int], np.ndarray],
    gate: Callable[[np.ndarray], np.ndarray] | None = None,
) -> Iterator[tuple[DetectorParams, Evaluation]]:
    """(parameters, evaluation) for every point of ``grid`` over one stream. ``sigma2_of(window)``:
    sigma^2 per axis for a window of that many samples (a calibration depends on the window).
    ``gate(check_times)``: another source's "at rest" per check, ANDed with the final static (the
    redundant rule: :func:`flightmode.detector.pressure.static_at`)."""
    grid.validate(fs_hz)
    sigma2_by_window: dict[int, np.ndarray] = {}  # a calibration depends on the window, not the method
    for (method, weight), w in itertools.product(grid.methods, grid.windows_s):
        base = DetectorParams(
            fs_hz=fs_hz,
            window_s=w,
            k_sigma=grid.ks[0],
            time_threshold_s=grid.time_thresholds_s[0],
            method=method,
            weight=weight,
        )
        if base.window not in sigma2_by_window:
            sigma2_by_window[base.window] = np.asarray(sigma2_of(base.window), float)
        sigma2 = sigma2_by_window[base.window]
        checks = detect(t_s, acc_g, base, sigma2)  # the moving variance, once
        allowed = None if gate is None else np.asarray(gate(checks.t_s), bool)
        for k in grid.ks:
            temp = np.all(checks.mv < k * sigma2, axis=1)  # eq. 7 (as FlightModeDetector: k_sigma * sigma2)
            for tth in grid.time_thresholds_s:
                p = dataclasses.replace(base, k_sigma=k, time_threshold_s=tth)
                fin = final_static(temp, checks.after_reset, p.checks_needed)  # eq. 8
                if allowed is not None:
                    fin = fin & allowed
                c = dataclasses.replace(checks, temporary_static=temp, final_static=fin)
                yield p, score(c, t_s, labels, p, sigma2)


__all__ = ["Grid", "evaluate_grid", "grid_of", "grid_from_text", "parse_axis", "GRID_KINDS", "grid_kind"]
