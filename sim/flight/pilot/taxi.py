"""Taxiing: pure pursuit along a taxi route (:mod:`flightmode.sim.flight.taxi_route`), out to the
runway's line-up and in from the rollout's exit to the stand."""

from __future__ import annotations

import math

from flightmode.sim.flight.pilot.control import clamp
from flightmode.sim.flight.pilot.controller import Controller
from flightmode.sim.flight.taxi_route import taxi_in_route


class Taxi(Controller):
    """Pure pursuit along a taxi route (:class:`~flightmode.sim.flight.taxi_route.TaxiRoute`) at its
    scheduled speed, stopping at its holds (``holding`` meanwhile); :meth:`taxi` returns True at the
    route's end.

    The speed reference closes on the schedule (and each stop's braking curve) read one time
    constant ``taxi_ref_tau_s`` of travel ahead, as a first-order lag whose rate stays between the
    crew's acceleration and 10 % more than its deceleration: the lag makes every change of
    acceleration gradual (a driver easing off the brakes as the speed is reached), the look-ahead
    cancels the lag on the schedule's ramps, so that turns are still entered at their speed. The
    throttle and brakes (:meth:`Autopilot.speed_on_ground`) follow that reference."""

    def start_route(self, route, v0_mps: float) -> None:
        ap = self.ap
        self.route = route
        ap.path = route.path
        self.stop_idx = 0
        self.hold_until: float | None = None
        self.v_ref = v0_mps
        ap.ground_spd_pid.reset()

    # Controller.holding is a class attribute that only the pilot reads (nothing sets it on a
    # controller): a read-only property in its place is sound, though mypy cannot know it
    @property
    def holding(self) -> bool:  # type: ignore[override]
        return self.hold_until is not None

    def taxi(self, x, frame) -> bool:
        ap, p, tau = self.ap, self.p, self.ap.tune.taxi_ref_tau_s
        style = self.route.style
        gs = ap.gs(x)
        s, cross = ap.follow(
            x,
            frame,
            max(12.0, ap.tune.taxi_lookahead_s * gs),
            ap.tune.taxi_max_steer_deg,
            1.2 * style.yaw_rate_max_radps,
        )
        if abs(cross) > TAXI_MAX_CROSS_M:
            p.fail(
                f"left the taxiway: {abs(cross):.1f} m from the taxi route, more than {TAXI_MAX_CROSS_M:.1f} m",
                kind="off_taxiway",
                quantity="distance from the taxi route (m)",
                value=abs(cross),
                limit=TAXI_MAX_CROSS_M,
            )
        stops = ap.path.stops
        decel = style.decel_mps2
        ahead = gs * tau
        v_cmd = min(self.route.speed_at(s), self.route.speed_at(s + ahead))
        if abs(cross) > TAXI_OFF_LINE_M:
            # off the centre line (a nose wheel that lags behind a reversal of turn, as the JSBSim
            # A320's does): slow down, as a crew would, so that the same yaw rate turns tighter
            v_cmd = min(v_cmd, TAXI_RECOVER_MPS)
        done = False
        if self.hold_until is not None:
            v_cmd = 0.0
            if p.t >= self.hold_until:
                self.hold_until = None
                ap.ground_spd_pid.reset()
                if stops[self.stop_idx].name == "lineup":
                    done = True
                self.stop_idx += 1
        else:
            if self.stop_idx < len(stops):
                st = stops[self.stop_idx]
                d, hold = st.s_m - s, st
            else:
                d, hold = ap.path.length_m - s, None
            v_cmd = min(v_cmd, math.sqrt(max(0.0, 2 * decel * (d - 1.0 - ahead))))
            if d < 3.0 and gs < (TAXI_PARKED_MPS if hold is None else 0.3):
                if hold is None:
                    done = True
                else:
                    self.hold_until = p.t + hold.hold_s
                    p.event("hold", f"{hold.name} {hold.hold_s:.0f} s")
        a_ref = clamp((v_cmd - self.v_ref) / tau, -1.1 * decel, style.accel_mps2)
        self.v_ref = max(0.0, self.v_ref + a_ref * ap.dt)
        ap.speed_on_ground(gs, self.v_ref, a_ref)
        return done


TAXI_OFF_LINE_M = 1.5  # off the taxi route's centre line by more than this, the crew slows down
TAXI_RECOVER_MPS = 1.5  # to this speed, until back on the line

# the stand is reached once the aircraft has come to rest on its taxi brakes: the parking brake set at
# a walking pace (0.3 m/s) stopped it in one jolt, 0.07 g on the 737
TAXI_PARKED_MPS = 0.05


class TaxiOut(Taxi):
    def enter(self, x) -> None:
        self.start_route(self.p.taxi.route_out, 0.0)

    def tick(self, x) -> None:
        if self.hold_until is None and self.ap.flaps == 0.0:
            self.ap.set_flaps(self.p.plan.takeoff_flaps_norm or self.p.prof.takeoff_flaps_norm)
        if self.taxi(x, self.ap.origin):
            self.p.fire("lined_up")


class TaxiIn(Taxi):
    """Taxi to the stand from where the rollout handed over, decelerating on at the rollout's last
    rate: the speed reference starts at the ground speed and the brakes where the autobrake left
    them (no step)."""

    def enter(self, x) -> None:
        ap, ix = self.ap, self.p.ix
        rx, _ = ap.dest.to_xy(x[ix["lat_deg"]], x[ix["lon_deg"]])
        gs = ap.gs(x)
        tx = self.p.taxi
        self.start_route(taxi_in_route(self.p.plan.taxi_in, tx.arrival, tx.style, rx, gs), gs)
        ap.taxi_brake = 0.5 * (ap.ac.get("fcs/left-brake-cmd-norm") + ap.ac.get("fcs/right-brake-cmd-norm"))
        ap.taxi_braking = True
        kp, ki = ap.tune.taxi_brake_pi
        ap.taxi_brake_int = (ap.taxi_brake - tx.style.decel_mps2 / ap.tune.taxi_brake_mps2) / ki

    def tick(self, x) -> None:
        if self.taxi(x, self.ap.dest):
            self.p.fire("at_stand")


# the taxi route's centre line this far away is off the paved taxiway: a code-E taxiway (787-8) is
# 23 m wide with 10.5 m shoulders each side (ICAO Annex 14, 3.9.4 and 3.10.1: 44 m overall), so 30 m
# from the centre line is on the grass for every type flown
TAXI_MAX_CROSS_M = 30.0
