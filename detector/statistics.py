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

Coloured noise (:func:`nmv_moments_acov`, :func:`pm_acov`): for a stationary Gaussian process with
autocovariance r(m) the MV is a quadratic form, MV = x^T C x / N with C = I - 1 1^T / N (the
centring projector), so its mean and variance follow from r(m) exactly and its distribution is a
weighted sum of chi-square(1) variables with weights the eigenvalues of C R C / N (R the Toeplitz
matrix of r). No stationary Gaussian noise fits seed 000's Tables 2 and 3 together (the spread
needs correlation, the flat Table 3 forbids it): sim.sensor.accelerometer's LIS302DL noise is white
with a wandering amplitude (:func:`nmv_moments_am` its moments, exact; :func:`pm_am` its P_M,
conditional on the amplitude a quadratic form as above, the amplitude sampled), fitted with these to
Table 2's spread (tests/sim/test_noise_colour.py).

Section 5.1.1's steps as functions: eq. 13 inverted (:func:`k_of_pm_gaussian`), the threshold of a
coloured or modulated noise (:func:`k_of_pm_acov`, :func:`k_of_pm_am`), and the last step, "if not
[P_FA below the maximum], then P_M is increased and a new MV threshold is computed"
(:func:`threshold_for_pfa`, any k(P_M) and P_FA(k) passed in).
"""

from __future__ import annotations

import math
from collections.abc import Callable

import numpy as np
from scipy.linalg import toeplitz
from scipy.optimize import brentq
from scipy.special import erfc
from scipy.stats import chi2, norm

from flightmode.errors import DetectorError
from flightmode.sim.sensor.accelerometer import noise_am_cov_a2


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
        rows.append(
            {
                "T_sigma": f"{k:g} sigma^2",
                "P_M_gaussian": pg,
                "P_M_exact": pe,
                "time_error_gaussian_s": window_s / pg if pg > 0 else np.inf,
                "time_error_exact_s": window_s / pe if pe > 0 else np.inf,
            }
        )
    return rows


def _centred_cov(acov: np.ndarray, n: int) -> np.ndarray:
    r = np.asarray(acov, float)
    if r.ndim != 1 or r.shape[0] < n:
        raise ValueError(f"autocovariance needs lags 0..{n - 1}, got shape {r.shape}")
    big_r = toeplitz(r[:n])
    c = np.eye(n) - 1.0 / n
    return c @ big_r @ c


def nmv_moments_acov(acov: np.ndarray, n: int) -> tuple[float, float]:
    """Mean and standard deviation of the N-sample NMV (1/N normalisation, seed 000 eq. 1) of a
    zero-mean stationary Gaussian process with autocovariance ``acov[m]`` (m = 0..N-1; the MV comes
    out in the units of ``acov``). With R_ij = r(i - j) and sums over i, j = 1..N:

        E[MV]   = r(0) - (1/N^2) sum_ij r(i-j)                      (the mean's share removed)
        var[MV] = 2 tr((C R)^2) / N^2
                = (2/N^2) [ sum_ij r(i-j)^2 - (2/N) sum_i (sum_j r(i-j))^2 + (1/N^2) (sum_ij r(i-j))^2 ]

    (a Gaussian quadratic form x^T A x has variance 2 tr(A R A R); C^2 = C). White noise, r = delta:
    (N-1)/N and sqrt(2 (N-1))/N, as :func:`nmv_moments`."""
    r = np.asarray(acov, float)[:n]
    big_r = toeplitz(r)
    s_all = big_r.sum()
    mean = r[0] - s_all / n**2
    var = 2.0 / n**2 * ((big_r**2).sum() - 2.0 / n * (big_r.sum(axis=1) ** 2).sum() + s_all**2 / n**2)
    return float(mean), math.sqrt(max(var, 0.0))


def _mv_weights(acov: np.ndarray, n: int) -> np.ndarray:
    """The weights l_j of MV = sum_j l_j chi2_1: the nonzero eigenvalues of C R C / N."""
    lam = np.linalg.eigvalsh(_centred_cov(acov, n)) / n
    return lam[lam > 1e-12 * lam.max()]  # drop the centring's zero eigenvalue


def pm_acov(threshold: float, acov: np.ndarray, n: int) -> float:
    """P(MV >= threshold) for the N-sample NMV of a stationary Gaussian process with
    autocovariance ``acov`` (threshold in its units; above the MV mean, P_M's side), MV being
    sum_j l_j chi2_1 (:func:`_mv_weights`). By Imhof's inversion of the characteristic function
    (J. P. Imhof, Biometrika 48, 1961, eq. 3.2):

        P(MV > t) = 1/2 + (1/pi) int_0^inf sin(theta(u)) / (u rho(u)) du,
        theta(u) = 1/2 sum_j atan(l_j u) - t u / 2,   rho(u) = prod_j (1 + l_j^2 u^2)^(1/4),

    numerically exact to the quadrature's ~1e-10 absolute error. Below 1e-8, where that error would
    show, the Lugannani-Rice saddlepoint formula (Butler, "Saddlepoint Approximations with
    Applications", 2007, eq. 1.21) takes over: for white noise it is within 0.02 % of the exact
    chi-square below 1e-8 (0.6 % at 1e-3 to 1e-6, tests/sim/test_noise_colour.py)."""
    lam = _mv_weights(acov, n)
    scale = float(lam.sum())  # work in units of the MV mean
    lam, t = lam / scale, threshold / scale
    if not t > 1.0 + 1e-6:
        raise ValueError(f"threshold {threshold:g} is not above the MV mean {scale:g}")

    def integrand(u):
        theta = 0.5 * np.arctan(lam * u).sum() - 0.5 * t * u
        return math.sin(theta) / (u * math.exp(0.25 * np.log1p((lam * u) ** 2).sum()))

    from scipy.integrate import quad

    p = 0.5 + quad(integrand, 0.0, np.inf, limit=2000, epsabs=1e-13, epsrel=1e-10)[0] / math.pi
    return p if p >= 1e-8 else pm_saddlepoint(lam, t)


def pm_saddlepoint(lam: np.ndarray, t: float) -> float:
    """Lugannani-Rice tail P(sum_j lam_j chi2_1 >= t), t above the mean sum(lam)."""
    lam = np.asarray(lam, float)

    def k1(s):  # K'(s); K(s) = -1/2 sum log(1 - 2 l s) is the cumulant generating function
        return float((lam / (1.0 - 2.0 * lam * s)).sum())

    hi = 1.0 / (2.0 * lam.max())
    s = brentq(lambda u: k1(u) - t, 0.0, hi * (1.0 - 1e-15), xtol=1e-16 * hi, rtol=1e-15)
    k0 = float(-0.5 * np.log1p(-2.0 * lam * s).sum())
    k2 = float((2.0 * lam**2 / (1.0 - 2.0 * lam * s) ** 2).sum())
    w = math.sqrt(2.0 * (s * t - k0))
    v = s * math.sqrt(k2)
    return float(norm.sf(w) + norm.pdf(w) * (1.0 / v - 1.0 / w))


def k_of_pm_gaussian(pm: float, mu: float = 1.0, sigma_mv: float = 0.14) -> float:
    """Seed 000 eq. (13) inverted: the threshold k (units of sigma^2) whose Gaussian P_M is ``pm``,
    k = mu + sigma_MV Phi^-1(1 - P_M); mu, sigma_MV: the static MV's mean and spread (sigma^2)."""
    if not 0.0 < pm < 1.0:
        raise DetectorError(f"P_M = {pm:g}: a probability in (0, 1)")
    return float(mu + sigma_mv * norm.isf(pm))


def k_of_pm_acov(pm: float, acov: np.ndarray, n: int) -> float:
    """The threshold k (units of acov[0], the noise variance sigma^2) with exact P(MV >= k sigma^2) =
    ``pm`` for the N-sample NMV of a Gaussian process with autocovariance ``acov`` (:func:`pm_acov`)."""
    if not 0.0 < pm < 0.5:
        raise DetectorError(f"P_M = {pm:g}: the exact threshold needs 0 < P_M < 0.5 (above the MV mean)")
    s2 = float(np.asarray(acov, float)[0])
    mean = float(_mv_weights(acov, n).sum())
    lo, hi = mean * (1.0 + 1e-5), mean
    while pm_acov(hi * 2.0, acov, n) > pm:
        hi *= 2.0
    hi *= 2.0
    f = lambda t: math.log(pm_acov(t, acov, n)) - math.log(pm)  # noqa: E731
    return float(brentq(f, lo, hi, xtol=1e-9 * mean)) / s2


def threshold_for_pfa(
    k_of_pm: Callable[[float], float],
    pfa_of_k: Callable[[float], float],
    pm_start: float,
    pfa_max: float,
    pm_step: float = 10.0,
    pm_max: float = 0.5,
) -> dict:
    """Seed 000 section 5.1.1's loop: set P_M, compute the MV threshold k(P_M) (step 4), derive the
    P_FA it gives and, "if not [below the maximum value], then P_M is increased and a new MV
    threshold is computed", until P_FA <= ``pfa_max`` or P_M would pass ``pm_max``.

    ``k_of_pm``: P_M -> k (e.g. :func:`k_of_pm_gaussian`, :func:`k_of_pm_acov`, or an empirical
    survival function inverted); ``pfa_of_k``: k -> P_FA (eq. 14 on a flight's dynamic checks, e.g.
    from :func:`flightmode.detector.evaluation.pfa_table`). P_M grows by ``pm_step`` each round (the
    paper gives no step; a decade per round is Table 2's grain). Returns {"met", "pm", "k", "pfa",
    "steps": [{"pm", "k", "pfa"}, ...]}; when not met, the last step tried (the lowest k)."""
    if not 0.0 < pm_start < pm_max < 1.0:
        raise DetectorError(f"P_M start {pm_start:g} and maximum {pm_max:g}: need 0 < start < max < 1")
    if not pm_step > 1.0:
        raise DetectorError(f"P_M step {pm_step:g}: must be > 1 (P_M is increased each round)")
    steps = []
    i = 0
    while True:
        pm = pm_start * pm_step**i
        k = float(k_of_pm(pm))
        pfa = float(pfa_of_k(k))
        steps.append({"pm": pm, "k": k, "pfa": pfa})
        if pfa <= pfa_max or pm * pm_step > pm_max:
            return {"met": pfa <= pfa_max, "pm": pm, "k": k, "pfa": pfa, "steps": steps}
        i += 1


def nmv_moments_am(n: int, depth: float, phi: float) -> tuple[float, float]:
    """Mean and standard deviation of the N-sample NMV (1/N, seed 000 eq. 1) of amplitude-modulated
    white noise x_k = a_k w_k (w white, unit variance; a as :func:`noise_am_cov_a2`, E[a^2] = 1), in units
    of its variance. With Q = x^T C x = N MV and c(m) = cov(a_j^2, a_{j+m}^2):

        E[Q]   = N - 1                                  (the carrier is white: any modulation)
        var[Q] = 2 sum_jk C_jk^2 (1 + c(j-k)) + (1 - 1/N)^2 sum_jk c(j-k),

    the first term E[var(Q | a)] = E[2 tr((C A^2)^2)], the second var(E[Q | a]) = var(tr(C A^2)).
    depth 0 gives :func:`nmv_moments`."""
    c = noise_am_cov_a2(depth, phi, n)
    lags = np.arange(n)
    mult = np.where(lags == 0, n, 2 * (n - lags)).astype(float)  # pairs (j, k) at |j - k| = m
    sum_c = float((mult * c).sum())
    diag = (1.0 - 1.0 / n) ** 2
    off = 1.0 / n**2
    # sum_jk C_jk^2 (1 + c): the diagonal (m = 0) carries (1 - 1/N)^2, every other pair 1/N^2
    first = n * diag * (1.0 + c[0]) + off * float((mult[1:] * (1.0 + c[1:])).sum())
    var_q = 2.0 * first + diag * sum_c
    return (n - 1) / n, math.sqrt(var_q) / n


def nmv_lag1_am(n: int, depth: float, phi: float) -> float:
    """Correlation of two consecutive non-overlapping N-sample NMVs of amplitude-modulated white
    noise (:func:`nmv_moments_am`): given the amplitude the two windows' carriers are independent,
    so cov(Q1, Q2) = cov(E[Q1 | a], E[Q2 | a]) = (1 - 1/N)^2 sum_{j in 1, k in 2} c(k - j), the pairs
    at lag m across the boundary numbering min(m, 2N - m)."""
    c = noise_am_cov_a2(depth, phi, 2 * n)
    m = np.arange(1, 2 * n)
    cross = float((c[1:] * np.minimum(m, 2 * n - m)).sum())
    sd = nmv_moments_am(n, depth, phi)[1] * n
    return (1.0 - 1.0 / n) ** 2 * cross / sd**2


def am_depth_for_spread(spread: float, n: int, phi: float) -> float:
    """The modulation depth whose N-sample NMV has the relative spread ``spread`` (sigma_MV / E[MV],
    :func:`nmv_moments_am`); at least white noise's sqrt(2 / (N - 1))."""
    white = nmv_moments(n)[1] / nmv_moments(n)[0]
    if spread <= white:
        raise DetectorError(f"spread {spread:g} is below white noise's {white:.3f}")

    def f(d):
        m, s = nmv_moments_am(n, d, phi)
        return s / m - spread

    hi = 1.0
    while f(hi) < 0:
        hi *= 2.0
        if hi > 1e3:
            raise DetectorError(f"spread {spread:g}: no modulation depth reaches it at phi {phi:g}")
    return float(brentq(f, 0.0, hi, xtol=1e-12))


def am_paths(n: int, depth: float, phi: float, paths: int, rng: np.random.Generator) -> np.ndarray:
    """``paths`` stationary amplitude sequences of length n, (paths, n), as the sensor draws them
    (:mod:`flightmode.sim.sensor.accelerometer`): g[0] ~ N(0, 1), g[k] = phi g[k-1] +
    sqrt(1 - phi^2) e[k], a = (1 + depth g) / sqrt(1 + depth^2)."""
    return (1.0 + depth * _ar1_paths(n, phi, paths, rng)) / math.sqrt(1.0 + depth**2)


def _ar1_paths(n: int, phi: float, paths: int, rng: np.random.Generator) -> np.ndarray:
    from scipy.signal import lfilter

    g0 = rng.standard_normal((paths, 1))
    e = rng.standard_normal((paths, n - 1)) * math.sqrt(1.0 - phi**2)
    return np.concatenate([g0, lfilter([1.0], [1.0, -phi], e, axis=1, zi=phi * g0)[0]], axis=1)


def _saddlepoint_rows(lam: np.ndarray, t: float) -> np.ndarray:
    """Lugannani-Rice P(sum_j lam_ij chi2_1 >= t) for every row i of ``lam`` (all weights > 0):
    :func:`pm_saddlepoint` vectorised, the saddlepoint found by bisection on every row at once (K' is
    increasing on (-inf, 1 / (2 max lam)); a t below a row's mean puts its saddlepoint below 0)."""
    lam = np.asarray(lam, float)
    hi = 0.5 / lam.max(axis=1) * (1.0 - 1e-13)
    lo = np.full(lam.shape[0], -lam.shape[1] / t)  # K'(lo) < (N - 1) / (2 |lo|) <= t / 2
    for _ in range(64):  # the bracket, under 1e3 wide, to 1e-16 (double precision's grain)
        mid = 0.5 * (lo + hi)
        below = (lam / (1.0 - 2.0 * lam * mid[:, None])).sum(axis=1) < t
        lo = np.where(below, mid, lo)
        hi = np.where(below, hi, mid)
    s = 0.5 * (lo + hi)
    one = 1.0 - 2.0 * lam * s[:, None]
    k0 = -0.5 * np.log(one).sum(axis=1)
    k2 = (2.0 * lam**2 / one**2).sum(axis=1)
    w = np.sign(s) * np.sqrt(np.maximum(2.0 * (s * t - k0), 0.0))
    v = s * np.sqrt(k2)
    near = np.abs(v) < 1e-6  # at the mean the formula is 0/0: its limit, 1/2 - K3 / (6 sqrt(2 pi) K2^1.5)
    with np.errstate(divide="ignore", invalid="ignore"):
        p = norm.sf(w) + norm.pdf(w) * (1.0 / v - 1.0 / w)
    if near.any():
        k3 = (8.0 * lam**3).sum(axis=1)
        p = np.where(near, 0.5 - k3 / (6.0 * math.sqrt(2.0 * math.pi) * k2**1.5), p)
    return np.clip(p, 0.0, 1.0)


# defensive mixture importance sampling (Hesterberg, Technometrics 37, 1995): the tail of the NMV
# comes from windows whose amplitude stays high, so paths are drawn in equal shares with g's mean
# shifted by each of these (units of its sd; 0 keeps the plain draw in the mixture)
AM_SHIFTS: tuple[float, ...] = (0.0, 1.0, 2.0, 3.0, 4.0, 5.0, 6.0)
_AM_WEIGHTS: dict = {}


def _am_weights(n: int, depth: float, phi: float, paths: int, seed: int) -> tuple[np.ndarray, np.ndarray]:
    """(conditional weights (paths, N - 1), likelihood ratios (paths,)) of :func:`pm_am`; the last
    four sets are kept (a threshold search calls pm_am with the same paths many times). The ratio of a
    path g is p(g) / sum_j (1/J) q_j(g), q_j the AR(1) law with mean ``AM_SHIFTS[j]``: for a
    stationary AR(1) of unit variance, log q_j/p = mu_j u - mu_j^2 c / 2 with u = 1' Sigma^-1 g and
    c = 1' Sigma^-1 1, Sigma^-1 tridiagonal (1' Sigma^-1 = (1 - phi) [1, 1 - phi, ..., 1 - phi, 1]
    / (1 - phi^2))."""
    key = (n, depth, phi, paths, seed)
    if key not in _AM_WEIGHTS:
        rng = np.random.default_rng(seed)
        mus = np.asarray(AM_SHIFTS)
        per = -(-paths // mus.size)
        g = np.concatenate([_ar1_paths(n, phi, per, rng) + mu for mu in mus])
        row = np.full(n, (1.0 - phi) ** 2)
        row[0] = row[-1] = 1.0 - phi
        row /= 1.0 - phi**2
        u, c = g @ row, float(row.sum())
        log_q_over_p = mus[None, :] * u[:, None] - 0.5 * mus[None, :] ** 2 * c
        ratio = 1.0 / np.exp(log_q_over_p).mean(axis=1)
        a = (1.0 + depth * g) / math.sqrt(1.0 + depth**2)
        cm = np.eye(n) - 1.0 / n
        lam = np.linalg.eigvalsh(a[:, :, None] * cm[None] * a[:, None, :])[:, 1:] / n
        if len(_AM_WEIGHTS) >= 4:
            _AM_WEIGHTS.pop(next(iter(_AM_WEIGHTS)))
        _AM_WEIGHTS[key] = (np.maximum(lam, 1e-300), ratio)  # the centring's zero eigenvalue dropped
    return _AM_WEIGHTS[key]


def pm_am(
    k: float, n: int, depth: float, phi: float, paths: int = 4096, seed: int = 0
) -> tuple[float, float]:
    """P(MV >= k sigma^2) for the N-sample NMV of amplitude-modulated white noise (units of its
    variance sigma^2) and the standard error of that estimate: (P_M, SE). Conditional on an
    amplitude path a, the NMV is a Gaussian quadratic form, sum_j l_j chi2_1 with l the nonzero
    eigenvalues of A C A / N (A = diag(a)); its tail is the Lugannani-Rice saddlepoint
    (:func:`pm_saddlepoint`), averaged over ``paths`` amplitude paths drawn from ``seed``
    (Rao-Blackwellised Monte Carlo: the carrier's randomness is integrated exactly, only the
    modulation's is sampled, with the mixture importance sampling of ``AM_SHIFTS``). The same seed
    gives the same paths at every k, so k -> P_M is smooth (:func:`k_of_pm_am`). Depth 0 is white
    noise: :func:`pm_exact`, SE 0."""
    if depth == 0:
        return pm_exact(k, n), 0.0
    lam, ratio = _am_weights(n, depth, phi, paths, seed)
    p = _saddlepoint_rows(lam, k) * ratio
    return float(p.mean()), float(p.std(ddof=1) / math.sqrt(p.size))


def k_of_pm_am(pm: float, n: int, depth: float, phi: float, paths: int = 4096, seed: int = 0) -> float:
    """The threshold k (units of sigma^2) with P(MV >= k sigma^2) = ``pm`` (:func:`pm_am`, its paths
    fixed by ``seed``)."""
    if not 0.0 < pm < 0.5:
        raise DetectorError(f"P_M = {pm:g}: the threshold needs 0 < P_M < 0.5 (above the MV mean)")

    def f(k):
        return math.log(max(pm_am(k, n, depth, phi, paths, seed)[0], 1e-300)) - math.log(pm)

    lo, hi = 1.0, 2.0
    while f(hi) > 0:
        lo, hi = hi, hi * 2.0
    return float(brentq(f, lo, hi, xtol=1e-9))
