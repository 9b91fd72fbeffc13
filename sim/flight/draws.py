"""What varies from flight to flight, drawn once per flight from its ``flight`` streams: the climb's
vertical rates (per type, :class:`~flightmode.sim.flight.aircraft.performance.ClimbSchedule`), the
takeoff acceleration (the type's real traffic, which the pilot turns into a throttle at brake release:
:class:`~flightmode.sim.flight.aircraft.performance.TakeoffThrust`), the touchdown sink speed the flare
aims at, and the turbulence (:mod:`flightmode.sim.flight.turbulence`).
Each draw has its own named stream, so adding one never moves another.

Touchdown sink speed by landing quality (the scenario's ``[landing].quality``):

- ``normal``: lognormal with a median of 2.0 ft/s, as video surveys of airline jets found at
  Washington National and JFK (FAA DOT/FAA/AR-97/106, 1999, and its JFK predecessor), and a spread that
  puts the once-in-1000 landing at 5.5 ft/s, the value NACA TN 3194 (Silsby, 1954, 478 landings)
  gives for calm air (ln spread ln(5.5 / 2.0) / 3.09 = 0.327);
- ``firm``: uniform 4.5-7 ft/s (270-420 ft/min), the upper tail of those surveys;
- ``hard``: uniform 7-9.5 ft/s (420-570 ft/min), just below the 10 ft/s limit sink speed of
  14 CFR 25.473(a) and the 600 ft/min hard-landing mark (SKYbrary, "Hard Landing"), so that the
  landing stays within what the gear is certified for and the flight goes on. Gusts scatter the
  flown sink by a few ft/s: a touchdown over 10 ft/s is a harder landing (the track says so, and
  validate fails its sink row); only one over 12 ft/s, the gear's reserve-energy sink (14 CFR
  25.723(b)), fails the flight.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass

import numpy as np

from flightmode.sim.flight.aircraft.profile import AircraftProfile
from flightmode.sim.flight.cabin import Weather, draw_weather
from flightmode.sim.flight.plan import FlightPlan
from flightmode.sim.flight.turbulence import Atmosphere, draw_atmosphere
from flightmode.units import FPS_MPS

LANDING_QUALITIES = ("normal", "firm", "hard")
SINK_NORMAL_MEDIAN_FPS = 2.0
SINK_NORMAL_LN_STD = math.log(5.5 / 2.0) / 3.09  # P(> 5.5 ft/s) = 1e-3
SINK_BANDS_FPS = {"firm": (4.5, 7.0), "hard": (7.0, 9.5)}  # module docstring


@dataclass(frozen=True, slots=True)
class FlightDraws:
    climb_vs_mps: tuple[float, float, float]  # below the CAS crossover, constant CAS, constant Mach
    initial_climb_vs_mps: float  # liftoff to 1,500 ft (ClimbSchedule.vs_initial)
    takeoff_accel_target_mps2: (
        float | None
    )  # the drawn takeoff acceleration (None: the plan sets the throttle)
    touchdown_sink_mps: float  # what the flare aims at
    atmosphere: Atmosphere
    departure_weather: Weather  # the airports' QNH and ISA deviation (sim.flight.cabin)
    arrival_weather: Weather

    def as_dict(self) -> dict:
        a = self.atmosphere
        return {
            "climb_vs_mps": list(self.climb_vs_mps),
            "initial_climb_vs_mps": self.initial_climb_vs_mps,
            "takeoff_accel_target_mps2": self.takeoff_accel_target_mps2,
            "touchdown_sink_target_mps": self.touchdown_sink_mps,
            "surface_wind_mps": a.w20_mps,
            "background_edr_mid": a.edr_mid,
            "background_edr_upper": a.edr_upper,
            "patch_edr": list(a.patch_edr),
            "convective_velocity_mps": a.w_star_mps,
            "mixed_layer_depth_m": a.z_i_m,
            "departure_weather": self.departure_weather.as_dict(),
            "arrival_weather": self.arrival_weather.as_dict(),
        }


def draw_sink_mps(quality: str, rng: np.random.Generator) -> float:
    if quality == "normal":
        fps = SINK_NORMAL_MEDIAN_FPS * math.exp(SINK_NORMAL_LN_STD * rng.standard_normal())
        return (
            min(fps, SINK_BANDS_FPS["hard"][1]) * FPS_MPS
        )  # the lognormal's far tail (1e-7 of landings) capped below the limit
    lo, hi = SINK_BANDS_FPS[quality]
    return rng.uniform(lo, hi) * FPS_MPS


def draw_flight(
    plan: FlightPlan, profile: AircraftProfile, streams, overrides: Mapping[str, float] | None = None
) -> FlightDraws:
    """One flight's draws from its ``flight`` streams (named: ``climb``, ``climb/initial``, ``takeoff``,
    ``landing``, ``turbulence/atmosphere``, ``weather/departure``, ``weather/arrival``); the plan's fixed
    values replace the draws; ``overrides``: the run's uncertain model parameters."""
    c = profile.climb
    r = streams.rng("climb")
    climb = (c.vs_pre_cas.draw(r), c.vs_cas.draw(r), c.vs_mach.draw(r))
    vs_initial = c.vs_initial.draw(streams.rng("climb/initial"))  # its own stream: no other draw moves
    accel = profile.takeoff.accel.draw(streams.rng("takeoff"))  # drawn even when unused: no other draw moves
    accel_target = accel if plan.takeoff_thrust_norm is None else None
    sink = draw_sink_mps(plan.landing_quality, streams.rng("landing"))
    if plan.touchdown_sink_mps is not None:
        sink = plan.touchdown_sink_mps
    atm = draw_atmosphere(
        streams.rng("turbulence/atmosphere"),
        plan.turbulence,
        w20_mps=plan.surface_wind_mps,
        background_edr=plan.background_edr,
        w_star_mps=plan.convective_velocity_mps,
        overrides=overrides,
    )
    dep = _weather(plan, plan.departure_qnh_hpa, streams.rng("weather/departure"))
    arr = _weather(plan, plan.arrival_qnh_hpa, streams.rng("weather/arrival"))
    if plan.origin.icao == plan.destination.icao and plan.arrival_qnh_hpa is None:
        arr = dep  # back where it started (a pattern): one airport, one weather (a flight's hour moves QNH ~1 hPa)
    return FlightDraws(climb, vs_initial, accel_target, float(sink), atm, dep, arr)


def _weather(plan: FlightPlan, qnh_hpa: float | None, rng: np.random.Generator) -> Weather:
    """One airport's weather: drawn (sim.flight.cabin.draw_weather), then the plan's fixed values."""
    w = draw_weather(rng)
    return Weather(
        w.qnh_hpa if qnh_hpa is None else float(qnh_hpa),
        w.isa_dev_k if plan.isa_dev_k is None else float(plan.isa_dev_k),
    )
