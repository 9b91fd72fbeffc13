"""The built-in airliner scenarios flown gate to gate (slow: 15-90 s of wall time each).

Kinematics are checked against OpenAP WRAP (real-traffic ranges from ADS-B, per type; FACTS.md):
liftoff speed, takeoff acceleration, initial climb rate, cruise altitude, final-approach vertical rate,
landing speed and braking deceleration must each fall within WRAP's [minimum, maximum]. WRAP speeds
come from ADS-B ground speed, so ground speed is compared (there is no wind in these flights).
"""

from __future__ import annotations

import json

import numpy as np
import pytest

SCENARIOS = ["gva-lhr-a320", "hel-zrh-f100", "ist-osl-737", "lhr-jfk-787"]
FT_M = 0.3048


def _wrap(wrap_type):
    from openap import WRAP  # a test dependency (pip install -e ".[test]")

    return WRAP(wrap_type)


@pytest.mark.slow
@pytest.mark.parametrize("name", SCENARIOS)
def test_flies_gate_to_gate_within_real_traffic_ranges(name, fly_cached, record_property):
    from flightmode.sim.flight.aircraft_profiles import get_profile
    from flightmode.sim.flight.flight_metrics import flight_metrics

    sc, tr = fly_cached(name)
    m = flight_metrics(tr, sc.plan)
    record_property("metrics", json.dumps(m))
    print(f"\n{name} metrics: " + json.dumps({k: round(v, 2) for k, v in m.items()}))
    # ends parked at the stand with engines off
    assert tr.phase[-1] == "parked"
    assert np.all(tr.n2_pct[-1] < 5.0) and tr.ground_speed_mps[-1] < 0.05

    w = _wrap(get_profile(sc.aircraft).wrap_type)

    def within(value, spec, what):
        lo, hi = spec["minimum"], spec["maximum"]
        assert lo <= value <= hi, f"{what} {value:.2f} outside WRAP {lo}..{hi}"

    within(m["liftoff_gs_mps"], w.takeoff_speed(), "liftoff speed (m/s)")
    within(m["takeoff_accel_mps2"], w.takeoff_acceleration(), "takeoff acceleration (m/s^2)")
    within(m["initial_climb_vs_mps"], w.initclimb_vs(), "initial climb rate (m/s)")
    within(m["cruise_alt_m"] / 1000.0, w.cruise_alt(), "cruise altitude (km)")
    within(m["final_approach_vs_mps"], w.finalapp_vs(), "final approach vertical rate (m/s)")
    within(m["touchdown_gs_mps"], w.landing_speed(), "landing speed (m/s)")
    within(-m["rollout_decel_mps2"], w.landing_acceleration(), "braking acceleration (m/s^2)")
    # passenger-transport manoeuvring: outside turbulence, the vertical load factor stays within
    # 1 +- 0.3 g while airborne (the pilot must not porpoise; touchdown itself is excluded)
    nz = -tr.specific_force_body_mps2[:, 2] / 9.80665
    turb = np.convolve(tr.turbulence_code > 0, np.ones(int(20 * tr.fs_hz)), mode="full")[: tr.n] > 0
    calm_air = tr.airborne & ~turb  # and 20 s after a turbulence segment (its gust field stops dead)
    # and away from the liftoff and touchdown transients (gear and ground effect; the light, fast
    # fokker100 zooms to 1.33 g in the first second after liftoff)
    t_lo, t_td = tr.event_time("liftoff"), tr.event_time("touchdown")
    calm_air &= (tr.t_s > t_lo + 5.0) & (tr.t_s < t_td - 5.0)
    assert 0.7 < nz[calm_air].min() and nz[calm_air].max() < 1.3, (nz[calm_air].min(), nz[calm_air].max())
    # touchdown quality (the acceptance ranges)
    sink_fpm = m["touchdown_sink_mps"] / FT_M * 60.0
    assert 60.0 <= sink_fpm <= 600.0, f"touchdown sink rate {sink_fpm:.0f} ft/min"
    assert 150.0 <= m["touchdown_past_threshold_m"] <= 900.0
    assert abs(m["touchdown_centreline_offset_m"]) <= 10.0


@pytest.mark.slow
def test_turbulence_intensity_rises_with_severity(fly_cached):
    """Three cruise segments of the default flight: the standard deviation of the vertical load
    factor must rise from light to moderate to severe, and each segment's peak change must fall in
    its ICAO/FAA band (FACTS.md). One seeded realisation per segment (240 s, ~28,000 samples)."""
    from flightmode.sim.flight.plan import TurbulenceSegment

    segs = (
        TurbulenceSegment(900.0, 240.0, "light"),
        TurbulenceSegment(1300.0, 240.0, "moderate"),
        TurbulenceSegment(1700.0, 240.0, "severe"),
    )
    sc, tr = fly_cached("gva-lhr-a320", turbulence=segs)
    nz = -tr.specific_force_body_mps2[:, 2] / 9.80665
    t_lo = tr.event_time("liftoff")
    stds, peaks = [], []
    for seg in segs:
        sel = (tr.t_s >= t_lo + seg.start_s + 10.0) & (tr.t_s < t_lo + seg.start_s + seg.duration_s)
        assert set(tr.phase[sel]) == {"cruise"}, "segment not in cruise: move it"
        stds.append(float(nz[sel].std()))
        peaks.append(float(np.abs(nz[sel] - np.median(nz[sel])).max()))
    calm = (tr.t_s >= t_lo + 1150.0) & (tr.t_s < t_lo + 1290.0)
    print(f"\nvertical load factor std (g): calm {nz[calm].std():.4f}, light {stds[0]:.4f}, "
          f"moderate {stds[1]:.4f}, severe {stds[2]:.4f}; peak |dn| (g): {[round(p, 3) for p in peaks]}")
    assert nz[calm].std() < stds[0] < stds[1] < stds[2]
    # ICAO/FAA intensity at the CG: light < 0.5 g change, moderate 0.5-1.0 g, severe > 1.0 g
    assert peaks[0] < 0.5
    assert 0.5 <= peaks[1] <= 1.0
    assert peaks[2] > 1.0
