"""Control blocks and taxi-route geometry."""

import math

import numpy as np
import pytest

from flightmode.sim.flight.pilot.control import PID, rate_limit
from flightmode.sim.flight.taxi_route import GRID_M, Path2D, draw_taxi, pure_pursuit_steer_rad, taxi_in_route


def test_pid_clamps_and_does_not_wind_up():
    pid = PID(kp=1.0, ki=1.0, lo=-1.0, hi=1.0)
    for _ in range(1000):
        u = pid(10.0, 0.01)  # saturated for 10 s
    assert u == 1.0
    # anti-windup: the integral did not grow while saturated, so the output leaves saturation
    # as soon as the error reverses (a wound-up integrator would stay at +1 for seconds)
    assert pid(-2.0, 0.01) < 1.0


def test_rate_limit():
    assert rate_limit(0.0, 5.0, 1.0) == 1.0
    assert rate_limit(0.0, -5.0, 1.0) == -1.0
    assert rate_limit(0.0, 0.5, 1.0) == 0.5


def test_path_projection_and_corners():
    p = Path2D([(0, 0), (100, 0), (100, 100)])
    assert p.length_m == pytest.approx(200.0)
    assert p.corners_s == (100.0,)
    s, cross = p.project(50.0, 3.0)
    assert s == pytest.approx(50.0)
    assert cross == pytest.approx(3.0)  # +y is right of a path heading +x
    assert p.point_at(150.0) == pytest.approx((100.0, 50.0))


def test_pure_pursuit_steers_toward_the_target_side():
    right, _ = pure_pursuit_steer_rad(0.0, 0.0, 0.0, (10.0, 5.0), 12.0)
    left, _ = pure_pursuit_steer_rad(0.0, 0.0, 0.0, (10.0, -5.0), 12.0)
    assert right > 0 > left
    straight, _ = pure_pursuit_steer_rad(0.0, 0.0, 0.0, (10.0, 0.0), 12.0)
    assert straight == pytest.approx(0.0)


def _routes(seed: int, holds_s=(30.0, 60.0)):
    import dataclasses

    from flightmode.scenarios.scenario import Scenario
    from flightmode.sim.flight.aircraft.registry import get_profile

    plan = Scenario.builtin("gva-lhr-a320").plan
    plan = dataclasses.replace(
        plan,
        taxi_out=dataclasses.replace(plan.taxi_out, length_m=2000.0, holds_s=holds_s),
        taxi_in=dataclasses.replace(plan.taxi_in, length_m=2500.0),
    )
    prof = get_profile(plan.aircraft)
    tx = draw_taxi(plan, prof, np.random.default_rng(seed))
    return plan, prof, tx


@pytest.mark.parametrize("seed", range(6))
def test_generated_taxi_routes_connect_stand_and_runway(seed):
    plan, prof, tx = _routes(seed)
    out = tx.route_out.path
    assert out.points[-1] == pytest.approx((plan.origin.length_m, 0.0))  # ends down the runway centreline
    assert [s.name for s in out.stops] == ["hold1", "hold2", "hold_short", "lineup"]
    lineup = out.point_at(out.s_of("lineup"))
    assert lineup[1] == pytest.approx(0.0, abs=1e-6) and lineup[0] > 0.0  # lined up on the centreline
    # the stand lies beyond the parallel taxiway, on the apron side (y < 0)
    assert tx.stand_xy_m[1] < -plan.taxi_out.taxiway_offset_m
    # sized to the plan: pushback (apron depth) + route to the line-up = the taxi-out length. The
    # builders size the parallel run by one linear correction (a fillet's length changes a little
    # when its leg moves), so within 1 % (the route is long enough here never to be clamped)
    assert out.s_of("lineup") + plan.taxi_out.apron_depth_m == pytest.approx(plan.taxi_out.length_m, rel=0.01)
    tin = taxi_in_route(plan.taxi_in, tx.arrival, tx.style, 1500.0, 10.0).path
    assert tin.points[0] == pytest.approx((1500.0, 0.0))  # starts where the rollout handed over
    assert tin.length_m == pytest.approx(plan.taxi_in.length_m, rel=0.01)
    assert tin.points[-1][1] < -plan.taxi_in.taxiway_offset_m  # ends at a stand beyond the taxiway


@pytest.mark.parametrize("seed", range(6))
def test_taxi_speed_schedule_obeys_its_turn_and_braking_limits(seed):
    """The schedule is the crew's limits, not a tuning: in every arc the speed is at most sqrt(a_lat R)
    and r_max R (a_lat: lateral acceleration, r_max: yaw rate, both drawn for the flight), and from one
    1 m grid point to the next the speed never falls faster than the drawn deceleration allows,
    v1^2 >= v0^2 - 2 a ds (kinematics; 1e-9 for rounding)."""
    _, _, tx = _routes(seed)
    route, st = tx.route_out, tx.style
    fl, path = route.fillet, route.path
    for i in np.flatnonzero(np.isfinite(fl.seg_radius_m)):
        r = float(fl.seg_radius_m[i])
        mid = 0.5 * (path.s_at[i] + path.s_at[i + 1])
        assert route.speed_at(mid) <= min(math.sqrt(st.lat_acc_mps2 * r), st.yaw_rate_max_radps * r) + 1e-9
    v = route.speed_mps
    assert np.all(v[1:] ** 2 >= v[:-1] ** 2 - 2.0 * st.decel_mps2 * GRID_M - 1e-9)
    # every speed within the crew's straight-taxiway speed
    assert v.max() <= st.straight_out_mps + 1e-9


def test_every_type_turns_within_the_icao_taxiway_curve_design():
    """ICAO Doc 9157 part 2 designs taxiway curves for v^2 / R = 1.32 m/s^2 (its speed-radius table,
    16 km/h on 15 m to 96 km/h on 540 m): no crew is drawn a lateral acceleration in turns above it."""
    from flightmode.sim.flight.aircraft.registry import PROFILES
    from flightmode.sim.flight.taxi_route import ICAO_CURVE_LAT_ACC_MPS2

    assert ICAO_CURVE_LAT_ACC_MPS2 == pytest.approx((96 / 3.6) ** 2 / 540.0, rel=0.02)  # the table's far end
    for name, prof in PROFILES.items():
        assert prof.tuning.taxi_lat_acc_mps2[1] <= ICAO_CURVE_LAT_ACC_MPS2, name


def _flown_on_schedule(route, frame, heading0_deg: float):
    """The route driven exactly on its speed schedule (t = integral of ds / v, each stop's hold added),
    sampled once a second as an ADS-B track is: times, latitudes, longitudes, speeds, headings."""
    path = route.path
    s = np.arange(0.0, path.length_m, 0.5)
    v = np.maximum(np.array([route.speed_at(x) for x in s]), 0.3)  # a stop's zero: crept through
    t = np.concatenate([[0.0], np.cumsum(0.5 / v[:-1])])
    for stop in path.stops:
        t[s >= stop.s_m] += stop.hold_s
    xy = np.array([path.point_at(x) for x in s])
    tg = np.arange(0.0, t[-1], 1.0)
    x, y = np.interp(tg, t, xy[:, 0]), np.interp(tg, t, xy[:, 1])
    ll = np.array([frame.to_latlon(a, b) for a, b in zip(x, y)])
    heading = (heading0_deg + np.degrees(np.unwrap(np.arctan2(np.gradient(y), np.gradient(x))))) % 360.0
    return tg, ll[:, 0], ll[:, 1], np.interp(tg, t, v), heading


def test_taxi_in_routes_turn_as_often_as_the_real_tracks_statistics_count():
    """A taxi-in is drawn a number of turns (the real tracks' turns per minute times its expected
    duration) and laid out to have them as taxi_stats counts them on an ADS-B track: driven on its own
    speed schedule and counted by the same statistics, each route shows its drawn count to within one
    turn (a rapid exit's merge onto the parallel taxiway is counted with the exit's tail, which a slow
    exit can leave outside the statistics' 20 s window), and the total over 40 routes to within 10 %,
    four such misses in 40 routes (measured: 132 drawn, 127 counted). Every apron layout (0-3 turns) occurs, and every route is as
    long as its plan (1 %; or its layout's shortest route) and ends at a stand beyond the parallel
    taxiway."""
    import dataclasses

    from flightmode.scenarios.scenario import Scenario
    from flightmode.sim.flight.aircraft.registry import get_profile
    from flightmode.sim.flight.geodesy import RunwayFrame
    from flightmode.sim.flight.taxi_stats import taxi_statistics

    base = Scenario.builtin("gva-lhr-a320").plan
    prof = get_profile(base.aircraft)
    frame = RunwayFrame(base.destination)
    drawn = counted = 0
    layouts = set()
    for seed in range(40):
        rng = np.random.default_rng(seed)
        length_m = float(np.exp(rng.uniform(np.log(400.0), np.log(4000.0))))  # stand near or far
        plan = dataclasses.replace(
            base, taxi_in=dataclasses.replace(base.taxi_in, length_m=length_m, holds_s=())
        )
        tx = draw_taxi(plan, prof, rng)
        lay = tx.arrival
        route = taxi_in_route(plan.taxi_in, lay, tx.style, 1500.0, 10.0)
        shortest = taxi_in_route(dataclasses.replace(plan.taxi_in, length_m=0.0), lay, tx.style, 1500.0, 10.0)
        assert route.path.length_m == pytest.approx(max(length_m, shortest.path.length_m), rel=0.01)
        assert route.path.points[-1][1] < -plan.taxi_in.taxiway_offset_m
        n = taxi_statistics(*_flown_on_schedule(route, frame, base.destination.heading_deg))["n_turns"]
        assert abs(n - lay.n_turns) <= 1, (seed, lay)
        drawn, counted = drawn + lay.n_turns, counted + n
        layouts.add(lay.apron_turns)
    assert layouts == {0, 1, 2, 3}
    assert counted == pytest.approx(drawn, rel=0.1), (drawn, counted)


def test_turn_count_keeps_a_short_segments_rate_inside_the_band():
    """turn_count: the drawn rate times the expected duration, rounded, while that rate stays inside
    the band; a short segment whose rounded count leaves it takes the count inside it, or the nearest
    by ratio when none fits; never under ``least``. The band is the profile's (the ADS-B 0.425-0.833
    turns per minute narrowed by a tenth at each end)."""
    from flightmode.sim.flight.aircraft.tuning import PilotTuning
    from flightmode.sim.flight.taxi_route import turn_count

    band = PilotTuning().taxi_turns_per_min
    lo, hi = band
    assert turn_count(0.6, 600.0, band, 3) == 6  # 10 min at 0.6: round(6.0), inside
    # 2.5 min: one turn is 0.40 per minute, under the band; two are 0.80, over it but nearer by ratio
    assert turn_count(0.5, 150.0, band, 1) == 2
    # 10 min at the band's top: round(7.6) = 8 is 0.80 per minute, outside; 7 (0.70) is inside
    assert turn_count(hi, 600.0, band, 3) == 7
    assert turn_count(0.6, 30.0, band, 3) == 3  # the least, whatever the rate
    assert turn_count(0.6, 0.0, band, 1) == 1  # no duration to time a rate over: the least
    for t_s in np.linspace(60.0, 1200.0, 200):  # every count inside the band where one fits
        for r in (lo, 0.6, hi):
            k = turn_count(r, t_s, band, 1)
            t_min = t_s / 60.0
            fits = [j for j in range(1, 40) if lo <= j / t_min <= hi]
            if fits:
                assert k in fits, (r, t_s, k)
            rounded = math.floor(r * t_min + 0.5 - 1e-12)  # a half to the lower count
            if rounded >= 1 and lo <= rounded / t_min <= hi:
                assert k == rounded, (r, t_s, k)  # the drawn rate's own count when it fits
