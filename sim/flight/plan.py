"""The flight plan: the plain, validated data :func:`flightmode.sim.flight.simulate.fly` consumes.

``scenarios/`` builds a :class:`FlightPlan` from a scenario (its flight sections); the flight side
never reads files itself. All units SI (or degrees where named).
"""

from __future__ import annotations

from dataclasses import dataclass

from flightmode.labels import SEVERITIES  # noqa: F401  (re-exported for validation)
from flightmode.units import FT_M


@dataclass(frozen=True, slots=True)
class Runway:
    """A runway threshold: where the landing aircraft crosses, and where takeoffs line up."""

    icao: str
    name: str
    lat_deg: float
    lon_deg: float
    elevation_m: float
    heading_deg: float
    length_m: float
    width_m: float = 45.0

    @property
    def touchdown_zone_end_m(self) -> float:
        """Where the touchdown zone ends, m past the threshold: 3,000 ft or the runway's midpoint,
        whichever is less (FAA AIM 2-1-5, touchdown zone lighting). 14 CFR 91.175(c)(1) lets an
        airline crew continue below the decision height only to a touchdown inside it."""
        return min(3000.0 * FT_M, self.length_m / 2.0)


@dataclass(frozen=True, slots=True)
class TaxiPlan:
    """A generated taxi route (see :mod:`flightmode.sim.flight.taxi_route`).

    ``length_m`` is the taxiway distance between the gate area and the runway; the route is a
    pushback, a straight run along a parallel taxiway ``taxiway_offset_m`` from the centreline,
    a connector, a hold short and a line-up (out), or a 45 degree exit, the taxiway and a
    90 degree turn into the stand (in). ``holds_s`` are stops along the taxiway (e.g. for
    crossing traffic), evenly spaced.
    """

    length_m: float
    holds_s: tuple[float, ...] = ()
    lineup_hold_s: float = 30.0
    taxiway_offset_m: float = 180.0
    apron_depth_m: float = 80.0


@dataclass(frozen=True, slots=True)
class TurbulenceSegment:
    """A turbulence patch from ``start_s`` after liftoff for ``duration_s``, of a named severity
    (light, moderate, severe); its EDR is drawn inside the severity's band unless ``edr`` is given
    (:mod:`flightmode.sim.flight.turbulence`)."""

    start_s: float
    duration_s: float
    severity: str
    edr: float | None = None


@dataclass(frozen=True, slots=True)
class FlightPlan:
    name: str
    aircraft: str
    origin: Runway
    destination: Runway
    taxi_out: TaxiPlan
    taxi_in: TaxiPlan
    cruise_alt_m: float
    cruise_mach: float
    gate_wait_s: float = 120.0
    takeoff_thrust_norm: float | None = None  # None: drawn per flight (sim.flight.draws)
    takeoff_flaps_norm: float | None = None  # None: the aircraft profile's value
    landing_flaps_norm: float | None = None
    waypoints: tuple[tuple[float, float], ...] = ()
    turbulence: tuple[TurbulenceSegment, ...] = ()
    descent_angle_deg: float = 2.8
    glideslope_deg: float = 3.0
    approach_fix_nm: float = 16.0
    autobrake_decel_mps2: float = 1.5
    post_shutdown_s: float = 30.0
    fdm_hz: int = 120  # JSBSim's integration rate and the FlightTrack's sample rate
    landing_quality: str = "normal"  # normal, firm, hard: the touchdown sink speed's distribution
    touchdown_sink_mps: float | None = None  # fixes the touchdown sink target instead of drawing it
    go_arounds: int = 0  # go-arounds ordered at the flare height (sim.flight.pilot.go_around.GoAround)
    surface_wind_mps: float | None = None  # fixes the wind at 20 ft (the boundary layer's gustiness)
    background_edr: float | None = None  # fixes the background turbulence above 2000 ft (EDR, m^2/3 s^-1)
    convective_velocity_mps: float | None = (
        None  # fixes the mixed layer's convective velocity scale w* (0: none)
    )
    departure_qnh_hpa: float | None = (
        None  # fixes the departure airport's QNH (None: drawn, sim.flight.cabin)
    )
    arrival_qnh_hpa: float | None = None  # fixes the arrival airport's QNH (None: drawn)
    isa_dev_k: float | None = (
        None  # fixes the ISA temperature deviation at both airports (None: drawn per airport)
    )
    hold: str = (
        "pressurised"  # the cargo hold: "pressurised" (the cabin's pressure) or "unpressurised" (ambient)
    )
