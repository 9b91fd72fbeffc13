"""Shared by the benchmark scripts (run as ``python benchmarks/bench_*.py``, so this directory is on
``sys.path``): best-of-N wall time and one way of printing the figures."""

from __future__ import annotations

import time


def timed(f):
    """(f's result, its wall time in seconds)."""
    t0 = time.perf_counter()
    out = f()
    return out, time.perf_counter() - t0


def best_timed(f, repeat: int = 3):
    """(f's last result, the least wall time of ``repeat`` calls): the machine's noise, and the
    first touch of fresh process memory, only ever add time."""
    out, t_min = None, float("inf")
    for _ in range(repeat):
        out, t = timed(f)
        t_min = min(t_min, t)
    return out, t_min


def best(f, repeat: int = 3) -> float:
    """The least wall time of ``repeat`` calls."""
    return best_timed(f, repeat)[1]


def report(res: dict) -> None:
    width = max(len(k) for k in res)
    for k, v in res.items():
        print(f"{k:>{width}}: {v:,.4g}" if isinstance(v, float) else f"{k:>{width}}: {v}")


def fly_scenario(name: str):
    """(scenario, its track flown as ``flightmode.run`` flies it, wall s)."""
    from flightmode.runs import pipeline
    from flightmode.scenarios.scenario import Scenario

    sc = Scenario.resolve(name)
    track, t = timed(lambda: pipeline.fly(sc, pipeline.streams_of(sc.seed).child("flight")))
    return sc, track, t


def bare_stepping_s(scenario, steps: int, repeats: int = 3) -> float:
    """The baseline of the flight benchmarks: the scenario's JSBSim model (loaded through flightmode's
    adapter: the same private copy, edits and settings) placed at the origin and stepped with bare
    ``fdm.run()`` ``steps`` times, no property reads, no pilot; loading is not timed. Best of
    ``repeats``."""
    from flightmode.sim.flight.aircraft.registry import get_profile
    from flightmode.sim.flight.jsbsim.adapter import JSBSimAircraft
    from flightmode.sim.flight.jsbsim.model_edits import edits_for

    plan = scenario.plan
    prof = get_profile(plan.aircraft)

    def bare() -> float:
        ac = JSBSimAircraft(plan.aircraft, 1.0 / plan.fdm_hz, prof.n_engines, edits=edits_for(prof))
        ac.init_on_ground(
            plan.origin.lat_deg, plan.origin.lon_deg, plan.origin.elevation_m, plan.origin.heading_deg
        )
        run = ac.fdm.run
        t0 = time.perf_counter()
        for _ in range(steps):
            run()
        return time.perf_counter() - t0

    return min(bare() for _ in range(repeats))


def in_flight_stepping_s(scenario) -> tuple[float, int]:
    """(seconds inside JSBSim's ``fdm.run``, steps) over one whole flight of ``scenario`` flown as
    ``flightmode.run`` flies it: the part of the fly stage that is JSBSim's own. Each step is timed on its
    own (the timer's calls are outside the sum), so the flight this measures is slower than an untimed
    one; what it sums is not."""
    from flightmode.runs import pipeline
    from flightmode.sim.flight.jsbsim import adapter as jsbsim_adapter

    total = [0.0, 0]
    clock = time.perf_counter

    class TimedFDM:
        """The FGFDMExec with ``run`` timed; everything else passed through."""

        def __init__(self, fdm):
            self._fdm = fdm

        def __getattr__(self, name):
            return getattr(self._fdm, name)

        def __getitem__(self, key):
            return self._fdm[key]

        def __setitem__(self, key, value):
            self._fdm[key] = value

        def run(self):
            t0 = clock()
            out = self._fdm.run()
            total[0] += clock() - t0
            total[1] += 1
            return out

    init = jsbsim_adapter.JSBSimAircraft.__init__

    def timed_init(self, *args, **kwargs):
        init(self, *args, **kwargs)
        self.fdm = TimedFDM(self.fdm)

    jsbsim_adapter.JSBSimAircraft.__init__ = timed_init
    try:
        pipeline.fly(scenario, pipeline.streams_of(scenario.seed).child("flight"))
    finally:
        jsbsim_adapter.JSBSimAircraft.__init__ = init
    return total[0], total[1]
