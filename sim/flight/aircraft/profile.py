"""Per-type speeds, flap schedules, geometry, procedures and gains: the one table the pilot flies
from (the controllers in :mod:`flightmode.sim.flight.pilot.controllers` hold no numbers of their own).

Speeds are chosen inside OpenAP WRAP's real-traffic ranges for the type (OpenAP's ``WRAP`` kinematic
model, built from ADS-B) and the type's published figures; gains were tuned on these JSBSim models.
Flap commands are ``fcs/flap-cmd-norm`` values of the JSBSim model (737: detents
1,2,5,10,15,25,30,40 at 1/8 steps; A320 and 787-8: degrees / full travel (40 and 35 deg);
fokker100: degrees / 42).

This module is the schema; each type's figures are a module beside it (:mod:`.b737`, :mod:`.a320`,
:mod:`.fokker100`, :mod:`.b787_8`), looked up by :func:`~flightmode.sim.flight.aircraft.registry.get_profile`.
"""

from __future__ import annotations

from dataclasses import dataclass, field

from flightmode.errors import AircraftError
from flightmode.sim.flight.aircraft.performance import ClimbSchedule, TakeoffThrust
from flightmode.sim.flight.aircraft.tuning import PilotTuning


@dataclass(frozen=True, slots=True)
class ApproachStep:
    """At ``dist_nm`` to the threshold: select ``flaps_norm`` (and gear if ``gear_down``) and slow to ``speed_kt``."""

    dist_nm: float
    flaps_norm: float
    speed_kt: float
    gear_down: bool = False


FLARE_LAWS = ("constant_deceleration", "exponential")  # sim.flight.pilot.flare.Flare


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
    # sim.flight.pilot.flare.FLARE_PITCH_GAIN
    flare_accel_gain: float = 1.0
    # the flare's guidance law (sim.flight.pilot.flare.Flare), one of FLARE_LAWS
    flare_law: str = "constant_deceleration"
    # the constant-deceleration law's lag compensation (sim.flight.pilot.flare.Flare._rate_decel): the
    # height above the runway at which it aims to reach the touchdown sink (m), and how far ahead (s) it
    # predicts the sink rate and height from the upward acceleration the aircraft has
    flare_aim_m: float = 2.0
    flare_predict_s: float = 0.0
    # begin the flare at flare_height_ft or, on an approach steeper than the glideslope (sink over
    # ground speed), at the same time to contact (sim.flight.pilot.flare.flare_start_height_m)
    flare_at_time_to_contact: bool = False
    # the exponential law's proportional gain: attitude change per sink-rate error, times the true
    # airspeed (rad per rad of flight-path angle; sim.flight.pilot.flare.FLARE_EXP_INTEGRAL_PER_S)
    flare_path_gain: float = 1.5
    # the exponential law's longest time constant (s; sim.flight.pilot.flare.exponential_flare_tau_s):
    # a flare entered with little sink to lose (a firm or hard landing) is held at its entry sink until
    # h / tau_max falls under the sink it has to lose
    flare_tau_max_s: float = 6.0
    # the exponential law's attitude for the lift the flare loses as the speed bleeds at idle (rad;
    # sim.flight.pilot.flare.Flare): this times ((V_0 / V)^2 - 1), V_0 the true airspeed at the flare height;
    # 0: none
    flare_lift_attitude_rad: float = 0.0
    # a flare still airborne this far past the threshold (m) aims at a touchdown sink of at least
    # flare_settle_sink_mps from there on (sim.flight.pilot.flare.Flare.tick): the crew lets a float
    # settle rather than hold off for a soft landing; None: never
    flare_settle_from_m: float | None = None
    flare_settle_sink_mps: float = 0.0
    # the main gear's height at which the flare pulls the thrust to idle ("retard")
    retard_height_ft: float = 20.0
    # the approach speed's wind additive (sim.flight.pilot.autopilot.Autopilot.vapp_mps): this fraction of
    # the wind at 20 ft (the flight's drawn surface wind, the boundary layer's gustiness) above the
    # additive that vapp_kt already holds (vapp_wind_included_kt), at most vapp_wind_max_kt in all
    vapp_wind_fraction: float = 0.0
    vapp_wind_included_kt: float = 0.0
    vapp_wind_max_kt: float = 0.0
    # the initial climb (sim.flight.pilot.takeoff.InitialClimb): the speed held from liftoff to the
    # acceleration height, V2 plus this, and the most pitch the speed loop may command for it.
    # Boeing: "V2 + 15 to V2 + 25" with all engines (Boeing 737 FCTM, takeoff, initial climb), 20 here
    initial_climb_v2_add_kt: float = 20.0
    initial_climb_pitch_max_deg: float = 15.0
    # None: the speed loop takes the pitch from liftoff on; a pitch (deg): the rotation goes on after
    # liftoff toward it at 3 deg/s (the rotation's rate, sim.flight.pilot.takeoff.TakeoffRoll) before the
    # speed loop takes over (sooner if the speed falls under V2)
    initial_climb_rotate_to_deg: float | None = None
    # True: from liftoff to the acceleration height the throttle may rise above the takeoff throttle
    # (to 1.0) to hold the flight's drawn initial rate of climb (climb.vs_initial) as an energy rate
    # (sim.flight.pilot.takeoff.InitialClimb), for a model whose drag in the takeoff configuration is
    # too high for the thrust that gives the real takeoff acceleration
    initial_climb_thrust_for_rate: bool = False
    # the go-around's thrust (sim.flight.pilot.go_around.GoAround): None, the type's climb thrust at once
    # (Airbus TOGA, Fokker GA); a rate of climb (ft/min), Boeing's reduced go-around thrust, which the
    # autothrottle adjusts to hold that climb once the pitch has come up
    go_around_climb_fpm: float | None = None
    # the share of the flare's elevator the attitude loop keeps at touchdown (sim.flight.pilot.rollout.Rollout):
    # 0 relaxes it to the loop's own (half its integrator), 1 keeps it all
    touchdown_elevator_keep: float = 0.0
    # maximum operating altitude (type certificate data sheet): the highest step climb (sim.flight.pilot.step_climb)
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
    # attitude and speed loop gains (flightmode.sim.flight.pilot.autopilot)
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
    elevator_nose_up_deg: float | None = (
        None  # extends the model's elevator travel (sim.flight.jsbsim.model_edits)
    )
    spread_spoiler_lift: bool = (
        False  # the ground spoilers' lift loss over their whole travel (sim.flight.jsbsim.model_edits)
    )
    add_ground_spoilers: bool = (
        False  # ground spoilers for a model without them (sim.flight.jsbsim.model_edits)
    )
    nose_side_friction: float | None = (
        None  # sets the nose tyre's side-force peak (sim.flight.jsbsim.model_edits)
    )
    vr_ref_mass_kg: float | None = None  # the mass vr_kt holds at (None: vr_kt at any mass)
    nose_static_deflection_m: float | None = (
        None  # a softer nose strut at the same stance (sim.flight.jsbsim.gear.set_nose_strut)
    )
    tuning: PilotTuning = field(default_factory=PilotTuning)
