"""The pilot's procedures, limits and loop gains: one :class:`PilotTuning` for every type unless its
profile (:mod:`flightmode.sim.flight.aircraft.profile`) sets its own."""

from __future__ import annotations

from dataclasses import dataclass

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
    taxi_ref_tau_s: float = 2.0  # the taxi speed reference's lag (sim.flight.pilot.taxi.Taxi)
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
