"""`flightmode path` and the path line of `flightmode fly`, on the pattern run."""

from __future__ import annotations

import json

from typer.testing import CliRunner

from flightmode.scenarios.cli import app


def test_fly_reports_the_path_error_and_stores_it(pattern_run):
    run, output = pattern_run
    assert "path from acceleration (truth-aided frames)" in " ".join(output.split())
    rows = json.loads((run / "run.json").read_text())["path"]
    methods = {r["method"].split(" ")[0] for r in rows}
    assert {"tridiagonal", "recurrence"} <= methods
    tri = next(r for r in rows if r["method"].startswith("tridiagonal"))
    assert tri["final_m"] < 1e-3  # the tridiagonal method is pinned to the destination gate
    assert tri["max_m"] > 0.0


def test_path_prints_the_table(pattern_run):
    run, _ = pattern_run
    r = CliRunner().invoke(app, ["path", str(run), "--sensors", "run,ideal"], env={"COLUMNS": "200"})
    assert r.exit_code == 0, r.output
    for text in ("truth acceleration", "point samples", "ideal, truth-aided", "lis302dl-logged16, truth-aided",
                 "recurrence + ZUPT", "tilt-only (vertical only)"):
        assert text in r.output, text
    r = CliRunner().invoke(app, ["path", str(run), "--sensors", "lis303"], env={"COLUMNS": "200"})
    assert r.exit_code == 2 and "unknown sensor preset" in r.output
