"""A dataset records each failed flight with its cause and goes on (issue 54, item 1): a family of four
hops, each made to fail a different limit of the flight (a NaN in JSBSim, the altitude limit, the flight
loop's time limit, the ground) and each retried once then recorded while the others fly, on a Dask cluster in this process (one worker
thread: the faults, set here, reach its flights). Every flight is a prefix (the first minute, as a
preview flies it): the faults trip in it, and the dataset never flies a route.

And the dataset's own limit, the wall-time limit per flight (--flight-timeout-s): its error names the
phase and the simulated time the flight had reached."""

from __future__ import annotations

import math
import re

import pytest

from flightmode.errors import FlightTimeoutError

pytestmark = pytest.mark.xdist_group("dataset")

# four hops whose members 0-3 leave from EGPH, EGCC, EGLL and EGBB (family seed 18)
FAMILY = """
[family]
name = "faults"
description = "four short hops, each failing a different limit"
seed = 18

[aircraft]
737 = 1

[routes]
pairs = [["EGBB", "EGCC"], ["EGCC", "EGBB"], ["EGLL", "EGBB"], ["EGPH", "EGCC"]]

[turbulence]
patch_probability = 0.0
"""
PREFIX_S = 60.0  # each flight's first minute at the gate (no route flown)
# the cause each departure airport's flights are made to fail with (test_failures provokes each alone)
FAULT_BY_ORIGIN = {"EGLL": "nan", "EGCC": "altitude", "EGBB": "stand_time", "EGPH": "below_ground"}


@pytest.fixture
def faults(monkeypatch):
    """The faults, keyed on the flight's departure airport; every flight stopped after PREFIX_S."""
    from flightmode.runs import pipeline
    from flightmode.sim.flight import simulate
    from flightmode.sim.flight.pilot import pilot as P

    fly = pipeline.fly

    def prefix(sc, streams, **kw):
        kw["stop_after_s"] = PREFIX_S
        return fly(sc, streams, **kw)

    monkeypatch.setattr(pipeline, "fly", prefix)
    tick = P.Pilot.tick

    def faulty(self, x, t):
        fault = FAULT_BY_ORIGIN.get(self.plan.origin.icao)
        if fault == "nan" and t >= 2.0:
            self.ac.set("atmosphere/wind-north-fps", math.nan)  # a NaN into JSBSim's equations of motion
        # the altitude limit under the field's elevation (EGCC: 78 m) for that airport's flights only
        P.MAX_ALT_M = 10.0 if fault == "altitude" else 16000.0
        P.BELOW_GROUND_M = 2.0 if fault == "below_ground" else -2.0  # over the parked CG's 0.9 m
        tick(self, x, t)

    monkeypatch.setattr(P.Pilot, "tick", faulty)
    monkeypatch.setattr(P, "MAX_ALT_M", 16000.0)
    monkeypatch.setattr(P, "BELOW_GROUND_M", -2.0)
    max_duration_s = simulate.max_duration_s
    monkeypatch.setattr(
        simulate,
        "max_duration_s",
        lambda plan: 30.0 if FAULT_BY_ORIGIN.get(plan.origin.icao) == "stand_time" else max_duration_s(plan),
    )


@pytest.fixture
def in_process_scheduler():
    """A Dask scheduler with one worker thread in this process (the flights see the monkeypatches)."""
    import logging

    from dask.distributed import LocalCluster

    cluster = LocalCluster(
        n_workers=1,
        threads_per_worker=1,
        processes=False,
        dashboard_address=None,
        silence_logs=logging.CRITICAL,
    )
    try:
        yield cluster.scheduler_address
    finally:
        cluster.close()


def test_each_failure_is_recorded_with_its_cause_and_the_dataset_goes_on(
    tmp_path, faults, in_process_scheduler
):
    from flightmode.datasets.make import make_dataset, read_manifest
    from flightmode.scenarios.family import Family

    fam = tmp_path / "faults.toml"
    fam.write_text(FAMILY)
    origins = [Family.from_toml_text(FAMILY, "f").member(i).plan.origin.icao for i in range(4)]
    assert origins == ["EGPH", "EGCC", "EGLL", "EGBB"]
    out = tmp_path / "ds"
    rows = make_dataset(str(fam), 4, out, scheduler=in_process_scheduler)
    m = read_manifest(out)
    assert sorted(m) == [0, 1, 2, 3]
    want = {
        "nan": r"FlightDivergedError: flight failed in phase 'gate' at t = 2\.\d\d s: NaN in the "
        r"flight state: JSBSim diverged \(lat_deg = nan, not finite\)",
        "altitude": r"FlightDivergedError: flight failed in phase 'gate' at t = 0\.00 s: divergence: "
        r"altitude \d+ m above 10 m",
        "stand_time": r"FlightDivergedError: flight failed in phase 'gate' at t = 30\.\d\d s: the "
        r"flight did not reach the stand within 30 s",
        "below_ground": r"FlightDivergedError: flight failed in phase 'gate' at t = 0\.00 s: below the ground: "
        r"height above ground [01]\.\d m, under 2 m",
    }
    import re

    for i in range(4):
        r = m[i]
        kind = FAULT_BY_ORIGIN[r["origin"]]
        # retried once (make.ATTEMPTS), then recorded
        assert r["status"] == "failed" and r["attempts"] == 2, r
        assert re.fullmatch(want[kind] + r".*", r["error"]), (kind, r["error"])
        assert r["aircraft"] == "737" and r["scenario_toml"]  # the member can be flown again alone
        assert rows[i]["error"] == r["error"]
    # every cause recorded, the dataset finished: its card counts them, and no data file is left
    assert {FAULT_BY_ORIGIN[m[i]["origin"]] for i in range(4)} == set(want)
    assert "0 ok, 4 failed" in (out / "README.md").read_text()
    assert [p.name for p in out.rglob("*.parquet")] == ["flights.parquet"]  # no data file of a failed flight
    # timings.jsonl: one line per flight's outcome (after its retry), in order of completion
    import json

    tries = [json.loads(line) for line in (out / "timings.jsonl").read_text().splitlines()]
    assert sorted(t["flight_id"] for t in tries) == ["000000", "000001", "000002", "000003"]


def test_a_flight_past_the_wall_time_limit(tmp_path, faults):
    """The dataset's wall-time limit per flight (checked once per simulated minute, from t = 0): its error
    names the flight, the limit, and where the flight was (phase and simulated time)."""
    from flightmode.datasets.make import fly_member

    with pytest.raises(FlightTimeoutError) as info:
        fly_member(FAMILY, 3, str(tmp_path), {"truth": "none", "flight_timeout_s": 1e-9})
    msg = str(info.value)
    assert re.fullmatch(
        r"flight 000003 exceeded the 1e-09 s wall-time limit in phase 'gate' at t = 0 s \(simulated\); "
        r"raise --flight-timeout-s and --resume",
        msg,
    ), msg
    assert list(tmp_path.iterdir()) == []  # nothing written
