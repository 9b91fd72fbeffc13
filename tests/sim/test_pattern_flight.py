"""The fast `pattern` flight (about 3 s of wall time): a whole gate-to-gate cycle, determinism,
labels, turbulence seeding and failure handling."""

from __future__ import annotations

import dataclasses
import subprocess
import sys

import numpy as np
import pytest

from flightmode.errors import FlightDivergedError
from flightmode.labels import PHASE_CODE
from flightmode.sim.flight.plan import TurbulenceSegment


def test_pattern_flies_gate_to_gate(fly_cached):
    sc, tr = fly_cached("pattern")
    names = [e.name for e in tr.events]
    order = [
        "gate",
        "engine_start",
        "pushback",
        "taxi_out",
        "takeoff_roll",
        "initial_climb",
        "approach",
        "flare",
        "rollout",
        "taxi_in",
        "shutdown",
        "engines_off",
        "parked",
    ]
    positions = [names.index(n) for n in order]
    assert positions == sorted(positions), "phases out of order"
    # under 15 simulated minutes from brake release to touchdown (the circuit), whole cycle < 20 min
    assert tr.event_time("touchdown") - tr.event_time("takeoff_roll") < 15 * 60
    assert tr.duration_s < 20 * 60
    # it ends parked, engines off, at rest, back on the ground
    assert tr.phase[-1] == "parked"
    assert np.all(tr.n2_pct[-1] < 5.0)
    assert tr.ground_speed_mps[-1] < 0.05
    assert tr.wow[-1]
    # the whole track is finite
    for name in ("lat_deg", "lon_deg", "alt_m", "pos_ned_m", "specific_force_body_mps2", "quat_wxyz"):
        assert np.isfinite(getattr(tr, name)).all(), name


def test_labels_follow_the_events(fly_cached):
    _, tr = fly_cached("pattern")
    t_push, t_off = tr.event_time("pushback"), tr.event_time("engines_off")
    win = np.flatnonzero(tr.in_flight_window)
    dt = 1.0 / tr.fs_hz
    # the window starts at pushback and ends at engines off, to one sample
    assert abs(tr.t_s[win[0]] - t_push) <= dt and abs(tr.t_s[win[-1]] + dt - t_off) <= dt
    assert np.all(np.diff(win) == 1)  # one contiguous window
    # airborne only between liftoff and touchdown, and never on the gear
    air = tr.airborne
    assert not np.any(air & tr.wow)
    assert tr.t_s[air][0] >= tr.event_time("liftoff") - dt
    assert tr.t_s[air][-1] <= tr.event_time("touchdown")
    # every airborne sample is inside the in-flight window
    assert np.all(tr.in_flight_window[air])
    # a parked aircraft at the gate is not in the window
    assert not tr.in_flight_window[tr.phase_code == PHASE_CODE["gate"]].any()


def test_same_seed_is_bit_identical_in_process_and_across_processes(fly_cached):
    from flightmode.runs import pipeline

    sc, tr = fly_cached("pattern")
    again = pipeline.fly(sc, pipeline.streams_of(sc.seed).child("flight"))
    assert again.digest() == tr.digest()
    code = "import flightmode; print(flightmode.run('pattern', stages=('fly',)).track.digest())"
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip().splitlines()[-1] == tr.digest()


def _turbulent(fly_cached, seed):
    """The pattern to 720 s, the exact prefix of its whole flight: the patch (liftoff, at 368 s on seed
    2 and 373 s on seed 4, + 120 s to + 240 s) and 100 s of air after it; the draws are made at the
    gate."""
    seg = (TurbulenceSegment(start_s=120.0, duration_s=120.0, severity="moderate"),)
    return fly_cached("pattern", seed=seed, stop_after_s=720.0, turbulence=seg)


def test_another_seed_gives_another_flight_and_air(fly_cached):
    """The seed draws the flight's variable parts (climb rates, touchdown sink, the air's background
    and the patch's EDR, the gusts themselves); the plan's turbulence patch is where it says in both,
    labelled exactly, and much rougher than the air around it."""
    from flightmode.sim.flight.turbulence import EDR_BANDS

    _, a = _turbulent(fly_cached, 2)
    _, b = _turbulent(fly_cached, 4)
    ca, cb = a.conditions, b.conditions
    for key in ("climb_vs_mps", "touchdown_sink_target_mps", "surface_wind_mps", "background_edr_mid"):
        assert ca[key] != cb[key], key
    for tr, c in ((a, ca), (b, cb)):
        lo, hi = EDR_BANDS["moderate"]
        assert lo <= c["patch_edr"][0] <= hi
        t0 = tr.event_time("liftoff") + 120.0
        # the pilot switches turbulence on at its first tick after the planned start (ticks are at
        # most 0.2 s apart in flight), and the label follows the switch exactly
        t_on = tr.t_s[np.argmax(tr.turbulence_code == 2)]
        assert t0 <= t_on <= t0 + 0.25
        on = np.flatnonzero(tr.turbulence_code == 2)
        t_off = tr.t_s[on[-1]]
        assert t0 + 120.0 - 0.25 <= t_off <= t0 + 120.0 + 0.25  # and off at its first tick after the end
        np.testing.assert_array_equal(on, np.arange(on[0], on[-1] + 1))  # one contiguous patch
        # sigma_w is 9.1 EDR m/s: the patch (EDR >= 0.2) at least twice the background (EDR < 0.1)
        # and the vertical load factor with it (linear response); each 60 s std is good to ~10 %
        # (a gust correlation time of ~1 s), so 1.4 is three errors below the least ratio of 2
        nz = tr.specific_force_body_mps2[:, 2]
        before = (tr.t_s >= t_on - 60.0) & (tr.t_s < t_on)
        inside = (tr.t_s >= t_on) & (tr.t_s < t_on + 60.0)
        assert nz[inside].std() > 1.4 * nz[before].std(), (nz[inside].std(), nz[before].std())


def test_exceeding_a_limit_raises_flight_error_naming_phase_time_and_cause(monkeypatch):
    import flightmode.sim.flight.aircraft.registry as ap
    from flightmode.runs import pipeline
    from flightmode.scenarios.scenario import Scenario

    # a pilot allowed 60 degrees of bank breaks the 45-degree limit in the first turn
    monkeypatch.setitem(ap.PROFILES, "737", dataclasses.replace(ap.PROFILES["737"], turn_bank_deg=60.0))
    sc = Scenario.builtin("pattern")
    with pytest.raises(FlightDivergedError) as ei:
        pipeline.fly(sc, pipeline.streams_of(sc.seed).child("flight"))
    e = ei.value
    assert "bank angle" in e.cause and "exceeds 45" in e.cause
    assert e.phase in ("initial_climb", "climb", "cruise", "descent", "approach")
    assert e.t_s > 0 and f"{e.t_s:.2f}" in str(e)


def test_the_nose_is_flown_down_after_the_mains_not_dropped(fly_cached):
    """Derotation (sim.flight.pilot.rollout.Rollout): the nose wheels meet the runway about 3.5 s after the
    mains on an A320 (a cabin-floor landing-shock record, Irvine, vibrationdata); the pilot lowers the
    nose over that time. The pattern 737 touches down at about 3 deg: lowered at (3 - 1) / 3.5 deg/s
    with the attitude loop's lag of about a second, its nose reaches the ground attitude 1.5-6 s after
    the mains and never pitches down as fast as a dropped nose does. Before the 737 kept its flare
    elevator, its nose fell in 0.8-1.9 s at 3-4 deg/s; flown down, 8 pattern landings gave
    0.9-2.6 deg/s at most (the rate grows as the nose wheels near the runway), so 2.8 deg/s divides
    the two (this flight: 2.04 deg/s since the taxi calibration and the convective layer)."""
    sc, tr = fly_cached("pattern")
    th = np.degrees(tr.euler_rad[:, 1])
    t_td = tr.event_time("touchdown")
    since = tr.t_s - t_td
    i0 = int(np.searchsorted(tr.t_s, t_td))
    ground = np.median(th[(since > 20.0) & (since < 25.0)])  # rolling on all its wheels
    k = i0 + int(np.argmax(th[i0:] < ground + 0.3))  # within 0.3 deg of it (the struts' pitch wobble)
    assert 1.5 <= tr.t_s[k] - t_td <= 6.0
    q_dps = np.gradient(th, tr.t_s)[i0 : k + 1]
    assert q_dps.min() > -2.8
