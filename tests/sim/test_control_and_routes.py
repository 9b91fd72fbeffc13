"""Control blocks and taxi-route geometry."""

import math

import pytest

from flightmode.sim.flight.control import PID, rate_limit
from flightmode.sim.flight.plan import TaxiPlan
from flightmode.sim.flight.taxi_route import Path2D, gate_position_out, pure_pursuit_steer_rad, taxi_in_path, taxi_out_path


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


def test_generated_taxi_routes_connect_stand_and_runway():
    plan = TaxiPlan(length_m=2000.0, holds_s=(30.0, 60.0), lineup_hold_s=20.0)
    gx, gy, gh = gate_position_out(plan)
    assert gy < -plan.taxiway_offset_m and gh == pytest.approx(-math.pi / 2)
    out = taxi_out_path(plan, (gx, -plan.taxiway_offset_m - 10.0), 3500.0)
    assert out.points[-1] == pytest.approx((3500.0, 0.0))  # ends down the runway centreline
    names = [s.name for s in out.stops]
    assert names == ["hold1", "hold2", "hold_short", "lineup"]
    lineup = out.point_at(out.s_of("lineup"))
    assert lineup[1] == pytest.approx(0.0) and lineup[0] > 0.0  # lined up on the centreline
    tin = taxi_in_path(plan, 1500.0)
    assert tin.points[0] == pytest.approx((1500.0, 0.0))
    assert tin.points[-1][1] == pytest.approx(-plan.taxiway_offset_m - plan.apron_depth_m)
