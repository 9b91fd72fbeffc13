"""Benchmark: `flightmode dataset` throughput on Dask, and its overhead per flight.

    python benchmarks/bench_dataset.py [N] [FAMILY]

All in the same run, on the family's first N members (default 6 of ``regional-hops``):

- baseline: each member run in this process by ``flightmode.run`` (fly, sense, detect) with its
  samples and truth written as Parquet (what a dataset flight writes), one after the other;
- the dataset with a LocalCluster of 1 worker process, then of 2 (each into a fresh folder).

Reported: flights per hour for each, the scaling efficiency (2 workers' flights per hour over twice
1 worker's; goal >= 0.8), the overhead per flight (1 worker's wall time per flight over the baseline's,
scheduling, serialisation and writing included; goal <= 1.25), the peak RSS per flight-hour of the
workers, and the MB per flight-hour of each part of the dataset.
"""

from __future__ import annotations

import json
import sys
import tempfile
from pathlib import Path

from _bench import report, timed


def _mb(root: Path, part: str) -> float:
    p = root / part
    files = [p] if p.is_file() else list(p.rglob("*.parquet"))
    return sum(f.stat().st_size for f in files) / 1e6


def main(n: int = 6, family: str = "regional-hops") -> dict:
    import flightmode
    from flightmode.datasets.make import make_dataset, read_manifest
    from flightmode.scenarios.family import Family

    fam = Family.resolve(family)
    members = list(fam.members(n))
    with tempfile.TemporaryDirectory() as d:
        flightmode.run(members[0], stages=("fly",))  # warm: imports, JSBSim's model files cached

        def baseline():
            for i, m in enumerate(members):
                flightmode.run(
                    m, stages=("fly", "sense", "detect", "write"), out=Path(d) / f"base{i}", rrd=False
                )

        _, t_base = timed(baseline)
        _, t1 = timed(lambda: make_dataset(fam, n, Path(d) / "w1", workers=1))
        _, t2 = timed(lambda: make_dataset(fam, n, Path(d) / "w2", workers=2))
        rows = read_manifest(Path(d) / "w2")
        hours = sum(r["gate_to_gate_s"] for r in rows.values() if r["status"] == "ok") / 3600.0
        timings = [json.loads(line) for line in (Path(d) / "w1" / "timings.jsonl").read_text().splitlines()]
        rss_per_h = max(t["peak_rss_mb"] / (t["gate_to_gate_s"] / 3600.0) for t in timings)
        root = Path(d) / "w2"
        res = {
            "family": fam.name,
            "flights": n,
            "flight_hours": hours,
            "baseline_s (in process, one by one)": t_base,
            "1 worker s": t1,
            "2 workers s": t2,
            "flights/h, 1 worker": n / t1 * 3600.0,
            "flights/h, 2 workers": n / t2 * 3600.0,
            "scaling efficiency (goal >= 0.8)": (t1 / t2) / 2.0,
            "overhead per flight, 1 worker / baseline (goal <= 1.25)": t1 / t_base,
            "peak RSS MB per flight-hour (worst flight)": rss_per_h,
            "samples MB per flight-hour (goal <= 20)": _mb(root, "samples") / hours,
            "truth (10 Hz) MB per flight-hour": _mb(root, "truth") / hours,
            "manifest MB per flight-hour": _mb(root, "flights.parquet") / hours,
            "failures": sum(r["status"] != "ok" for r in rows.values()),
        }
    report(res)
    return res


if __name__ == "__main__":
    main(*(int(a) if i == 0 else a for i, a in enumerate(sys.argv[1:3])))
