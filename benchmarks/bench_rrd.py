"""Benchmark: writing the default flight's recording.rrd against flying it, same run (goal: <= 0.2),
and the file size per flight-hour at 100 Hz (goal: <= 60 MB).

    python benchmarks/bench_rrd.py [SCENARIO]

Timed here: ``pipeline.fly`` (JSBSim and the pilot), and ``viz.rrd.write_rrd`` of the assembled
RunView (sensing, the detector and nav run before, untimed). Size per hour: the .rrd's bytes divided
by the accelerometer recording's duration in hours (the bag records from the terminal to arrival).
"""

from __future__ import annotations

import sys
import tempfile
from pathlib import Path

from _bench import best, best_timed, fly_scenario, report


def main(name: str = "gva-lhr-a320") -> dict:
    from flightmode.runs import pipeline
    from flightmode.runs.run_view import run_view
    from flightmode.viz.rrd import write_rrd

    (sc, track, _), t_fly = best_timed(lambda: fly_scenario(name))
    r = pipeline.run(sc, track=track, stages=("fly", "sense", "detect", "path"))
    rec = r.recording
    view = run_view("bench", sc.plan, track, rec, r.detection, r.path.estimates)
    with tempfile.TemporaryDirectory() as d:
        t_rrd = best(lambda: write_rrd(view, Path(d) / "recording.rrd"))
        size = (Path(d) / "recording.rrd").stat().st_size
    hours = float(rec.t_s[-1] - rec.t_s[0]) / 3600.0
    res = {
        "scenario": name,
        "fly_wall_s": t_fly,
        "rrd_wall_s": t_rrd,
        "ratio": t_rrd / t_fly,
        "rrd_mb": size / 1e6,
        "recording_hours": hours,
        "mb_per_hour": size / 1e6 / hours,
        "samples": rec.n,
    }
    report(res)
    print(
        f"goal: ratio <= 0.2 -> {'met' if res['ratio'] <= 0.2 else 'NOT met'}; "
        f"size <= 60 MB per hour -> {'met' if res['mb_per_hour'] <= 60 else 'NOT met'}"
    )
    return res


if __name__ == "__main__":
    main(*sys.argv[1:2])
