"""Simulation room: the only ``import jsbsim`` (in :mod:`sim.jsbsim_adapter`), the pilot, and the
FlightTrack. Nothing is imported here at package import time."""
