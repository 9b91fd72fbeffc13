"""Detector thresholds over whole datasets: ``flightmode sweep DATASET... --k ... --time-threshold-s ...``.

Every flight of one or more datasets made by ``flightmode dataset`` is read once and the grid
evaluated on it with each moving variance computed once (:func:`flightmode.detector.grid.
evaluate_grid`); flights run in this process, or one Dask task per flight (``workers`` > 1: a
LocalCluster on 127.0.0.1). Failed flights are excluded and counted, never silently.

sigma^2: ``preset`` (default) is the bench calibration of the flight's own sensor unit, exactly as the
dataset's own detector run did it (the unit and the bench stream regenerated from the flight's
scenario and seed: :func:`flightmode.runs.pipeline.unit_sigma2`); ``rest`` the truly static
samples the tracker saw before the flight.

The sweep folder (written file by file, atomically; ``sweep.json`` last):

- ``points.parquet``: per grid point and flight, false statics inside the in-flight window (count,
  seconds, the longest, their phases), the suspension latency (from pushback to the first check that
  forbids transmission), the response at the destination (truly at rest to the first final static),
  the availability (the share of truly-static check time outside the window reported static) and the
  flight's conditions (type, placement, turbulence, landing, sensor) for breakdowns;
- ``phases.parquet``: per (method, weight, window, k), flight and phase, the in-window checks and
  those under ``k sigma^2`` on each axis and on all three at once (eq. 7's temporary static): the
  per-phase form of seed 000's Tables 4-5;
- ``static.parquet``: per (method, weight, window) and flight, the moving variance of every check
  whose whole window is truly static, in units of sigma^2, as moments and log-binned histograms
  (:data:`STATIC_EDGES`) per axis and of the largest axis: the data of seed 000 section 5.1.1;
- ``sweep.json``: the datasets (family, manifest digest, flights used and excluded), the grid, the
  sigma^2 source and the versions.

Detectors of the interface (``detectors``: :mod:`flightmode.studies.detectors`) are swept beside the
grid: each point runs per sample on each stream and is scored per sample
(:func:`flightmode.detector.decisions.score`); its rows carry the detector's label as ``method``, its
parameters as JSON in ``params`` (``""`` for the grid's points) and 0 in ``weight``, ``window_s``,
``k`` and ``time_threshold_s``; ``in_flight_checks`` and ``checks`` count samples, and its phase rows
count in-window samples and those it called at rest (``under_*``); ``seconds`` is every phase row's
in-window time. A detector whose factory has ``grid_method`` is swept by the grid's fast path.

Per grid point (:func:`summarise`): the false-static rate per in-window flight-hour and its exact
upper bound (:mod:`flightmode.detector.confidence`), response p50/p95/max, mean availability.
"""

from __future__ import annotations

import hashlib
import json
import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from flightmode.cluster import map_flights
from flightmode.errors import InputDataError

CONDITIONS = (
    "aircraft",
    "placement",
    "carrier_kind",
    "turbulence",
    "landing_quality",
    "sensor_preset",
    "family",
)
# a built-in grid's point; a sweep's rows add ``params`` (POINT_ID): "" for the grid's points, the
# parameters as JSON of a detector of the interface (method = its label, the other four 0)
POINT_KEYS = ("method", "weight", "window_s", "k", "time_threshold_s")
POINT_ID = (*POINT_KEYS, "params")
# log-spaced bins of MV / sigma^2 for truly static checks: 1e-2 to 1e3, 2.3 % wide (underflow and
# overflow folded into the first and last bins, which a threshold search never reaches)
STATIC_EDGES = np.geomspace(1e-2, 1e3, 501)
AXES = ("x", "y", "z")
MV_METHODS = ("nmv", "emv")  # seed 000's moving variance; any other method is one of seed 001's detectors
SWEEP_FORMAT = 4  # the sweep folder's layout (read_sweep refuses others: sweep again)


@dataclass(frozen=True)
class SweepResult:
    points: object  # pyarrow Table
    phases: object
    static: object
    failed: list[dict]  # excluded flights' manifest rows (with "dataset")
    meta: dict


def manifest_digest(dataset: str | Path) -> str:
    """SHA-256 over each flight's id, status and samples digest, in flight order: equal digests mean
    the same flights with bit-identical samples."""
    from flightmode.datasets.make import read_manifest

    rows = read_manifest(Path(dataset))
    h = hashlib.sha256()
    for i in sorted(rows):
        r = rows[i]
        h.update(f"{r['flight_id']}|{r['status']}|{r.get('samples_sha256') or ''}\n".encode())
    return h.hexdigest()


def sigma2_of_flight(source: str, row: dict, columns: dict) -> Callable[[int], np.ndarray]:
    """sigma^2 per axis of one dataset flight's stream, as a function of the window (samples):
    ``preset``, the bench calibration of the unit its sensing drew (what its own detector used);
    ``rest``, its truly static samples before the flight."""
    from flightmode.detector.recommended import sigma2_from_rest
    from flightmode.runs import pipeline
    from flightmode.scenarios.scenario import Scenario
    from flightmode.sim.sensor.accelerometer import draw_unit

    sc = Scenario.from_toml_text(row["scenario_toml"], f"flight {row['flight_id']}")
    preset = pipeline.sensor_preset(sc.sensor)
    if source == "preset":
        # the unit sensing drew (stream sensor/unit) and the bench stream of the run's own detector
        unit = draw_unit(preset, pipeline.streams_of(sc.seed).child("sensor").rng("unit")).as_dict()
        return lambda window: pipeline.unit_sigma2(
            preset.name, preset.odr_hz, unit, window, pipeline.streams_of(sc.seed).rng("detector/bench")
        )
    if source == "rest":
        return lambda window: sigma2_from_rest(
            columns["acc_g"], columns["sensor_static"], columns["in_flight_window"], window, preset.lsb_g
        )[0]
    raise InputDataError(f"--sigma2-from {source!r}: use preset or rest")


def _static_stats(mv: np.ndarray, sigma2: np.ndarray, whole_static: np.ndarray) -> dict:
    """Moments and histograms of MV / sigma^2 over the checks whose whole window is truly static."""
    r = mv[whole_static] / sigma2[None, :]
    out: dict = {"static_checks": int(r.shape[0])}
    folded = np.clip(r, STATIC_EDGES[0], STATIC_EDGES[-1] * (1 - 1e-9))  # the tails into the end bins
    for j, a in enumerate(AXES):
        out[f"sum_{a}"] = float(r[:, j].sum())
        out[f"sumsq_{a}"] = float(np.square(r[:, j]).sum())
        out[f"hist_{a}"] = np.histogram(folded[:, j], STATIC_EDGES)[0].tolist()
    out["hist_max"] = np.histogram(folded.max(axis=1), STATIC_EDGES)[0].tolist()
    return out


def flight_streams(dataset: str, row: dict, sensors: Sequence[str] | None):
    """(sensor preset, columns, scenario TOML) of each stream to sweep on one flight: the dataset's
    own samples, or the flight re-sensed from its full-rate truth with each preset of ``sensors``
    (the flight's own sensor streams, its carrier and floor: only the sensor differs)."""
    from flightmode.datasets.make import flight_file
    from flightmode.runs.run_io import read_samples

    if not sensors:
        cols, _ = read_samples(flight_file(dataset, row))
        yield row.get("sensor_preset"), cols, row["scenario_toml"]
        return
    from flightmode.datasets.flight import flight_track
    from flightmode.runs import pipeline
    from flightmode.scenarios.scenario import Scenario

    track = flight_track(dataset, row)
    sc = Scenario.from_toml_text(row["scenario_toml"], f"flight {row['flight_id']}")
    for preset in sensors:
        sc2 = sc.replace(sensor={"preset": preset, "odr_hz": None})
        rec = pipeline.sense(
            track,
            sc2.carrier,
            sc2.sensor,
            pipeline.streams_of(sc2.seed).child("sensor"),
            overrides=sc2.overrides,
        )
        cols = {
            "t_s": rec.t_s,
            "acc_g": rec.acc_g,
            "in_flight_window": rec.in_flight_window,
            "sensor_static": rec.sensor_static,
            "phase": rec.phase,
        }
        if rec.baro_pa is not None:
            cols |= {"baro_pa": rec.baro_pa, "baro_new": rec.baro_new}
        if rec.gyro_dps is not None:
            cols["gyro_dps"] = rec.gyro_dps
        yield preset, cols, sc2.to_toml()


def sweep_flight(
    dataset: str,
    row: dict,
    grid,
    sigma2_from: str = "preset",
    family: str = "",
    sensors: Sequence[str] | None = None,
    detectors: Sequence = (),
) -> dict:
    """Every grid point (of ``grid``, None for none, and of each detector entry of ``detectors``:
    :class:`flightmode.studies.detectors.Entry`) on one flight of a dataset (on each of ``sensors``,
    re-sensed, if given): {"points", "phases", "static"} lists of rows (module docstring)."""
    out: dict = {"points": [], "phases": [], "static": []}
    for preset, cols, text in flight_streams(dataset, row, sensors):
        part = _sweep_stream(
            cols,
            row | {"scenario_toml": text, "sensor_preset": preset},
            grid,
            sigma2_from,
            {"dataset": dataset, "family": family, "flight_id": row["flight_id"]},
            detectors,
        )
        for k in out:
            out[k] += part[k]
    return out


def grid_kind(method: str) -> str:
    """The ``kind`` of a grid method's registered factory (``flightmode.detector.builtin``'s
    declaration: moving_variance, redundant, activity; a flexible one's ``name:signal`` by its name);
    a DetectorError for a method the grid cannot sweep (use ``--detector``)."""
    from flightmode.detector import grid
    from flightmode.detector.interface import load
    from flightmode.errors import DetectorError

    kind = grid.grid_kind(method.partition(":")[0])
    if kind is None:  # the registry's own error for an unknown name, else: no grid of its own
        other = getattr(load(method.partition(":")[0], what="--method").factory, "kind", None)
        raise DetectorError(
            f"--method {method}: no grid of its own ({other}); sweep it with --detector {method}"
        )
    return kind


def _evaluate(t, acc, gyr, labels, grid, fs, sigma2_from, row, cols):
    """(method name, parameters, evaluation) for every point of the grid: the moving variance's
    (:func:`~flightmode.detector.grid.evaluate_grid`), the moving variance AND the pressure source's
    (``nmv+baro``, ``emv+baro``: the redundant rule, :func:`_pressure_gate`) and seed 001's detectors'
    (:func:`~flightmode.detector.activity.flight.evaluate_activity_grid`, calibrated on the same rest
    recording as sigma^2). Which of the three a method is, its registered factory's ``kind`` says
    (:func:`grid_kind`)."""
    import dataclasses

    from flightmode.detector.grid import evaluate_grid

    kinds = {m: grid_kind(m) for m, _ in grid.methods}
    mv = tuple(m for m in grid.methods if kinds[m[0]] == "moving_variance")
    if mv:
        for p, e in evaluate_grid(
            t,
            acc,
            labels,
            dataclasses.replace(grid, methods=mv),
            fs,
            sigma2_of_flight(sigma2_from, row, cols),
        ):
            yield p.method, p, e
    red = tuple((m.partition("+")[0], w) for m, w in grid.methods if kinds[m] == "redundant")
    if red:
        gate = _pressure_gate(row, cols)
        for p, e in evaluate_grid(
            t,
            acc,
            labels,
            dataclasses.replace(grid, methods=red),
            fs,
            sigma2_of_flight(sigma2_from, row, cols),
            gate=gate,
        ):
            yield f"{p.method}+baro", p, e
    others = [m for m, _ in grid.methods if kinds[m] == "activity"]
    if others:
        from flightmode.detector.activity import registry
        from flightmode.detector.activity.flight import evaluate_activity_grid

        bench = None
        for method in others:
            name, _, signal = method.partition(":")
            if registry.get(name).needs_gyro or signal not in ("", "acc"):
                bench_acc, bench_gyr = _gyro_rest(row, cols)
            else:
                bench = _rest_of(sigma2_from, row, cols, fs) if bench is None else bench
                bench_acc, bench_gyr = bench, None
            for p, e in evaluate_activity_grid(
                t,
                acc,
                gyr,
                labels,
                name,
                grid.windows_s,
                grid.ks,
                grid.time_thresholds_s,
                fs,
                bench_acc,
                signal or "acc",
                bench_gyr,
            ):
                yield method, p, e


def _gyro_rest(row: dict, cols: dict) -> tuple[np.ndarray, np.ndarray]:
    """The rest recording of the detectors that read the gyroscope: the truly static samples before the
    flight, both sensors (the bench recording models no gyroscope; a tracker zeroes its gyroscope at
    rest after power-on)."""
    from flightmode.runs import pipeline

    if cols.get("gyro_dps") is None:
        raise InputDataError(
            f"flight {row['flight_id']}: a gyroscope method needs gyro_*_dps in the samples; make the "
            'dataset from a family with [sensor].gyro (e.g. gyro = "bmi270")'
        )
    acc, gyr, _ = pipeline.stream_rest("rest", cols, None)
    if gyr is None:  # never: stream_rest cuts the gyro_dps checked above
        raise InputDataError(f"flight {row['flight_id']}: no gyroscope samples at rest before the flight")
    return acc, gyr


def _pressure_gate(row: dict, cols: dict):
    """The pressure source's "at rest" as of any time, from the flight's barometer (its default
    thresholds, the destination known: :func:`flightmode.runs.pipeline.pressure_params`)."""
    from flightmode.detector.pressure import detect_pressure, static_at
    from flightmode.runs import pipeline
    from flightmode.scenarios.scenario import Scenario

    if "baro_pa" not in cols or "baro_new" not in cols:
        raise InputDataError(
            f"flight {row['flight_id']}: --method ...+baro needs a barometer in the samples; make "
            "the dataset from a family with [sensor].baro (e.g. isolated-parcel)"
        )
    sc = Scenario.from_toml_text(row["scenario_toml"], f"flight {row['flight_id']}")
    baro = pipeline.baro_preset(sc.sensor)
    if baro is None:
        raise InputDataError(f"flight {row['flight_id']}: its scenario fits no barometer ([sensor].baro)")
    new = np.asarray(cols["baro_new"], bool)
    checks = detect_pressure(
        cols["t_s"][new], cols["baro_pa"][new], pipeline.pressure_params(sc, baro.odr_hz)
    )
    return lambda t_checks: static_at(checks, t_checks)


def _rest_of(source: str, row: dict, cols: dict, fs: float) -> np.ndarray:
    """The rest recording seed 001's detectors calibrate on: the unit's bench recording (the stream
    that gives sigma^2 for ``preset``), or the truly static samples before the flight (``rest``)."""
    import dataclasses

    from flightmode.runs import pipeline
    from flightmode.scenarios.scenario import Scenario
    from flightmode.sim.sensor.accelerometer import bench_static, draw_unit

    if source == "rest":
        return pipeline.stream_rest("rest", cols, None)[0]
    sc = Scenario.from_toml_text(row["scenario_toml"], f"flight {row['flight_id']}")
    preset = dataclasses.replace(pipeline.sensor_preset(sc.sensor), odr_hz=fs)
    unit = draw_unit(preset, pipeline.streams_of(sc.seed).child("sensor").rng("unit"))
    return bench_static(preset, unit, pipeline.streams_of(sc.seed).rng("detector/bench")).acc_g


def _sweep_stream(cols: dict, row: dict, grid, sigma2_from: str, key: dict, detectors: Sequence = ()) -> dict:
    t, acc = cols["t_s"], cols["acc_g"]
    fs = round(1.0 / float(np.median(np.diff(t))), 6)
    labels = {k: cols[k] for k in ("in_flight_window", "sensor_static", "phase")}
    window = np.asarray(labels["in_flight_window"], bool)
    static = np.asarray(labels["sensor_static"], bool)
    phase_names, phase_code = np.unique(
        np.asarray(labels["phase"], dtype=object).astype(str), return_inverse=True
    )
    static_cs = np.concatenate([[0], np.cumsum(static)])
    dt = 1.0 / fs
    in_window_h = float(window.sum()) * dt / 3600.0
    w_start = float(t[np.flatnonzero(window)[0]]) if window.any() else math.nan
    # truly at rest after the flight: a response that never comes is then infinitely slow (inf), not
    # missing (NaN: nothing to answer), so that percentiles count it
    rest_after = bool(window.any() and static[int(np.flatnonzero(window)[-1]) :].any())
    key = key | {"sensor_preset": row.get("sensor_preset"), "fs_hz": fs}
    cond = {k: row.get(k) for k in CONDITIONS if k not in ("family", "sensor_preset")}
    points, phases, statics = [], [], []
    seen: set[tuple] = set()
    from flightmode.studies.detectors import fast_grid

    runs = [_evaluate(t, acc, cols.get("gyro_dps"), labels, grid, fs, sigma2_from, row, cols)] if grid else []
    plugins = []
    for entry in detectors:  # a built-in with a grid fast path is swept by it, under its label
        g = fast_grid(entry)
        if g is None:
            plugins.append(entry)
        else:
            runs.append(
                (entry.name, p, e)
                for _, p, e in _evaluate(t, acc, cols.get("gyro_dps"), labels, g, fs, sigma2_from, row, cols)
            )
    for method, p, e in (x for run in runs for x in run):
        c = e.checks
        base = (method, p.weight, p.window_s)
        mv_method = p.method in MV_METHODS
        bk = {**key, "method": method, "weight": p.weight, "window_s": p.window_s, "params": ""}
        in_w = window[c.index]
        codes = phase_code[c.index][in_w]
        if (*base, p.k_sigma) not in seen:  # once per (detector run, k): per-phase checks under k
            seen.add((*base, p.k_sigma))
            n_ph = np.bincount(codes, minlength=len(phase_names))
            if mv_method:
                below = (c.mv < p.k_sigma * e.sigma2[None, :])[in_w]  # eq. 7, per axis
            else:  # seed 001's detectors: one merit for the three axes
                below = np.repeat(c.temporary_static[in_w][:, None], 3, axis=1)
            under = [np.bincount(codes[below[:, j]], minlength=len(phase_names)) for j in range(3)]
            under_all = np.bincount(codes[below.all(axis=1)], minlength=len(phase_names))
            for i, name in enumerate(phase_names):
                if n_ph[i]:
                    phases.append(
                        {
                            **bk,
                            "k": p.k_sigma,
                            "phase": str(name),
                            "checks": int(n_ph[i]),
                            "under_x": int(under[0][i]),
                            "under_y": int(under[1][i]),
                            "under_z": int(under[2][i]),
                            "under_all": int(under_all[i]),
                            "seconds": float(n_ph[i]) * p.window_s,
                        }
                    )
        if mv_method and base not in seen:  # once per moving variance: the static MV in sigma^2 units
            seen.add(base)
            whole = (c.index + 1 >= p.window) & (
                static_cs[c.index + 1] - static_cs[np.maximum(c.index + 1 - p.window, 0)] == p.window
            )
            statics.append({**bk, **_static_stats(c.mv, e.sigma2, whole)})
        truth_out = static[c.index] & ~window[c.index]
        static_s = float(truth_out.sum()) * p.window_s
        after = np.flatnonzero((c.t_s >= w_start) & ~c.final_static) if window.any() else np.zeros(0, int)
        events = e.false_static_events
        points.append(
            {
                **key,
                **cond,
                "method": method,
                "weight": p.weight,
                "window_s": p.window_s,
                "k": p.k_sigma,
                "time_threshold_s": p.time_threshold_s,
                "params": "",
                "in_window_h": in_window_h,
                "in_flight_checks": e.in_flight_checks,
                "false_static_count": e.false_static_count,
                "false_static_s": e.false_static_s,
                "longest_false_static_s": max((ev["duration_s"] for ev in events), default=0.0),
                "false_static_phases": ",".join(ev["phase"] for ev in events),
                "suspend_s": float(c.t_s[after[0]] - w_start) if after.size else math.nan,
                "response_s": e.response_s
                if e.response_s is not None
                else (math.inf if rest_after else math.nan),
                "static_s": static_s,
                "missed_static_s": e.missed_static_s,
                "checks": int(c.t_s.shape[0]),
                "accuracy": e.accuracy,
                "availability": (static_s - e.missed_static_s) / static_s if static_s > 0 else math.nan,
            }
        )
    for entry in plugins:
        from flightmode.studies.detectors import params_text, run_entry

        sample_codes = phase_code[window]
        n_ph = np.bincount(sample_codes, minlength=len(phase_names))
        for params, dec, d in run_entry(entry, cols, row, fs, sigma2_from, _rest_of):
            pk = {"method": entry.name, "weight": 0.0, "window_s": 0.0, "k": 0.0}
            text = params_text(params)
            at_rest = np.bincount(sample_codes[dec[window]], minlength=len(phase_names))
            for i, name in enumerate(phase_names):
                if n_ph[i]:  # per phase: in-window samples, and those the detector called at rest
                    u = int(at_rest[i])
                    phases.append(
                        {**key, **pk, "params": text, "phase": str(name), "checks": int(n_ph[i])}
                        | {"under_x": u, "under_y": u, "under_z": u, "under_all": u}
                        | {"seconds": float(n_ph[i]) * d.dt_s}
                    )
            s = d.summary()
            points.append(
                {**key, **cond, **pk, "time_threshold_s": 0.0, "params": text, "in_window_h": in_window_h}
                | {k: s[k] for k in ("false_static_count", "false_static_s", "longest_false_static_s")}
                | {
                    "in_flight_checks": d.in_flight_samples,
                    "false_static_phases": s["false_static_phases"],
                    "suspend_s": d.suspend_s,
                    "response_s": d.response_s
                    if d.response_s is not None
                    else (math.inf if d.rest_after else math.nan),
                    "static_s": d.static_s,
                    "missed_static_s": d.missed_static_s,
                    "checks": d.samples,
                    "accuracy": d.accuracy,
                    "availability": d.availability,
                }
            )
    return {"points": points, "phases": phases, "static": statics}


def _versions() -> dict:
    import platform
    from importlib.metadata import PackageNotFoundError, version

    out = {"python": platform.python_version()}
    for pkg in ("flightmode", "numpy", "scipy", "pyarrow", "jsbsim"):
        try:
            out[pkg] = version(pkg)
        except PackageNotFoundError:
            out[pkg] = "not installed"
    return out


def check_request(
    datasets: str | Path | Sequence[str | Path],
    grid,
    sigma2_from: str = "preset",
    sensors: Sequence[str] | None = None,
    detectors: Sequence = (),
) -> list[Path]:
    """The dataset folders, once each, every one a dataset with a successful flight (and its full-rate
    truth if ``sensors`` re-sense it); the grid's axes; the detector entries (each loads, each label
    once: :func:`flightmode.studies.detectors.check`); the sigma^2 source; the sensor presets. An
    InputDataError, DetectorError or SensorError naming what is wrong; reads only."""
    paths = [Path(datasets)] if isinstance(datasets, (str, Path)) else [Path(d) for d in datasets]
    if not paths:
        raise InputDataError("no dataset given: name at least one folder made by `flightmode dataset`")
    if len({p.resolve() for p in paths}) != len(paths):
        raise InputDataError("the same dataset is named twice: its flights would count double")
    if sigma2_from not in ("preset", "rest"):
        raise InputDataError(f"--sigma2-from {sigma2_from!r}: use preset or rest")
    if grid is None and not detectors:
        raise InputDataError("nothing to sweep: give --method or --detector (or --grid-file)")
    if grid is not None:
        grid.check_axes()
    if detectors:
        from flightmode.studies.detectors import check

        check(detectors, [m for m, _ in grid.methods] if grid is not None else [])
    if sensors is not None:
        from flightmode.sim.sensor.accelerometer import get_preset

        if not sensors or len(set(sensors)) != len(sensors):
            raise InputDataError(f"--sensor {','.join(sensors)!r}: name each preset once, at least one")
        for name in sensors:
            get_preset(name)  # a SensorError with the presets to choose from
    from flightmode.datasets.make import ok_flights

    seen: dict[str, str] = {}
    for d in paths:
        ok, _, _ = ok_flights(d, full_truth_for="--sensor re-senses each flight" if sensors else None)
        for r in ok:  # the same flight twice would count its hours and events twice
            other = seen.setdefault(r["samples_sha256"], f"{d}/{r['flight_id']}")
            if other != f"{d}/{r['flight_id']}":
                raise InputDataError(
                    f"{d}: flight {r['flight_id']} has the very samples of {other}: the same flight "
                    "in two datasets would count twice; name each dataset once"
                )
    return paths


def sweep(
    datasets: str | Path | Sequence[str | Path],
    grid,
    *,
    sigma2_from: str = "preset",
    workers: int = 1,
    sensors: Sequence[str] | None = None,
    out: str | Path | None = None,
    on_start: Callable[[int], None] | None = None,
    on_flight: Callable[[str], None] | None = None,
    scheduler: str | None = None,
    detectors: Sequence = (),
) -> SweepResult:
    """Evaluate ``grid`` (None: none) and the ``detectors`` (:class:`flightmode.studies.detectors.
    Entry`, each point run per sample on each stream) on every successful flight of ``datasets`` (module docstring); the failed
    flights are excluded and returned. ``sensors``: re-sense each flight with each of these presets
    (datasets made with ``--truth full``) instead of reading its samples. Writes the sweep folder
    ``out`` if given. ``on_start(flights)`` and ``on_flight(flight_id)`` report progress. One Dask
    task per flight on ``workers`` local processes, or on the Dask ``scheduler`` at that address
    (:func:`flightmode.cluster.map_flights`)."""
    import pyarrow as pa
    import pyarrow.parquet as pq

    from flightmode.datasets.make import ok_flights

    paths = check_request(datasets, grid, sigma2_from, sensors, detectors)
    sensors = tuple(sensors) if sensors else None
    detectors = tuple(detectors)
    jobs, failed, described = [], [], []
    for d in paths:
        ok, bad, meta = ok_flights(d)
        family = meta.get("family", "")
        jobs += [(str(d), r, family) for r in ok]
        failed += bad
        described.append(
            {
                "path": str(d),
                "family": family,
                "family_sha256": meta.get("family_sha256"),
                "options": meta.get("options"),
                "manifest_sha256": manifest_digest(d),
                "flights": len(ok) + len(bad),
                "flights_ok": len(ok),
                "failed": [r["flight_id"] for r in bad],
            }
        )
    d0, r0, _ = jobs[0]
    t0 = pq.read_table(Path(d0) / r0["samples_file"], columns=["t_s"])["t_s"].to_numpy()[:1000]
    if grid is not None:  # a window under 2 samples, before any work
        grid.validate(round(1.0 / float(np.median(np.diff(t0))), 6))
    if on_start:
        on_start(len(jobs))
    results = map_flights(
        sweep_flight,
        [(d, r, grid, sigma2_from, fam, sensors, detectors) for d, r, fam in jobs],
        workers,
        (lambda n: on_flight(jobs[n][1]["flight_id"])) if on_flight else None,
        scheduler=scheduler,
    )
    tables = {
        part: pa.Table.from_pylist([row for res in results for row in res[part]])
        for part in ("points", "phases", "static")
    }
    meta = {
        "format": SWEEP_FORMAT,
        "datasets": described,
        "sigma2_from": sigma2_from,
        "sensors": list(sensors) if sensors else None,
        "grid": None
        if grid is None
        else {
            "methods": [list(m) for m in grid.methods],
            "windows_s": list(grid.windows_s),
            "ks": list(grid.ks),
            "time_thresholds_s": list(grid.time_thresholds_s),
            "points": len(grid),
        },
        "detectors": [e.as_dict() for e in detectors],
        "static_edges": "geomspace(1e-2, 1e3, 501)",
        "versions": _versions(),
    }
    result = SweepResult(tables["points"], tables["phases"], tables["static"], failed, meta)
    if out is not None:
        write_sweep(result, out)
    return result


def write_sweep(result: SweepResult, out: str | Path) -> None:
    """The sweep folder (module docstring); ``sweep.json`` last, so a folder without it is incomplete."""
    from flightmode.atomic import write_parquet as atomic_parquet
    from flightmode.atomic import write_text as atomic_text

    out = Path(out)
    if out.exists() and not out.is_dir():
        raise InputDataError(f"--out {out} is a file: give a folder for the sweep")
    out.mkdir(parents=True, exist_ok=True)
    (out / "sweep.json").unlink(missing_ok=True)
    for part in ("points", "phases", "static"):
        atomic_parquet(getattr(result, part), out / f"{part}.parquet")
    atomic_text(
        json.dumps(
            result.meta
            | {
                "failed_flights": [
                    {"dataset": r["dataset"], "flight_id": r["flight_id"], "error": r.get("error")}
                    for r in result.failed
                ]
            },
            indent=2,
        ),
        out / "sweep.json",
    )


def read_sweep(path: str | Path) -> SweepResult:
    """A sweep folder written by :func:`sweep` (InputDataError if it is missing, incomplete or damaged)."""
    from flightmode.atomic import read_parquet

    path = Path(path)
    if not (path / "sweep.json").exists():
        raise InputDataError(
            f"{path}: no sweep.json: not a finished sweep (run `flightmode sweep DATASET --out {path}`)"
        )
    meta = json.loads((path / "sweep.json").read_text())
    if meta.get("format") != SWEEP_FORMAT:
        raise InputDataError(
            f"{path}: a sweep of an older flightmode (format {meta.get('format', 1)}); "
            f"sweep again (`flightmode sweep DATASET --out {path}`)"
        )
    tables = {
        part: read_parquet(path / f"{part}.parquet", "sweep's table")
        for part in ("points", "phases", "static")
    }
    failed = [dict(r) for r in meta.pop("failed_flights", [])]
    return SweepResult(tables["points"], tables["phases"], tables["static"], failed, meta)


def summarise(
    table, confidence: float = 0.95, target_rate_per_h: float | None = None, by_sensor: bool = False
) -> list[dict]:
    """One row per grid point over all flights: events, in-window hours, rate, its exact upper bound,
    response p50/p95/max (a flight that never answered counts as infinitely slow), availability (the
    share of all truly static time reported static), and the hours still needed for
    ``target_rate_per_h``. ``by_sensor``: a point per sensor preset too (a sweep with ``--sensor``
    re-senses the same flights: their hours must not add up across presets)."""
    from flightmode.detector.confidence import hours_needed, rate_and_response

    table = with_params(table)
    keys = list(POINT_ID) + (["sensor_preset"] if by_sensor else [])
    df = table.select(
        keys
        + [
            "in_window_h",
            "false_static_count",
            "false_static_s",
            "response_s",
            "static_s",
            "missed_static_s",
            "suspend_s",
        ]
    ).to_pydict()
    groups: dict[tuple, list[int]] = {}
    for i in range(len(df["k"])):
        groups.setdefault(tuple(df[k][i] for k in keys), []).append(i)
    out = []
    for key, idx in groups.items():
        hours = float(sum(df["in_window_h"][i] for i in idx))
        events = int(sum(df["false_static_count"][i] for i in idx))
        resp = np.array([df["response_s"][i] for i in idx], float)
        susp = np.array([df["suspend_s"][i] for i in idx], float)
        susp = susp[np.isfinite(susp)]
        static_s = float(sum(df["static_s"][i] for i in idx))
        missed_s = float(sum(df["missed_static_s"][i] for i in idx))
        row = dict(zip(keys, key)) | {
            "flights": len(idx),
            "false_static_s": float(sum(df["false_static_s"][i] for i in idx)),
            **rate_and_response(events, hours, resp, confidence),
            "suspend_max_s": float(susp.max()) if susp.size else math.nan,
            "availability": (static_s - missed_s) / static_s if static_s > 0 else math.nan,
        }
        if target_rate_per_h is not None:  # in-window flight-hours the claim needs, with this many events
            row["hours_needed"] = hours_needed(target_rate_per_h, confidence, events)
            row["hours_short"] = max(0.0, row["hours_needed"] - hours)
        out.append(row)
    return out


def rank_points(rows: list[dict]) -> list[dict]:
    """:func:`summarise`'s rows best first: the lowest upper bound on false statics per flight-hour,
    then the fastest response p95, then the highest availability; a point nothing could measure (NaN)
    last, ties in a fixed order of the grid's keys."""

    def fin(v, sign=1.0):
        return sign * v if v == v else math.inf

    return sorted(
        rows,
        key=lambda r: (
            fin(r["rate_upper_per_h"]),
            fin(r["response_p95_s"]),
            fin(r["availability"], -1.0),
            r["method"],
            r["weight"],
            r["window_s"],
            r["k"],
            r["time_threshold_s"],
            r.get("params", ""),
        ),
    )


def compare_methods(table, confidence: float = 0.95) -> list[dict]:
    """Each method at its best grid point (among the points that answer at the gate, the lowest upper
    bound on false statics per flight-hour, then the fastest response p95; :func:`summarise`'s row), with its accuracy (per check, weighted by the
    flights' checks) and the area under its ROC curve: the threshold k swept at that point's window and
    time threshold (seed 001's "ROC at the best window"), false-positive rate = the in-window checks
    declared static, true-positive rate = the truly static time reported static (availability), the
    curve closed at (0, 0) and (1, 1). Sorted as the points are chosen."""
    table = with_params(table)
    rows = summarise(table, confidence)
    d = table.select(
        [
            "method",
            "weight",
            "window_s",
            "k",
            "time_threshold_s",
            "in_flight_checks",
            "false_static_s",
            "static_s",
            "missed_static_s",
            "checks",
            "accuracy",
            "params",
            "in_window_h",
        ]
    ).to_pydict()
    n = len(d["k"])
    out = []
    for method in dict.fromkeys(r["method"] for r in rows):
        mine = [r for r in rows if r["method"] == method]
        # a point that leaves some flight's bag unanswered at the gate (p95 inf) is no candidate while another answers
        best = min(
            mine,
            key=lambda r: (
                not math.isfinite(r["response_p95_s"]),
                r["rate_upper_per_h"],
                r["response_p95_s"],
                r["k"],
            ),
        )
        key = (method, best["weight"], best["window_s"], best["time_threshold_s"])
        fpr: dict[tuple[float, str], list[float]] = {}
        acc_num = acc_den = 0.0
        for i in range(n):
            if (d["method"][i], d["weight"][i], d["window_s"][i], d["time_threshold_s"][i]) != key:
                continue
            k = (d["k"][i], d["params"][i])  # a detector of the interface: its grid's points
            f = fpr.setdefault(k, [0.0, 0.0, 0.0, 0.0])
            f[0] += d["false_static_s"][i]
            # in-window time: the checks' (W_s each) or, per sample, the window's
            f[1] += (
                d["in_flight_checks"][i] * d["window_s"][i]
                if not d["params"][i]
                else d["in_window_h"][i] * 3600
            )
            f[2] += d["static_s"][i] - d["missed_static_s"][i]
            f[3] += d["static_s"][i]
            if k == (best["k"], best["params"]) and d["checks"][i] and not math.isnan(d["accuracy"][i]):
                acc_num += d["accuracy"][i] * d["checks"][i]
                acc_den += d["checks"][i]
        pts = sorted(
            (f[0] / f[1] if f[1] else math.nan, f[2] / f[3] if f[3] else math.nan) for f in fpr.values()
        )
        pts = [(0.0, 0.0)] + [p for p in pts if not any(map(math.isnan, p))] + [(1.0, 1.0)]
        x, y = np.array(pts).T
        auc = float(np.trapezoid(y, x)) if len(pts) > 3 else math.nan  # two or more thresholds swept
        out.append(
            best
            | {"accuracy": acc_num / acc_den if acc_den else math.nan, "auc": auc, "roc_points": len(pts) - 2}
        )
    return sorted(
        out,
        key=lambda r: (not math.isfinite(r["response_p95_s"]), r["rate_upper_per_h"], r["response_p95_s"]),
    )


def where(table, values: dict):
    """The rows of a sweep table (points, phases or static) whose columns equal ``values``."""
    import pyarrow.compute as pc

    mask = None
    for k, v in values.items():
        m = pc.equal(table[k], v)
        mask = m if mask is None else pc.and_(mask, m)
    return table if mask is None else table.filter(mask)


def at_point(table, point: dict) -> list[dict]:
    """The rows of one grid point (``method``, ``weight``, ``window_s``, ``k``, ``time_threshold_s``,
    ``params``: "" if not given, a built-in grid's point; and ``sensor_preset`` if the point names one)."""
    keys = POINT_ID + (("sensor_preset",) if "sensor_preset" in point else ())
    return where(
        with_params(table), {k: point.get(k, "") if k == "params" else point[k] for k in keys}
    ).to_pylist()


def with_params(table):
    """``table`` with a ``params`` column ("" in every row: a built-in grid's points) if it has none
    (a table made by hand of a built-in grid's rows)."""
    import pyarrow as pa

    if "params" in table.column_names:
        return table
    return table.append_column("params", pa.array([""] * table.num_rows, pa.string()))


def breakdown(table, point: dict, phases=None) -> list[dict]:
    """At one grid point: per condition (:data:`CONDITIONS`) and value, the flights, in-window hours,
    false statics, and the response p95, so that the conditions that produce false statics or slow
    responses stand out. With the sweep's ``phases`` table, also per phase of the flight: the
    in-window hours spent in it and the false statics that began in it."""
    rows = at_point(table, point)
    out = []
    for cond in CONDITIONS:
        for value in sorted({str(r.get(cond)) for r in rows}):
            sel = [r for r in rows if str(r.get(cond)) == value]
            resp = np.array([r["response_s"] for r in sel], float)
            resp = resp[~np.isnan(resp)]
            out.append(
                {
                    "condition": cond,
                    "value": value or "none",
                    "flights": len(sel),
                    "in_window_h": float(sum(r["in_window_h"] for r in sel)),
                    "false_statics": int(sum(r["false_static_count"] for r in sel)),
                    "false_static_s": float(sum(r["false_static_s"] for r in sel)),
                    "response_p95_s": float(np.percentile(resp, 95, method="higher"))
                    if resp.size
                    else math.nan,
                }
            )
    if phases is not None:
        keys = ("method", "weight", "window_s", "k") + (
            ("sensor_preset",) if "sensor_preset" in point else ()
        )
        phases = with_params(phases)
        point = point | {"params": point.get("params", "")}
        hours: dict[str, float] = {}
        flights: dict[str, set] = {}
        for r in (
            where(phases, {k: point[k] for k in (*keys, "params")})
            .select(
                ["phase", "checks", "dataset", "flight_id"]
                + (["seconds"] if "seconds" in phases.column_names else [])
            )
            .to_pylist()
        ):  # in-phase time: the rows' own (checks x W_s, or samples x dt), else the checks' at W_s
            sec = r.get("seconds", r["checks"] * point["window_s"])
            hours[r["phase"]] = hours.get(r["phase"], 0.0) + sec / 3600.0
            flights.setdefault(r["phase"], set()).add((r["dataset"], r["flight_id"]))
        events: dict[str, int] = {}
        for r in rows:
            for ph in filter(None, (r["false_static_phases"] or "").split(",")):
                events[ph] = events.get(ph, 0) + 1
        for ph in sorted(hours, key=lambda p: -hours[p]):
            out.append(
                {
                    "condition": "phase",
                    "value": ph,
                    "flights": len(flights[ph]),
                    "in_window_h": hours[ph],
                    "false_statics": events.get(ph, 0),
                    "false_static_s": math.nan,
                    "response_p95_s": math.nan,
                }
            )
    return out


__all__ = [
    "rank_points",
    "sweep",
    "check_request",
    "where",
    "sweep_flight",
    "write_sweep",
    "read_sweep",
    "summarise",
    "breakdown",
    "at_point",
    "manifest_digest",
    "SweepResult",
    "CONDITIONS",
    "POINT_KEYS",
    "POINT_ID",
    "STATIC_EDGES",
]
