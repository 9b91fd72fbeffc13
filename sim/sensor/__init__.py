"""Sensing: the bag's life around the flight (carrier), airframe vibration, the accelerometer and
gyroscope models and the Recording. May read a FlightTrack, never changes it. Nothing is imported
here at package import time."""
