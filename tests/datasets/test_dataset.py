"""flightmode dataset on real Dask clusters: a LocalCluster, a SIGKILL mid-run and --resume, a real
`dask scheduler` with two `dask worker` processes on 127.0.0.1, a failing flight, the dataset card's
four loaders, and the one-line refusals."""

from __future__ import annotations

import hashlib
import json
import os
import re
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

from flightmode.datasets.make import DatasetError, check_request, make_dataset, read_manifest
from tests.hops import HOPS, N

# one worker runs this module (pytest-xdist --dist loadgroup): the reference dataset is made once, and
# two clusters of its own never compete with each other for the two cores
pytestmark = pytest.mark.xdist_group("dataset")


def _files(root: Path) -> dict[str, str]:
    """Every file under samples/ and truth/ (hidden temporary files included) -> SHA-256."""
    out = {}
    for part in ("samples", "truth"):
        for p in sorted((root / part).rglob("*")):
            if p.is_file():
                out[str(p.relative_to(root))] = hashlib.sha256(p.read_bytes()).hexdigest()
    return out


def _manifest(root: Path):
    import pyarrow.parquet as pq

    return pq.read_table(root / "flights.parquet")


@pytest.mark.slow
def test_sigkill_mid_run_then_resume_gives_the_uninterrupted_dataset(tmp_path, family_file, reference):
    out = tmp_path / "ds"
    cmd = ["flightmode", "dataset", str(family_file), "--n", str(N), "--out", str(out), "--workers", "1"]
    proc = subprocess.Popen(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, start_new_session=True)
    try:
        t0 = time.monotonic()
        while not read_manifest(out) if (out / "flights.parquet").exists() else True:
            assert proc.poll() is None, "the command ended before its first flight was recorded"
            assert time.monotonic() - t0 < 300, "no flight recorded in 300 s"
            time.sleep(0.2)
    finally:
        os.killpg(proc.pid, signal.SIGKILL)  # the command and its cluster's processes, mid-run
        proc.wait()
    done = read_manifest(out)
    assert 1 <= len(done) < N  # killed with the second flight on its way (one worker: one at a time)
    # what a kill inside a write leaves: a half-written file beside the data (planted: the kill above
    # may fall between writes)
    part = out / "samples" / "aircraft=A320" / ".part-000001.parquet.tmp-1234-deadbeef"
    part.parent.mkdir(parents=True, exist_ok=True)
    part.write_bytes(b"PAR1 half")
    subprocess.run([*cmd, "--resume"], check=True, capture_output=True)
    assert not list(out.rglob(".*.tmp-*"))  # no half-written file left
    assert _files(out) == _files(reference)  # exactly N flights, byte-identical files, no duplicate
    assert (out / "flights.parquet").read_bytes() == (reference / "flights.parquet").read_bytes()
    assert sorted(read_manifest(out)) == list(range(N))
    with pytest.raises(DatasetError, match=r"holds flights up to member 1: resume with --n 2 or more"):
        check_request(str(family_file), 1, out, resume=True)


@pytest.mark.slow
def test_a_scheduler_and_two_workers_on_localhost_give_the_same_dataset(tmp_path, family_file, reference):
    sched_file = tmp_path / "scheduler.json"
    procs = [
        subprocess.Popen(
            [
                "dask",
                "scheduler",
                "--host",
                "127.0.0.1",
                "--port",
                "0",
                "--dashboard-address",
                "127.0.0.1:0",
                "--scheduler-file",
                str(sched_file),
            ],
            stdout=subprocess.DEVNULL,
            stderr=subprocess.DEVNULL,
            start_new_session=True,
        )
    ]
    try:
        t0 = time.monotonic()
        while not sched_file.exists():
            assert time.monotonic() - t0 < 60, "dask scheduler did not start"
            time.sleep(0.2)
        time.sleep(0.2)  # the file is written whole before its address is used
        address = json.loads(sched_file.read_text())["address"]
        assert address.startswith("tcp://127.0.0.1:")
        for _ in range(2):
            procs.append(
                subprocess.Popen(
                    [
                        "dask",
                        "worker",
                        address,
                        "--nthreads",
                        "1",
                        "--host",
                        "127.0.0.1",
                        "--no-dashboard",
                        "--memory-limit",
                        "0",
                    ],
                    stdout=subprocess.DEVNULL,
                    stderr=subprocess.DEVNULL,
                    start_new_session=True,
                )
            )
        out = tmp_path / "ds"
        r = subprocess.run(
            [
                "flightmode",
                "dataset",
                str(family_file),
                "--n",
                str(N),
                "--out",
                str(out),
                "--scheduler",
                address,
                "--rrd",
            ],
            capture_output=True,
            text=True,
            timeout=600,
        )
        assert r.returncode == 0, r.stdout + r.stderr
    finally:
        for p in procs:
            os.killpg(p.pid, signal.SIGKILL)
            p.wait()
    assert _files(out) == _files(reference)  # the same Parquet files, byte for byte
    # the manifests differ only by the recordings' names (--rrd here)
    ours, ref = _manifest(out), _manifest(reference)
    assert ours.drop_columns(["rrd_file"]).equals(ref.drop_columns(["rrd_file"]))
    # --rrd: each flight's recording for offline replay, the member's run, no scratch folder left
    from rerun.chunk import RrdReader

    from flightmode.scenarios.family import Family

    fam = Family.from_toml(family_file)
    for row in read_manifest(out).values():
        rec = RrdReader(out / row["rrd_file"]).recordings()[0]
        assert rec.recording_id == fam.member(row["index"]).run_id
    assert not list(out.glob(".rrd-*"))


@pytest.mark.slow
def test_failed_flights_are_retried_once_and_recorded_without_stopping(tmp_path, family_file):
    out = tmp_path / "ds"
    # a wall-time limit no flight can meet: every flight fails, twice, and the dataset still completes
    rows = make_dataset(str(family_file), 1, out, workers=1, flight_timeout_s=0.3)
    assert sorted(rows) == [0]
    for r in rows.values():
        assert r["status"] == "failed" and r["attempts"] == 2
        assert r["error"].startswith("FlightTimeoutError: flight") and "0.3 s wall-time limit" in r["error"]
    m = read_manifest(out)
    assert [m[0]["status"]] == ["failed"]
    assert [p.name for p in out.rglob("*.parquet")] == ["flights.parquet"]  # no data file of a failed flight
    from flightmode.datasets.make import manifest_schema

    assert _manifest(out).schema.equals(manifest_schema())  # every column, typed, even with no success
    assert "0 ok, 1 failed" in (out / "README.md").read_text()
    # the time limit may change on --resume (it changes no file): the failure is tried again
    rows = make_dataset(str(family_file), 1, out, workers=1, flight_timeout_s=0.4, resume=True)
    assert [r["attempts"] for r in rows.values()] == [2]
    with pytest.raises(DatasetError, match=r"resume with the same --truth and --rrd"):
        check_request(str(family_file), 1, out, resume=True, truth="full")
    check_request(str(family_file), 1, out, resume=True, flight_timeout_s=10.0)


@pytest.mark.slow  # the reference dataset: two route hops gate to gate on Dask workers
def test_the_manifest_records_how_each_bag_lay_in_flight(reference):
    from flightmode.datasets.make import stowage_of_row
    from flightmode.scenarios.scenario import Scenario

    for row in read_manifest(reference).values():
        sc = Scenario.from_toml_text(row["scenario_toml"])
        # a handbag: at its placement (or its cruise placement) in a cabin row, its sensor level to within
        # a few degrees (Rayleigh tilt, scale 3-8 deg: 40 deg is beyond any draw's reach), x folded to 0-90
        assert row["inflight_placement"] in (sc.carrier.placement, sc.carrier.cruise_placement)
        assert row["cabin_row"] in ("front", "mid", "rear") and row["packing"] == "soft"
        assert 0.0 <= row["stowed_yaw_deg"] < 360.0 and 0.0 <= row["stowed_tilt_deg"] < 40.0
        yaw = row["stowed_yaw_deg"]
        folded = min(yaw % 180.0, 180.0 - yaw % 180.0)
        assert abs(row["sensor_x_from_fuselage_deg"] - folded) <= row["stowed_tilt_deg"] + 1e-9
        back = stowage_of_row(row)["in_flight"]
        assert back["x_from_fuselage_deg"] == row["sensor_x_from_fuselage_deg"]
        assert back["cabin_row"] == row["cabin_row"]


@pytest.mark.slow  # the reference dataset
def test_timings_give_each_flights_wall_time_by_stage(reference):
    """timings.jsonl (not data): each flight's wall time, whole and by pipeline stage; the stages are
    parts of the whole (the rest is writing its files), so they sum to less than it."""
    import json

    log = [json.loads(x) for x in (reference / "timings.jsonl").read_text().splitlines()]
    assert sorted(e["flight_id"] for e in log) == ["000000", "000001"]
    for e in log:
        assert set(e["stages_s"]) == {"fly", "sense", "detect"}
        assert all(v > 0.0 for v in e["stages_s"].values())
        assert sum(e["stages_s"].values()) < e["wall_s"]


@pytest.mark.slow
def test_the_card_documents_the_dataset_and_its_four_loaders_read_it(tmp_path, reference, monkeypatch):
    monkeypatch.setenv("HF_DATASETS_CACHE", str(tmp_path / "hf"))
    monkeypatch.setenv("HF_HUB_OFFLINE", "1")
    card = (reference / "README.md").read_text()
    manifest = read_manifest(reference)
    total = sum(r["samples"] for r in manifest.values())
    in_window = sum(r["samples_in_flight_window"] for r in manifest.values())
    assert f"{N} ok, 0 failed" in card and f"samples: {total:,}" in card
    for col in ("acc_x_g", "in_flight_window", "phase", "flight_id", "aircraft"):
        assert f"`{col}`" in card
    blocks = dict(
        zip(("pyarrow", "polars", "duckdb", "datasets"), re.findall(r"```python\n(.*?)```", card, re.S))
    )
    assert len(blocks) == 4
    got = {}
    for name, code in blocks.items():
        ns: dict = {}
        exec(code, ns)
        got[name] = ns
    assert got["pyarrow"]["table"].num_rows == in_window  # filtered on the label
    assert got["polars"]["df"].shape[0] == total and "aircraft" in got["polars"]["df"].columns
    assert got["duckdb"]["rows"] == [("A320", total)]
    assert got["datasets"]["hf"].num_rows == total
    # windows for learning: 10 s windows never straddle flights, the label follows the window's majority
    import flightmode.datasets as fd

    w = list(fd.windows(reference, 10.0))
    assert {fid for _, _, fid in w} == {"000000", "000001"}
    x, y, _ = w[0]
    assert x.shape == (1000, 3) and y is False  # 100 Hz; the first 10 s: a walk in the terminal


def test_bad_requests_are_one_line_errors_and_write_nothing(tmp_path, family_file, monkeypatch):
    from flightmode import cluster

    monkeypatch.setattr(cluster, "SCHEDULER_TIMEOUT", "1s")  # the same path as the 5 s default, sooner
    out = tmp_path / "ds"
    with pytest.raises(DatasetError, match=r"--n 0: the number of flights must be a positive integer"):
        check_request(str(family_file), 0, out)
    with pytest.raises(DatasetError, match=r"--truth '5hz': choose one of full, 10hz, none"):
        check_request(str(family_file), 2, out, truth="5hz")
    with pytest.raises(DatasetError, match=r"does not answer"):
        make_dataset(str(family_file), 2, out, scheduler="tcp://127.0.0.1:9")  # discard port: nothing listens
    assert not out.exists()
    other = tmp_path / "other"
    other.mkdir()
    (other / "notes.txt").write_text("mine")
    with pytest.raises(DatasetError, match="holds no flightmode dataset"):
        check_request(str(family_file), 2, other)
    # a folder of another family's dataset: refused, with or without --resume
    theirs = tmp_path / "theirs"
    theirs.mkdir()
    (theirs / "family.toml").write_text(HOPS.replace("seed = 5", "seed = 6"))
    for resume in (False, True):
        with pytest.raises(DatasetError, match="holds a dataset of another family .*: choose another --out"):
            check_request(str(family_file), 2, theirs, resume=resume)
    # this family's: --resume continues it
    ours = tmp_path / "ours"
    ours.mkdir()
    (ours / "family.toml").write_text(HOPS)
    with pytest.raises(DatasetError, match="already holds a dataset of this family: pass --resume"):
        check_request(str(family_file), 2, ours)
    check_request(str(family_file), 2, ours, resume=True)
    r = subprocess.run(
        [
            sys.executable,
            "-m",
            "flightmode.cli.main",
            "dataset",
            str(family_file),
            "--n",
            "0",
            "--out",
            str(out),
        ],
        capture_output=True,
        text=True,
    )
    assert r.returncode == 2 and r.stderr.strip().splitlines() == [
        "error: --n 0: the number of flights must be a positive integer"
    ]


def _same_response(sweep_s: float, detector_s) -> bool:
    """The sweep's response against the detector's: equal; or the detector never answered (None, or
    NaN in the manifest) and the sweep says missing (NaN) or never (inf: the bag rested, no answer)."""
    import math

    if detector_s is None or (isinstance(detector_s, float) and math.isnan(detector_s)):
        return math.isnan(sweep_s) or math.isinf(sweep_s)
    return sweep_s == detector_s


@pytest.mark.slow
def test_sweep_reproduces_each_flights_own_detector_and_writes_every_point(tmp_path, reference):
    import pyarrow.parquet as pq

    from flightmode.detector.evaluation import evaluate
    from flightmode.detector.flight_mode import DetectorParams
    from flightmode.detector.grid import Grid
    from flightmode.runs.run_io import read_samples
    from flightmode.studies.sweep import at_point, read_sweep, sigma2_of_flight, summarise, sweep

    grid = Grid(
        methods=(("nmv", 1.0), ("emv", 5.0)),
        windows_s=(1.0, 2.0),
        ks=(3.0, 4.0, 5.0),
        time_thresholds_s=(2.0, 4.0),
    )
    result = sweep(reference, grid, out=tmp_path / "sweep")
    table = result.points
    assert not result.failed and table.num_rows == len(grid) * N
    back = read_sweep(tmp_path / "sweep")
    assert (
        back.points.equals(table) and back.phases.equals(result.phases) and back.static.equals(result.static)
    )
    assert pq.read_table(tmp_path / "sweep" / "points.parquet").equals(table)
    # seed 000's point with sigma^2 from each unit's bench calibration (regenerated from the flight's
    # scenario and seed) is the dataset's own detector run: the same false statics and response, exactly
    manifest = read_manifest(reference)
    rec = at_point(
        table, {"method": "nmv", "weight": 1.0, "window_s": 1.0, "k": 4.0, "time_threshold_s": 4.0}
    )
    assert len(rec) == N
    for r in rec:
        m = next(x for x in manifest.values() if x["flight_id"] == r["flight_id"])
        assert r["false_static_count"] == m["detector_false_static_count"]
        assert _same_response(r["response_s"], m["detector_response_s"])
    # any point, EMV included, is the detector run alone on that flight with those parameters
    row = manifest[0]
    cols, _ = read_samples(reference / row["samples_file"])
    labels = {k: cols[k] for k in ("in_flight_window", "sensor_static", "phase")}
    for method, weight, w, k, tth in (
        ("emv", 5.0, 2.0, 5.0, 2.0),
        ("emv", 5.0, 1.0, 3.0, 4.0),
        ("nmv", 1.0, 2.0, 5.0, 2.0),
    ):
        p = DetectorParams(
            fs_hz=100.0, window_s=w, k_sigma=k, time_threshold_s=tth, method=method, weight=weight
        )
        e = evaluate(cols["t_s"], cols["acc_g"], labels, p, sigma2_of_flight("preset", row, cols)(p.window))
        got = [
            r
            for r in at_point(
                table, {"method": method, "weight": weight, "window_s": w, "k": k, "time_threshold_s": tth}
            )
            if r["flight_id"] == row["flight_id"]
        ]
        assert len(got) == 1
        assert (
            got[0]["false_static_count"] == e.false_static_count
            and got[0]["false_static_s"] == e.false_static_s
        )
        assert _same_response(got[0]["response_s"], e.response_s)
        assert got[0]["missed_static_s"] == e.missed_static_s
        # the per-phase counts: every in-window check once, the joint count never above an axis's
        ph = [
            x
            for x in result.phases.to_pylist()
            if (x["flight_id"], x["method"], x["window_s"], x["k"]) == (row["flight_id"], method, w, k)
        ]
        assert sum(x["checks"] for x in ph) == e.in_flight_checks
        assert all(x["under_all"] <= min(x["under_x"], x["under_y"], x["under_z"]) for x in ph)
    # the static statistics: one row per moving variance and flight, each histogram holding every check
    st = result.static.to_pylist()
    assert len(st) == 4 * N
    for r in st:
        assert (
            sum(r["hist_x"]) == sum(r["hist_max"]) == r["static_checks"] > 1000
        )  # > 15 min at rest, W_s <= 2 s
    # the breakdown at that point: each condition's values partition the flights and their events
    from flightmode.studies.sweep import CONDITIONS, breakdown

    b = breakdown(table, {"method": "nmv", "weight": 1.0, "window_s": 1.0, "k": 4.0, "time_threshold_s": 4.0})
    for cond in CONDITIONS:
        part = [r for r in b if r["condition"] == cond]
        assert sum(r["flights"] for r in part) == N
        assert sum(r["false_statics"] for r in part) == sum(r["false_static_count"] for r in rec)
    # by phase: the phases' in-window hours add up to the flights' (1 s checks tile the window to a
    # second per flight), and every false static began in one of them
    bp = [
        r
        for r in breakdown(
            table,
            {"method": "nmv", "weight": 1.0, "window_s": 1.0, "k": 4.0, "time_threshold_s": 4.0},
            result.phases,
        )
        if r["condition"] == "phase"
    ]
    assert sum(r["in_window_h"] for r in bp) == pytest.approx(
        sum(r["in_window_h"] for r in rec), abs=N / 3600
    )
    assert sum(r["false_statics"] for r in bp) == sum(r["false_static_count"] for r in rec)
    assert {"cruise", "taxi_out", "takeoff_roll"} <= {r["value"] for r in bp}
    # two worker processes give the same rows as this process
    result2 = sweep(reference, grid, workers=2)
    assert result2.points.equals(table) and result2.phases.equals(result.phases)
    # summary: the rate bound of each point is the exact Poisson bound of its events and hours
    from flightmode.detector.confidence import rate_upper_bound

    for s in summarise(table, target_rate_per_h=1e-4):
        assert s["flights"] == N
        assert s["rate_upper_per_h"] == rate_upper_bound(s["false_statics"], s["in_window_h"])
        assert s["hours_short"] == pytest.approx(max(0.0, s["hours_needed"] - s["in_window_h"]))


@pytest.mark.slow
def test_sweep_re_senses_full_truth_flights_with_other_presets(tmp_path, family_file, reference):
    from flightmode.detector.grid import Grid
    from flightmode.errors import InputDataError, SensorError
    from flightmode.studies.sweep import at_point, sweep

    grid = Grid(methods=(("nmv", 1.0),), windows_s=(1.0,), ks=(4.0,), time_thresholds_s=(4.0,))
    # a 10 Hz truth cannot be re-sensed (the floor vibration is 10-30 Hz): said before any work
    with pytest.raises(
        InputDataError, match=r"--sensor re-senses each flight from its full-rate truth.*--truth full"
    ):
        sweep(reference, grid, sensors=("lis302dl",))
    with pytest.raises(SensorError, match="lis302"):
        sweep(reference, grid, sensors=("lis302d",))
    full = tmp_path / "full"
    rows = make_dataset(str(family_file), 1, full, workers=1, truth="full")
    own = rows[0]["sensor_preset"]
    res = sweep(full, grid, sensors=(own, "lis302dl-8g"))
    got = {
        r["sensor_preset"]: r
        for r in at_point(
            res.points, {"method": "nmv", "weight": 1.0, "window_s": 1.0, "k": 4.0, "time_threshold_s": 4.0}
        )
    }
    assert sorted(got) == sorted({own, "lis302dl-8g"})
    stored = sweep(full, grid).points.to_pylist()[0]
    # re-sensed with its own preset from the full-rate truth, the flight is the flight: the same labels
    # (in-window hours, static time, to the sample) and the same detector outcome (the truth keeps the
    # forces in float32, 7 digits, far below one count of the sensor)
    for k in ("in_window_h", "in_flight_checks", "static_s", "false_static_count"):
        assert got[own][k] == stored[k], k
    assert got[own]["response_s"] == pytest.approx(stored["response_s"], abs=0.011)  # one 100 Hz sample
    # another preset: the same flight and labels, another sensor (8 g range: 4x coarser counts)
    assert got["lis302dl-8g"]["in_window_h"] == stored["in_window_h"]
    st = {r["sensor_preset"]: r for r in res.static.to_pylist()}
    assert st["lis302dl-8g"]["static_checks"] == st[own]["static_checks"]
    assert st["lis302dl-8g"]["hist_max"] != st[own]["hist_max"]
    # the e-obs battery trade-off on the same full-truth dataset (issue 18)
    _eobs_tradeoff_on_a_population(reference, full)
    # and `flightmode validate` on it
    _validate_a_population(reference, full, rows[0])


def _validate_a_population(ten_hz, full, row):
    import pyarrow.parquet as pq
    from typer.testing import CliRunner

    from flightmode.cli.main import app
    from flightmode.units import FPS_MPS

    out = full.parent / "checks.parquet"  # `validate --out DIR` writes DIR/checks.parquet
    r = CliRunner().invoke(app, ["validate", str(full), "--json", "--out", str(full.parent)])
    assert r.exit_code == 0, r.output
    doc = json.loads(r.output)
    assert doc["flights_validated"] == 1 and not doc["not_validated"] and doc["failed_to_fly"] == 0
    checks = {c["figure"]: c for c in pq.read_table(out).to_pylist()}
    assert {c["flight_id"] for c in checks.values()} == {row["flight_id"]} and len(checks) == len(
        doc["figures"]
    )
    # the flight's checks see the stream its own detector saw: the same unit's sigma^2 and window give
    # the same number of in-flight checks as the dataset's detector counted when it flew
    note = checks["in-flight checks under 4 sigma^2 on all axes at once"]["note"]
    assert int(re.search(r"of (\d+)$", note).group(1)) == row["detector_in_flight_checks"] > 0, note
    # and the track rebuilt from the full-rate truth touches down as the flown one did (float32 storage:
    # 7 significant digits)
    sink = [c for f, c in checks.items() if f.startswith("sink speed")][0]
    assert sink["value"] == pytest.approx(row["touchdown_sink_mps"] / FPS_MPS, rel=1e-5)
    by_fig = {f["figure"]: f for f in doc["figures"]}
    assert by_fig[sink["figure"]]["median"] == sink["value"] and by_fig[sink["figure"]]["flights"] == 1
    # a 10 Hz truth cannot rebuild a track: said before any work, with the fix
    r = CliRunner().invoke(app, ["validate", str(ten_hz)])
    assert r.exit_code == 2 and "--truth full" in r.output, r.output


def _eobs_tradeoff_on_a_population(ten_hz, full):
    import math

    from flightmode.eobs.flight import tradeoff_on_track
    from flightmode.eobs.population import summarise, tradeoff_population
    from flightmode.errors import InputDataError
    from flightmode.runs import run_io

    with pytest.raises(InputDataError, match="--truth full"):
        tradeoff_population([ten_hz], (30.0,), 216, (1,))
    rows = tradeoff_population([full], (30.0, 120.0), 216, (1, 2))
    # the population's row is the flight's own trade-off (its track rebuilt from the full-rate truth)
    (r0,) = read_manifest(full).values()
    import pyarrow.parquet as pq

    t = pq.read_table(full / r0["truth_file"])
    track = run_io.track_from_table(t, json.loads(t.schema.metadata[run_io.TRACK_INFO_KEY]))
    from flightmode.scenarios.scenario import Scenario

    direct = tradeoff_on_track(
        track, Scenario.from_toml_text(r0["scenario_toml"]), (30.0, 120.0), 216, (1, 2)
    )
    assert [(r["interval_s"], r["m"], r["false_statics"]) for r in rows] == [
        (d.burst_interval_s, d.m, d.false_statics) for d in direct
    ]
    # samples per hour per axis: N per burst, one burst per interval
    for r in rows:
        assert r["samples_per_hour_per_axis"] == pytest.approx(r["burst_samples"] * 3600.0 / r["interval_s"])
    # m quiet bursts in a row: a larger m declares a subset of the smaller m's bursts final static, so
    # it can only have fewer false statics and answer later
    by = {(r["interval_s"], r["m"]): r for r in rows}
    for interval in (30.0, 120.0):
        a, b = by[(interval, 1)], by[(interval, 2)]
        assert b["false_statics"] <= a["false_statics"]
        assert b["response_s"] >= a["response_s"] or math.isnan(a["response_s"])
    s = summarise(rows)
    assert [(x["interval_s"], x["m"]) for x in s] == [(30.0, 1), (30.0, 2), (120.0, 1), (120.0, 2)]
    assert all(x["flights"] == 1 and x["in_window_h"] > 0 for x in s)


GRID_SMALL = (("nmv", 1.0), ("emv", 5.0)), (1.0, 2.0), (3.0, 4.0, 5.0), (2.0, 4.0, 6.0)


@pytest.fixture(scope="module")
def certified(tmp_path_factory, reference):
    """certify over a copy of the reference dataset in which the manifest records member 1 as failed
    (as `flightmode dataset` does for a flight that diverged twice)."""
    import shutil

    from flightmode.datasets.make import _write_manifest
    from flightmode.detector.grid import Grid
    from flightmode.studies.certify import Target, certify

    root = tmp_path_factory.mktemp("certify")
    broken = root / "broken"
    shutil.copytree(reference, broken)
    rows = read_manifest(broken)
    rows[1] = {k: None for k in rows[1]} | {
        "flight_id": "000001",
        "index": 1,
        "status": "failed",
        "attempts": 2,
        "error": "FlightDivergedError: stall in the flare",
    }
    _write_manifest(broken, rows)
    out = root / "out"
    msgs: list[str] = []
    cert = certify([broken], Grid(*GRID_SMALL), Target(1e-4, 0.95, 60.0, 1e-2), out=out, log=msgs.append)
    return cert, out, msgs


@pytest.mark.slow
def test_certify_recommends_from_the_sweep_and_excludes_failed_flights(certified, reference):
    from flightmode.detector.confidence import hours_needed
    from flightmode.detector.grid import Grid
    from flightmode.studies.certify import SEED000_POINT, Target, certify
    from flightmode.studies.sweep import POINT_KEYS

    cert, out, msgs = certified
    assert [x["flight_id"] for x in cert.meta["excluded"]] == [
        "000001"
    ]  # excluded with a count, not silently
    assert "Excluded as failed: <b>1</b>" in (out / "report.html").read_text()
    assert all(s["flights"] == N - 1 for s in cert.summary)
    # the same flight in two datasets would count its hours twice: refused before any work
    from flightmode.errors import InputDataError

    with pytest.raises(InputDataError, match="has the very samples of .*: the same flight in two datasets"):
        certify([reference, out.parent / "broken"], Grid(*GRID_SMALL), Target(), out=out.parent / "twice")
    # one flight (0.6 in-window h) cannot show 1e-4 /h: too small, with the hours the claim lacks
    rec = cert.recommendation
    assert rec["status"] == "too_small"
    p = rec["point"]
    assert rec["hours_needed"] == pytest.approx(hours_needed(1e-4, 0.95, p["false_statics"]))
    assert rec["hours_short"] == pytest.approx(rec["hours_needed"] - p["in_window_h"])
    # at 95 % and no event, 3.0 / 1e-4 = 29,957 h (the rule of three); one flight is ~0.6 h in the window
    assert 25_000 < rec["flights_short"]["hops"] < 120_000
    # the provisional point has the fewest false statics of the points answering within 60 s, then the best response
    fast = [s for s in cert.summary if s["response_p95_s"] <= 60.0]
    assert p["false_statics"] == min(s["false_statics"] for s in fast)
    assert p["response_p95_s"] == min(
        s["response_p95_s"] for s in fast if s["false_statics"] == p["false_statics"]
    )

    # the Pareto front: no point beats a front point everywhere, and every other point is beaten by one
    def beats(a, b):
        ge = (
            a["rate_upper_per_h"] <= b["rate_upper_per_h"]
            and a["response_p95_s"] <= b["response_p95_s"]
            and a["availability"] >= b["availability"]
        )
        return ge and (a["rate_upper_per_h"], a["response_p95_s"], -a["availability"]) != (
            b["rate_upper_per_h"],
            b["response_p95_s"],
            -b["availability"],
        )

    front = set(cert.pareto)
    for i, s in enumerate(cert.summary):
        assert any(beats(t, s) for t in cert.summary) == (i not in front)
    assert cert.seed000 is not None and {k: cert.seed000[k] for k in POINT_KEYS} == SEED000_POINT
    # a larger target (6 false statics per hour; 95 %: 0.5 h with none) is met by the same flights'
    # sweep, reused: the point with the best response among those whose bound is under it
    cert2 = certify(
        [out.parent / "broken"],
        Grid(*GRID_SMALL),
        Target(6.0, 0.95, None, 1e-2),
        out=out,
        log=msgs.append,
        figures=False,
    )
    assert any("reusing the sweep" in m for m in msgs)
    ok = [s for s in cert2.summary if s["rate_upper_per_h"] <= 6.0]
    assert cert2.recommendation["status"] == "meets"
    assert cert2.recommendation["point"]["response_p95_s"] == min(s["response_p95_s"] for s in ok)


@pytest.mark.slow
def test_certify_sets_section_5_1_1_threshold_from_the_static_data(certified):
    from scipy.stats import chi2

    cert, _, _ = certified
    th = cert.threshold
    # one flight, > 40 min at rest: thousands of 1 s checks, enough for P_M 1e-2 (>= 3 exceedances)
    assert th["pm"] == 1e-2 and th["static_checks"] > 2000 and th["empirical_resolved"]
    # white noise over N = 100 samples: P(any of 3 axes >= k) = P_M at the chi-square quantile
    n = th["samples_per_window"]
    assert n == 100
    assert 1 - (1 - chi2.sf(n * th["chi2_white_k"], n - 1)) ** 3 == pytest.approx(1e-2, rel=1e-6)
    # the sensor's coloured static noise (fitted to seed 000 Table 2's spread) spreads the 1 s MV more
    # than white noise does, so the measured threshold sits above the white one
    assert th["empirical_k"] > th["chi2_white_k"]
    for a in "xyz":
        assert 0.25 < th["axes"][a]["sd"] < 0.5  # Table 2's rows imply sigma_MV of 0.30-0.40 sigma^2


@pytest.mark.slow
def test_certify_report_renders_every_figure_in_headless_chromium(certified, tmp_path):
    """The report opens offline in the real browser (the gate of tests/viz's viewer test): every
    figure decodes to an image of its own size, and the page asks for nothing over the network."""
    from tests.browser import chromium_or_skip

    chromium = chromium_or_skip()
    from playwright.sync_api import sync_playwright

    from flightmode.viz.certify_report import FIGURES

    _, out, _ = certified
    requests: list[str] = []
    with sync_playwright() as pw:
        b = pw.chromium.launch(
            executable_path=chromium, headless=True, args=["--no-sandbox", "--no-first-run"]
        )
        page = b.new_page(viewport={"width": 1280, "height": 1600})
        page.set_default_timeout(180_000)  # a loaded 2-core machine (tests/viz/test_rrd.py's web viewer)
        page.on("request", lambda r: requests.append(r.url))
        page.goto((out / "report.html").resolve().as_uri())
        page.wait_for_load_state("load")
        imgs = page.eval_on_selector_all(
            "img", "els => els.map(e => [e.alt, e.complete, e.naturalWidth, e.naturalHeight])"
        )
        text = page.inner_text("body")
        page.screenshot(path=str(tmp_path / "report.png"), full_page=False)
        b.close()
    assert sorted(i[0] for i in imgs) == sorted(FIGURES)
    from PIL import Image

    for alt, complete, w, h in imgs:  # each decoded at the size of the PNG file written beside the report
        assert complete and (w, h) == Image.open(out / "figures" / f"{alt}.png").size, alt
    assert [u for u in requests if not u.startswith(("file:", "data:"))] == []
    assert "too_small" in text and "section 5.1.1" in text


def test_sweep_refuses_what_is_not_a_dataset(tmp_path):
    from flightmode.detector.grid import Grid
    from flightmode.errors import InputDataError
    from flightmode.studies.sweep import sweep

    with pytest.raises(InputDataError, match="no flights.parquet: not a dataset"):
        sweep(tmp_path, Grid())
    from typer.testing import CliRunner

    from flightmode.cli.main import app

    r = CliRunner().invoke(app, ["sweep", str(tmp_path), "--k", "2:x"])
    assert r.exit_code == 2 and "--k '2:x': give values as 2,3,4 or a range start:stop:step" in r.output


def test_an_interrupted_run_leaves_no_temporary_behind(tmp_path, family_file):
    """Ctrl-C closes the run's LocalCluster, whose nannies stop their workers, perhaps in the middle of a
    write (test_faults' Ctrl-C test once found a worker's `.part-000001.parquet.tmp-...` left in the
    samples). The run sweeps such temporaries once its cluster has closed, before it lets the folder go.
    Here one is planted where a stopped worker would leave it, and the interrupt raised as the run starts
    (no flight is flown): it is gone, the folder is free for --resume, and the run's files are whole."""
    from flightmode.atomic import TMP_GLOB, tmp_name

    out = tmp_path / "ds"
    planted = []

    def interrupt(dashboard, to_do):
        (out / "samples").mkdir(exist_ok=True)
        p = tmp_name(out / "samples" / "part-000001.parquet")
        p.write_bytes(b"half a parquet file")
        planted.append(p)
        raise KeyboardInterrupt

    with pytest.raises(KeyboardInterrupt):
        make_dataset(str(family_file), 1, out, workers=1, on_start=interrupt)
    assert planted and not planted[0].exists() and not list(out.rglob(TMP_GLOB))
    assert (out / "family.toml").exists()  # the folder stays this family's: --resume completes it
    check_request(str(family_file), 1, out, resume=True)


@pytest.mark.slow  # the reference dataset
def test_damaged_or_lost_flight_files_are_refused_on_read_and_flown_again_with_verify(tmp_path, reference):
    """Every reader of a dataset flight's files checks them against the manifest's SHA-256 first, and
    names the file and the command that flies it again; ``--resume --verify`` takes such flights out of
    the manifest and removes their files, so that the run flies them again (not flown here: the
    interrupt comes as the run starts; the resumed files' bytes are the sigkill test's)."""
    import shutil

    from flightmode.datasets.flight import flight_stream
    from flightmode.datasets.make import damage
    from flightmode.errors import InputDataError

    ds = tmp_path / "ds"
    shutil.copytree(reference, ds)
    rows = read_manifest(ds)
    assert [damage(ds, r) for r in rows.values()] == [None, None]  # the copy is whole
    samples0 = ds / rows[0]["samples_file"]
    data = bytearray(samples0.read_bytes())
    data[len(data) // 3] ^= 0x01  # one flipped bit
    samples0.write_bytes(bytes(data))
    (ds / rows[1]["truth_file"]).unlink()
    with pytest.raises(InputDataError, match=r"part-000000\.parquet: not the file this dataset wrote") as e:
        flight_stream(ds, 0)
    assert f"flightmode dataset {ds / 'family.toml'} --n 2 --out {ds} --resume --verify" in str(e.value)
    cols, _ = flight_stream(ds, 1)  # its samples are whole: read
    assert cols["acc_g"].shape[1] == 3

    found: dict[str, str] = {}

    def interrupt(dashboard, to_do):
        assert to_do == 2  # both to fly again
        raise KeyboardInterrupt

    with pytest.raises(KeyboardInterrupt):
        make_dataset(
            str(ds / "family.toml"),
            2,
            ds,
            workers=1,
            resume=True,
            verify=True,
            on_damaged=found.update,
            on_start=interrupt,
        )
    assert found == {
        "000000": f"{samples0}: not the file this dataset wrote (its SHA-256 is not the one flights.parquet holds)",
        "000001": f"{ds / rows[1]['truth_file']}: missing",
    }
    assert read_manifest(ds) == {}  # both out of the manifest, their files gone: nothing stale to read
    assert not list(ds.rglob("part-*.parquet"))
    with pytest.raises(
        DatasetError, match="--verify checks the flights of a dataset being resumed: add --resume"
    ):
        make_dataset(str(ds / "family.toml"), 2, ds, workers=1, verify=True)


def test_a_damaged_manifest_or_sweep_table_is_one_line_naming_it(tmp_path):
    """The dataset's manifest and a sweep's tables are read with their page checksums checked
    (flightmode.atomic.read_parquet): a flipped bit is an InputDataError naming the file (it was a
    pyarrow traceback, or wrong rows read as the dataset's)."""
    import pyarrow as pa

    from flightmode.atomic import write_json, write_parquet
    from flightmode.errors import InputDataError
    from flightmode.studies.sweep import SWEEP_FORMAT, read_sweep

    def flip(p):
        data = bytearray(p.read_bytes())
        data[len(data) // 2] ^= 0x10
        p.write_bytes(bytes(data))

    rows = pa.table({"index": list(range(5000)), "flight_id": [f"{i:06d}" for i in range(5000)]})
    ds = tmp_path / "ds"
    flip(write_parquet(rows, ds / "flights.parquet", compression="none"))
    with pytest.raises(
        InputDataError, match=r"flights\.parquet: not a readable Parquet file, the dataset's manifest"
    ):
        read_manifest(ds)
    sw = tmp_path / "sweep"
    write_json({"format": SWEEP_FORMAT}, sw / "sweep.json")
    for part in ("points", "phases", "static"):
        write_parquet(rows, sw / f"{part}.parquet", compression="none")
    assert read_sweep(sw).points.num_rows == 5000
    flip(sw / "phases.parquet")
    with pytest.raises(
        InputDataError, match=r"phases\.parquet: not a readable Parquet file, the sweep's table"
    ):
        read_sweep(sw)


def test_a_flight_without_truth_cannot_rebuild_its_track_and_says_so(tmp_path):
    """A dataset made with --truth none keeps no truth part: rebuilding a flight's track (sweep
    --sensor, validate, the e-obs trade-off) names it and the option that keeps one (it was a
    TypeError on the missing file name)."""
    from flightmode.datasets.flight import flight_track
    from flightmode.errors import InputDataError

    with pytest.raises(InputDataError, match=r"flight 000003 has no truth file \(made with --truth none\)"):
        flight_track(tmp_path, {"flight_id": "000003", "truth_file": None})
