"""A scenario between any two airports: :func:`scenario_between` (``flightmode fly --from LSGG --to
EGLL --aircraft A320``).

Every choice is drawn from the run's own streams (``route/...``, :mod:`flightmode.streams`), so the
same airports, type and seed give the same scenario:

- the runway in use at each end: a surface wind from a direction uniform on the compass (no
  climatology is shipped), and the usable paved end with the most headwind
  (:func:`flightmode.scenarios.airports.pick_end`); the landing threshold is the displaced one.
- the route: straight out along the runway, then the great circle to the approach fix, lined up with
  the arrival runway (the pilot's lateral navigation); no published procedures.
- the cruise level: the type's usual level (:attr:`AircraftProfile.cruise_level_ft`, OpenAP WRAP)
  or, on a route too short for it, the highest level whose climb and descent take at most
  :data:`CLIMB_DESCENT_SHARE` of the route; then the flight level below it by the semicircular rule
  (ICAO Annex 2, Appendix 3: courses 000-179 deg odd thousands of feet, 180-359 even).
- the taxi distances: log-uniform between the shortest and the longest real taxi of that direction
  in the ADS-B sample (:data:`flightmode.sim.flight.taxi_stats.ADSB_TAXI_ANCHORS`); one hold on the
  way out and the line-up wait uniform in the built-in scenarios' ranges.
"""

from __future__ import annotations

import math

from flightmode.errors import ScenarioError
from flightmode.units import FT_M, NM_M

CLIMB_DESCENT_SHARE = 0.7  # on a short route, climb + descent take at most this share of it
MIN_ROUTE_M = 100_000.0  # shorter: no airliner schedules it (and there is no cruise to speak of)
TAXI_HOLD_S = (20.0, 90.0)  # the one hold on the way out (built-ins: 45-90 s)
LINEUP_HOLD_S = (10.0, 45.0)  # line up and wait (built-ins: 10-45 s)
GATE_WAIT_S = 300.0  # engines off at the stand before engine start (the default built-in's)


def _taxi_range_m(direction: str) -> tuple[float, float]:
    from flightmode.sim.flight.taxi_stats import ADSB_TAXI_ANCHORS

    d = [
        seg["distance_m"]
        for segs in ADSB_TAXI_ANCHORS.values()
        for k, seg in segs.items()
        if k.startswith(direction)
    ]
    return min(d), max(d)


def flight_level_ft(max_alt_m: float, course_deg: float) -> float:
    """The highest flight level at or below ``max_alt_m`` for a true course (semicircular rule: odd
    thousands of feet eastbound, 000-179 deg; even westbound)."""
    thousands = math.floor(max_alt_m / FT_M / 1000.0)
    odd = (course_deg % 360.0) < 180.0
    if (thousands % 2 == 1) != odd:
        thousands -= 1
    return thousands * 1000.0


def cruise_altitude_m(
    route_m: float,
    course_deg: float,
    prof,
    origin_elev_m: float,
    dest_elev_m: float,
    descent_angle_deg: float,
    glideslope_deg: float = 3.0,
) -> float:
    """The cruise altitude (module docstring) for a route of ``route_m``."""
    from flightmode.scenarios.spec import CLIMB_GRADIENT

    budget = CLIMB_DESCENT_SHARE * route_m - 10.0 * NM_M  # the last 10 NM are the glideslope's
    per_m = 1.0 / CLIMB_GRADIENT + 1.0 / math.tan(math.radians(descent_angle_deg))
    by_distance = max(origin_elev_m, dest_elev_m) + budget / per_m
    top = min(prof.cruise_level_ft, prof.ceiling_ft) * FT_M
    return flight_level_ft(min(top, by_distance), course_deg) * FT_M


def scenario_between(origin: str, destination: str, aircraft: str, seed: int = 1, **overrides):
    """The :class:`~flightmode.scenarios.scenario.Scenario` of a flight from ``origin`` to
    ``destination`` (ICAO codes) on ``aircraft``; ``overrides`` go to :meth:`Scenario.replace`."""
    from flightmode.scenarios import airports as ap
    from flightmode.scenarios.scenario import Scenario
    from flightmode.sim.flight.aircraft.registry import get_profile
    from flightmode.sim.flight.geodesy import gc_distance_m, initial_course_deg
    from flightmode.streams import Streams

    prof = get_profile(aircraft)
    o, d = ap.airport(origin), ap.airport(destination)
    if o.icao == d.icao:
        raise ScenarioError(f"--from and --to are both {o.icao}: give two different airports")
    dist = gc_distance_m(o.lat_deg, o.lon_deg, d.lat_deg, d.lon_deg)
    if dist < MIN_ROUTE_M:
        raise ScenarioError(
            f"{o.icao} to {d.icao} is {dist / 1000:.0f} km, shorter than the {MIN_ROUTE_M / 1000:.0f} km "
            "an airliner route needs here; choose airports farther apart"
        )
    if dist > prof.range_km * 1000.0:
        from flightmode.sim.flight.aircraft.registry import PROFILES

        longer = [
            f"{m}: {p.range_km:,.0f} km" for m, p in sorted(PROFILES.items()) if p.range_km * 1000.0 >= dist
        ]
        raise ScenarioError(
            f"{o.icao} to {d.icao} is {dist / 1000:,.0f} km, beyond the {aircraft}'s range of "
            f"{prof.range_km:,.0f} km; choose a nearer destination"
            + (f" or a type that reaches it ({', '.join(longer)})" if longer else "")
        )
    rng = Streams(seed).child("route")
    wind = rng.rng("wind").uniform(0.0, 360.0, 2)  # from, at the origin and at the destination
    try:
        dep = ap.pick_end(o, prof.min_runway_m, float(wind[0]), aircraft, landing=False)
    except ScenarioError as e:
        raise ScenarioError(
            f"{e} (nearest that suit: {', '.join(ap.nearest_usable(o.lat_deg, o.lon_deg, prof.min_runway_m))})"
        ) from None
    try:
        arr = ap.pick_end(d, prof.min_runway_m, float(wind[1]), aircraft, landing=True)
    except ScenarioError as e:
        raise ScenarioError(
            f"{e} (nearest that suit: {', '.join(ap.nearest_usable(d.lat_deg, d.lon_deg, prof.min_runway_m))})"
        ) from None
    course = float(initial_course_deg(o.lat_deg, o.lon_deg, d.lat_deg, d.lon_deg)) % 360.0
    descent_deg = prof.descent_angle_deg
    cruise_m = cruise_altitude_m(dist, course, prof, dep.elevation_m, arr.elevation_m, descent_deg)
    t = rng.rng("taxi")
    lo_out, hi_out = _taxi_range_m("taxi_out")
    lo_in, hi_in = _taxi_range_m("taxi_in")
    taxi_out = float(math.exp(t.uniform(math.log(lo_out), math.log(hi_out))))
    taxi_in = float(math.exp(t.uniform(math.log(lo_in), math.log(hi_in))))
    hold, lineup = float(t.uniform(*TAXI_HOLD_S)), float(t.uniform(*LINEUP_HOLD_S))
    name = f"{o.icao.lower()}-{d.icao.lower()}-{prof.model.lower()}"
    doc = {
        "scenario": {
            "name": name,
            "aircraft": prof.model,
            "seed": int(seed),
            "gate_wait_s": GATE_WAIT_S,
            "description": f"{o.name} ({o.icao} {dep.ident}) to {d.name} ({d.icao} {arr.ident}) on the "
            f"{prof.model}, {dist / 1000:,.0f} km, FL{cruise_m / FT_M / 100:.0f}",
        },
        "origin": {"icao": o.icao, "runway": dep.ident, **ap.runway_keys(o.icao, dep.ident, landing=False)},
        "destination": {
            "icao": d.icao,
            "runway": arr.ident,
            **ap.runway_keys(d.icao, arr.ident, landing=True),
        },
        "taxi_out": {
            "length_m": round(taxi_out, 1),
            "holds_s": [round(hold, 1)],
            "lineup_hold_s": round(lineup, 1),
        },
        "taxi_in": {"length_m": round(taxi_in, 1)},
        "cruise": {"altitude_m": round(cruise_m, 1), "mach": prof.cruise_mach},
        "descent": {"angle_deg": descent_deg},
    }
    sc = Scenario.from_doc(doc, f"{o.icao} -> {d.icao} ({prof.model})")
    return sc.replace(**overrides) if overrides else sc


__all__ = ["scenario_between", "cruise_altitude_m", "flight_level_ft"]
