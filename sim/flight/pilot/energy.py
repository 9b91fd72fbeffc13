"""The energy-rate autothrottle the initial climb and the go-around share (Lambregts's total energy
control, AIAA paper 83-2239, 1983)."""

from __future__ import annotations

import math

from flightmode.sim.flight.pilot.control import PID, first_order_lag
from flightmode.units import G0_MPS2

# The energy-rate autothrottle of Boeing's reduced go-around thrust (AircraftProfile.go_around_climb_fpm)
# and of the A320's initial climb (AircraftProfile.initial_climb_thrust_for_rate): a PI (throttle per
# m/s of energy-rate error, and per m of its integral) on the energy rate, not the rate of climb:
# thrust sets the total energy's rate d(h + V^2 / 2g)/dt = V f_path / g (f_path the specific force
# along the flight path, (T cos(alpha) - D) / m), the pitch shares it between climb and speed (it
# holds the speed): the principle of Lambregts's total energy control (AIAA paper 83-2239, 1983).
# Closed on the rate of climb instead, the two loops fought here: the pitch traded speed for climb, the
# thrust answered the climb, and a 737 pattern go-around sank again at 430 ft at 127 kt. One throttle's
# worth of thrust is about 0.3 of the weight, 20 m/s of climb at 75 m/s: a loop gain near 0.6;
# integral time 3 s. The specific force is low-passed over ENERGY_RATE_TAU_S (gusts)
ENERGY_RATE_THRUST_PI = (0.03, 0.01)
ENERGY_RATE_TAU_S = 1.0


def energy_rate_mps(x, ix) -> float:
    """The total energy's rate V f_path / g (m/s; ENERGY_RATE_THRUST_PI)."""
    alpha = x[ix["alpha_rad"]]
    f_path = x[ix["fx_mps2"]] * math.cos(alpha) + x[ix["fz_mps2"]] * math.sin(alpha)
    return x[ix["tas_mps"]] * f_path / G0_MPS2


class EnergyRateThrottle:
    """An autothrottle that holds the total energy's rate (ENERGY_RATE_THRUST_PI: its PI, and its
    low-pass over ENERGY_RATE_TAU_S), the throttle within [``lo``, ``hi``], starting from ``start``."""

    def __init__(self, x, ix, lo: float, hi: float, start: float):
        kp, ki = ENERGY_RATE_THRUST_PI
        self.ix = ix
        self.pid = PID(kp, ki, 0.0, lo, hi)
        self.pid.reset(integral=start / ki)
        self.rate_mps = energy_rate_mps(x, ix)  # low-passed

    def __call__(self, x, target_mps: float, dt_s: float) -> float:
        self.rate_mps = first_order_lag(self.rate_mps, energy_rate_mps(x, self.ix), dt_s, ENERGY_RATE_TAU_S)
        return self.pid(target_mps - self.rate_mps, dt_s)
