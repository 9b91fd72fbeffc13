"""Per-type speeds, flap schedules, geometry, procedures and gains: the one table the pilot flies
from (the controllers in :mod:`flightmode.sim.flight.controllers` hold no numbers of their own).

Speeds are chosen inside OpenAP WRAP's real-traffic ranges for the type (OpenAP's ``WRAP`` kinematic
model, built from ADS-B) and the type's published figures; gains were tuned on these JSBSim models.
Flap commands are ``fcs/flap-cmd-norm`` values of the JSBSim model (737: detents
1,2,5,10,15,25,30,40 at 1/8 steps; A320 and 787-8: degrees / full travel (40 and 35 deg);
fokker100: degrees / 42).
"""

from __future__ import annotations

from dataclasses import dataclass, field

from flightmode.errors import AircraftError, did_you_mean
from flightmode.units import FT_M, G0_MPS2, KT_MPS


@dataclass(frozen=True, slots=True)
class PilotTuning:
    """The pilot's procedures, limits and loop gains (the same for every type unless a profile sets
    its own). PID tuples are (kp, ki, kd, lo, hi) in the units named."""

    # taxi (sim.flight.taxi_route.draw_taxi draws each flight's values inside these (lo, hi) ranges).
    # "ADS-B": the six real taxi segments of sim.flight.taxi_stats.ADSB_TAXI_ANCHORS.
    # Straight taxiway speed: ADS-B speed p90 8.7-10.2 m/s taxi-out, 5.4-7.8 m/s taxi-in; the OpenAP
    # A320 QAR sample's medians 14 kt out, 11 kt in; all under the A320 FCOM's 30 kt and the
    # "about 20 kt" of the Boeing 737 FCTM
    taxi_speed_out_mps: tuple = (7.5, 10.0)
    taxi_speed_in_mps: tuple = (5.5, 8.0)
    # apron taxilanes and stand lead-ins, where most of a taxi-in's turns are: ADS-B median speed in
    # turns 3.6-5.7 m/s (median of the six 4.2), taxi-in speed p50 2.7-4.2 m/s; at 3.5-5.0 m/s, 20
    # flown A320 routes turned at 3.6-3.8 m/s (medians of taxi-out and taxi-in)
    taxi_apron_speed_mps: tuple = (4.0, 5.5)
    # turns: lateral acceleration 0.10-0.13 g, below the 0.134 g of the ICAO Doc 9157 curve table;
    # yaw rate at most 7-10 deg/s (ADS-B yaw-rate maxima 4.8-9.1 deg/s, median 6.9, never above 12:
    # the flown maxima come out about a quarter under the limit, pure pursuit rounding the turns)
    taxi_lat_acc_mps2: tuple = (0.10 * G0_MPS2, 0.13 * G0_MPS2)
    taxi_yaw_rate_max_dps: tuple = (7.0, 10.0)
    # slowing before turns and stops, and the rollout's last deceleration: 0.03-0.05 g (ADS-B largest
    # braking 0.029-0.062 g, 9 s smoothed); speeding up 0.02-0.04 g (ADS-B largest 0.014-0.047 g)
    taxi_decel_mps2: tuple = (0.03 * G0_MPS2, 0.05 * G0_MPS2)
    taxi_accel_mps2: tuple = (0.02 * G0_MPS2, 0.04 * G0_MPS2)
    # turns per minute of taxi, drawn per segment (sim.flight.taxi_route.turn_count): the ADS-B tracks'
    # 0.425-0.833 narrowed by a tenth at each end, the error of the expected duration the count is made
    # for (sim.flight.taxi_route.TAXI_TIME_FIT): drawn at 0.45-0.80, 7 of 40 flown segments of a
    # european-trio population fell outside the real range (0.37-0.41 and 0.86-0.87)
    taxi_turns_per_min: tuple = (0.47, 0.76)
    # taxi speed loop: brakes from the deceleration wanted over the brakes' gain (deceleration per unit
    # brake command, measured at 10 m/s: JSBSim 737 7.0 m/s^2, A320 4.2), plus a PI on the over-speed;
    # the command moves at most 0.05/s while rolling (0.35 m/s^3 on the 737: no deceleration step),
    # 1/s at a standstill
    taxi_brake_mps2: float = 7.0
    taxi_brake_max_mps2: float = 0.06 * G0_MPS2  # the most the taxi brakes ask for (ADS-B: 0.03-0.06 g)
    taxi_brake_pi: tuple = (0.03, 0.01)  # over-speed (m/s) -> brake command
    taxi_brake_rate: tuple = (0.05, 0.1, 1.0)  # per second: applying, releasing, at a standstill
    taxi_hold_brake: float = 0.5  # standing at a hold
    taxi_ref_tau_s: float = 2.0  # the taxi speed reference's lag (sim.flight.controllers.Taxi)
    # path following: pure-pursuit look-ahead (s of travel, at least 12 m) and nose-wheel angle limit
    taxi_lookahead_s: float = 2.5
    taxi_max_steer_deg: float = 40.0
    rollout_ease_mps3: float = 0.3  # the autobrake's deceleration eases to the taxi deceleration at this rate
    rollout_settle_mps: float = 2.0  # and has settled there this much above the exit speed (3-5 s before it)
    pushback_mps: float = 1.2  # a tug's pushing speed
    pushback_decel_mps2: float = (
        0.2  # the tug starts the push and stops it at the end of its turn this gently
    )
    accel_height_m: float = 1500.0 * FT_M  # thrust reduction and acceleration height after takeoff
    climb_out_m: float = 3000.0 * FT_M  # above the runway: initial climb ends, the climb begins
    speed_limit_alt_m: float = 10_000.0 * FT_M  # 250 kt below FL100 (ICAO Annex 11, Appendix 4)
    speed_limit_mps: float = 250.0 * KT_MPS
    touchdown_aim_m: float = 300.0  # glideslope origin past the threshold (50 ft crossing at 3 deg)
    exit_speed_mps: float = 20.0 * KT_MPS  # rollout ends, taxi-in begins
    # limits: exceeding one fails the flight (FlightDivergedError)
    max_bank_deg: float = 45.0
    # a touchdown over 14 CFR 25.473(a)'s 10 ft/s design sink is a hard landing (inspected, A320 AMM), not a
    # crash: the gear may not fail up to 12 ft/s, its reserve-energy sink (14 CFR 25.723(b)). Over 12 the
    # flight fails. At 10 it failed 4-6 of 28 hard pattern landings of the 737 and 787-8 at 10.5-11.9 ft/s
    # (2.3-3.0 g at the CG), which now land; one 787-8 at 13.6 ft/s still fails
    max_touchdown_sink_mps: float = 12.0 * FT_M
    # loop gains
    climb_speed_pid: tuple = (
        0.008,
        0.001,
        0.04,
        -0.1,
        0.35,
    )  # IAS error (m/s) -> pitch (rad); kd damps the phugoid
    path_pid: tuple = (1.0, 0.15, 0.0, -0.2, 0.35)  # flight-path angle error (rad) -> pitch (rad)
    ground_speed_pid: tuple = (0.08, 0.02, 0.0)  # ground speed error (m/s) -> throttle (to taxi_throttle_max)
    tug_pid: tuple = (20000.0, 4000.0, 0.0, -60000.0, 60000.0)  # speed error (m/s) -> tug force (lbf)
    brake_pid: tuple = (0.5, 0.3, 0.0, 0.0, 1.0)  # deceleration error (m/s^2) -> brake command


@dataclass(frozen=True, slots=True)
class Spread:
    """A figure's real-traffic distribution as OpenAP WRAP gives it: mean, standard deviation and
    the [minimum, maximum] it reports (draws are clipped to that range)."""

    mean: float
    std: float
    lo: float
    hi: float

    def draw(self, rng) -> float:
        return float(min(self.hi, max(self.lo, rng.normal(self.mean, self.std))))


@dataclass(frozen=True, slots=True)
class ClimbSchedule:
    """The climb of a type in three bands, from OpenAP's WRAP kinematic model (Sun, Ellerbroek and
    Hoekstra, "WRAP: An open-source kinematic aircraft performance model", Transportation Research
    Part C 98, 2019, fitted on ADS-B): vertical rate below the constant-CAS crossover altitude
    (``climb_vs_pre_concas``), in the constant-CAS climb (``climb_vs_concas``) and in the constant-Mach
    climb (``climb_vs_conmach``), the crossover altitudes and the climb CAS. Each flight draws its
    three rates from these spreads."""

    vs_pre_cas: Spread  # m/s, up to cross_cas_m
    vs_cas: Spread  # m/s, cross_cas_m to cross_mach_m
    vs_mach: Spread  # m/s, above cross_mach_m
    cross_cas_m: float
    cross_mach_m: float
    cas_mps: float  # constant-CAS climb speed (above 10,000 ft)
    vs_initial: Spread  # m/s, liftoff to 1,500 ft (WRAP ``initclimb_vs``)


@dataclass(frozen=True, slots=True)
class TakeoffThrust:
    """How hard a type accelerates down the runway, and the throttle that gives it.

    ``accel`` is WRAP's takeoff acceleration (``takeoff_acceleration``: the mean from brake release to
    liftoff on real ADS-B traffic; Sun, Ellerbroek and Hoekstra 2019, as :class:`ClimbSchedule`); each
    flight draws its own from it (:mod:`flightmode.sim.flight.draws`). ``curve`` is the model's answer:
    (takeoff throttle, mean acceleration brake release to liftoff in m/s^2) measured on the JSBSim
    model at ``mass_kg`` and a field air density ``rho_kgm3``. At brake release the pilot turns the
    drawn acceleration into a throttle (:meth:`throttle_for`), as a crew's takeoff performance is
    computed for the actual weight and field: the acceleration is scaled to the curve's conditions by
    ``(mass / mass_kg) ** mass_exp`` (measured on each model with 4-20 t more fuel at 0.90 throttle;
    the A320's fitted on route flights) and by the density ratio (:data:`TAKEOFF_DENSITY_EXP`), then
    interpolated on the curve, clipped to its ends.

    The JSBSim models fly at their stock weights, without passengers: the 737 at 83,000 lb, the
    published operating empty weight of the 737-700 (37,648 kg); the Fokker 100 at 54,217 lb, within
    1 % of its published 24,375 kg; the A320 at 111,000 lb, 7.7 t above the A320ceo's typical 42.6 t
    (the manufacturers' figures as Wikipedia tabulates them); only the 787-8's model carries its
    passengers and cargo (22 t of point masses). With the real airline payload their
    approach speeds, already at the top of the real range, would rise further: measured on 12
    pattern flights each, 10.4 t more on the 737 (126 seats at IATA's 2019 82.6 % passenger load
    factor, 100 kg each) raised its median touchdown speed from 131 to 143 kt (and at the old speeds
    it stalled on approach, 3 of 12), 8.3 t more on the Fokker 100 from 152 to 156 kt. So a light
    aircraft at a deeper reduced thrust stands in for a loaded one at its usual flex thrust: the
    thrust-to-weight ratio, which sets the acceleration the accelerometer records, is the real one."""

    accel: Spread  # m/s^2, WRAP takeoff_acceleration
    curve: tuple[tuple[float, float], ...]  # (throttle, m/s^2), throttle increasing
    mass_kg: float  # the curve's mass at brake release
    rho_kgm3: float  # the curve's field air density
    mass_exp: float  # mean acceleration ~ mass ** -mass_exp near the curve's mass

    def throttle_for(
        self, accel_mps2: float, mass_kg: float | None = None, rho_kgm3: float | None = None
    ) -> float:
        """The throttle that gives a mean acceleration ``accel_mps2`` brake release to liftoff at this
        mass and field density (the curve's when None)."""
        import numpy as np

        a = accel_mps2
        if mass_kg is not None:
            a *= (mass_kg / self.mass_kg) ** self.mass_exp
        if rho_kgm3 is not None:
            a *= (self.rho_kgm3 / rho_kgm3) ** TAKEOFF_DENSITY_EXP
        thr, acc = zip(*self.curve)
        return float(np.interp(a, acc, thr))


# the mean takeoff acceleration scales with the field's air density to this power: measured on the
# pattern flown at 10 and 900 m field elevation (density 1.224 and 1.122 kg/m^3) at 0.90 throttle:
# A320 1.05, 737 0.91, Fokker 100 0.90 (the engines' thrust lapse with density)
TAKEOFF_DENSITY_EXP = 0.95


@dataclass(frozen=True, slots=True)
class ApproachStep:
    """At ``dist_nm`` to the threshold: select ``flaps_norm`` (and gear if ``gear_down``) and slow to ``speed_kt``."""

    dist_nm: float
    flaps_norm: float
    speed_kt: float
    gear_down: bool = False


FLARE_LAWS = ("constant_deceleration", "exponential")  # sim.flight.controllers.Flare


@dataclass(frozen=True, slots=True)
class AircraftProfile:
    model: str  # JSBSim aircraft directory
    description: str
    wrap_type: str  # OpenAP WRAP type used to check this model's kinematics
    n_engines: int
    length_m: float
    wingspan_m: float
    cg_height_m: float  # settled reference height on the gear (JSBSim ground trim, measured)
    wheelbase_m: float
    fuel_kg: float  # the least loaded at the gate (sim.flight.simulate.planned_fuel_kg adds trip fuel), over the tanks by capacity
    vr_kt: float  # rotation speed; at vr_ref_mass_kg when that is set, scaled by sqrt(mass / ref)
    v2_kt: float  # takeoff safety speed; at vr_ref_mass_kg when that is set, scaled as vr_kt
    descent_ias_kt: float
    vapp_kt: float  # final approach speed at ref_landing_mass_kg; scaled by sqrt(mass / ref)
    ref_landing_mass_kg: float
    rotate_pitch_deg: float
    takeoff_flaps_norm: float
    approach_steps: tuple[ApproachStep, ...]
    flap_retract_kt: tuple[tuple[float, float], ...]  # (IAS above which, flaps_norm)
    alpha_stall_deg: float
    climb_throttle: float
    taxi_throttle_max: float
    reverse_throttle: float
    flare_height_ft: float
    flare_pitch_kp: (
        float  # elevator (normalised) per rad of attitude error in the flare, on top of the pitch loop
    )
    climb: ClimbSchedule
    takeoff: TakeoffThrust
    # the flare guidance's pitch rate per missing upward acceleration, as a fraction of
    # sim.flight.controllers.FLARE_PITCH_GAIN
    flare_accel_gain: float = 1.0
    # the flare's guidance law (sim.flight.controllers.Flare), one of FLARE_LAWS
    flare_law: str = "constant_deceleration"
    # the constant-deceleration law's lag compensation (sim.flight.controllers.Flare._rate_decel): the
    # height above the runway at which it aims to reach the touchdown sink (m), and how far ahead (s) it
    # predicts the sink rate and height from the upward acceleration the aircraft has
    flare_aim_m: float = 2.0
    flare_predict_s: float = 0.0
    # begin the flare at flare_height_ft or, on an approach steeper than the glideslope (sink over
    # ground speed), at the same time to contact (sim.flight.controllers.flare_start_height_m)
    flare_at_time_to_contact: bool = False
    # the exponential law's proportional gain: attitude change per sink-rate error, times the true
    # airspeed (rad per rad of flight-path angle; sim.flight.controllers.FLARE_EXP_INTEGRAL_PER_S)
    flare_path_gain: float = 1.5
    # the exponential law's longest time constant (s; sim.flight.controllers.exponential_flare_tau_s):
    # a flare entered with little sink to lose (a firm or hard landing) is held at its entry sink until
    # h / tau_max falls under the sink it has to lose
    flare_tau_max_s: float = 6.0
    # the exponential law's attitude for the lift the flare loses as the speed bleeds at idle (rad;
    # sim.flight.controllers.Flare): this times ((V_0 / V)^2 - 1), V_0 the true airspeed at the flare height;
    # 0: none
    flare_lift_attitude_rad: float = 0.0
    # the main gear's height at which the flare pulls the thrust to idle ("retard")
    retard_height_ft: float = 20.0
    # the approach speed's wind additive (sim.flight.autopilot.Autopilot.vapp_mps): this fraction of
    # the wind at 20 ft (the flight's drawn surface wind, the boundary layer's gustiness) above the
    # additive that vapp_kt already holds (vapp_wind_included_kt), at most vapp_wind_max_kt in all
    vapp_wind_fraction: float = 0.0
    vapp_wind_included_kt: float = 0.0
    vapp_wind_max_kt: float = 0.0
    # the initial climb (sim.flight.controllers.InitialClimb): the speed held from liftoff to the
    # acceleration height, V2 plus this, and the most pitch the speed loop may command for it.
    # Boeing: "V2 + 15 to V2 + 25" with all engines (Boeing 737 FCTM, takeoff, initial climb), 20 here
    initial_climb_v2_add_kt: float = 20.0
    initial_climb_pitch_max_deg: float = 15.0
    # None: the speed loop takes the pitch from liftoff on; a pitch (deg): the rotation goes on after
    # liftoff toward it at 3 deg/s (the rotation's rate, sim.flight.controllers.TakeoffRoll) before the
    # speed loop takes over (sooner if the speed falls under V2)
    initial_climb_rotate_to_deg: float | None = None
    # True: from liftoff to the acceleration height the throttle may rise above the takeoff throttle
    # (to 1.0) to hold the flight's drawn initial rate of climb (climb.vs_initial) as an energy rate
    # (sim.flight.controllers.InitialClimb), for a model whose drag in the takeoff configuration is
    # too high for the thrust that gives the real takeoff acceleration
    initial_climb_thrust_for_rate: bool = False
    # the go-around's thrust (sim.flight.controllers.GoAround): None, the type's climb thrust at once
    # (Airbus TOGA, Fokker GA); a rate of climb (ft/min), Boeing's reduced go-around thrust, which the
    # autothrottle adjusts to hold that climb once the pitch has come up
    go_around_climb_fpm: float | None = None
    # the share of the flare's elevator the attitude loop keeps at touchdown (sim.flight.controllers.Rollout):
    # 0 relaxes it to the loop's own (half its integrator), 1 keeps it all
    touchdown_elevator_keep: float = 0.0
    # maximum operating altitude (type certificate data sheet): the highest step climb (sim.flight.step_climb)
    ceiling_ft: float = 37_000.0
    # the descent path's angle from cruise to the glideslope on flights between any two airports
    # (flightmode.scenarios.routes; a scenario file sets its own). One geometric path: the vertical rate
    # is the ground speed times its tangent, about 11.7 m/s at 2.8 deg in the constant-Mach band (240 m/s)
    # and 9-10 m/s at constant CAS, inside WRAP's A320 / B738 ranges (-13.5 / -12.7 m/s at most at
    # constant Mach, defaults -10.0 at constant CAS); the faster types fly shallower paths (their profiles)
    descent_angle_deg: float = 2.8
    # flights between any two airports (flightmode.scenarios.routes): the type's usual cruise level
    # and Mach (OpenAP WRAP ``cruise_alt`` / ``cruise_mach`` defaults where WRAP has the type), its
    # range (OpenAP ``prop.aircraft`` "cruise.range"), and the shortest paved runway it is sent to
    # (the manufacturer's airport-planning take-off field length at MTOW, ISA, sea level, rounded)
    cruise_level_ft: float = 35_000.0
    cruise_mach: float = 0.78
    range_km: float = 4600.0
    min_runway_m: float = 2100.0
    # mean fuel flow gate to gate, kg/h, for the fuel plan (sim.flight.simulate.planned_fuel_kg)
    burn_kg_per_h: float = 2600.0
    # attitude and speed loop gains (flightmode.sim.flight.autopilot)
    pitch_kp: float = 2.0
    pitch_ki: float = 0.6
    pitch_kq: float = 1.2
    roll_kp: float = 1.5
    roll_kp_p: float = 0.4
    spd_kp: float = 0.05  # throttle per m/s of speed error
    spd_ki: float = 0.005
    turn_bank_deg: float = 25.0
    cabin_half_width_m: float = 1.8

    def __post_init__(self) -> None:
        if self.flare_law not in FLARE_LAWS:
            raise AircraftError(
                f"aircraft profile '{self.model}': unknown flare_law {self.flare_law!r}; "
                f"use one of {', '.join(FLARE_LAWS)}"
            )
        if not self.flare_lift_attitude_rad >= 0.0:
            raise AircraftError(
                f"aircraft profile '{self.model}': flare_lift_attitude_rad "
                f"{self.flare_lift_attitude_rad:g} must not be negative (0: no attitude "
                "for the lift lost as the speed bleeds)"
            )
        if self.flare_aim_m < 0.0 or self.flare_predict_s < 0.0:
            raise AircraftError(
                f"aircraft profile '{self.model}': flare_aim_m {self.flare_aim_m:g} and "
                f"flare_predict_s {self.flare_predict_s:g} must not be negative"
            )
        if not self.flare_height_ft > 0.0:
            raise AircraftError(
                f"aircraft profile '{self.model}': flare_height_ft {self.flare_height_ft:g} "
                "is not a height; give the main gear's height (ft) at which the flare begins"
            )
        if self.retard_height_ft < 0.0:
            raise AircraftError(
                f"aircraft profile '{self.model}': retard_height_ft {self.retard_height_ft:g} is "
                "negative; give the main gear's height (ft) at which the flare pulls the thrust to idle"
            )
        if self.go_around_climb_fpm is not None and not self.go_around_climb_fpm > 0.0:
            raise AircraftError(
                f"aircraft profile '{self.model}': go_around_climb_fpm {self.go_around_climb_fpm:g} "
                "is not a climb; give a positive rate (ft/min), or None for climb thrust"
            )
        if not (
            0.0 <= self.vapp_wind_fraction <= 1.0
            and 0.0 <= self.vapp_wind_included_kt <= self.vapp_wind_max_kt
        ):
            raise AircraftError(
                f"aircraft profile '{self.model}': the approach wind additive needs 0 <= "
                "vapp_wind_fraction <= 1 and 0 <= vapp_wind_included_kt <= vapp_wind_max_kt"
            )

    @property
    def locations_m(self) -> dict[str, tuple[float, float, float]]:
        """Typical bag positions as lever arms from the CG in body axes (x forward, y right, z down;
        m), for FlightTrack.specific_force_at: rough cabin and hold geometry scaled from the type's
        length (the CG sits near 45 % of the fuselage). An assumption, not a seating chart."""
        length, half = self.length_m, self.cabin_half_width_m
        return {
            "cabin_seat_front": (0.30 * length, -half * 0.6, 0.6),
            "cabin_seat_mid": (0.0, half * 0.6, 0.6),
            "cabin_seat_rear": (-0.30 * length, -half * 0.6, 0.6),
            "overhead_bin_mid": (0.0, half * 0.85, -1.0),
            "forward_hold": (0.22 * length, 0.0, 1.8),
            "aft_hold": (-0.20 * length, 0.0, 1.8),
        }

    taxi_turn_kt: float = 10.0  # about 10 kt in turns (Airbus A319 FCOM)
    rotate_elevator: float = 0.3  # nose-up elevator bias during rotation (fraction of full travel)
    elevator_nose_up_deg: float | None = None  # extends the model's elevator travel (sim.flight.jsbsim.model_edits)
    spread_spoiler_lift: bool = (
        False  # the ground spoilers' lift loss over their whole travel (sim.flight.jsbsim.model_edits)
    )
    add_ground_spoilers: bool = False  # ground spoilers for a model without them (sim.flight.jsbsim.model_edits)
    nose_side_friction: float | None = None  # sets the nose tyre's side-force peak (sim.flight.jsbsim.model_edits)
    vr_ref_mass_kg: float | None = None  # the mass vr_kt holds at (None: vr_kt at any mass)
    nose_static_deflection_m: float | None = (
        None  # a softer nose strut at the same stance (sim.flight.jsbsim.gear.set_nose_strut)
    )
    tuning: PilotTuning = field(default_factory=PilotTuning)


PROFILES: dict[str, AircraftProfile] = {
    "737": AircraftProfile(
        model="737",
        description="Boeing 737 (JSBSim 737, CFM56)",
        ceiling_ft=37_000.0,  # FAA TCDS A16WE: 737-300/-400/-500 (the CFM56-3 classics)
        cruise_level_ft=37_000.0,  # WRAP B737 cruise_alt 11.74 km (FL385), capped at the ceiling
        cruise_mach=0.76,  # WRAP B737 cruise Mach range; the 737 built-in's
        range_km=4600.0,  # OpenAP prop B737
        min_runway_m=2000.0,  # Boeing 737 Airplane Characteristics for Airport Planning (737-300)
        # the two real 737 taxi-outs (N899DN, a 737-900, MSP: speed p50 6.3 and 7.3 m/s, p90 7.8 and
        # 10.2) against 7.9 m/s p50 over 19 seeded ist-osl flights at the default straight speeds
        tuning=PilotTuning(taxi_speed_out_mps=(6.5, 9.0)),
        spread_spoiler_lift=True,  # the stock table's lift loss is all in 10 % of the travel (sim.flight.jsbsim.model_edits)
        wrap_type="B737",
        n_engines=2,
        length_m=33.4,
        wingspan_m=28.9,
        cg_height_m=3.69 * 0.3048,
        wheelbase_m=12.4,
        fuel_kg=9000.0,
        burn_kg_per_h=2700.0,  # measured on this model: 2.6 t per airborne hour on ist-osl-737 (3.3 h airborne)
        # the approach speed's wind additive by Boeing's rule for an approach flown without the
        # autothrottle's gust response: half the steady headwind plus the gust increment, VREF + 5 kt at
        # least and VREF + 20 kt at most (Boeing 737 FCTM, approach speed); vapp_kt taken as holding the
        # 5 kt, the drawn wind at 20 ft as all headwind and no separate gust increment (the model's
        # turbulence has no direction and no gusts reported apart from it). The flight's speed loop is a
        # plain PI on the IAS, not the 737's autothrottle. On the 20 flights of a seeded european-trio 737
        # population (seed 2611; the same scenarios flown both ways) without the additive the windy ones
        # touched down hard: 10.6 ft/s in a 27.5 kt wind (drawn target 1.8), 6.3-6.6 in 12-16 kt; with it
        # 5.0 and 4.5-4.6: sink p90 6.65 -> 5.30 ft/s, max 10.64 -> 6.69, 1.70 -> 1.21 ft/s above the
        # drawn target on average, CG peak max 2.59 -> 1.80 g (the flights in under 10 kt of wind unchanged)
        vapp_wind_fraction=0.5,
        vapp_wind_included_kt=5.0,
        vapp_wind_max_kt=20.0,
        # Boeing 737 FCOM, TO/GA: the first push advances the thrust "toward the reduced go-around N1
        # to produce 1000 to 2000 fpm rate of climb" (the middle of it held here)
        go_around_climb_fpm=1500.0,
        vr_kt=150.0,
        v2_kt=158.0,
        descent_ias_kt=280.0,
        vapp_kt=138.0,
        ref_landing_mass_kg=46000.0,
        rotate_pitch_deg=9.0,
        takeoff_flaps_norm=0.375,
        approach_steps=(
            ApproachStep(20.0, 0.125, 210.0),
            ApproachStep(15.0, 0.375, 180.0),
            ApproachStep(12.0, 0.625, 160.0),
            ApproachStep(9.0, 0.625, 155.0, gear_down=True),
            ApproachStep(7.5, 0.875, 138.0, gear_down=True),
        ),
        flap_retract_kt=((185.0, 0.125), (205.0, 0.0)),
        alpha_stall_deg=16.0,
        climb_throttle=0.92,
        taxi_throttle_max=0.35,
        reverse_throttle=0.6,
        flare_height_ft=55.0,
        flare_pitch_kp=4.0,
        flare_law="exponential",  # it balloons and drops under the constant-deceleration law (Flare)
        # the attitude for the lift lost as the speed bleeds (Flare), chosen among 0.1-0.3 on still-air
        # pattern landings (seeds 0-7; flown minus drawn touchdown sink +0.53 ft/s without, -0.08 at 0.1,
        # -0.70 at 0.2). In gusts, seeds 16-55 / held-out 56-95: +1.16 / +0.92 ft/s (sd 1.36 / 1.32) -> +0.56
        # / +0.31 (1.13 / 1.13), median 3.28 / 2.88 -> 2.56 / 2.49 ft/s, p90 4.83 / 4.78 -> 3.65 / 3.57;
        # touchdown 30 m further on (median 588 / 598 m); firm (seeds 0-15) -0.48 -> -0.65; hard (seeds 12-39)
        # over 10 ft/s, then failed flights, 5 -> 4 of 28 (none fails now: PilotTuning.max_touchdown_sink_mps)
        flare_lift_attitude_rad=0.1,
        # the 737's nose fell at 3-4 deg/s after its elevator relaxed at touchdown (the nose wheels
        # down 0.8-1.9 s after the mains, 8 pattern landings); kept: 2.0-4.0 s, at most 0.9-2.6 deg/s
        touchdown_elevator_keep=1.0,
        # WRAP B737
        climb=ClimbSchedule(
            Spread(11.41, 2.07, 8.01, 14.82),
            Spread(11.71, 1.96, 8.49, 14.93),
            Spread(6.74, 1.42, 4.4, 9.08),
            3400.0,
            8900.0,
            151.95,
            vs_initial=Spread(11.94, 2.37, 8.05, 15.83),
        ),
        # WRAP B737 takeoff_acceleration; the curve measured on the pattern (LSGG, 46.5 t at brake release)
        takeoff=TakeoffThrust(
            Spread(1.77, 0.28, 1.31, 2.23),
            (
                (0.70, 1.264),
                (0.75, 1.465),
                (0.80, 1.674),
                (0.85, 1.890),
                (0.90, 2.112),
                (0.95, 2.337),
                (1.00, 2.568),
            ),
            mass_kg=46_520.0,
            rho_kgm3=1.1767,
            mass_exp=1.07,
        ),
    ),
    "A320": AircraftProfile(
        model="A320",
        description="Airbus A320 (JSBSim A320, CFM56-5)",
        ceiling_ft=39_100.0,  # EASA TCDS A.064: A320 maximum operating altitude 39,100 ft (39,800 ft by modification)
        cruise_level_ft=36_000.0,  # WRAP A320 cruise_alt 10.92 km (FL358)
        cruise_mach=0.78,  # WRAP A320 climb_const_mach / OpenAP prop A320
        range_km=5000.0,  # OpenAP prop A320
        min_runway_m=2100.0,  # Airbus A320 Aircraft Characteristics, Airport and Maintenance Planning
        wrap_type="A320",
        tuning=PilotTuning(taxi_brake_mps2=4.2),
        nose_side_friction=0.8,  # the stock 0.5 let the nose wheel turn it at 1.7-2.1 deg/s^2 (sim.flight.jsbsim.model_edits)
        rotate_elevator=0.6,
        elevator_nose_up_deg=35.0,  # no trimmable stabiliser in the model (sim.flight.jsbsim.model_edits)
        n_engines=2,
        length_m=37.57,
        wingspan_m=34.1,
        cg_height_m=8.42 * 0.3048,
        wheelbase_m=12.64,
        fuel_kg=5500.0,
        # measured on this model: 5,500 kg ran out 7,500-7,650 s after the gate on 20 airline-mix
        # flights; with its fuel planned it burns 3.5 t (a 2.5 h airline-mix flight) to 3.9 t
        # (gva-lhr-a320) per airborne hour, above the real A320's 2.5 t/h
        burn_kg_per_h=3900.0,
        # rotated at a fixed 138 kt, this model (which lifts off near 150 kt at 55.7 t and 159-163 kt
        # at the 60-65 t of 900-2,000 km routes, 9-10 deg of pitch) sat 8-18 s on its mains at
        # rotation attitude: 7 route takeoffs 7.9-15.0 s from Vr to liftoff, the pattern's 4-18 s by
        # throttle, where the 737 and Fokker 100 take 3.4-4.6 s and a rotation at 3 deg/s to about
        # 10 deg lifts off in some 4 s (Airbus A320 FCTM, takeoff). Vr scales with sqrt(mass), as the
        # stall speed does: 143 kt at the pattern's 55.7 t gives 3.1-4.4 s at every throttle there
        vr_kt=143.0,
        vr_ref_mass_kg=55_690.0,
        v2_kt=148.0,
        descent_ias_kt=280.0,
        vapp_kt=145.0,
        ref_landing_mass_kg=52500.0,
        rotate_pitch_deg=10.0,
        takeoff_flaps_norm=0.375,
        # the JSBSim A320 needs nearly full nose-up elevator to trim with more than 25 deg of flap
        # (measured by JSBSim trim: flaps 30 deg at 140 kt -> elevator -0.98), so it lands with 25
        approach_steps=(
            ApproachStep(20.0, 0.125, 210.0),
            ApproachStep(15.0, 0.25, 190.0),
            ApproachStep(12.0, 0.375, 170.0),
            ApproachStep(9.0, 0.5, 160.0, gear_down=True),
            ApproachStep(7.5, 0.625, 145.0, gear_down=True),
        ),
        flap_retract_kt=((185.0, 0.125), (205.0, 0.0)),
        alpha_stall_deg=15.0,
        climb_throttle=0.92,
        taxi_throttle_max=0.35,
        reverse_throttle=0.6,
        flare_height_ft=70.0,  # a heavy, slow-responding model in landing trim: start early
        flare_pitch_kp=4.0,
        # the flare aims 1.5 m up (flare_aim_m) and begins at a constant time to contact when the
        # approach is steeper than the glideslope (flare_at_time_to_contact); below the aim it holds the
        # attitude unless ballooning (controllers.Flare._rate_decel). Measured on pattern landings (flown
        # minus drawn touchdown sink, ft/s; normal: mean (sd) on seeds 16-55, firm on seeds 0-15), against
        # the 2 m aim, the fixed 70 ft start and the push below the aim: normal +0.72 (1.33), was +1.22
        # (1.19), flown median 2.62 ft/s (was 3.33; the surveys' 2.0); firm -0.12 (1.22), was -0.52
        # (1.21); hard, seeds 12-39: 2 over the 10 ft/s limit, was 3. In still air (seeds 0-15) the flown
        # sink now follows the drawn one (-0.48, sd 0.07), where it was about 3.2 ft/s whatever was drawn
        # (+1.13, sd 0.83). Aims of 1.0 and 1.2 m and flare heights of 40-50 ft were worse
        flare_aim_m=1.5,
        flare_at_time_to_contact=True,
        # thrust to idle at 10 ft, where Airbus's autoland calls "RETARD" (20 ft in a manual landing;
        # Airbus A320 FCOM, auto callouts), and the approach speed's wind additive by Airbus's rule,
        # VAPP = VLS + 1/3 of the headwind, 5 kt at least, 15 kt at most (A320 FCOM, approach speed
        # computation), vapp_kt taken as holding the 5 kt and the drawn wind at 20 ft as all headwind.
        # On the 20 flights of a seeded european-trio A320 population (seed 2611) the stock 20 ft and
        # no additive landed 1.51 ft/s above the drawn touchdown sink on average (p90 3.28) and 2 of 20
        # failed in the flare at 10.6 and 12.2 ft/s: the thrust, idle seconds before the wheels met
        # the runway, let the speed and then the sink run away while the elevator was at its stop (the
        # model has no trimmable stabiliser: sim.flight.jsbsim.model_edits); one of the two was flown in a
        # 27 kt wind. Retarding at 10 ft alone: 0.77 ft/s above (p90 1.87), 1 of 20 failed (the windy one);
        # with the additive too (4 kt in that wind): 0.78 ft/s above (p90 2.53), 0 of 20 failed
        retard_height_ft=10.0,
        vapp_wind_fraction=1.0 / 3.0,
        vapp_wind_included_kt=5.0,
        vapp_wind_max_kt=15.0,
        # the stock model has no ground spoilers (sim.flight.jsbsim.model_edits gives it the 737's). With them the
        # wing lets go of the weight at touchdown and half the flare's elevator can be kept: on 30 seeded
        # pattern landings the fastest nose-down rate went from 4.9-6.4 deg/s to 2.7-4.5 deg/s (nose on
        # the runway 4.3-4.9 s after the mains, 0 bounces); keeping it all (1.0) left the elevator's
        # integrator holding the nose off the runway for over 8 s in most of them
        add_ground_spoilers=True,
        touchdown_elevator_keep=0.5,
        # Airbus SRS: "the speed target in SRS TO mode is V2 + 10 kt" from liftoff to the acceleration
        # altitude (A320 FCOM DSC-22_30-40-20-20, SRS TO mode). At V2 + 20 the model, which lifts off
        # near V2 + 5, spent the first 1,500 ft accelerating 20-25 kt (about 100 m of height in
        # energy): 8 european-trio A320s climbed at 4.7-11.1 m/s, 2 of 8 within WRAP's 9.15-16.0
        initial_climb_v2_add_kt=10.0,
        # "At VR, initiate the rotation to achieve a continuous rotation with a rate of about 3 deg/s,
        # towards a pitch attitude of 15 deg" (Airbus A320 FCOM, standard operating procedures, takeoff).
        # Handed to the speed loop at liftoff (9-10 deg), the model pitched up at under 0.5 deg/s and
        # spent its thrust on speed: 160 to 175-185 kt over the first 1,500 ft
        initial_climb_rotate_to_deg=15.0,
        # The stock model's drag due to lift is about twice an A320's: its CDalpha table (clean, 8 deg)
        # gives CL 1.02 for CD 0.086 + CDo 0.016, an Oswald factor of about 0.41 at its aspect ratio
        # 9.4, where a swept transport wing has 0.75-0.85 (Raymer, "Aircraft Design: A Conceptual
        # Approach", 5th ed., 2012, section 12.6); so at the throttle that gives WRAP's takeoff
        # acceleration (TakeoffThrust) it climbs with a lift-to-drag ratio near 5 at 9 deg of incidence:
        # 8 european-trio A320s climbed from liftoff to 1,500 ft at 4.7-11.1 m/s (median 7.6), WRAP's
        # initclimb_vs being 12.6 +- 2.1 (9.15-16.0). The extra thrust stands for the extra drag: the
        # accelerometer feels (T - D) / m, which the climb and speed kinematics set
        initial_climb_thrust_for_rate=True,
        # WRAP A320
        climb=ClimbSchedule(
            Spread(10.25, 1.59, 7.63, 12.87),
            Spread(8.44, 1.31, 6.28, 10.6),
            Spread(5.29, 1.03, 3.6, 6.97),
            3700.0,
            8800.0,
            151.04,
            vs_initial=Spread(12.59, 2.09, 9.15, 16.04),
        ),
        # WRAP A320 takeoff_acceleration; the curve measured on the pattern (LSGG, 55.7 t at brake release,
        # mean of seeds 1 and 4, Vr 143 kt; at 0.70 it does not lift off before the runway's end). The mass
        # exponent 1.2 fits 16 european-trio A320 takeoffs (60-65 t): flown minus drawn acceleration
        # +0.007 m/s^2 on average, sd 0.065 (1.0: -0.049; 1.4: +0.060)
        takeoff=TakeoffThrust(
            Spread(1.93, 0.27, 1.5, 2.37),
            ((0.75, 1.542), (0.80, 1.772), (0.85, 1.999), (0.90, 2.234), (0.95, 2.468), (1.00, 2.708)),
            mass_kg=55_690.0,
            rho_kgm3=1.1766,
            mass_exp=1.2,
        ),
    ),
    "fokker100": AircraftProfile(
        model="fokker100",
        description="Fokker 100 (JSBSim fokker100, Rolls-Royce Tay): stand-in for seed 000's Avro RJ85",
        ceiling_ft=35_000.0,  # EASA TCDS (Fokker F28 Mk 0100): maximum operating altitude 35,000 ft
        cruise_level_ft=35_000.0,  # no WRAP model for the F100: its ceiling, where the built-ins cruise
        cruise_mach=0.72,  # the F100 built-ins' (Fokker 100 typical cruise Mach 0.72-0.73)
        range_km=2400.0,  # Fokker 100 standard range, about 1,300 NM (manufacturer's brochure)
        min_runway_m=1800.0,  # Fokker 100 airport planning take-off field length at MTOW
        wrap_type="E190",
        # 2.5 deg: WRAP E190's constant-Mach descent is at most 11.8 m/s, which 2.8 deg exceeds at the
        # F100's 230-250 m/s ground speeds in cruise winds (12.1-12.9 m/s on 6 of 10 european-trio
        # routes); at 2.5 deg the same ten flights descend at 9.6-11.5 m/s there and at 8.9-9.1 m/s at
        # constant CAS, on WRAP E190's default of 9.1 (the built-in hel-zrh-f100 flies 2.5 deg too)
        descent_angle_deg=2.5,
        rotate_elevator=0.1,  # a light, pitch-sensitive model: a gentle pull (nz < 1.3 g)
        n_engines=2,
        length_m=35.5,
        wingspan_m=28.08,
        cg_height_m=7.35 * 0.3048,
        wheelbase_m=14.0,
        fuel_kg=9000.0,
        burn_kg_per_h=2400.0,  # measured on this model: 2.3 t per airborne hour on hel-zrh-f100 (2.6 h airborne)
        vr_kt=146.0,
        v2_kt=152.0,
        descent_ias_kt=280.0,
        vapp_kt=145.0,
        ref_landing_mass_kg=29000.0,
        rotate_pitch_deg=6.0,  # light and fast at rotation (Vr set by the E190 stand-in ranges)
        takeoff_flaps_norm=8.0 / 42.0,
        # the JSBSim fokker100's flap lift table has no rows below zero angle of attack, so with
        # flaps out it cannot shed lift by pitching down: it lands with 15 deg at a speed that keeps
        # alpha positive (JSBSim trim: 15 deg at 160 kt -> alpha 0.8 deg)
        approach_steps=(
            ApproachStep(20.0, 0.0, 190.0),
            ApproachStep(15.0, 8.0 / 42.0, 170.0),
            ApproachStep(11.0, 15.0 / 42.0, 160.0, gear_down=True),
            ApproachStep(8.0, 15.0 / 42.0, 145.0, gear_down=True),
        ),
        flap_retract_kt=((175.0, 0.0),),
        alpha_stall_deg=15.0,
        climb_throttle=0.95,
        taxi_throttle_max=0.4,
        reverse_throttle=0.4,
        flare_height_ft=40.0,
        flare_pitch_kp=1.0,  # the fokker100 answers its elevator faster: 4 diverges in its flare
        flare_accel_gain=1.0
        / 3.0,  # and so does its flare loop at the full gain (JSBSim blew up, 2 of 8 seeds)
        # its flare loop, at a third of the gain, lags: aiming at 2 m and steering on the present sink,
        # it kept pulling past the target and its landings came out near 3-5 ft/s whatever was drawn
        # (pattern landings, flown minus drawn touchdown sink: normal +2.25 ft/s mean on seeds 0-39,
        # firm -2.3 and hard -2.3 on seeds 0-15). Steering on the sink and height 1 s ahead and aiming
        # at the runway: normal +0.94 (seeds 0-39), firm -0.8, hard -1.4 (seeds 0-15); no flight lost
        flare_aim_m=0.0,
        flare_predict_s=1.0,
        # the approach speed's wind additive: no Fokker 100 manual was found, so the common practice
        # (VAPP = VREF plus headwind and gust terms: Dassault Falcon service advisory "Approach speed
        # considerations", 2010; Boeing's flight crew training manuals: half the steady headwind plus the
        # gust increment, VREF + 5 to VREF + 20 kt) is flown by the 737's rule. Without it: on
        # european-trio (members 0-68) flown minus drawn touchdown sink +1.8 ft/s (median) in over 6 m/s
        # at 20 ft, -0.3 under 3 m/s. 40 seeded pattern landings in a 10 m/s wind: +1.90 ft/s mean
        # (flown p90 6.66) without, +1.29 (5.42) with it, touching down a median 467 and 437 m past the
        # threshold (one of 40 past 914 m, at 942); in 7 m/s (an additive of 1.8 kt) +1.17 and +1.16:
        # the firmness in moderate winds is the flare's, not the speed's
        vapp_wind_fraction=0.5,
        vapp_wind_included_kt=5.0,
        vapp_wind_max_kt=20.0,
        # WRAP E190 (the nearest type WRAP models)
        climb=ClimbSchedule(
            Spread(10.44, 1.98, 7.18, 13.71),
            Spread(8.93, 1.62, 6.27, 11.6),
            Spread(4.82, 1.14, 2.95, 6.7),
            3000.0,
            9200.0,
            140.0,
            vs_initial=Spread(11.2, 3.3, 5.78, 16.62),
        ),
        # WRAP E190 takeoff_acceleration (the stand-in, as above); the curve measured on the pattern
        # (LSGG, 33.9 t at brake release)
        takeoff=TakeoffThrust(
            Spread(1.83, 0.27, 1.38, 2.28),
            (
                (0.70, 1.340),
                (0.75, 1.541),
                (0.80, 1.752),
                (0.85, 1.972),
                (0.90, 2.199),
                (0.95, 2.434),
                (1.00, 2.676),
            ),
            mass_kg=33_884.0,
            rho_kgm3=1.1766,
            mass_exp=0.99,
        ),
    ),
    "787-8": AircraftProfile(
        model="787-8",
        description="Boeing 787-8 (JSBSim 787-8, Trent 1000)",
        ceiling_ft=43_100.0,  # FAA TCDS T00021SE: 787-8 maximum operating altitude 43,100 ft
        cruise_level_ft=39_000.0,  # WRAP B788 cruise_alt 12.01 km (FL394)
        cruise_mach=0.85,  # OpenAP prop B788
        range_km=13_600.0,  # Boeing 787-8 published range 7,305 NM (OpenAP prop B788: 14,800 km)
        min_runway_m=2600.0,  # Boeing 787 Airplane Characteristics for Airport Planning (787-8)
        wrap_type="B788",
        # WRAP B788 descends from its 12.01 km cruise over a 292 km descent range (defaults), a mean
        # path of 2.36 deg (A320 and B738: 2.67 deg, E190 2.50). At the 2.8 deg of the narrow-bodies
        # this model's 280-290 m/s ground speeds at Mach 0.85 put the constant-Mach band at 13.8-14.4
        # m/s (european-787, members 0-19: 8 of 20 past WRAP B788's steepest, -14.16 m/s; default -7.6)
        # and 4 of 20 past its steepest below the CAS crossover (-7.94)
        descent_angle_deg=2.4,
        cabin_half_width_m=2.9,
        n_engines=2,
        length_m=56.7,
        wingspan_m=60.1,
        cg_height_m=13.78 * 0.3048,
        wheelbase_m=22.8,
        # at least 40 t: short routes land at 163-166 t, under the 787-8's 172 t maximum landing mass
        # (OpenAP prop "mlw"), within the masses its flare was tuned at. On 20 European routes
        # (european-trio's, one 787 each): at a 50 t floor all landed, at 173-175 t (over the MLW); at
        # 44 t one floated 4.3 km down the runway and off its end, and at 40 t the same flight floated
        # 3.2 km, before the pilot flew go-arounds; with them (a float over the runway's second half goes
        # around: sim.flight.controllers.FLOAT_LIMIT_FRACTION) it goes around once and lands 460 m past
        # the threshold, and all 20 land (sink median 3.7 ft/s, p90 6.3; CG peak max 2.3 g, a "hard"
        # draw). Planned with the real type's burn (OpenAP FuelFlow("B788"): 4.6 t/h; at least 10 t),
        # the same routes landed near 137 t and 1 of 20 failed (a normal landing at 10.0 ft/s): the
        # flare is not tuned that light
        fuel_kg=40000.0,
        burn_kg_per_h=3500.0,  # measured on this model: 3.4 t per airborne hour on lhr-jfk-787 (the real 787-8: about 5.4)
        # the stock nose strut (160,000 lbf/ft: 5 cm under its share of the weight) put 0.36-0.57 g
        # at the cockpit on the takeoff roll and rollout of 4 seeded pattern flights on ISO 8608 class
        # A runways, and 19 of 20 route flights of a validated population over NASA's +-0.4 g for an
        # acceptable runway (Morris and Hall 1965); at 0.15 m 0.22-0.39 g, at 0.25 m 0.18-0.29 g (same
        # seeds), the CG's roughness unchanged (0.018-0.023 g RMS). A very good runway stays well inside
        # the worst acceptable one's bound: 0.25 m, stiffer than the mains' 0.35 (gear.STATIC_DEFLECTION_M)
        nose_static_deflection_m=0.25,
        # Boeing 747-400/-8 and 787 FCOM, TO/GA switch: the autothrottle's go-around thrust "adjusts to
        # provide a 2000 feet per minute climb" (THR mode)
        go_around_climb_fpm=2000.0,
        # no approach-speed wind additive (the 737's Boeing rule was tried): without it the 787-8 lands
        # firmer the stronger the wind (european-787, members 0-19: flown minus drawn touchdown sink
        # +2.7 ft/s median in over 6 m/s at 20 ft, -0.6 under 3 m/s). 30 seeded pattern landings in a
        # 10 m/s wind: +1.76 ft/s mean (flown p90 5.99) without it, +1.36 (4.68) with it, but with it 9
        # of the 30 floated past the touchdown zone (914 m) against 5, one to 1,927 m
        vr_kt=150.0,
        v2_kt=160.0,
        descent_ias_kt=290.0,
        vapp_kt=145.0,
        ref_landing_mass_kg=150000.0,
        rotate_pitch_deg=9.0,
        takeoff_flaps_norm=15.0 / 35.0,
        approach_steps=(
            ApproachStep(24.0, 5.0 / 35.0, 220.0),
            ApproachStep(18.0, 15.0 / 35.0, 190.0),
            ApproachStep(14.0, 20.0 / 35.0, 170.0),
            ApproachStep(11.0, 20.0 / 35.0, 165.0, gear_down=True),
            ApproachStep(9.0, 30.0 / 35.0, 145.0, gear_down=True),
        ),
        flap_retract_kt=((190.0, 5.0 / 35.0), (215.0, 0.0)),
        alpha_stall_deg=15.0,
        climb_throttle=0.95,
        taxi_throttle_max=0.35,
        reverse_throttle=0.6,
        # the exponential flare (from 80 ft until the lift attitude below), its time constant unbounded in
        # practice (30 s); measured on route landings (gva-lhr, seeds 0-11; normal / firm / hard landings 12 /
        # 8 / 8):
        # - the constant-deceleration law from 50 ft ballooned near the runway and floated: 7 of 11
        #   normal landings past 900 m (up to 1,255 m), one flare begun too late for the 787's slow
        #   pitch response (10.6 ft/s, a failed flight; a failed firm and hard landing too);
        # - the exponential law from 50 ft came in late (sink p90 8.6 ft/s), from 65 ft p90 5.9,
        #   from 80 ft p90 4.5 with 1 float, but with its time constant cut to 6 s a firm or hard
        #   landing's command is held at the approach's sink down to 6 s x (entry - target sink),
        #   about 30 ft, too late for this type: 2 of 8 firm and 5 of 8 hard landings over 10 ft/s;
        # - cut at 30 s the command eases from the flare height on: 0 of 8 firm and 1 of 8 hard
        #   (10.0 ft/s against an 8.2 target) failed, normal sinks 3.48 / 4.74 / 4.93 ft/s (median,
        #   p90, max), 4 of 12 past 900 m (up to 1,148 m); at 10 s, 4 of 8 hard landings failed.
        # On 12 other seeds (12-23), constant deceleration -> this: sink 3.10 / 4.10 / 4.80 ->
        # 3.15 / 4.39 / 5.82 ft/s, past 900 m 9 -> 6 of 12. The floats left come from the long
        # flare (13 s from 80 ft) and a fast, heavy approach: on short routes the 50 t fuel floor
        # (fuel_kg) of the time landed it at about 177 t, above the 787-8's 172 t maximum landing mass,
        # and its mass-scaled Vapp (autopilot.vapp_mps) was then 158 kt, 13 kt over vapp_kt.
        # Then the attitude for the lift lost as the speed bleeds (flare_lift_attitude_rad, Flare): without it
        # the sink, arrested near the target 5 ft up, rose to about 2.9 ft/s whatever was drawn (still air,
        # seeds 0-7: 1.36-3.49 ft/s drawn, 2.89-3.40 flown, +0.94 on average). With it the flare is firmer and
        # begins at 70 ft: from 80 ft, 0.25 rad floated past 914 m in 21 of 40 landings in gusts (seeds
        # 16-55), against 12 before; from 65 ft the late tail grew. From 70 ft in still air 0.2 / 0.25 rad
        # give -0.07 / -0.24 ft/s (0.2 / 0.25 / 0.3 from 80 ft: +0.28 / +0.08 / -0.13). In gusts, seeds 16-55
        # / held-out 56-95: flown minus drawn +1.66 / +1.53 ft/s (sd 1.60 / 1.19) -> +0.81 / +0.66 (1.44 /
        # 1.12), median 3.38 / 3.52 -> 2.76 / 2.51 ft/s, p90 5.16 / 4.78 -> 3.86 / 4.12, past 914 m 12 / 14 ->
        # 10 / 14 of 40 (0.25 rad: +0.77 / +0.51, 11 / 14 past); firm (seeds 0-15) +0.01 -> -0.48; hard (seeds
        # 12-39) over 10 ft/s, then failed flights, 6 -> 6 of 28 (1 fails now, at 13.6 ft/s).
        # Most of those floats began above the glideslope: the short-final pitch floor held the nose up
        # (controllers.FINAL_PITCH_MARGIN_DEG). With the floor lowered (its 10 s mean), the flare from 70 ft,
        # begun on the glideslope, landed firmer (seeds 56-95 / 96-135: flown minus drawn +0.66 / +0.88 ->
        # +0.77 / +1.32 ft/s, p90 4.12 / 5.46 -> 4.50 / 6.82), from 75 ft +0.71 / +0.87 (p90 4.64 / 5.33),
        # as before; past 914 m 14 / 12 -> 6 / 3 of 40 (from 70 ft 2 / 1), touchdown median 796 / 744 ->
        # 638 / 576 m; from 80 ft +0.64, 6 past (56-95). With the floor's 30 s mean, from 75 ft, seeds 56-95
        # / 96-135 / 136-175: +0.74 / +0.54 / +0.78 ft/s, p90 4.40 / 4.56 / 3.98, past 914 m 3 / 3 / 6 of 40;
        # in still air (seed 0) 1.5 / 3.0 ft/s targets land at 0.98 / 3.40 (1.74 / 2.53 from 70 ft before)
        flare_height_ft=75.0,
        flare_pitch_kp=4.0,
        flare_tau_max_s=30.0,
        flare_law="exponential",
        flare_lift_attitude_rad=0.2,
        # WRAP B788
        climb=ClimbSchedule(
            Spread(9.58, 1.38, 7.32, 11.85),
            Spread(9.02, 1.77, 6.12, 11.93),
            Spread(6.03, 1.48, 3.59, 8.47),
            3800.0,
            9500.0,
            158.68,
            # WRAP gives a beta law (6.24, 5.05, loc 0.78, scale 17.49): its mean and sd
            vs_initial=Spread(10.45, 2.48, 6.27, 14.45),
        ),
        # WRAP B788 takeoff_acceleration; the curve measured on lhr-jfk-787 (EGLL, 180 t at brake release)
        takeoff=TakeoffThrust(
            Spread(1.61, 0.28, 1.16, 2.07),
            ((0.75, 1.234), (0.80, 1.411), (0.85, 1.591), (0.90, 1.773), (0.95, 1.955), (1.00, 2.139)),
            mass_kg=180_040.0,
            rho_kgm3=1.2218,
            mass_exp=1.02,
        ),
    ),
}


def get_profile(model: str) -> AircraftProfile:
    """The profile of a JSBSim model; an :class:`AircraftError` with a suggestion otherwise."""
    try:
        return PROFILES[model]
    except KeyError:
        raise AircraftError(
            f"no flight profile for aircraft '{model}'{did_you_mean(model, PROFILES)}; "
            f"profiled aircraft: {', '.join(sorted(PROFILES))}"
        ) from None
