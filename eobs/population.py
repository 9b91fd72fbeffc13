"""The battery trade-off of a duty-cycled e-obs tag on a flight population: every flight of one or
more datasets (made with ``--truth full``) re-sensed by a tag at each ACC interval, the duty-cycled
detector (:mod:`flightmode.eobs.duty_cycle`) at each ``m``, and per (interval, m) the samples per
hour (the battery's cost: the ADC and the radio-off time are proportional to them, seed 003
section 10) against the false statics per in-window flight-hour (with Garwood's upper bound) and
the response at the gate. One flight per task on the sweep's executor
(:func:`flightmode.cluster.map_flights`)."""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from pathlib import Path

import numpy as np

from flightmode.errors import InputDataError


def tradeoff_flight(
    dataset: str,
    row: dict,
    intervals_s: Sequence[float],
    byte_count: int,
    ms: Sequence[int],
    k: float,
    odr_per_axis_hz: float,
) -> list[dict]:
    """One flight's rows (:func:`flightmode.eobs.flight.tradeoff_on_track` on its full-rate truth)."""
    from flightmode import Scenario
    from flightmode.datasets import flight_track
    from flightmode.eobs.flight import tradeoff_on_track

    track = flight_track(dataset, row)
    sc = Scenario.from_toml_text(row["scenario_toml"], f"flight {row['flight_id']}")
    in_window_h = float(np.count_nonzero(track.in_flight_window)) / track.fs_hz / 3600.0
    out = []
    for r in tradeoff_on_track(track, sc, intervals_s, byte_count, ms, k, odr_per_axis_hz):
        out.append(
            {
                "dataset": dataset,
                "flight_id": row["flight_id"],
                "aircraft": row.get("aircraft"),
                "interval_s": r.burst_interval_s,
                "burst_samples": r.burst_samples,
                "m": r.m,
                "k": r.k,
                "in_window_h": in_window_h,
                "bursts": r.bursts,
                "in_window_bursts": r.in_window_bursts,
                "false_statics": r.false_statics,
                # at rest after the flight but never answered: infinitely slow (counted by percentiles)
                "response_s": math.inf if r.response_s is None else r.response_s,
                "samples_per_hour_per_axis": r.samples_per_hour,
            }
        )
    return out


def check_request(
    datasets, intervals_s, byte_count: int, ms, k: float, odr_per_axis_hz: float
) -> list[tuple]:
    """(dataset, row) of every successful flight, after checking the request (one-line errors)."""
    from flightmode.datasets import ok_flights
    from flightmode.errors import DetectorError
    from flightmode.sim.sensor.accelerometer import eobs_preset

    paths = [Path(d) for d in datasets]
    if not paths:
        raise InputDataError(
            "no dataset given: name at least one folder made by `flightmode dataset --truth full`"
        )
    if not intervals_s or not ms:
        raise DetectorError("give at least one ACC interval and one m")
    for m in ms:
        if not (isinstance(m, int) and m >= 1):
            raise DetectorError(f"--m {m!r}: the quiet bursts in a row must be an integer >= 1")
    if not k > 0:
        raise DetectorError(f"--k {k!r}: the threshold k sigma^2 needs k > 0")
    for interval in intervals_s:
        eobs_preset(float(interval), byte_count, odr_per_axis_hz)  # the tag's own rules (a SensorError)
    jobs = []
    for d in paths:
        ok, _, _ = ok_flights(d, "evaluate", full_truth_for="the trade-off re-senses each flight")
        jobs += [(str(d), r) for r in ok]
    return jobs


def tradeoff_population(
    datasets,
    intervals_s: Sequence[float],
    byte_count: int,
    ms: Sequence[int],
    k: float = 4.0,
    odr_per_axis_hz: float = 10.0,
    workers: int = 1,
    on_start: Callable[[int], None] | None = None,
    on_flight: Callable[[int], None] | None = None,
    scheduler: str | None = None,
) -> list[dict]:
    """Every flight's rows (:func:`tradeoff_flight`), in dataset and flight order; one Dask task per
    flight on ``workers`` local processes or the ``scheduler`` at that address (:mod:`flightmode.cluster`)."""
    from flightmode.cluster import map_flights

    jobs = check_request(datasets, intervals_s, byte_count, ms, k, odr_per_axis_hz)
    if on_start:
        on_start(len(jobs))
    args = [(d, r, tuple(intervals_s), byte_count, tuple(ms), k, odr_per_axis_hz) for d, r in jobs]
    results = map_flights(tradeoff_flight, args, workers, on_flight, scheduler=scheduler)
    return [row for rows in results for row in rows]


def summarise(rows: list[dict], confidence: float = 0.95) -> list[dict]:
    """Per (interval, burst, m): flights, in-window hours, false statics, their rate and exact upper
    bound per flight-hour, response p50 / p95 / max at the gate, samples per hour per axis."""
    from flightmode.detector.confidence import rate_and_response

    groups: dict[tuple, list[dict]] = {}
    for r in rows:
        groups.setdefault((r["interval_s"], r["burst_samples"], r["m"], r["k"]), []).append(r)
    out = []
    for (interval, n, m, k), rs in sorted(groups.items()):
        out.append(
            {
                "interval_s": interval,
                "burst_samples": n,
                "m": m,
                "k": k,
                "flights": len(rs),
                **rate_and_response(
                    sum(r["false_statics"] for r in rs),
                    sum(r["in_window_h"] for r in rs),
                    [r["response_s"] for r in rs],
                    confidence,
                ),
                "samples_per_hour_per_axis": float(np.mean([r["samples_per_hour_per_axis"] for r in rs])),
            }
        )
    return out


__all__ = ["tradeoff_flight", "tradeoff_population", "summarise", "check_request"]
