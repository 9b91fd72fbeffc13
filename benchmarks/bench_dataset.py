"""Benchmark: `flightmode dataset` throughput on Dask, and its overhead per flight.

    python benchmarks/bench_dataset.py [N] [FAMILY]
    python benchmarks/bench_dataset.py rate [N] [FAMILY]     (default 6 members of airline-mix)

``rate``: in-window flight-hours per core-hour of the family's first N members made as ``flightmode
dataset`` makes them (fly, sense, detect, write; ``make_dataset`` with 2 workers on this machine's 2
cores, core-hours = wall time x 2), beside the limit bare JSBSim sets: 3,600 s / (bare seconds per step
x steps per flight-hour), the steps per flight-hour being the flight's FDM rate (the plan's ``fdm_hz``,
as sim/flight/simulate.py steps it) x 3,600. The bare seconds per step: the members' edited models
(benchmarks/_bench.py ``step_cost_table``), parked for their ground time and in a climb for their
airborne time, weighted by each member's steps. Reported: the figure, the limit and figure / limit
(target >= 0.6); and beside them the same bare stepping measured in as many processes at once as there
are workers (``_bench.concurrent_step_cost_table``), the limit the workers can reach on this machine
when its cores slow each other down, and the figure against it. Then the same flights once more on a
cluster whose workers are warm (imports done; in each worker, each aircraft type flown for a minute and
the pattern circuit flown, sensed and detected), as the workers of a long dataset are after their first
flights: the figure without the start-up that a six-flight run pays in full.

And the bound: the figure these flights would reach if each cost no more than its bare stepping (at
the limit's cost per step), its track's reads (``_bench.recording_stepping_s`` less bare stepping, per
type, times its steps), both at one process's cost, and its sensing and detection (as the dataset's
workers timed them: timings.jsonl's ``stages_s``): no pilot, gusts, roughness, track assembly,
writing, scheduling or start-up, and no two processes stepping slowing each other. No change to the
loop around JSBSim that keeps its per-step record can take figure / limit above bound / limit.

Without ``rate``:

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

from _bench import concurrent_step_cost_table, recording_stepping_s, report, step_cost_table, timed


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


def _in_window_s(path: Path) -> float:
    """Seconds of a samples file inside the in-flight window (pushback start to engines off)."""
    import numpy as np
    import pyarrow.parquet as pq

    t = pq.read_table(path, columns=["t_s", "in_flight_window"])
    ts = t["t_s"].to_numpy()
    win = t["in_flight_window"].to_numpy()
    return float(np.count_nonzero(win) * np.median(np.diff(ts)))


def _warm(scenario_tomls: list[str]) -> None:
    """On a worker: import what a flight needs; fly each scenario's first minute, and fly, sense and
    detect the pattern circuit."""
    from flightmode.runs import pipeline
    from flightmode.scenarios.scenario import Scenario

    for text in scenario_tomls:  # each type's model made and flown
        sc = Scenario.from_toml_text(text)
        pipeline.fly(sc, pipeline.streams_of(sc.seed).child("flight"), stop_after_s=60.0)
    # sensing and detection need a whole flight: the built-in pattern circuit's
    pipeline.run(Scenario.builtin("pattern"), stages=("fly", "sense", "detect"))


def rate(n: int = 6, family: str = "airline-mix", workers: int = 2) -> dict:
    import flightmode
    from flightmode.datasets.make import make_dataset
    from flightmode.scenarios.family import Family

    fam = Family.resolve(family)
    members = list(fam.members(n))
    flightmode.run(members[0], stages=("fly",))  # warm: imports, JSBSim's model files cached
    with tempfile.TemporaryDirectory() as d:
        rows, t_wall = timed(lambda: make_dataset(fam, n, Path(d) / "ds", workers=workers))
        ok = [r for r in rows.values() if r["status"] == "ok"]
        in_window_h = sum(_in_window_s(Path(d) / "ds" / r["samples_file"]) for r in ok) / 3600.0
        timings = [json.loads(line) for line in (Path(d) / "ds" / "timings.jsonl").read_text().splitlines()]
        # the same flights on workers already warm (_warm): a dataset of thousands of flights pays the
        # start-up once per worker, not once per three flights
        from flightmode.cluster import open_client

        first_of_type = {m.plan.aircraft: m.to_toml() for m in reversed(members)}
        with open_client(workers) as c:
            c.run(_warm, list(first_of_type.values()))
            _, t_warm = timed(lambda: make_dataset(fam, n, Path(d) / "warm", scheduler=c.scheduler.address))
    busy_s = sum(t["wall_s"] for t in timings)  # the workers' time inside fly_member, summed
    longest_s = max(t["wall_s"] for t in timings)
    g2g_h = sum(r["gate_to_gate_s"] for r in ok) / 3600.0
    # bare stepping of each aircraft type's edited model, parked and climbing (after the dataset:
    # the machine is quiet again)
    by_type = {}
    for m in members:
        by_type.setdefault(m.plan.aircraft, m)
    costs = {a: step_cost_table(m, steps=30_000) for a, m in by_type.items()}
    # the same, stepped in `workers` processes at once: the limit the workers themselves can reach here
    costs_together = {a: concurrent_step_cost_table(m, workers) for a, m in by_type.items()}
    # the record's reads per step, each type (edited model parked, stepped while reading; less bare)
    reads_us = {
        a: recording_stepping_s(m, 30_000) / 30_000 * 1e6 - costs[a]["edited", "parked"]
        for a, m in by_type.items()
    }
    stages = {t["flight_id"]: t["stages_s"] for t in timings if t["status"] == "ok"}
    fdm_hz = {m.plan.fdm_hz for m in members}
    if len(fdm_hz) != 1:
        raise ValueError(f"members fly at several FDM rates {sorted(fdm_hz)}: one limit needs one")
    (hz,) = fdm_hz
    steps = ground = air = 0.0
    cost_s = cost_together_s = floor_s = 0.0
    for r in ok:
        ac = members[r["index"]].plan.aircraft
        air_steps = r["airborne_s"] * hz
        ground_steps = (r["gate_to_gate_s"] - r["airborne_s"]) * hz
        c, ct = costs[ac], costs_together[ac]
        bare_s = (ground_steps * c["edited", "parked"] + air_steps * c["edited", "climb"]) * 1e-6
        cost_s += bare_s
        cost_together_s += (ground_steps * ct["edited", "parked"] + air_steps * ct["edited", "climb"]) * 1e-6
        st = stages[r["flight_id"]]
        floor_s += bare_s + (ground_steps + air_steps) * reads_us[ac] * 1e-6 + st["sense"] + st["detect"]
        steps += air_steps + ground_steps
        ground += ground_steps
        air += air_steps
    s_per_step = cost_s / steps
    limit = 3600.0 / (s_per_step * hz * 3600.0)
    limit_together = 3600.0 / (cost_together_s / steps * hz * 3600.0)
    core_h = t_wall * workers / 3600.0
    figure = in_window_h / core_h
    res = {
        "family": fam.name,
        "members (first N)": n,
        "flights ok": len(ok),
        "aircraft": ", ".join(sorted(m.plan.aircraft for m in members)),
        "workers": workers,
        "wall s (cluster start included)": t_wall,
        "core-hours (wall x workers)": core_h,
        "gate-to-gate flight-hours": g2g_h,
        "in-window flight-hours": in_window_h,
        "airborne share of steps": air / steps,
        "FDM rate Hz": hz,
        "steps per flight-hour": hz * 3600.0,
        **{
            f"bare us/step {a} edited parked / climb": f"{c['edited', 'parked']:.3f} / {c['edited', 'climb']:.3f}"
            for a, c in costs.items()
        },
        "bare us/step (members' mix)": s_per_step * 1e6,
        "limit: flight-hours per core-hour": limit,
        "in-window flight-hours per core-hour": figure,
        "gate-to-gate flight-hours per core-hour": g2g_h / core_h,
        "figure / limit (target >= 0.6)": figure / limit,
        f"bare us/step (members' mix), {workers} processes at once": cost_together_s / steps * 1e6,
        f"limit with {workers} processes stepping at once": limit_together,
        "figure / that limit": figure / limit_together,
        "workers busy in flights, share of core-hours": busy_s / (t_wall * workers),
        "longest flight s (one worker)": longest_s,
        "in-window flight-hours per busy core-hour": in_window_h / (busy_s / 3600.0),
        "busy figure / limit": in_window_h / (busy_s / 3600.0) / limit,
        "warm workers: wall s": t_warm,
        "warm workers: in-window flight-hours per core-hour": in_window_h / (t_warm * workers / 3600.0),
        "warm workers: figure / limit": in_window_h / (t_warm * workers / 3600.0) / limit,
        **{f"the record's reads, us/step, {a}": v for a, v in reads_us.items()},
        "sense + detect s, all flights": sum(st["sense"] + st["detect"] for st in stages.values()),
        "bound: in-window flight-hours per floor core-hour": in_window_h / (floor_s / 3600.0),
        "bound / limit (no loop around JSBSim's record reaches past it)": in_window_h
        / (floor_s / 3600.0)
        / limit,
    }
    report(res)
    print(f"target: figure / limit >= 0.6 -> {'met' if figure / limit >= 0.6 else 'NOT met'}")
    return res


if __name__ == "__main__":
    if sys.argv[1:2] == ["rate"]:
        rate(*(int(a) if i == 0 else a for i, a in enumerate(sys.argv[2:4])))
    else:
        main(*(int(a) if i == 0 else a for i, a in enumerate(sys.argv[1:3])))
