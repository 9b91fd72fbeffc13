"""Benchmark: the whole `fly` of the default scenario against bare JSBSim stepping, same run.

    python benchmarks/bench_flight.py [SCENARIO]

Baseline: the same JSBSim model (loaded through flightmode's adapter, so the same private copy and
settings) stepped with bare ``fdm.run()`` for exactly as many steps as the flight took, with no
property reads and no pilot. Reported: both wall times (best of 3 each) and their ratio
(goal <= 1.5).
"""

from __future__ import annotations

import sys
import time

from _bench import best_timed, report


def main(name: str = "gva-lhr-a320", repeats: int = 3) -> dict:
    from flightmode.scenarios.registry import resolve
    from flightmode.sim.flight.aircraft_profiles import get_profile
    from flightmode.sim.flight.simulate import FDM_HZ, SETTLE_S, fly
    from flightmode.sim.flight.jsbsim_adapter import JSBSimAircraft

    plan, _, _ = resolve(name)
    prof = get_profile(plan.aircraft)
    track, t_fly = best_timed(lambda: fly(plan), repeats)
    n = track.n + int(SETTLE_S * FDM_HZ)  # fly() also steps the gear settling before t = 0

    def bare() -> float:
        ac = JSBSimAircraft(plan.aircraft, 1.0 / FDM_HZ, prof.n_engines)
        ac.init_on_ground(plan.origin.lat_deg, plan.origin.lon_deg, plan.origin.elevation_m, plan.origin.heading_deg)
        run = ac.fdm.run
        t0 = time.perf_counter()  # loading the model is not timed: only the stepping
        for _ in range(n):
            run()
        return time.perf_counter() - t0

    t_bare = min(bare() for _ in range(repeats))
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
