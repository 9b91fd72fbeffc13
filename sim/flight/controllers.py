"""One small controller per phase of the flight. Each flies its phase with the shared loops of
:class:`~flightmode.sim.flight.autopilot.Autopilot` and reports, through :meth:`Pilot.fire`, the
condition that ends it; the next phase comes from the transition table
(:data:`flightmode.sim.flight.phases.TRANSITIONS`), never from here. ``enter`` runs once, on the tick
the phase begins; ``tick`` on every control tick of the phase (from the next one). Numbers come from
the aircraft profile and its :class:`~flightmode.sim.flight.aircraft_profiles.PilotTuning`.
"""

from __future__ import annotations

import math

from flightmode.sim.flight.control import clamp, rate_limit
from flightmode.sim.flight.taxi_route import taxi_in_path, taxi_out_path
from flightmode.units import FT_M, G0_MPS2, KT_MPS


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
    """The tug (a body-axis force at the nose gear, a PI loop on ground speed) pushes straight back
    across the apron, then turns the tail so the nose swings 90 deg left onto the taxiway (turn radius
    = wheelbase / tan(35 deg)), and stops."""

    def enter(self, x) -> None:
        self.heading0 = x[self.p.ix["psi_rad"]]
        self.turning = False
        self.ap.brakes(0.0)
        self.ap.tug_pid.reset()

    def tick(self, x) -> None:
        ap, ix = self.ap, self.p.ix
        v = ap.ground_speed_signed(x)
        turned = (x[ix["psi_rad"]] - self.heading0 + math.pi) % (2 * math.pi) - math.pi
        rx, ry = ap.origin.to_xy(x[ix["lat_deg"]], x[ix["lon_deg"]])
        radius = self.p.prof.wheelbase_m / math.tan(math.radians(35.0))
        if ry > -self.p.plan.taxi_out.taxiway_offset_m - radius:
            self.turning = True
        steering = math.radians(35.0) if self.turning else 0.0
        done = turned < -math.radians(88.0)
        target = 0.0 if done else -ap.tune.pushback_mps
        ap.ac.set("external_reactions/pushback/magnitude", ap.tug_pid(target - v, ap.dt))
        ap.steer(steering if not done else 0.0)
        if done:
            ap.brakes(1.0)
            if abs(v) < 0.05:
                ap.ac.set("external_reactions/pushback/magnitude", 0.0)
                self.p.event("tug_disconnected")
                self.p.fire("tug_disconnected")


class Taxi(Controller):
    """Pure pursuit along a taxi route at the taxi speed, slowing for corners and stopping at its
    holds (``holding`` meanwhile); :meth:`taxi` returns True at the route's end."""

    def start_route(self, path) -> None:
        self.ap.path = path
        self.stop_idx = 0
        self.hold_until: float | None = None
        self.ap.ground_spd_pid.reset()

    @property
    def holding(self) -> bool:
        return self.hold_until is not None

    def taxi(self, x, frame) -> bool:
        ap, p = self.ap, self.p
        gs = ap.gs(x)
        s, cross, v_t = ap.follow(x, frame, ap.tune.taxi_straight_mps, max(12.0, 3.0 * gs), 70.0)
        if abs(cross) > 30.0:
            p.fail(f"left the taxiway: {cross:.0f} m from the taxi route")
        stops = ap.path.stops
        decel = ap.tune.taxi_decel_mps2
        if self.hold_until is not None:
            v_t = 0.0
            if p.t >= self.hold_until:
                self.hold_until = None
                ap.ground_spd_pid.reset()
                if stops[self.stop_idx].name == "lineup":
                    return True
                self.stop_idx += 1
        elif self.stop_idx < len(stops):
            st = stops[self.stop_idx]
            d = st.s_m - s
            v_t = min(v_t, math.sqrt(max(0.0, 2 * decel * (d - 2.0))))
            if d < 3.0 and gs < 0.3:
                self.hold_until = p.t + st.hold_s
                p.event("hold", f"{st.name} {st.hold_s:.0f} s")
        else:
            d = ap.path.length_m - s
            v_t = min(v_t, math.sqrt(max(0.0, 2 * decel * (d - 2.0))))
            if d < 3.0 and gs < 0.3:
                return True
        ap.speed_on_ground(gs, v_t)
        return False


class TaxiOut(Taxi):
    def enter(self, x) -> None:
        ix = self.p.ix
        rx, ry = self.ap.origin.to_xy(x[ix["lat_deg"]], x[ix["lon_deg"]])
        self.start_route(taxi_out_path(self.p.plan.taxi_out, (rx, ry), self.p.plan.origin.length_m))

    def tick(self, x) -> None:
        if self.hold_until is None and self.ap.flaps == 0.0:
            self.ap.set_flaps(self.p.plan.takeoff_flaps_norm or self.p.prof.takeoff_flaps_norm)
        if self.taxi(x, self.ap.origin):
            self.p.fire("lined_up")


class TakeoffRoll(Controller):
    def enter(self, x) -> None:
        ap = self.ap
        ap.brake_pid.reset()
        ap.brakes(0.0)
        ap.throttle(self.p.plan.takeoff_thrust_norm)
        ap.theta_cmd = x[self.p.ix["theta_rad"]]
        ap.pitch_pid.reset()
        self.rotating = False

    def tick(self, x) -> None:
        ap, p, ix, prof = self.ap, self.p, self.p.ix, self.p.prof
        ap.runway_track(x, ap.origin)
        ias = x[ix["ias_mps"]]
        ap.bank_to(x, 0.0)
        if ias >= prof.vr_kt * KT_MPS:
            if not self.rotating:
                self.rotating = True
                p.event("rotate", f"{ias / KT_MPS:.0f} kt")
            ap.theta_cmd = rate_limit(ap.theta_cmd, math.radians(prof.rotate_pitch_deg), math.radians(3.0) * ap.dt)
            # nose-up elevator bias while the mains still carry the aircraft (rotation)
            ap.pitch_to(x, ap.theta_cmd, bias=prof.rotate_elevator)
        else:
            ap.ac.set("fcs/elevator-cmd-norm", 0.0)
        if x[ix["wow"]] < 0.5 and x[ix["agl_m"]] > prof.cg_height_m + 1.0:
            p.t_liftoff = p.t
            p.event("liftoff", f"{ias / KT_MPS:.1f} kt")
            ap.steer(0.0)
            ap.ac.set("fcs/rudder-cmd-norm", 0.0)
            # hand the rotation bias over to the pitch integrator so the elevator does not jump
            ap.pitch_pid.integral += prof.rotate_elevator / ap.pitch_pid.ki
            ap.climb_spd_pid.reset(integral=x[ix["theta_rad"]] / ap.climb_spd_pid.ki)
            p.fire("liftoff")


class InitialClimb(Controller):
    """V2 + 20 kt to the acceleration height, then accelerate while still climbing (the speed target
    ramps up at 1.5 kt/s, no level-off) at climb thrust, flaps up on schedule, runway heading to
    400 ft then the route."""

    def enter(self, x) -> None:
        self.t_accel: float | None = None

    def tick(self, x) -> None:
        ap, p, ix, prof, tu = self.ap, self.p, self.p.ix, self.p.prof, self.ap.tune
        agl = x[ix["agl_m"]]
        if ap.ac.get("gear/gear-cmd-norm") > 0.5 and agl > 15.0 and -x[ix["v_down_mps"]] > 1.0:
            ap.ac.set("gear/gear-cmd-norm", 0.0)
            p.event("gear_up")
        target = (prof.v2_kt + 20.0) * KT_MPS
        if agl > tu.accel_height_m:
            if self.t_accel is None:
                self.t_accel = p.t
                ap.throttle(prof.climb_throttle)
                p.event("acceleration_height")
            target = min(tu.speed_limit_mps, (prof.v2_kt + 20.0 + 1.5 * (p.t - self.t_accel)) * KT_MPS)
        # pitch command moves at most 2 deg/s here, where the speeds are low
        ap.speed_on_pitch(x, target, lo_deg=5.0, hi_deg=15.0, rate_dps=2.0)
        ap.retract_flaps(x, above_m=tu.accel_height_m)
        ap.lateral(x, runway_heading_below_m=400.0 * FT_M)
        if agl > tu.climb_out_m or x[ix["alt_m"]] > p.plan.cruise_alt_m - 150.0:
            # bumpless hand-over to the climb's vertical-rate mode: its loops start where these are
            ap.gamma_pid.reset(integral=x[ix["theta_rad"]] / ap.gamma_pid.ki)
            ap.spd_pid.reset(integral=prof.climb_throttle / prof.spd_ki)
            ap.thr = prof.climb_throttle
            ap.vs_cmd = -x[ix["v_down_mps"]]
            p.fire("climb_out_done")


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
        h_tgt = min(p.plan.cruise_alt_m, ap.path_alt_m(d))
        v_new = ap.speed_target_mps(x, d, climbing=phase == "climb", on_approach_legs=phase != "climb")
        if ap.v_tgt is None:
            ap.v_tgt = v_new
        ap.v_tgt = rate_limit(ap.v_tgt, v_new, KT_MPS * ap.dt)
        v_tgt = ap.v_tgt
        if ap.lateral(x, may_capture=phase in ("cruise", "descent")):
            p.fire("localizer_capture")
        if phase == "climb":
            ap.retract_flaps(x)
            if h < h_tgt - 250.0:
                self._climb(x, v_tgt, h_tgt - h)
                return
            ap.spd_pid.hi = 1.0
            p.fire("level")
        if p.phase == "cruise" and h_tgt < p.plan.cruise_alt_m - 1.0:
            p.fire("top_of_descent")
        if p.phase in ("descent", "approach"):
            ap.configure_approach(d, x[ix["ias_mps"]])
        # vertical: altitude error -> vertical speed -> flight-path angle -> pitch
        gs = ap.gs(x)
        on_path = h_tgt < p.plan.cruise_alt_m
        slope = (ap.path_alt_m(d) - ap.path_alt_m(d - 100.0)) / 100.0 if on_path else 0.0
        vs_ff = -gs * slope
        if ap.loc_mode:
            vs_cmd = clamp(vs_ff + 0.1 * (h_tgt - h), -8.0, 3.0)
        else:
            vs_cmd = clamp(vs_ff + 0.05 * (h_tgt - h), -15.0, 10.0)
        if ap.vs_cmd is None:
            ap.vs_cmd = -x[ix["v_down_mps"]]
        ap.vs_cmd = rate_limit(ap.vs_cmd, vs_cmd, 0.8 * ap.dt)
        lo_deg = -8.0
        mg = x[ix["agl_m"]] - prof.cg_height_m
        if ap.loc_mode and mg < 200 * FT_M:
            # short final: hold the stabilised attitude (no diving into ground effect)
            if ap.theta_final is None:
                ap.theta_final = math.degrees(x[ix["theta_rad"]])
            lo_deg = ap.theta_final - 1.0
        ap.path_to(x, ap.vs_cmd, lo_deg, 15.0, rate_dps=1.5 if ap.loc_mode else 1.0)
        # speed: throttle, speedbrake when idle is not enough
        err = v_tgt - x[ix["ias_mps"]]
        thr = ap.spd_pid(err, ap.dt)
        ap.throttle_smooth(thr)
        agl = x[ix["agl_m"]]
        sb = clamp((-err - 4.0) / 10.0, 0.0, 1.0) if thr <= 0.01 and agl > 1000 * FT_M else 0.0
        ap.ac.set("fcs/speedbrake-cmd-norm", sb)
        if ap.loc_mode and agl - prof.cg_height_m < prof.flare_height_ft * FT_M:
            p.fire("flare_height")


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


class Flare(Controller):
    """Exponential flare: the sink rate commanded as (h + h_b) / tau, continuous at flare entry and
    tending to the flight's drawn touchdown sink v_td (h: main-gear height). The flight-path loop
    closes on the sink rate predicted ``FLARE_LEAD_S`` ahead from the vertical acceleration (the
    specific force), as a pilot anticipates: without that lead the attitude's lag behind the
    command makes the flare either late (a firm landing) or overdone (a balloon, then a drop)."""

    def enter(self, x) -> None:
        self.tau: float | None = None

    def tick(self, x) -> None:
        ap, p, ix, prof = self.ap, self.p, self.p.ix, self.p.prof
        mg_ft = (x[ix["agl_m"]] - prof.cg_height_m) / FT_M
        target_fps = ap.draws.touchdown_sink_mps / FT_M
        if self.tau is None:
            # h_b = v_td h0 / (sink0 - v_td) makes (h0 + h_b) / tau = sink0 and h_b / tau = v_td
            sink0_fps = max(x[ix["v_down_mps"]] / FT_M, target_fps + 2.0)
            self.hb_ft = target_fps * mg_ft / (sink0_fps - target_fps)
            self.tau = (mg_ft + self.hb_ft) / sink0_fps
            ap.gamma_pid.reset(integral=x[ix["theta_rad"]] / ap.gamma_pid.ki)  # bumpless
        vs_cmd = -max(target_fps, (mg_ft + self.hb_ft) / self.tau) * FT_M
        # vertical acceleration (up) from the specific force: a = -f_z cos(theta) - g (near wings level)
        a_up = -x[ix["fz_mps2"]] * math.cos(x[ix["theta_rad"]]) - G0_MPS2
        vs_pred = -x[ix["v_down_mps"]] + FLARE_LEAD_S * a_up
        lo_deg = -3.0 if ap.theta_final is None else ap.theta_final - 1.0
        ap.path_to(x, vs_cmd, lo_deg, 12.0, rate_dps=5.0, boost=prof.flare_gain, vs_now=vs_pred)
        ap.throttle_smooth(0.0 if mg_ft < 20.0 else ap.spd_pid(ap.vapp_mps() - x[ix["ias_mps"]], ap.dt))
        rx, ry = ap.dest.to_xy(x[ix["lat_deg"]], x[ix["lon_deg"]])
        ap.heading_to(x, ap.dest.heading_rad - math.atan2(ry, 1500.0), 5.0)
        if x[ix["wow"]] > 0.5:
            sink = x[ix["v_down_mps"]]
            p.event("touchdown", f"sink {sink / FT_M * 60:.0f} fpm at {rx:.0f} m")
            if sink > ap.tune.max_touchdown_sink_mps:
                p.fail(f"hard landing: touchdown sink rate {sink / FT_M:.1f} ft/s exceeds "
                       f"{ap.tune.max_touchdown_sink_mps / FT_M:.0f} ft/s")
            p.fire("touchdown")


FLARE_LEAD_S = 1.0  # the flare loop's anticipation of the sink rate


class Rollout(Controller):
    """Spoilers and speedbrake out, reversers while fast, a deceleration-loop autobrake to the plan's
    target; the reverse thrust is trimmed down when it alone decelerates harder than the target."""

    def enter(self, x) -> None:
        ap = self.ap
        ap.ac.set("fcs/speedbrake-cmd-norm", 1.0)
        ap.ac.set("fcs/spoiler-cmd-norm", 1.0)
        # stop flaring: the attitude held as it is (no further pull: with lift still near the weight,
        # a pull after the first contact bounces the aircraft back into the air), then lowered
        ap.theta_cmd = x[self.p.ix["theta_rad"]]
        ap.pitch_pid.integral *= 0.5
        self.rev_thr = self.p.prof.reverse_throttle
        ap.brake_pid.reset()

    def tick(self, x) -> None:
        ap, p, ix, prof = self.ap, self.p, self.p.ix, self.p.prof
        ap.runway_track(x, ap.dest)
        ap.ac.set("fcs/aileron-cmd-norm", 0.0)
        ap.theta_cmd = rate_limit(ap.theta_cmd, math.radians(-1.0), math.radians(2.0) * ap.dt)
        if x[ix["theta_rad"]] > math.radians(0.5):
            ap.pitch_to(x, ap.theta_cmd)
        else:
            ap.ac.set("fcs/elevator-cmd-norm", 0.2)
        gs = ap.gs(x)
        nose_down = x[ix["theta_rad"]] < math.radians(1.5)
        rev = nose_down and gs > 70.0 * KT_MPS
        for i in range(prof.n_engines):
            ap.ac.set(f"propulsion/engine[{i}]/reverser-angle-rad", math.pi if rev else 0.0)
        target = p.plan.autobrake_decel_mps2
        self.rev_thr = clamp(self.rev_thr + 0.5 * ap.dt * (target - ap.decel_f), 0.0, prof.reverse_throttle)
        ap.throttle(self.rev_thr if rev else 0.0)
        if nose_down:
            ap.brakes(ap.brake_pid(target - ap.decel_f, ap.dt))
        if gs < ap.tune.exit_speed_mps:
            for prop in ("fcs/speedbrake-cmd-norm", "fcs/spoiler-cmd-norm", "fcs/rudder-cmd-norm",
                         "fcs/elevator-cmd-norm"):
                ap.ac.set(prop, 0.0)
            ap.set_flaps(0.0)
            p.fire("exit_speed")


class TaxiIn(Taxi):
    def enter(self, x) -> None:
        ix = self.p.ix
        rx, _ = self.ap.dest.to_xy(x[ix["lat_deg"]], x[ix["lon_deg"]])
        self.start_route(taxi_in_path(self.p.plan.taxi_in, rx))

    def tick(self, x) -> None:
        if self.taxi(x, self.ap.dest):
            self.p.fire("at_stand")


class Shutdown(Controller):
    def enter(self, x) -> None:
        ap = self.ap
        ap.brakes(1.0)
        ap.throttle(0.0)
        ap.steer(0.0)
        ap.ac.set("propulsion/active_engine", -1)
        ap.ac.set("propulsion/cutoff_cmd", 1)

    def tick(self, x) -> None:
        self.ap.brakes(1.0)
        # engines off: every N2 below 5 % after fuel cut-off (the end of the seed's flight time)
        if all(x[self.p.ix[f"n2_pct_{i}"]] < 5.0 for i in range(self.p.prof.n_engines)):
            self.p.t_engines_off = self.p.t
            self.p.event("engines_off")
            self.p.fire("engines_off")


class Parked(Controller):
    holding = True

    def tick(self, x) -> None:
        self.ap.brakes(1.0)
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
    "rollout": Rollout,
    "taxi_in": TaxiIn,
    "shutdown": Shutdown,
    "parked": Parked,
}
