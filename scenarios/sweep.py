"""Detector thresholds over a whole dataset: ``flightmode sweep DATASET --k ... --time-threshold-s ...``.

Every flight of a dataset made by ``flightmode dataset`` is read once and the grid evaluated on it
with each moving variance computed once (:func:`flightmode.detector.grid.evaluate_grid`); flights run
in this process, or one Dask task per flight (``workers`` > 1: a LocalCluster on 127.0.0.1).

sigma^2: ``preset`` (default) is the bench calibration of the flight's own sensor unit, exactly as the
dataset's own detector run did it (the unit and the bench stream regenerated from the flight's
scenario and seed: :func:`flightmode.scenarios.pipeline.unit_sigma2`); ``rest`` the truly static
samples the tracker saw before the flight.

Per grid point and flight (``sweep.parquet``): false statics inside the in-flight window (count,
seconds, the longest, their phases), the suspension latency (from pushback to the first check that
forbids transmission), the response at the destination (truly at rest to the first final static), the
availability (the share of truly-static check time outside the window reported static) and the
flight's conditions (type, placement, turbulence, landing, sensor) for breakdowns. Per grid point
(:func:`summarise`): the false-static rate per in-window flight-hour and its exact upper bound
(:mod:`flightmode.detector.confidence`), response p50/p95/max, mean availability.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from pathlib import Path

import numpy as np

from flightmode.errors import InputDataError

CONDITIONS = ("aircraft", "placement", "carrier_kind", "turbulence", "landing_quality", "sensor_preset")


def _sigma2_of(source: str, row: dict, columns: dict) -> Callable[[int], np.ndarray]:
    from flightmode.detector.recommended import sigma2_from_rest
    from flightmode.scenarios import pipeline
    from flightmode.scenarios.scenario import Scenario
    from flightmode.sim.sensor.accelerometer import draw_unit

    sc = Scenario.from_toml_text(row["scenario_toml"], f"flight {row['flight_id']}")
    preset = pipeline.sensor_preset(sc.sensor)
    if source == "preset":
        # the unit sensing drew (stream sensor/unit) and the bench stream of the run's own detector
        unit = draw_unit(preset, pipeline.streams_of(sc.seed).child("sensor").rng("unit")).as_dict()
        return lambda window: pipeline.unit_sigma2(preset.name, preset.odr_hz, unit, window,
                                                   pipeline.streams_of(sc.seed).rng("detector/bench"))
    if source == "rest":
        return lambda window: sigma2_from_rest(columns["acc_g"], columns["sensor_static"], columns["in_flight_window"],
                                               window, preset.lsb_g)[0]
    raise InputDataError(f"--sigma2-from {source!r}: use preset or rest")


def sweep_flight(dataset: str, row: dict, grid, sigma2_from: str = "preset") -> list[dict]:
    """Every grid point on one flight of the dataset: a list of rows (module docstring)."""
    from flightmode.detector.grid import evaluate_grid
    from flightmode.scenarios.run_io import read_samples

    cols, _ = read_samples(Path(dataset) / row["samples_file"])
    t, acc = cols["t_s"], cols["acc_g"]
    fs = 1.0 / float(np.median(np.diff(t)))
    fs = round(fs, 6)
    labels = {k: cols[k] for k in ("in_flight_window", "sensor_static", "phase")}
    window = labels["in_flight_window"]
    static = labels["sensor_static"]
    dt = 1.0 / fs
    in_window_h = float(window.sum()) * dt / 3600.0
    w_start = float(t[np.flatnonzero(window)[0]]) if window.any() else math.nan
    cond = {k: row.get(k) for k in CONDITIONS}
    out = []
    for p, e in evaluate_grid(t, acc, labels, grid, fs, _sigma2_of(sigma2_from, row, cols)):
        c = e.checks
        truth_out = static[c.index] & ~window[c.index]
        static_s = float(truth_out.sum()) * p.window_s
        after = np.flatnonzero((c.t_s >= w_start) & ~c.final_static) if window.any() else np.zeros(0, int)
        events = e.false_static_events
        out.append({
            "flight_id": row["flight_id"], **cond,
            "method": p.method, "weight": p.weight, "window_s": p.window_s, "k": p.k_sigma,
            "time_threshold_s": p.time_threshold_s,
            "in_window_h": in_window_h, "in_flight_checks": e.in_flight_checks,
            "false_static_count": e.false_static_count, "false_static_s": e.false_static_s,
            "longest_false_static_s": max((ev["duration_s"] for ev in events), default=0.0),
            "false_static_phases": ",".join(ev["phase"] for ev in events),
            "suspend_s": float(c.t_s[after[0]] - w_start) if after.size else math.nan,
            "response_s": math.nan if e.response_s is None else e.response_s,
            "static_s": static_s, "missed_static_s": e.missed_static_s,
            "availability": (static_s - e.missed_static_s) / static_s if static_s > 0 else math.nan,
        })
    return out


def _ok_rows(dataset: Path) -> tuple[list[dict], list[dict]]:
    from flightmode.scenarios.dataset import read_manifest

    if not (dataset / "flights.parquet").exists():
        raise InputDataError(f"{dataset}: no flights.parquet: not a dataset made by `flightmode dataset`")
    rows = read_manifest(dataset)
    ok = [rows[i] for i in sorted(rows) if rows[i]["status"] == "ok"]
    failed = [rows[i] for i in sorted(rows) if rows[i]["status"] != "ok"]
    if not ok:
        raise InputDataError(f"{dataset}: no flight succeeded ({len(failed)} failed): nothing to sweep")
    return ok, failed


def sweep(dataset: str | Path, grid, *, sigma2_from: str = "preset", workers: int = 1,
          out: str | Path | None = None, on_start: Callable[[int], None] | None = None,
          on_flight: Callable[[str], None] | None = None):
    """Evaluate ``grid`` on every successful flight of ``dataset``; (pyarrow Table of the rows,
    flights excluded as failed). Writes the table to ``out`` (Parquet, atomically) if given.
    ``on_start(flights)`` and ``on_flight(flight_id)`` report progress."""
    import pyarrow as pa

    dataset = Path(dataset)
    ok, failed = _ok_rows(dataset)
    if sigma2_from not in ("preset", "rest"):
        raise InputDataError(f"--sigma2-from {sigma2_from!r}: use preset or rest")
    import pyarrow.parquet as pq

    t0 = pq.read_table(dataset / ok[0]["samples_file"], columns=["t_s"])["t_s"].to_numpy()[:1000]
    grid.validate(round(1.0 / float(np.median(np.diff(t0))), 6))  # a bad axis fails before any work
    if on_start:
        on_start(len(ok))
    rows: list[dict] = []
    if workers <= 1:
        for r in ok:
            rows += sweep_flight(str(dataset), r, grid, sigma2_from)
            if on_flight:
                on_flight(r["flight_id"])
    else:
        import logging

        from dask.distributed import Client, LocalCluster, as_completed

        with LocalCluster(n_workers=workers, threads_per_worker=1, processes=True, host="127.0.0.1",
                          dashboard_address="127.0.0.1:0", silence_logs=logging.CRITICAL) as cluster, \
                Client(cluster) as client:
            futs = [client.submit(sweep_flight, str(dataset), r, grid, sigma2_from, pure=False) for r in ok]
            done: dict[str, list[dict]] = {}
            for f in as_completed(futs):
                res = f.result()
                done[res[0]["flight_id"]] = res
                if on_flight:
                    on_flight(res[0]["flight_id"])
            for r in ok:  # flight order, whatever the completion order
                rows += done[r["flight_id"]]
    table = pa.Table.from_pylist(rows)
    if out is not None:
        from flightmode.scenarios.dataset import _atomic_parquet

        _atomic_parquet(table, Path(out))
    return table, failed


def summarise(table, confidence: float = 0.95, target_rate_per_h: float | None = None) -> list[dict]:
    """One row per grid point over all flights: events, in-window hours, rate, its exact upper bound,
    response p50/p95/max, availability, and the hours still needed for ``target_rate_per_h``."""
    from flightmode.detector.confidence import hours_needed, rate_upper_bound

    keys = ["method", "weight", "window_s", "k", "time_threshold_s"]
    df = table.select(keys + ["in_window_h", "false_static_count", "false_static_s", "response_s", "availability",
                              "flight_id"]).to_pydict()
    groups: dict[tuple, list[int]] = {}
    for i in range(len(df["k"])):
        groups.setdefault(tuple(df[k][i] for k in keys), []).append(i)
    out = []
    for key, idx in groups.items():
        hours = float(sum(df["in_window_h"][i] for i in idx))
        events = int(sum(df["false_static_count"][i] for i in idx))
        resp = np.array([df["response_s"][i] for i in idx], float)
        resp = resp[np.isfinite(resp)]
        avail = np.array([df["availability"][i] for i in idx], float)
        row = dict(zip(keys, key)) | {
            "flights": len(idx), "in_window_h": hours, "false_statics": events,
            "false_static_s": float(sum(df["false_static_s"][i] for i in idx)),
            "rate_per_h": events / hours if hours > 0 else math.nan,
            "rate_upper_per_h": rate_upper_bound(events, hours, confidence) if hours > 0 else math.nan,
            "response_p50_s": float(np.percentile(resp, 50)) if resp.size else math.nan,
            "response_p95_s": float(np.percentile(resp, 95)) if resp.size else math.nan,
            "response_max_s": float(resp.max()) if resp.size else math.nan,
            "no_response": int(len(idx) - resp.size),
            "availability": float(np.nanmean(avail)) if np.isfinite(avail).any() else math.nan,
        }
        if target_rate_per_h is not None:  # in-window flight-hours the claim needs, with this many events
            row["hours_needed"] = hours_needed(target_rate_per_h, confidence, events)
            row["hours_short"] = max(0.0, row["hours_needed"] - hours)
        out.append(row)
    return out


def breakdown(table, point: dict) -> list[dict]:
    """At one grid point (``method``, ``weight``, ``window_s``, ``k``, ``time_threshold_s``): per
    condition (:data:`CONDITIONS`) and value, the flights, in-window hours, false statics, and the
    response p95, so that the conditions that produce false statics or slow responses stand out."""
    keys = ("method", "weight", "window_s", "k", "time_threshold_s")
    rows = [r for r in table.to_pylist() if all(r[k] == point[k] for k in keys)]
    out = []
    for cond in CONDITIONS:
        for value in sorted({str(r[cond]) for r in rows}):
            sel = [r for r in rows if str(r[cond]) == value]
            resp = np.array([r["response_s"] for r in sel], float)
            resp = resp[np.isfinite(resp)]
            out.append({"condition": cond, "value": value or "none", "flights": len(sel),
                        "in_window_h": float(sum(r["in_window_h"] for r in sel)),
                        "false_statics": int(sum(r["false_static_count"] for r in sel)),
                        "response_p95_s": float(np.percentile(resp, 95)) if resp.size else math.nan})
    return out


__all__ = ["sweep", "sweep_flight", "summarise", "breakdown", "CONDITIONS"]
