"""The flare, its two guidance laws and their constants, and the rejected landing's decision (a
balloon or a float over the runway's second half goes around: :mod:`flightmode.sim.flight.pilot.go_around`).
Sources: Blakelock, *Automatic Control of Aircraft and Missiles* (1991), NASA TN D-6544 (the flare laws),
Lee 1976 (the time-to-contact start), each cited where it is used."""

from __future__ import annotations

import math

from flightmode.sim.flight.pilot.control import clamp
from flightmode.sim.flight.pilot.controller import Controller
from flightmode.units import FT_M, G0_MPS2

# rejected landings (Flare._go_around, GoAround). Airline procedures go around when the touchdown
# cannot be made inside the touchdown zone (Runway.touchdown_zone_end_m: 3,000 ft on a long runway).
# The pilot here goes around only from a float over the runway's second half: the 787-8's flare (from
# 80 ft, 11 s) touches down past 3,000 ft on 4-8 of 20 route landings (fuel floors 40-50 t; median
# 690-780 m past the threshold), and going around on each would make go-arounds about a hundred times
# as frequent as the 1-3 per 1,000 approaches of real operations (Go-around Safety Forum, Brussels,
# 2013, finding F1); validate reports those long touchdowns against the touchdown zone instead
FLOAT_LIMIT_FRACTION = 0.5
MAX_APPROACHES = 3  # approaches flown before a balloon fails the flight and a float lands long


def flare_start_height_m(ap, x) -> float:
    """The main gear's height at which the flare begins: the type's flare height, or, for a type that
    flares at a time to contact (``flare_at_time_to_contact``) and descends more steeply than the
    glideslope (its sink over its ground speed), higher: at the time to contact the flare height gives on
    the glideslope at this ground speed, at most FLARE_START_MAX_FACTOR times the flare height (under
    the balloon check's FLARE_BALLOON_FACTOR, which a flare begun higher would trip on its first tick).
    A pilot judges the flare by the closing of the runway, not by a height: the tau hypothesis (Lee, "A
    theory of visual control of braking based on information about time-to-collision", Perception 5,
    1976) has the braking of an approach to a surface begin at a constant time to contact."""
    prof = ap.prof
    h = prof.flare_height_ft * FT_M
    if not prof.flare_at_time_to_contact:
        return h
    glide_sink = max(ap.gs(x), 1.0) * math.tan(math.radians(ap.plan.glideslope_deg))
    return clamp(h / glide_sink * x[ap.ix["v_down_mps"]], h, FLARE_START_MAX_FACTOR * h)


class Flare(Controller):
    """The flare: the pitch attitude is moved so that the sink rate meets the flight's drawn touchdown
    sink v_td as the main gear meets the runway, by one of two guidance laws (the type's
    ``flare_law``):

    - ``"constant_deceleration"``: at every tick, the upward acceleration that would bring the sink
      rate v (main-gear height h) to v_td exactly at h = 0 is a_req = (v^2 - v_td^2) / (2 h), the
      kinematics of a uniform deceleration. The pitch attitude is moved at a rate proportional to the
      error between a_req and the measured vertical acceleration (from the specific force), as a
      pilot eases the stick back while watching the sink rate. The guidance corrects itself: a flare
      begun late asks for more, one overdone asks for less (a float above the aim height is allowed a
      gentle push, never a dive; below it, only a balloon is). Stock autoland flare laws are of this
      kinematic kind (e.g. NASA TN D-6544, exponential and constant-deceleration flare paths).
    - ``"exponential"``: the classic automatic flare (Blakelock, *Automatic Control of Aircraft and
      Missiles*, 2nd ed. 1991, automatic flare control): the sink rate is commanded along the
      exponential path v_cmd = v_td + h / tau, which meets the runway at v_td; tau is set at the flare
      height so that the command starts at the sink rate the aircraft has there
      (:func:`exponential_flare_tau_s`). The pitch attitude is the approach attitude plus the change of
      flight-path angle the command asks for, (v_0 - v_cmd) / V, plus a proportional-integral
      correction on the sink-rate error. Its gain does not grow as h shrinks, as a_req's does: on the
      737 the constant-deceleration law overshot into balloons near 4 ft and then dropped (24 pattern
      landings, seeds 16-39: touchdown sink median / p90 / max 3.63 / 5.35 / 6.37 ft/s, 1.87 ft/s over
      the drawn targets; 1,135 m past the threshold at worst); with this law 3.08 / 3.83 / 5.05 ft/s,
      0.74 ft/s over, 799 m at worst; hard landings (7-9.5 ft/s targets) 0.41 ft/s over, 8 of 8 under
      the 10 ft/s limit. The 787-8 flies it too, from 80 ft and with its time constant unbounded
      in practice (its profile's comment has the measurements): under the constant deceleration it
      ballooned and floated past 900 m in 16 of 23 route landings and one flare came in at 10.6 ft/s.
      On the A320 the same law flared too little (its flare is
      shorter and its lift answers the attitude more slowly: median 6.5 ft/s on 16 landings, against
      3.7 with the constant deceleration), so each type keeps the law that lands it best.
      The thrust at idle, the speed bleeds through the flare (8-10 kt), and the wing holds its lift
      1/2 rho V^2 S CL_alpha (alpha - alpha_0L) only if alpha - alpha_0L grows as (V_0 / V)^2 (V_0:
      the true airspeed at the flare height). The type's ``flare_lift_attitude_rad`` A adds
      A ((V_0 / V)^2 - 1) to the attitude goal for it, ahead of the sink-rate loop, whose integral is
      too slow for the last seconds; a pilot raises the nose through the flare for the same reason.
      A is at most alpha - alpha_0L = CL / CL_alpha at the flare height; the sink-rate loop does part
      of the work, so A is chosen per type on still-air landings (aircraft profiles).
      Without it the 787-8's attitude stood still over the last 3 s while it lost 8 kt, and its sink,
      arrested near the target 5 ft up, rose to about 2.9 ft/s whatever was drawn (still air).
    """

    approaches = 0  # approaches flown to the flare height, this one included (one Flare per flight)

    def enter(self, x) -> None:
        ix, prof = self.p.ix, self.p.prof
        self.theta_cmd = self.theta_0 = x[ix["theta_rad"]]
        self.sink_0 = x[ix["v_down_mps"]]
        self.tau_s = exponential_flare_tau_s(
            x[ix["agl_m"]] - prof.cg_height_m,
            self.sink_0,
            self.ap.draws.touchdown_sink_mps,
            prof.flare_tau_max_s,
        )
        self.sink_err_int = 0.0  # the exponential law's integral of the sink-rate error (m)
        # the exponential law's speed at the flare height
        self.v_0 = max(x[ix["tas_mps"]], FLARE_EXP_MIN_TAS_MPS)
        self.retarded = False  # the thrust pulled to idle at the type's retard height: for good
        self.approaches += 1
        self.float_limit_m = FLOAT_LIMIT_FRACTION * self.ap.dest.rwy.length_m

    def _rate_decel(self, x, gear_h_m: float, sink: float, target: float) -> float:
        """The constant-deceleration law: the pitch rate (rad/s) it asks for. The lag between the
        attitude and the sink rate is met two ways, each set by the type's profile: the guidance aims
        to reach the touchdown sink ``flare_aim_m`` above the runway, and, with ``flare_predict_s``
        T > 0, it steers on the state T seconds ahead if the upward acceleration a the aircraft has
        now were kept: sink v - a T at height h - v T + a T^2 / 2 (a predictor of the simplest kind:
        the deceleration already under way is not asked for a second time). Below the aim height it
        pulls against a sink above the target and otherwise holds the attitude, lowering the nose only
        when the aircraft climbs (a balloon), as a pilot holds the flare attitude in the last feet."""
        ix, prof = self.p.ix, self.p.prof
        # vertical acceleration (up) from the specific force: a = -f_z cos(theta) - g (near wings level)
        a_up = -x[ix["fz_mps2"]] * math.cos(x[ix["theta_rad"]]) - G0_MPS2
        h_m = gear_h_m - prof.flare_aim_m
        if prof.flare_predict_s > 0.0:
            lead = prof.flare_predict_s
            h_m -= sink * lead - 0.5 * a_up * lead * lead
            sink -= a_up * lead
        lowest = -FLARE_PITCH_DOWN_RADPS
        if h_m > FLARE_MIN_H_M:
            a_req = (sink * abs(sink) - target * target) / (2.0 * h_m)
        else:  # at the aim height: limit the sink to the target until the wheels meet the runway
            a_req = FLARE_HOLD_PER_S * (sink - target)
            if sink >= 0.0:
                # and never lower the nose there unless the aircraft climbs (a balloon): an A320 in still
                # air that had arrested its sink at 3 ft was pushed to 3.4 ft/s by the loop chasing its
                # drawn 1.5 ft/s, with the speed decaying at idle (pattern seed 0; now 1.0 ft/s:
                # test_the_a320s_flare_lands_where_it_aims_in_still_air). Shared by the Fokker 100,
                # whose flare reaches this regime only in its last foot (pattern landings within 0.01 ft/s)
                lowest = 0.0
        a_req = clamp(a_req, -FLARE_MAX_PUSH_MPS2, FLARE_MAX_UP_MPS2)
        return clamp(prof.flare_accel_gain * FLARE_PITCH_GAIN * (a_req - a_up), lowest, FLARE_PITCH_UP_RADPS)

    def _rate_exponential(self, x, gear_h_m: float, sink: float, target: float) -> float:
        """The exponential law: the pitch rate (rad/s) that moves the attitude command towards its
        goal, within the flare's pitch-rate limits."""
        ix, prof, dt = self.p.ix, self.p.prof, self.ap.dt
        sink_cmd = exponential_flare_sink_cmd_mps(gear_h_m, target, self.tau_s, self.sink_0)
        v = max(x[ix["tas_mps"]], FLARE_EXP_MIN_TAS_MPS)
        kp = prof.flare_path_gain / v  # rad per m/s of sink-rate error
        ki = FLARE_EXP_INTEGRAL_PER_S * kp
        err = sink - sink_cmd
        lim = FLARE_EXP_INTEGRAL_MAX_RAD / ki  # anti-windup: the integral moves the attitude 3 deg at most
        self.sink_err_int = clamp(self.sink_err_int + err * dt, -lim, lim)
        goal = self.theta_0 + (self.sink_0 - sink_cmd) / v + kp * err + ki * self.sink_err_int
        # the lift 1/2 rho V^2 S CL_alpha (alpha - alpha_0L) holds as V bleeds only if alpha - alpha_0L grows
        # as (V_0 / V)^2: the attitude for it is given ahead, not left to the slow integral
        goal += prof.flare_lift_attitude_rad * ((self.v_0 / v) ** 2 - 1.0)
        return clamp((goal - self.theta_cmd) / dt, -FLARE_PITCH_DOWN_RADPS, FLARE_PITCH_UP_RADPS)

    def tick(self, x) -> None:
        ap, p, ix, prof = self.ap, self.p, self.p.ix, self.p.prof
        sink = x[ix["v_down_mps"]]
        target = ap.draws.touchdown_sink_mps
        gear_h_m = x[ix["agl_m"]] - prof.cg_height_m  # the main gear's height above the runway
        rx, ry = ap.dest.to_xy(x[ix["lat_deg"]], x[ix["lon_deg"]])
        if self._go_around(x, gear_h_m, rx):
            return
        if prof.flare_settle_from_m is not None and rx > prof.flare_settle_from_m:
            target = max(target, prof.flare_settle_sink_mps)  # a float let settle (the type's profile)
        if prof.flare_law == "exponential":
            rate = self._rate_exponential(x, gear_h_m, sink, target)
        else:
            rate = self._rate_decel(x, gear_h_m, sink, target)
        if math.degrees(x[ix["alpha_rad"]]) > prof.alpha_stall_deg - FLARE_ALPHA_MARGIN_DEG:
            rate = min(rate, 0.0)  # a float that bleeds speed: never pull towards the stall
        lo = math.radians(-3.0 if ap.theta_final is None else ap.theta_final - 1.0)
        self.theta_cmd = clamp(self.theta_cmd + rate * ap.dt, lo, math.radians(12.0))
        ap.theta_cmd = self.theta_cmd
        # a firmer attitude loop than in flight (the flare is seconds long; the cruise loop's soft
        # gain lags it by degrees)
        ap.pitch_to(x, self.theta_cmd, bias=prof.flare_pitch_kp * (self.theta_cmd - x[ix["theta_rad"]]))
        # thrust to idle at the type's "retard" height, and kept there: a flare that floats back above
        # it does not take the thrust back (an A320 pattern flight in a 10 m/s wind, seed 0, floated
        # about the 10 ft retard height with the speed loop's 0.7 throttle, rose and climbed away in
        # its flare)
        self.retarded = self.retarded or gear_h_m < prof.retard_height_ft * FT_M
        ap.throttle_smooth(0.0 if self.retarded else ap.spd_pid(ap.vapp_mps() - x[ix["ias_mps"]], ap.dt))
        ap.track_centreline(x, rx, ry, FLARE_MAX_BANK_DEG)
        if x[ix["wow"]] > 0.5:
            # the sink at the last step before contact (Pilot.contact_sink_mps), not this tick's: up to
            # three steps after it the struts have already slowed the sink (a touchdown recorded at
            # 12.20 ft/s was checked under 12 and landed)
            sink = p.contact_sink_mps()
            p.event("touchdown", f"sink {sink / FT_M * 60:.0f} fpm at {rx:.0f} m")
            tdz_m = ap.dest.rwy.touchdown_zone_end_m
            if rx > tdz_m:
                # a float past the touchdown zone: landed, not failed (FLOAT_LIMIT_FRACTION), but flagged
                # in the flight's events (docs/failures.md; the 787-8 on some routes)
                p.event(
                    "long_landing",
                    f"touchdown {rx:.0f} m past the threshold, beyond the touchdown zone's {tdz_m:.0f} m",
                )
            if sink > ap.tune.max_touchdown_sink_mps:
                p.fail(
                    f"hard landing: touchdown sink rate {sink / FT_M:.1f} ft/s exceeds "
                    f"{ap.tune.max_touchdown_sink_mps / FT_M:.0f} ft/s, the gear's reserve-energy sink "
                    "(14 CFR 25.723(b))",
                    kind="hard_landing",
                    quantity="touchdown sink rate (ft/s)",
                    value=sink / FT_M,
                    limit=ap.tune.max_touchdown_sink_mps / FT_M,
                )
            p.fire("touchdown")

    def _go_around(self, x, gear_h_m: float, rx_m: float) -> bool:
        """Go around (True: the phase has changed) when the scenario orders it (on the flare's first
        tick), when the flare balloons (FLARE_BALLOON_FACTOR) or when it floats over the runway's second
        half (FLOAT_LIMIT_FRACTION; rejected landings: a crew goes around rather than land long). On
        approach MAX_APPROACHES a balloon fails the flight (a crew would divert; none is flown) and a
        float lands long."""
        p, prof = self.p, self.p.prof
        if self.approaches <= p.plan.go_arounds:
            cause = f"ordered ({self.approaches} of {p.plan.go_arounds})"
        elif gear_h_m > FLARE_BALLOON_FACTOR * prof.flare_height_ft * FT_M:
            # a 787-8 pattern flight in a 27 kt wind flown with Boeing's wind additive (165 kt on
            # approach) climbed to 570 ft in its flare within a minute
            cause = (
                f"balloon: the flare climbed to {gear_h_m / FT_M:.0f} ft above the runway, over "
                f"{FLARE_BALLOON_FACTOR * prof.flare_height_ft:.0f} ft ({FLARE_BALLOON_FACTOR:g} x the flare "
                f"height {prof.flare_height_ft:.0f} ft)"
            )
            if self.approaches >= MAX_APPROACHES:
                p.fail(
                    f"{cause} on approach {self.approaches}; no diversion is flown after {MAX_APPROACHES}",
                    kind="balloon_last_approach",
                    quantity="main gear height in the flare (ft)",
                    value=gear_h_m / FT_M,
                    limit=FLARE_BALLOON_FACTOR * prof.flare_height_ft,
                )
        elif rx_m > self.float_limit_m and x[p.ix["wow"]] < 0.5 and self.approaches < MAX_APPROACHES:
            cause = (
                f"long flare: still airborne {rx_m:.0f} m past the threshold, over the runway's second half "
                f"({self.float_limit_m:.0f} m)"
            )
        else:
            return False
        p.event("go_around_call", cause)
        p.fire("go_around")
        return True


def exponential_flare_tau_s(
    gear_height_m: float, sink_mps: float, touchdown_sink_mps: float, tau_max_s: float
) -> float:
    """The exponential flare's time constant (s), set at the flare height: the one whose command
    v_td + h / tau equals the sink rate there, so the flare begins without a jump in the command,
    within FLARE_TAU_MIN_S-``tau_max_s`` (the type's ``flare_tau_max_s``; a flare entered at or below
    the touchdown sink: the longest)."""
    excess = sink_mps - touchdown_sink_mps
    if excess <= 0.0:
        return tau_max_s
    return clamp(max(gear_height_m, 0.0) / excess, FLARE_TAU_MIN_S, tau_max_s)


def exponential_flare_sink_cmd_mps(
    gear_height_m: float, touchdown_sink_mps: float, tau_s: float, entry_sink_mps: float
) -> float:
    """The exponential flare's sink-rate command (m/s, down) at main-gear height ``gear_height_m``:
    dh/dt = -(h / tau + v_td), whose path meets the runway at the touchdown sink v_td (Blakelock),
    never more than the sink at the flare height (``entry_sink_mps``): a firm or hard landing's path,
    whose tau is at its longest, would otherwise begin by asking for more sink than the approach's,
    and the push over the runway ended over the 10 ft/s limit (2 of 8 hard pattern landings of the 737)."""
    return min(touchdown_sink_mps + max(gear_height_m, 0.0) / tau_s, max(entry_sink_mps, touchdown_sink_mps))


# the flare guidance (Flare): pitch rate (rad/s) per m/s^2 of missing upward acceleration. An airliner
# on approach gains about 4-5 g of load factor per radian of angle of attack, so this closes the
# acceleration loop near 2 rad/s. Chosen over 0.7 rad/s by flying both on the A320 and 737 in gusts,
# 6 seeds each: at 0.7 the A320's flare lagged into 8-10 ft/s touchdowns (2.3 g), at 2.1 its sinks
# fell to 1.7-6 ft/s, the 737's about the same
FLARE_PITCH_GAIN = 2.1 / (4.5 * G0_MPS2)
FLARE_ALPHA_MARGIN_DEG = 3.0  # the flare stops pitching up this close to the type's stall angle
FLARE_MAX_UP_MPS2 = 0.25 * G0_MPS2  # a flare pulls at most a quarter g
FLARE_MAX_PUSH_MPS2 = 0.03 * G0_MPS2  # and pushes gently when floating (below the aim: in a balloon)
FLARE_MIN_H_M = 0.3  # the guidance's height floor (a_req stays finite at contact)
FLARE_HOLD_PER_S = 1.0  # below the aim height: upward acceleration per m/s of sink above the target
FLARE_PITCH_UP_RADPS = math.radians(3.0)  # the flare's attitude command moves at most this fast up
FLARE_PITCH_DOWN_RADPS = math.radians(2.0)  # and down
# the exponential flare (Flare): its time constant's lower bound (a 40-80 ft flare height and 8-12 ft/s
# of sink above the target give 3-9 s; the upper bound is the type's flare_tau_max_s); the integral's
# rate per second relative to the proportional gain (the profile's flare_path_gain) and its largest
# share of the attitude. Chosen on 16 pattern landings of the
# 737 (seeds 0-15) among proportional gains 1.0-2.5 and integral rates 0.1-0.6 /s: a gain of 2.5, or an
# integral rate of 0.6, oscillated into 7-9 ft/s touchdowns (three of them over the 10 ft/s limit);
# 1.0-2.0 with 0.1-0.15 gave medians of 2.2-2.5 ft/s and at most 4.0-5.2 ft/s
FLARE_TAU_MIN_S = 1.5
FLARE_EXP_INTEGRAL_PER_S = 0.15
FLARE_EXP_INTEGRAL_MAX_RAD = math.radians(3.0)
FLARE_EXP_MIN_TAS_MPS = 30.0  # the exponential law's airspeed floor (its gains and lift ratio divide by it)
FLARE_BALLOON_FACTOR = 2.0  # a flare that climbs above twice its height is a balloon (Flare._go_around)
FLARE_START_MAX_FACTOR = 1.5  # a steep approach's flare begins at most this many flare heights up
# the flare's bank limit (deg): wings nearly level at touchdown (its value before the track law too)
FLARE_MAX_BANK_DEG = 5.0
