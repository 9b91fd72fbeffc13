"""Duty-cycled (per-burst) flight-mode detection: seed 000 eq. 1, 7, 8, 13-14 on seed 003's bursts.

Monte Carlo tolerances: an estimate p^ of a probability p from T independent trials is binomial; the
tests accept |p^ - p| <= 4.42 sqrt(p (1 - p) / T), the normal two-sided 1e-5 tail, so a correct
implementation fails for fewer than 1 seed in 10^5 (the seeds are fixed: the run is deterministic),
while the wrong models named in each test lie several tolerances away.
"""

from __future__ import annotations

import itertools
import math
import warnings

import numpy as np
import pytest
from scipy.stats import chi2

from flightmode.detector.statistics import pm_exact
from flightmode.eobs.calibration import NominalCalibrationWarning
from flightmode.eobs.duty_cycle import (
    BurstChecks,
    BurstDetector,
    burst_variance,
    calibrate_sigma2_bursts,
    detect_bursts,
    detect_movebank,
    k_for_pm,
    m_for_pfa,
    pfa_final,
    pfa_temporary,
    pm_burst,
    pm_final,
    pm_table,
    tradeoff,
)
from flightmode.eobs.movebank import read_movebank
from flightmode.errors import DetectorError

Z_1E5 = 4.42  # two-sided normal quantile for a 1e-5 false failure rate


def _binomial_tol(p: float, trials: int) -> float:
    return Z_1E5 * math.sqrt(p * (1.0 - p) / trials)


def _stream(rng, n_bursts=40, sigma=(0.002, 0.003)):
    """Bursts of varying length: static noise on a 1 g / 0 g mean, some with motion added."""
    bursts = []
    for _ in range(n_bursts):
        n = int(rng.integers(2, 80))
        a = rng.normal(0.0, sigma, size=(n, 2)) + [1.0, 0.0]
        if rng.random() < 0.3:
            a += rng.normal(0.0, 0.02, size=(n, 2))  # motion: 40-50 sigma^2
        bursts.append(a)
    return bursts


def _push_all(det: BurstDetector, t, bursts) -> BurstChecks:
    rows = [det.push(ti, b) for ti, b in zip(t, bursts)]
    return BurstChecks(*(np.concatenate([getattr(r, f) for r in rows]) for f in BurstChecks.__slots__))


def _assert_same(a: BurstChecks, b: BurstChecks) -> None:
    for f in BurstChecks.__slots__:
        x, y = getattr(a, f), getattr(b, f)
        assert x.dtype == y.dtype and np.array_equal(x, y), f


# ------------------------------------------------------------------------------------ the decision


def test_batch_and_streaming_agree_exactly():
    rng = np.random.default_rng(18)
    bursts = _stream(rng)
    sigma2 = np.array([0.002, 0.003]) ** 2
    t_s = np.cumsum(rng.choice([300.0, 300.0, 300.0, 1500.0], size=len(bursts)))  # some missing bursts
    for k, m, gap in [(4.0, 1, None), (4.0, 3, None), (2.5, 2, 600.0), (10.0, 4, 600.0)]:
        batch = detect_bursts(t_s, bursts, sigma2, k, m, max_gap_s=gap)
        _assert_same(batch, _push_all(BurstDetector(sigma2, k, m, max_gap_s=gap), t_s, bursts))
        assert batch.quiet.any() and (~batch.quiet).any() and batch.final_static.any()
        assert np.array_equal(
            batch.after_reset[1:], (np.diff(t_s) > gap) if gap else np.zeros(len(bursts) - 1, bool)
        )
    t_ns = np.datetime64("2008-07-27T00:00:00", "ns") + (t_s * 1e9).astype(
        "timedelta64[ns]"
    )  # times as in a file
    batch = detect_bursts(t_ns, bursts, sigma2, 4.0, 2, max_gap_s=600.0)
    _assert_same(batch, _push_all(BurstDetector(sigma2, 4.0, 2, max_gap_s=600.0), t_ns, bursts))
    assert np.array_equal(
        batch.final_static, detect_bursts(t_s, bursts, sigma2, 4.0, 2, max_gap_s=600.0).final_static
    )


def test_eq1_eq7_eq8_by_hand():
    # eq. 1: 1/N normalisation about the burst's own mean, per axis
    np.testing.assert_allclose(burst_variance([[1.0, 0.0], [3.0, 0.0], [5.0, 3.0]]), [8.0 / 3.0, 2.0])
    # eq. 7: quiet when every axis is strictly below k sigma^2; eq. 8: the last m bursts all quiet
    sigma2, k = np.array([0.5, 1.0]), 2.0  # thresholds 1 and 2
    loud = np.array([[0.0, 0.0], [3.0, 0.0]])  # X variance 2.25 >= 1
    edge = np.array([[0.0, 0.0], [2.0, 0.0]])  # X variance exactly 1 = k sigma^2: not quiet (eq. 7's "<")
    calm = np.array([[0.0, 0.0], [1.0, 1.0]])  # 0.25, 0.25
    bursts = [calm, calm, loud, calm, calm, calm, edge, calm]
    got = detect_bursts(np.arange(8.0), bursts, sigma2, k, 2)
    assert got.quiet.tolist() == [1, 1, 0, 1, 1, 1, 0, 1]
    assert got.final_static.tolist() == [0, 1, 0, 0, 1, 1, 0, 0]
    assert detect_bursts(np.arange(8.0), bursts, sigma2, k, 1).final_static.tolist() == got.quiet.tolist()
    # a gap longer than max_gap_s restarts the count: bursts 4 and 5 after a 10 s gap
    t = np.array([0, 1, 2, 3, 13, 14, 15, 16.0])
    got = detect_bursts(t, [calm] * 8, sigma2, k, 2, max_gap_s=5.0)
    assert got.final_static.tolist() == [0, 1, 1, 1, 0, 1, 1, 1]


# ------------------------------------------------------------------------------------- calibration


def test_calibration_recovers_the_noise_from_mixed_bursts():
    """300 static bursts of 60 samples among 700 moving ones (30 % static): the pooled within-burst
    variance has relative spread sqrt(2 / (300 x 59)) = 1.06 %, so 4.42 x that = 4.7 %. The decile's
    median alone would say 0.70-1 sigma^2 depending on the static share."""
    rng = np.random.default_rng(3)
    sigma = np.array([0.002, 0.004])
    static = [rng.normal(0.0, sigma, (60, 2)) + [1.0, 0.0] for _ in range(300)]
    moving = [rng.normal(0.0, sigma * rng.uniform(4, 30), (60, 2)) for _ in range(700)]
    bursts = [b for pair in zip(static, moving[:300]) for b in pair] + moving[300:]
    tol = Z_1E5 * math.sqrt(2.0 / (300 * 59))
    np.testing.assert_allclose(calibrate_sigma2_bursts(bursts), sigma**2, rtol=tol)
    # every burst static: the same estimate, unbiased (the decile's median would be 0.70 sigma^2 at N = 60)
    all_static = [rng.normal(0.0, sigma, (60, 2)) for _ in range(300)]
    np.testing.assert_allclose(calibrate_sigma2_bursts(all_static), sigma**2, rtol=tol)
    # counts that do not move at rest: floored at the quantisation noise lsb^2 / 12, never 0
    flat = [np.full((60, 2), 0.5)] * 20
    np.testing.assert_allclose(calibrate_sigma2_bursts(flat, lsb_g=0.0022), [0.0022**2 / 12] * 2)


# ---------------------------------------------------------------------------------------- P_M, P_FA


@pytest.mark.parametrize("n", [12, 60])
def test_chi_square_threshold_reproduces_monte_carlo_pm(n):
    """k from the exact chi-square for a 5 % burst P_M on 2 axes; 20 000 static bursts (unequal noise
    per axis, 1 g on X) through the detector: tolerance 4.42 sqrt(0.05 x 0.95 / 20000) = 0.0068.
    Wrong models it rejects: eq. 13's Gaussian at the same target gives a true P_M of 0.084 (N = 12)
    and 0.068 (N = 60); a 1/(N-1) variance against the 1/N law gives 0.087 and 0.063."""
    rng = np.random.default_rng(1000 + n)
    target, trials = 0.05, 20_000
    k = k_for_pm(target, n, 2)
    assert pm_burst(k, n, 2) == pytest.approx(target, rel=1e-9)
    sigma = np.array([0.002, 0.005])
    a = rng.normal(0.0, sigma, size=(trials, n, 2)) + [1.0, 0.0]
    got = detect_bursts(np.arange(float(trials)), a, sigma**2, k, 1)
    pm_hat = 1.0 - got.quiet.mean()
    assert abs(pm_hat - target) <= _binomial_tol(target, trials)


def test_final_false_alarm_is_q_to_the_m():
    """Motion modelled as white noise of 1.8 sigma^2 per axis: per axis q_i = P(chi2_{N-1} < N k / 1.8),
    per burst P_tFA = q_x q_y (eq. 14), final P_FA = q^m. The final decision at burst j depends on bursts
    j-m+1 .. j only, so every m-th decision of one stream is an independent trial."""
    rng = np.random.default_rng(14)
    n, k, m, c, trials = 60, 2.0, 3, 1.8, 10_000
    q_axis = float(chi2.cdf(n * k / c, n - 1))
    q = pfa_temporary([q_axis, q_axis])
    sigma2 = np.array([1e-5, 1e-5])
    a = rng.normal(0.0, np.sqrt(c * sigma2), size=(trials * m, n, 2))
    got = detect_bursts(np.arange(float(trials * m)), a, sigma2, k, m)
    assert abs(got.quiet.mean() - q) <= _binomial_tol(q, trials * m)
    finals = got.final_static[m - 1 :: m]
    assert finals.size == trials
    p = pfa_final(q, m)
    assert p == pytest.approx(q**3) and abs(p - 0.2081) < 1e-4
    assert abs(finals.mean() - p) <= _binomial_tol(p, trials)  # 0.018; q^(m-1) = 0.35 would fail
    assert m_for_pfa(q, p) == m and m_for_pfa(0.5, 1e-3) == 10 and m_for_pfa(0.5, 0.25) == 2


def test_fewer_samples_need_a_higher_k():
    ns = [6, 12, 30, 60, 120, 300]
    for pm in (1e-2, 1e-6):
        ks = [k_for_pm(pm, n) for n in ns]
        assert all(a > b for a, b in itertools.pairwise(ks))
    assert k_for_pm(1e-6, 12) > 4.0 > k_for_pm(1e-6, 30)  # 12 samples: even 4 sigma^2 misses 1e-6
    rows = pm_table(ns, [2.5, 4.0])
    assert [(r["n_samples"], r["k"]) for r in rows[:4]] == [(6, 2.5), (6, 4.0), (12, 2.5), (12, 4.0)]
    for k in (2.5, 4.0):
        pms = [r["pm_burst"] for r in rows if r["k"] == k]
        assert all(a > b for a, b in itertools.pairwise(pms))
    r = next(r for r in rows if (r["n_samples"], r["k"]) == (12, 2.5))
    assert r["pm_axis"] == pm_exact(2.5, 12)
    assert r["pm_burst"] == pytest.approx(1 - (1 - r["pm_axis"]) ** 2, rel=1e-12)
    assert r["pm_axis_gaussian"] < r["pm_axis"] / 50  # eq. 13's Gaussian misses the chi-square tail
    assert pm_final(2.5, 12, 3) == pytest.approx(1 - (1 - r["pm_burst"]) ** 3, rel=1e-12)


# ------------------------------------------------------------------------------------ the battery


def test_tradeoff_arithmetic_by_hand():
    """900 s interval, 60 samples per axis at 5 Hz (the albatross tags), 2 axes, m = 2, an assumed
    2 uC per ADC sample over an assumed 5 uA sleep current (illustrative, from no source):
    240 samples/h per axis, 480 conversions/h, 5 + 2 x 480 / 3600 = 5.2667 uA; worst response
    2 x 900 + 12 = 1812 s, best 900 + 12 = 912 s."""
    rows = tradeoff(
        [300.0, 900.0], [12, 60], 2, n_axes=2, rate_hz=5.0, charge_per_sample_uC=2.0, baseline_uA=5.0
    )
    assert [(r["interval_s"], r["burst_samples"]) for r in rows] == [
        (300, 12),
        (300, 60),
        (900, 12),
        (900, 60),
    ]
    r = rows[3]
    assert (
        r["burst_s"] == 12.0
        and r["samples_per_hour_per_axis"] == 240.0
        and r["adc_samples_per_hour"] == 480.0
    )
    assert r["mean_current_uA"] == pytest.approx(5.0 + 2.0 * 480 / 3600, rel=1e-12)
    assert (r["worst_response_s"], r["best_response_s"]) == (1812.0, 912.0)
    assert rows[0]["samples_per_hour_per_axis"] == 144.0 and rows[0]["worst_response_s"] == 602.4
    bare = tradeoff([900.0], [60], 3, pm_target=1e-3)
    assert bare[0]["burst_s"] is None and bare[0]["worst_response_s"] == 2700.0  # m x interval
    assert "mean_current_uA" not in bare[0] and bare[0]["k_for_pm"] == k_for_pm(1e-3, 60, 2)
    with pytest.raises(DetectorError, match=r"lasts 12 s, longer than the 10 s interval"):
        tradeoff([10.0], [60], 1, rate_hz=5.0)


# ------------------------------------------------------------------------------------ the real file


def _fixes(f):
    """GPS rows: individual -> (fix time, ground speed m/s)."""
    out = {}
    for r in f.rows:
        if r.burst is None:
            ind = r.get(f.header, "individual-local-identifier")
            t = np.datetime64(r.get(f.header, "timestamp")[:19], "ns")
            out[ind] = (t, float(r.get(f.header, "ground-speed")))
    return out


def test_real_albatross_file(real_movebank):
    """Public Movebank study 2911040, 9 albatrosses, 5 bursts each (XY, 60 samples at 5 Hz), one GPS
    fix each at the first burst. The ids are not tag numbers: the counts go to g with the nominal
    constants of an assumed tag number (2242); with sigma^2 calibrated from the same counts the
    decisions do not depend on the slope, only the variances in g^2 do."""
    f = read_movebank(real_movebank)
    per_ind: dict[str, int] = {}
    for b in f.bursts:
        per_ind[b.tag_id] = per_ind.get(b.tag_id, 0) + 1
    with pytest.warns(NominalCalibrationWarning):
        res = detect_movebank(real_movebank, k=4.0, m=2, tag_number=2242)
    assert res.nominal and res.sigma2_source == "file" and (res.k, res.m) == (4.0, 2)
    assert {i: d.checks.t.size for i, d in res.individuals.items()} == per_ind  # every burst, 9 x 5
    assert sum(per_ind.values()) == len(f.bursts) == 45 and len(res.rows()) == 45
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", NominalCalibrationWarning)
        again = detect_movebank(real_movebank, k=4.0, m=2, tag_number=2242)
        low = detect_movebank(real_movebank, k=4.0, m=2, tag_number=2241, sensitivity="low")  # 0.0027 g/count
    for i, d in res.individuals.items():
        _assert_same(d.checks, again.individuals[i].checks)  # deterministic
        np.testing.assert_array_equal(d.checks.quiet, low.individuals[i].checks.quiet)
        np.testing.assert_array_equal(d.checks.final_static, low.individuals[i].checks.final_static)
        np.testing.assert_allclose(
            low.individuals[i].checks.var_g2, d.checks.var_g2 * (0.0027 / 0.0022) ** 2, rtol=1e-12
        )
        assert np.all(np.diff(d.checks.t) > np.timedelta64(0)) and (d.axes, d.rate_hz, d.n_samples) == (
            "XY",
            5.0,
            60,
        )
        assert not np.any(d.checks.final_static & ~d.checks.quiet)
    # one sensor setting in the file: one sigma^2, above the ADC's quantisation floor; on this file
    # within a factor 2 of the quietest burst (the colony's resting bursts agree with one another)
    s2 = {tuple(d.sigma2_g2) for d in res.individuals.values()}
    assert len(s2) == 1
    sigma2 = np.array(s2.pop())
    v_min = np.min([d.checks.var_g2.min(axis=0) for d in res.individuals.values()], axis=0)
    assert np.all(sigma2 > 0.0022**2 / 12) and np.all(v_min < sigma2) and np.all(sigma2 < 2 * v_min)
    # the fix speed says which birds fly (~10 m/s) or drift on the water (0.4-1.3 m/s): the burst that
    # starts at the fix (same second) of each of those is far from quiet, even at k = 10 (riding a 1 m
    # swell of 8 s period alone is 1 x (2 pi / 8)^2 = 0.62 m/s^2, about 60 mg against 8 mg of noise)
    fixes = _fixes(f)
    moving = [i for i, (_, v) in fixes.items() if v >= 0.4]
    assert len(moving) == 6
    for i in moving:
        d = res.individuals[i]
        assert abs(d.checks.t[0] - fixes[i][0]) < np.timedelta64(1, "s")
        assert np.all(d.checks.var_g2[0] >= 10 * sigma2)
        assert not d.checks.quiet[0]


def test_real_file_per_individual_calibration_refuses_birds_that_never_rest(real_movebank):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", NominalCalibrationWarning)
        with pytest.raises(DetectorError, match=r"^calibration: none of the 5 bursts .* hold no rest") as e:
            detect_movebank(real_movebank, k=4.0, m=2, tag_number=2242, sigma2_pool="individual")
        assert "\n" not in str(e.value)
        with pytest.raises(
            DetectorError, match=r"sigma2_pool 'individuals' \(did you mean \"individual\"\?\)"
        ):
            detect_movebank(real_movebank, k=4.0, m=2, tag_number=2242, sigma2_pool="individuals")
        with pytest.raises(DetectorError, match=r"tag_number: no entry for individual '4266-84831108'"):
            detect_movebank(real_movebank, k=4.0, m=2, tag_number={"4266-8483110": 2242})
        with pytest.raises(DetectorError, match=r"2 axes where 3 are expected"):
            detect_movebank(real_movebank, k=4.0, m=2, tag_number=2242, sigma2=[1e-4, 1e-4, 1e-4])


# ------------------------------------------------------------------------------------- bad inputs


@pytest.mark.parametrize(
    "change, message",
    [
        ({"m": 0}, r"^m = 0: .* integer >= 1"),
        ({"m": 1.5}, r"^m = 1.5: "),
        ({"m": True}, r"^m = True: "),
        ({"k": 0.0}, r"^k = 0.0: .* k > 0"),
        ({"k": -2.0}, r"^k = -2.0: "),
        ({"k": float("nan")}, r"^k = nan: "),
        ({"bursts": [np.zeros((1, 2))]}, r"^burst 0: 1 sample\(s\) per axis; a variance needs >= 2"),
        ({"bursts": [np.array([[0.0, 1.0], [np.nan, 1.0]])]}, r"^burst 0: sample 1 of axis 0 is nan"),
        ({"bursts": [np.zeros((5, 3))]}, r"^burst 0: 3 axes where 2 are expected"),
        ({"sigma2": [1e-5, -1e-5]}, r"^sigma\^2 \[1e-05, -1e-05\]: must be"),
        (
            {"t": [1.0, 1.0], "bursts": [np.zeros((5, 2))] * 2},
            r"^burst times: burst 1 \(t = 1.0\) is not after burst 0",
        ),
    ],
)
def test_bad_input_raises_one_line_detector_error(change, message):
    args = {"t": [0.0], "bursts": [np.zeros((5, 2))], "sigma2": [1e-5, 1e-5], "k": 4.0, "m": 2} | change
    with pytest.raises(DetectorError, match=message) as e:
        detect_bursts(args["t"], args["bursts"], args["sigma2"], args["k"], args["m"])
    assert "\n" not in str(e.value)
    with pytest.raises(DetectorError, match=message):  # the streaming front end refuses the same
        det = BurstDetector(args["sigma2"], args["k"], args["m"])
        for t, b in zip(args["t"], args["bursts"]):
            det.push(t, b)


def test_bad_analysis_input():
    for call, message in [
        (lambda: k_for_pm(0.0, 60), r"target P_M = 0.0"),
        (lambda: k_for_pm(0.01, 1), r"N = 1 samples per axis"),
        (lambda: pm_burst(2.0, 60, n_axes=4), r"n_axes = 4"),
        (lambda: pfa_final(1.5, 2), r"q = 1.5"),
        (lambda: pfa_final(0.5, 0), r"m = 0"),
        (lambda: tradeoff([0.0], [60], 1), r"ACC interval 0.0 s"),
        (lambda: calibrate_sigma2_bursts([]), r"no bursts given"),
        (
            lambda: calibrate_sigma2_bursts([np.zeros((5, 2)), np.zeros((5, 1))]),
            r"calibration burst 1: 1 axes where 2 are expected",
        ),
    ]:
        with pytest.raises(DetectorError, match=message):
            call()
