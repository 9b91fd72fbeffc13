"""Confidence bounds for a certification claim on a rate of rare events (false statics per flight-hour).

Events in flight-hours are counted as a Poisson process; the exact (Garwood 1936, "Fiducial limits
for the Poisson distribution", Biometrika 28) one-sided upper bound at confidence ``c`` on the rate,
after ``x`` events in ``T`` hours, is ``chi2.ppf(c, 2 (x + 1)) / (2 T)``, the Poisson counterpart of
Clopper-Pearson's binomial bound. With no event it is ``-ln(1 - c) / T``: at 95 %, 3.0 / T, the "rule
of three" (Hanley and Lippman-Hand 1983, JAMA 249). Per-check proportions (the detector's checks, a
binomial count) take Clopper-Pearson's exact bound (``scipy.stats.binomtest``).
"""

from __future__ import annotations

import math

import numpy as np

from flightmode.detector.moving_variance import DetectorError


def _check(confidence: float) -> None:
    if not 0.0 < confidence < 1.0:
        raise DetectorError(f"confidence {confidence!r}: must be strictly between 0 and 1 (e.g. 0.95)")


def rate_upper_bound(events: int, hours: float, confidence: float = 0.95) -> float:
    """Exact one-sided upper bound on an event rate per hour (Garwood)."""
    from scipy.stats import chi2

    _check(confidence)
    if events < 0 or not hours > 0:
        raise DetectorError(f"{events} events in {hours} h: need events >= 0 and hours > 0")
    return float(chi2.ppf(confidence, 2 * (events + 1)) / (2.0 * hours))


def hours_needed(target_rate_per_h: float, confidence: float = 0.95, events: int = 0) -> float:
    """Flight-hours in which ``events`` events (0 by default) bring the upper bound down to the target."""
    from scipy.stats import chi2

    _check(confidence)
    if not target_rate_per_h > 0:
        raise DetectorError(f"target rate {target_rate_per_h!r} per hour: must be > 0")
    return float(chi2.ppf(confidence, 2 * (events + 1)) / (2.0 * target_rate_per_h))


def proportion_upper_bound(k: int, n: int, confidence: float = 0.95) -> float:
    """Clopper-Pearson one-sided upper bound on a proportion (k of n checks)."""
    from scipy.stats import binomtest

    _check(confidence)
    if n <= 0:
        return math.nan
    return float(binomtest(k, n).proportion_ci(confidence_level=2 * confidence - 1, method="exact").high)


__all__ = ["rate_upper_bound", "hours_needed", "proportion_upper_bound"]


def rate_and_response(events: int, hours: float, responses, confidence: float = 0.95) -> dict:
    """A population's false statics and gate responses in the figures every table here prints: in-window
    hours, events, their rate and exact upper bound per flight-hour, response p50 / p95 / max (a NaN
    response, nothing to answer, is left out; inf, never answered, counts as infinitely slow) and the
    number of flights never answered."""
    resp = np.asarray(responses, float)
    resp = resp[~np.isnan(resp)]
    return {
        "in_window_h": hours,
        "false_statics": events,
        "rate_per_h": events / hours if hours > 0 else math.nan,
        "rate_upper_per_h": rate_upper_bound(events, hours, confidence) if hours > 0 else math.nan,
        "response_p50_s": float(np.percentile(resp, 50, method="higher")) if resp.size else math.nan,
        "response_p95_s": float(np.percentile(resp, 95, method="higher")) if resp.size else math.nan,
        "response_max_s": float(resp.max()) if resp.size else math.nan,
        "no_response": int(np.isinf(resp).sum()),
    }
