"""One small controller per phase of the flight. Each flies its phase with the shared loops of
:class:`~flightmode.sim.flight.autopilot.Autopilot` and reports, through :meth:`Pilot.fire`, the
condition that ends it; the next phase comes from the transition table
(:data:`flightmode.sim.flight.phases.TRANSITIONS`), never from here. ``enter`` runs once, on the tick
the phase begins; ``tick`` on every control tick of the phase (from the next one). Numbers come from
the aircraft profile and its :class:`~flightmode.sim.flight.aircraft.tuning.PilotTuning`.
"""

from __future__ import annotations

import math

from flightmode.labels import ENGINES_OFF_N2_PCT
from flightmode.sim.flight.control import PID, clamp, first_order_lag, rate_limit
from flightmode.sim.flight.step_climb import STEP_MIN_CRUISE_S, STEP_VS_MPS, next_level_m
from flightmode.sim.flight.taxi_route import taxi_in_route
from flightmode.units import FPM_MPS, FT_M, G0_MPS2, KT_MPS, NM_M, SLUG_FT3_KGM3


class Controller:
    """A phase's controller. ``self.p`` is the pilot (time, events, :meth:`Pilot.fire`), ``self.ap``
    its autopilot (loops, actuators, shared navigation state)."""

    holding = False  # standing still on the brakes (the pilot then ticks at 4 Hz)

    def __init__(self, pilot):
        self.p = pilot
        self.ap = pilot.ap

    def enter(self, x) -> None:
        """Actions on the tick the phase begins."""

    def tick(self, x) -> None:
        raise NotImplementedError


class Gate(Controller):
    holding = True

    def tick(self, x) -> None:
        self.ap.brakes(1.0)
        self.ap.throttle(0.0)
        if self.p.t - self.p.t_phase >= self.p.plan.gate_wait_s:
            self.p.fire("gate_wait_over")


class EngineStart(Controller):
    """Engines started one by one, the last first: starter on; fuel on at N2 > 15 %; the starter stays
    engaged until the engine runs (releasing it earlier aborts the start)."""

    holding = True

    def enter(self, x) -> None:
        self.engine = self.p.prof.n_engines - 1
        self._start(self.engine)

    def _start(self, i: int) -> None:
        ac = self.ap.ac
        ac.set("propulsion/active_engine", i)
        if ac.get("propulsion/cutoff_cmd") < 0.5:  # fuel off for the next engine (on since the last one)
            ac.set("propulsion/cutoff_cmd", 1)
        ac.set("propulsion/starter_cmd", 1)
        self.p.event("starter", f"engine {i}")

    def tick(self, x) -> None:
        ac, i = self.ap.ac, self.engine
        if ac.get("propulsion/cutoff_cmd") > 0.5 and x[self.p.ix[f"n2_pct_{i}"]] > 15.0:
            ac.set("propulsion/cutoff_cmd", 0)
            self.p.event("fuel_on", f"engine {i}")
        elif ac.get("propulsion/cutoff_cmd") < 0.5 and ac.get(f"propulsion/engine[{i}]/set-running") > 0.5:
            ac.set("propulsion/starter_cmd", 0)
            self.p.event("engine_running", f"engine {i}")
            if i == 0:
                ac.set("propulsion/active_engine", -1)
                self.p.fire("engines_running")
            else:
                self.engine = i - 1
                self._start(self.engine)


class Pushback(Controller):
    """The tug (a body-axis force at the nose gear, a PI loop on ground speed) pushes the aircraft
    straight back from its stand (``TaxiDraws.push_straight_m``), then turns the tail so the nose
    swings 90 deg left onto the apron taxilane (turn radius = wheelbase / tan(35 deg)), slowing to a
    stop over the last of the turn (``pushback_decel_mps2``), and stops."""

    def enter(self, x) -> None:
        ix = self.p.ix
        self.heading0 = x[ix["psi_rad"]]
        self.xy0 = self.ap.origin.to_xy(x[ix["lat_deg"]], x[ix["lon_deg"]])
        self.turning = False
        self.v_tug = 0.0  # the tug's speed target (backwards)
        self.ap.brakes(0.0)
        self.ap.tug_pid.reset()

    def tick(self, x) -> None:
        ap, ix, tu = self.ap, self.p.ix, self.ap.tune
        v = ap.ground_speed_signed(x)
        turned = (x[ix["psi_rad"]] - self.heading0 + math.pi) % (2 * math.pi) - math.pi
        rx, ry = ap.origin.to_xy(x[ix["lat_deg"]], x[ix["lon_deg"]])
        radius = self.p.prof.wheelbase_m / math.tan(math.radians(35.0))
        if math.hypot(rx - self.xy0[0], ry - self.xy0[1]) >= self.p.taxi.push_straight_m:
            self.turning = True
        steering = math.radians(35.0) if self.turning else 0.0
        to_go_m = radius * max(0.0, math.radians(90.0) + turned) if self.turning else math.inf
        done = turned < -math.radians(89.0)
        # the tug starts and stops the push at pushback_decel_mps2 (no jolt)
        speed = max(0.15, min(tu.pushback_mps, math.sqrt(2.0 * tu.pushback_decel_mps2 * to_go_m)))
        self.v_tug = rate_limit(self.v_tug, 0.0 if done else speed, tu.pushback_decel_mps2 * ap.dt)
        ap.ac.set("external_reactions/pushback/magnitude", ap.tug_pid(-self.v_tug - v, ap.dt))
        ap.steer(steering if not done else 0.0)
        if done:
            ap.brakes(0.1)
            if abs(v) < 0.05:
                ap.ac.set("external_reactions/pushback/magnitude", 0.0)
                self.p.event("tug_disconnected")
                self.p.fire("tug_disconnected")


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

    @property
    def holding(self) -> bool:
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
        if abs(cross) > 30.0:
            p.fail(f"left the taxiway: {cross:.0f} m from the taxi route")
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


# The energy-rate autothrottle of Boeing's reduced go-around thrust (AircraftProfile.go_around_climb_fpm)
# and of the A320's initial climb (AircraftProfile.initial_climb_thrust_for_rate): a PI (throttle per
# m/s of energy-rate error, and per m of its integral) on the energy rate, not the rate of climb:
# thrust sets the total energy's rate d(h + V^2 / 2g)/dt = V f_path / g (f_path the specific force
# along the flight path, (T cos(alpha) - D) / m), the pitch shares it between climb and speed (it
# holds the speed): the principle of Lambregts's total energy control (AIAA paper 83-2239, 1983).
# Closed on the rate of climb instead, the two loops fought here: the pitch traded speed for climb, the
# thrust answered the climb, and a 737 pattern go-around sank again at 430 ft at 127 kt. One throttle's
# worth of thrust is about 0.3 of the weight, 20 m/s of climb at 75 m/s: a loop gain near 0.6;
# integral time 3 s. The specific force is low-passed over ENERGY_RATE_TAU_S (gusts)
ENERGY_RATE_THRUST_PI = (0.03, 0.01)
ENERGY_RATE_TAU_S = 1.0


def energy_rate_mps(x, ix) -> float:
    """The total energy's rate V f_path / g (m/s; ENERGY_RATE_THRUST_PI)."""
    alpha = x[ix["alpha_rad"]]
    f_path = x[ix["fx_mps2"]] * math.cos(alpha) + x[ix["fz_mps2"]] * math.sin(alpha)
    return x[ix["tas_mps"]] * f_path / G0_MPS2


class EnergyRateThrottle:
    """An autothrottle that holds the total energy's rate (ENERGY_RATE_THRUST_PI: its PI, and its
    low-pass over ENERGY_RATE_TAU_S), the throttle within [``lo``, ``hi``], starting from ``start``."""

    def __init__(self, x, ix, lo: float, hi: float, start: float):
        kp, ki = ENERGY_RATE_THRUST_PI
        self.ix = ix
        self.pid = PID(kp, ki, 0.0, lo, hi)
        self.pid.reset(integral=start / ki)
        self.rate_mps = energy_rate_mps(x, ix)  # low-passed

    def __call__(self, x, target_mps: float, dt_s: float) -> float:
        self.rate_mps = first_order_lag(self.rate_mps, energy_rate_mps(x, self.ix), dt_s, ENERGY_RATE_TAU_S)
        return self.pid(target_mps - self.rate_mps, dt_s)


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


# Short final (main gear below 200 ft on the localizer): the path loop may lower the nose at most
# FINAL_PITCH_MARGIN_DEG below the stabilised approach attitude, so that it cannot dive into the runway.
# That attitude is the pitch's running mean on the localizer (time constant THETA_FINAL_TAU_S). It was
# the attitude of the one tick that crossed 200 ft, less 1 deg: in gusts that tick's attitude is partly
# a gust's (a 787-8 pattern flight, seed 59, crossed at 1.9 deg after flying the glideslope at 0.5-0.9),
# and a high one pinned the nose up while the aircraft rose above the glideslope: its main gear crossed
# the threshold up to 117 ft up (the glideslope puts it at 38 ft), and the 787-8's pattern landings in
# gusts touched down past the 914 m touchdown zone in 14 / 12 / 16 of 40 (seeds 56-95 / 96-135 /
# 136-175), up to 1,839 m. Measured on seeds 56-95 with its flare from 70 ft, a 10 s mean: 12 of 40 at
# 1 deg, 2 at 2 deg (the sink's p90 4.1 -> 4.5 ft/s: the flare now begins from the glideslope), 1 at
# 3 deg (p90 5.7). At 2 deg, with the flare from 75 ft (aircraft.b787_8) and a 10 s mean: 6 / 3 / 9
# of 40; a 30 s mean, which a correction just before 200 ft (a thermal's downdraft, then its updraft:
# seed 155) lifts less: 3 / 3 / 6, touchdown sink flown minus drawn +0.74 / +0.54 / +0.78 ft/s
# (+0.66 / +0.88 / +0.79 before). The 737's pattern landings moved less (seeds 56-95: past the
# threshold median 598 -> 582 m, at most 823 -> 748 m, sink +0.31 -> +0.24 ft/s); the A320's and the
# Fokker 100's touchdown medians not at all (seeds 56-65)
THETA_FINAL_TAU_S = 30.0
FINAL_PITCH_MARGIN_DEG = 2.0


class EnRoute(Controller):
    """Climb, cruise, descent and approach: one set of loops, targets by phase and distance to go.
    The vertical target is the cruise altitude capped by the planned descent path (the glideslope
    inside 10 nm); the speed target moves at most 1 kt/s (no step at 10,000 ft or at the approach
    gates); vertical speed changes at most 0.8 m/s^2 (< 0.1 g: smooth level-offs and top of descent)."""

    def tick(self, x) -> None:
        ap, p, ix, prof = self.ap, self.p, self.p.ix, self.p.prof
        phase = p.phase
        d = ap.distance_to_go_m(x)
        h = x[ix["alt_m"]]
        if phase == "cruise":
            self._step_climb(x, d)
        h_tgt = min(ap.cruise_alt_m, ap.path_alt_m(d))
        v_new = min(
            ap.speed_target_mps(x, d, climbing=phase == "climb", on_approach_legs=phase != "climb"),
            self.speed_cap_mps(),
        )
        if ap.v_tgt is None:
            ap.v_tgt = v_new
        ap.v_tgt = rate_limit(ap.v_tgt, v_new, KT_MPS * ap.dt)
        v_tgt = ap.v_tgt
        if ap.lateral(x, may_capture=phase in ("cruise", "descent", "go_around")):
            p.fire("localizer_capture")
        if phase == "climb":
            ap.retract_flaps(x)
            if h < h_tgt - 250.0:
                self._climb(x, v_tgt, h_tgt - h)
                return
            ap.spd_pid.hi = 1.0
            p.fire("level")
            # the weight the first cruise level is taken as optimum for (sim.flight.step_climb)
            self.ref = (ap.ac.get("inertia/weight-lbs"), ap.cruise_alt_m)
        if p.phase == "cruise" and h_tgt < ap.cruise_alt_m - 1.0:
            p.fire("top_of_descent")
        if p.phase != "climb":
            # wherever the speed target follows the approach gates (phase != climb above), the flaps
            # and gear follow them too: a pattern, or a short hop, may reach the 20 nm gate still in
            # cruise, and slowing there clean flew the 737 to a stall (pattern at 0.78 takeoff thrust)
            ap.configure_approach(d, x[ix["ias_mps"]])
        # vertical: altitude error -> vertical speed -> flight-path angle -> pitch
        gs = ap.gs(x)
        on_path = h_tgt < ap.cruise_alt_m
        slope = (ap.path_alt_m(d) - ap.path_alt_m(d - 100.0)) / 100.0 if on_path else 0.0
        vs_ff = -gs * slope
        if ap.loc_mode:
            vs_cmd = clamp(vs_ff + 0.1 * (h_tgt - h), -8.0, 3.0)
        else:
            vs_max = STEP_VS_MPS if phase == "cruise" else 10.0  # a step climb at cruise thrust
            vs_cmd = clamp(vs_ff + 0.05 * (h_tgt - h), -15.0, vs_max)
        if ap.vs_cmd is None:
            ap.vs_cmd = -x[ix["v_down_mps"]]
        ap.vs_cmd = rate_limit(ap.vs_cmd, vs_cmd, 0.8 * ap.dt)
        lo_deg = -8.0
        mg = x[ix["agl_m"]] - prof.cg_height_m
        if ap.loc_mode and ap.theta_final is None:  # the approach's mean attitude, until it is held
            th = math.degrees(x[ix["theta_rad"]])
            ap.theta_mean = (
                th if ap.theta_mean is None else first_order_lag(ap.theta_mean, th, ap.dt, THETA_FINAL_TAU_S)
            )
        if ap.loc_mode and mg < 200 * FT_M:
            # short final: no diving into ground effect below the stabilised attitude (THETA_FINAL_TAU_S)
            if ap.theta_final is None:
                ap.theta_final = ap.theta_mean
            lo_deg = ap.theta_final - FINAL_PITCH_MARGIN_DEG
        ap.path_to(x, ap.vs_cmd, lo_deg, 15.0, rate_dps=1.5 if ap.loc_mode else 1.0)
        # speed: throttle, speedbrake when idle is not enough
        err = v_tgt - x[ix["ias_mps"]]
        thr = ap.spd_pid(err, ap.dt)
        ap.throttle_smooth(thr)
        agl = x[ix["agl_m"]]
        sb = clamp((-err - 4.0) / 10.0, 0.0, 1.0) if thr <= 0.01 and agl > 1000 * FT_M else 0.0
        ap.ac.set("fcs/speedbrake-cmd-norm", sb)
        if ap.loc_mode and (
            agl - prof.cg_height_m < flare_start_height_m(ap, x)
            or -d > FLOAT_LIMIT_FRACTION * ap.dest.rwy.length_m
        ):
            # over the runway's second half still above the flare height (a float in gusts on the
            # approach's speed): the flare's first tick goes around (Flare._go_around)
            p.fire("flare_height")

    def speed_cap_mps(self) -> float:
        """A ceiling on the speed target beyond the route's (none en route; :class:`GoAround`'s circuit)."""
        return math.inf

    ref: tuple[float, float] | None = None  # (weight lbs, altitude m) at the first level-off
    next_check_s = 0.0

    def _step_climb(self, x, d_m: float) -> None:
        """Raise the cruise level by one step when it is due (:mod:`flightmode.sim.flight.step_climb`)
        and the flight would stay at the new level for ``STEP_MIN_CRUISE_S`` before its descent;
        checked every ``STEP_CHECK_S``."""
        ap, p = self.ap, self.p
        if self.ref is None or p.t < self.next_check_s:
            return
        self.next_check_s = p.t + STEP_CHECK_S
        new = next_level_m(
            ap.cruise_alt_m,
            ap.ac.get("inertia/weight-lbs"),
            self.ref[0],
            self.ref[1],
            p.prof.ceiling_ft * FT_M,
        )
        if new is None or abs(x[p.ix["alt_m"]] - ap.cruise_alt_m) > 30.0:
            return
        if ap.path_alt_m(d_m - ap.gs(x) * STEP_MIN_CRUISE_S) < new:
            return  # too close to the top of descent
        p.event("step_climb", f"{ap.cruise_alt_m / FT_M:.0f} ft -> {new / FT_M:.0f} ft")
        ap.cruise_alt_m = new

    def _climb(self, x, v_tgt: float, to_go_m: float) -> None:
        """The climb as airline pilots fly it on the FMS: the vertical rate of this flight's draw for
        the altitude band (OpenAP WRAP), the speed on the throttle up to climb thrust; when climb
        thrust cannot hold the speed at that rate (the acceleration at 10,000 ft, a heavy aircraft
        high up), the rate gives way, as an FMS's speed protection does."""
        ap, ix, prof = self.ap, self.p.ix, self.p.prof
        ap.spd_pid.hi = prof.climb_throttle
        err = v_tgt - x[ix["ias_mps"]]
        thr = ap.spd_pid(err, ap.dt)
        ap.throttle_smooth(thr)
        vs = ap.climb_vs_mps(x[ix["alt_m"]])
        deficit = err - 5.0 * KT_MPS  # slower than the target by more than 5 kt
        if deficit > 0.0 and thr >= prof.climb_throttle - 0.01:
            vs *= clamp(1.0 - deficit / (10.0 * KT_MPS), 0.2, 1.0)
        vs = min(vs, 0.05 * to_go_m + 1.0)  # level off smoothly (within 250 m the cruise takes over)
        if ap.vs_cmd is None:
            ap.vs_cmd = -x[ix["v_down_mps"]]
        ap.vs_cmd = rate_limit(ap.vs_cmd, vs, 0.8 * ap.dt)
        ap.path_to(x, ap.vs_cmd, 0.0, 15.0, rate_dps=1.0)
        ap.ac.set("fcs/speedbrake-cmd-norm", 0.0)


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
            p.event("touchdown", f"sink {sink / FT_M * 60:.0f} fpm at {rx:.0f} m")
            if sink > ap.tune.max_touchdown_sink_mps:
                p.fail(
                    f"hard landing: touchdown sink rate {sink / FT_M:.1f} ft/s exceeds "
                    f"{ap.tune.max_touchdown_sink_mps / FT_M:.0f} ft/s, the gear's reserve-energy sink "
                    "(14 CFR 25.723(b))"
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
                f"balloon: the flare climbed to {gear_h_m / FT_M:.0f} ft above the runway (flare height "
                f"{prof.flare_height_ft:.0f} ft)"
            )
            if self.approaches >= MAX_APPROACHES:
                p.fail(f"{cause} on approach {self.approaches}; no diversion is flown after {MAX_APPROACHES}")
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


# rejected landings (Flare._go_around, GoAround). Airline procedures go around when the touchdown
# cannot be made inside the touchdown zone (Runway.touchdown_zone_end_m: 3,000 ft on a long runway).
# The pilot here goes around only from a float over the runway's second half: the 787-8's flare (from
# 80 ft, 11 s) touches down past 3,000 ft on 4-8 of 20 route landings (fuel floors 40-50 t; median
# 690-780 m past the threshold), and going around on each would make go-arounds about a hundred times
# as frequent as the 1-3 per 1,000 approaches of real operations (Go-around Safety Forum, Brussels,
# 2013, finding F1); validate reports those long touchdowns against the touchdown zone instead
FLOAT_LIMIT_FRACTION = 0.5
MAX_APPROACHES = 3  # approaches flown before a balloon fails the flight and a float lands long
# the circuit after a go-around: a left-hand circuit (ICAO's standard direction) through the pattern
# built-in's corners, in the destination runway's frame (nm past the threshold, nm right of the line),
# then the localizer from a fix GO_AROUND_FIX_NM out (its glideslope height, about 2,600 ft, is the
# circuit's altitude)
CIRCUIT_CORNERS_NM = ((3.0, -3.0), (-5.0, -3.0))
GO_AROUND_FIX_NM = 8.0
# the go-around's rotation: towards 15 deg at 2-3 deg/s (Boeing 737 FCTM, go-around and missed approach;
# Airbus's SRS commands up to 17.5 deg)
GO_AROUND_PITCH_DEG = 15.0
GO_AROUND_PITCH_RATE_DPS = 3.0


class GoAround(EnRoute):
    """A go-around from the flare and the circuit back to the localizer. First, as the go-around modes
    of airliner flight directors fly it (Airbus SRS, Boeing TO/GA): climb thrust at once, the pitch
    holding the speed of the moment (the approach speed at least) up to 15 deg, flaps one setting up,
    gear up with a positive climb, the runway's heading to 400 ft. A Boeing's autothrottle holds its
    type's rate of climb from the call on, as the first push of TO/GA does, climb thrust its ceiling
    (AircraftProfile.go_around_climb_fpm, ENERGY_RATE_THRUST_PI). From the acceleration height on,
    the en-route loops fly the circuit (:data:`CIRCUIT_CORNERS_NM`) at its altitude, configured: the
    speed capped at the approach schedule's for the flaps set, which the approach gates extend again;
    the localizer is captured at the circuit's fix as on any approach."""

    def enter(self, x) -> None:
        ap, ix, prof = self.ap, self.p.ix, self.p.prof
        self.srs = True
        self.rotating = True  # pitching up to GO_AROUND_PITCH_DEG (then the pitch holds the speed)
        ap.loc_mode = False
        ap.theta_final = None
        ap.theta_mean = None
        ap.set_route([ap.dest.to_latlon(a * NM_M, b * NM_M) for a, b in CIRCUIT_CORNERS_NM], GO_AROUND_FIX_NM)
        ap.cruise_alt_m = ap.path_alt_m(GO_AROUND_FIX_NM * NM_M)  # the glideslope's height at the fix
        self.v_srs = max(ap.vapp_mps(), x[ix["ias_mps"]])
        ap.thr = prof.climb_throttle
        ap.throttle(ap.thr)
        # Boeing's reduced go-around thrust: from climb thrust, adjusted to hold the type's rate of climb
        self.vs_target_mps = None if prof.go_around_climb_fpm is None else prof.go_around_climb_fpm * FPM_MPS
        self.autothrottle = EnergyRateThrottle(x, ix, 0.0, prof.climb_throttle, prof.climb_throttle)
        ap.ac.set("fcs/speedbrake-cmd-norm", 0.0)
        settings = sorted({s.flaps_norm for s in prof.approach_steps if s.flaps_norm < ap.flaps})
        if settings:
            ap.set_flaps(settings[-1])
        ap.theta_cmd = x[ix["theta_rad"]]
        ap.climb_spd_pid.reset(integral=x[ix["theta_rad"]] / ap.climb_spd_pid.ki)

    def speed_cap_mps(self) -> float:
        """The approach schedule's speed for the flaps set: the fastest step whose flaps are at least
        these (Autopilot.step_speed_mps: the last step's is the final approach speed for the mass), as
        on any approach (the circuit is flown configured; it once flew the 787-8's 20/35 flaps at
        220 kt, and, capped at the last step's nominal 145 kt with landing flaps, under its mass-scaled
        Vapp, a 787-8 stalled in the turn to final)."""
        ap, steps = self.ap, self.p.prof.approach_steps
        return max(
            (ap.step_speed_mps(s) for s in steps if s.flaps_norm >= ap.flaps - 1e-9),
            default=steps[0].speed_kt * KT_MPS,
        )

    def tick(self, x) -> None:
        ap, p, ix = self.ap, self.p, self.p.ix
        agl = x[ix["agl_m"]]
        if self.srs:
            ap.gear_up_when_climbing(x)
            if self.vs_target_mps is not None:
                ap.thr = self.autothrottle(x, self.vs_target_mps, ap.dt)
                ap.throttle(ap.thr)
            if self.rotating:
                # rotate at once towards the go-around attitude: waiting for the speed to ask for it
                # sank a 737 pattern flight from 57 ft onto the runway at 2.5 g
                ap.theta_cmd = rate_limit(
                    ap.theta_cmd,
                    math.radians(GO_AROUND_PITCH_DEG),
                    math.radians(GO_AROUND_PITCH_RATE_DPS) * ap.dt,
                )
                ap.pitch_to(x, ap.theta_cmd)
                if ap.theta_cmd >= math.radians(GO_AROUND_PITCH_DEG) - 1e-9:
                    self.rotating = False
                    ap.climb_spd_pid.reset(integral=ap.theta_cmd / ap.climb_spd_pid.ki)
            else:
                ap.speed_on_pitch(x, self.v_srs, lo_deg=0.0, hi_deg=GO_AROUND_PITCH_DEG, rate_dps=2.0)
            if agl < 400.0 * FT_M:
                ap.heading_to(x, ap.dest.heading_rad, 5.0)
            else:
                ap.lateral(x)
            if agl < ap.tune.accel_height_m:
                return
            # to the en-route loops, as after the initial climb
            self.srs = False
            p.event("acceleration_height")
            ap.hand_over_to_path_loops(x, ap.thr)
            ap.spd_pid.hi = 1.0
            ap.v_tgt = x[ix["ias_mps"]]  # the target then moves at 1 kt/s (EnRoute)
        super().tick(x)


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


STEP_CHECK_S = 60.0  # how often the cruise checks whether a step climb is due

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


class Shutdown(Controller):
    """Fuel cut off at the stand. The parking brake is set gradually from the taxi brake's hold
    (``PARKING_BRAKE_RATE_PER_S``): set at once, JSBSim's gear friction at rest (a stiff spring)
    kicked the 737 with 0.35 g fore-aft and could leave it rocking on its gear."""

    def enter(self, x) -> None:
        ap = self.ap
        ap.parking_brake = ap.taxi_brake
        ap.brakes(ap.parking_brake)
        ap.throttle(0.0)
        ap.steer(0.0)
        ap.ac.set("propulsion/active_engine", -1)
        ap.ac.set("propulsion/cutoff_cmd", 1)

    def tick(self, x) -> None:
        self.ap.set_parking_brake(PARKING_BRAKE_RATE_PER_S)
        # engines off: every N2 below 5 % after fuel cut-off (the end of the seed's flight time)
        if all(x[self.p.ix[f"n2_pct_{i}"]] < ENGINES_OFF_N2_PCT for i in range(self.p.prof.n_engines)):
            self.p.t_engines_off = self.p.t
            self.p.event("engines_off")
            self.p.fire("engines_off")


PARKING_BRAKE_RATE_PER_S = 0.1


class Parked(Controller):
    holding = True

    def tick(self, x) -> None:
        self.ap.set_parking_brake(PARKING_BRAKE_RATE_PER_S)
        if self.p.t - self.p.t_engines_off >= self.p.plan.post_shutdown_s:
            self.p.fire("recording_over")


CONTROLLERS: dict[str, type[Controller]] = {
    "gate": Gate,
    "engine_start": EngineStart,
    "pushback": Pushback,
    "taxi_out": TaxiOut,
    "takeoff_roll": TakeoffRoll,
    "initial_climb": InitialClimb,
    "climb": EnRoute,
    "cruise": EnRoute,
    "descent": EnRoute,
    "approach": EnRoute,
    "flare": Flare,
    "go_around": GoAround,
    "rollout": Rollout,
    "taxi_in": TaxiIn,
    "shutdown": Shutdown,
    "parked": Parked,
}
