"""The one label vocabulary every sample carries (tracks, recordings, datasets).

Phases are stored as small integer codes into :data:`PHASES` inside arrays and as strings at
the dataset edge. The flight phases are the pilot's (:mod:`flightmode.sim.flight.pilot.phases`); the bag's ground phases
(terminal walk, boarding, ...) from the carrier timeline.
"""

from __future__ import annotations

FLIGHT_PHASES = (
    "gate",
    "engine_start",
    "pushback",
    "taxi_out",
    "takeoff_roll",
    "initial_climb",
    "climb",
    "cruise",
    "descent",
    "approach",
    "flare",
    "go_around",
    "rollout",
    "taxi_in",
    "shutdown",
    "parked",
)
CARRIER_PHASES = (
    "terminal_walk",
    "terminal_rest",
    "boarding",
    "deplaning",
    "arrival_rest",
    "truck",
    "loading",
    "unloading",
)
PHASES = FLIGHT_PHASES + CARRIER_PHASES
PHASE_CODE = {name: i for i, name in enumerate(PHASES)}

# the in-flight window ends when every engine's N2 is below this after fuel cut-off ("engines off": the
# pilot's shutdown, sim.flight.pilot.ground.Shutdown); the engines excite no vibration from there on
ENGINES_OFF_N2_PCT = 5.0

AIRBORNE_PHASES = frozenset({"initial_climb", "climb", "cruise", "descent", "approach", "flare", "go_around"})

SEVERITIES = ("none", "light", "moderate", "severe")
SEVERITY_CODE = {name: i for i, name in enumerate(SEVERITIES)}
