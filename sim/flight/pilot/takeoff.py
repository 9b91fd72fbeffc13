"""The takeoff: the roll and rotation, then the initial climb to the acceleration height and the
climb-out (:mod:`flightmode.sim.flight.pilot.energy` holds its autothrottle)."""

from __future__ import annotations

import math

from flightmode.sim.flight.pilot.control import clamp, rate_limit
from flightmode.sim.flight.pilot.controller import Controller
from flightmode.sim.flight.pilot.energy import EnergyRateThrottle
from flightmode.units import FT_M, KT_MPS, SLUG_FT3_KGM3

# The rotation's nose-up elevator bias is applied over this time, not at once: a step of it pitched the
# A320 and the 787-8 up at 11-17 deg/s^2 (0.36-0.53 g at the cockpit, at 40 % of the length ahead of
# the CG), where a smooth rotation toward 2-3 deg/s of pitch rate (Boeing 737 FCTM, Airbus A320 FCTM)
# takes about a second to build it (a few deg/s^2)
ROTATE_RAMP_S = 1.5
# the rotation's pitch rate: "about 3 deg/s" (Airbus A320 FCOM SOP; Boeing 737 FCTM: 2-3 deg/s)
ROTATE_RATE_DPS = 3.0


class TakeoffRoll(Controller):
    def enter(self, x) -> None:
        ap = self.ap
        ap.brake_pid.reset()
        ap.brakes(0.0)
        target = ap.draws.takeoff_accel_target_mps2
        if target is None:
            thr = self.p.plan.takeoff_thrust_norm
        else:  # the drawn acceleration at this weight and field (TakeoffThrust)
            thr = self.p.prof.takeoff.throttle_for(
                target, ap.mass_kg(), ap.ac.get("atmosphere/rho-slugs_ft3") * SLUG_FT3_KGM3
            )
        self.p.takeoff_thrust_norm = thr
        ap.throttle(thr)
        ap.theta_cmd = x[self.p.ix["theta_rad"]]
        ap.pitch_pid.reset()
        self.t_rotate = None  # when the rotation began (Vr)
        self.vr_mps = ap.vr_mps()  # at brake release (the roll burns little)
        self.bias = 0.0  # the rotation's elevator bias (ramped in: ROTATE_RAMP_S)

    def tick(self, x) -> None:
        ap, p, ix, prof = self.ap, self.p, self.p.ix, self.p.prof
        ap.runway_track(x, ap.origin)
        ias = x[ix["ias_mps"]]
        ap.bank_to(x, 0.0)
        if ias >= self.vr_mps:
            if self.t_rotate is None:
                self.t_rotate = p.t
                p.event("rotate", f"{ias / KT_MPS:.0f} kt")
            ap.theta_cmd = rate_limit(
                ap.theta_cmd, math.radians(prof.rotate_pitch_deg), math.radians(ROTATE_RATE_DPS) * ap.dt
            )
            # nose-up elevator bias while the mains still carry the aircraft (rotation), applied
            # smoothly (ROTATE_RAMP_S)
            self.bias = prof.rotate_elevator * min(1.0, (p.t - self.t_rotate) / ROTATE_RAMP_S)
            ap.pitch_to(x, ap.theta_cmd, bias=self.bias)
        else:
            ap.ac.set("fcs/elevator-cmd-norm", 0.0)
        if x[ix["wow"]] < 0.5 and x[ix["agl_m"]] > prof.cg_height_m + 1.0:
            p.t_liftoff = p.t
            p.event("liftoff", f"{ias / KT_MPS:.1f} kt")
            ap.steer(0.0)
            ap.ac.set("fcs/rudder-cmd-norm", 0.0)
            # hand the rotation bias over to the pitch integrator so the elevator does not jump
            ap.pitch_pid.integral += self.bias / ap.pitch_pid.ki
            ap.climb_spd_pid.reset(integral=x[ix["theta_rad"]] / ap.climb_spd_pid.ki)
            p.fire("liftoff")


INITIAL_CLIMB_RATE_MAX = 1.3  # InitialClimb's autothrottle: at most this times the drawn rate


class InitialClimb(Controller):
    """V2 + the type's initial-climb additive (``initial_climb_v2_add_kt``: Airbus 10 kt, Boeing 20) to
    the acceleration height, then accelerate while still climbing (the speed target ramps up at
    1.5 kt/s, no level-off) at climb thrust, flaps up on schedule, runway heading to 400 ft then the
    route. A type whose model climbs too slowly at its takeoff throttle
    (``initial_climb_thrust_for_rate``) has an autothrottle until then that holds the flight's drawn
    initial rate of climb as an energy rate (:class:`EnergyRateThrottle`; once the rotation is over the
    pitch holds the speed), the throttle between the takeoff throttle and 1. A type with
    ``initial_climb_rotate_to_deg`` goes on rotating toward that attitude after liftoff first."""

    def enter(self, x) -> None:
        self.t_accel: float | None = None
        self.v2_mps = self.ap.v2_mps()  # at liftoff's mass
        self.v_climb_mps = self.v2_mps + self.p.prof.initial_climb_v2_add_kt * KT_MPS
        thr = self.p.takeoff_thrust_norm
        self.autothrottle = (
            EnergyRateThrottle(x, self.p.ix, thr, max(1.0, thr), thr)
            if self.p.prof.initial_climb_thrust_for_rate and thr is not None
            else None
        )
        # the drawn rate is WRAP's mean from liftoff to 1,500 ft (the acceleration height), the slow
        # first seconds of the climb included: the autothrottle aims at the height still to gain over
        # the time left, never less than the drawn rate nor more than INITIAL_CLIMB_RATE_MAX times it
        vs = self.ap.draws.initial_climb_vs_mps
        # (heights: the CG's above the ground, as tick's switch at the acceleration height)
        self.t_goal_s = self.p.t + (self.ap.tune.accel_height_m - x[self.p.ix["agl_m"]]) / vs
        self.rotate_to = self.p.prof.initial_climb_rotate_to_deg  # None once the speed loop has the pitch

    def tick(self, x) -> None:
        ap, p, ix, prof, tu = self.ap, self.p, self.p.ix, self.p.prof, self.ap.tune
        agl = x[ix["agl_m"]]
        ap.gear_up_when_climbing(x)
        target = self.v_climb_mps
        if self.autothrottle is not None and self.t_accel is None and agl <= tu.accel_height_m:
            vs = ap.draws.initial_climb_vs_mps
            togo = (tu.accel_height_m - agl) / max(self.t_goal_s - p.t, 1.0)
            ap.throttle(self.autothrottle(x, clamp(togo, vs, INITIAL_CLIMB_RATE_MAX * vs), ap.dt))
        if agl > tu.accel_height_m:
            if self.t_accel is None:
                self.t_accel = p.t
                ap.throttle(prof.climb_throttle)
                p.event("acceleration_height")
            target = min(tu.speed_limit_mps, self.v_climb_mps + 1.5 * KT_MPS * (p.t - self.t_accel))
        if self.rotate_to is not None:
            ap.theta_cmd = rate_limit(
                ap.theta_cmd, math.radians(self.rotate_to), math.radians(ROTATE_RATE_DPS) * ap.dt
            )
            ap.pitch_to(x, ap.theta_cmd)
            if ap.theta_cmd >= math.radians(self.rotate_to) - 1e-9 or x[ix["ias_mps"]] < self.v2_mps:
                self.rotate_to = None
                ap.climb_spd_pid.reset(integral=ap.theta_cmd / ap.climb_spd_pid.ki)
        else:
            # pitch command moves at most 2 deg/s here, where the speeds are low
            ap.speed_on_pitch(x, target, lo_deg=5.0, hi_deg=prof.initial_climb_pitch_max_deg, rate_dps=2.0)
        ap.retract_flaps(x, above_m=tu.accel_height_m)
        ap.lateral(x, runway_heading_below_m=400.0 * FT_M)
        if agl > tu.climb_out_m or x[ix["alt_m"]] > p.plan.cruise_alt_m - 150.0:
            ap.hand_over_to_path_loops(x, prof.climb_throttle)  # to the climb's vertical-rate mode
            p.fire("climb_out_done")
