"""Seed 001's Monte Carlo evaluation (section 3.1.2): the threshold sweep against brute force, the
ROC area of a perfect and of a random detector, the grid search on a case whose best point is known,
and a tiny study that gives the same numbers twice, in any run order and on Dask."""

from __future__ import annotations

import itertools
import json
import os

import numpy as np
import pytest

from flightmode.detector.activity import montecarlo as mc
from flightmode.detector.activity.common import decide
from flightmode.errors import DetectorError

FS = 50.0


# ---------------------------------------------------------------- sweep, correlation, ROC, AUC
def test_sweep_equals_the_decision_rule_sample_by_sample():
    rng = np.random.default_rng(0)
    truth = rng.random(500) < 0.4
    merit = np.round(rng.normal(truth * 1.0, 1.0), 1)  # rounded: many ties
    merit[:7] = np.nan  # a detector's warm-up: active
    s = mc.sweep(merit, truth)
    assert np.all(np.diff(s.thresholds) > 0)
    for k in range(0, s.thresholds.size, 3):
        marker = decide(merit, s.thresholds[k]).astype(bool)
        assert s.accuracy[k] == np.mean(marker == truth)  # exact: the same counts
        r = np.corrcoef(marker, truth)[0, 1] if 0 < marker.sum() < marker.size else 0.0
        assert s.correlation[k] == pytest.approx(r, abs=1e-12)  # phi == Pearson's r, to rounding
    # the exact sweep holds every partition: no threshold does better
    brute = max(np.mean(decide(merit, t).astype(bool) == truth) for t in np.unique(merit[np.isfinite(merit)]))
    assert s.accuracy.max() >= brute


def test_auc_of_a_perfect_detector_is_one_and_of_its_inverse_zero():
    truth = np.zeros(400, bool)
    truth[100:250] = True
    merit = np.where(truth, 5.0, 1.0) + np.linspace(0, 0.1, 400)
    fpr, tpr = mc.roc_curve(merit, truth)
    assert mc.auc(fpr, tpr) == 1.0  # exact: the trapezoids' heights are 0 or 1
    fpr, tpr = mc.roc_curve(-merit, truth)
    assert mc.auc(fpr, tpr) == 0.0


def test_auc_of_a_random_detector_is_one_half_and_equals_mann_whitney():
    from scipy.stats import mannwhitneyu

    rng = np.random.default_rng(1)
    truth = rng.random(4000) < 0.5
    merit = np.round(rng.normal(size=4000), 2)  # ties with the truth's classes mixed
    fpr, tpr = mc.roc_curve(merit, truth)
    a = mc.auc(fpr, tpr)
    p, n = truth.sum(), (~truth).sum()
    # under the null the AUC (Mann-Whitney U / (P N)) has sd sqrt((P + N + 1) / (12 P N)) ~ 0.0091:
    # 4 sd
    assert abs(a - 0.5) < 4 * np.sqrt((p + n + 1) / (12 * p * n))
    u = mannwhitneyu(merit[truth], merit[~truth]).statistic
    assert a == pytest.approx(u / (p * n), abs=1e-12)  # trapezoids on the full ROC = U with ties halved


def test_roc_on_a_grid_takes_the_top_of_a_vertical_step():
    fpr = np.array([0.0, 0.0, 0.5, 0.5, 1.0])
    tpr = np.array([0.0, 0.6, 0.8, 1.0, 1.0])
    assert np.array_equal(mc.roc_on_grid(fpr, tpr, np.array([0.0, 0.25, 0.5, 1.0])), [0.6, 0.8, 1.0, 1.0])


# ---------------------------------------------------------------- the grid search on a known case
def _known_case(k: int = 7, blocks: int = 3):
    """|a| along z: still (exactly 1 g) and active blocks alternating 1 +- 0.5 g, each active block
    with two runs of k samples of 1.25 g (a pause of the alternation; a value neither neighbour has).
    AMVD (eq. 1, a causal window of w) is then 0 exactly on windows of still samples or of one run,
    > 0 on any other. Per window w:
    the w - 1 warm-up samples (NaN: active) and the w - 1 samples after each block are false
    activity, and the k - w + 1 windows inside each run (w <= k) false inactivity:
    errors(w) = (w - 1)(blocks + 1) + 2 blocks max(0, k - w + 1); at threshold just above 0."""
    parts, truth = [np.ones(60)], [np.zeros(60, bool)]
    for _ in range(blocks):
        alt = 1.0 + 0.5 * (-1.0) ** np.arange(20)
        block = np.concatenate([alt, np.full(k, 1.25), alt, np.full(k, 1.25), alt])
        parts += [block, np.ones(60)]
        truth += [np.ones(block.size, bool), np.zeros(60, bool)]
    z = np.concatenate(parts)
    acc = np.column_stack([np.zeros_like(z), np.zeros_like(z), z])
    return np.arange(z.size) / FS, acc, np.concatenate(truth), k, blocks


def test_grid_search_finds_the_known_best_window_and_accuracy():
    t, acc, truth, k, blocks = _known_case()
    n = truth.size
    windows = (16, 2, 8, 4)  # any order: searched ascending
    b = mc.grid_search("amvd", None, t, acc, None, truth, [(w, None) for w in sorted(windows)], fs_hz=FS)

    def errors(w):
        return (w - 1) * (blocks + 1) + 2 * blocks * max(0, k - w + 1)

    # the surface is the formula at every window (exact: counts over n)
    assert [(w, acc_w) for w, _, acc_w in b.surface] == [(w, 1 - errors(w) / n) for w in sorted(windows)]
    assert b.window == 8 and b.shift is None  # 40, 36, 28, 60 errors for w = 2, 4, 8, 16
    assert b.accuracy == 1 - 28 / n
    # the threshold separates the zero merits from the smallest positive one (midpoint of 0 and it)
    pos = b.merit[np.isfinite(b.merit) & (b.merit > 0)]
    assert 0 < b.threshold < pos.min()
    # and a coarse explicit threshold grid containing a separating value finds the same point
    c = mc.grid_search(
        "amvd",
        None,
        t,
        acc,
        None,
        truth,
        [(w, None) for w in sorted(windows)],
        fs_hz=FS,
        thresholds=[-1.0, b.threshold, 10.0],
    )
    assert (c.window, c.accuracy, c.threshold) == (8, b.accuracy, b.threshold)


def test_grid_search_without_points_says_so():
    t, acc, truth, _, _ = _known_case()
    with pytest.raises(DetectorError, match="points is empty"):  # was a TypeError on None
        mc.grid_search("amvd", None, t, acc, None, truth, [], fs_hz=FS)


# ---------------------------------------------------------------- a tiny study
TINY = mc.MonteCarloConfig(
    duration_s=30.0,
    bench_s=4.0,
    grid=mc.Grid(
        detectors=("shod", "mbgtd"),
        signals=("acc", "product"),
        magnitude_windows=(5, 10),
        memory_windows=(4, 8),
    ),
)


def _same(a: mc.MonteCarloResult, b: mc.MonteCarloResult) -> bool:
    # json: NaN-safe (NaN != NaN) and exact (floats written with their shortest round-trip repr)
    rows_equal = json.dumps(a.rows, default=str) == json.dumps(b.rows, default=str)
    return (
        rows_equal
        and a.roc_tpr.keys() == b.roc_tpr.keys()
        and all(np.array_equal(a.roc_tpr[k], b.roc_tpr[k]) for k in a.roc_tpr)
    )


@pytest.fixture(scope="module")
def tiny():
    return mc.run_montecarlo(3, seed=5, config=TINY)


def test_tiny_study_is_reproducible_in_any_run_order(tiny):
    assert len(tiny.rows) == 3 * 3  # 3 runs x (SHOD, MBGTD-Acc., MBGTD-Prod)
    assert [r["run"] for r in tiny.rows] == [0, 0, 0, 1, 1, 1, 2, 2, 2]
    assert _same(tiny, mc.run_montecarlo(3, seed=5, config=TINY))
    assert _same(tiny, mc.run_montecarlo(3, seed=5, config=TINY, order=[2, 0, 1]))
    # a run is regenerated alone (its generator depends on its index only)
    alone = mc.evaluate_run(1, 5, TINY)["rows"]
    assert json.dumps(alone, default=str) == json.dumps([r for r in tiny.rows if r["run"] == 1], default=str)
    other = mc.run_montecarlo(3, seed=6, config=TINY)
    assert not _same(tiny, other)


def test_tiny_study_on_dask_equals_in_process(tiny):
    from dask.distributed import Client, LocalCluster

    with (
        LocalCluster(n_workers=1, threads_per_worker=1, processes=False, dashboard_address=None) as cluster,
        Client(cluster) as client,
    ):
        assert _same(tiny, mc.run_montecarlo(3, seed=5, config=TINY, client=client))


def test_tiny_study_on_its_own_two_worker_cluster_equals_in_process(tiny):
    """run_montecarlo(workers=2) opens flightmode.cluster's LocalCluster itself (the CLI's path)."""
    done = []
    assert _same(tiny, mc.run_montecarlo(3, seed=5, config=TINY, workers=2, on_run=done.append))
    assert sorted(done) == [0, 1, 2]  # every run reported once, by its index
    with pytest.raises(mc.DetectorError, match="workers = 0: must be a positive integer"):
        mc.run_montecarlo(3, seed=5, config=TINY, workers=0)


def test_summary_and_files(tiny, tmp_path):
    rows = mc.summary(tiny)
    assert [(r["table"], r["label"]) for r in rows] == [(1, "SHOD"), (4, "MBGTD-Acc."), (4, "MBGTD-Prod")]
    assert sorted(r["auc_rank"] for r in rows) == [1, 2, 3]
    shod = rows[0]
    accs = [r["accuracy"] for r in tiny.rows if r["detector"] == "shod"]
    assert shod["accuracy_mean"] == pytest.approx(np.mean(accs), rel=1e-15)
    assert shod["accuracy_std"] == pytest.approx(np.std(accs, ddof=1), rel=1e-12)
    assert (shod["paper_accuracy_mean"], shod["paper_auc"], shod["paper_auc_rank"]) == (0.9817, 0.9880, 1)
    text = mc.format_tables(tiny)
    assert "Table 1" in text and "Table 13" in text and "0.9817 +- 0.0124" in text
    paths = mc.write_results(tiny, tmp_path)
    import pyarrow.parquet as pq

    assert pq.read_table(paths["runs"]).num_rows == 9
    assert pq.read_table(paths["tables"]).num_rows == 3
    with open(paths["results"]) as f:
        assert json.load(f)["n_runs"] == 3
    for name in ("roc_best8", "roc_table1", "roc_table4"):
        with open(paths[name], "rb") as f:
            assert f.read(8) == b"\x89PNG\r\n\x1a\n"
    assert not [f for f in os.listdir(tmp_path) if ".tmp-" in f]  # every temporary renamed


# ---------------------------------------------------------------- the paper's numbers
def test_the_papers_tables_cover_every_default_case_and_rank_by_auc():
    cases = mc.Grid().cases()
    assert len(cases) == 24 and all(mc.paper_row(*c) is not None for c in cases)
    by_rank = sorted(mc.PAPER_TABLES, key=lambda p: p.auc_rank)
    assert [p.auc_rank for p in by_rank] == list(range(1, 25))
    assert all(a.auc > b.auc for a, b in itertools.pairwise(by_rank))  # Table 13's ranks order its AUCs
    assert mc.paper_row("shod", None).accuracy == (0.9817, 0.0124)


def test_a_bad_grid_fails_loudly():
    from flightmode.errors import DetectorError

    with pytest.raises(DetectorError, match='did you mean "mbcd"'):
        mc.run_montecarlo(1, config=mc.MonteCarloConfig(grid=mc.Grid(detectors=("mbcdd",))))
    with pytest.raises(DetectorError, match="permutation"):
        mc.run_montecarlo(2, config=TINY, order=[0, 0])


def test_the_cli_runs_the_study_and_prints_the_paper_beside_it(tmp_path):
    """`flightmode activity synth`: one run in this process, Table 13 printed with the paper's column,
    the files written; a run count of 0 is refused in one line."""
    from typer.testing import CliRunner

    from flightmode.cli.main import app

    args = ["activity", "synth", "--n", "1", "--workers", "1", "--grid", "narrow", "--window", "centred"]
    r = CliRunner().invoke(app, [*args, "--compare", "--out", str(tmp_path / "mc")])
    assert r.exit_code == 0, r.output
    assert "MBCD-Acc." in r.output and (tmp_path / "mc" / "results.json").exists()
    # --compare: the z-scores, the AUC rank correlation, the grid edges (the narrow grid's 3-120)
    assert "z500" in r.output and "Spearman's rho" in r.output and "3-120" in r.output
    with open(tmp_path / "mc" / "results.json") as f:
        assert json.load(f)["config"]["alignment"] == "centred"
    r = CliRunner().invoke(app, ["activity", "synth", "--n", "0"])
    assert (
        r.exit_code == 2 and r.output.strip() == "error: --n 0: the number of runs must be a positive integer"
    )


def test_the_cli_scales_the_periods_and_restricts_the_detectors(tmp_path):
    """--period-scale k multiplies the still, activity and seated/lying ranges and the record's length
    by k and nothing else (the study's config in results.json); --detectors grid-searches only those;
    a bad factor or detector is one line, exit 2."""
    from typer.testing import CliRunner

    from flightmode.cli.main import app
    from flightmode.detector.activity.synth import DEFAULT_RANGES

    base = ["activity", "synth", "--n", "1", "--detectors", "amd,shod", "--window", "centred", "--json"]
    r = CliRunner().invoke(app, [*base, "--period-scale", "4", "--out", str(tmp_path / "x4")])
    assert r.exit_code == 0, r.output
    d = json.loads(r.output[r.output.index("{") :])
    assert [t["label"] for t in d["tables"]] == ["AMD", "SHOD"]
    with open(tmp_path / "x4" / "results.json") as f:
        cfg = json.load(f)["config"]
    assert cfg["duration_s"] == 480.0
    for name, v in cfg["ranges"].items():
        v0 = getattr(DEFAULT_RANGES, name)
        k = 4.0 if name in ("still_s", "activity_s", "posture_rest_s") else 1.0
        assert v == [v0[0] * k, v0[1] * k], name
    for bad, msg in (("0", "--period-scale 0.0"), ("nan", "--period-scale nan")):
        r = CliRunner().invoke(app, ["activity", "synth", "--n", "1", "--period-scale", bad])
        assert r.exit_code == 2 and r.output.strip().startswith(f"error: {msg}"), r.output
    r = CliRunner().invoke(app, ["activity", "synth", "--n", "1", "--detectors", "amdx"])
    assert r.exit_code == 2 and 'did you mean "amd"' in r.output


def test_the_cli_takes_a_sequence_of_activities_in_order(tmp_path):
    """--mix sequence with --activities takes them in order, cycling: given the Figure 2 sequence it is
    --mix figure2, number for number (the same draws in the same order); without --activities, or
    --activities beside --mix figure2, it is one line, exit 2."""
    from typer.testing import CliRunner

    from flightmode.cli.main import app
    from flightmode.detector.activity.synth import FIGURE2_SEQUENCE

    base = ["activity", "synth", "--n", "1", "--seed", "3", "--detectors", "amd", "--json"]
    docs = []
    for extra in (["--mix", "figure2"], ["--mix", "sequence", "--activities", ",".join(FIGURE2_SEQUENCE)]):
        r = CliRunner().invoke(app, [*base, *extra])
        assert r.exit_code == 0, r.output
        docs.append(json.loads(r.output[r.output.index("{") :])["tables"])
    assert docs[0] == docs[1]
    r = CliRunner().invoke(app, [*base, "--mix", "sequence", "--activities", "walking,constant_rate"])
    assert r.exit_code == 0, r.output
    for bad, msg in (
        (["--mix", "sequence"], "--mix sequence takes the activities in order"),
        (["--mix", "figure2", "--activities", "walking"], "--mix figure2 fixes the activities"),
    ):
        r = CliRunner().invoke(app, [*base, *bad])
        assert r.exit_code == 2 and r.output.strip().startswith(f"error: {msg}"), r.output


def test_the_errors_by_period_add_up_to_the_accuracy_and_show_what_each_input_cannot_see():
    """Each run row's err_<kind> shares sum to 1 - accuracy (to rounding: they count the same wrong
    samples). And the physics of the inputs, on the Figure 2 sequence (FSD, centred, 4 runs): |w| alone
    (Ang.) cannot see the constant acceleration (no rotation: at least 90 % of its samples missed; the
    centred window's reach into the still periods either side marks a few), and never errs in a jump's
    flight; |a| |w| (Prod) reads near 0 in free fall, so it misses flight samples where Ang. sees them
    all: 39 % of them in these four runs on this grid (a fifth on the full grid; per run 0.1 % to 1.3 % of
    a record's samples), bounded at 10 %, under a quarter of what it is."""
    from flightmode.detector.activity.synth import FIGURE2_SEQUENCE, PERIOD_KINDS, synthesize
    from flightmode.streams import as_streams

    cfg = mc.MonteCarloConfig(
        alignment="centred",
        activities=FIGURE2_SEQUENCE,
        sequence=True,
        # FSD's best windows on this study are 2-8 samples at shift 1-2 (docs/seed001_tables_n500.txt):
        # that corner of the grid, to keep the test short
        grid=mc.Grid(
            detectors=("fsd",), signals=("gyr", "product"), spectrum_windows=(2, 4, 8), spectrum_shifts=(1, 2)
        ),
    )
    res = mc.run_montecarlo(4, seed=1, config=cfg)
    kinds = [f"err_{k}" for k in PERIOD_KINDS]
    for r in res.rows:
        assert sum(r[k] for k in kinds) == pytest.approx(1.0 - r["accuracy"], abs=1e-12)
        assert 0.0 <= r["err_jumping_flight"] <= r["err_jumping"]
    acc_share = flight_share = 0.0
    for i in range(4):  # the same records, drawn as evaluate_run draws them
        streams = as_streams(mc._run_generator(1, i))
        rec = synthesize(
            streams.rng("recording"),
            cfg.duration_s,
            activities=FIGURE2_SEQUENCE,
            sequence=True,
            fs_hz=cfg.fs_hz,
            gravity_axis=cfg.gravity_axis,
            sigma_acc_g=cfg.sigma_acc_g,
            sigma_gyr_dps=cfg.sigma_gyr_dps,
            acc_range_g=cfg.acc_range_g,
            gyr_range_dps=cfg.gyr_range_dps,
        )
        kind = mc.period_index(rec.periods, rec.marker.size)
        acc_share += (kind == PERIOD_KINDS.index("constant_acc")).mean() / 4
        flight = (kind == PERIOD_KINDS.index("jumping")) & (
            np.linalg.norm(rec.acc_g, axis=1) < mc.JUMP_FLIGHT_G
        )
        flight_share += flight.mean() / 4
    ang = [r for r in res.rows if r["signal"] == "gyr"]
    prod = [r for r in res.rows if r["signal"] == "product"]
    assert acc_share > 0.02 and flight_share > 0.01
    assert np.mean([r["err_constant_acc"] for r in ang]) >= 0.9 * acc_share
    assert all(r["err_jumping_flight"] == 0.0 for r in ang)
    assert np.mean([r["err_jumping_flight"] for r in prod]) >= 0.1 * flight_share
