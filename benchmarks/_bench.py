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


MODELS = ("stock", "edited")
STATES = ("parked", "climb")


def bare_aircraft(scenario, model: str = "edited", state: str = "parked"):
    """The scenario's JSBSim aircraft loaded through flightmode's adapter (the private copy and its
    settings), ready to be stepped bare. ``model``: ``"edited"`` (flightmode's edits, as the flight flies
    it: sim/flight/jsbsim/model_edits.py) or ``"stock"`` (the same private copy, no edits). ``state``:
    ``"parked"`` (at rest at the origin's gate position, brakes on, JSBSim's ground trim, as the flight
    starts) or ``"climb"`` (in the air at 10,000 ft, 250 kt, a 3 degree climb path, gear and flaps up,
    engines running, trimmed by JSBSim's full trim; stepped untouched it keeps climbing for the whole
    timed stretch: about 1,000 ft/min over 60,000 steps)."""
    from flightmode.sim.flight.aircraft.registry import get_profile
    from flightmode.sim.flight.jsbsim.adapter import JSBSimAircraft
    from flightmode.sim.flight.jsbsim.model_edits import edits_for

    if model not in MODELS or state not in STATES:
        raise ValueError(f"model {model!r} / state {state!r}: allowed {MODELS} / {STATES}")
    plan = scenario.plan
    prof = get_profile(plan.aircraft)
    edits = edits_for(prof) if model == "edited" else ()
    ac = JSBSimAircraft(plan.aircraft, 1.0 / plan.fdm_hz, prof.n_engines, edits=edits)
    o = plan.origin
    if state == "parked":
        ac.init_on_ground(o.lat_deg, o.lon_deg, o.elevation_m, o.heading_deg)
        return ac
    fdm = ac.fdm
    fdm["ic/lat-geod-deg"] = o.lat_deg
    fdm["ic/long-gc-deg"] = o.lon_deg
    fdm["ic/terrain-elevation-ft"] = 0.0
    fdm["ic/h-sl-ft"] = 10_000.0
    fdm["ic/vc-kts"] = 250.0
    fdm["ic/gamma-deg"] = 3.0
    fdm["ic/psi-true-deg"] = o.heading_deg
    fdm.run_ic()
    fdm["propulsion/set-running"] = -1
    fdm["gear/gear-cmd-norm"] = 0.0
    fdm["fcs/flap-cmd-norm"] = 0.0
    for i in range(prof.n_engines):
        fdm[f"fcs/throttle-cmd-norm[{i}]"] = 0.9
    fdm["simulation/do_simple_trim"] = 1  # full trim; JSBSim raises if it fails
    return ac


def bare_stepping_s(
    scenario, steps: int, repeats: int = 3, *, model: str = "edited", state: str = "parked"
) -> float:
    """The baseline of the flight benchmarks: the scenario's JSBSim model (:func:`bare_aircraft`: by
    default flightmode's edited private copy, parked at the origin) stepped with bare ``fdm.run()``
    ``steps`` times, no property reads, no pilot; loading and trimming are not timed. Best of
    ``repeats``."""

    def bare() -> float:
        run = bare_aircraft(scenario, model, state).fdm.run
        t0 = time.perf_counter()
        for _ in range(steps):
            run()
        return time.perf_counter() - t0

    return min(bare() for _ in range(repeats))


def recording_stepping_s(scenario, steps: int, repeats: int = 3) -> float:
    """The least a flight's stepping can cost while it records its track: the scenario's edited model
    parked (:func:`bare_aircraft`), each step reading the channels that sim/flight/simulate.py records at
    every step (``JSBSimAircraft.n_every_step`` of them, through the same cached property nodes and
    the same ``array.extend(map(get, nodes))``) and then ``fdm.run()``; no pilot, no gusts, no
    roughness. JSBSim's Python binding reads one property per call (jsbsim 1.3: no bulk read, and the
    wheel ships no C++ headers to read them from a compiled loop). Best of ``repeats``, seconds."""
    from array import array

    def recorded() -> float:
        ac = bare_aircraft(scenario, "edited", "parked")
        run = ac.fdm.run
        get, nodes = ac.raw_getter()
        fast = nodes[: ac.n_every_step]
        data = array("d")
        ext = data.extend
        t0 = time.perf_counter()
        for _ in range(steps):
            ext(map(get, fast))
            run()
        return time.perf_counter() - t0

    return min(recorded() for _ in range(repeats))


def step_cost_table(scenario, steps: int = 60_000, repeats: int = 3) -> dict[tuple[str, str], float]:
    """Bare JSBSim stepping in microseconds per step, (model, state) -> us, for the stock and the edited
    model, parked and in a steady climb (:func:`bare_aircraft`), ``steps`` steps each, best of
    ``repeats`` (the four cases taken in turn, round by round, so a slow stretch of the machine
    touches them alike)."""
    cases = [(m, s) for m in MODELS for s in STATES]
    best_s = dict.fromkeys(cases, float("inf"))
    for _ in range(repeats):
        for m, s in cases:
            best_s[m, s] = min(best_s[m, s], bare_stepping_s(scenario, steps, 1, model=m, state=s))
    return {c: t / steps * 1e6 for c, t in best_s.items()}


def _table_of(name: str, steps: int, repeats: int, barrier) -> dict:
    """One process's step-cost table of the built-in or family member ``name`` (a pickled scenario would
    do as well; the name keeps the child's imports its own), started with the others at ``barrier``."""
    from flightmode.scenarios.scenario import Scenario

    sc = Scenario.resolve(name) if isinstance(name, str) else name
    bare_aircraft(sc, "stock", "parked")  # load once before the common start (JSBSim's files cached)
    barrier.wait()
    return step_cost_table(sc, steps=steps, repeats=repeats)


def concurrent_step_cost_table(scenario, procs: int, steps: int = 30_000, repeats: int = 3) -> dict:
    """:func:`step_cost_table` measured in ``procs`` processes at once (started together at a barrier),
    the slowest process's figure for each case: what bare JSBSim costs a step when every core steps
    an aircraft, as a dataset's workers do. On a machine whose cores slow each other down (shared caches,
    memory bandwidth, a hypervisor's scheduling) it is above the one-process table; the limit a
    ``procs``-worker dataset can reach is set by it."""
    import multiprocessing as mp
    from concurrent.futures import ProcessPoolExecutor

    ctx = mp.get_context("spawn")
    with ctx.Manager() as manager:
        barrier = manager.Barrier(procs)
        with ProcessPoolExecutor(max_workers=procs, mp_context=ctx) as pool:
            futs = [pool.submit(_table_of, scenario, steps, repeats, barrier) for _ in range(procs)]
            tables = [f.result() for f in futs]
    return {c: max(t[c] for t in tables) for c in tables[0]}


def timer_overhead_s(n: int = 200_000) -> float:
    """What one ``t0 = clock(); ...; total += clock() - t0`` adds to the sum around an empty body
    (s), least of three: subtracted per step from the in-flight sum."""
    clock = time.perf_counter
    best_s = float("inf")
    for _ in range(3):
        total = 0.0
        for _ in range(n):
            t0 = clock()
            total += clock() - t0
        best_s = min(best_s, total / n)
    return best_s


def in_flight_stepping(scenario) -> dict:
    """JSBSim's own stepping inside one whole flight of ``scenario`` flown as ``flightmode.run`` flies
    it (``pipeline.fly``): the part of the fly stage that is JSBSim's. The flight's aircraft has its
    FGFDMExec wrapped so that each ``fdm.run()`` is timed on its own, split by whether the gear
    touched the ground before the step (``gear/wow``, read outside the timed span). The timer's own
    cost per step (:func:`timer_overhead_s`) is taken off the sums, so they compare with bare stepping
    (:func:`step_cost_table`: parked with the ground steps, climb with the airborne ones). The
    flight this measures is slower than an untimed one; what it sums is not.

    Returns ``ground_s``, ``ground_steps``, ``air_s``, ``air_steps``, ``total_s``, ``steps``,
    ``assembly_s`` (the track built from the record after the last step: ``simulate._to_track`` and
    ``simulate.pressure_truth``, timed in the same flight) and the ``track``; a :class:`RuntimeError`
    if the steps timed are not the flight's own (its samples plus the gear's settling before t = 0),
    i.e. the wrapper did not sit inside this flight."""
    from flightmode.runs import pipeline
    from flightmode.sim.flight import simulate
    from flightmode.sim.flight.jsbsim import adapter as jsbsim_adapter
    from flightmode.sim.flight.simulate import SETTLE_S

    sums = {True: [0.0, 0], False: [0.0, 0]}  # airborne? -> [s, steps]
    clock = time.perf_counter
    wrapped = []

    class TimedFDM:
        """The FGFDMExec with ``run`` timed; everything else passed through."""

        def __init__(self, fdm):
            self._fdm = fdm
            self._run = fdm.run
            self._wow = fdm.get_property_manager().get_node("gear/wow", False).get_double_value

        def __getattr__(self, name):
            return getattr(self._fdm, name)

        def __getitem__(self, key):
            return self._fdm[key]

        def __setitem__(self, key, value):
            self._fdm[key] = value

        def run(self):
            acc = sums[self._wow() < 0.5]
            run = self._run
            t0 = clock()
            out = run()
            acc[0] += clock() - t0
            acc[1] += 1
            return out

    init = jsbsim_adapter.JSBSimAircraft.__init__

    def timed_init(self, *args, **kwargs):
        init(self, *args, **kwargs)
        self.fdm = TimedFDM(self.fdm)
        wrapped.append(self)

    # the track's assembly after the last step (the record to SI arrays, and the pressure truth)
    assembly = [0.0]

    def timed_call(f):
        def call(*args, **kwargs):
            t0 = clock()
            out = f(*args, **kwargs)
            assembly[0] += clock() - t0
            return out

        return call

    overhead = timer_overhead_s()
    parts = {name: getattr(simulate, name) for name in ("_to_track", "pressure_truth")}
    jsbsim_adapter.JSBSimAircraft.__init__ = timed_init
    for name, f in parts.items():
        setattr(simulate, name, timed_call(f))
    try:
        track = pipeline.fly(scenario, pipeline.streams_of(scenario.seed).child("flight"))
    finally:
        jsbsim_adapter.JSBSimAircraft.__init__ = init
        for name, f in parts.items():
            setattr(simulate, name, f)
    steps = sums[True][1] + sums[False][1]
    expected = track.n + int(SETTLE_S * scenario.plan.fdm_hz)
    if len(wrapped) != 1 or steps != expected:
        raise RuntimeError(
            f"timed {steps} steps on {len(wrapped)} aircraft; the flight is one aircraft, {expected} steps"
        )
    (air_s, air_n), (ground_s, ground_n) = sums[True], sums[False]
    return {
        "ground_s": ground_s - overhead * ground_n,
        "ground_steps": ground_n,
        "air_s": air_s - overhead * air_n,
        "air_steps": air_n,
        "total_s": ground_s + air_s - overhead * steps,
        "steps": steps,
        "timer_overhead_us": overhead * 1e6,
        "assembly_s": assembly[0],
        "track": track,
    }
