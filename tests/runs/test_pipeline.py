"""flightmode.run and its stages: the API reproduces the CLI's run, stages are callable alone, bad
requests are named, and a run folder appears whole or not at all."""

from __future__ import annotations

import json

import numpy as np
import pyarrow.parquet as pq
import pytest

import flightmode
from flightmode.errors import FlightmodeError, SensorError
from flightmode.runs import pipeline, run_io


def test_the_api_reproduces_the_cli_run(pattern_run, run_cached):
    """`flightmode fly pattern` is a shell over flightmode.run: the same seed gives the same samples
    (bit for bit: both sense the flight in memory), the same detector figures and the same truth."""
    run, _ = pattern_run
    r = run_cached("pattern", stages=("fly", "sense", "detect", "path"))
    assert pq.read_table(run / "samples.parquet").equals(run_io.recording_table(r.recording))
    info = json.loads((run / "run.json").read_text())
    assert info["truth"]["sha256"] == r.track.digest()
    assert info["detector"]["sigma2_g2"] == r.detection.sigma2.tolist()
    assert info["detector"]["false_static_events"] == r.detection.false_static_events
    assert info["path"] == r.path.rows
    assert info["scenario_toml"] == r.scenario.to_toml()


def test_stages_alone_give_what_run_gives(fly_cached, run_cached):
    sc, track = fly_cached("pattern")
    r = run_cached("pattern")
    streams = pipeline.streams_of(sc.seed)
    rec = pipeline.sense(track, sc.carrier, sc.sensor, streams.child("sensor"))
    assert rec.digest() == r.recording.digest()
    ev = pipeline.detect(rec, streams.rng("detector/bench"))
    assert (
        np.array_equal(ev.sigma2, r.detection.sigma2)
        and ev.false_static_events == r.detection.false_static_events
    )
    # a stage not asked for is not run; a stage without what it needs is refused, by name
    only = flightmode.run(sc, track=track, stages=("fly", "sense"))
    assert only.recording is not None and only.detection is None and only.path is None
    with pytest.raises(FlightmodeError, match="stage 'detect' needs sense"):
        flightmode.run(sc, track=track, stages=("fly", "detect"))
    with pytest.raises(FlightmodeError, match='unknown pipeline stage .senes.*did you mean "sense"'):
        flightmode.run(sc, track=track, stages=("fly", "senes"))
    with pytest.raises(FlightmodeError, match="not this scenario's flight"):
        flightmode.run(sc.replace(aircraft="A320"), track=track, stages=("fly",))


def test_a_failed_write_or_stage_leaves_no_run_folder(fly_cached, tmp_path, monkeypatch):
    sc, track = fly_cached("pattern")
    out = tmp_path / "out"

    def broken(stage, rec):
        raise OSError("disk full")

    monkeypatch.setattr(run_io, "write_samples", broken)
    with pytest.raises(OSError, match="disk full"):
        flightmode.run(sc, track=track, out=out, rrd=False)
    assert list(out.iterdir()) == []  # truth.parquet had been written: the staging folder is gone too
    monkeypatch.undo()
    # a stage that fails while the truth is being written in the background
    with pytest.raises(SensorError, match="unknown sensor preset"):
        flightmode.run(sc, track=track, out=out, sensor="lis303")
    assert list(out.iterdir()) == []
    r = flightmode.run(sc, track=track, out=out, rrd=False)
    assert sorted(p.name for p in out.iterdir()) == ["pattern-s1"]
    assert sorted(p.name for p in (out / "pattern-s1").iterdir()) == [
        "run.json",
        "samples.parquet",
        "truth.parquet",
    ]
    assert set(r.written) == {"truth", "samples", "run_json"}


@pytest.mark.parametrize("rest_n", [4_000, 9_000])  # rest shorter, then longer, than the 60 s bench
def test_the_bench_recording_pairs_with_the_gyroscope_at_rest_before_the_flight(rest_n):
    """stream_rest("preset") on a stream with a gyroscope: the unit's own bench recording (the run's
    "detector/bench" stream) and the gyroscope's longest truly static run before the in-flight
    window, both cut to the shorter. Exact: both are slices of the same arrays."""
    from flightmode.sim.sensor.accelerometer import UnitDraw, bench_static, get_preset

    n = 30_000
    gyro = np.arange(3 * n, dtype=float).reshape(n, 3)  # every row distinct: the slice is identified
    static = np.zeros(n, bool)
    static[1_000:2_000] = True  # a shorter run before the window
    static[3_000 : 3_000 + rest_n] = True  # the longest before the window
    window = np.zeros(n, bool)
    window[15_000:] = True
    static[16_000:29_000] = True  # longer still, but in the window: never the rest
    cols = {"acc_g": np.zeros((n, 3)), "gyro_dps": gyro, "sensor_static": static, "in_flight_window": window}
    info = {"seed": 7, "sensor": {"preset": "ideal", "odr_hz": 100.0, "unit": None}}
    acc, gyr, said = pipeline.stream_rest("preset", cols, info)
    bench = bench_static(get_preset("ideal"), UnitDraw(), pipeline.streams_of(7).rng("detector/bench")).acc_g
    m = min(bench.shape[0], rest_n)
    assert acc.shape == gyr.shape == (m, 3)
    assert np.array_equal(acc, bench[:m]) and np.array_equal(gyr, gyro[3_000 : 3_000 + m])
    assert said.endswith(f"the gyroscope's {m} samples at rest before the flight")
