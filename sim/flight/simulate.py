"""Fly a :class:`~flightmode.sim.flight.plan.FlightPlan` gate to gate in JSBSim and return its
:class:`~flightmode.sim.flight.track.FlightTrack`.

The FDM runs at the plan's ``fdm_hz`` (120 Hz by default); every step's state is recorded (the
FlightTrack rate); the pilot ticks at 4-40 Hz by phase (:attr:`Pilot.control_every`: 40 Hz on the
runway and below 1000 ft, 5 Hz en route). Per-flight draws (:mod:`flightmode.sim.flight.draws`: the
climb's rates, the touchdown sink, the turbulence) come from the flight's named streams; the gusts
(:mod:`flightmode.sim.flight.turbulence`) are written into JSBSim before every step while airborne.
The same plan and streams give a bit-identical track.

Terrain: JSBSim's terrain is one flat elevation. It is the origin's elevation on the ground and is
switched to the destination's at the top of climb (the aircraft is then far above both).
"""

from __future__ import annotations

import dataclasses
import math
import operator
from array import array
from collections.abc import Callable, Mapping
from pathlib import Path

import numpy as np

from flightmode.errors import AircraftError, FlightDivergedError
from flightmode.labels import AIRBORNE_PHASES, PHASE_CODE, PHASES
from flightmode.sim.flight import geodesy
from flightmode.sim.flight.aircraft.registry import get_profile
from flightmode.sim.flight.draws import draw_flight
from flightmode.sim.flight.geodesy import RunwayFrame
from flightmode.sim.flight.jsbsim.adapter import ROTATIONAL_RATE_INTEGRATOR_RECT_EULER, JSBSimAircraft
from flightmode.sim.flight.jsbsim.model_edits import edits_for
from flightmode.sim.flight.pilot.ground import pushback_tuning
from flightmode.sim.flight.pilot.pilot import Pilot
from flightmode.sim.flight.plan import FlightPlan
from flightmode.sim.flight.taxi_route import draw_taxi
from flightmode.sim.flight.track import Event, FlightTrack, euler_to_quat_wxyz
from flightmode.sim.flight.turbulence import GustFeed, GustField
from flightmode.streams import Streams, as_streams
from flightmode.units import FT_M, LB_KG


def max_duration_s(plan: FlightPlan) -> float:
    """A generous time limit: a flight slower than this is stuck, not slow."""
    d = float(
        geodesy.great_circle_distance_m(
            plan.origin.lat_deg, plan.origin.lon_deg, plan.destination.lat_deg, plan.destination.lon_deg
        )
    )
    ground = plan.gate_wait_s + sum(plan.taxi_out.holds_s) + sum(plan.taxi_in.holds_s) + 2 * 3600.0
    return ground + d / 120.0 + 3600.0  # 120 m/s: slower than any airliner's mean speed


# the fuel an airline loads beyond the trip: 30 min at holding speed (final reserve, ICAO Annex 6
# Part I 4.3.6.3) and about as much again for contingency (5 % of the trip) and an alternate; as
# hours of the type's mean burn
RESERVE_H = 1.0
# climb and descent take longer than cruising the same ground distance: about 0.3 h on any airliner's
# profile (WRAP's climb and descent phases against cruise TAS)
CLIMB_DESCENT_EXTRA_H = 0.3


# on the ground the engines idle: a tenth of the airborne burn (the gate wait counted too, with the APU)
TAXI_BURN_FRACTION = 0.1


def planned_fuel_kg(plan: FlightPlan, prof) -> float:
    """The fuel planned at the gate: the type's mean airborne burn over the estimated airborne time
    plus reserves (:data:`RESERVE_H`), and taxi fuel; never less than the profile's ``fuel_kg``. The
    tanks may hold less: the track's conditions record what was loaded (``fuel_loaded_kg``)."""
    d = float(
        geodesy.great_circle_distance_m(
            plan.origin.lat_deg, plan.origin.lon_deg, plan.destination.lat_deg, plan.destination.lon_deg
        )
    )
    ground_h = (plan.gate_wait_s + sum(plan.taxi_out.holds_s) + sum(plan.taxi_in.holds_s)) / 3600.0 + 0.5
    tas_mps = prof.cruise_mach * 295.0  # the speed of sound in the ISA above 36,000 ft (295 m/s)
    airborne_h = d / tas_mps / 3600.0 + CLIMB_DESCENT_EXTRA_H
    return max(prof.fuel_kg, prof.burn_kg_per_h * (airborne_h + RESERVE_H + TAXI_BURN_FRACTION * ground_h))


def _fuel_lbs(ac: JSBSimAircraft) -> float:
    """The fuel in every tank (``propulsion/total-fuel-lbs`` is only summed when the FDM runs)."""
    total, i = 0.0, 0
    while ac.has(f"propulsion/tank[{i}]/contents-lbs"):
        total += ac.get(f"propulsion/tank[{i}]/contents-lbs")
        i += 1
    return total


def _load_fuel(ac: JSBSimAircraft, fuel_kg: float) -> None:
    """Fill the model's (initially non-empty) tanks with ``fuel_kg`` in proportion to capacity."""
    caps = []
    i = 0
    while ac.has(f"propulsion/tank[{i}]/contents-lbs"):
        pct = ac.get(f"propulsion/tank[{i}]/pct-full")
        caps.append(ac.get(f"propulsion/tank[{i}]/contents-lbs") * 100.0 / pct if pct > 0 else 0.0)
        i += 1
    total = sum(caps)
    for i, cap in enumerate(caps):
        ac.set(f"propulsion/tank[{i}]/contents-lbs", min(cap, fuel_kg / LB_KG * cap / total))


SETTLE_S = 8.0  # FDM time let run after run_ic, before the track's t = 0


def fly(
    plan: FlightPlan,
    streams: Streams | np.random.Generator | int,
    *,
    workdir: Path | None = None,
    progress: Callable[[float, str], None] | None = None,
    stop_after_s: float | None = None,
    overrides: Mapping[str, float] | None = None,
) -> FlightTrack:
    """Fly ``plan`` gate to gate; raise :class:`FlightDivergedError` if the flight fails.

    ``streams``: the flight's random streams (:class:`flightmode.streams.Streams`; a Generator or an
    integer seed is turned into streams), by name: ``climb``, ``landing``, ``turbulence/atmosphere``
    (the draws), ``turbulence/field`` (the gusts) and ``taxi`` (the taxi routes and speeds).
    ``progress(t_s, phase)`` is called about once per simulated minute. ``stop_after_s``: stop after
    that much simulated time (a preview, or a quick check: the track is then the exact prefix of the
    whole flight's, its in-flight window running to its end if the engines still run).
    ``overrides``: the run's uncertain model parameters (a scenario's ``[model]`` table: name -> value,
    :mod:`flightmode.uncertain`), passed to the functions that read them; None: every one nominal.
    """
    streams = as_streams(streams)
    fdm_hz = float(plan.fdm_hz)
    prof = get_profile(plan.aircraft)
    if (tuning := pushback_tuning(prof.tuning, overrides)) is not prof.tuning:  # [model] pushback.*
        prof = dataclasses.replace(prof, tuning=tuning)
    # flightmode's changes to the stock model, each with its reason (sim.flight.jsbsim.model_edits)
    ac = JSBSimAircraft(plan.aircraft, 1.0 / fdm_hz, prof.n_engines, workdir=workdir, edits=edits_for(prof))
    origin = RunwayFrame(plan.origin)
    taxi = draw_taxi(plan, prof, streams.rng("taxi"))  # the taxi routes and the departure stand
    (gx, gy), gh = taxi.stand_xy_m, taxi.stand_heading_rad
    lat0, lon0 = origin.to_latlon(gx, gy)
    ac.init_on_ground(
        lat0, lon0, plan.origin.elevation_m, (plan.origin.heading_deg + math.degrees(gh)) % 360.0
    )
    fuel_kg = planned_fuel_kg(plan, prof)
    _load_fuel(ac, fuel_kg)
    fuel_start_lbs = _fuel_lbs(ac)
    ac.set("atmosphere/turb-type", 0)  # JSBSim's own turbulence is off: flightmode feeds its gusts
    if ac.get("simulation/integrator/rate/rotational") != ROTATIONAL_RATE_INTEGRATOR_RECT_EULER:
        # the track's angular acceleration is the rates' forward difference (jsbsim.adapter, the
        # comment above ROTATIONAL_RATE_INTEGRATOR_RECT_EULER)
        raise AircraftError(
            f"'{plan.aircraft}' integrates its body rates with JSBSim integrator "
            f"{ac.get('simulation/integrator/rate/rotational'):g}, not rectangular Euler (1): "
            "remove the model's <integrator> setting"
        )
    ac.set("propulsion/cutoff_cmd", 1)
    draws = draw_flight(plan, prof, streams, overrides)
    pilot = Pilot(ac, plan, prof, fdm_hz, draws, taxi)
    gusts = GustFeed(ac, GustField(fdm_hz, streams.rng("turbulence/field")), draws.atmosphere, ac.index)
    # JSBSim's state straight after run_ic is the requested initial condition, not yet resolved on
    # its gear: its first step moves the aircraft 0.2 m at once, and the gear then settles for about
    # 4 s (0.08 m/s, a few m/s^2). Let it settle before recording, so that the track starts truly at
    # rest at the gate (a 0.2 m jump in one 1/120 s step is 3,000 m/s^2 of phantom acceleration to anything
    # that integrates the track, such as nav/).
    for _ in range(int(SETTLE_S * fdm_hz)):
        ac.step()
    # the CG's height on the settled gear (the pilot's flare and liftoff heights refer to it)
    pilot.set_cg_height(ac.get("position/h-agl-ft") * FT_M)
    from flightmode.sim.flight.jsbsim.roughness import GearRoughness

    # runway and taxiway roughness felt through the gear (made at rest: the static loads set the tyres)
    rough_tick = GearRoughness(ac, streams, fdm_hz).tick

    nch = len(ac.channels)
    nf = ac.n_every_step  # channels recorded every step; the rest at the pilot's ticks
    scales_list = ac.scales.tolist()
    get, nodes = ac.raw_getter()
    fast_nodes = nodes[:nf]
    run = ac.fdm.run
    set_gust, (node_n, node_e, node_d) = gusts.set, gusts.nodes
    mul = operator.mul
    i_alt = ac.index["alt_m"]
    data = array("d")  # every step's fast channels, appended in place (no per-step NumPy work)
    ext = data.extend
    slow = array("d")  # the slow channels at each tick
    ext_slow = slow.extend
    tick_steps = array("q")
    changes: list[tuple[int, int, int]] = [(0, pilot.phase_code, pilot.severity_code)]
    i_wow, i_vd = ac.index["wow"], ac.index["v_down_mps"]
    if max(i_wow, i_vd) >= nf:
        raise RuntimeError(
            "jsbsim.adapter: wow and v_down_mps must be recorded every step (not slow channels)"
        )
    flare_code = PHASE_CODE["flare"]

    def contact_sink_mps() -> float:
        """The sink (m/s) at the last recorded step before the main gear's first contact in the last
        flare: the sample flight_metrics' touchdown_sink_mps reads from the track (Pilot.contact_sink_mps)."""
        k = len(changes) - 1
        while changes[k][1] != flare_code:
            k -= 1
        while k > 0 and changes[k - 1][1] == flare_code:  # the last flare span's first row
            k -= 1
        row, rows = changes[k][0], len(data) // nf
        while row < rows and data[row * nf + i_wow] <= 0.5:
            row += 1
        return data[(row - 1) * nf + i_vd] * scales_list[i_vd]

    pilot.contact_sink_mps = contact_sink_mps
    limit_steps = int(max_duration_s(plan) * fdm_hz)
    step = 0
    terrain_m = plan.origin.elevation_m
    dest_terrain_from = None  # first step whose state lies over the destination's terrain
    next_progress = 0.0
    stop_steps = None if stop_after_s is None else int(stop_after_s * fdm_hz)
    while not pilot.done and (stop_steps is None or step < stop_steps):
        # a control tick: sample every channel, decide, step
        raw = list(map(get, nodes))
        ext(raw[:nf])
        ext_slow(raw[nf:])
        tick_steps.append(step)
        t = step / fdm_hz
        codes = (pilot.phase_code, pilot.severity_code)
        x = list(map(mul, raw, scales_list))  # SI floats
        x.append(x[i_alt] - terrain_m)  # the derived channels (jsbsim.adapter.DERIVED_CHANNELS)
        pilot.tick(x, t)
        if (pilot.phase_code, pilot.severity_code) != codes:
            # labels change at the sample whose state made the pilot change phase
            changes.append((step, pilot.phase_code, pilot.severity_code))
        if dest_terrain_from is None and pilot.phase in ("cruise", "descent", "approach"):
            terrain_m = plan.destination.elevation_m
            ac.set("position/terrain-elevation-asl-ft", terrain_m / FT_M)
            dest_terrain_from = step + 1
        if progress is not None and t >= next_progress:
            progress(t, pilot.phase)
            next_progress = t + 60.0
        every = 1 if pilot.done else pilot.control_every
        rough_tick(x, pilot.phase, every)  # the roughness forces' knots for these steps
        if pilot.gust_sigma_mps is not None:
            # turbulent air: a gust for every step (turbulence.GustFeed), then record and step
            gn, ge, gd = gusts.take(every, x, pilot.gust_sigma_mps)
            set_gust(node_n, gn[0])
            set_gust(node_e, ge[0])
            set_gust(node_d, gd[0])
            run()
            for k in range(1, every):
                ext(map(get, fast_nodes))
                set_gust(node_n, gn[k])
                set_gust(node_e, ge[k])
                set_gust(node_d, gd[k])
                run()
        else:
            gusts.stop()
            run()
            # the steps between ticks: record the fast channels and step, nothing else
            for _ in range(every - 1):
                ext(map(get, fast_nodes))
                run()
        step += every
        if step > limit_steps:
            raise FlightDivergedError(
                f"the flight did not reach the stand within {limit_steps / fdm_hz:.0f} s "
                "(simulate.max_duration_s: its ground time, the distance at 120 m/s, and 3 h)",
                phase=pilot.phase,
                t_s=step / fdm_hz,
                kind="stand_time",
                quantity="simulated time (s)",
                value=step / fdm_hz,
                limit=limit_steps / fdm_hz,
            )
    # the rates one step past the last row: the last row's angular acceleration (_to_track)
    rates_after = [get(nodes[ac.index[name]]) for name in ("p_radps", "q_radps", "r_radps")]
    fast = np.frombuffer(data, dtype=np.float64).reshape(-1, nf)  # (steps, fast channels), raw units
    ticks = np.frombuffer(tick_steps, dtype=np.int64)
    at_ticks = np.frombuffer(slow, dtype=np.float64).reshape(-1, nch - nf)
    all_steps = np.arange(step, dtype=np.float64)
    slow_cols = []  # the slow channels at every step: linear between ticks (jsbsim.adapter.Channel)
    for j, ch in enumerate(ac.channels[nf:]):
        if ch.name == "alpha_rad":  # an angle: interpolated the short way round (it wraps at standstill)
            slow_cols.append(np.angle(np.exp(1j * np.interp(all_steps, ticks, np.unwrap(at_ticks[:, j])))))
        else:
            slow_cols.append(np.interp(all_steps, ticks, at_ticks[:, j]))
    terrain = np.full(step, plan.origin.elevation_m)
    if dest_terrain_from is not None:
        terrain[dest_terrain_from:] = plan.destination.elevation_m
    starts = np.array([c[0] for c in changes] + [step])
    reps = np.diff(starts)
    phase_code = np.repeat(np.array([c[1] for c in changes], dtype=np.uint8), reps)
    turb_code = np.repeat(np.array([c[2] for c in changes], dtype=np.uint8), reps)
    events = tuple(Event(t, n, d) for t, n, d in pilot.events)
    track = _to_track(plan, ac, fast, slow_cols, terrain, phase_code, turb_code, events, rates_after)
    fuel = {
        "fuel_planned_kg": fuel_kg,
        "fuel_loaded_kg": fuel_start_lbs * LB_KG,
        "fuel_used_kg": (fuel_start_lbs - _fuel_lbs(ac)) * LB_KG,
    }
    cab = pressure_truth(track, plan, draws, overrides)
    return dataclasses.replace(
        track,
        conditions=draws.as_dict()
        | {"takeoff_thrust_norm": pilot.takeoff_thrust_norm}
        | taxi.as_dict()
        | {"cg_height_m": pilot.prof.cg_height_m}
        | fuel
        | {
            "cruise_cabin_altitude_m": cab.cruise_cabin_altitude_m,
            "cabin_descent_rate_fpm": cab.descent_rate_fpm,
            "hold": cab.hold,
        },
        ambient_pressure_pa=cab.ambient_pressure_pa,
        cabin_pressure_pa=cab.cabin_pressure_pa,
        cabin_altitude_m=cab.cabin_altitude_m,
        hold_pressure_pa=cab.hold_pressure_pa,
    )


def pressure_truth(track: FlightTrack, plan: FlightPlan, draws, overrides: Mapping[str, float] | None = None):
    """The flight's pressure truth (:func:`flightmode.sim.flight.cabin.cabin_pressure`): the type's
    schedule to the plan's cruise level, under the drawn (or fixed) weather at both airports, with the
    run's uncertain model parameters ``overrides``."""
    from flightmode.sim.flight.cabin import cabin_pressure

    return cabin_pressure(
        track.t_s,
        track.alt_m,
        track.phase_code,
        plan.cruise_alt_m,
        plan.aircraft,
        weather=draws.departure_weather,
        arrival_weather=draws.arrival_weather,
        departure_elev_m=plan.origin.elevation_m,
        arrival_elev_m=plan.destination.elevation_m,
        hold=plan.hold,
        overrides=overrides,
    )


SI_BLOCK_ROWS = 16_384  # _si_groups' block of the record: 16,384 rows x 16 channels x 8 B = 2 MiB


def _si_groups(
    ac, fast: np.ndarray, slow_cols: list[np.ndarray], groups: dict[str, list[int]]
) -> dict[str, np.ndarray]:
    """SI arrays from the raw record: ``fast`` (steps, fast channels) and ``slow_cols`` (one array per
    slow channel, every step), in jsbsim.adapter's channel order; one (steps,) array per one-channel
    group, one (steps, k) array per group of k. Each value is scaled once, straight into its array:
    a whole scaled copy of the record first was a second 100+ MB array to fill and read again. The
    fast channels are read a block of rows at a time (``SI_BLOCK_ROWS``, 2 MiB, held in the cache
    while every group takes its columns): a column read whole strides the record 16 values apart, one
    cache line per value: this function took 0.46 s of a 1.5 h flight's 666,000 steps that way, 0.18 s
    by blocks. The same products, so the same bits (the flight's digest is unchanged)."""
    nf, scales = fast.shape[1], ac.scales
    n = fast.shape[0]
    out: dict[str, np.ndarray] = {}
    # (a (steps, k) view of the output array, its column, channel index) for every fast channel used; a
    # one-channel group's (steps,) array is viewed as (steps, 1)
    fast_parts: list[tuple[np.ndarray, int, int]] = []
    for name, idx in groups.items():
        arr = out[name] = np.empty(n) if len(idx) == 1 else np.empty((n, len(idx)))
        cols = arr.reshape(n, len(idx))  # a view
        for j, i in enumerate(idx):
            if i < nf:
                fast_parts.append((cols, j, i))
            else:
                cols[:, j] = slow_cols[i - nf] * scales[i]
    for r0 in range(0, n, SI_BLOCK_ROWS):
        block = fast[r0 : r0 + SI_BLOCK_ROWS]
        for cols, j, i in fast_parts:
            np.multiply(block[:, i], scales[i], out=cols[r0 : r0 + SI_BLOCK_ROWS, j])
    return out


def _to_track(
    plan, ac, fast, slow_cols, terrain_m, phase_code, turb_code, events, rates_after
) -> FlightTrack:
    """Assemble the FlightTrack from the raw record (``fast``: (steps, fast channels); ``slow_cols``: the
    slow channels interpolated to every step), the terrain per step and the body rates one step past
    the last row (rad/s)."""
    ix = ac.index
    ne = get_profile(plan.aircraft).n_engines
    one = lambda name: [ix[name]]  # noqa: E731
    three = lambda *names: [ix[k] for k in names]  # noqa: E731
    eng = lambda key: [ix[f"{key}_{i}"] for i in range(ne)]  # noqa: E731
    groups = {
        name: one(name)
        for name in (
            "lat_deg",
            "lon_deg",
            "alt_m",
            "wow",
            "flap_norm",
            "gear_norm",
            "speedbrake_norm",
            "ias_mps",
            "tas_mps",
            "mach",
            "alpha_rad",
        )
    }
    groups |= {
        "euler": three("phi_rad", "theta_rad", "psi_rad"),
        "rates": three("p_radps", "q_radps", "r_radps"),
        "vel": three("v_north_mps", "v_east_mps", "v_down_mps"),
        "sf": three("fx_mps2", "fy_mps2", "fz_mps2"),
        "n1": eng("n1_pct"),
        "n2": eng("n2_pct"),
        "thrust": eng("thrust_n"),
    }
    g = _si_groups(ac, fast, slow_cols, groups)
    col = g.__getitem__
    n = fast.shape[0]
    fdm_hz = float(plan.fdm_hz)
    t = np.arange(n) / fdm_hz
    o = plan.origin
    pos = geodesy.geodetic_to_ned(
        col("lat_deg"), col("lon_deg"), col("alt_m"), o.lat_deg, o.lon_deg, o.elevation_m
    )
    vel = g["vel"]
    # JSBSim's own angular acceleration of each step: the rates' forward difference (rectangular
    # Euler: jsbsim.adapter, ROTATIONAL_RATE_INTEGRATOR_RECT_EULER)
    ang_acc = np.diff(g["rates"], axis=0, append=np.asarray(rates_after)[None, :]) * fdm_hz
    euler = g["euler"]
    t_push = next((e.t_s for e in events if e.name == "pushback"), math.inf)
    t_off = next((e.t_s for e in events if e.name == "engines_off"), math.inf)  # a stopped flight
    airborne_codes = np.array([PHASE_CODE[p] for p in AIRBORNE_PHASES])
    return FlightTrack(
        aircraft=plan.aircraft,
        fs_hz=fdm_hz,
        origin_lat_deg=o.lat_deg,
        origin_lon_deg=o.lon_deg,
        origin_alt_m=o.elevation_m,
        t_s=t,
        lat_deg=col("lat_deg"),
        lon_deg=col("lon_deg"),
        alt_m=col("alt_m"),
        agl_m=col("alt_m") - terrain_m,
        pos_ned_m=pos,
        vel_ned_mps=vel,
        euler_rad=euler,
        quat_wxyz=euler_to_quat_wxyz(euler),
        rates_radps=g["rates"],
        ang_acc_radps2=ang_acc,
        specific_force_body_mps2=g["sf"],
        n1_pct=g["n1"],
        n2_pct=g["n2"],
        thrust_n=g["thrust"],
        wow=col("wow") > 0.5,
        flap_norm=col("flap_norm"),
        gear_norm=col("gear_norm"),
        speedbrake_norm=col("speedbrake_norm"),
        ias_mps=col("ias_mps"),
        tas_mps=col("tas_mps"),
        mach=col("mach"),
        alpha_rad=col("alpha_rad"),
        ground_speed_mps=np.hypot(vel[:, 0], vel[:, 1]),
        vertical_speed_mps=-vel[:, 2],
        phase_code=phase_code,
        in_flight_window=(t >= t_push) & (t < t_off),
        airborne=np.isin(phase_code, airborne_codes) & (col("wow") < 0.5),
        turbulence_code=turb_code,
        events=events,
    )


__all__ = ["fly", "PHASES"]
