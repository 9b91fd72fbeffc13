"""Benchmark: the whole pipeline on the default scenario against bare JSBSim stepping, same run.

    python benchmarks/bench_pipeline.py [SCENARIO]

Baselines (benchmarks/_bench.py ``bare_aircraft``, ``step_cost_table``): bare ``fdm.run()`` of the
scenario's JSBSim model, no property reads, no pilot, both the *stock* model and flightmode's *edited*
one (the private copy with sim/flight/jsbsim/model_edits.py's edits, as the flight flies it), each
parked at the gate and in a trimmed steady climb, as a step-cost table in microseconds per step.

Timed: ``flightmode.run`` with every stage (fly, sense, detect, path, and write: truth.parquet,
samples.parquet, run.json, recording.rrd) into a temporary folder, in a warm process (imports done),
and once the whole ``flightmode fly`` command in a fresh interpreter (imports included). The ratios are
against the *stock* model stepped parked for as many steps as the flight took; the warm run and that
baseline are timed in turn, three times each, and each keeps its least time. Goal: run ratio <= 1.8
(aim 1.3).

One more, instrumented flight (``_bench.in_flight_stepping``) reports how much of the fly stage is
JSBSim's own stepping, timed inside that flight step by step (the timer's cost taken off), on the
ground and in the air, beside the bare table's parked and climb figures, and how long the track's
assembly from the record takes after the last step.

The floors: what the fly stage and the run cannot go under while the track records every FDM step
through JSBSim's Python binding. The record's reads cost ``_bench.recording_stepping_s`` (the edited
model parked, stepped while reading the every-step channels) less bare stepping; the fly stage's floor
is JSBSim's in-flight stepping + those reads for every step + the assembly, with no pilot, gusts or
roughness at all; the run's floor adds what the fastest run spent after its fly stage (sense, detect,
path, and the writer's tail). The last line bounds ``bench_dataset.py rate``'s figure / limit for this
flight from above: its in-window share x bare stepping at the dataset's limit (edited model, parked for
the ground steps, climbing for the airborne ones) / (the fly floor + sense + detect), one process alone,
nothing written.
"""

from __future__ import annotations

import subprocess
import sys
import tempfile

from _bench import bare_stepping_s, in_flight_stepping, recording_stepping_s, report, step_cost_table, timed


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
            t_bare = min(t_bare, bare_stepping_s(sc, steps, 1, model="stock", state="parked"))
            del r
            r, t = timed(lambda: flightmode.run(sc, out=d))
            if t < t_run:
                t_run, best = t, r.wall_s
        _, t_cli = timed(
            lambda: subprocess.run(["flightmode", "fly", name, "--out", d], check=True, capture_output=True)
        )
    table = step_cost_table(sc)
    # where the fly stage's time goes: JSBSim's own stepping inside the flight (one more, instrumented
    # flight), the rest being flightmode's work in the loop (pilot, gusts, roughness, recording)
    jsb = in_flight_stepping(sc)
    t_fly = best["fly"]
    floor_steps = 60_000
    reads_us = recording_stepping_s(sc, floor_steps) / floor_steps * 1e6 - table["edited", "parked"]
    fly_floor_s = jsb["total_s"] + reads_us * 1e-6 * steps + jsb["assembly_s"]
    after_fly_s = t_run - t_fly
    bare_mix_s = (
        jsb["ground_steps"] * table["edited", "parked"] + jsb["air_steps"] * table["edited", "climb"]
    ) * 1e-6
    in_window = float(jsb["track"].in_flight_window.mean())
    dataset_bound = in_window * bare_mix_s / (fly_floor_s + best["sense"] + best["detect"])
    res = {
        "scenario": name,
        "steps": steps,
        "simulated_s": r.track.duration_s,
        "baseline: stock model, parked, bare, same steps s": t_bare,
        "run_wall_s (warm)": t_run,
        "run ratio (goal <= 1.8, aim 1.3)": t_run / t_bare,
        "fly stage ratio": t_fly / t_bare,
        "cli_wall_s (fresh process)": t_cli,
        "cli ratio": t_cli / t_bare,
    }
    res |= {f"stage {k} s (fastest run)": v for k, v in best.items()}
    res |= {f"bare us/step, {m}, {s}": v for (m, s), v in table.items()}
    res |= {
        "in the flight: JSBSim stepping s": jsb["total_s"],
        "in the flight: steps (= the flight's)": jsb["steps"],
        "in the flight: us/step, all": jsb["total_s"] / jsb["steps"] * 1e6,
        "in the flight: us/step, on the ground": jsb["ground_s"] / max(jsb["ground_steps"], 1) * 1e6,
        "in the flight: us/step, airborne": jsb["air_s"] / max(jsb["air_steps"], 1) * 1e6,
        "in the flight: airborne share of steps": jsb["air_steps"] / jsb["steps"],
        "in the flight: timer cost taken off, us/step": jsb["timer_overhead_us"],
        "in the flight: JSBSim share of the fly stage (fastest run)": jsb["total_s"] / t_fly,
        "fly stage us/step (fastest run)": t_fly / steps * 1e6,
        "in the flight: track assembly after the last step s": jsb["assembly_s"],
        "floor: the record's reads, us/step": reads_us,
        "floor: fly stage s (stepping + reads + assembly; no pilot, gusts, roughness)": fly_floor_s,
        "floor: fly stage ratio (target 1.3)": fly_floor_s / t_bare,
        "fly stage above its floor s (pilot, gusts, roughness, loop)": t_fly - fly_floor_s,
        "after the fly stage s (fastest run: sense, detect, path, writer's tail)": after_fly_s,
        "floor: run ratio (fly floor + after the fly stage; target 1.8)": (fly_floor_s + after_fly_s)
        / t_bare,
        "in-window share of the steps": in_window,
        "bound: bench_dataset figure / limit, this flight (target 0.6)": dataset_bound,
    }
    report(res)
    print("step cost, bare fdm.run(), us per step:")
    print(f"  {'model':8} {'parked':>8} {'climb':>8}")
    for m in ("stock", "edited"):
        print(f"  {m:8} {table[m, 'parked']:8.3f} {table[m, 'climb']:8.3f}")
    g = jsb["ground_s"] / max(jsb["ground_steps"], 1) * 1e6
    a = jsb["air_s"] / max(jsb["air_steps"], 1) * 1e6
    print(f"  {'flight':8} {g:8.3f} {a:8.3f}   (edited, inside the flight: ground / airborne)")
    print(
        f"goal: run ratio <= 1.8 -> {'met' if res['run ratio (goal <= 1.8, aim 1.3)'] <= 1.8 else 'NOT met'}"
    )
    return res


if __name__ == "__main__":
    main(*sys.argv[1:2])
