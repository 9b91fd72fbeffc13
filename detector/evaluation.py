"""The detector against the truth labels of a Recording (seed 000 sections 5.1.2, 5.3, 6 and 7.1).

Inputs are plain arrays (time, acceleration in g, and the per-sample labels ``in_flight_window``,
``sensor_static`` and ``phase``), so a Recording in memory and a ``samples.parquet`` read back give
the same figures. A *check* is judged at its closing sample (``Checks.index``): its truth is the
label of that sample.

- **False-static events**: runs of consecutive final-static checks inside the in-flight window
  (pushback to engines off), each with its start time, duration (checks x W_s) and phase.
- **Missed static**: outside the window, checks where the bag is truly static but the detector does
  not (yet) allow transmission, in seconds. It includes the unavoidable ``T_th`` delay after every
  put-down.
- **Response time**: from the first truly static sample after the in-flight window ends (the bag
  set down at arrival, or a parcel in the hold after engines off) to the first final static at or
  after it.
- **Accuracy and correlation**: per check, final static against ``sensor_static`` (fraction equal,
  and Pearson's coefficient of the two 0/1 series, the phi coefficient).
- **P_FA tables** (Tables 4-5 form, eq. 14): over the in-flight window's checks, P_FA^x, ^y, ^z =
  fraction of checks whose MV on that axis is below T_sigma; P_FA^t their product (the paper's
  independence assumption, checked against the joint fraction, shown beside it); P_FA =
  (P_FA^t)^(T_th / W_s); and, with no independence assumption, the observed fraction of in-window
  checks declared final static by the detector itself.
- **MV average against window size** on truly static data (Table 3 form).
- **Response from turn-on** on static data (section 7.1, Fig. 18): NMV and EMV started from
  ``emv_initial_k sigma^2``.
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass
from typing import cast

import numpy as np

from flightmode.detector.flight_mode import Checks, DetectorParams, axis_thresholds, detect, final_static
from flightmode.detector.moving_variance import moving_variance
from flightmode.errors import DetectorError
from flightmode.intervals import true_runs


@dataclass(frozen=True, slots=True)
class Evaluation:
    params: DetectorParams
    sigma2: np.ndarray
    checks: Checks
    false_static_events: list[dict]  # {"t_s", "duration_s", "phase"}
    in_flight_checks: int
    missed_static_s: float
    response_s: float | None  # None: the bag never came to rest after the flight, or never detected
    accuracy: float
    correlation: float

    @property
    def false_static_count(self) -> int:
        return len(self.false_static_events)

    @property
    def false_static_s(self) -> float:
        return float(sum(e["duration_s"] for e in self.false_static_events))

    def summary(self) -> dict:
        return {
            "method": self.params.method,
            "window_s": self.params.window_s,
            "k_sigma": self.params.k_sigma,
            "time_threshold_s": self.params.time_threshold_s,
            "weight": self.params.weight,
            "sigma2_g2": self.sigma2.tolist(),
            "checks": int(self.checks.t_s.shape[0]),
            "in_flight_checks": self.in_flight_checks,
            "false_static_events": self.false_static_events,
            "false_static_count": self.false_static_count,
            "false_static_s": self.false_static_s,
            "missed_static_s": self.missed_static_s,
            "response_s": self.response_s,
            "accuracy": self.accuracy,
            "correlation": self.correlation,
        }


def check_labels(t_s, labels: dict) -> None:
    """A DetectorError unless ``labels`` holds in_flight_window, sensor_static and phase, one row per
    sample of ``t_s``."""
    n = np.asarray(t_s).shape[0]
    for name in ("in_flight_window", "sensor_static", "phase"):
        if name not in labels:
            raise DetectorError(
                f"label '{name}' missing: scoring needs in_flight_window, sensor_static and phase"
            )
        if np.asarray(labels[name]).shape[0] != n:
            raise DetectorError(
                f"label '{name}' has {np.asarray(labels[name]).shape[0]} rows, the stream {n}"
            )


def evaluate(
    t_s: np.ndarray, acc_g: np.ndarray, labels: dict, params: DetectorParams, sigma2: np.ndarray
) -> Evaluation:
    """Run the detector over a labelled stream and score it (module docstring)."""
    check_labels(t_s, labels)
    return score(detect(t_s, acc_g, params, sigma2), t_s, labels, params, sigma2)


def score(c: Checks, t_s: np.ndarray, labels: dict, params: DetectorParams, sigma2: np.ndarray) -> Evaluation:
    """Score the detector's checks ``c`` over the stream against its labels (module docstring)."""
    window = np.asarray(labels["in_flight_window"], bool)
    static = np.asarray(labels["sensor_static"], bool)
    phase = np.asarray(labels["phase"], dtype=object)
    k = c.index
    in_w, truth = window[k], static[k]
    fin = c.final_static
    events = []
    for s, e in true_runs(fin & in_w):
        events.append(
            {"t_s": float(c.t_s[s]), "duration_s": (e - s) * params.window_s, "phase": str(phase[k[s]])}
        )
    missed = float(np.sum(truth & ~fin & ~in_w)) * params.window_s
    response = None
    if window.any():
        end = int(np.flatnonzero(window)[-1])
        after = np.flatnonzero(static[end:])
        if after.size:
            t_rest = float(t_s[end + after[0]])
            hit = np.flatnonzero(fin & (c.t_s >= t_rest))
            if hit.size:
                response = float(c.t_s[hit[0]] - t_rest)
    acc = float(np.mean(fin == truth)) if fin.size else math.nan
    corr = phi_coefficient(fin, truth)
    return Evaluation(
        params, np.asarray(sigma2, float), c, events, int(in_w.sum()), missed, response, acc, corr
    )


def phi_coefficient(a: np.ndarray, b: np.ndarray) -> float:
    """Pearson's coefficient of two 0/1 series (the phi coefficient); NaN when either is constant."""
    a, b = np.asarray(a, float), np.asarray(b, float)
    if a.size < 2 or a.std() == 0 or b.std() == 0:
        return math.nan  # undefined when either series is constant
    return float(np.corrcoef(a, b)[0, 1])


def pfa_table(
    t_s,
    acc_g,
    labels: dict,
    params: DetectorParams,
    sigma2,
    ks=(3.0, 4.0, 5.0),
    time_thresholds_s=(3.0, 4.0),
    checks: Checks | None = None,
) -> list[dict]:
    """Rows in the form of seed 000 Tables 4-5 (module docstring), one per (T_sigma, T_th). ``checks``:
    the detector already run over this stream with these parameters (``detect``), to count another
    window of the same stream without running it again."""
    check_labels(t_s, labels)
    window = np.asarray(labels["in_flight_window"], bool)
    # the moving variance does not depend on T_sigma or T_th: one pass, then eq. 7-8 per row
    c = detect(t_s, acc_g, params, sigma2) if checks is None else checks
    in_w = window[c.index]
    n = int(in_w.sum())
    rows = []
    for k in ks:
        # eq. 7 against k sigma_i^2 per axis, or eq. 12's common threshold (params.threshold)
        below_all = c.mv < axis_thresholds(dataclasses.replace(params, k_sigma=float(k)), sigma2)[None, :]
        temp = cast(np.ndarray, below_all.all(axis=1))  # eq. 7 (an array: below_all is 2-D)
        below = below_all[in_w]
        pa = below.mean(axis=0) if n else np.full(3, math.nan)
        pt = float(np.prod(pa))  # the paper's P_FA^t: the axes taken as independent
        for tth in time_thresholds_s:
            need = dataclasses.replace(params, time_threshold_s=float(tth)).checks_needed
            final = final_static(temp, c.after_reset, need)[in_w]  # eq. 8
            rows.append(
                {
                    "T_sigma": k,
                    "T_th_s": tth,
                    "checks": n,
                    "P_FA_x": float(pa[0]),
                    "P_FA_y": float(pa[1]),
                    "P_FA_z": float(pa[2]),
                    "P_FA_t": pt,
                    "P_FA_t_joint": float(below.all(axis=1).mean()) if n else math.nan,
                    "P_FA": pt ** (tth / params.window_s),  # eq. 14
                    "observed_final_static_rate": float(final.mean()) if n else math.nan,
                    "observed_final_static_checks": int(final.sum()),
                }
            )
    return rows


def mv_vs_window(
    t_s, acc_g, static: np.ndarray, params: DetectorParams, sigma2, windows_s=(0.5, 1.0, 2.0, 3.0)
) -> list[dict]:
    """Table 3 form: the mean NMV per axis over checks whose whole window is truly static."""
    static = np.asarray(static, bool)
    cs = np.concatenate([[0], np.cumsum(static)])
    rows = []
    for w in windows_s:
        p = dataclasses.replace(params, window_s=float(w), method="nmv")
        c = detect(t_s, acc_g, p, sigma2)
        n = p.window
        ok = (c.index + 1 >= n) & (cs[c.index + 1] - cs[np.maximum(c.index + 1 - n, 0)] == n)
        mv = c.mv[ok].mean(axis=0) if ok.any() else np.full(3, math.nan)
        rows.append(
            {"window_s": w, "checks": int(ok.sum()), "mv_g2": mv.tolist(), "mv_mean_g2": float(np.mean(mv))}
        )
    return rows


def turn_on_response(t_s, acc_g, params: DetectorParams, sigma2, weights=(1.0, 5.0, 10.0)) -> list[dict]:
    """Section 7.1 / Fig. 18: a fresh detector on static data; seconds to the first final static, and
    to the first MV below T_sigma on every axis, for NMV and EMV with each weight."""
    t = np.asarray(t_s, float)
    variants = [("nmv", 1.0)] + [("emv", float(w)) for w in weights]
    rows = []
    for method, w in variants:
        p = dataclasses.replace(params, method=method, weight=w)
        c = detect(t, acc_g, p, sigma2)
        first = np.flatnonzero(c.final_static)
        temp = np.flatnonzero(c.temporary_static)
        mv = moving_variance(
            np.asarray(acc_g, float), p.window, method, w, p.emv_initial_k * np.asarray(sigma2)
        )
        below = np.flatnonzero(np.all(mv < axis_thresholds(p, sigma2)[None, :], axis=1))
        rows.append(
            {
                "method": method,
                "weight": w,
                # the MV itself (every sample, not only at checks) first below T_sigma on all axes: the
                # curve of Fig. 18, where a larger EMV weight crosses sooner
                "mv_below_threshold_s": float(t[below[0]] - t[0] + 1.0 / p.fs_hz) if below.size else None,
                "first_temporary_static_s": float(c.t_s[temp[0]] - t[0] + 1.0 / p.fs_hz)
                if temp.size
                else None,
                "response_s": float(c.t_s[first[0]] - t[0] + 1.0 / p.fs_hz) if first.size else None,
            }
        )
    return rows


def longest_static_run(static: np.ndarray) -> tuple[int, int]:
    """[start, end) of the longest run of truly static samples (for Table 3 and turn-on response)."""
    runs = true_runs(static)
    if not runs:
        raise DetectorError("the stream has no truly static sample: calibrate or test on static data")
    return max(runs, key=lambda r: r[1] - r[0])
