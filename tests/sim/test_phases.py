"""The pilot's phase transition table (sim.flight.pilot.phases), walked as a graph, and fired in flight."""

from __future__ import annotations

import pytest

from flightmode.labels import FLIGHT_PHASES
from flightmode.sim.flight.pilot.controllers import CONTROLLERS
from flightmode.sim.flight.pilot.phases import START, TABLE, TRANSITIONS, reachable, successors


def test_every_phase_is_reachable_has_an_exit_and_can_end():
    assert set(CONTROLLERS) == set(FLIGHT_PHASES)  # one controller per phase, no other
    assert reachable(START) == set(FLIGHT_PHASES)  # every phase reachable from the gate
    for phase in FLIGHT_PHASES:
        assert successors(phase), f"{phase} has no exit"
        # and from every phase the flight can still end (no trap)
        assert any(None in successors(p) for p in reachable(phase)), f"no way to end from {phase}"
    # the table is a function of (phase, condition): no duplicate keys, every target a phase
    assert len(TABLE) == len(TRANSITIONS)
    assert {t.target for t in TRANSITIONS} - {None} <= set(FLIGHT_PHASES)


def fired_transitions(track) -> set[tuple[str, str]]:
    """(phase, condition) of every transition a flight took, from its phase events (each phase
    event's detail is the condition that started it; the end is the 'end' event)."""
    out, prev = set(), None
    for e in track.events:
        if e.name in FLIGHT_PHASES or e.name == "end":
            if prev is not None:
                out.add((prev, e.detail))
            prev = e.name
    return out


@pytest.mark.slow
def test_every_transition_fires_in_some_built_in_flight(fly_cached):
    from flightmode.scenarios.scenario import builtin_names

    fired = set()
    for name in builtin_names():
        _, tr = fly_cached(name)
        got = fired_transitions(tr)
        assert got <= set(TABLE), got - set(TABLE)  # nothing outside the table ever fires
        fired |= got
    assert fired == set(TABLE), f"never fired: {sorted(set(TABLE) - fired)}"


def test_cli_prints_the_table():
    from typer.testing import CliRunner

    from flightmode.cli.main import app

    r = CliRunner().invoke(app, ["scenarios", "--phases"], env={"COLUMNS": "200"})
    assert r.exit_code == 0, r.output
    for t in TRANSITIONS:
        assert t.source in r.output and (t.target or "end of the flight") in r.output
        assert t.doc[:40] in r.output
