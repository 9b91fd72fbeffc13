"""Simulation: :mod:`flightmode.sim.flight` (JSBSim flies the aircraft, the FlightTrack) and
:mod:`flightmode.sim.sensor` (what the bag's sensors record, the Recording). One-way: the sensor side
reads a track; the flight side never imports the sensor side."""
