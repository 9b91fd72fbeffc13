"""Benchmark: the whole `fly` of the default scenario against bare JSBSim stepping, same run.

    python benchmarks/bench_flight.py [SCENARIO]

Baseline: the same JSBSim model (loaded through flightmode's adapter, so the same private copy, edits
and settings: benchmarks/_bench.py ``bare_stepping_s``) stepped with bare ``fdm.run()`` for exactly as
many steps as the flight took, with no property reads and no pilot. Reported: both wall times (best of 3 each) and their ratio
(goal <= 1.5).
"""

from __future__ import annotations

import sys

from _bench import bare_stepping_s, best_timed, fly_scenario, report


def main(name: str = "gva-lhr-a320", repeats: int = 3) -> dict:
    from flightmode.sim.flight.simulate import SETTLE_S

    (sc, track, _), t_fly = best_timed(lambda: fly_scenario(name), repeats)
    n = track.n + int(SETTLE_S * sc.plan.fdm_hz)  # fly() also steps the gear settling before t = 0
    t_bare = bare_stepping_s(sc, n, repeats)
    res = {
        "scenario": name,
        "steps": n,
        "simulated_s": track.duration_s,
        "fly_wall_s": t_fly,
        "bare_run_wall_s": t_bare,
        "ratio": t_fly / t_bare,
        "fly_steps_per_s": n / t_fly,
        "bare_steps_per_s": n / t_bare,
    }
    report(res)
    print(f"goal: ratio <= 1.5 -> {'met' if res['ratio'] <= 1.5 else 'NOT met'}")
    return res


if __name__ == "__main__":
    main(*sys.argv[1:2])
