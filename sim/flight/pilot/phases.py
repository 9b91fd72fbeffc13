"""The pilot's phases and the transitions between them, as data.

A flight moves from phase to phase only through :data:`TRANSITIONS`: a controller
(:mod:`flightmode.sim.flight.pilot.controllers`) reports that a named condition holds, and the pilot looks
the (phase, condition) pair up here to find the next phase (:meth:`Pilot.fire`); a pair that is not
in the table is a programming error. Each phase event of a FlightTrack carries the condition that
started it, so a flight shows which transitions fired. ``flightmode scenarios --phases`` prints the
table; ``tests/sim/test_phases.py`` walks it (every phase reachable from the gate, every phase has an
exit, the flight can always end) and checks every transition fires in some built-in flight.
"""

from __future__ import annotations

from dataclasses import dataclass

from flightmode.labels import FLIGHT_PHASES

START = "gate"


@dataclass(frozen=True, slots=True)
class Transition:
    source: str  # the phase the pilot is in
    condition: str  # what its controller reports
    target: str | None  # the next phase; None: the flight is over
    doc: str  # the condition in words


TRANSITIONS: tuple[Transition, ...] = (
    Transition("gate", "gate_wait_over", "engine_start", "the planned wait at the gate is over (starter on)"),
    Transition(
        "engine_start", "engines_running", "pushback", "every engine runs, started one by one (tug on)"
    ),
    Transition(
        "pushback", "tug_disconnected", "taxi_out", "pushed back and turned 90 deg onto the taxiway, stopped"
    ),
    Transition(
        "taxi_out", "lined_up", "takeoff_roll", "lined up on the runway, line-up hold over (takeoff thrust)"
    ),
    Transition(
        "takeoff_roll", "liftoff", "initial_climb", "off the ground: no weight on wheels, 1 m above the gear"
    ),
    Transition(
        "initial_climb", "climb_out_done", "climb", "3000 ft above the runway, or near the cruise altitude"
    ),
    Transition(
        "climb", "level", "cruise", "within 250 m of the target altitude (cruise, or the descent path)"
    ),
    Transition(
        "cruise", "top_of_descent", "descent", "the planned descent path falls below the cruise altitude"
    ),
    Transition("cruise", "localizer_capture", "approach", "localizer captured at the cruise altitude"),
    Transition(
        "descent", "localizer_capture", "approach", "on the approach fix's leg, aligned: localizer captured"
    ),
    Transition(
        "approach",
        "flare_height",
        "flare",
        "main gear below the type's flare height on the localizer (higher on a steep approach for a "
        "type that flares at a time to contact) or over the runway's second half still above it "
        "(the flare then goes around)",
    ),
    Transition("flare", "touchdown", "rollout", "weight on wheels (spoilers, reversers, autobrake)"),
    Transition(
        "flare",
        "go_around",
        "go_around",
        "a go-around ordered at the flare height, or the flare floats over the runway's second half or "
        "balloons (climb thrust, a circuit)",
    ),
    Transition("go_around", "localizer_capture", "approach", "back on the localizer after the circuit"),
    Transition("rollout", "exit_speed", "taxi_in", "below the runway exit speed (20 kt): flaps in, exit"),
    Transition("taxi_in", "at_stand", "shutdown", "stopped at the stand (fuel cut off)"),
    Transition("shutdown", "engines_off", "parked", "every engine's N2 below 5 %: the in-flight window ends"),
    Transition("parked", "recording_over", None, "the planned recording time after engines off is over"),
)

TABLE: dict[tuple[str, str], Transition] = {(t.source, t.condition): t for t in TRANSITIONS}
PHASES: tuple[str, ...] = FLIGHT_PHASES


def successors(phase: str) -> set[str | None]:
    return {t.target for t in TRANSITIONS if t.source == phase}


def reachable(start: str = START) -> set[str]:
    """Every phase reachable from ``start`` through the table."""
    seen, todo = {start}, [start]
    while todo:
        for nxt in successors(todo.pop()):
            if nxt is not None and nxt not in seen:
                seen.add(nxt)
                todo.append(nxt)
    return seen
