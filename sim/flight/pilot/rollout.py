"""The rollout: from touchdown to the exit speed (derotation, spoilers, reversers, autobrake)."""

from __future__ import annotations

import math

from flightmode.sim.flight.pilot.control import clamp, rate_limit
from flightmode.sim.flight.pilot.controller import Controller
from flightmode.units import KT_MPS

# derotation: the nose wheels meet the runway about 3.5 s after the mains (A320 cabin-floor landing
# shock record, Irvine, vibrationdata), so the pitch is lowered from its touchdown attitude to 1 deg
# over that time (and at no less than DEROTATION_MIN_RATE)
DEROTATION_S = 3.5
DEROTATION_MIN_RATE = math.radians(0.5)
# the nose gear's weight-on-wheels: the first ground contact of every profiled model is its nose gear
# (tests/sim/test_model_edits.py checks it)
NOSE_WOW = "gear/unit[0]/WOW"


class Rollout(Controller):
    """Spoilers and speedbrake out, reversers while fast, a deceleration-loop autobrake to the plan's
    target; the reverse thrust is trimmed down when it alone decelerates harder than the target."""

    def enter(self, x) -> None:
        ap = self.ap
        ap.ac.set("fcs/speedbrake-cmd-norm", 1.0)
        ap.ac.set("fcs/spoiler-cmd-norm", 1.0)
        # stop flaring: the attitude held as it is (no further pull: with lift still near the weight,
        # a pull after the first contact bounces the aircraft back into the air), then lowered
        ix, prof = self.p.ix, self.p.prof
        theta = x[ix["theta_rad"]]
        ap.theta_cmd = theta
        # the elevator keeps the type's share of where the flare left it (the attitude loop's
        # integrator takes over the flare's bias; the rest relaxes at once, as the flare's pull)
        u_now = -ap.ac.get("fcs/elevator-cmd-norm")
        keep = prof.touchdown_elevator_keep
        ap.pitch_pid.reset(
            integral=keep * (u_now + prof.pitch_kq * x[ix["q_radps"]]) / prof.pitch_ki
            + (1.0 - keep) * 0.5 * ap.pitch_pid.integral
        )
        # the nose is flown down to the runway over DEROTATION_S, not let fall
        self.derotation_rate = max((theta - math.radians(1.0)) / DEROTATION_S, DEROTATION_MIN_RATE)
        self.rev_thr = prof.reverse_throttle
        self.nose_down = False
        self.nose_on = False
        ap.brake_pid.reset()

    def tick(self, x) -> None:
        ap, p, ix, prof = self.ap, self.p, self.p.ix, self.p.prof
        ap.runway_track(x, ap.dest)
        ap.ac.set("fcs/aileron-cmd-norm", 0.0)
        ap.theta_cmd = rate_limit(ap.theta_cmd, math.radians(-1.0), self.derotation_rate * ap.dt)
        # the nose is flown down until its wheels carry weight (latched), then held on the runway; a
        # switch at a fixed attitude (0.5 deg) pushed the 787-8, whose nose wheels meet the runway at
        # -0.4 deg, into it at 4 deg/s (a 1.7 g increment at the cockpit on lhr-jfk-787)
        self.nose_on = self.nose_on or ap.ac.get(NOSE_WOW) > 0.5
        if not self.nose_on:
            # the flare's firmer attitude loop: the stock models' noses otherwise fall at 3-6 deg/s
            ap.pitch_to(x, ap.theta_cmd, bias=prof.flare_pitch_kp * (ap.theta_cmd - x[ix["theta_rad"]]))
        else:
            ap.ac.set("fcs/elevator-cmd-norm", 0.2)
        gs = ap.gs(x)
        # the nose wheel is down once the pitch falls below 1.5 deg (latched: some models sit at about
        # that attitude on their gear, and an unlatched test froze the brakes whenever it flickered)
        self.nose_down = self.nose_down or x[ix["theta_rad"]] < math.radians(1.5)
        nose_down = self.nose_down
        rev = nose_down and gs > 70.0 * KT_MPS
        for i in range(prof.n_engines):
            ap.ac.set(f"propulsion/engine[{i}]/reverser-angle-rad", math.pi if rev else 0.0)
        target = p.plan.autobrake_decel_mps2
        # below the easing speed the deceleration eases off linearly with the speed, to reach the
        # crew's taxi deceleration at ``rollout_settle_mps`` above the exit speed at about
        # ``rollout_ease_mps3``, and holds it to the exit speed (the taxi-in then goes on
        # decelerating at that rate: no braking step at the hand-over)
        a_taxi = p.taxi.style.decel_mps2
        v_settled = ap.tune.exit_speed_mps + ap.tune.rollout_settle_mps
        dv_ease = 0.5 * (target + a_taxi) * max(target - a_taxi, 0.0) / ap.tune.rollout_ease_mps3
        if gs < v_settled + dv_ease:
            target = a_taxi + (target - a_taxi) * max(0.0, gs - v_settled) / dv_ease
        self.rev_thr = clamp(self.rev_thr + 0.5 * ap.dt * (target - ap.decel_f), 0.0, prof.reverse_throttle)
        ap.throttle(self.rev_thr if rev else 0.0)
        if nose_down:
            ap.brakes(ap.brake_pid(target - ap.decel_f, ap.dt))
        if gs < ap.tune.exit_speed_mps:
            for prop in (
                "fcs/speedbrake-cmd-norm",
                "fcs/spoiler-cmd-norm",
                "fcs/rudder-cmd-norm",
                "fcs/elevator-cmd-norm",
            ):
                ap.ac.set(prop, 0.0)
            ap.set_flaps(0.0)
            p.fire("exit_speed")
