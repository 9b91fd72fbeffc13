"""The go-around from the flare and the circuit back to the localizer, flown as the go-around modes of
airliner flight directors fly it (Airbus SRS, Boeing TO/GA: Boeing 737 FCTM, Airbus A320 FCOM)."""

from __future__ import annotations

import math

from flightmode.sim.flight.pilot.control import rate_limit
from flightmode.sim.flight.pilot.energy import EnergyRateThrottle
from flightmode.sim.flight.pilot.enroute import EnRoute
from flightmode.units import FPM_MPS, FT_M, KT_MPS, NM_M

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
