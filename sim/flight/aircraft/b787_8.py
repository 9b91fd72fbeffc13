"""The Boeing 787-8 (the JSBSim 787-8, Trent 1000) profile: its speeds, schedules, procedures and gains for
:class:`~flightmode.sim.flight.aircraft.profile.AircraftProfile`, each figure with its source or the
measurement it was tuned on."""

from __future__ import annotations

from flightmode.sim.flight.aircraft.performance import ClimbSchedule, Spread, TakeoffThrust
from flightmode.sim.flight.aircraft.profile import AircraftProfile, ApproachStep
from flightmode.units import FT_M

PROFILE = AircraftProfile(
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
    cg_height_m=13.78 * FT_M,
    wheelbase_m=22.8,
    # at least 40 t: short routes land at 163-166 t, under the 787-8's 172 t maximum landing mass
    # (OpenAP prop "mlw"), within the masses its flare was tuned at. On 20 European routes
    # (european-trio's, one 787 each): at a 50 t floor all landed, at 173-175 t (over the MLW); at
    # 44 t one floated 4.3 km down the runway and off its end, and at 40 t the same flight floated
    # 3.2 km, before the pilot flew go-arounds; with them (a float over the runway's second half goes
    # around: sim.flight.pilot.flare.FLOAT_LIMIT_FRACTION) it goes around once and lands 460 m past
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
    # and its mass-scaled Vapp (pilot.autopilot.Autopilot.vapp_mps) was then 158 kt, 13 kt over vapp_kt.
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
    # (pilot.enroute.FINAL_PITCH_MARGIN_DEG). With the floor lowered (its 10 s mean), the flare from 70 ft,
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
    # the floats past the touchdown zone (914 m, FAA AIM 2-1-5) left: the exponential flare from 75 ft
    # lasts tau ln(1 + h / (v_td tau)), long when the drawn touchdown sink v_td is small (0.9-1.1 ft/s)
    # or the flare begins late (the gear 100 ft up at the threshold): pattern seeds 136-155 floated
    # 10-12.5 s, 3 of 20 past 914 m (952, 972, 989 m). A crew does not hold off a float for a soft
    # landing (Airplane Flying Handbook, FAA-H-8083-3, floating during round out: prolonged floating
    # uses considerable runway and should be avoided): past the zone's middle (457 m) the flare aims at
    # 3 ft/s at least. The same
    # seeds: 0 of 20 past 914 m (at most 901), touchdown median 706 -> 644 m; flown sink median 2.30 ->
    # 2.67 ft/s, p90 3.63 -> 3.98, flown minus drawn +0.71 -> +1.10 (a floor of 2 ft/s, or from 600 m,
    # left 1-3 floats); held out, seeds 56-75: 1 -> 0 past 914 m (976 -> 850 m), sink median 2.55 ->
    # 2.59 ft/s, p90 4.37 both, flown minus drawn +0.52 -> +0.61; routes, european-787 members 0-19: 1 -> 0
    # past 914 m (member 11, LOWW-EGLL: 936 -> 786 m; flightmode validate: that row FAIL -> pass, the
    # other 56 rows' statuses unchanged), sink median 2.63 -> 2.73 ft/s, p90 4.38 -> 5.17, max 8.53 both
    flare_settle_from_m=457.2,
    flare_settle_sink_mps=3.0 * FT_M,
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
)
