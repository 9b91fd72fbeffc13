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

from flightmode.scenarios.dataset import DatasetError, check_request, make_dataset, read_manifest

# one worker runs this module (pytest-xdist --dist loadgroup): the reference dataset is made once, and
# two clusters of its own never compete with each other for the two cores
pytestmark = pytest.mark.xdist_group("dataset")

# the shortest hop (Birmingham - Manchester, 106 km: 45 min gate to gate, about 10 s of wall time)
HOPS = """
[family]
name = "hops"
description = "the shortest hop, both ways"
seed = 5

[aircraft]
A320 = 1

[routes]
pairs = [["EGBB", "EGCC"], ["EGCC", "EGBB"]]

[turbulence]
patch_probability = 0.0
"""
N = 2


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


@pytest.fixture(scope="module")
def family_file(tmp_path_factory) -> Path:
    p = tmp_path_factory.mktemp("family") / "hops.toml"
    p.write_text(HOPS)
    return p


@pytest.fixture(scope="module")
def reference(tmp_path_factory, family_file) -> Path:
    """The uninterrupted dataset, made through the API on a LocalCluster of two worker processes."""
    out = tmp_path_factory.mktemp("ref") / "ds"
    rows = make_dataset(str(family_file), N, out, workers=2)
    assert sorted(rows) == list(range(N)) and all(r["status"] == "ok" for r in rows.values())
    return out


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
    procs = [subprocess.Popen(["dask", "scheduler", "--host", "127.0.0.1", "--port", "0", "--dashboard-address",
                               "127.0.0.1:0", "--scheduler-file", str(sched_file)],
                              stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, start_new_session=True)]
    try:
        t0 = time.monotonic()
        while not sched_file.exists():
            assert time.monotonic() - t0 < 60, "dask scheduler did not start"
            time.sleep(0.2)
        time.sleep(0.2)  # the file is written whole before its address is used
        address = json.loads(sched_file.read_text())["address"]
        assert address.startswith("tcp://127.0.0.1:")
        for _ in range(2):
            procs.append(subprocess.Popen(["dask", "worker", address, "--nthreads", "1", "--host", "127.0.0.1",
                                           "--no-dashboard", "--memory-limit", "0"],
                                          stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, start_new_session=True))
        out = tmp_path / "ds"
        r = subprocess.run(["flightmode", "dataset", str(family_file), "--n", str(N), "--out", str(out),
                            "--scheduler", address, "--rrd"], capture_output=True, text=True, timeout=600)
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
    from flightmode.scenarios.dataset import manifest_schema

    assert _manifest(out).schema.equals(manifest_schema())  # every column, typed, even with no success
    assert "0 ok, 1 failed" in (out / "README.md").read_text()
    # the time limit may change on --resume (it changes no file): the failure is tried again
    rows = make_dataset(str(family_file), 1, out, workers=1, flight_timeout_s=0.4, resume=True)
    assert [r["attempts"] for r in rows.values()] == [2]
    with pytest.raises(DatasetError, match=r"resume with the same --truth and --rrd"):
        check_request(str(family_file), 1, out, resume=True, truth="full")
    check_request(str(family_file), 1, out, resume=True, flight_timeout_s=10.0)


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
    blocks = dict(zip(("pyarrow", "polars", "duckdb", "datasets"), re.findall(r"```python\n(.*?)```", card, re.S)))
    assert len(blocks) == 4
    got = {}
    for name, code in blocks.items():
        ns: dict = {}
        exec(code, ns)  # noqa: S102  the card's own example, as a reader would paste it
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


def test_bad_requests_are_one_line_errors_and_write_nothing(tmp_path, family_file):
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
    r = subprocess.run([sys.executable, "-m", "flightmode.scenarios.cli", "dataset", str(family_file), "--n", "0",
                        "--out", str(out)], capture_output=True, text=True)
    assert r.returncode == 2 and r.stderr.strip().splitlines() == ["error: --n 0: the number of flights must be a positive integer"]


@pytest.mark.slow
def test_sweep_reproduces_each_flights_own_detector_and_writes_every_point(tmp_path, reference):
    import pyarrow.parquet as pq

    from flightmode.detector.grid import Grid
    from flightmode.scenarios.sweep import summarise, sweep

    grid = Grid(methods=(("nmv", 1.0), ("emv", 5.0)), windows_s=(1.0, 2.0), ks=(3.0, 4.0, 5.0),
                time_thresholds_s=(2.0, 4.0))
    table, failed = sweep(reference, grid, out=tmp_path / "sweep.parquet")
    assert not failed and table.num_rows == len(grid) * N
    assert pq.read_table(tmp_path / "sweep.parquet").equals(table)
    # seed 000's point with sigma^2 from each unit's bench calibration (regenerated from the flight's
    # scenario and seed) is the dataset's own detector run: the same false statics and response, exactly
    manifest = read_manifest(reference)
    rec = [r for r in table.to_pylist() if (r["method"], r["window_s"], r["k"], r["time_threshold_s"]) == ("nmv", 1.0, 4.0, 4.0)]
    assert len(rec) == N
    for r in rec:
        m = next(x for x in manifest.values() if x["flight_id"] == r["flight_id"])
        assert r["false_static_count"] == m["detector_false_static_count"]
        assert r["response_s"] == m["detector_response_s"]
    # the breakdown at that point: each condition's values partition the flights and their events
    from flightmode.scenarios.sweep import CONDITIONS, breakdown

    b = breakdown(table, {"method": "nmv", "weight": 1.0, "window_s": 1.0, "k": 4.0, "time_threshold_s": 4.0})
    for cond in CONDITIONS:
        part = [r for r in b if r["condition"] == cond]
        assert sum(r["flights"] for r in part) == N
        assert sum(r["false_statics"] for r in part) == sum(r["false_static_count"] for r in rec)
    # two worker processes give the same rows as this process
    table2, _ = sweep(reference, grid, workers=2)
    assert table2.equals(table)
    # summary: the rate bound of each point is the exact Poisson bound of its events and hours
    from flightmode.detector.confidence import rate_upper_bound

    for s in summarise(table, target_rate_per_h=1e-4):
        assert s["flights"] == N
        assert s["rate_upper_per_h"] == rate_upper_bound(s["false_statics"], s["in_window_h"])
        assert s["hours_short"] == pytest.approx(max(0.0, s["hours_needed"] - s["in_window_h"]))


def test_sweep_refuses_what_is_not_a_dataset(tmp_path):
    from flightmode.detector.grid import Grid
    from flightmode.errors import InputDataError
    from flightmode.scenarios.sweep import sweep

    with pytest.raises(InputDataError, match="no flights.parquet: not a dataset"):
        sweep(tmp_path, Grid())
    from typer.testing import CliRunner

    from flightmode.scenarios.cli import app

    r = CliRunner().invoke(app, ["sweep", str(tmp_path), "--k", "2:x"])
    assert r.exit_code == 2 and "--k '2:x': give values as 2,3,4 or a range start:stop:step" in r.output
