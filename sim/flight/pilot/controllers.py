"""One small controller per phase of the flight. Each flies its phase with the shared loops of
:class:`~flightmode.sim.flight.pilot.autopilot.Autopilot` and reports, through :meth:`Pilot.fire`, the
condition that ends it; the next phase comes from the transition table
(:data:`flightmode.sim.flight.pilot.phases.TRANSITIONS`), never from here. ``enter`` runs once, on the tick
the phase begins; ``tick`` on every control tick of the phase (from the next one). Numbers come from
the aircraft profile and its :class:`~flightmode.sim.flight.aircraft.tuning.PilotTuning`.

This module is the table, :data:`CONTROLLERS` (phase -> controller class); the controllers live in
one module per phase group beside it.
"""

from __future__ import annotations

from flightmode.sim.flight.pilot.controller import Controller
from flightmode.sim.flight.pilot.enroute import EnRoute
from flightmode.sim.flight.pilot.flare import Flare
from flightmode.sim.flight.pilot.go_around import GoAround
from flightmode.sim.flight.pilot.ground import EngineStart, Gate, Parked, Pushback, Shutdown
from flightmode.sim.flight.pilot.rollout import Rollout
from flightmode.sim.flight.pilot.takeoff import InitialClimb, TakeoffRoll
from flightmode.sim.flight.pilot.taxi import TaxiIn, TaxiOut

CONTROLLERS: dict[str, type[Controller]] = {
    "gate": Gate,
    "engine_start": EngineStart,
    "pushback": Pushback,
    "taxi_out": TaxiOut,
    "takeoff_roll": TakeoffRoll,
    "initial_climb": InitialClimb,
    "climb": EnRoute,
    "cruise": EnRoute,
    "descent": EnRoute,
    "approach": EnRoute,
    "flare": Flare,
    "go_around": GoAround,
    "rollout": Rollout,
    "taxi_in": TaxiIn,
    "shutdown": Shutdown,
    "parked": Parked,
}
