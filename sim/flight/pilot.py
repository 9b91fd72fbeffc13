"""The gate-to-gate pilot: a phase state machine with PID loops, flying a JSBSim airliner.

No JSBSim airliner has a usable autopilot (FACTS.md), so this module is one: every control tick
it reads the SI state row of :class:`sim.jsbsim_adapter.JSBSimAircraft`, decides the phase, and
writes the controls. The loops (FACTS.md, "JSBSim"): pitch on elevator with pitch-rate damping;
vertical speed -> flight-path angle -> pitch (with the measured angle of attack as feed-forward);
speed on pitch in the climb; heading -> bank -> aileron; IAS/Mach -> throttle (speedbrake when
idle is not enough); great-circle course to each waypoint; localizer and glideslope by geometry
to the destination runway; an exponential flare; spoilers, reversers and a deceleration-loop
autobrake on the rollout; pure-pursuit nose-wheel steering on the ground.

The tug (pushback) is a body-axis external force at the nose gear, with a PI loop on ground speed
(see :mod:`sim.jsbsim_adapter`), the same for every type.

Limits checked every tick raise :class:`sim.errors.FlightError` naming phase, time and cause.
"""

from __future__ import annotations

import math

from flightmode.sim.flight import geodesy
from flightmode.sim.flight.aircraft_profiles import AircraftProfile
from flightmode.sim.flight.control import PID, clamp, rate_limit
from flightmode.errors import FlightError
from flightmode.sim.flight.jsbsim_adapter import FT_M, KT_MPS
from flightmode.labels import AIRBORNE_PHASES, PHASE_CODE, SEVERITY_CODE
from flightmode.sim.flight.geodesy import RunwayFrame
from flightmode.sim.flight.plan import FlightPlan
from flightmode.sim.flight.taxi_route import Path2D, pure_pursuit_steer_rad, taxi_in_path, taxi_out_path

NM_M = 1852.0
LBF_N = 4.4482216152605
TAXI_STRAIGHT_MPS = 20.0 * KT_MPS  # FACTS.md: about 20 kt straight (A319 manual); turns: the profile
TAXI_DECEL_MPS2 = 0.5
PUSHBACK_MPS = 1.2
MAX_BANK_DEG = 45.0
MAX_SINK_FPS = 10.0
ACCEL_HEIGHT_FT = 1500.0  # thrust reduction and acceleration height after takeoff
FLARE_HB_FT = 15.0  # exponential-flare bias height: touchdown sink about FLARE_HB_FT / tau
TOUCHDOWN_AIM_M = 300.0  # glideslope origin past the threshold (50 ft crossing height at 3 deg)


class Pilot:
    """Flies ``plan`` with ``profile`` on ``ac``; call :meth:`tick` every ``dt_s`` seconds."""

    def __init__(self, ac, plan: FlightPlan, profile: AircraftProfile, dt_s: float):
        self.ac = ac
        self.plan = plan
        self.prof = profile
        self.dt = dt_s
        self.ix = ac.index
        self.origin = RunwayFrame(plan.origin)
        self.dest = RunwayFrame(plan.destination)
        self.events: list[tuple[float, str, str]] = [(0.0, "gate", "phase")]  # (t_s, name, detail)
        self.phase = "gate"
        self.phase_code = PHASE_CODE["gate"]
        self.severity_code = 0
        self.done = False
        self._t_phase = 0.0
        self._t = 0.0
        # loops
        p = profile
        self.pitch_pid = PID(p.pitch_kp, p.pitch_ki, 0.0, -1.0, 1.0)
        self.spd_pid = PID(p.spd_kp, p.spd_ki, 0.0, 0.0, 1.0)
        self.climb_spd_pid = PID(0.008, 0.001, 0.04, -0.1, 0.35)  # rad per m/s; kd damps the phugoid
        self.gamma_pid = PID(1.0, 0.15, 0.0, -0.2, 0.35)  # rad per rad
        self._thr = 0.0
        self.ground_spd_pid = PID(0.08, 0.02, 0.0, 0.0, p.taxi_throttle_max)
        self.tug_pid = PID(20000.0, 4000.0, 0.0, -60000.0, 60000.0)  # lbf per m/s
        self.brake_pid = PID(0.5, 0.3, 0.0, 0.0, 1.0)
        self.theta_cmd = 0.0
        self.flaps = 0.0
        self.path: Path2D | None = None
        self._stop_idx = 0
        self._hold_until = None
        self._waypoints = list(plan.waypoints) + [self._approach_fix()]
        self._wp = 0
        # distance from each waypoint to the threshold along the remaining legs (constant)
        legs = [geodesy.gc_distance_m(*a, *b) for a, b in zip(self._waypoints, self._waypoints[1:])]
        self._legs_after_m = [sum(legs[i:]) + plan.approach_fix_nm * NM_M for i in range(len(self._waypoints))]
        self._loc_mode = False
        self._gs_prev = 0.0
        self._decel_f = 0.0
        self._engine = 0
        self._t_liftoff = None
        self._t_off = None
        self._turb_active = 0
        self._push_heading0 = 0.0
        self._push_turning = False
        self._diff_brake = 0.0
        self._flare_tau = None
        self._theta_final = None
        self._t_last = None
        self._t_accel = None
        self._t_alpha_high = None
        self._v_tgt = None
        self._vs_cmd = None
        self._en_route = False
        self._airborne_high = False

    # ------------------------------------------------------------------ helpers
    def _event(self, name: str, detail: str = "") -> None:
        self.events.append((self._t, name, detail))

    def _set_phase(self, phase: str) -> None:
        if phase != self.phase:
            self.phase = phase
            self.phase_code = PHASE_CODE[phase]
            self._t_phase = self._t
            self._event(phase, "phase")

    def _fail(self, cause: str) -> None:
        raise FlightError(cause, phase=self.phase, t_s=self._t)

    def _approach_fix(self) -> tuple[float, float]:
        d = self.plan.destination
        return geodesy.destination_point(
            d.lat_deg, d.lon_deg, (d.heading_deg + 180.0) % 360.0, self.plan.approach_fix_nm * NM_M
        )

    def _throttle(self, u: float) -> None:
        for i in range(self.prof.n_engines):
            self.ac.set(f"fcs/throttle-cmd-norm[{i}]", u)

    def _brakes(self, u: float) -> None:
        self.ac.set("fcs/left-brake-cmd-norm", u)
        self.ac.set("fcs/right-brake-cmd-norm", u)

    def _steer(self, rad: float) -> None:
        self.ac.set("fcs/steer-pos-deg[0]", math.degrees(rad))

    def _flaps(self, norm: float) -> None:
        if norm != self.flaps:
            self.flaps = norm
            self.ac.set("fcs/flap-cmd-norm", norm)
            self._event("flaps", f"{norm:.3f}")

    def _pitch_to(self, x, theta_cmd: float, bias: float = 0.0) -> None:
        e = theta_cmd - x[self.ix["theta_rad"]]
        u = self.pitch_pid(e, self.dt, ff=bias - self.prof.pitch_kq * x[self.ix["q_radps"]])
        self.ac.set("fcs/elevator-cmd-norm", -u)

    def _bank_to(self, x, phi_cmd: float) -> None:
        p = self.prof
        u = p.roll_kp * (phi_cmd - x[self.ix["phi_rad"]]) - p.roll_kp_p * x[self.ix["p_radps"]]
        self.ac.set("fcs/aileron-cmd-norm", clamp(u, -1.0, 1.0))

    def _heading_to(self, x, psi_cmd: float, max_bank_deg: float) -> None:
        err = (psi_cmd - x[self.ix["psi_rad"]] + math.pi) % (2 * math.pi) - math.pi
        phi_cmd = clamp(2.0 * err, -math.radians(max_bank_deg), math.radians(max_bank_deg))
        self._bank_to(x, phi_cmd)

    def _gs(self, x) -> float:
        return math.hypot(x[self.ix["v_north_mps"]], x[self.ix["v_east_mps"]])

    def _ground_speed_signed(self, x) -> float:
        psi = x[self.ix["psi_rad"]]
        return x[self.ix["v_north_mps"]] * math.cos(psi) + x[self.ix["v_east_mps"]] * math.sin(psi)

    # ------------------------------------------------------------------ tick
    @property
    def control_every(self) -> int:
        """FDM steps between ticks: 40 Hz on the runway and below 1000 ft; 20 Hz pushing back;
        10 Hz taxiing and airborne above 1000 ft; 5 Hz en route (the loops' bandwidths are well
        below 1 Hz there, and the pilot is most of flightmode's cost per step); 4 Hz standing still
        or waiting for an engine to spool up."""
        if self.phase in ("gate", "parked", "engine_start") or self._hold_until is not None:
            return 30  # standing still on the brakes (or waiting for a spool-up): 4 Hz
        if self._en_route:
            return 24  # 5 Hz
        if self._airborne_high or self.phase in ("taxi_out", "taxi_in"):
            # 10 Hz: airborne above 1000 ft (climb-out, approach before the last 1000 ft), and on
            # the taxiways (at 20 kt the aircraft moves 1 m per tick; the steering loops' time
            # constants are seconds)
            return 12
        if self.phase == "pushback":
            return 6  # 20 Hz: the tug's speed loop
        return 3

    def tick(self, x, t: float) -> None:
        if self._t_last is not None:
            self.dt = t - self._t_last
        self._t_last = t
        self._t = t
        self._check_limits(x)
        gs = self._gs(x)
        self._decel_f += 0.3 * (-(gs - self._gs_prev) / self.dt - self._decel_f)
        self._gs_prev = gs
        getattr(self, "_ph_" + self.phase)(x)
        self._turbulence()

    def _check_limits(self, x) -> None:
        if not math.isfinite(sum(x)):
            self._fail("NaN in the flight state: JSBSim diverged")
        ix = self.ix
        self._en_route = (
            self.phase in ("climb", "cruise", "descent")
            and x[ix["agl_m"]] > 3000 * FT_M
            and not self._loc_mode
        )
        self._airborne_high = (
            self.phase in ("initial_climb", "climb", "cruise", "descent", "approach")
            and x[ix["agl_m"]] > 1000 * FT_M
        )
        if abs(math.degrees(x[ix["phi_rad"]])) > MAX_BANK_DEG:
            self._fail(f"bank angle {math.degrees(x[ix['phi_rad']]):.1f} deg exceeds {MAX_BANK_DEG:.0f} deg")
        # stall: angle of attack above the type's stall angle for a whole second (gusts in
        # turbulence spike alpha for a fraction of a second without stalling the wing)
        if self.phase in AIRBORNE_PHASES and x[ix["wow"]] < 0.5 and math.degrees(x[ix["alpha_rad"]]) > self.prof.alpha_stall_deg:
            if self._t_alpha_high is None:
                self._t_alpha_high = self._t
            if self._t - self._t_alpha_high >= 1.0:
                self._fail(
                    f"stall: angle of attack {math.degrees(x[ix['alpha_rad']]):.1f} deg above "
                    f"{self.prof.alpha_stall_deg:.0f} deg for 1 s at IAS {x[ix['ias_mps']] / KT_MPS:.0f} kt"
                )
        else:
            self._t_alpha_high = None
        if x[ix["agl_m"]] < -2.0:
            self._fail(f"below the ground: height above ground {x[ix['agl_m']]:.1f} m")
        if x[ix["alt_m"]] > 16000.0 or x[ix["mach"]] > 0.95:
            self._fail(f"divergence: altitude {x[ix['alt_m']]:.0f} m, Mach {x[ix['mach']]:.2f}")
        if self.phase in AIRBORNE_PHASES and self.phase != "initial_climb" and x[ix["wow"]] > 0.5:
            fr = self.dest if self._loc_mode else self.origin
            rx, ry = fr.to_xy(x[ix["lat_deg"]], x[ix["lon_deg"]])
            if abs(ry) > fr.rwy.width_m / 2 or not (-50.0 < rx < fr.rwy.length_m):
                self._fail(f"ground contact off the runway at x = {rx:.0f} m, y = {ry:.0f} m from the threshold")

    def _turbulence(self) -> None:
        if self._t_liftoff is None:
            return
        since = self._t - self._t_liftoff
        sev = 0
        for seg in self.plan.turbulence:
            if seg.start_s <= since < seg.start_s + seg.duration_s:
                sev = SEVERITY_CODE[seg.severity]
        if self.phase not in AIRBORNE_PHASES:
            sev = 0
        if sev != self._turb_active:
            self._turb_active = sev
            self.severity_code = sev
            ac = self.ac
            if sev == 0:
                ac.set("atmosphere/turb-type", 0)
            else:
                # MIL-F-8785C via JSBSim's Milspec model (turb-type 3): probability-of-exceedance
                # index and the 20 ft wind that sets low-altitude intensity (sim.flight docs).
                index, wind_kt = MILSPEC[sev]
                ac.set("atmosphere/turb-type", 3)
                ac.set("atmosphere/turbulence/milspec/severity", index)
                ac.set("atmosphere/turbulence/milspec/windspeed_at_20ft_AGL-fps", wind_kt * KT_MPS / FT_M)
            self._event("turbulence", ("none", "light", "moderate", "severe")[sev])

    # ------------------------------------------------------------------ ground phases
    def _ph_gate(self, x) -> None:
        self._brakes(1.0)
        self._throttle(0.0)
        if self._t - self._t_phase >= self.plan.gate_wait_s:
            self._set_phase("engine_start")
            self._engine = self.prof.n_engines - 1
            self.ac.set("propulsion/active_engine", self._engine)
            self.ac.set("propulsion/starter_cmd", 1)
            self._event("starter", f"engine {self._engine}")

    def _ph_engine_start(self, x) -> None:
        ac, i = self.ac, self._engine
        if ac.get("propulsion/cutoff_cmd") > 0.5 and x[self.ix[f"n2_pct_{i}"]] > 15.0:
            ac.set("propulsion/cutoff_cmd", 0)  # fuel on at N2 > 15 % (FACTS.md)
            self._event("fuel_on", f"engine {i}")
        elif ac.get("propulsion/cutoff_cmd") < 0.5 and ac.get(f"propulsion/engine[{i}]/set-running") > 0.5:
            # the starter stays engaged until the engine is running: releasing it earlier aborts the start
            ac.set("propulsion/starter_cmd", 0)
            self._event("engine_running", f"engine {i}")
            if i == 0:
                ac.set("propulsion/active_engine", -1)
                self._set_phase("pushback")
                self._push_heading0 = x[self.ix["psi_rad"]]
                self._brakes(0.0)
                self.tug_pid.reset()
            else:
                self._engine = i - 1
                ac.set("propulsion/active_engine", self._engine)
                ac.set("propulsion/cutoff_cmd", 1)
                ac.set("propulsion/starter_cmd", 1)
                self._event("starter", f"engine {self._engine}")

    def _ph_pushback(self, x) -> None:
        ix = self.ix
        v = self._ground_speed_signed(x)
        turned = (x[ix["psi_rad"]] - self._push_heading0 + math.pi) % (2 * math.pi) - math.pi
        # push straight back across the apron, then turn the tail so the nose swings 90 deg left
        # onto the taxiway (turn radius = wheelbase / tan(35 deg))
        rx, ry = self.origin.to_xy(x[ix["lat_deg"]], x[ix["lon_deg"]])
        radius = self.prof.wheelbase_m / math.tan(math.radians(35.0))
        if ry > -self.plan.taxi_out.taxiway_offset_m - radius:
            self._push_turning = True
        steering = math.radians(35.0) if self._push_turning else 0.0
        done = turned < -math.radians(88.0)
        target = 0.0 if done else -PUSHBACK_MPS
        force_lbf = self.tug_pid(target - v, self.dt)
        self.ac.set("external_reactions/pushback/magnitude", force_lbf)
        self._steer(steering if not done else 0.0)
        if done:
            self._brakes(1.0)
            if abs(v) < 0.05:
                self.ac.set("external_reactions/pushback/magnitude", 0.0)
                self._event("tug_disconnected")
                rx, ry = self.origin.to_xy(x[ix["lat_deg"]], x[ix["lon_deg"]])
                self.path = taxi_out_path(self.plan.taxi_out, (rx, ry), self.plan.origin.length_m)
                self._stop_idx = 0
                self.ground_spd_pid.reset()
                self._set_phase("taxi_out")

    def _follow(self, x, frame: RunwayFrame, v_max: float, lookahead_m: float, max_steer_deg: float):
        """Pure pursuit along ``self.path``; returns (s, cross, speed target)."""
        ix = self.ix
        rx, ry = frame.to_xy(x[ix["lat_deg"]], x[ix["lon_deg"]])
        s, cross = self.path.project(rx, ry)
        target = self.path.point_at(s + lookahead_m)
        hdg = frame.heading_in_frame(x[ix["psi_rad"]])
        steer, alpha = pure_pursuit_steer_rad(rx, ry, hdg, target, self.prof.wheelbase_m)
        # yaw-rate feedback around the kinematic pure-pursuit angle: the gear's yaw response lags
        # (badly on the A320 model), and without it the turns overshoot
        gs = self._gs(x)
        ld = max(math.hypot(target[0] - rx, target[1] - ry), 1.0)
        r_des = gs * 2.0 * math.sin(alpha) / ld
        r_err = r_des - x[ix["r_radps"]]
        steer += 1.5 * r_err
        # differential braking where the nose wheel alone cannot hold the turn rate (as pilots do)
        self._diff_brake = clamp(4.0 * r_err, -0.4, 0.4) if gs > 1.0 else 0.0
        lim = math.radians(max_steer_deg)
        self._steer(clamp(steer, -lim, lim))
        v_t = v_max
        if abs(steer) > math.radians(15.0):  # hard steering: no faster than a turn
            v_t = self.prof.taxi_turn_kt * KT_MPS
        for sc in self.path.corners_s:
            if sc > s - 15.0:
                d = max(0.0, sc - s - 10.0)
                v_turn = self.prof.taxi_turn_kt * KT_MPS
                v_t = min(v_t, math.sqrt(v_turn**2 + 2 * TAXI_DECEL_MPS2 * d))
        return s, cross, v_t

    def _taxi(self, x, frame: RunwayFrame, at_end) -> None:
        gs = self._gs(x)
        s, cross, v_t = self._follow(x, frame, TAXI_STRAIGHT_MPS, max(12.0, 3.0 * gs), 70.0)
        if abs(cross) > 30.0:
            self._fail(f"left the taxiway: {cross:.0f} m from the taxi route")
        stops = self.path.stops
        if self._hold_until is not None:
            v_t = 0.0
            if self._t >= self._hold_until:
                self._hold_until = None
                self.ground_spd_pid.reset()
                if stops[self._stop_idx].name == "lineup":
                    at_end(x)
                    return
                self._stop_idx += 1
        elif self._stop_idx < len(stops):
            st = stops[self._stop_idx]
            d = st.s_m - s
            v_t = min(v_t, math.sqrt(max(0.0, 2 * TAXI_DECEL_MPS2 * (d - 2.0))))
            if d < 3.0 and gs < 0.3:
                self._hold_until = self._t + st.hold_s
                self._event("hold", f"{st.name} {st.hold_s:.0f} s")
        else:
            d = self.path.length_m - s
            v_t = min(v_t, math.sqrt(max(0.0, 2 * TAXI_DECEL_MPS2 * (d - 2.0))))
            if d < 3.0 and gs < 0.3:
                at_end(x)
                return
        self._speed_on_ground(gs, v_t)

    def _speed_on_ground(self, gs: float, v_t: float) -> None:
        err = v_t - gs
        thr = self.ground_spd_pid(err, self.dt)
        if v_t < 0.05:
            thr = 0.0
        self._throttle(thr)
        brake = 0.0
        if err < -0.8 or v_t < 0.05:
            brake = clamp(-0.3 * err, 0.15 if v_t < 0.05 else 0.0, 1.0)
        d = self._diff_brake
        self.ac.set("fcs/left-brake-cmd-norm", clamp(brake + max(0.0, -d), 0.0, 1.0))
        self.ac.set("fcs/right-brake-cmd-norm", clamp(brake + max(0.0, d), 0.0, 1.0))

    def _ph_taxi_out(self, x) -> None:
        if self._hold_until is None and self.flaps == 0.0:
            self._flaps(self.plan.takeoff_flaps_norm or self.prof.takeoff_flaps_norm)
        self._taxi(x, self.origin, self._lineup_done)

    def _lineup_done(self, x) -> None:
        self._set_phase("takeoff_roll")
        self.brake_pid.reset()
        self._brakes(0.0)
        self._throttle(self.plan.takeoff_thrust_norm)
        self.theta_cmd = x[self.ix["theta_rad"]]
        self.pitch_pid.reset()

    # ------------------------------------------------------------------ takeoff and air
    def _runway_track(self, x, frame: RunwayFrame) -> None:
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
        self._steer(clamp(2.0 * psi_err - 1.0 * r, -steer_lim, steer_lim))
        # JSBSim convention: positive rudder command yaws the nose left (checked in flight for all
        # four models), the opposite of the nose wheel's positive-right steering angle
        self.ac.set("fcs/rudder-cmd-norm", clamp(-(4.0 * psi_err - 3.0 * r), -1.0, 1.0))

    def _ph_takeoff_roll(self, x) -> None:
        ix = self.ix
        self._runway_track(x, self.origin)
        ias = x[ix["ias_mps"]]
        self._bank_to(x, 0.0)
        if ias >= self.prof.vr_kt * KT_MPS:
            if "rotate" not in (e[1] for e in self.events):
                self._event("rotate", f"{ias / KT_MPS:.0f} kt")
            self.theta_cmd = rate_limit(self.theta_cmd, math.radians(self.prof.rotate_pitch_deg), math.radians(3.0) * self.dt)
            # nose-up elevator bias while the mains still carry the aircraft (rotation)
            self._pitch_to(x, self.theta_cmd, bias=self.prof.rotate_elevator)
        else:
            self.ac.set("fcs/elevator-cmd-norm", 0.0)
        if x[ix["wow"]] < 0.5 and x[ix["agl_m"]] > self.prof.cg_height_m + 1.0:
            self._t_liftoff = self._t
            self._event("liftoff", f"{ias / KT_MPS:.1f} kt")
            self._steer(0.0)
            self.ac.set("fcs/rudder-cmd-norm", 0.0)
            # hand the rotation bias over to the pitch integrator so the elevator does not jump
            self.pitch_pid.integral += self.prof.rotate_elevator / self.pitch_pid.ki
            self.climb_spd_pid.reset(integral=x[ix["theta_rad"]] / self.climb_spd_pid.ki)
            self._set_phase("initial_climb")

    def _distance_to_go_m(self, x) -> float:
        lat, lon = x[self.ix["lat_deg"]], x[self.ix["lon_deg"]]
        if self._loc_mode:
            rx, _ = self.dest.to_xy(lat, lon)
            return -rx
        wp = self._waypoints[self._wp]
        return geodesy.gc_distance_m(lat, lon, *wp) + self._legs_after_m[self._wp]

    def _path_alt_m(self, d_m: float) -> float:
        """The vertical profile: glideslope inside 10 nm, the descent path beyond."""
        elev = self.plan.destination.elevation_m
        gs = math.tan(math.radians(self.plan.glideslope_deg))
        d_gs = 10.0 * NM_M
        d_m = max(d_m, -TOUCHDOWN_AIM_M)
        if d_m <= d_gs:
            return elev + gs * (d_m + TOUCHDOWN_AIM_M)
        return elev + gs * (d_gs + TOUCHDOWN_AIM_M) + math.tan(math.radians(self.plan.descent_angle_deg)) * (d_m - d_gs)

    def _lateral(self, x) -> None:
        ix = self.ix
        lat, lon = x[ix["lat_deg"]], x[ix["lon_deg"]]
        agl = x[ix["agl_m"]]
        if self.phase == "initial_climb" and agl < 400 * FT_M:
            self._heading_to(x, self.origin.heading_rad, 5.0)
            return
        if not self._loc_mode:
            wp = self._waypoints[self._wp]
            d = geodesy.gc_distance_m(lat, lon, *wp)
            if self._wp == len(self._waypoints) - 1:
                # approach fix: engage the localizer once close, or once abeam inside the cone
                rx, ry = self.dest.to_xy(lat, lon)
                hdg_err = abs((x[ix["psi_rad"]] - self.dest.heading_rad + math.pi) % (2 * math.pi) - math.pi)
                inside_cone = -(self.plan.approach_fix_nm + 2.0) * NM_M < rx < -3.0 * NM_M and abs(ry) < 1.5 * NM_M
                if (d < 2.5 * NM_M or inside_cone) and hdg_err < math.radians(75.0):
                    self._loc_mode = True
                    self._event("localizer_capture")
                    self._set_phase("approach")
            elif d < 2.0 * NM_M:
                self._wp += 1
                self._event("waypoint", f"{self._wp}")
            if not self._loc_mode:
                crs = geodesy.gc_course_rad(lat, lon, *wp)
                self._heading_to(x, crs, self.prof.turn_bank_deg)
                return
        rx, ry = self.dest.to_xy(lat, lon)
        look = max(1500.0, min(6000.0, -rx * 0.25))
        crs = self.dest.heading_rad - math.atan2(ry, look)
        bank = self.prof.turn_bank_deg if x[ix["agl_m"]] > 500 * FT_M else 8.0
        self._heading_to(x, crs, bank)

    def _speed_target_mps(self, x, d_m: float) -> float:
        p = self.prof
        ix = self.ix
        alt_ft = x[ix["alt_m"]] / FT_M
        ias = x[ix["ias_mps"]]
        mach = max(x[ix["mach"]], 0.05)
        if self.phase in ("initial_climb", "climb"):
            v = 250.0 if alt_ft < 10000.0 else p.climb_ias_kt
        else:
            v = 250.0 if alt_ft < 10500.0 else p.descent_ias_kt
        v *= KT_MPS
        v = min(v, ias / mach * self.plan.cruise_mach)  # Mach limit above the crossover
        for step in p.approach_steps:
            if d_m < step.dist_nm * NM_M and self.phase in ("descent", "approach", "cruise"):
                final = step is p.approach_steps[-1]
                v = min(v, self._vapp_mps() if final else step.speed_kt * KT_MPS)
        return v

    def _vapp_mps(self) -> float:
        """Final approach speed for the current mass (stall speed scales with sqrt(mass))."""
        mass_kg = self.ac.get("inertia/weight-lbs") * 0.45359237
        k = clamp(math.sqrt(mass_kg / self.prof.ref_landing_mass_kg), 0.95, 1.1)
        return self.prof.vapp_kt * k * KT_MPS

    def _configure_approach(self, d_m: float, ias_mps: float) -> None:
        for step in self.prof.approach_steps:
            # a setting is selected inside its distance gate once slow enough for it: within 10 kt
            # of its own speed (these models' flaps give so much lift that, selected fast on a light
            # aircraft, they drive the angle of attack negative and the pitch loop porpoises)
            limit_kt = step.speed_kt + 10.0
            if d_m < step.dist_nm * NM_M and ias_mps <= limit_kt * KT_MPS:
                flaps = step.flaps_norm
                if step.gear_down and self.ac.get("gear/gear-cmd-norm") < 0.5:
                    self.ac.set("gear/gear-cmd-norm", 1.0)
                    self._event("gear_down")
                if flaps > self.flaps:
                    landing = self.plan.landing_flaps_norm
                    self._flaps(min(flaps, landing) if landing is not None and step is self.prof.approach_steps[-1] else flaps)

    def _ph_initial_climb(self, x) -> None:
        ix = self.ix
        p = self.prof
        agl = x[ix["agl_m"]]
        ias = x[ix["ias_mps"]]
        if self.ac.get("gear/gear-cmd-norm") > 0.5 and agl > 15.0 and -x[ix["v_down_mps"]] > 1.0:
            self.ac.set("gear/gear-cmd-norm", 0.0)
            self._event("gear_up")
        # V2 + 20 kt to the acceleration height (1500 ft), then accelerate while still climbing:
        # the speed target ramps up at 1.5 kt/s (no level-off), thrust back to climb thrust
        target = (p.v2_kt + 20.0) * KT_MPS
        if agl > ACCEL_HEIGHT_FT * FT_M:
            if self._t_accel is None:
                self._t_accel = self._t
                self._throttle(p.climb_throttle)
                self._event("acceleration_height")
            target = min(250.0, p.v2_kt + 20.0 + 1.5 * (self._t - self._t_accel)) * KT_MPS
        self._speed_on_pitch(x, target, lo_deg=5.0, hi_deg=15.0)
        for v_kt, fl in p.flap_retract_kt:
            if ias > v_kt * KT_MPS and fl < self.flaps and agl > ACCEL_HEIGHT_FT * FT_M:
                self._flaps(fl)
        self._lateral(x)
        if agl > 3000 * FT_M or (x[ix["alt_m"]] > self.plan.cruise_alt_m - 150.0):
            self._set_phase("climb")

    def _speed_on_pitch(self, x, target_mps: float, lo_deg: float, hi_deg: float) -> None:
        """Too fast -> pitch up: PI from IAS error to the pitch command (integrator = trim pitch)."""
        ix = self.ix
        err = x[ix["ias_mps"]] - target_mps
        theta = self.climb_spd_pid(err, self.dt)
        theta = clamp(theta, math.radians(lo_deg), math.radians(hi_deg))
        # pitch rate at most 0.6 deg/s once established (about 0.15 g at climb speeds: comfort);
        # 2 deg/s in the initial climb, where the speeds are low
        rate = 2.0 if self.phase == "initial_climb" else 0.6
        self.theta_cmd = rate_limit(self.theta_cmd, theta, math.radians(rate) * self.dt)
        self._pitch_to(x, self.theta_cmd)

    def _path_to(
        self, x, vs_cmd: float, lo_deg: float, hi_deg: float, rate_dps: float = 3.0, boost: float = 0.0
    ) -> None:
        """Vertical speed -> flight-path angle error -> pitch (PI; the integrator is trim pitch)."""
        ix = self.ix
        tas = max(x[ix["tas_mps"]], 30.0)
        gamma_cmd = math.asin(clamp(vs_cmd / tas, -0.3, 0.3))
        gamma = math.asin(clamp(-x[ix["v_down_mps"]] / tas, -0.5, 0.5))
        # the pitch limits are the PID's own output limits, so its integrator cannot wind up
        # against them (it did, holding attitude on short final, and then the flare was late)
        self.gamma_pid.lo, self.gamma_pid.hi = math.radians(lo_deg), math.radians(hi_deg)
        theta = self.gamma_pid(gamma_cmd - gamma, self.dt) + boost * (gamma_cmd - gamma)
        theta = clamp(theta, math.radians(lo_deg), math.radians(hi_deg))
        self.theta_cmd = rate_limit(self.theta_cmd, theta, math.radians(rate_dps) * self.dt)
        self._pitch_to(x, self.theta_cmd)

    def _set_throttle_smooth(self, u: float) -> None:
        self._thr = rate_limit(self._thr, u, 0.15 * self.dt)
        self._throttle(self._thr)

    def _air(self, x) -> None:
        """Climb, cruise, descent and approach: one set of loops, targets by phase and distance."""
        ix = self.ix
        p = self.prof
        d = self._distance_to_go_m(x)
        h = x[ix["alt_m"]]
        h_tgt = min(self.plan.cruise_alt_m, self._path_alt_m(d))
        # speed target changes at most 1 kt/s (no step at 10,000 ft or at the approach gates)
        v_new = self._speed_target_mps(x, d)
        if self._v_tgt is None:
            self._v_tgt = v_new
        self._v_tgt = rate_limit(self._v_tgt, v_new, KT_MPS * self.dt)
        v_tgt = self._v_tgt
        self._lateral(x)
        for v_kt, fl in p.flap_retract_kt:
            if x[ix["ias_mps"]] > v_kt * KT_MPS and fl < self.flaps and self.phase == "climb":
                self._flaps(fl)
        if self.phase == "climb" and h < h_tgt - 250.0:
            self._throttle(p.climb_throttle)
            self._thr = p.climb_throttle
            self._speed_on_pitch(x, v_tgt, lo_deg=0.0, hi_deg=15.0)
            self.spd_pid.reset(integral=p.climb_throttle / p.spd_ki)
            self.gamma_pid.reset(integral=x[ix["theta_rad"]] / self.gamma_pid.ki)
            return
        if self.phase == "climb":
            self._set_phase("cruise")
        if self.phase == "cruise" and h_tgt < self.plan.cruise_alt_m - 1.0:
            self._set_phase("descent")
        if self.phase in ("descent", "approach"):
            self._configure_approach(d, x[ix["ias_mps"]])
        # vertical: altitude error -> vertical speed -> flight-path angle -> pitch
        gs = self._gs(x)
        on_path = h_tgt < self.plan.cruise_alt_m
        slope = (self._path_alt_m(d) - self._path_alt_m(d - 100.0)) / 100.0 if on_path else 0.0
        vs_ff = -gs * slope
        if self._loc_mode:
            vs_cmd = clamp(vs_ff + 0.1 * (h_tgt - h), -8.0, 3.0)
        else:
            vs_cmd = clamp(vs_ff + 0.05 * (h_tgt - h), -15.0, 10.0)
        # vertical acceleration at most 0.8 m/s^2 (< 0.1 g): smooth top of descent and level-offs
        if self._vs_cmd is None:
            self._vs_cmd = -x[ix["v_down_mps"]]
        self._vs_cmd = rate_limit(self._vs_cmd, vs_cmd, 0.8 * self.dt)
        vs_cmd = self._vs_cmd
        lo_deg = -8.0
        mg = x[ix["agl_m"]] - p.cg_height_m
        if self._loc_mode and mg < 200 * FT_M:
            # short final: hold the stabilised attitude (no diving into ground effect)
            if self._theta_final is None:
                self._theta_final = math.degrees(x[ix["theta_rad"]])
            lo_deg = self._theta_final - 1.0
        self._path_to(x, vs_cmd, lo_deg, 15.0, rate_dps=1.5 if self._loc_mode else 1.0)
        # speed: throttle, speedbrake when idle is not enough
        err = v_tgt - x[ix["ias_mps"]]
        thr = self.spd_pid(err, self.dt)
        self._set_throttle_smooth(thr)
        agl = x[ix["agl_m"]]
        sb = clamp((-err - 4.0) / 10.0, 0.0, 1.0) if thr <= 0.01 and agl > 1000 * FT_M else 0.0
        self.ac.set("fcs/speedbrake-cmd-norm", sb)
        if self._loc_mode:
            mg = agl - p.cg_height_m
            if mg < p.flare_height_ft * FT_M:
                self._set_phase("flare")

    _ph_climb = _air
    _ph_cruise = _air
    _ph_descent = _air
    _ph_approach = _air

    def _ph_flare(self, x) -> None:
        """Exponential flare: sink rate commanded as (h + h_b) / tau, continuous at flare entry, so
        the touchdown sink rate tends to h_b / tau (h: main-gear height)."""
        ix = self.ix
        p = self.prof
        mg_ft = (x[ix["agl_m"]] - p.cg_height_m) / FT_M
        if self._flare_tau is None:
            sink0_fps = max(x[ix["v_down_mps"]] / FT_M, 5.0)
            self._flare_tau = (mg_ft + FLARE_HB_FT) / sink0_fps
            self.gamma_pid.reset(integral=x[ix["theta_rad"]] / self.gamma_pid.ki)  # bumpless
        vs_cmd = -max(p.touchdown_sink_fps, (mg_ft + FLARE_HB_FT) / self._flare_tau) * FT_M
        vs_cmd = min(vs_cmd, -p.touchdown_sink_fps * FT_M)
        lo_deg = -3.0 if self._theta_final is None else self._theta_final - 1.0
        self._path_to(x, vs_cmd, lo_deg, 12.0, rate_dps=5.0, boost=2.0)
        self._set_throttle_smooth(0.0 if mg_ft < 20.0 else self.spd_pid(self._vapp_mps() - x[ix["ias_mps"]], self.dt))
        rx, ry = self.dest.to_xy(x[ix["lat_deg"]], x[ix["lon_deg"]])
        crs = self.dest.heading_rad - math.atan2(ry, 1500.0)
        self._heading_to(x, crs, 5.0)
        if x[ix["wow"]] > 0.5:
            self._event("touchdown", f"sink {x[ix['v_down_mps']] / FT_M * 60:.0f} fpm at {rx:.0f} m")
            if x[ix["v_down_mps"]] / FT_M > MAX_SINK_FPS:
                self._fail(f"hard landing: touchdown sink rate {x[ix['v_down_mps']] / FT_M:.1f} ft/s exceeds {MAX_SINK_FPS:.0f} ft/s")
            self._set_phase("rollout")
            self.ac.set("fcs/speedbrake-cmd-norm", 1.0)
            self.ac.set("fcs/spoiler-cmd-norm", 1.0)
            self._rev_thr = p.reverse_throttle
            self.brake_pid.reset()

    def _ph_rollout(self, x) -> None:
        ix = self.ix
        p = self.prof
        self._runway_track(x, self.dest)
        self.ac.set("fcs/aileron-cmd-norm", 0.0)
        self.theta_cmd = rate_limit(self.theta_cmd, math.radians(-1.0), math.radians(2.0) * self.dt)
        if x[ix["theta_rad"]] > math.radians(0.5):
            self._pitch_to(x, self.theta_cmd)
        else:
            self.ac.set("fcs/elevator-cmd-norm", 0.2)
        gs = self._gs(x)
        nose_down = x[ix["theta_rad"]] < math.radians(1.5)
        rev = nose_down and gs > 70.0 * KT_MPS
        for i in range(p.n_engines):
            self.ac.set(f"propulsion/engine[{i}]/reverser-angle-rad", math.pi if rev else 0.0)
        # reverse thrust is trimmed down when it alone decelerates harder than the autobrake target
        target = self.plan.autobrake_decel_mps2
        self._rev_thr = clamp(self._rev_thr + 0.5 * self.dt * (target - self._decel_f), 0.0, p.reverse_throttle)
        self._throttle(self._rev_thr if rev else 0.0)
        if nose_down:
            u = self.brake_pid(target - self._decel_f, self.dt)
            self._brakes(u)
        if gs < 20.0 * KT_MPS:
            rx, _ = self.dest.to_xy(x[ix["lat_deg"]], x[ix["lon_deg"]])
            self.ac.set("fcs/speedbrake-cmd-norm", 0.0)
            self.ac.set("fcs/spoiler-cmd-norm", 0.0)
            self.ac.set("fcs/rudder-cmd-norm", 0.0)
            self.ac.set("fcs/elevator-cmd-norm", 0.0)
            self._flaps(0.0)
            self.path = taxi_in_path(self.plan.taxi_in, rx)
            self._stop_idx = 0
            self.ground_spd_pid.reset()
            self._set_phase("taxi_in")

    def _ph_taxi_in(self, x) -> None:
        self._taxi(x, self.dest, self._at_stand)

    def _at_stand(self, x) -> None:
        self._brakes(1.0)
        self._throttle(0.0)
        self._steer(0.0)
        self.ac.set("propulsion/active_engine", -1)
        self.ac.set("propulsion/cutoff_cmd", 1)
        self._set_phase("shutdown")

    def _ph_shutdown(self, x) -> None:
        self._brakes(1.0)
        # engines off: every N2 below 5 % after fuel cut-off (the end of the seed's flight time)
        if all(x[self.ix[f"n2_pct_{i}"]] < 5.0 for i in range(self.prof.n_engines)):
            self._event("engines_off")
            self._t_off = self._t
            self._set_phase("parked")

    def _ph_parked(self, x) -> None:
        self._brakes(1.0)
        if self._t - self._t_off >= self.plan.post_shutdown_s:
            self.done = True


# MIL-F-8785C probability-of-exceedance index (JSBSim milspec severity) and 20 ft wind (kt) per
# severity code: light 1e-3 / 15 kt, moderate 1e-5 / 30 kt, severe 1e-6 / 45 kt. Chosen so that the
# A320 at FL360 meets the ICAO/FAA intensity definitions (FACTS.md) at its centre of gravity: peak
# load-factor change in a 4-minute segment 0.25 g (light, < 0.5 g), 0.79 g (moderate, 0.5-1.0 g),
# 1.14 g (severe, > 1.0 g). The handbook's own 1e-2 / 1e-3 / 1e-5 gave only 0.02 / 0.22 / 0.73 g
# at cruise altitude (its 1e-2 curve vanishes above about 30,000 ft).
MILSPEC = {1: (4, 15.0), 2: (6, 30.0), 3: (7, 45.0)}
