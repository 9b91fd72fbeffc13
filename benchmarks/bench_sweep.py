"""Benchmark: a detector grid over one flight against one detector run, same run.

    python benchmarks/bench_sweep.py [DATASET]

On the first flight of a dataset (default: a one-flight ``regional-hops`` dataset made here), timed,
best of 3: one detector run (batch :func:`~flightmode.detector.evaluation.evaluate` at seed 000's
point), and :func:`~flightmode.detector.grid.evaluate_grid` over 20 k x 10 time thresholds = 200 points
at one window and method (the moving variance computed once, each point a comparison and a run-length
pass), and over the same 200 points for each of NMV and EMV (w 5) and windows 0.5, 1 and 2 s (1,200
points, six moving variances). Goal: the 200-point grid in <= 3x the single run. Then what
``flightmode sweep`` does per flight (:func:`~flightmode.studies.sweep.sweep_flight`: read, the
unit's sigma^2, the default 624-point grid, per-phase counts, static histograms) against reading the
flight and running the detector once.
"""

from __future__ import annotations

import sys
import tempfile
from pathlib import Path

import numpy as np
from _bench import best, report


def main(dataset: str | None = None) -> dict:
    from flightmode.datasets.make import make_dataset

    with tempfile.TemporaryDirectory() as d:
        if dataset is None:
            dataset = str(Path(d) / "ds")
            make_dataset("regional-hops", 1, dataset, workers=1)
        return _measure(dataset)


def _measure(dataset: str) -> dict:
    from flightmode.datasets.make import read_manifest
    from flightmode.detector.evaluation import evaluate
    from flightmode.detector.flight_mode import DetectorParams
    from flightmode.detector.grid import Grid, evaluate_grid
    from flightmode.runs.run_io import read_samples

    row = next(r for r in read_manifest(Path(dataset)).values() if r["status"] == "ok")
    cols, _ = read_samples(Path(dataset) / row["samples_file"])
    t, acc = cols["t_s"], cols["acc_g"]
    fs = round(1.0 / float(np.median(np.diff(t))), 6)
    labels = {k: cols[k] for k in ("in_flight_window", "sensor_static", "phase")}
    s2 = np.var(acc[: int(60 * fs)], axis=0)  # any positive sigma^2: the cost does not depend on it
    one = DetectorParams(fs_hz=fs)
    ks = tuple(np.round(np.linspace(2.0, 8.0, 20), 3))
    tths = tuple(float(x) for x in range(1, 11))
    g200 = Grid((("nmv", 1.0),), (1.0,), ks, tths)
    g1200 = Grid((("nmv", 1.0), ("emv", 5.0)), (0.5, 1.0, 2.0), ks, tths)
    t_one = best(lambda: evaluate(t, acc, labels, one, s2))
    t200 = best(lambda: list(evaluate_grid(t, acc, labels, g200, fs, lambda w: s2)))
    t1200 = best(lambda: list(evaluate_grid(t, acc, labels, g1200, fs, lambda w: s2)))
    # what `flightmode sweep` does per flight with its default 624-point grid: read the samples,
    # regenerate the unit's bench sigma^2 per window, every point, the per-phase counts and the
    # static-MV histograms; against the same flight's one detector run with its reading
    from flightmode.studies.sweep import sweep_flight

    g624 = Grid(
        (("nmv", 1.0), ("emv", 5.0)),
        (0.5, 1.0, 2.0),
        tuple(np.arange(2.0, 8.01, 0.5)),
        tuple(float(x) for x in range(1, 9)),
    )
    t_read_one = best(lambda: evaluate(*_read(dataset, row, fs), one, s2))
    t624 = best(lambda: sweep_flight(str(dataset), row, g624, "preset", ""))
    res = {
        "samples": int(t.shape[0]),
        "one detector run s": t_one,
        "200-point grid s": t200,
        "200-point grid / one run (goal <= 3)": t200 / t_one,
        "1,200-point grid s": t1200,
        "1,200-point grid / one run": t1200 / t_one,
        "per point, 200 grid (ms)": t200 / 200 * 1e3,
        "read + one detector run s": t_read_one,
        "sweep_flight, 624-point default grid s": t624,
        "sweep_flight 624 / (read + one run)": t624 / t_read_one,
    }
    report(res)
    return res


def _read(dataset, row, fs):
    from flightmode.runs.run_io import read_samples

    cols, _ = read_samples(Path(dataset) / row["samples_file"])
    return cols["t_s"], cols["acc_g"], {k: cols[k] for k in ("in_flight_window", "sensor_static", "phase")}


if __name__ == "__main__":
    main(*sys.argv[1:2])
