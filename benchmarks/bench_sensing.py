"""Benchmark: sensing the default flight against flying it, same run (goal: ratio <= 0.25).

    python benchmarks/bench_sensing.py [SCENARIO] [PRESET]

Both timed here, best of 3 each (as in bench_flight): ``pipeline.fly`` (JSBSim and the pilot) and
``pipeline.sense`` (carrier timeline, vibration, mount, accelerometer chain at the internal
rate, labels).
"""

from __future__ import annotations

import sys

from _bench import best_timed, fly_scenario, report


def main(name: str = "gva-lhr-a320", preset_name: str = "lis302dl-logged16", repeats: int = 3) -> dict:
    from flightmode.runs import pipeline
    from flightmode.sim.sensor.sensing import FS_INTERNAL_HZ

    (sc, track, _), t_fly = best_timed(lambda: fly_scenario(name), repeats)
    streams = pipeline.streams_of(sc.seed).child("sensor")
    rec, t_sense = best_timed(lambda: pipeline.sense(track, sc.carrier, preset_name, streams), repeats)
    span = float(rec.t_s[-1] - rec.t_s[0])
    res = {
        "scenario": name,
        "preset": preset_name,
        "flight_s": track.duration_s,
        "recording_s": span,
        "internal_samples": int(span * FS_INTERNAL_HZ),
        "output_samples": rec.n,
        "fly_wall_s": t_fly,
        "sense_wall_s": t_sense,
        "ratio": t_sense / t_fly,
    }
    report(res)
    print(f"goal: ratio <= 0.25 -> {'met' if res['ratio'] <= 0.25 else 'NOT met'}")
    return res


if __name__ == "__main__":
    main(*sys.argv[1:3])
