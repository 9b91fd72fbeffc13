"""`flightmode detect` and the detector's line in `flightmode fly`, on the pattern run."""

from __future__ import annotations

import json

import pyarrow as pa
import pyarrow.parquet as pq
from typer.testing import CliRunner

from flightmode.cli.main import app


def test_fly_runs_the_recommended_detector_and_stores_its_result(pattern_run):
    run, output = pattern_run
    assert "detector (NMV, 1 s, 4 sigma^2, 4 s): 0 false-static events in flight" in " ".join(output.split())
    d = json.loads((run / "run.json").read_text())["detector"]
    assert (d["method"], d["window_s"], d["k_sigma"], d["time_threshold_s"]) == ("nmv", 1.0, 4.0, 4.0)
    assert d["false_static_count"] == 0
    assert 0.0 <= d["response_s"] <= 10.0  # the bound after the bag truly comes to rest


def test_detect_prints_the_seed_tables(pattern_run):
    run, _ = pattern_run
    r = CliRunner().invoke(app, ["detect", str(run), "--tables"], env={"COLUMNS": "160"})
    assert r.exit_code == 0, r.output
    for title in ("Table 2 form", "Table 3 form", "Tables 4-5 form", "Turn-on response"):
        assert title in r.output
    assert "false-static events in flight" in r.output
    # EMV with another weight, a bare samples file calibrated from its own rest
    r = CliRunner().invoke(
        app,
        ["detect", str(run / "samples.parquet"), "--method", "emv", "--weight", "5", "--sigma2-from", "rest"],
        env={"COLUMNS": "160"},
    )
    assert r.exit_code == 0, r.output
    assert "EMV weight 5" in r.output


def test_detect_bad_input_is_one_line_and_exit_2(pattern_run, tmp_path):
    run, _ = pattern_run
    cases = [
        (["detect", str(tmp_path)], "no samples.parquet"),
        (["detect", str(run), "--k", "0"], "k > 0"),
        (["detect", str(run), "--window-s", "0.01"], "a variance needs >= 2"),
        (["detect", str(run), "--method", "median"], "use 'nmv' or 'emv'"),
        (["detect", str(run), "--sigma2-from", "moon"], "use one of preset, rest"),
    ]
    for args, msg in cases:
        r = CliRunner().invoke(app, args, env={"COLUMNS": "200"})
        assert r.exit_code == 2, (args, r.output)
        assert msg in r.output, (args, r.output)
    # a samples file whose stream holds a NaN: named, not silently skipped
    t = pq.read_table(run / "samples.parquet")
    x = t["acc_x_g"].to_numpy().copy()
    x[1234] = float("nan")
    bad = tmp_path / "samples.parquet"
    pq.write_table(t.set_column(t.schema.get_field_index("acc_x_g"), "acc_x_g", pa.array(x)), bad)
    r = CliRunner().invoke(app, ["detect", str(bad), "--sigma2-from", "rest"], env={"COLUMNS": "200"})
    assert r.exit_code == 2 and "NaN or inf in the stream at sample 1234" in r.output
