"""Flying: the only ``import jsbsim`` (:mod:`flightmode.sim.flight.jsbsim.adapter`), the pilot, the
flight plan, taxi routes, aircraft profiles, geodesy and the FlightTrack. Never imports the sensor
side. Nothing is imported here at package import time."""
