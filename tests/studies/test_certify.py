"""flightmode certify's pieces on data whose answer is known: the Pareto front of hand-made points,
the recommendation's three outcomes, seed 000 section 5.1.1's threshold on white-noise static data,
and the one-line refusals. (certify on real flights, its report and the browser: test_dataset.py.)"""

from __future__ import annotations

import math

import numpy as np
import pytest

from flightmode.errors import InputDataError
from flightmode.studies.certify import Target, pareto_front, recommend, threshold_from_static


def _row(i, events, hours, rate_up, p95, avail, k=4.0):
    return {
        "method": "nmv",
        "weight": 1.0,
        "window_s": 1.0,
        "k": k,
        "time_threshold_s": float(i),
        "params": "",  # a built-in grid's point (summarise's rows)
        "false_statics": events,
        "in_window_h": hours,
        "rate_per_h": events / hours,
        "rate_upper_per_h": rate_up,
        "response_p95_s": p95,
        "availability": avail,
    }


def test_the_pareto_front_holds_exactly_the_points_nothing_beats():
    rows = [
        _row(0, 0, 10, 0.3, 10.0, 0.90),  # front: lowest bound
        _row(1, 0, 10, 0.3, 12.0, 0.80),  # beaten by 0 everywhere
        _row(2, 1, 10, 0.5, 5.0, 0.95),  # front: fastest
        _row(3, 1, 10, 0.5, 5.0, 0.99),  # front: beats 2 on availability alone
        _row(4, 2, 10, 0.6, 8.0, 0.99),  # beaten by 3 (worse bound and response, equal availability)
        _row(5, 0, 10, 0.3, math.nan, 1.0),  # never answers: the worst response, but the best availability
        _row(6, 0, 10, 0.3, 10.0, 0.90),
    ]  # a tie with 0: neither beats the other, both on the front
    assert pareto_front(rows) == [0, 3, 5, 6]


def test_the_recommendation_meets_the_target_or_says_what_is_missing():
    from flightmode.detector.confidence import hours_needed, rate_upper_bound

    t = Target(rate_per_h=0.01, confidence=0.95, max_response_s=30.0)
    per = {"airline-mix": 2.0, "rough-air": 1.5}
    # 600 h with no event: bound 3.0 / 600 = 5e-3 < 1e-2, so both quiet points meet it; the faster one wins
    rows = [
        _row(0, 0, 600, rate_upper_bound(0, 600), 20.0, 0.9),
        _row(1, 0, 600, rate_upper_bound(0, 600), 12.0, 0.8),
        _row(2, 3, 600, rate_upper_bound(3, 600), 4.0, 0.99),
        _row(3, 0, 600, rate_upper_bound(0, 600), 40.0, 1.0),
    ]
    r = recommend(rows, t, lambda p: per)
    assert r["status"] == "meets" and r["point"]["time_threshold_s"] == 1.0 and r["candidates"] == 2
    # 100 h: no bound reaches 1e-2; the provisional point has no event and answers within 30 s, and the
    # claim needs 3.0 / 1e-2 = 299.6 h: 199.6 h more, 100 flights of airline-mix or 134 of rough-air
    rows100 = [
        x
        | {
            "in_window_h": 100.0,
            "rate_upper_per_h": rate_upper_bound(x["false_statics"], 100.0),
            "rate_per_h": x["false_statics"] / 100.0,
        }
        for x in rows
    ]
    r = recommend(rows100, t, lambda p: per)
    assert r["status"] == "too_small" and r["point"]["time_threshold_s"] == 1.0
    assert r["hours_needed"] == pytest.approx(-math.log(0.05) / 0.01)
    assert r["hours_short"] == pytest.approx(hours_needed(0.01) - 100.0)
    assert r["flights_short"] == {"airline-mix": 100, "rough-air": 134}
    assert (
        "199.6" not in r["text"] and "200 h more" in r["text"]
    )  # hours shown rounded, as a reader wants them
    # the best point's rate is above the target even at its lower bound (Garwood: chi2.ppf(0.05, 10) / 200
    # = 0.0197 /h for 5 events in 100 h): no amount of data helps
    from scipy.stats import chi2

    hot = [
        _row(0, 5, 100, rate_upper_bound(5, 100), 5.0, 0.9),
        _row(1, 2, 100, rate_upper_bound(2, 100), 50.0, 0.9),
    ]
    r = recommend(hot, t, lambda p: per)
    assert r["status"] == "unreachable" and r["point"]["false_statics"] == 5  # the only one within 30 s
    assert r["rate_lower_per_h"] == pytest.approx(chi2.ppf(0.05, 10) / 200)
    # one event in 90 h against 1e-2 /h: observed 1.1e-2, but the lower bound (5.7e-4) is below the
    # target: more hours can still show it, if the events slow down; with events at 1.1e-2 /h never
    warm = [_row(0, 1, 90, rate_upper_bound(1, 90), 5.0, 0.9)]
    r = recommend(warm, t, lambda p: per)
    assert r["status"] == "too_small" and r["hours_needed"] == pytest.approx(chi2.ppf(0.95, 4) / 2 / 0.01)
    # 3 events in 1000 h (3e-3 /h < 1e-2): if they keep coming at that rate, the bound reaches the
    # target at T with chi2.ppf(0.95, 2 (3e-3 T + 1)) / 2T = 1e-2
    r = recommend(
        [_row(0, 3, 100, rate_upper_bound(3, 100), 5.0, 0.9) | {"rate_per_h": 3e-3}], t, lambda p: per
    )
    big_t = r["hours_needed_at_rate"]
    assert chi2.ppf(0.95, 2 * (3e-3 * big_t + 1)) / (2 * big_t) == pytest.approx(0.01, rel=1e-6)
    # points that meet the rate but not the response limit: the response limit is what fails
    slow = [
        _row(0, 0, 600, rate_upper_bound(0, 600), 45.0, 0.9),
        _row(1, 0, 600, rate_upper_bound(0, 600), 40.0, 0.9),
    ]
    r = recommend(slow, t, lambda p: per)
    assert (
        r["status"] == "too_slow"
        and r["point"]["time_threshold_s"] == 1.0
        and "raise --max-response-s" in r["text"]
    )


def _static_table(rng, n_checks: int, n: int = 100, colour: float = 1.0, keep: list | None = None):
    """The static statistics of synthetic flights, made by the sweep's own reducer, from MVs of white
    Gaussian noise: N MV / sigma^2 ~ chi-square(N - 1) per axis (``colour`` > 1 widens the spread)."""
    import pyarrow as pa

    from flightmode.studies.sweep import _static_stats

    rows = []
    for f in range(4):
        r = rng.chisquare(n - 1, size=(n_checks // 4, 3)) / n
        r = 1 + (r - 1) * colour
        if keep is not None:
            keep.append(r)
        rows.append(
            {
                "dataset": "d",
                "family": "f",
                "flight_id": f"{f:06d}",
                "sensor_preset": "x",
                "fs_hz": 100.0,
                "method": "nmv",
                "weight": 1.0,
                "window_s": 1.0,
                **_static_stats(r, np.ones(3), np.ones(r.shape[0], bool)),
            }
        )
    return pa.Table.from_pylist(rows)


def test_section_5_1_1_threshold_from_white_static_data_is_the_chi_square_quantile():
    from scipy.stats import chi2

    rng = np.random.default_rng(511)
    raw: list = []
    th = threshold_from_static(_static_table(rng, 400_000, keep=raw), 1e-3)
    # the histograms' survival at the measured k is the share of checks whose largest axis reaches it
    r = np.concatenate(raw)
    assert th["empirical_pm_at_k"] == np.mean(r.max(axis=1) >= th["empirical_k"])
    assert th["static_checks"] == 400_000 and th["empirical_resolved"]
    # exact: P(any of 3 independent axes >= k) = 1e-3 at the chi-square(99) quantile / 100, k = 1.54
    pm_axis = 1 - (1 - 1e-3) ** (1 / 3)
    k_exact = chi2.isf(pm_axis, 99) / 100
    assert th["chi2_white_k"] == pytest.approx(k_exact, rel=1e-12)
    # the measured k is a bin edge (2.3 % wide) at or just above the quantile; 400 expected exceedances
    # give a 5 % count error, about 0.4 % in k at this tail's slope: within one bin and a half
    assert k_exact * 0.985 < th["empirical_k"] < k_exact * 1.035
    assert th["empirical_pm_at_k"] <= 1e-3
    # eq. 13 with the measured moments is close to the white-noise moments' version (mean 0.99, sd 0.141)
    for a in "xyz":
        assert th["axes"][a]["mean"] == pytest.approx(0.99, abs=0.002)  # 4e5 samples: se 2e-4
        assert th["axes"][a]["sd"] == pytest.approx(math.sqrt(2 * 99) / 100, rel=0.01)
    assert th["gaussian_measured_k"] == pytest.approx(th["gaussian_white_k"], abs=0.01)
    # the Gaussian (eq. 13) underestimates the chi-square's heavier right tail: its k is lower
    assert th["gaussian_white_k"] < k_exact
    # a wider spread (as seed 000's Table 2 implies) moves the measured threshold up
    wide = threshold_from_static(_static_table(rng, 400_000, colour=2.5), 1e-3)
    assert wide["empirical_k"] > th["empirical_k"] + 0.5
    # too few checks to see P_M: said, not hidden
    few = threshold_from_static(_static_table(rng, 2_000), 1e-3)
    assert not few["empirical_resolved"]


def test_bad_targets_and_inputs_are_one_line_errors(tmp_path):
    for t, msg in (
        (Target(rate_per_h=0.0), "--target-fa-per-h 0.0: must be a rate > 0"),
        (Target(rate_per_h=-1e-4), "must be a rate > 0"),
        (Target(confidence=1.0), "--confidence 1.0: must be strictly between 0 and 1"),
        (Target(max_response_s=0.0), "--max-response-s 0.0: must be > 0 s"),
        (Target(pm=0.0), "--pm 0.0: a probability of misdetection strictly between 0 and 1"),
    ):
        with pytest.raises(InputDataError, match=msg):
            t.validate()
    from typer.testing import CliRunner

    from flightmode.cli.main import app

    cases = (
        (["certify", str(tmp_path), "--target-fa-per-h", "0"], "--target-fa-per-h 0.0: must be a rate > 0"),
        (["certify", str(tmp_path)], "no flights.parquet: not a dataset made by `flightmode dataset`"),
        (["certify", str(tmp_path), "--k", "0,4"], "--k 0.0: the threshold k sigma^2 needs k > 0"),
        (["certify", str(tmp_path), "--window-s", ""], "--window-s: the grid axis is empty"),
        (["certify", str(tmp_path), "--k", "4,4"], "--k: a value is given twice"),
        (["sweep", str(tmp_path), str(tmp_path)], "several datasets: give --out"),
    )
    for args, msg in cases:
        r = CliRunner().invoke(app, args)
        assert r.exit_code == 2, (args, r.output)
        assert msg in r.output and "Traceback" not in r.output
        assert len(r.output.strip().splitlines()) == 1, r.output
    assert not any(tmp_path.iterdir())  # nothing half-written


def test_section_5_1_1_loop_raises_p_m_until_eq_14_p_fa_meets_the_target():
    """The loop on the swept flights: white static data at 100 Hz (1 s windows: thresholds near the
    chi-square's, 1.86 sigma^2 at P_M 1e-6 down to 1.29 at 0.1) and phase rows whose in-window
    fraction under k is crafted (0.5 at k 2, 0.05 at k 1.6, 0.001 at k 1.3). With T_th 4 s and W_s 1 s,
    eq. 14 gives P_FA = f^4; the target 1e-4 /h is 1e-4 / 3,600 per 1 s check, 2.8e-8: reached only
    at the grid's k 1.3 (1e-12; k 1.6 gives 6.25e-6). So the loop climbs P_M a decade at a time until
    k(P_M) <= 1.3, which the chi-square puts at P_M 0.1 (k 1.29)."""
    import pyarrow as pa
    from scipy.stats import chi2

    from flightmode.studies.certify import loop_5_1_1

    rng = np.random.default_rng(11)
    th = threshold_from_static(_static_table(rng, 400_000), 1e-6)
    frac = {2.0: 0.5, 1.6: 0.05, 1.3: 0.001}
    phases = pa.Table.from_pylist(
        [
            {
                "method": "nmv",
                "weight": 1.0,
                "window_s": 1.0,
                "k": k,
                "checks": 100_000,
                "under_all": int(f * 100_000),
            }
            for k, f in frac.items()
        ]
    )
    loop = loop_5_1_1(th, phases, ("nmv", 1.0), 1.0, Target(rate_per_h=1e-4, pm=1e-6))
    assert loop is not None and loop["pfa_max"] == pytest.approx(1e-4 / 3600.0)
    steps = loop["steps"]
    assert [s["pm"] for s in steps] == pytest.approx([1e-6 * 10**i for i in range(len(steps))])
    assert all(b["k"] <= a["k"] for a, b in zip(steps, steps[1:]))  # P_M up, threshold down
    assert loop["met"] and loop["pfa"] == pytest.approx(0.001**4)
    assert 1.2 < loop["k"] <= 1.3 and all(s["k"] > 1.3 for s in steps[:-1])
    assert loop["pm"] == pytest.approx(0.1)
    # the thresholds are the measured survival's, within a bin (2.3 %) of the exact white-noise one
    pm_axis = 1 - (1 - loop["pm"]) ** (1 / 3)
    assert loop["k"] == pytest.approx(chi2.isf(pm_axis, 99) / 100, rel=0.05)
