"""Duty-cycled flight-mode detection for bursty sensors: one decision per acceleration burst.

Seed 000's detector (section 5, eq. 6-9) checks the moving variance every ``W_s`` seconds of a
continuous stream; an e-obs tag (seed 003 section 4.1) records acceleration only in bursts: ``N``
samples per axis every ACC interval, the sensor asleep in between, which is what saves the battery
(seed 000 section 7.3: "a timer can periodically wake up the tracking module ... for limited time
duration"). Here each burst is one check:

    v_i = (1/N) sum_n (a_i(n) - mean_i)^2       seed 000 eq. (1), over the whole burst, axis i
    quiet  = AND_i  v_i < k sigma_i^2            seed 000 eq. (7) with T_sigma = k sigma^2 (eq. 12)
    final static = the last m bursts all quiet   seed 000 eq. (8), bursts in place of checks

``sigma_i^2`` is the static noise variance of axis i for the tag and its rate
(:func:`calibrate_sigma2_bursts`). One set of maths, two front ends: :func:`detect_bursts` (batch)
and :class:`BurstDetector` (streaming, ``push`` one burst at a time); they agree exactly. An optional
``max_gap_s`` resets eq. 8's run when bursts are further apart than that (a missing burst could hide
motion), as a time gap resets :class:`flightmode.detector.flight_mode.FlightModeDetector`.

Statistics (seed 000 section 5.1, white Gaussian noise): ``N v_i / sigma_i^2`` is chi-square with
``N - 1`` degrees of freedom, so per axis P(v_i >= k sigma^2) = :func:`~flightmode.detector.statistics.
pm_exact` (k, N); a burst of d independent axes is missed (declared moving while static) with

    P_M,burst = 1 - (1 - pm_exact(k, N))^d                          (section 5.1.1, exact chi-square)

and the threshold for a target P_M is k = chi2.isf(1 - (1 - P_M)^(1/d), N - 1) / N. With a per-burst
quiet probability q in motion, the final decision's false alarm is (section 5.1.2, eq. 14 with
T_th / W_s = m)

    P_tFA = prod_i q_i,        P_FA = q^m.

Fewer samples per burst widen the chi-square, so the same P_M needs a higher k (:func:`pm_table`):
the battery saved by short bursts is paid in a higher threshold, i.e. a higher q in motion.

:func:`tradeoff` gives samples per hour, mean current (given a charge per sample and a sleep
current, both the caller's: the seeds give no per-sample figure, only seed 000 section 7.3's power
bounds) and the response time against the burst interval and length. :func:`detect_movebank` runs the
detector over a Movebank e-obs file (seed 003 section 5.4), one run per individual.
"""

from __future__ import annotations

import math
import os
from collections.abc import Iterable, Mapping, Sequence
from dataclasses import dataclass

import numpy as np

from flightmode.detector.flight_mode import final_static
from flightmode.detector.statistics import pm_exact, pm_gaussian
from flightmode.errors import DetectorError, did_you_mean

# ------------------------------------------------------------------------------------ the decision


def _check_km(k: float, m: int) -> tuple[float, int]:
    if (
        isinstance(k, bool)
        or not isinstance(k, (int, float, np.integer, np.floating))
        or not (math.isfinite(k) and k > 0)
    ):
        raise DetectorError(f"k = {k!r}: the threshold k sigma^2 needs a finite k > 0 (seed 000 eq. 7, 12)")
    if isinstance(m, bool) or not isinstance(m, (int, np.integer)) or m < 1:
        raise DetectorError(
            f"m = {m!r}: the number of quiet bursts for final static must be an integer >= 1 (eq. 8)"
        )
    return float(k), int(m)


def _check_sigma2(sigma2) -> np.ndarray:
    s2 = np.asarray(sigma2, dtype=float)
    if s2.ndim != 1 or s2.size < 1 or not np.all(np.isfinite(s2)) or not np.all(s2 > 0):
        raise DetectorError(
            f"sigma^2 {np.asarray(sigma2).tolist()!r}: must be one finite variance > 0 (g^2) per axis"
        )
    return s2


def burst_variance(acc_g, n_axes: int | None = None, *, where: str = "burst") -> np.ndarray:
    """Per-axis NMV of one whole burst, seed 000 eq. (1): ``(1/N) sum (a - mean)^2``, shape (d,).

    acc_g: (N, d) samples in g, N >= 2; ``n_axes`` (from sigma^2) is checked when given."""
    a = np.asarray(acc_g, dtype=float)
    if a.ndim == 1:
        a = a[:, None]
    if a.ndim != 2:
        raise DetectorError(f"{where}: need samples of shape (N, axes), got shape {a.shape}")
    if a.shape[0] < 2:
        raise DetectorError(f"{where}: {a.shape[0]} sample(s) per axis; a variance needs >= 2")
    if n_axes is not None and a.shape[1] != n_axes:
        raise DetectorError(
            f"{where}: {a.shape[1]} axes where {n_axes} are expected (one sigma^2 per recorded axis)"
        )
    if not np.all(np.isfinite(a)):
        bad = np.argwhere(~np.isfinite(a))[0]
        raise DetectorError(
            f"{where}: sample {bad[0]} of axis {bad[1]} is {a[tuple(bad)]} (need finite values in g)"
        )
    d = a - a.mean(axis=0)
    return (d * d).mean(axis=0)  # eq. (1), two-pass (no cancellation against the 1 g mean)


def _gap_s(t_prev, t_next) -> np.ndarray:
    """t_next - t_prev in seconds, elementwise (floats in seconds, or ``datetime64``)."""
    d = np.asarray(t_next) - np.asarray(t_prev)
    if np.issubdtype(d.dtype, np.timedelta64):
        return (d / np.timedelta64(1, "ns")) * 1e-9
    return d.astype(float)


@dataclass(frozen=True, slots=True)
class BurstChecks:
    """One row per burst: its time (seconds or ``datetime64``), per-axis NMV (g^2), the decisions."""

    t: np.ndarray  # (B,)
    var_g2: np.ndarray  # (B, d)
    quiet: np.ndarray  # (B,) bool, eq. 7
    final_static: np.ndarray  # (B,) bool, eq. 8
    after_reset: np.ndarray  # (B,) bool: the first burst, or the first after a gap > max_gap_s


def _check_times(t: np.ndarray, max_gap_s: float | None) -> np.ndarray:
    if t.ndim != 1:
        raise DetectorError(f"burst times: need one time per burst, got shape {t.shape}")
    if t.size > 1 and not np.all(t[1:] > t[:-1]):
        i = int(np.flatnonzero(~(t[1:] > t[:-1]))[0]) + 1
        raise DetectorError(
            f"burst times: burst {i} (t = {t[i]}) is not after burst {i - 1} (t = {t[i - 1]})"
        )
    reset = np.zeros(t.shape[0], bool)
    if t.size:
        reset[0] = True
    if max_gap_s is not None and t.size > 1:
        reset[1:] = _gap_s(t[:-1], t[1:]) > max_gap_s
    return reset


def _check_gap(max_gap_s):
    if max_gap_s is not None and not (isinstance(max_gap_s, (int, float)) and max_gap_s > 0):
        raise DetectorError(f"max_gap_s = {max_gap_s!r}: must be None or a number of seconds > 0")


def detect_bursts(
    t, bursts_g: Iterable, sigma2, k: float, m: int, max_gap_s: float | None = None
) -> BurstChecks:
    """Batch front end: every burst's decision.

    t: (B,) burst times (seconds, or ``datetime64``), strictly increasing; bursts_g: B arrays (N_b, d)
    in g (N_b may differ between bursts); sigma2: (d,) g^2; k > 0; m >= 1 integer."""
    k, m = _check_km(k, m)
    _check_gap(max_gap_s)
    s2 = _check_sigma2(sigma2)
    t = np.asarray(t)
    bursts = list(bursts_g)
    if t.shape != (len(bursts),):
        raise DetectorError(f"burst times: {t.shape} for {len(bursts)} bursts; need one time per burst")
    reset = _check_times(t, max_gap_s)
    var = np.array([burst_variance(b, s2.size, where=f"burst {i}") for i, b in enumerate(bursts)]).reshape(
        -1, s2.size
    )
    quiet = np.all(var < k * s2, axis=1)  # eq. 7
    return BurstChecks(t, var, quiet, final_static(quiet, reset, m), reset)  # eq. 8


class BurstDetector:
    """Streaming front end: ``push(t, acc_g)`` one burst, get its row (a :class:`BurstChecks` of length 1)."""

    def __init__(self, sigma2, k: float, m: int, max_gap_s: float | None = None):
        self.k, self.m = _check_km(k, m)
        _check_gap(max_gap_s)
        self.sigma2 = _check_sigma2(sigma2)
        self.max_gap_s = max_gap_s
        self._t_last = None
        self._run = 0  # quiet bursts in a row so far (eq. 8's state)
        self._n = 0

    def push(self, t, acc_g) -> BurstChecks:
        var = burst_variance(acc_g, self.sigma2.size, where=f"burst {self._n}")
        t = np.asarray(t)
        if t.ndim != 0:
            raise DetectorError(f"burst {self._n}: one time per pushed burst, got shape {t.shape}")
        reset = self._t_last is None
        if not reset:
            if not t > self._t_last:
                raise DetectorError(
                    f"burst times: burst {self._n} (t = {t}) is not after burst {self._n - 1} (t = {self._t_last})"
                )
            reset = self.max_gap_s is not None and bool(_gap_s(self._t_last, t) > self.max_gap_s)
        if reset:
            self._run = 0
        quiet = bool(np.all(var < self.k * self.sigma2))  # eq. 7
        self._run = self._run + 1 if quiet else 0
        final = quiet and self._run >= self.m  # eq. 8
        self._t_last = t
        self._n += 1
        return BurstChecks(t[None], var[None, :], np.array([quiet]), np.array([final]), np.array([reset]))


# ------------------------------------------------------------------------------------- calibration

# the lowest decile of the bursts seeds the calibration: it is static as long as >= 10 % of the bursts are
CALIBRATION_FRACTION = 0.1
# a static burst is kept with at least this probability per axis (white noise)
CALIBRATION_KEEP_P = 0.999


def calibrate_sigma2_bursts(
    bursts_g: Sequence, *, fraction: float = CALIBRATION_FRACTION, lsb_g: float | None = None
) -> np.ndarray:
    """Per-axis static noise variance (g^2) from bursts of which at least ``fraction`` are static
    (seed 000 section 5.1 step (1): "measure the noise variance on each axis").

    1. Per burst and axis the unbiased variance s = N v / (N - 1) (v: eq. 1).
    2. Seed: s0_i = the median of the lowest ``ceil(fraction B)`` values of s_i (at least one). If
       the lowest decile is static, s0 lies between the static law's fraction/2 quantile (every burst
       static) and its median (only ``fraction`` static); the median of the decile, not its minimum,
       so one burst of stuck counts does not set it alone.
    3. Keep the bursts with s_i <= s0_i R on every axis, R = chi2.ppf(0.999, nu) / chi2.ppf(fraction/2, nu)
       (nu = N - 1 of the shortest burst): a static burst passes with probability >= 0.999 per axis
       even when s0 is at its lowest, while motion far above the noise is dropped.
    4. sigma_i^2 = sum N v_i / sum (N - 1) over the kept bursts: the pooled within-burst variance,
       unbiased for white noise (unlike the decile's median alone, which sits 0.70-1 sigma^2 for
       N = 60 depending on the unknown static share).

    Floored at ``lsb_g^2 / 12`` (quantisation noise) when given, else 1e-12 g^2: a tag whose counts
    do not move at rest would otherwise give sigma^2 = 0, a zero threshold, never a quiet burst.
    If fewer than ``fraction`` of the bursts are static the result is motion, not noise, and the
    thresholds k sigma^2 are too high: the calibration data must include rest."""
    from scipy.stats import chi2

    if not 0 < fraction <= 1:
        raise DetectorError(f"fraction = {fraction!r}: the calibration decile must be in (0, 1]")
    bursts = [np.asarray(b, float) for b in bursts_g]
    if not bursts:
        raise DetectorError("calibration: no bursts given; need at least one static burst")
    d = burst_variance(bursts[0], where="calibration burst 0").size
    v = np.array([burst_variance(b, d, where=f"calibration burst {i}") for i, b in enumerate(bursts)])
    n = np.array([b.shape[0] for b in bursts], float)
    s = v * (n / (n - 1.0))[:, None]
    low = max(1, math.ceil(fraction * len(bursts) - 1e-9))
    s0 = np.median(np.sort(s, axis=0)[:low], axis=0)
    nu = n.min() - 1.0
    ratio = chi2.ppf(CALIBRATION_KEEP_P, nu) / chi2.ppf(fraction / 2.0, nu)
    keep = np.all(s <= s0 * ratio, axis=1)
    if not keep.any():
        raise DetectorError(
            f"calibration: none of the {len(bursts)} bursts is near the quietest on every axis at once "
            f"(seed {np.array2string(s0, precision=3)} g^2): the bursts hold no rest; give sigma^2 measured at rest"
        )
    sigma2 = (n[keep, None] * v[keep]).sum(axis=0) / (n[keep] - 1.0).sum()
    floor = lsb_g**2 / 12.0 if lsb_g else 1e-12
    return np.maximum(sigma2, floor)


# ---------------------------------------------------------------------------------------- P_M, P_FA


def _check_n(n_samples) -> int:
    if isinstance(n_samples, bool) or not isinstance(n_samples, (int, np.integer)) or n_samples < 2:
        raise DetectorError(f"N = {n_samples!r} samples per axis: must be an integer >= 2")
    return int(n_samples)


def _check_axes(n_axes) -> int:
    if isinstance(n_axes, bool) or not isinstance(n_axes, (int, np.integer)) or not 1 <= n_axes <= 3:
        raise DetectorError(f"n_axes = {n_axes!r}: must be 1, 2 or 3")
    return int(n_axes)


def _check_p(p, what: str) -> float:
    if isinstance(p, bool) or not isinstance(p, (int, float, np.floating)) or not 0 < p < 1:
        raise DetectorError(f"{what} = {p!r}: a probability strictly between 0 and 1")
    return float(p)


def pm_burst(k: float, n_samples: int, n_axes: int = 2) -> float:
    """P_M of one burst on a static sensor: any of ``n_axes`` independent axes has v >= k sigma^2,
    1 - (1 - P(chi2_{N-1} >= N k))^d (seed 000 section 5.1.1, exact chi-square)."""
    k, _ = _check_km(k, 1)
    p = pm_exact(k, _check_n(n_samples))
    return float(-math.expm1(_check_axes(n_axes) * math.log1p(-p))) if p < 1 else 1.0


def pm_final(k: float, n_samples: int, m: int, n_axes: int = 2) -> float:
    """P_M of the final decision on a sensor static for m bursts: one of them not quiet, 1 - (1 - P_M,burst)^m."""
    p = pm_burst(k, n_samples, n_axes)
    _, m = _check_km(k, m)
    return float(-math.expm1(m * math.log1p(-p))) if p < 1 else 1.0


def k_for_pm(pm: float, n_samples: int, n_axes: int = 2) -> float:
    """The k whose burst P_M (:func:`pm_burst`) equals ``pm``: chi2.isf(1 - (1 - pm)^(1/d), N - 1) / N."""
    from scipy.stats import chi2

    pm = _check_p(pm, "target P_M")
    n = _check_n(n_samples)
    per_axis = -math.expm1(math.log1p(-pm) / _check_axes(n_axes))
    return float(chi2.isf(per_axis, n - 1) / n)


def pm_table(n_samples_list: Iterable[int], ks: Iterable[float], n_axes: int = 2) -> list[dict]:
    """Rows (N, k): P_M per axis and per burst (exact chi-square) and seed 000 eq. 13's Gaussian
    approximation per axis. At a fixed k > 1, P_M grows as N shrinks: fewer samples per decision need
    a higher k for the same P_M (see :func:`k_for_pm`)."""
    rows = []
    for n in n_samples_list:
        n = _check_n(n)
        for k in ks:
            k, _ = _check_km(k, 1)
            rows.append(
                {
                    "n_samples": n,
                    "k": k,
                    "pm_axis": pm_exact(k, n),
                    "pm_axis_gaussian": pm_gaussian(k, n),  # eq. 13, white-noise mean and spread
                    "pm_burst": pm_burst(k, n, n_axes),
                }
            )
    return rows


def pfa_temporary(q_axes: Iterable[float]) -> float:
    """Seed 000 eq. (14), first line: a moving burst is quiet on every axis, P_tFA = prod_i q_i."""
    out = 1.0
    for q in q_axes:
        if not 0 <= q <= 1:
            raise DetectorError(f"per-axis quiet probability {q!r}: must be in [0, 1]")
        out *= float(q)
    return out


def pfa_final(q: float, m: int) -> float:
    """Seed 000 eq. (14), second line, with T_th / W_s = m bursts: P_FA = q^m (independent bursts)."""
    if not 0 <= q <= 1:
        raise DetectorError(f"per-burst quiet probability in motion q = {q!r}: must be in [0, 1]")
    _, m = _check_km(1.0, m)
    return float(q) ** m


def m_for_pfa(q: float, pfa: float) -> int:
    """The least m with q^m <= pfa: ceil(ln pfa / ln q)."""
    q = _check_p(q, "per-burst quiet probability in motion q")
    pfa = _check_p(pfa, "target P_FA")
    m = max(1, math.ceil(math.log(pfa) / math.log(q) - 1e-12))
    return m + 1 if q**m > pfa else m


# ------------------------------------------------------------------------------------ the battery


def tradeoff(
    intervals_s: Iterable[float],
    burst_samples: Iterable[int],
    m: int,
    *,
    n_axes: int = 2,
    rate_hz: float | None = None,
    charge_per_sample_uC: float | None = None,
    baseline_uA: float = 0.0,
    pm_target: float | None = None,
) -> list[dict]:
    """One row per (ACC interval, samples per axis per burst):

    samples_per_hour_per_axis = N 3600 / interval;  adc_samples_per_hour = that x n_axes;
    worst_response_s = m interval + N / rate_hz: motion stops just after a burst began (it is not
        quiet), the next burst starts at most one interval later and the m-th quiet burst ends
        (m - 1) intervals plus one burst length after that; with ``rate_hz`` None the burst length
        is neglected (m x interval);
    best_response_s = (m - 1) interval + N / rate_hz (motion stops just before a burst);
    mean_current_uA = baseline_uA + charge_per_sample_uC x adc_samples_per_hour / 3600 (only when
        ``charge_per_sample_uC`` is given). The charge per sample and the sleep current are the
        caller's assumptions: the seeds give none (seed 000 section 7.3 bounds only power: < 1 mW for
        the LIS302DL, < 5 mW for the detection module while active);
    k_for_pm: the k that keeps a burst's P_M at ``pm_target`` for that N (when given)."""
    _, m = _check_km(1.0, m)
    n_axes = _check_axes(n_axes)
    if rate_hz is not None and not (isinstance(rate_hz, (int, float)) and rate_hz > 0):
        raise DetectorError(f"rate_hz = {rate_hz!r}: the per-axis sampling frequency must be > 0 Hz")
    if charge_per_sample_uC is not None and not charge_per_sample_uC >= 0:
        raise DetectorError(f"charge_per_sample_uC = {charge_per_sample_uC!r}: must be >= 0")
    if not baseline_uA >= 0:
        raise DetectorError(f"baseline_uA = {baseline_uA!r}: must be >= 0")
    ns = [_check_n(n) for n in burst_samples]
    rows = []
    for interval in intervals_s:
        if not (isinstance(interval, (int, float)) and math.isfinite(interval) and interval > 0):
            raise DetectorError(f"ACC interval {interval!r} s: must be a finite number > 0")
        for n in ns:
            burst_s = n / rate_hz if rate_hz is not None else 0.0
            if burst_s > interval:
                raise DetectorError(
                    f"a burst of {n} samples at {rate_hz:g} Hz lasts {burst_s:g} s, longer than the {interval:g} s "
                    "interval: the tag then samples (nearly) continuously (seed 003 section 10)"
                )
            per_axis = n * 3600.0 / interval
            row = {
                "interval_s": float(interval),
                "burst_samples": n,
                "burst_s": burst_s if rate_hz is not None else None,
                "m": m,
                "samples_per_hour_per_axis": per_axis,
                "adc_samples_per_hour": per_axis * n_axes,
                "worst_response_s": m * interval + burst_s,
                "best_response_s": (m - 1) * interval + burst_s,
            }
            if charge_per_sample_uC is not None:
                row["mean_current_uA"] = baseline_uA + charge_per_sample_uC * per_axis * n_axes / 3600.0
            if pm_target is not None:
                row["k_for_pm"] = k_for_pm(pm_target, n, n_axes)
            rows.append(row)
    return rows


# ------------------------------------------------------------------------------------ Movebank files

SIGMA2_POOLS = ("file", "individual")


@dataclass(frozen=True, slots=True, eq=False)
class IndividualDetection:
    """One individual's bursts, in time order: ``checks.t`` is ``datetime64[ns]`` (UTC)."""

    individual: str
    axes: str
    rate_hz: float
    n_samples: int
    sigma2_g2: np.ndarray  # (d,)
    nominal: bool  # counts converted with seed 003 section 6's nominal constants
    checks: BurstChecks


@dataclass(frozen=True, slots=True, eq=False)
class MovebankDetection:
    path: str
    k: float
    m: int
    sigma2_source: str  # 'given', or how it was calibrated ('file' / 'individual' pool)
    nominal: bool  # any individual converted with the nominal constants
    individuals: dict[str, IndividualDetection]

    def rows(self) -> list[dict]:
        """One dict per burst: individual, time, per-axis variance (g^2), quiet, final static."""
        out = []
        for ind in self.individuals.values():
            c = ind.checks
            for j in range(c.t.shape[0]):
                row = {"individual": ind.individual, "t": c.t[j]}
                row.update({f"var_{a.lower()}_g2": float(c.var_g2[j, i]) for i, a in enumerate(ind.axes)})
                row.update(quiet=bool(c.quiet[j]), final_static=bool(c.final_static[j]))
                out.append(row)
        return out


def _per_individual(value, individual: str, what: str, names: list[str]):
    if isinstance(value, Mapping):
        if individual not in value:
            raise DetectorError(
                f"{what}: no entry for individual {individual!r}{did_you_mean(individual, list(value))}; "
                f"the file's individuals: {', '.join(names)}"
            )
        return value[individual]
    return value


def detect_movebank(
    path: str | os.PathLike,
    *,
    k: float,
    m: int,
    calibration=None,
    sigma2=None,
    tag_number=None,
    sensitivity: str | None = None,
    sigma2_pool: str = "file",
    max_gap_s: float | None = None,
) -> MovebankDetection:
    """Run the burst detector over every individual of a Movebank e-obs file.

    Counts go to g with :func:`flightmode.eobs.calibration.to_g` (``calibration``: one
    ``Calibration`` or a mapping individual -> Calibration; None: the nominal constants, which warns
    ``NominalCalibrationWarning``, and ``nominal`` is set; ``tag_number`` / ``sensitivity`` as
    ``to_g`` takes them, one value or a mapping; a Movebank individual id is not a tag number).
    Bursts are grouped by the burst's tag id (in Movebank's export without ``tag-local-identifier``:
    the individual) and put in time order.

    sigma2: (d,) g^2, or a mapping individual -> (d,); None: :func:`calibrate_sigma2_bursts` over
    ``sigma2_pool``: 'file' (default) pools the bursts of all individuals with the same axes, rate
    and burst length (one sensor type and setting: its noise is the sensor's, not the animal's), so
    an individual that never rested still gets the noise of those that did; 'individual' calibrates
    each on its own bursts, valid only if at least a tenth of them are at rest."""
    from flightmode.eobs.calibration import to_g
    from flightmode.eobs.movebank import read_movebank

    k, m = _check_km(k, m)
    if sigma2_pool not in SIGMA2_POOLS:
        raise DetectorError(
            f"sigma2_pool {sigma2_pool!r}{did_you_mean(sigma2_pool, SIGMA2_POOLS)}; one of {', '.join(SIGMA2_POOLS)}"
        )
    f = read_movebank(path)
    groups: dict[str, list] = {}
    for b in f.bursts:
        groups.setdefault(b.tag_id, []).append(b)
    if not groups:
        raise DetectorError(f"{path}: no acceleration bursts in the file")
    names = list(groups)
    conv: dict[str, tuple] = {}
    for ind, bursts in groups.items():
        bursts = sorted(bursts, key=lambda b: b.start_time)  # stable: file order for equal times
        key = (bursts[0].axes, bursts[0].rate_hz, bursts[0].n_samples)
        for b in bursts:
            if (b.axes, b.rate_hz, b.n_samples) != key:
                raise DetectorError(
                    f"{path}: individual {ind!r}: bursts with axes/rate/length {b.axes}/{b.rate_hz:g} Hz/{b.n_samples} "
                    f"and {key[0]}/{key[1]:g} Hz/{key[2]}: one sigma^2 per tag and setting; split the file"
                )
        cal = _per_individual(calibration, ind, "calibration", names)
        tn = _per_individual(tag_number, ind, "tag_number", names)
        sens = _per_individual(sensitivity, ind, "sensitivity", names)
        gs = [to_g(b, cal, tag_number=tn, sensitivity=sens) for b in bursts]
        conv[ind] = (key, bursts, [g.acc_g for g in gs], any(g.nominal for g in gs))
    if sigma2 is not None:
        s2 = {ind: _check_sigma2(_per_individual(sigma2, ind, "sigma2", names)) for ind in conv}
        source = "given"
    elif sigma2_pool == "individual":
        s2 = {ind: calibrate_sigma2_bursts(c[2]) for ind, c in conv.items()}
        source = "individual"
    else:
        pools: dict[tuple, list] = {}
        for c in conv.values():
            pools.setdefault(c[0], []).extend(c[2])
        by_key = {key: calibrate_sigma2_bursts(acc) for key, acc in pools.items()}
        s2 = {ind: by_key[c[0]] for ind, c in conv.items()}
        source = "file"
    out = {}
    for ind, (key, bursts, acc, nominal) in conv.items():
        t = np.array([b.start_time for b in bursts], dtype="datetime64[ns]")
        checks = detect_bursts(t, acc, s2[ind], k, m, max_gap_s)
        out[ind] = IndividualDetection(ind, key[0], key[1], key[2], s2[ind], nominal, checks)
    return MovebankDetection(str(path), k, m, source, any(i.nominal for i in out.values()), out)
