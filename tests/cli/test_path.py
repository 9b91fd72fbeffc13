"""`flightmode path` (the whole-flight drift and its explanation) and the ground-roll table of
`flightmode fly`, on the pattern run."""

from __future__ import annotations

import json
import math

from typer.testing import CliRunner

from flightmode.cli.main import app


def test_path_prints_the_aided_error_first_and_the_drift_laws(pattern_run):
    """(Moved from `flightmode fly`'s output, which now shows the ground rolls: the same assertions on
    `flightmode path`'s paragraph.)"""
    run, _ = pattern_run
    r = CliRunner().invoke(app, ["path", str(run), "--sensor", "run"], env={"COLUMNS": "200"})
    assert r.exit_code == 0, r.output
    text = " ".join(r.output.split())
    info = json.loads((run / "run.json").read_text())
    rows = {r["method"].split(" ")[0]: r for r in info["path"]}
    laws = info["path_laws_m"]
    # seed 002 eq. 15-16: the tridiagonal spline is pinned to both end positions, so its error at the
    # destination gate is rounding only (1 mm is a million times the flight's scale of metres)
    assert rows["tridiagonal"]["final_m"] < 1e-3
    # the random-walk law, computed here from the LIS302DL's noise (seed 000 Table 1: 2.23 mg) at
    # 100 Hz over the span: sigma_x(t) = sigma_a sqrt(dt) t^1.5 / sqrt(3), sigma_a being the white
    # level with the noise's 0 Hz density: the noise is white (its amplitude modulated: that leaves
    # the density flat), so sigma_a is the 2.23 mg itself
    sigma_a = 2.23e-3 * 9.80665
    expect = sigma_a * math.sqrt(1 / 100.0) * laws["span_s"] ** 1.5 / math.sqrt(3.0)
    assert laws["random_walk"] == expect or abs(laws["random_walk"] / expect - 1) < 1e-12
    # a constant offset b integrates to b t^2 / 2: the unit's own offset (run.json) over the span
    b = math.sqrt(sum(x * x for x in info["sensor"]["unit"]["offset_g"])) * 9.80665
    assert abs(laws["offset"] / (0.5 * b * laws["span_s"] ** 2) - 1) < 1e-12
    # the printed figures are those stored, the aided (gate-bounded) one before the unaided one
    aided = text.index(f"max error {rows['tridiagonal']['max_m']:,.0f} m")
    unaided = text.index(f"final error {rows['recurrence']['final_m']:,.0f} m")
    assert aided < unaided
    assert f"{laws['random_walk']:,.0f} m RMS" in text and f"{laws['offset']:,.0f} m" in text


def test_path_table_agrees_with_the_run_and_sensor_error_dominates(pattern_run):
    run, _ = pattern_run
    r = CliRunner().invoke(app, ["path", str(run), "--sensor", "run,ideal", "--json"])
    assert r.exit_code == 0, r.output
    rows = {(x["source"], x["method"]): x["max_m"] for x in json.loads(r.output)}
    info = json.loads((run / "run.json").read_text())
    # re-sensing with the run's own preset and streams gives its samples again, so the rows for the
    # run's sensor are the run.json's; not bit for bit: `path` reads the truth back from
    # truth.parquet, which stores attitudes and forces in float32 (relative rounding 6e-8), and the
    # frames built from them move the error by a few parts in 1e7 (1e-5 leaves a factor 20)
    for stored in info["path"]:
        got = rows[(stored["source"], stored["method"])]
        assert abs(got / stored["max_m"] - 1) < 1e-5, (stored, got)
    # an ideal accelerometer (no noise, offset, gain or quantisation) leaves only the truth-aided
    # frames' own approximations: its path error is orders of magnitude below the real unit's,
    # whose zero-g offset alone drifts by b t^2 / 2 (hundreds of km here)
    ideal = rows[("ideal, truth-aided", "tridiagonal (gate positions)")]
    real = rows[("lis302dl-logged16, truth-aided", "tridiagonal (gate positions)")]
    assert ideal < 1e-3 * real
    # the truth's own acceleration, integrating samples, rebuilds the path to metres
    assert rows[("truth acceleration", "tridiagonal (gate positions)")] < 1.0
    r = CliRunner().invoke(app, ["path", str(run)], env={"COLUMNS": "200"})  # the table, for people
    assert r.exit_code == 0 and "recurrence + ZUPT" in r.output and "tilt-only (vertical only)" in r.output
    r = CliRunner().invoke(app, ["path", str(run), "--sensor", "lis303"], env={"COLUMNS": "200"})
    assert r.exit_code == 2 and "unknown sensor preset 'lis303'" in r.output


def test_fly_prints_the_ground_rolls_against_the_truth_and_not_the_drift(pattern_run, tmp_path):
    run, output = pattern_run
    text = " ".join(output.split())
    info = json.loads((run / "run.json").read_text())
    rolls = info["ground_rolls"]
    assert [c["segment"] for c in rolls] == ["takeoff roll", "rollout"]
    # the table's figures are run.json's, rounded as printed: lengths to the metre, speeds to 0.1 m/s
    for c in rolls:
        row = (
            f"{c['segment']} {c['est_length_m']:,.0f} {c['true_length_m']:,.0f} {c['length_error_m']:+,.0f} "
            f"{c['length_error_pct']:+.1f} {c['est_speed_mps']:.1f} {c['true_speed_mps']:.1f} "
            f"{c['speed_error_mps']:+.1f}"
        )
        assert row in text, row
    assert f"exit speed {rolls[1]['known_speed_mps']:.1f} m/s" in text
    # the whole-flight drift is no longer fly's: it points to `flightmode path`
    rows = {r["method"].split(" ")[0]: r for r in info["path"]}
    assert f"max error {rows['tridiagonal']['max_m']:,.0f} m" not in text and "final error" not in text
    assert f"flightmode path {run}" in text
    # --json carries the same numbers (the same scenario and seed fly the same flight, bit for bit)
    r = CliRunner().invoke(app, ["fly", "pattern", "--out", str(tmp_path), "--no-rrd", "--json"])
    assert r.exit_code == 0, r.output
    assert json.loads(r.output)["ground_rolls"] == rolls
