"""Climb, cruise, descent and approach: one controller whose targets follow the phase and the
distance to go (the step climbs: :mod:`flightmode.sim.flight.pilot.step_climb`)."""

from __future__ import annotations

import math

from flightmode.sim.flight.pilot.control import clamp, first_order_lag, rate_limit
from flightmode.sim.flight.pilot.controller import Controller
from flightmode.sim.flight.pilot.flare import FLOAT_LIMIT_FRACTION, flare_start_height_m
from flightmode.sim.flight.pilot.step_climb import STEP_MIN_CRUISE_S, STEP_VS_MPS, next_level_m
from flightmode.units import FT_M, KT_MPS

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


STEP_CHECK_S = 60.0  # how often the cruise checks whether a step climb is due


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
            # the weight the first cruise level is taken as optimum for (sim.flight.pilot.step_climb)
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
        """Raise the cruise level by one step when it is due (:mod:`flightmode.sim.flight.pilot.step_climb`)
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
