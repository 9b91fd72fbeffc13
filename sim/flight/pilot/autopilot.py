"""The loops every phase controller flies with: actuators, attitude and path loops, lateral
navigation, runway tracking and taxiing. No JSBSim airliner has a usable autopilot, so this is one.

Loops (PID blocks of :mod:`flightmode.sim.flight.pilot.control`): pitch on elevator with pitch-rate
damping; vertical speed -> flight-path angle -> pitch; speed on pitch in the climb; heading -> bank ->
aileron; IAS/Mach -> throttle (speedbrake when idle is not enough); great-circle course to each
waypoint; localizer (on the ground track) and glideslope by geometry to the destination runway;
nose-wheel steering by pure pursuit on the ground, with yaw-rate feedback and differential braking. Gains and procedures
come from the aircraft profile (:class:`~flightmode.sim.flight.aircraft.tuning.PilotTuning`).

Each control tick the pilot hands the loops ``x``, the SI state row of
:class:`~flightmode.sim.flight.jsbsim.adapter.JSBSimAircraft` (``x[ix["alt_m"]]``...). Plain scalar
Python: the loops run at 4-40 Hz and NumPy scalars would be slower.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import cast

from flightmode.sim.flight import geodesy
from flightmode.sim.flight.aircraft.profile import AircraftProfile
from flightmode.sim.flight.geodesy import RunwayFrame
from flightmode.sim.flight.pilot.control import PID, clamp, rate_limit
from flightmode.sim.flight.plan import FlightPlan
from flightmode.sim.flight.taxi_route import Path2D, pure_pursuit_steer_rad
from flightmode.units import FT_M, KT_MPS, LB_KG, NM_M

# bank per radian of heading (or track) error: a first-order turn of time constant V / (2 g), 3.7 s at
# 140 kt
HEADING_BANK_GAIN = 2.0
# the localizer's shortest look-ahead (m; the look-ahead is a quarter of the distance to the threshold
# between this and 6 km). Steering the track at a point L ahead through that turn makes the
# cross-track offset y a second-order loop: y'' + (2 g / V) y' + (2 g / L) y = 0, omega = sqrt(2 g / L)
# whatever the speed, damping g / (V omega). At 600 m: omega 0.18 rad/s (a 35 s undamped period),
# damping 0.75 at 140 kt. The heading-steered law with 1500 m before it (omega 0.11 rad/s) let the
# boundary layer's lateral gusts (sim.flight.turbulence, 1-2 m/s over seconds) carry a 787 15 m either
# side of the centreline on short final and, in the flare, 24-26 m off it onto the runway's edge: 2 of
# 20 route landings of the 787-8 planned with the real type's burn (european-trio's routes), which now
# land 6.5 m from it at most
LOC_LOOK_MIN_M = 600.0
# the approach fix reached without a capture (Autopilot._turn_back): how long after first coming within
# 2.5 nm of it, and the leg out beyond it. A lap of a circle about the fix at 200-250 kt and 25 deg of
# bank takes 2 pi V / (g tan 25 deg) = 140-180 s: after 300 s the aircraft has circled the fix more than
# once without meeting the capture's conditions, and would go on circling (the pattern's approaches of
# the four types, a go-around each, capture 81-111 s after first coming within 2.5 nm). 6 nm out,
# the waypoint is reached 2 nm short of it; the turn back (a 1.5-2 nm radius) then leaves the aircraft
# 3-4 nm beside the centreline and 4-5 nm out, headed for the fix about 40 deg off the course, inside
# the capture's 75 deg
FIX_CAPTURE_WAIT_S = 300.0
TURN_BACK_NM = 6.0


class Autopilot:
    """The loops and actuators of one flight, and the navigation state the phases share."""

    def __init__(
        self, ac, plan: FlightPlan, profile: AircraftProfile, draws, event: Callable[[str, str], None]
    ):
        self.ac = ac
        self.plan = plan
        self.prof = profile
        self.draws = draws  # this flight's draws (flightmode.sim.flight.draws.FlightDraws)
        self.tune = profile.tuning
        self.event = event  # event(name, detail): logs a flight event at the current time
        self.ix = ac.index
        self.dt = 0.025
        self.t = 0.0
        self.origin = RunwayFrame(plan.origin)
        self.dest = RunwayFrame(plan.destination)
        p, tu = profile, profile.tuning
        self.pitch_pid = PID(p.pitch_kp, p.pitch_ki, 0.0, -1.0, 1.0)
        self.spd_pid = PID(p.spd_kp, p.spd_ki, 0.0, 0.0, 1.0)
        self.climb_spd_pid = PID(*tu.climb_speed_pid)
        self.gamma_pid = PID(*tu.path_pid)
        # (kp, ki, kd) and the limits; mypy gives a *args of unknown length all the remaining parameters
        self.ground_spd_pid = PID(*tu.ground_speed_pid, 0.0, p.taxi_throttle_max)  # type: ignore[call-arg]
        self.tug_pid = PID(*tu.tug_pid)
        self.brake_pid = PID(*tu.brake_pid)
        # shared state
        self.thr = 0.0  # the smoothed throttle
        self.theta_cmd = 0.0
        self.flaps = 0.0
        self.path: Path2D | None = None  # the taxi route being followed
        self.diff_brake = 0.0
        self.cruise_alt_m = plan.cruise_alt_m  # the current cruise level (step climbs raise it)
        self.parking_brake = 0.0  # the shutdown's brake command (sim.flight.pilot.ground.Shutdown)
        self.taxi_brake = 0.0  # the taxi speed loop's brake command, its mode and integrator
        self.taxi_braking = False
        self.taxi_brake_int = 0.0
        self.decel_f = 0.0  # filtered ground deceleration (m/s^2)
        self._gs_prev = 0.0
        self.fix_nm = plan.approach_fix_nm  # the approach fix, nm before the threshold (a circuit's: its own)
        self.set_route(list(plan.waypoints))
        self.loc_mode = False  # on the localizer
        self.theta_final: float | None = None  # pitch held on short final (deg)
        self.theta_mean: float | None = None  # the pitch attitude's running mean on the localizer (deg)
        self.v_tgt: float | None = None
        self.vs_cmd: float | None = None

    # ------------------------------------------------------------------ every tick
    def update(self, x, t: float, dt: float) -> None:
        """Time, and the filtered deceleration the autobrake loop closes on."""
        self.t, self.dt = t, dt
        gs = self.gs(x)
        self.decel_f += 0.3 * (-(gs - self._gs_prev) / dt - self.decel_f)
        self._gs_prev = gs

    # ------------------------------------------------------------------ actuators
    def throttle(self, u: float) -> None:
        for i in range(self.prof.n_engines):
            self.ac.set(f"fcs/throttle-cmd-norm[{i}]", u)

    def throttle_smooth(self, u: float) -> None:
        self.thr = rate_limit(self.thr, u, 0.15 * self.dt)
        self.throttle(self.thr)

    def brakes(self, u: float) -> None:
        self.ac.set("fcs/left-brake-cmd-norm", u)
        self.ac.set("fcs/right-brake-cmd-norm", u)

    def steer(self, rad: float) -> None:
        self.ac.set("fcs/steer-pos-deg[0]", math.degrees(rad))

    def set_flaps(self, norm: float) -> None:
        if norm != self.flaps:
            self.flaps = norm
            self.ac.set("fcs/flap-cmd-norm", norm)
            self.event("flaps", f"{norm:.3f}")

    # ------------------------------------------------------------------ state
    def gs(self, x) -> float:
        return math.hypot(x[self.ix["v_north_mps"]], x[self.ix["v_east_mps"]])

    def ground_speed_signed(self, x) -> float:
        psi = x[self.ix["psi_rad"]]
        return x[self.ix["v_north_mps"]] * math.cos(psi) + x[self.ix["v_east_mps"]] * math.sin(psi)

    # ------------------------------------------------------------------ attitude and path loops
    def pitch_to(self, x, theta_cmd: float, bias: float = 0.0) -> None:
        e = theta_cmd - x[self.ix["theta_rad"]]
        u = self.pitch_pid(e, self.dt, ff=bias - self.prof.pitch_kq * x[self.ix["q_radps"]])
        self.ac.set("fcs/elevator-cmd-norm", -u)

    def bank_to(self, x, phi_cmd: float) -> None:
        p = self.prof
        u = p.roll_kp * (phi_cmd - x[self.ix["phi_rad"]]) - p.roll_kp_p * x[self.ix["p_radps"]]
        self.ac.set("fcs/aileron-cmd-norm", clamp(u, -1.0, 1.0))

    def heading_to(self, x, psi_cmd: float, max_bank_deg: float) -> None:
        self._turn(x, psi_cmd - x[self.ix["psi_rad"]], max_bank_deg)

    def _turn(self, x, err_rad: float, max_bank_deg: float) -> None:
        """Bank HEADING_BANK_GAIN times the direction error (wrapped), within ``max_bank_deg``."""
        err = (err_rad + math.pi) % (2 * math.pi) - math.pi
        lim = math.radians(max_bank_deg)
        self.bank_to(x, clamp(HEADING_BANK_GAIN * err, -lim, lim))

    def track_centreline(self, x, rx_m: float, ry_m: float, max_bank_deg: float) -> None:
        """Steer the ground track (not the heading) at the destination runway's extended centreline,
        from (``rx_m``, ``ry_m``) in its runway frame (m past the threshold, m right of the line), at a
        point a quarter of the distance to go ahead, between LOC_LOOK_MIN_M and 6 km. A lateral gust
        drifts the aircraft with the air: the drift is in the track at once, where a heading law sees
        it only as the offset grows (LOC_LOOK_MIN_M)."""
        ix = self.ix
        look = max(LOC_LOOK_MIN_M, min(6000.0, -rx_m * 0.25))
        track = math.atan2(x[ix["v_east_mps"]], x[ix["v_north_mps"]])
        self._turn(x, self.dest.heading_rad - math.atan2(ry_m, look) - track, max_bank_deg)

    def gear_up_when_climbing(self, x) -> None:
        """Gear up once climbing (positive rate, 15 m above the ground), as after every liftoff."""
        if (
            self.ac.get("gear/gear-cmd-norm") > 0.5
            and x[self.ix["agl_m"]] > 15.0
            and -x[self.ix["v_down_mps"]] > 1.0
        ):
            self.ac.set("gear/gear-cmd-norm", 0.0)
            self.event("gear_up", "")

    def hand_over_to_path_loops(self, x, throttle: float) -> None:
        """Bumpless hand-over from speed on pitch to the vertical-rate loops (path_to, speed on the
        throttle): their integrators start at the attitude and ``throttle`` of the moment."""
        self.gamma_pid.reset(integral=x[self.ix["theta_rad"]] / self.gamma_pid.ki)
        self.spd_pid.reset(integral=throttle / self.prof.spd_ki)
        self.thr = throttle
        self.vs_cmd = -x[self.ix["v_down_mps"]]

    def speed_on_pitch(self, x, target_mps: float, lo_deg: float, hi_deg: float, rate_dps: float) -> None:
        """Too fast -> pitch up: PI from IAS error to the pitch command (integrator = trim pitch),
        the command moving at most ``rate_dps``."""
        err = x[self.ix["ias_mps"]] - target_mps
        theta = clamp(self.climb_spd_pid(err, self.dt), math.radians(lo_deg), math.radians(hi_deg))
        self.theta_cmd = rate_limit(self.theta_cmd, theta, math.radians(rate_dps) * self.dt)
        self.pitch_to(x, self.theta_cmd)

    def path_to(
        self,
        x,
        vs_cmd: float,
        lo_deg: float,
        hi_deg: float,
        rate_dps: float = 3.0,
        boost: float = 0.0,
        vs_now: float | None = None,
    ) -> None:
        """Vertical speed -> flight-path angle error -> pitch (PI; the integrator is trim pitch).
        ``vs_now``: the vertical speed to close the loop on (default: the measured one)."""
        ix = self.ix
        tas = max(x[ix["tas_mps"]], 30.0)
        gamma_cmd = math.asin(clamp(vs_cmd / tas, -0.3, 0.3))
        vs = -x[ix["v_down_mps"]] if vs_now is None else vs_now
        gamma = math.asin(clamp(vs / tas, -0.5, 0.5))
        # the pitch limits are the PID's own output limits, so its integrator cannot wind up
        # against them (it did, holding attitude on short final, and then the flare was late)
        self.gamma_pid.lo, self.gamma_pid.hi = math.radians(lo_deg), math.radians(hi_deg)
        theta = self.gamma_pid(gamma_cmd - gamma, self.dt) + boost * (gamma_cmd - gamma)
        theta = clamp(theta, math.radians(lo_deg), math.radians(hi_deg))
        self.theta_cmd = rate_limit(self.theta_cmd, theta, math.radians(rate_dps) * self.dt)
        self.pitch_to(x, self.theta_cmd)

    # ------------------------------------------------------------------ navigation
    def approach_fix(self) -> tuple[float, float]:
        d = self.plan.destination
        return geodesy.destination_point(
            d.lat_deg, d.lon_deg, (d.heading_deg + 180.0) % 360.0, self.fix_nm * NM_M
        )

    def set_route(self, waypoints: list[tuple[float, float]], fix_nm: float | None = None) -> None:
        """Fly ``waypoints`` (lat, lon), then the approach fix ``fix_nm`` before the destination's
        threshold (default: the current one), then the localizer."""
        if fix_nm is not None:
            self.fix_nm = fix_nm
        self.waypoints = list(waypoints) + [self.approach_fix()]
        self.wp = 0
        self.fix_reached_t: float | None = None  # first time within 2.5 nm of the fix, not captured
        # distance from each waypoint to the threshold along the remaining legs (constant)
        legs = [geodesy.gc_distance_m(*a, *b) for a, b in zip(self.waypoints, self.waypoints[1:])]
        self.legs_after_m = [sum(legs[i:]) + self.fix_nm * NM_M for i in range(len(self.waypoints))]

    def _turn_back(self, hdg_err_rad: float) -> None:
        """At the approach fix for FIX_CAPTURE_WAIT_S without a capture (a route that reaches the fix from
        the runway's side, headed away from the final course): fly out along the extended centreline
        TURN_BACK_NM past the fix and back to it, at the glideslope's height at the fix (a procedure
        turn's outbound leg: ICAO Doc 8168 Vol I, reversal procedures). Without it the pure pursuit of
        the fix circled it, the fix inside its turn circle, until a lap happened to meet the capture's
        conditions: regional-hops member 38 (EDDF-LKPR, runway 24 reached from the west) circled it
        about 10 min with seeds 0-4 and 17 min with seed 5, burning 3.4 t/h of the 6.6 t it had at the
        fix: about 1.9 h of circling. Issue 54's flight of that member, which stalled in its flare 2.7 h
        after the gate, had likely circled there about 1.8 h. The distance to go counts the leg out as
        the fix's."""
        self.fix_reached_t = None
        out = self.dest.to_latlon(-(self.fix_nm + TURN_BACK_NM) * NM_M, 0.0)
        self.waypoints.insert(self.wp, out)
        self.legs_after_m.insert(self.wp, self.legs_after_m[self.wp])
        self.cruise_alt_m = min(self.cruise_alt_m, self.path_alt_m(self.fix_nm * NM_M))
        self.event(
            "turn_back",
            f"at the approach fix {FIX_CAPTURE_WAIT_S:.0f} s without a capture, "
            f"{math.degrees(hdg_err_rad):.0f} deg off the final course",
        )

    def distance_to_go_m(self, x) -> float:
        lat, lon = x[self.ix["lat_deg"]], x[self.ix["lon_deg"]]
        if self.loc_mode:
            rx, _ = self.dest.to_xy(lat, lon)
            return -rx
        wp = self.waypoints[self.wp]
        return geodesy.gc_distance_m(lat, lon, *wp) + self.legs_after_m[self.wp]

    def path_alt_m(self, d_m: float) -> float:
        """The vertical profile: glideslope inside 10 nm, the descent path beyond."""
        elev = self.plan.destination.elevation_m
        gs = math.tan(math.radians(self.plan.glideslope_deg))
        d_gs = 10.0 * NM_M
        aim = self.tune.touchdown_aim_m
        d_m = max(d_m, -aim)
        if d_m <= d_gs:
            return elev + gs * (d_m + aim)
        return elev + gs * (d_gs + aim) + math.tan(math.radians(self.plan.descent_angle_deg)) * (d_m - d_gs)

    def lateral(self, x, *, runway_heading_below_m: float | None = None, may_capture: bool = False) -> bool:
        """Fly the route: runway heading below ``runway_heading_below_m`` (after takeoff), great-circle
        courses to each waypoint, then the localizer. Returns True on the tick the localizer is
        captured (only when ``may_capture``)."""
        ix = self.ix
        lat, lon = x[ix["lat_deg"]], x[ix["lon_deg"]]
        if runway_heading_below_m is not None and x[ix["agl_m"]] < runway_heading_below_m:
            self.heading_to(x, self.origin.heading_rad, 5.0)
            return False
        captured = False
        if not self.loc_mode:
            wp = self.waypoints[self.wp]
            d = geodesy.gc_distance_m(lat, lon, *wp)
            if self.wp == len(self.waypoints) - 1:
                # approach fix: engage the localizer once close, or once abeam inside the cone
                rx, ry = self.dest.to_xy(lat, lon)
                hdg_err = abs((x[ix["psi_rad"]] - self.dest.heading_rad + math.pi) % (2 * math.pi) - math.pi)
                inside_cone = -(self.fix_nm + 2.0) * NM_M < rx < -3.0 * NM_M and abs(ry) < 1.5 * NM_M
                if may_capture and (d < 2.5 * NM_M or inside_cone) and hdg_err < math.radians(75.0):
                    self.loc_mode = captured = True
                    self.event("localizer_capture", "")
                else:
                    if may_capture and d < 2.5 * NM_M and self.fix_reached_t is None:
                        self.fix_reached_t = self.t
                    if self.fix_reached_t is not None and self.t - self.fix_reached_t > FIX_CAPTURE_WAIT_S:
                        self._turn_back(hdg_err)
            elif d < 2.0 * NM_M:
                self.wp += 1
                self.event("waypoint", f"{self.wp}")
            if not self.loc_mode:
                self.heading_to(x, geodesy.gc_course_rad(lat, lon, *wp), self.prof.turn_bank_deg)
                return captured
        rx, ry = self.dest.to_xy(lat, lon)
        bank = self.prof.turn_bank_deg if x[ix["agl_m"]] > 500 * FT_M else 8.0
        self.track_centreline(x, rx, ry, bank)
        return captured

    def speed_target_mps(self, x, d_m: float, climbing: bool, on_approach_legs: bool) -> float:
        p, tu = self.prof, self.tune
        ix = self.ix
        alt = x[ix["alt_m"]]
        ias = x[ix["ias_mps"]]
        mach = max(x[ix["mach"]], 0.05)
        if climbing:
            v = tu.speed_limit_mps if alt < tu.speed_limit_alt_m else p.climb.cas_mps
        else:  # descending: slow to 250 kt 500 ft above the limit's altitude
            v = tu.speed_limit_mps if alt < tu.speed_limit_alt_m + 500.0 * FT_M else p.descent_ias_kt * KT_MPS
        v = min(v, ias / mach * self.plan.cruise_mach)  # Mach limit above the crossover
        if on_approach_legs:
            for step in p.approach_steps:
                if d_m < step.dist_nm * NM_M:
                    v = min(v, self.step_speed_mps(step))
        return v

    def step_speed_mps(self, step) -> float:
        """An approach step's speed: its own, the last step's being the final approach speed for the
        mass (:meth:`vapp_mps`)."""
        return self.vapp_mps() if step is self.prof.approach_steps[-1] else step.speed_kt * KT_MPS

    def climb_vs_mps(self, alt_m: float) -> float:
        """The climb's vertical-rate target at this altitude: this flight's draw for the band
        (:class:`~flightmode.sim.flight.aircraft.performance.ClimbSchedule`)."""
        c = self.prof.climb
        pre, cas, mach = self.draws.climb_vs_mps
        return pre if alt_m < c.cross_cas_m else cas if alt_m < c.cross_mach_m else mach

    def mass_kg(self) -> float:
        """The aircraft's mass now (JSBSim's weight, fuel burnt included)."""
        return self.ac.get("inertia/weight-lbs") * LB_KG

    def vapp_mps(self) -> float:
        """Final approach speed for the current mass (stall speed scales with sqrt(mass)), plus the
        type's wind additive (:meth:`vapp_wind_additive_mps`)."""
        k = clamp(math.sqrt(self.mass_kg() / self.prof.ref_landing_mass_kg), 0.95, 1.1)
        return self.prof.vapp_kt * k * KT_MPS + self.vapp_wind_additive_mps()

    def vapp_wind_additive_mps(self) -> float:
        """The approach speed's wind additive beyond what the profile's ``vapp_kt`` holds: the
        profile's fraction of this flight's wind at 20 ft (the drawn surface wind, taken as all
        headwind), less ``vapp_wind_included_kt``, within 0 and ``vapp_wind_max_kt`` in all (a type
        without the rule has all three at 0)."""
        p = self.prof
        return clamp(
            p.vapp_wind_fraction * self.draws.atmosphere.w20_mps - p.vapp_wind_included_kt * KT_MPS,
            0.0,
            (p.vapp_wind_max_kt - p.vapp_wind_included_kt) * KT_MPS,
        )

    def _takeoff_speed_mps(self, kt: float) -> float:
        """A takeoff speed of the profile for the current mass: scaled with sqrt(mass), as the stall
        speed is, when the profile gives the mass it holds at (``vr_ref_mass_kg``)."""
        v = kt * KT_MPS
        if self.prof.vr_ref_mass_kg is None:
            return v
        return v * math.sqrt(self.mass_kg() / self.prof.vr_ref_mass_kg)

    def vr_mps(self) -> float:
        """Rotation speed for the current mass (:meth:`_takeoff_speed_mps`)."""
        return self._takeoff_speed_mps(self.prof.vr_kt)

    def v2_mps(self) -> float:
        """Takeoff safety speed for the current mass (:meth:`_takeoff_speed_mps`: V2 is at least 1.13
        times the 1-g stall speed, 14 CFR 25.107(b), which grows as sqrt(mass))."""
        return self._takeoff_speed_mps(self.prof.v2_kt)

    def configure_approach(self, d_m: float, ias_mps: float) -> None:
        for step in self.prof.approach_steps:
            # a setting is selected inside its distance gate once slow enough for it: within 10 kt
            # of its own speed (these models' flaps give so much lift that, selected fast on a light
            # aircraft, they drive the angle of attack negative and the pitch loop porpoises)
            limit_kt = step.speed_kt + 10.0
            if d_m < step.dist_nm * NM_M and ias_mps <= limit_kt * KT_MPS:
                flaps = step.flaps_norm
                if step.gear_down and self.ac.get("gear/gear-cmd-norm") < 0.5:
                    self.ac.set("gear/gear-cmd-norm", 1.0)
                    self.event("gear_down", "")
                if flaps > self.flaps:
                    landing = self.plan.landing_flaps_norm
                    last = step is self.prof.approach_steps[-1]
                    self.set_flaps(min(flaps, landing) if landing is not None and last else flaps)

    def retract_flaps(self, x, above_m: float | None = None) -> None:
        """Flaps up on the schedule (IAS above which each setting goes), above ``above_m`` AGL."""
        if above_m is not None and x[self.ix["agl_m"]] <= above_m:
            return
        for v_kt, fl in self.prof.flap_retract_kt:
            if x[self.ix["ias_mps"]] > v_kt * KT_MPS and fl < self.flaps:
                self.set_flaps(fl)

    # ------------------------------------------------------------------ on the ground
    def runway_track(self, x, frame: RunwayFrame) -> None:
        """Centreline tracking on the runway: nose wheel (fading with speed) plus rudder."""
        ix = self.ix
        rx, ry = frame.to_xy(x[ix["lat_deg"]], x[ix["lon_deg"]])
        ias = x[ix["ias_mps"]]
        hdg = frame.heading_in_frame(x[ix["psi_rad"]])
        hdg = (hdg + math.pi) % (2 * math.pi) - math.pi
        psi_err = -math.atan2(ry, 150.0) - hdg
        r = x[ix["r_radps"]]
        # the JSBSim airliners are directionally unstable on their gear: keep nose-wheel authority
        # (fading from 30 to 6 deg with speed) and damp the yaw rate with wheel and rudder alike
        steer_lim = math.radians(max(6.0, 30.0 * (1.0 - ias / 40.0)))
        self.steer(clamp(2.0 * psi_err - 1.0 * r, -steer_lim, steer_lim))
        # JSBSim convention: positive rudder command yaws the nose left (checked in flight for all
        # four models), the opposite of the nose wheel's positive-right steering angle
        self.ac.set("fcs/rudder-cmd-norm", clamp(-(4.0 * psi_err - 3.0 * r), -1.0, 1.0))

    def follow(
        self,
        x,
        frame: RunwayFrame,
        lookahead_m: float,
        max_steer_deg: float,
        max_yaw_rate_radps: float = math.inf,
    ) -> tuple[float, float]:
        """Pure pursuit along ``self.path``; returns (s, cross-track error). The path curvature it
        steers for is capped so that the yaw rate it asks for stays within ``max_yaw_rate_radps``
        (a nose wheel that lags would otherwise be asked for ever more as it falls behind). The
        speed is the taxi route's (:meth:`speed_on_ground`)."""
        ix = self.ix
        rx, ry = frame.to_xy(x[ix["lat_deg"]], x[ix["lon_deg"]])
        path = cast(Path2D, self.path)  # the taxi route: Taxi.start_route set it
        s, cross = path.project(rx, ry)
        target = path.point_at(s + lookahead_m)
        hdg = frame.heading_in_frame(x[ix["psi_rad"]])
        _, alpha = pure_pursuit_steer_rad(rx, ry, hdg, target, self.prof.wheelbase_m)
        gs = self.gs(x)
        ld = max(math.hypot(target[0] - rx, target[1] - ry), 1.0)
        kappa_max = max_yaw_rate_radps / max(gs, 0.5)
        kappa = clamp(2.0 * math.sin(alpha) / ld, -kappa_max, kappa_max)
        steer = math.atan(self.prof.wheelbase_m * kappa)
        # yaw-rate feedback around the kinematic pure-pursuit angle: the gear's yaw response lags
        # (badly on the A320 model), and without it the turns overshoot
        r_err = gs * kappa - x[ix["r_radps"]]
        steer += 1.5 * r_err
        # a touch of differential braking where the nose wheel alone lags the turn rate (as pilots
        # do); small, so that it never brakes the aircraft noticeably
        self.diff_brake = clamp(1.0 * r_err, -0.03, 0.03) if gs > 1.0 else 0.0
        lim = math.radians(max_steer_deg)
        self.steer(clamp(steer, -lim, lim))
        return s, cross

    def set_parking_brake(self, rate_per_s: float) -> None:
        """Move the parking brake toward fully set at ``rate_per_s`` and apply it to both sides."""
        self.parking_brake = rate_limit(self.parking_brake, 1.0, rate_per_s * self.dt)
        self.brakes(self.parking_brake)

    def speed_on_ground(self, gs: float, v_ref: float, a_ref: float) -> None:
        """Throttle and brakes to the taxi speed reference ``v_ref`` that changes at ``a_ref``
        (m/s^2), with the differential braking of :meth:`follow`. Throttle: PI on the speed error.
        Brakes (while the reference falls, or the aircraft is too fast): the deceleration wanted over
        the brakes' gain, plus a PI on the over-speed; the command moves at a limited rate, so the
        deceleration never steps. At a standstill with a zero reference: the hold brake."""
        tu, dt = self.tune, self.dt
        err = v_ref - gs
        standing = v_ref < 0.05 and gs < 0.3
        if self.taxi_braking:
            if err > 0.3 and a_ref > -0.01:
                self.taxi_braking = False
                self.ground_spd_pid.reset()
        elif err < -0.5 or (a_ref < -0.02 and err < 0.2) or v_ref < 0.05:
            self.taxi_braking = True
            self.taxi_brake_int = 0.0
        kp, ki = tu.taxi_brake_pi
        if standing:
            target, thr = tu.taxi_hold_brake, 0.0
        elif self.taxi_braking:
            self.taxi_brake_int = clamp(self.taxi_brake_int - err * dt, -5.0, 5.0)
            target = clamp(
                -a_ref / tu.taxi_brake_mps2 - kp * err + ki * self.taxi_brake_int,
                0.0,
                tu.taxi_brake_max_mps2 / tu.taxi_brake_mps2,
            )
            thr = 0.0
        else:
            target, thr = 0.0, self.ground_spd_pid(err, dt)
        up, down, still = tu.taxi_brake_rate
        rate = still if gs < 0.1 else (up if target > self.taxi_brake else down)
        self.taxi_brake = rate_limit(self.taxi_brake, target, rate * dt)
        self.throttle(thr)
        b, d = self.taxi_brake, self.diff_brake
        self.ac.set("fcs/left-brake-cmd-norm", clamp(b + max(0.0, -d), 0.0, 1.0))
        self.ac.set("fcs/right-brake-cmd-norm", clamp(b + max(0.0, d), 0.0, 1.0))
