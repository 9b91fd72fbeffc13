"""Benchmark: the whole pipeline on the default scenario against bare JSBSim stepping, same run.

    python benchmarks/bench_pipeline.py [SCENARIO]

Timed: ``flightmode.run`` with every stage (fly, sense, detect, path, and write: truth.parquet,
samples.parquet, run.json, recording.rrd) into a temporary folder, in a warm process (imports done),
and once the whole ``flightmode fly`` command in a fresh interpreter (imports included). One more,
instrumented flight reports how much of the fly stage is JSBSim's own stepping
(``_bench.in_flight_stepping_s``).
Baseline: the same JSBSim model stepped with bare ``fdm.run()`` for as many steps as the flight took
(benchmarks/_bench.py ``bare_stepping_s``). The run and the baseline are timed in turn, three times each,
and each keeps its least time. Goal: ratio <= 1.8 (aim 1.3).
"""

from __future__ import annotations

import subprocess
import sys
import tempfile

from _bench import bare_stepping_s, in_flight_stepping_s, report, timed


def main(name: str = "gva-lhr-a320", repeats: int = 3) -> dict:
    import flightmode
    from flightmode.scenarios.scenario import Scenario
    from flightmode.sim.flight.simulate import SETTLE_S

    sc = Scenario.resolve(name)
    with tempfile.TemporaryDirectory() as d:
        r = flightmode.run(sc, stages=("fly",), progress=None)  # warm: imports, JSBSim's model files cached
        steps = r.track.n + int(SETTLE_S * sc.plan.fdm_hz)
        # interleaved, best of each: this machine's neighbours slow whole stretches of seconds (the
        # same bare stepping has measured 9.2 s and 13.6 s minutes apart), so the two timings are
        # taken side by side, repeatedly, and each keeps its least
        t_run = t_bare = float("inf")
        best = None  # the fastest run's result: its stage times are reported
        for _ in range(repeats):
            t_bare = min(t_bare, bare_stepping_s(sc, steps, 1))
            del r
            r, t = timed(lambda: flightmode.run(sc, out=d))
            if t < t_run:
                t_run, best = t, r.wall_s
        _, t_cli = timed(
            lambda: subprocess.run(["flightmode", "fly", name, "--out", d], check=True, capture_output=True)
        )
    # where the fly stage's time goes: JSBSim's own stepping inside the flight (one more, instrumented
    # flight), the rest being flightmode's work in the loop (pilot, gusts, roughness, recording)
    t_jsb, n_jsb = in_flight_stepping_s(sc)
    res = {
        "scenario": name,
        "steps": steps,
        "simulated_s": r.track.duration_s,
        "bare_run_wall_s": t_bare,
        "run_wall_s": t_run,
        "ratio": t_run / t_bare,
        "cli_wall_s (fresh process)": t_cli,
        "cli_ratio": t_cli / t_bare,
    }
    res |= {f"stage {k} s (fastest run)": v for k, v in best.items()}
    res |= {
        "JSBSim stepping inside the flight s": t_jsb,
        "JSBSim us per step inside the flight": t_jsb / n_jsb * 1e6,
        "bare us per step": t_bare / steps * 1e6,
    }
    report(res)
    print(f"goal: ratio <= 1.8 -> {'met' if res['ratio'] <= 1.8 else 'NOT met'} (aim 1.3)")
    return res


if __name__ == "__main__":
    main(*sys.argv[1:2])
