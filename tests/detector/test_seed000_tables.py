"""Seed 000's tables reproduced (issue 53 item 2): Tables 2, 3, 6-9, eq. (15), eq. (12)'s common
threshold, section 5.1.1's loop, each against the paper's printed numbers at a stated tolerance."""

from __future__ import annotations

import math

import numpy as np
import pytest

from flightmode.detector import seed000 as s0
from flightmode.detector.flight_mode import DetectorParams, FlightModeDetector, axis_thresholds
from flightmode.detector.statistics import (
    k_of_pm_acov,
    k_of_pm_am,
    k_of_pm_gaussian,
    pm_acov,
    pm_am,
    threshold_for_pfa,
)
from flightmode.errors import DetectorError
from flightmode.sim.sensor.accelerometer import get_preset
from flightmode.studies import seed000 as study


@pytest.fixture(scope="module")
def bench_100hz():
    """10 minutes of the bench model (1,800 one-second checks over three axes): enough to resolve
    the 2 sigma^2 row (P_M ~ 5e-3, ~9 hits) and every Table 3 mean to well under 1 %."""
    from flightmode.detector.flight_mode import calibrate_sigma2

    acc, p = study.bench(duration_s=600.0, seed=3)
    return acc, p, calibrate_sigma2(acc, 100, p.lsb_g)


def test_table8_is_reproduced_cell_for_cell():
    # exact integers: Table 7's NMV row recovered from Table 8, its EMV row as printed
    assert s0.table8() == s0.TABLE8


def test_table9_resource_bounds_are_3_blocks_from_8_to_20_bits():
    # Table 9: 813 <= LEs <= 3405 (NMV), 540 <= LEs <= 2016 (EMV), with memory, N = 64
    assert (3 * s0.nmv_les(8, 64, True), 3 * s0.nmv_les(20, 64, True)) == (813, 3405)
    assert (3 * s0.emv_les(8), 3 * s0.emv_les(20)) == (540, 2016)
    # Table 9's alpha row at N = 64: weights 1-5 whose alpha/N is a power of two (a shift)
    assert s0.power_of_two_weights(64) == [1.0, 2.0, 4.0]


def test_eq15_is_the_n_point_moving_average_and_its_response():
    rng = np.random.default_rng(0)
    x = rng.normal(size=(400, 3))
    n = 64
    fir = np.stack([np.convolve(x[:, j], np.ones(n) / n)[: x.shape[0]] for j in range(3)], axis=1)
    # the comb-integrator form and the FIR sum agree to rounding (400 additions of O(1) values)
    assert np.max(np.abs(s0.moving_average_eq15(x, n) - fir)) < 1e-12
    # |H| = 1 at 0 Hz and 0 at every multiple of fs / N (eq. 15's zeros)
    assert s0.eq15_response(n, np.array([0.0]))[0] == 1.0
    assert np.max(s0.eq15_response(n, np.arange(1, 10) / n)) < 1e-12
    # Fig. 20's network is eq. 1's NMV once the delay line is full
    from flightmode.detector.moving_variance import moving_variance

    mv = moving_variance(x, n, "nmv", 1.0)
    assert np.max(np.abs(s0.nmv_network(x, n)[n - 1 :] - mv[n - 1 :])) < 1e-10  # cancellation of O(1) terms


def test_exponential_averager_is_eq4():
    x = np.array([1.0, 2.0, 3.0])
    a = 0.25
    y = s0.exponential_averager(x, a, y0=0.0)
    # hand: 0.25, 0.25 + 0.25 (2 - 0.25) = 0.6875, 0.6875 + 0.25 (3 - 0.6875) = 1.265625
    assert np.allclose(y, [0.25, 0.6875, 1.265625], rtol=0, atol=1e-15)


def test_the_papers_tables_4_and_5_follow_eq14_except_one_misprint():
    # each cell is printed to one significant digit: three factors each off by up to ~10 %, raised to
    # the 4th power, move a product by up to a factor ~2
    bad = []
    for r in s0.paper_pfa_consistency():
        ratio = r["P_FA_printed"] / r["P_FA_from_product"]
        if not 0.5 <= ratio <= 2.0:
            bad.append((r["table"], r["T_sigma"], r["T_th_s"]))
    # Table 4 at 3 sigma^2, T_th 3 s: 6e-33 printed, 3.1e-32 from its axes (and its P_FA^t 2e-10 is
    # not the product 3.2e-11 of its axes either, while T_th 4 s's 1e-42 is 3.2e-11^4)
    assert bad == [(4, 3.0, 3.0)]


def test_table2_three_ways(bench_100hz):
    acc, p, s2 = bench_100hz
    rows = {r["T_sigma"]: r for r in study.table2(acc, p, s2)}
    # our noise's P_M (pm_am, tests/sim/test_noise_colour.py) with its Monte Carlo standard error:
    # at 2 sigma^2 1.3e-2, about twice the paper's 6e-3 (the skewed MV against eq. 13's Gaussian
    # tail, with the paper's own mean E[MV] = sigma^2 of Table 3); the Gauss-Markov model it
    # replaced matched that row only through its mean of 0.81 sigma^2, which Table 3 contradicts
    assert rows[2.0]["exact_P_M"] == pytest.approx(1.3e-2, rel=0.1)
    assert rows[2.0]["exact_P_M_se"] < 0.1 * rows[2.0]["exact_P_M"]
    assert rows[2.0]["gm_before_P_M"] == pytest.approx(4.9e-3, rel=0.05)
    assert 1.5 < rows[2.0]["exact_P_M"] / 6e-3 < 3.5
    # the Gaussian approximation (eq. 13 with our measured moments) is orders low at 4 sigma^2
    assert rows[4.0]["gaussian_over_exact"] < 1e-10
    # Monte Carlo agrees with the exact value at 2 sigma^2 within 3 binomial standard errors (+1 hit;
    # the exact value's own standard error is < 10 % of it)
    r = rows[2.0]
    exp = r["exact_P_M"] * r["checks"]
    assert abs(r["measured_hits"] - exp) <= 3 * math.sqrt(exp) + 1 + 3 * r["exact_P_M_se"] * r["checks"]


def test_table3_is_flat_from_1_to_3_s_and_the_papers_05s_cell_is_out_of_reach(bench_100hz):
    acc, p, s2 = bench_100hz
    rows = study.table3(acc, p, s2)
    exact = [r["exact"] for r in rows]
    # a white carrier loses 1/N of its variance to the window's mean whatever its amplitude does
    assert exact == pytest.approx([49 / 50, 99 / 100, 199 / 200, 299 / 300], rel=1e-12)
    # the paper's 1-3 s cells (1.00, 1.02, 1.02 sigma^2) within 0.03 (two digits of 0.5e-5 g^2);
    # the Gauss-Markov model before issue 53 was 0.19 below at 1 s and rose 15 % to 3 s
    for r in rows[1:]:
        assert r["exact"] == pytest.approx(r["paper"], abs=0.03)
    gm = [r["gm_before"] for r in rows]
    assert gm == pytest.approx([0.673, 0.806, 0.895, 0.928], abs=0.001)  # the 0.67 ... 0.93
    for r in rows:
        # measured over 600 s: 1,800 (0.5 s: 3,600) window means, each within ~1.5 % of the exact
        # mean (sigma_MV 0.37 / sqrt(1,800) = 0.9 % at 1 s)
        assert r["measured"] == pytest.approx(r["exact"], rel=0.05)
        # whatever the definition, no stationary noise gets E[MV] above N/(N-1) sigma^2 (with
        # 1/(N-1): E = (N r0 - N var(mean)) / (N - 1)): the paper's 1.2 at 0.5 s (N = 50) is beyond it
        n = round(r["window_s"] * p.odr_hz)
        assert r["exact_unbiased"] <= n / (n - 1) + 1e-12
    assert s0.TABLE3[0.5] > 50 / 49


def test_common_threshold_is_eq12():
    s2 = np.array([1e-6, 2e-6, 3e-6])
    assert np.allclose(axis_thresholds(DetectorParams(), s2), 4 * s2)  # default unchanged: per axis
    assert np.allclose(axis_thresholds(DetectorParams(threshold="common"), s2), 8e-6)  # 4 x mean
    with pytest.raises(DetectorError):
        DetectorParams(threshold="shared").validate()
    # an axis with a variance between its own threshold and the common one: static only under "common"
    rng = np.random.default_rng(1)
    n = 2000
    acc = rng.normal(0, 1, (n, 3)) * np.sqrt([1e-6, 2e-6, 5e-6])[None, :]
    t = np.arange(n) / 100.0
    s2_cal = np.array([1e-6, 2e-6, 1e-6])  # z calibrated low: per-axis T_z = 4e-6 < 5e-6 < common 5.3e-6
    per = FlightModeDetector(DetectorParams(), s2_cal).push(t, acc)
    com = FlightModeDetector(DetectorParams(threshold="common"), s2_cal).push(t, acc)
    assert per.temporary_static.mean() < 0.2 and com.temporary_static.mean() > 0.5


def test_section_511_loop_against_a_hand_computation():
    # k(P_M) = 1 + 0.4 Phi^-1(1 - P_M) (eq. 13, mu 1, sigma_MV 0.4); P_FA(k) = 1e-3 k; P_FA <= 2e-3.
    # By hand: P_M 1e-6 -> k 2.901 (P_FA 2.90e-3), 1e-5 -> 2.706, 1e-4 -> 2.488, 1e-3 -> 2.236,
    # 1e-2 -> 1 + 0.4 x 2.3263 = 1.9305 (P_FA 1.93e-3 <= 2e-3): met after five rounds
    r = threshold_for_pfa(lambda pm: k_of_pm_gaussian(pm, 1.0, 0.4), lambda k: 1e-3 * k, 1e-6, 2e-3)
    assert r["met"] and len(r["steps"]) == 5
    assert r["pm"] == pytest.approx(1e-2, rel=1e-12)
    assert r["k"] == pytest.approx(1.9305, abs=1e-4)
    assert [s["k"] for s in r["steps"][:4]] == pytest.approx([2.9014, 2.7060, 2.4876, 2.2361], abs=1e-4)
    # never met: stops at pm_max with the last k tried
    r = threshold_for_pfa(lambda pm: k_of_pm_gaussian(pm, 1.0, 0.4), lambda k: 1.0, 1e-6, 2e-3, pm_max=0.05)
    assert not r["met"] and r["pm"] == pytest.approx(1e-2)


def test_the_threshold_inverts_the_pm_of_our_noise():
    p = get_preset("lis302dl-logged16")
    d, phi = p.noise_am_depth, p.noise_am_phi
    k = k_of_pm_am(1e-6, 100, d, phi)
    assert pm_am(k, 100, d, phi)[0] == pytest.approx(1e-6, rel=1e-6)
    assert 3.5 < k < 4.5  # P_M 1e-6 sits near 4 sigma^2 (Table 2: 1.2e-6 at 4 sigma^2)
    # the Gaussian-process inversion still holds for the Gauss-Markov what-if (k_of_pm_acov)
    ac = study.gm_before_acov(100.0, 100)
    k = k_of_pm_acov(3.6e-6, ac, 100)
    assert k == pytest.approx(4.0, abs=0.01)  # the 3.6e-6 at 4 sigma^2, inverted
    assert pm_acov(k * ac[0], ac, 100) == pytest.approx(3.6e-6, rel=1e-6)
