"""One flight of a dataset as a stream a detector can run on: its samples and the run.json it would
have had (:func:`flight_stream`), rebuilt from the manifest's scenario and seed.

A dataset keeps no run.json per flight; what a detection needs of one is the sensor's preset, rate
and unit (the bench calibration of ``--sigma2-from preset`` regenerates the unit's 60 s bench
recording on the run's own ``detector/bench`` stream) and the scenario (the pressure detector's
destination). Both follow from the manifest row's ``scenario_toml``: the unit is the one sensing
drew from the run's ``sensor/unit`` stream, as :func:`flightmode.studies.sweep.sigma2_of_flight`
draws it, so a flight's detection here equals its row in a sweep.
"""

from __future__ import annotations

import json
from pathlib import Path

from flightmode.errors import InputDataError, did_you_mean


def manifest_row(dataset: str | Path, flight: str | int) -> dict:
    """The manifest row of one flight, by its id (``000003``) or index (``3``); an InputDataError
    naming the flights there are, or a flight that failed to fly."""
    from flightmode.datasets.make import is_dataset, read_manifest

    if not is_dataset(dataset):
        raise InputDataError(f"{dataset}: no flights.parquet: not a dataset made by `flightmode dataset`")
    rows = read_manifest(Path(dataset))
    by_id = {r["flight_id"]: r for r in rows.values()}
    key = str(flight).strip()
    row = by_id.get(key)
    if row is None and key.isdigit():
        row = rows.get(int(key))
    if row is None:
        ids = sorted(by_id)
        shown = ", ".join(ids[:5]) + (", ..." if len(ids) > 5 else "")
        raise InputDataError(
            f"{dataset}: no flight {key!r} (flights {shown}: an id or an index 0..{len(ids) - 1})"
            f"{did_you_mean(key, ids)}"
        )
    if row["status"] != "ok":
        raise InputDataError(f"{dataset}: flight {row['flight_id']} failed to fly ({row.get('error')})")
    return row


def flight_info(row: dict) -> dict:
    """The run.json a dataset flight would have had, as far as a detection reads it: ``run_id``,
    ``seed``, ``scenario_toml`` and ``sensor`` (preset, rate, the unit sensing drew)."""
    from flightmode.runs import pipeline
    from flightmode.scenarios.scenario import Scenario
    from flightmode.sim.sensor.accelerometer import draw_unit

    sc = Scenario.from_toml_text(row["scenario_toml"], f"flight {row['flight_id']}")
    preset = pipeline.sensor_preset(sc.sensor)
    unit = draw_unit(preset, pipeline.streams_of(sc.seed).child("sensor").rng("unit")).as_dict()
    return {
        "run_id": f"{sc.name}-s{sc.seed}",
        "seed": sc.seed,
        "scenario_toml": row["scenario_toml"],
        "sensor": {"preset": preset.name, "odr_hz": preset.odr_hz, "unit": unit},
    }


def flight_stream(dataset: str | Path, flight: str | int) -> tuple[dict, dict]:
    """(columns, run.json) of one flight of a dataset: its samples as
    :func:`flightmode.runs.run_io.read_samples` gives a run's, and :func:`flight_info`."""
    from flightmode.datasets.make import flight_file
    from flightmode.runs.run_io import read_samples

    row = manifest_row(dataset, flight)
    cols, _ = read_samples(flight_file(dataset, row))
    return cols, flight_info(row)


__all__ = ["flight_info", "flight_stream", "manifest_row"]


def flight_track(dataset: str | Path, row: dict):
    """A dataset flight's FlightTrack, rebuilt from its full-rate truth (``--truth full``; the Parquet
    metadata carries what run.json would: :data:`flightmode.runs.run_io.TRACK_INFO_KEY`)."""
    import pyarrow.parquet as pq

    from flightmode.datasets.make import flight_file
    from flightmode.runs import run_io

    t = pq.read_table(flight_file(dataset, row, "truth"))
    if not t.schema.metadata or run_io.TRACK_INFO_KEY not in t.schema.metadata:
        raise InputDataError(
            f"{dataset}: flight {row['flight_id']}'s truth cannot rebuild its track (an older "
            "dataset, or not --truth full); make the dataset with `flightmode dataset ... --truth full`"
        )
    return run_io.track_from_table(t, json.loads(t.schema.metadata[run_io.TRACK_INFO_KEY]))
