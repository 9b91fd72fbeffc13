"""The base of the pilot's per-phase controllers (:mod:`flightmode.sim.flight.pilot.controllers` lists
them by phase). ``enter`` runs once, on the tick the phase begins; ``tick`` on every control tick of the
phase (from the next one)."""

from __future__ import annotations


class Controller:
    """A phase's controller. ``self.p`` is the pilot (time, events, :meth:`Pilot.fire`), ``self.ap``
    its autopilot (loops, actuators, shared navigation state)."""

    holding = False  # standing still on the brakes (the pilot then ticks at 4 Hz)

    def __init__(self, pilot):
        self.p = pilot
        self.ap = pilot.ap

    def enter(self, x) -> None:
        """Actions on the tick the phase begins."""

    def tick(self, x) -> None:
        raise NotImplementedError
