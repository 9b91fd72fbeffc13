"""`flightmode detect` with its defaults on what a user has: one flight of a dataset (its bench
calibration regenerated from the manifest's scenario and seed) and a flight flown with a gyroscope
(its gyroscope on the bench too); and --json printing the numbers of the table."""

from __future__ import annotations

import json

import pytest
from typer.testing import CliRunner

from flightmode.cli.main import app


@pytest.fixture(scope="module")
def gyro_run(tmp_path_factory, fly_cached):
    """The pattern flight sensed with a BMI270 gyroscope beside the accelerometer, as `flightmode fly
    pattern --gyro` writes it."""
    from flightmode.runs import pipeline

    sc, track = fly_cached("pattern")
    out = tmp_path_factory.mktemp("gyro")
    r = pipeline.run(
        sc, track=track, out=out, gyro=True, rrd=False, stages=("fly", "sense", "detect", "write")
    )
    return r.written["run_json"].parent


@pytest.mark.slow
def test_a_gyroscope_method_runs_with_the_defaults_on_a_gyroscope_flight(gyro_run):
    r = CliRunner().invoke(app, ["detect", str(gyro_run), "--method", "ared"], env={"COLUMNS": "200"})
    assert r.exit_code == 0, r.output
    text = " ".join(r.output.split())
    assert (
        "bench recording of this" in text
        and "the gyroscope's" in text
        and "at rest before the flight" in text
    )
    # --json gives the table's numbers
    j = CliRunner().invoke(app, ["detect", str(gyro_run), "--method", "ared", "--json"])
    assert j.exit_code == 0, j.output
    d = json.loads(j.output)
    e = d["evaluation"]
    assert f"{e['false_static_count']} ({e['false_static_s']:g} s in all)" in text
    assert f"{d['rest']['threshold']:.4g}" in text
    # the gyroscope's bench is its rest before the flight: the same gyroscope figures as --sigma2-from rest
    # give the same rest level to the 4 digits printed when the accelerometer plays no part (ared reads
    # the gyroscope only)
    rest = json.loads(
        CliRunner()
        .invoke(app, ["detect", str(gyro_run), "--method", "ared", "--sigma2-from", "rest", "--json"])
        .output
    )
    assert rest["evaluation"]["false_static_count"] == e["false_static_count"]


@pytest.mark.slow
def test_detect_on_a_dataset_flight_regenerates_its_bench_recording(reference):
    """The dataset keeps no run.json; detect rebuilds the unit and its bench recording from the
    manifest's scenario and seed, so the default (--sigma2-from preset) gives exactly the figures
    the flight's own detector wrote into the manifest (the session's reference dataset: tests/conftest.py)."""
    import pyarrow.parquet as pq

    ds = reference
    row = pq.read_table(ds / "flights.parquet").to_pylist()[0]
    assert row["status"] == "ok", row
    j = CliRunner().invoke(app, ["detect", str(ds), "--flight", "0", "--json"])
    assert j.exit_code == 0, j.output
    d = json.loads(j.output)
    e = d["evaluation"]
    assert "bench calibration" in d["calibration_source"]
    # exactly the flight's own detector (same unit, same bench stream, same samples)
    assert e["false_static_count"] == row["detector_false_static_count"]
    assert e["in_flight_checks"] == row["detector_in_flight_checks"]
    assert e["response_s"] == row["detector_response_s"]
    # the table prints the same numbers; the flight id works as the index does
    r = CliRunner().invoke(app, ["detect", str(ds), "--flight", row["flight_id"]], env={"COLUMNS": "200"})
    assert r.exit_code == 0, r.output
    text = " ".join(r.output.split())
    assert f"{e['false_static_count']} ({e['false_static_s']:g} s in all)" in text
    assert f"{e['in_flight_checks']:,}" in text
    bad = CliRunner().invoke(app, ["detect", str(ds), "--flight", "7"])
    assert bad.exit_code == 2 and "no flight '7'" in bad.output


def test_a_method_name_fails_loudly_with_the_nearest():
    from flightmode.detector import methods
    from flightmode.errors import DetectorError

    assert methods.get("EMV").kind == "moving_variance" and methods.get("shod").needs_gyro
    with pytest.raises(DetectorError, match='did you mean "ared"'):
        methods.get("arde")


def test_the_grid_pairs_emv_weights_only_with_emv():
    from flightmode.detector.grid import grid_from_text, grid_of, parse_axis

    g = grid_from_text("nmv,emv,emv+baro", "1,5", "1", "4", "4")
    assert g.methods == (("nmv", 1.0), ("emv", 1.0), ("emv", 5.0), ("emv+baro", 1.0), ("emv+baro", 5.0))
    assert parse_axis("2:3:0.5", "--k") == (2.0, 2.5, 3.0)  # stop included
    assert (
        len(grid_of("nmv,emv", (5.0,), (0.5, 1, 2), parse_axis("2:8:0.5", "--k"), parse_axis("1:8:1", "x")))
        == 624
    )
