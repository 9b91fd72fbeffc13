"""`flightmode validate DATASET`: a population of flights beside the public figures.

A single run says little about a distribution: a touchdown's sink speed is one draw, a taxi's yaw rate
one airport. Every flight of a dataset made by ``flightmode dataset ... --truth full`` is checked here
exactly as a run folder is (:func:`flightmode.studies.validate.track_checks` on the track rebuilt
from its full-rate truth and the plan of the scenario in its manifest row;
:func:`~flightmode.studies.validate.seed000_checks` on its samples, sigma^2 the bench calibration of
the unit its sensing drew, as its own detector had it). Flights run in this process or one Dask task
per flight (``workers`` > 1: :func:`flightmode.cluster.map_flights`).

The summary (:func:`summarise`) gives, per aircraft type and figure, the anchor, the flights' values
(p5, median, p95 over the flights that show the figure) and how many of the flights that judge it
pass, with the 95 % Clopper-Pearson interval of the pass fraction
(:func:`~flightmode.studies.validate.fraction_interval`): 20 flights that all pass still allow a
true failure rate up to 17 %. A flight shows a figure without judging it when the anchor does not
apply to it (seed 000's Tables 4 / 5 for a bag whose sensor lay unlike the paper's:
:func:`~flightmode.studies.validate.placement_text`). A flight that cannot be checked
is reported with its error, never dropped silently; nothing is written (``--out DIR`` writes the
per-flight rows to DIR/checks.parquet, atomically).
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import asdict, dataclass
from pathlib import Path

import numpy as np

from flightmode.errors import InputDataError

SUMMARY_QUANTILES = (5.0, 50.0, 95.0)


@dataclass(frozen=True, slots=True)
class FigureSummary:
    """One figure over the flights of one aircraft type that show it."""

    aircraft: str
    group: str
    figure: str
    unit: str
    anchor: str
    source: str
    flights: int  # flights showing the figure
    passed: int  # of the judged flights
    p5: float  # over the flights with a finite value (NaN if none)
    median: float
    p95: float
    pass_ci: tuple[float, float]  # 95 % Clopper-Pearson interval of the pass fraction
    # flights whose check has an anchor to pass (a row shown without one, e.g. a seed 000 Table 4 cell
    # of a bag lying unlike the paper's, is not judged); None: every flight's
    judged: int | None = None

    @property
    def n_judged(self) -> int:
        return self.flights if self.judged is None else self.judged

    @property
    def pass_fraction(self) -> float:
        return self.passed / self.n_judged if self.n_judged else math.nan

    def as_dict(self) -> dict:
        return asdict(self) | {"pass_fraction": self.pass_fraction}


def check_request(dataset: str | Path, paper_flight: int = 1) -> tuple[list[dict], list[dict]]:
    """The dataset's flights (ok, failed), checked before any work: a folder that is not a dataset,
    one without a successful flight or without full-rate truth raises an InputDataError saying how
    to make one that can be validated."""
    from flightmode.datasets.make import ok_flights
    from flightmode.studies.validate import PAPER_TABLES

    if paper_flight not in PAPER_TABLES:
        raise InputDataError(
            f"--paper-flight {paper_flight}: seed 000 has flights 1 (Table 4) and 2 (Table 5)"
        )
    ok, failed, _ = ok_flights(dataset, "validate", full_truth_for="validation rebuilds each flight")
    return ok, failed


def validate_flight(dataset: str, row: dict, paper_flight: int = 1) -> dict:
    """One dataset flight's checks: ``{"flight_id", "aircraft", "checks": [Check, ...]}``, or with
    ``"error"`` (the exception's type and message) instead of checks if it cannot be validated."""
    from flightmode.datasets.flight import flight_track
    from flightmode.datasets.make import flight_file, stowage_of_row
    from flightmode.runs import pipeline
    from flightmode.runs.run_io import read_samples
    from flightmode.scenarios.scenario import Scenario
    from flightmode.studies.sweep import sigma2_of_flight
    from flightmode.studies.validate import seed000_checks, sensor_noise_psd, track_checks

    head = {"flight_id": row["flight_id"], "aircraft": row["aircraft"]}
    try:
        track = flight_track(dataset, row)
        sc = Scenario.from_toml_text(row["scenario_toml"], f"flight {row['flight_id']} (scenario_toml)")
        checks = track_checks(track, sc.plan)
        columns, _ = read_samples(flight_file(dataset, row))
        preset = pipeline.sensor_preset(sc.sensor)
        checks += seed000_checks(
            columns,
            preset.odr_hz,
            sigma2_of_flight("preset", row, columns),
            paper_flight,
            stowage_of_row(row),
            sensor_noise_psd(preset.name, preset.odr_hz),
        )
    except Exception as e:
        return head | {"error": f"{type(e).__name__}: {e}"}
    return head | {"checks": checks}


def validate_dataset(
    dataset: str | Path,
    paper_flight: int = 1,
    workers: int = 1,
    on_done: Callable[[int], None] | None = None,
    scheduler: str | None = None,
) -> tuple[list[dict], list[dict]]:
    """Every successful flight of the dataset validated: (per-flight results of :func:`validate_flight`
    in manifest order, the manifest rows of the flights that failed to fly). One Dask task per flight
    on ``workers`` local processes or the ``scheduler`` at that address (:mod:`flightmode.cluster`)."""
    from flightmode.cluster import map_flights

    ok, failed = check_request(dataset, paper_flight)
    args = [(str(dataset), r, paper_flight) for r in ok]
    results = map_flights(validate_flight, args, workers, on_done, scheduler=scheduler)
    return results, failed


def summarise(results: Sequence[dict]) -> list[FigureSummary]:
    """Per aircraft type (in order of appearance) and figure (in the order a run prints them), the
    flights' values and passes (module docstring)."""
    from flightmode.studies.validate import fraction_interval

    cells: dict[tuple[str, str, str], list] = {}
    for r in results:
        for c in r.get("checks", ()):
            cells.setdefault((r["aircraft"], c.group, c.figure), []).append(c)
    out = []
    for (aircraft, group, figure), checks in cells.items():
        values = np.array([c.value for c in checks], float)
        finite = values[np.isfinite(values)]
        q = (
            np.percentile(finite, SUMMARY_QUANTILES)
            if finite.size
            else np.full(len(SUMMARY_QUANTILES), math.nan)
        )
        judged = [c for c in checks if c.judged]
        n_pass = sum(c.passed for c in judged)
        # one anchor per figure: the same source range for every judged flight of the type (the first's text)
        c0 = (judged or checks)[0]
        ci = fraction_interval(n_pass, len(judged)) if judged else (0.0, 1.0)  # nothing judged: no bound
        out.append(
            FigureSummary(
                aircraft,
                group,
                figure,
                c0.unit,
                c0.anchor_text(),
                c0.source,
                len(checks),
                n_pass,
                float(q[0]),
                float(q[1]),
                float(q[2]),
                ci,
                len(judged),
            )
        )
    return out


def checks_table(results: Sequence[dict]):
    """The per-flight rows as a pyarrow Table: one row per flight and check (flights that could not be
    validated: one row with the error)."""
    import pyarrow as pa

    rows = []
    for r in results:
        if "error" in r:
            rows.append({"flight_id": r["flight_id"], "aircraft": r["aircraft"], "error": r["error"]})
        for c in r.get("checks", ()):
            rows.append({"flight_id": r["flight_id"], "aircraft": r["aircraft"], "error": None} | c.as_dict())
    schema = pa.schema(
        [
            ("flight_id", pa.string()),
            ("aircraft", pa.string()),
            ("error", pa.string()),
            ("group", pa.string()),
            ("figure", pa.string()),
            ("unit", pa.string()),
            ("value", pa.float64()),
            ("lo", pa.float64()),
            ("hi", pa.float64()),
            ("source", pa.string()),
            ("note", pa.string()),
            ("passed", pa.bool_()),
        ]
    )
    return pa.Table.from_pylist(rows, schema=schema)
