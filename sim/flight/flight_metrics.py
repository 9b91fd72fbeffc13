"""Kinematic figures of a flown FlightTrack, measured from its arrays (not from the pilot).

The definitions follow OpenAP WRAP's quantities (the ADS-B kinematic model of Sun et al., package
``openap``), so the figures can be checked against
real-traffic ranges: liftoff speed, takeoff acceleration, initial climb rate, cruise altitude,
final-approach vertical rate, landing (touchdown) speed and braking deceleration. All SI.
"""

from __future__ import annotations

import math

import numpy as np

from flightmode.errors import InputDataError
from flightmode.labels import PHASE_CODE
from flightmode.sim.flight.geodesy import RunwayFrame
from flightmode.sim.flight.plan import FlightPlan
from flightmode.sim.flight.track import FlightTrack
from flightmode.units import FT_M, G0_MPS2


def _phase_span(track: FlightTrack, phase: str) -> tuple[int, int]:
    idx = np.flatnonzero(track.phase_code == PHASE_CODE[phase])
    if idx.size == 0:
        raise InputDataError(
            f"the track has no '{phase}' phase: flight figures need a whole gate-to-gate flight "
            "(fly it with flightmode.run or `flightmode fly`)"
        )
    return int(idx[0]), int(idx[-1])


def _last_span_start(track: FlightTrack, phase: str) -> int:
    """The first sample of the phase's last span (a go-around flies a second approach and flare)."""
    first, last = _phase_span(track, phase)
    idx = np.flatnonzero(track.phase_code[first : last + 1] != PHASE_CODE[phase])
    return first if idx.size == 0 else first + int(idx[-1]) + 1


def touchdown_index(track: FlightTrack) -> int:
    """The touchdown sample: the first weight-on-wheels sample of the (last) flare. The sample before it
    is the touchdown's sink (the flight's hard-landing check reads the same one while flying)."""
    f0 = _last_span_start(track, "flare")
    return f0 + int(np.argmax(track.wow[f0:]))


def takeoff_accel_mps2(track: FlightTrack) -> float:
    """WRAP's takeoff acceleration: the mean along the ground roll, brake release to liftoff (ground
    speed at liftoff over the roll's time). Needs only the track up to liftoff."""
    t_roll = track.event_time("takeoff_roll")
    i_lo = int(np.searchsorted(track.t_s, track.event_time("liftoff")))
    return float(track.ground_speed_mps[i_lo] / (track.t_s[i_lo] - t_roll))


def initial_climb_vs_mps(track: FlightTrack, plan: FlightPlan) -> float:
    """WRAP's initial climb rate: the mean vertical rate from liftoff to 1,500 ft above the runway.
    Needs only the track up to there."""
    t = track.t_s
    i_lo = int(np.searchsorted(t, track.event_time("liftoff")))
    agl_o = track.alt_m - plan.origin.elevation_m
    i_1500 = i_lo + int(np.argmax(agl_o[i_lo:] > 1500 * FT_M))
    return float((track.alt_m[i_1500] - track.alt_m[i_lo]) / (t[i_1500] - t[i_lo]))


def flight_metrics(track: FlightTrack, plan: FlightPlan) -> dict[str, float]:
    """Figures of one gate-to-gate flight; see the module docstring. Keys carry their units."""
    t = track.t_s
    gs = track.ground_speed_mps
    vs = track.vertical_speed_mps
    m: dict[str, float] = {}
    t_push = track.event_time("pushback")
    t_roll = track.event_time("takeoff_roll")
    i_lo = int(np.searchsorted(t, track.event_time("liftoff")))
    m["gate_to_gate_s"] = float(t[-1] - t[0])
    m["taxi_out_s"] = t_roll - t_push
    m["liftoff_ias_mps"] = float(track.ias_mps[i_lo])
    m["liftoff_gs_mps"] = float(gs[i_lo])
    m["takeoff_accel_mps2"] = takeoff_accel_mps2(track)
    m["initial_climb_vs_mps"] = initial_climb_vs_mps(track, plan)
    c0, c1 = _phase_span(track, "cruise")
    m["cruise_alt_m"] = float(np.median(track.alt_m[c0 : c1 + 1]))
    m["max_alt_m"] = float(track.alt_m.max())
    i_td = touchdown_index(track)
    m["touchdown_sink_mps"] = float(-vs[i_td - 1])  # the sample the hard-landing check reads (simulate.fly)
    m["touchdown_ias_mps"] = float(track.ias_mps[i_td])
    m["touchdown_gs_mps"] = float(gs[i_td])
    frame = RunwayFrame(plan.destination)
    x_td, y_td = frame.to_xy(float(track.lat_deg[i_td]), float(track.lon_deg[i_td]))
    m["touchdown_past_threshold_m"] = x_td
    m["touchdown_centreline_offset_m"] = y_td
    # final approach: mean vertical rate from 1000 ft to 100 ft above the destination
    h_d = track.alt_m[:i_td] - plan.destination.elevation_m
    a0 = _last_span_start(track, "approach")
    sel = np.flatnonzero((h_d[a0:] < 1000 * FT_M) & (h_d[a0:] > 100 * FT_M)) + a0
    m["final_approach_vs_mps"] = float(np.mean(vs[sel]))
    # rollout: touchdown to the runway exit (start of taxi-in)
    ti0, _ = _phase_span(track, "taxi_in")
    m["rollout_decel_mps2"] = float((gs[i_td] - gs[ti0]) / (t[ti0] - t[i_td]))
    x_exit, _ = frame.to_xy(float(track.lat_deg[ti0]), float(track.lon_deg[ti0]))
    m["rollout_distance_m"] = x_exit - x_td
    s0, _ = _phase_span(track, "shutdown")
    m["taxi_in_s"] = float(t[s0] - t[ti0])
    m["engines_off_s"] = track.event_time("engines_off")
    m["max_bank_deg"] = float(np.degrees(np.abs(track.euler_rad[:, 0]).max()))
    airborne = track.airborne
    m["airborne_s"] = float(airborne.sum() / track.fs_hz)
    m["max_load_factor_g"] = float((-track.specific_force_body_mps2[:, 2] / G0_MPS2).max())
    m["min_load_factor_g"] = float((-track.specific_force_body_mps2[:, 2][airborne] / G0_MPS2).min())
    for k, v in m.items():
        if not math.isfinite(v):
            raise InputDataError(
                f"flight figure {k} is {v}: the track holds NaN or a phase of zero length "
                "(re-fly the scenario)"
            )
    return m
