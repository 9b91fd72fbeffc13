"""Airports, runways and scenarios between any two airports (flightmode.scenarios.airports, .routes)."""

from __future__ import annotations

import math

import pytest

from flightmode.errors import AircraftError, ScenarioError
from flightmode.scenarios import airports as ap
from flightmode.scenarios.routes import cruise_altitude_m, flight_level_ft, scenario_between
from flightmode.sim.flight.aircraft.registry import get_profile
from flightmode.sim.flight.geodesy import gc_distance_m, initial_course_deg
from flightmode.units import FT_M


def test_geneva_runway_ends_agree_with_the_aerodrome_chart():
    # LSGG's one paved runway, 04/22 (AIP Switzerland: 3,900 m x 50 m, QFU 045/225): OurAirports gives
    # 12,795 ft = 3,900 m, headings 45.5/225.5 true; the two ends are the runway's length apart (within
    # 1 %: the end coordinates are rounded to 1e-6 deg, i.e. 0.1 m, so the rest is the data's own)
    a = ap.airport("lsgg")
    ends = {e.ident: e for e in a.runways}
    assert set(ends) == {"04", "22"}
    e04, e22 = ends["04"], ends["22"]
    assert e04.length_m == pytest.approx(3900.0, abs=1.0)
    assert (e22.heading_deg - e04.heading_deg) % 360.0 == pytest.approx(180.0, abs=0.5)
    d = gc_distance_m(e04.lat_deg, e04.lon_deg, e22.lat_deg, e22.lon_deg)
    assert d == pytest.approx(e04.length_m, rel=0.01)
    # the heading given is the course from one end to the other (0.5 deg: rounding of the data)
    assert float(initial_course_deg(e04.lat_deg, e04.lon_deg, e22.lat_deg, e22.lon_deg)) == pytest.approx(
        e04.heading_deg, abs=0.5
    )


def test_runway_in_use_has_the_most_headwind():
    a = ap.airport("EGLL")  # 09L/27R and 09R/27L
    west = ap.pick_end(a, 2100.0, 270.0, "A320")  # wind from the west: land and take off westwards
    east = ap.pick_end(a, 2100.0, 90.0, "A320")
    assert west.ident.startswith("27") and east.ident.startswith("09")
    # two parallel strips with exactly opposite ends: a wind straight across gives every end zero
    # headwind (cos 90 deg, rounded), and the longer strip wins, landing or taking off by its own length
    import dataclasses

    e = a.runways[0]
    ends = (
        dataclasses.replace(e, ident="36L", heading_deg=0.0, length_m=3000.0, displaced_m=0.0),
        dataclasses.replace(e, ident="18R", heading_deg=180.0, length_m=3000.0, displaced_m=0.0),
        dataclasses.replace(e, ident="36R", heading_deg=0.0, length_m=3500.0, displaced_m=1000.0),
        dataclasses.replace(e, ident="18L", heading_deg=180.0, length_m=3500.0, displaced_m=0.0),
    )
    twin = dataclasses.replace(a, runways=ends)
    assert ap.pick_end(twin, 2100.0, 90.0, "A320", landing=False).length_m == 3500.0
    assert ap.pick_end(twin, 2100.0, 90.0, "A320", landing=True).ident == "18L"  # 36R lands on 2,500 m only
    assert ap.pick_end(twin, 2100.0, 10.0, "A320", landing=True).ident == "36L"  # into wind beats length


def test_unknown_airport_and_too_short_runways_are_one_line_errors():
    with pytest.raises(ScenarioError, match=r'unknown airport .LSGX. \(did you mean "LSG.'):
        ap.airport("LSGX")
    # London City (EGLC): one 1,508 m runway; the A320 needs 2,100 m here
    with pytest.raises(
        ScenarioError, match=r"EGLC .* no paved runway of 2100 m for the A320 .*longest is 15\d\d m"
    ):
        ap.pick_end(ap.airport("EGLC"), get_profile("A320").min_runway_m, 0.0, "A320")
    with pytest.raises(ScenarioError, match="nearest that suit: EG"):
        scenario_between("EGLC", "LFPG", "A320")


def test_route_errors_name_the_limit():
    with pytest.raises(
        ScenarioError, match=r"LFPG to KLAX is 9,\d{3} km, beyond the A320's range of 5,000 km"
    ):
        scenario_between("LFPG", "KLAX", "A320")
    with pytest.raises(ScenarioError, match="both LFPG"):
        scenario_between("LFPG", "lfpg", "A320")
    with pytest.raises(ScenarioError, match="shorter than the 100 km"):
        scenario_between("LFPG", "LFPO", "A320")
    with pytest.raises(AircraftError, match='did you mean "A320"'):
        scenario_between("LFPG", "LEMD", "A321")


def test_semicircular_rule():
    # ICAO Annex 2 Appendix 3: eastbound (000-179) odd thousands, westbound even
    assert flight_level_ft(11_000.0, 90.0) == 35_000.0  # 36,089 ft -> FL350 (odd)
    assert flight_level_ft(11_000.0, 270.0) == 36_000.0
    assert flight_level_ft(11_000.0, 179.9) == 35_000.0
    assert flight_level_ft(11_000.0, 180.0) == 36_000.0


def test_cruise_level_by_distance_fits_the_climb_and_descent():
    from flightmode.scenarios.routes import CLIMB_DESCENT_SHARE
    from flightmode.scenarios.spec import CLIMB_GRADIENT
    from flightmode.units import NM_M

    prof = get_profile("A320")
    for route_km in (150, 230, 400, 800, 2000):
        h = cruise_altitude_m(route_km * 1000.0, 90.0, prof, 400.0, 400.0, 2.8)
        # climb at 6 % and descent at 2.8 deg from h take at most 70 % of the route (+10 NM of glideslope)
        need = (h - 400.0) / CLIMB_GRADIENT + (h - 400.0) / math.tan(math.radians(2.8)) + 10 * NM_M
        assert need <= CLIMB_DESCENT_SHARE * route_km * 1000.0 + 1.0
        assert h <= prof.cruise_level_ft * FT_M  # never above the type's usual level
        assert round(h / FT_M / 1000.0) % 2 == 1  # an odd level eastbound
    # a long route cruises at the type's usual level's flight level
    assert cruise_altitude_m(2e6, 90.0, prof, 0.0, 0.0, 2.8) == 35_000 * FT_M


def test_scenario_between_is_a_valid_deterministic_scenario():
    a = scenario_between("LFPG", "LEMD", "A320", seed=4)
    b = scenario_between("LFPG", "LEMD", "A320", seed=4)
    assert a == b and a.digest() == b.digest()
    c = scenario_between("LFPG", "LEMD", "A320", seed=5)
    assert c.plan.taxi_out.length_m != a.plan.taxi_out.length_m  # the seed draws the taxi and the wind
    p = a.plan
    assert p.origin.icao == "LFPG" and p.destination.icao == "LEMD"
    assert p.origin.name in {e.ident for e in ap.airport("LFPG").runways}
    # the route is south-westbound (course about 200 deg): an even flight level, at most FL360
    assert round(p.cruise_alt_m / FT_M / 1000.0) % 2 == 0 and p.cruise_alt_m <= 36_000 * FT_M + 0.5
    # it writes and reads back as a scenario file
    from flightmode.scenarios.scenario import Scenario

    assert Scenario.from_toml_text(a.to_toml()) == a


@pytest.mark.parametrize("model", ["A320", "737", "fokker100", "787-8"])
def test_a_routes_descent_angle_is_its_types_and_keeps_the_mach_band_inside_wrap(model):
    """A flight between two airports descends on its type's path angle (profile descent_angle_deg).
    On one geometric path the vertical rate is the ground speed times the angle's tangent, largest
    in the constant-Mach band: at WRAP's descent Mach at its crossover altitude (ISA speed of sound),
    with a 40 kt (20 m/s) tailwind, it must stay under WRAP's largest constant-Mach descent rate for
    the type (the F100's 2.8 deg did not: 12.4 m/s against E190's 11.8; flown, 6 of 10 routes over)."""
    from openap import WRAP

    from flightmode.sim.flight import atmosphere

    prof = get_profile(model)
    sc = scenario_between("LFPG", "LEMD", model, seed=4)
    assert sc.plan.descent_angle_deg == prof.descent_angle_deg
    w = WRAP(prof.wrap_type)
    h_cross_m = float(w.descent_cross_alt_conmach()["default"]) * 1e3
    a_mps = math.sqrt(
        1.4 * atmosphere.R_AIR * float(atmosphere.temperature_k(h_cross_m))
    )  # gamma 1.4, dry air
    gs_mps = float(w.descent_const_mach()["default"]) * a_mps + 20.0
    vs_mps = gs_mps * math.tan(math.radians(sc.plan.descent_angle_deg))
    assert vs_mps < -float(w.descent_vs_conmach()["minimum"])


def test_a_scenario_file_without_a_descent_angle_takes_its_types():
    """[descent] angle_deg absent: the aircraft type's angle (the Fokker 100's 2.5 deg, the others'
    2.8), written back explicitly so the file round-trips."""
    import re

    from flightmode.scenarios.scenario import Scenario

    text = re.sub(r"\[descent\]\nangle_deg = [0-9.]+\n", "", Scenario.builtin("pattern").to_toml())
    assert "[descent]" not in text
    for model in ("737", "fokker100"):
        sc = Scenario.from_toml_text(text.replace('aircraft = "737"', f'aircraft = "{model}"'), model)
        assert sc.plan.descent_angle_deg == get_profile(model).descent_angle_deg
        assert Scenario.from_toml_text(sc.to_toml(), "again") == sc
    assert get_profile("fokker100").descent_angle_deg == 2.5 and get_profile("737").descent_angle_deg == 2.8


def test_cli_pair_options_go_together():
    from typer.testing import CliRunner

    from flightmode.cli.main import app

    r = CliRunner().invoke(app, ["fly", "--from", "LFPG", "--to", "LEMD"])
    assert r.exit_code == 2 and "--from, --to and --aircraft go together" in r.output
    r = CliRunner().invoke(app, ["fly", "--from", "LFPG", "--to", "LEMX", "--aircraft", "A320"])
    assert r.exit_code == 2 and "unknown airport 'LEMX' (did you mean \"LEM" in r.output


@pytest.mark.slow
def test_a_flight_between_two_airports_lands_on_the_runway_it_chose():
    import numpy as np

    from flightmode.runs import pipeline
    from flightmode.sim.flight.geodesy import RunwayFrame

    sc = scenario_between("LSGG", "LSZH", "A320", seed=3)
    track = pipeline.fly(sc, pipeline.streams_of(sc.seed).child("flight"))
    ev = {e.name: e.t_s for e in track.events}
    assert {"takeoff_roll", "cruise", "flare", "rollout", "taxi_in", "parked"} <= set(ev)
    # touchdown: on the destination runway chosen, within its width and length (the pilot's own
    # limits would have failed the flight otherwise; here from the track, independently)
    td = int(np.flatnonzero(track.wow & (track.t_s > ev["flare"]))[0])
    x, y = RunwayFrame(sc.plan.destination).to_xy(track.lat_deg[td], track.lon_deg[td])
    assert 0.0 < x < sc.plan.destination.length_m and abs(y) < sc.plan.destination.width_m / 2
    # the cruise level chosen was flown (within 30 m: the altitude hold's band)
    from flightmode.labels import PHASE_CODE

    cruise = track.phase_code == PHASE_CODE["cruise"]
    assert np.median(track.alt_m[cruise]) == pytest.approx(sc.plan.cruise_alt_m, abs=30.0)
