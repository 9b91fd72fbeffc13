"""Every way a flight can fail, provoked (issue 54, item 1): each limit the pilot and the flight loop check
raises its typed FlightDivergedError naming the phase, the simulated time, the quantity that broke the
limit, its value and the limit; docs/failures.md lists every one of them (checked against the raise sites).

The flights are the pattern circuit's prefixes (tests/conftest.py FAST_TIER_MAX_PLANNED_S), shortened
(no gate wait, the shortest taxi-out): a limit is tripped either by the flight itself under a crafted
condition (a lowered profile figure, an aim point moved, a fault in one JSBSim property) or by lowering
the limit so that an ordinary state breaks it early. Nothing of the flight is mocked.
"""

from __future__ import annotations

import ast
import dataclasses
import math
import re
from pathlib import Path

import pytest

from flightmode.errors import FlightDivergedError

ROOT = Path(__file__).resolve().parents[2]
# the pattern circuit, shortened on the ground: engine start at once, a 300 m taxi-out, no line-up hold
# (liftoff near t = 320 s, the 737's touchdown near 850 s)
SHORT = {"gate_wait_s": 0, "taxi_out": {"length_m": 300, "lineup_hold_s": 0}}


def _fly(stop_after_s: float, aircraft: str = "737", **changes):
    """Fly the shortened pattern (with ``changes``) for at most ``stop_after_s``; the failure it raised."""
    from flightmode.runs import pipeline
    from flightmode.scenarios.scenario import Scenario
    from flightmode.sim.flight import simulate

    sc = Scenario.builtin("pattern").replace(aircraft=aircraft, **(SHORT | changes))
    with pytest.raises(FlightDivergedError) as info:
        simulate.fly(sc.plan, pipeline.streams_of(sc.seed).child("flight"), stop_after_s=stop_after_s)
    return info.value


def _profile(monkeypatch, aircraft: str = "737", tuning: dict | None = None, **changes) -> None:
    import flightmode.sim.flight.aircraft.registry as reg

    prof = reg.PROFILES[aircraft]
    if tuning:
        changes["tuning"] = dataclasses.replace(prof.tuning, **tuning)
    monkeypatch.setitem(reg.PROFILES, aircraft, dataclasses.replace(prof, **changes))


def _check(e: FlightDivergedError, kind: str, phase: str, text: str, *, over: bool = True) -> None:
    """The error's fields agree with its one-line message, and its value is beyond its limit."""
    assert e.kind == kind and e.phase == phase, (e.kind, e.phase, str(e))
    msg = str(e)
    print(f"{kind}: {type(e).__name__}: {msg}")  # docs/failures.md quotes these (pytest -s)
    assert msg.startswith(f"flight failed in phase '{phase}' at t = {e.t_s:.2f} s: "), msg
    assert re.search(text, msg), msg
    assert "\n" not in msg
    assert e.quantity, msg
    if e.limit is not None:
        assert (e.value > e.limit) if over else (e.value < e.limit), (e.value, e.limit)
    # it crosses a process boundary (a Dask worker) whole
    import pickle

    again = pickle.loads(pickle.dumps(e))
    fields = ("kind", "phase", "t_s", "quantity", "limit")
    assert [getattr(again, f) for f in fields] == [getattr(e, f) for f in fields] and str(again) == msg
    assert again.value == e.value or math.isnan(again.value) and math.isnan(e.value)


# ---------------------------------------------------------------------- at the gate: limits lowered
def test_nan_in_a_jsbsim_property_ends_the_flight_naming_the_channel(monkeypatch):
    """A NaN fed into one JSBSim input (the wind, as a broken weather feed would) spreads through the
    equations of motion in one step; the pilot's next tick names the first channel it reaches."""
    from flightmode.sim.flight.pilot import pilot as P

    tick = P.Pilot.tick

    def faulty(self, x, t):
        if t >= 2.0:
            self.ac.set("atmosphere/wind-north-fps", math.nan)
        tick(self, x, t)

    monkeypatch.setattr(P.Pilot, "tick", faulty)
    e = _fly(10.0)
    _check(
        e, "nan", "engine_start", r"NaN in the flight state: JSBSim diverged \(lat_deg = nan, not finite\)"
    )
    assert 2.0 < e.t_s < 2.5 and e.quantity == "lat_deg" and math.isnan(e.value)  # one tick (4 Hz) later


def test_below_the_ground(monkeypatch):
    """The parked 737's CG is 3.69 ft (1.1 m) above the apron (FACTS: settled CG heights; 0.9 m on the
    edited gear): a floor of 2 m puts it 'below the ground' on the first tick."""
    from flightmode.sim.flight.pilot import pilot as P

    monkeypatch.setattr(P, "BELOW_GROUND_M", 2.0)
    e = _fly(5.0)
    _check(
        e, "below_ground", "gate", r"below the ground: height above ground [01]\.\d m, under 2 m", over=False
    )
    assert e.t_s == 0.0 and 0.5 < e.value < 1.5


def test_altitude_divergence(monkeypatch):
    """Geneva's apron is 416 m above the sea: a ceiling of 300 m is broken on the first tick."""
    from flightmode.sim.flight.pilot import pilot as P

    monkeypatch.setattr(P, "MAX_ALT_M", 300.0)
    e = _fly(5.0)
    _check(e, "altitude", "gate", r"divergence: altitude 4\d\d m above 300 m")
    assert e.t_s == 0.0 and 416 < e.value < 425  # the field elevation plus the CG's 3.7 m


def test_mach_divergence_in_the_takeoff_roll(monkeypatch):
    """Mach 0.1 (66 kt at Geneva) is passed in the takeoff roll, before rotation at 150 kt."""
    from flightmode.sim.flight.pilot import pilot as P

    monkeypatch.setattr(P, "MAX_MACH", 0.1)
    e = _fly(400.0)
    _check(e, "mach", "takeoff_roll", r"divergence: Mach 0\.10\d above 0\.100")
    assert e.value - 0.1 < 0.005  # caught on the first tick past it (40 Hz, 2 m/s^2: 0.0002 Mach a tick)


def test_stand_time_limit(monkeypatch):
    """The flight loop's own limit (simulate.max_duration_s), lowered to 30 s: the engines are still
    starting (the first start takes 28 s)."""
    from flightmode.sim.flight import simulate

    monkeypatch.setattr(simulate, "max_duration_s", lambda plan: 30.0)
    e = _fly(60.0)
    _check(e, "stand_time", "engine_start", r"did not reach the stand within 30 s \(simulate\.max_duration_s")
    assert 30.0 < e.t_s < 30.5  # the first tick past it (4 Hz while the engine spools)


# ---------------------------------------------------------------------- taxi and takeoff
def test_left_the_taxiway(monkeypatch):
    """A taxiway 0.6 m wide either side of the route's centre line: the tug leaves the aircraft 1-2 m off
    the taxi route's start, which the first taxi tick measures."""
    from flightmode.sim.flight.pilot import taxi

    monkeypatch.setattr(taxi, "TAXI_MAX_CROSS_M", 0.6)
    e = _fly(320.0)
    _check(e, "off_taxiway", "taxi_out", r"left the taxiway: \d+\.\d m from the taxi route, more than 0\.6 m")
    assert 0.6 < e.value < 30.0  # over the lowered limit, under the real one


def test_bank_limit_in_the_first_turn(monkeypatch):
    """The type's turn bank set to 60 deg: the first turn after takeoff passes the 45 deg limit."""
    _profile(monkeypatch, turn_bank_deg=60.0)
    e = _fly(420.0)
    _check(e, "bank", e.phase, r"bank angle -?4\d\.\d deg exceeds 45 deg")
    # the circuit turns left: a negative bank, its size over the limit
    assert e.phase in ("initial_climb", "climb", "cruise") and e.value > 45.0 and e.limit == 45.0


def test_stall_in_the_initial_climb(monkeypatch):
    """A stall angle of 6 deg: the climb-out at V2 + 10-20 kt flies 7-9 deg of angle of attack, for
    more than the one second the check allows a gust."""
    _profile(monkeypatch, alpha_stall_deg=6.0)
    e = _fly(400.0)
    _check(
        e, "stall", "initial_climb", r"stall: angle of attack \d+\.\d deg above 6 deg for 1 s at IAS \d+ kt"
    )
    assert e.value > 6.0 and e.limit == 6.0


# ---------------------------------------------------------------------- airborne: no progress
def test_a_flight_that_circles_ends_long_before_its_fuel_does(monkeypatch):
    """The wandering approach of issue 54 (a stall in the flare after 2.7 h of a 400 km hop): an
    aircraft that cannot turn tightly enough to reach its next waypoint circles around it. The type's
    turn bank cut to 5 deg (a 16 km radius at 190 kt: the circuit's corners are 5.6 km apart), and the
    no-progress window cut from 15 min to 2 min to keep the test short: the flight ends in the circuit,
    naming the distance it failed to gain."""
    from flightmode.sim.flight.pilot import pilot as P

    monkeypatch.setattr(P, "PROGRESS_WINDOW_S", 120.0)
    _profile(monkeypatch, turn_bank_deg=5.0)
    e = _fly(900.0)
    _check(e, "no_progress", e.phase, r"no progress to the runway: \d+\.\d nm to go, not 1 nm closer")
    assert e.phase in ("climb", "cruise") and 120.0 < e.value <= 130.0  # checked every 10 s


def test_a_route_that_reaches_the_approach_fix_headed_away_turns_back_instead_of_circling(monkeypatch):
    """Issue 54's wandering approach, found: a route that reaches the approach fix from the runway's
    side (regional-hops member 38, EDDF-LKPR landing on runway 24 from the west) arrives over the fix
    headed away from the final course, and the pure pursuit of the fix circled it, the fix inside its
    turn circle at 200+ kt: seed 5 of that member circled 17 min before a lap happened to meet the
    capture's conditions, and its seeds 0-4 for about 10 min. Here the pattern's downwind ends on the
    extended centreline 3 nm out and the fix is 16 nm out (the routes' default): without the turn back
    the 737 circles the fix for the whole flight (flown to 1,500 s: no capture). With it, after 300 s at
    the fix (Autopilot.FIX_CAPTURE_WAIT_S) it flies out 6 nm along the centreline and back, and
    captures the localizer.

    And a touchdown past the touchdown zone (a float: the 787-8's on some routes) lands and goes on,
    flagged in the flight's events: the zone's end moved here from 914 m to 300 m, short of the 737's
    touchdowns (500-700 m past the threshold)."""
    from flightmode.runs import pipeline
    from flightmode.scenarios.scenario import Scenario
    from flightmode.sim.flight import simulate
    from flightmode.sim.flight.plan import Runway

    monkeypatch.setattr(Runway, "touchdown_zone_end_m", property(lambda self: 300.0))
    sc = Scenario.builtin("pattern").replace(
        route={"waypoints": [[46.1797, 6.1261], [46.2854, 6.1786]]},  # crosswind corner; 3 nm out on the line
        approach={"fix_nm": 16.0},
        **SHORT,
    )
    tr = simulate.fly(sc.plan, pipeline.streams_of(sc.seed).child("flight"), stop_after_s=1680.0)
    names = [e.name for e in tr.events if e.name in ("turn_back", "waypoint", "localizer_capture")]
    assert names == ["waypoint", "waypoint", "turn_back", "waypoint", "localizer_capture"], names
    t_back, t_capture = tr.event_time("turn_back"), tr.event_time("localizer_capture")
    # the fix first within 2.5 nm about 645 s in: the turn back 300 s later, the capture 5 min after it
    assert 900.0 < t_back < 1000.0 and t_back < t_capture < t_back + 400.0
    assert "300 s without a capture" in next(e.detail for e in tr.events if e.name == "turn_back")
    # landed, long by the moved zone, flagged, and rolling out
    (td,) = [e for e in tr.events if e.name == "touchdown"]
    (flag,) = [e for e in tr.events if e.name == "long_landing"]
    x_td = float(td.detail.split(" at ")[1].removesuffix(" m"))
    assert flag.t_s == td.t_s == tr.event_time("rollout") and 300.0 < x_td < 914.4
    assert flag.detail == f"touchdown {x_td:.0f} m past the threshold, beyond the touchdown zone's 300 m"


# ---------------------------------------------------------------------- the landing
def test_hard_landing(monkeypatch):
    """A hard landing drawn at 9.5 ft/s (the scenario's firmest allowed sink, 2.9 m/s) against the
    limit lowered from 12 to 6 ft/s (the 737's flare lands within about 1 ft/s of its draw). The sink it
    judges is the one the track records (flight_metrics.touchdown_index: the step before first contact),
    to the bit: the same flight, stopped half a second after that touchdown under the 12 ft/s limit,
    records the failure's value. (Judged at the pilot's tick instead, up to three steps after contact,
    the struts had slowed the sink: a flight recorded at 12.20 ft/s was checked at under 12 and landed.)"""
    from flightmode.runs import pipeline
    from flightmode.scenarios.scenario import Scenario
    from flightmode.sim.flight import simulate
    from flightmode.sim.flight.flight_metrics import touchdown_index

    changes = SHORT | {"landing": {"sink_mps": 2.9}}
    with monkeypatch.context() as m:
        _profile(m, tuning={"max_touchdown_sink_mps": 6.0 * 0.3048})
        e = _fly(1000.0, **changes)
    _check(e, "hard_landing", "flare", r"hard landing: touchdown sink rate \d+\.\d ft/s exceeds 6 ft/s")
    assert 7.5 < e.value < 12.0
    sc = Scenario.builtin("pattern").replace(aircraft="737", **changes)
    tr = simulate.fly(sc.plan, pipeline.streams_of(sc.seed).child("flight"), stop_after_s=e.t_s + 0.5)
    assert tr.wow[-1] and e.value == -tr.vertical_speed_mps[touchdown_index(tr) - 1] / 0.3048


def test_touchdown_short_of_the_runway(monkeypatch):
    """The glideslope aimed 800 m before the threshold instead of 300 m past it: the 737 lands short."""
    _profile(monkeypatch, tuning={"touchdown_aim_m": -800.0})
    e = _fly(1000.0)
    _check(e, "off_runway", "flare", r"ground contact off the runway at x = -\d+ m", over=False)
    assert e.quantity == "distance past the threshold (m)" and e.limit == -50.0 and e.value < -50.0


def test_balloon_on_the_last_approach(monkeypatch):
    """The last approach (MAX_APPROACHES lowered to 1) with a balloon threshold of half the flare height:
    the flare's first tick is 'a balloon', which on the last approach fails the flight."""
    from flightmode.sim.flight.pilot import flare

    monkeypatch.setattr(flare, "MAX_APPROACHES", 1)
    monkeypatch.setattr(flare, "FLARE_BALLOON_FACTOR", 0.5)
    e = _fly(1000.0)
    _check(e, "balloon_last_approach", "flare", r"balloon: the flare climbed to \d+ ft .* on approach 1;")
    from flightmode.sim.flight.aircraft.registry import PROFILES

    assert e.limit == 0.5 * PROFILES["737"].flare_height_ft and e.value > e.limit  # both in ft


# ---------------------------------------------------------------------- the table
KINDS_PROVOKED = {
    "nan": test_nan_in_a_jsbsim_property_ends_the_flight_naming_the_channel,
    "below_ground": test_below_the_ground,
    "altitude": test_altitude_divergence,
    "mach": test_mach_divergence_in_the_takeoff_roll,
    "stand_time": test_stand_time_limit,
    "off_taxiway": test_left_the_taxiway,
    "bank": test_bank_limit_in_the_first_turn,
    "stall": test_stall_in_the_initial_climb,
    "no_progress": test_a_flight_that_circles_ends_long_before_its_fuel_does,
    "hard_landing": test_hard_landing,
    "off_runway": test_touchdown_short_of_the_runway,
    "balloon_last_approach": test_balloon_on_the_last_approach,
}


def raise_sites() -> dict[str, list[str]]:
    """Every FlightDivergedError the package raises (``raise FlightDivergedError(...)`` or a pilot's
    ``fail(...)``), by its ``kind`` keyword: kind -> ["file:line", ...]. A site without a literal kind
    is listed under None."""
    sites: dict = {}
    for path in sorted((ROOT / "sim").rglob("*.py")) + sorted((ROOT / "flightmode").rglob("*.py")):
        tree = ast.parse(path.read_text(), str(path))
        for node in ast.walk(tree):
            if not isinstance(node, ast.Call):
                continue
            f = node.func
            name = f.attr if isinstance(f, ast.Attribute) else f.id if isinstance(f, ast.Name) else None
            if name == "FlightDivergedError" and path.name == "errors.py":
                continue  # the class's own unpickling helper
            if name not in ("FlightDivergedError", "fail"):
                continue
            if name == "fail" and "pilot" not in path.parts:
                continue
            kind = next((k.value for k in node.keywords if k.arg == "kind"), None)
            if isinstance(kind, ast.Name) and kind.id == "kind":
                continue  # Pilot.fail itself, passing its caller's kind on
            kind = kind.value if isinstance(kind, ast.Constant) else None
            sites.setdefault(kind, []).append(f"{path.relative_to(ROOT)}:{node.lineno}")
    return sites


def table_kinds() -> dict[str, str]:
    """docs/failures.md's table of causes (above its first section; the sections' tables are of
    tests and parsers): kind -> the row."""
    rows = {}
    causes = (ROOT / "docs" / "failures.md").read_text().split("\n## ")[0]
    for line in causes.splitlines():
        m = re.match(r"\|\s*`([a-z_]+)`\s*\|", line)
        if m:
            rows[m.group(1)] = line
    return rows


def test_every_raise_site_has_a_kind_a_row_in_docs_failures_and_a_test():
    sites = raise_sites()
    assert None not in sites, f"FlightDivergedError raised without a literal kind= at {sites.get(None)}"
    rows = table_kinds()
    flight_kinds = {k for k in rows if k != "wall_time"}
    assert set(sites) == flight_kinds, (sorted(sites), sorted(flight_kinds))
    assert set(KINDS_PROVOKED) == set(sites)
    # each row names the test that provokes it
    for kind, test in KINDS_PROVOKED.items():
        assert test.__name__ in rows[kind], kind
    assert "test_a_flight_past_the_wall_time_limit" in rows["wall_time"]
