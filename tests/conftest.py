"""Shared fixtures. Flights are the expensive part of the suite, so each (scenario, seed, changes) is
flown once per test session, whatever the number of pytest-xdist workers: the first worker to need
a flight flies it and stores it (pickle, renamed into place) in the session's shared temporary
folder, under a lock; the others load it. Before its first test each worker also flies ahead, longest
first, the built-ins that the selected tests are parametrised over and that no other worker has
claimed (then their runs), so that the workers fly side by side instead of one waiting on the
other's lock.

Two tiers (pyproject's ``addopts`` and the README): ``pytest`` runs the fast tier, ``-m "not slow"``;
``pytest -m ""`` runs everything, as CI does. ``slow`` means exactly "flies a whole airliner on a
route, or drives a browser", and a test not marked slow that asks for a longer flight fails instead of
slipping into the fast tier: :func:`guard_flight`, called by the flight cache (``fly_cached``,
``pattern_run``) and by the pipeline's JSBSim ``fly`` itself in this process (a flight in another
process, a subprocess or a Dask worker, is not seen)."""

from __future__ import annotations

import dataclasses
import os
import pickle
import shutil
from pathlib import Path

# The suite runs one xdist worker per core, so BLAS threads of its own would only contend with the
# other worker: the stacked 100 x 100 eigenproblems of statistics.pm_am took 55 s instead of 1 s so.
# Set before anything here imports NumPy (a variable the caller set is kept).
for _var in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "1")

import pytest  # noqa: E402

# The fast tier's longest flight, as planned: a flight's ``stop_after_s``, or for a whole flight the
# pipeline's own time limit (sim.flight.simulate.max_duration_s: its ground time and the distance at
# 120 m/s, plus 3 h of margins). The pattern circuit of any type plans 3 h 0.3 min (no distance, a 20 s
# gate wait; it flies 20-75 min in 5-15 s of wall time), the shortest route the suite flies (the 106
# km Birmingham - Manchester hop of tests/datasets) 3 h 21 min, gva-lhr-a320 4 h 51 min: 3 h 5 min
# admits the circuit and any prefix of up to three hours, and refuses every route.
FAST_TIER_MAX_PLANNED_S = 3 * 3600.0 + 300.0

_current: dict = {"item": None}  # the test being set up, run or torn down in this process
_guard_off: list = []  # non-empty while _fly_ahead flies for the slow tests it was asked for


def planned_s(plan, stop_after_s=None) -> float:
    """A flight's planned duration: ``stop_after_s`` when it is stopped early, else the pipeline's
    time limit for the whole flight."""
    from flightmode.sim.flight.simulate import max_duration_s

    whole = max_duration_s(plan)
    return whole if stop_after_s is None else min(float(stop_after_s), whole)


def guard_flight(sc, stop_after_s=None) -> None:
    """Fail the current test, in one line naming it and the flight, when it is not marked slow and the
    flight it asks for plans more than :data:`FAST_TIER_MAX_PLANNED_S`."""
    item = _current["item"]
    if _guard_off or item is None or item.get_closest_marker("slow") is not None:
        return
    planned = planned_s(sc.plan, stop_after_s)
    if planned > FAST_TIER_MAX_PLANNED_S:
        stop = "whole" if stop_after_s is None else f"stop_after_s={stop_after_s:g}"
        pytest.fail(
            f"{item.nodeid} is not marked slow but flies '{sc.name}' ({sc.aircraft}, seed {sc.seed}, "
            f"{stop}): planned {planned / 60:.0f} min > the fast tier's "
            f"{FAST_TIER_MAX_PLANNED_S / 60:.0f} min; fly a prefix (stop_after_s) or mark it slow",
            pytrace=False,
        )


def _guarded(fly):
    """sim.flight.simulate.fly, checked by :func:`guard_flight` before it flies (the pipeline and
    the CLI reach JSBSim through it; a Scenario is rebuilt from the plan only for the message)."""
    import functools

    @functools.wraps(fly)
    def _fly(plan, *args, stop_after_s=None, **kwargs):
        guard_flight(_PlanOnly(plan), stop_after_s)
        return fly(plan, *args, stop_after_s=stop_after_s, **kwargs)

    _fly.guarded = True
    return _fly


@dataclasses.dataclass(frozen=True)
class _PlanOnly:
    plan: object

    @property
    def name(self) -> str:
        return f"{self.plan.origin.icao}-{self.plan.destination.icao}"

    @property
    def aircraft(self) -> str:
        return self.plan.aircraft

    @property
    def seed(self) -> str:
        return "?"


@pytest.hookimpl(tryfirst=True)
def pytest_runtest_setup(item):
    """Remember the test (before its fixtures: a session fixture may fly for it) and wrap JSBSim's
    ``fly`` once per process (:func:`_guarded`)."""
    from flightmode.sim.flight import simulate

    _current["item"] = item
    if not getattr(simulate.fly, "guarded", False):
        simulate.fly = _guarded(simulate.fly)


@pytest.fixture(scope="session")
def _flight_cache_dir(tmp_path_factory, worker_id):
    # with xdist, every worker's basetemp is a folder of one shared per-session folder
    root = tmp_path_factory.getbasetemp()
    if worker_id != "master":
        root = root.parent
    d = root / "flight-cache"
    d.mkdir(exist_ok=True)
    return d


def _store(path, value) -> None:
    # streamed into the file (no second copy of a gigabyte in memory), then renamed into place
    tmp = path.with_suffix(f".tmp-{os.getpid()}")
    with open(tmp, "wb") as f:
        pickle.dump(value, f, protocol=pickle.HIGHEST_PROTOCOL)
    os.replace(tmp, path)


def _load(path):
    with open(path, "rb") as f:
        return pickle.load(f)


def _shared(path, compute, store=lambda v: v, restore=lambda v: v):
    """``compute()`` once per test session whatever the number of workers: the first to need it
    computes and stores ``store(value)`` (pickled, renamed into place) under a lock, the others load
    it and return ``restore(stored)``."""
    from filelock import FileLock

    with FileLock(str(path) + ".lock"):
        if path.exists():
            return restore(_load(path))
        value = compute()
        _store(path, store(value))
        return value


def _without_track(run):
    """A run as stored: its track is the flight's own file (a long haul's track is a gigabyte; stored
    twice, the session's cache outgrew the page cache and waited on the disk)."""
    return dataclasses.replace(run, track=None)


def _claim(path, compute) -> None:
    """Compute and store ``compute()`` (already in its stored form) at ``path`` if it is not there and
    no other worker holds its lock; return at once otherwise (the worker flying ahead:
    :func:`_fly_ahead`)."""
    from filelock import FileLock, Timeout

    lock = FileLock(str(path) + ".lock")
    try:
        lock.acquire(timeout=0)
    except Timeout:
        return
    try:
        if not path.exists():
            _store(path, compute())
    finally:
        lock.release()


def _flight_key(sc, stop_after_s=None) -> str:
    return sc.digest() + ("" if stop_after_s is None else f"-stop{stop_after_s:g}")


def _run_key(sc, stages) -> str:
    return f"{sc.digest()}-run-{'-'.join(stages)}"


RUN_STAGES = ("fly", "sense", "detect")  # run_cached's default


@pytest.fixture(scope="session", autouse=True)
def _fly_ahead(request, _flight_cache_dir):
    """Fly ahead (module docstring): the built-in scenarios the selected tests are parametrised
    over (``name``) in the slow tests, longest route first, each by the first worker to claim it; then their runs
    (``run_cached``'s default stages) whose flight is already stored. Nothing is kept in memory."""
    from flightmode.scenarios.scenario import Scenario, builtin_names
    from flightmode.sim.flight.simulate import max_duration_s

    known = set(builtin_names())
    names = {
        item.callspec.params.get("name")
        for item in request.session.items
        if hasattr(item, "callspec") and item.get_closest_marker("slow") is not None
    }  # a test not marked slow that names a built-in route fails in guard_flight: nothing to fly for it
    scenarios = sorted((Scenario.builtin(n) for n in names & known), key=lambda sc: -max_duration_s(sc.plan))
    _guard_off.append(True)  # flown for the slow tests that asked (the test being set up may not be one)
    try:
        _fly_ahead_claims(scenarios, _flight_cache_dir)
    finally:
        _guard_off.pop()


def _fly_ahead_claims(scenarios, _flight_cache_dir) -> None:
    from flightmode.runs import pipeline

    for sc in scenarios:
        _claim(
            _flight_cache_dir / f"{_flight_key(sc)}.pkl",
            lambda sc=sc: pipeline.fly(sc, pipeline.streams_of(sc.seed).child("flight")),
        )
    for sc in scenarios:
        flight = _flight_cache_dir / f"{_flight_key(sc)}.pkl"
        if flight.exists():
            _claim(
                _flight_cache_dir / f"{_run_key(sc, RUN_STAGES)}.pkl",
                lambda sc=sc, flight=flight: _without_track(
                    pipeline.run(sc, track=_load(flight), stages=RUN_STAGES)
                ),
            )


@pytest.fixture(scope="session")
def fly_cached(_flight_cache_dir):
    """fly_cached(name, seed=None, stop_after_s=None, **scenario_changes) -> (scenario, track): the
    scenario (a built-in with ``Scenario.replace`` changes) flown by the pipeline's own ``fly`` with
    the run's ``flight`` streams, exactly as ``flightmode.run`` flies it (``stop_after_s``: only that
    much of it, the exact prefix)."""
    from flightmode.runs import pipeline
    from flightmode.scenarios.scenario import Scenario

    memo: dict = {}

    def _fly(name: str, seed: int | None = None, stop_after_s: float | None = None, **changes):
        sc = Scenario.builtin(name)
        if seed is not None:
            changes["seed"] = seed
        if changes:
            sc = sc.replace(**changes)
        guard_flight(sc, stop_after_s)  # before the cache: a flight another test flew still counts
        key = _flight_key(sc, stop_after_s)
        if key not in memo:
            track = _shared(
                _flight_cache_dir / f"{key}.pkl",
                lambda: pipeline.fly(
                    sc, pipeline.streams_of(sc.seed).child("flight"), stop_after_s=stop_after_s
                ),
            )
            memo[key] = (sc, track)
        return memo[key]

    return _fly


@pytest.fixture(scope="session")
def run_cached(fly_cached, _flight_cache_dir):
    """run_cached(name, seed=None, stages=(fly, sense, detect), **changes) -> RunResult of
    ``flightmode.run`` (no files written), on the session's cached flight; like the flights, each
    result is computed once per session whatever the number of workers (pickled, renamed into
    place, under a lock)."""
    from flightmode.runs import pipeline

    memo: dict = {}

    def _run(name: str, seed: int | None = None, stages=RUN_STAGES, **changes):
        sc, track = fly_cached(name, seed, **changes)
        key = _run_key(sc, stages)
        if key not in memo:
            memo[key] = _shared(
                _flight_cache_dir / f"{key}.pkl",
                lambda: pipeline.run(sc, track=track, stages=stages),
                store=_without_track,
                restore=lambda r: dataclasses.replace(r, track=track),
            )
        return memo[key]

    return _run


@pytest.fixture(scope="session")
def pattern_run(_flight_cache_dir):
    """A run folder written by `flightmode fly pattern` (the CLI, end to end), once per session (shared
    by the workers like the flights; tests only read it). Returns (run folder, the command's output)."""
    from filelock import FileLock
    from typer.testing import CliRunner

    from flightmode.cli.main import app
    from flightmode.scenarios.scenario import Scenario

    guard_flight(Scenario.builtin("pattern"))  # whoever flew it first, this test asks for it
    out = _flight_cache_dir / "pattern-cli"
    with FileLock(str(out) + ".lock"):
        if not (out / "output.txt").exists():
            r = CliRunner().invoke(app, ["fly", "pattern", "--out", str(out)])
            assert r.exit_code == 0, r.output
            (out / "output.txt").write_text(r.output)
    return out / "pattern-s1", (out / "output.txt").read_text()


@pytest.fixture(scope="session")
def default_run(tmp_path_factory, fly_cached):
    """The default scenario's run folder (recording.rrd included), written by ``flightmode.run`` on the
    session's cached flight (the CLI end to end is `pattern_run`'s)."""
    from flightmode.runs import pipeline
    from flightmode.scenarios.scenario import DEFAULT_SCENARIO

    sc, track = fly_cached(DEFAULT_SCENARIO)
    out = tmp_path_factory.mktemp("runs")
    r = pipeline.run(sc, out=out, track=track)
    return r.written["run_json"].parent, r


@pytest.fixture(scope="session")
def family_file(_flight_cache_dir) -> Path:
    """tests/hops.py's family as a file (shared by the workers)."""
    from tests.hops import HOPS

    p = _flight_cache_dir / "hops.toml"
    if not p.exists():  # the same text from every worker: written whole, then renamed into place
        tmp = p.with_suffix(f".tmp-{os.getpid()}")
        tmp.write_text(HOPS)
        os.replace(tmp, p)
    return p


@pytest.fixture(scope="session")
def reference(_flight_cache_dir, family_file) -> Path:
    """The uninterrupted dataset of tests/hops.py's family (two 106 km hops), made through the API on a
    LocalCluster of two worker processes, once per session whatever the number of xdist workers: the
    first worker to ask makes it, the other waits for it (tests only read it). test_dataset and
    test_faults (each an xdist group of its own) compare their interrupted datasets with it; made once
    per worker, the two were made at the same time, four Dask workers and two clients on two cores, at
    100 s each."""
    from filelock import FileLock

    from flightmode.datasets.make import make_dataset
    from tests.hops import N

    out = _flight_cache_dir / "hops-reference"
    done = out.with_name(out.name + ".complete")  # beside it: the tests compare the folder's files
    with FileLock(str(out) + ".lock"):
        if not done.exists():
            shutil.rmtree(out, ignore_errors=True)  # what a worker that failed making it left
            rows = make_dataset(str(family_file), N, out, workers=2)
            assert sorted(rows) == list(range(N)) and all(r["status"] == "ok" for r in rows.values())
            done.write_text("")
    return out


def pytest_collection_modifyitems(config, items):
    """The slow tests first, the quick ones after (a coarse longest-first, as a scheduler packs jobs):
    pytest-xdist hands the ungrouped tests out in collection order, and a slow one collected last (the
    browser's, under tests/viz) ran alone for 40 s after the other worker had finished. The sort is
    stable: within each kind the order stays the collection's, so a module's slow tests stay together
    (its module-scoped fixtures are made once). The ``dataset`` group is one unit that xdist schedules
    by its own size."""
    items.sort(key=lambda item: item.get_closest_marker("slow") is None)
