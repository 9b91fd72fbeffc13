"""Detector statistics from seed 000 section 5.1: the probability of misdetection P_M of one
moving-variance check on a static sensor (eq. 13, Table 2).

Two models of the static MV distribution, side by side:

- the paper's Gaussian approximation (eq. 13): P_M = 1/2 (1 - erf((T - mu) / sqrt(2 sigma_MV^2)));
  with white Gaussian noise of variance sigma^2 and an NMV over N samples (1/N normalisation),
  mu = (N - 1)/N sigma^2 and sigma_MV = sigma^2 sqrt(2 (N - 1)) / N;
- the exact distribution: N MV / sigma^2 is chi-square with N - 1 degrees of freedom, so
  P_M = P(chi2_{N-1} >= N k), for T = k sigma^2.

TimeError = W_s / P_M: the mean time between two misdetections when a check is made every W_s.

Finding (see tests/detector/test_statistics.py): seed 000's Table 2 (P_M 6e-3, 8e-6, 2e-11, 6e-19 at
2, 2.5, 3, 4 sigma^2) is not reproducible from N = 100 white samples: at 2 sigma^2 the Gaussian
model gives 4e-13 and the exact chi-square 8e-9 (the chi-square's heavier right tail). The paper's rows imply an MV spread sigma_MV of 0.30-0.40 sigma^2, i.e. only
12-23 effectively independent samples per 1-s window. That suggests its 100 Hz stream was not white:
it was oversampled or filtered from a slower source. The rows also disagree with one another (no
single sigma_MV gives all four).
"""

from __future__ import annotations

import math

import numpy as np
from scipy.special import erfc
from scipy.stats import chi2, norm


def nmv_moments(n: int) -> tuple[float, float]:
    """Mean and standard deviation of an N-sample NMV of unit-variance white Gaussian noise."""
    return (n - 1) / n, math.sqrt(2.0 * (n - 1)) / n


def pm_gaussian(k: float, n: int, sigma_mv: float | None = None, mu: float | None = None) -> float:
    """Seed 000 eq. 13 with T = k sigma^2 (all in units of sigma^2). ``sigma_mv`` and ``mu``
    default to the white-noise values of :func:`nmv_moments`."""
    m, s = nmv_moments(n)
    mu = m if mu is None else mu
    s = s if sigma_mv is None else sigma_mv
    return 0.5 * float(erfc((k - mu) / (math.sqrt(2.0) * s)))  # = 1/2 (1 - erf(...))


def pm_exact(k: float, n: int) -> float:
    """P(MV >= k sigma^2) for white Gaussian noise: chi-square with N - 1 degrees of freedom."""
    return float(chi2.sf(n * k, n - 1))


def implied_sigma_mv(pm: float, k: float, mu: float = 1.0) -> float:
    """The MV spread (units of sigma^2) that makes eq. 13 give ``pm`` at T = k sigma^2."""
    return (k - mu) / float(norm.isf(pm))


def table2(ks=(2.0, 2.5, 3.0, 4.0, 5.0), window_s: float = 1.0, fs_hz: float = 100.0) -> list[dict]:
    """Rows in the form of seed 000 Table 2, both models."""
    n = int(round(window_s * fs_hz))
    rows = []
    for k in ks:
        pg, pe = pm_gaussian(k, n), pm_exact(k, n)
        rows.append({
            "T_sigma": f"{k:g} sigma^2",
            "P_M_gaussian": pg,
            "P_M_exact": pe,
            "time_error_gaussian_s": window_s / pg if pg > 0 else np.inf,
            "time_error_exact_s": window_s / pe if pe > 0 else np.inf,
        })
    return rows
