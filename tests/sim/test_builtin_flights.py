"""The built-in airliner scenarios flown gate to gate (slow: 15-90 s of wall time each).

Kinematics are checked against OpenAP WRAP (real-traffic ranges from ADS-B, per type; Sun et al., "WRAP", 2019):
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


# MIL-F-8785C Figure 7 (p. 49; also MIL-HDBK-1797 Figure 268): sigma_w = sigma_u (ft/s) above
# 2,000 ft against altitude (ft) for probability-of-exceedance curves 1..7; the table JSBSim's
# Milspec model interpolates (linearly in altitude, FGWinds.cpp). Rows used here: curves 4 (1e-3),
# 6 (1e-5) and 7 (1e-6), between 15,000 and 55,000 ft.
POE_ALT_FT = (15000.0, 25000.0, 35000.0, 45000.0, 55000.0)
POE_SIGMA_FTPS = {4: (8.0, 6.6, 5.0, 4.2, 2.7), 6: (22.1, 20.0, 16.0, 15.1, 12.1), 7: (30.7, 31.0, 25.2, 23.1, 17.5)}


@pytest.mark.slow
def test_turbulence_intensity_rises_with_severity(fly_cached):
    """Three cruise segments of the default flight (240 s each, one seeded realisation apiece):

    1. each segment's peak load-factor change falls in its ICAO/FAA band at the CG (FAA AIM 7-1-21,
       Table 7-1-10: light < 0.5 g, moderate 0.5-1.0 g, severe > 1.0 g);
    2. the gust intensity: the aircraft's load-factor response is linear in the gust velocity (small
       angle-of-attack changes, a linear autopilot), and JSBSim's Milspec gust field is the same
       shaping filters scaled by sigma_w (sigma_u = sigma_w, sigma_p and the q, r gusts are
       proportional to it, the scale length is 1,750 ft at every severity). So the ratio of the
       load-factor standard deviations of two segments at the same altitude and speed equals the
       ratio of MIL-F-8785C's sigma_w for their curves at that altitude."""
    from flightmode.sim.flight.pilot import MILSPEC
    from flightmode.sim.flight.plan import TurbulenceSegment

    index = {"light": 4, "moderate": 6, "severe": 7}  # 1e-3, 1e-5, 1e-6 (sim.flight.pilot's choice)
    assert {sev: MILSPEC[code][0] for sev, code in (("light", 1), ("moderate", 2), ("severe", 3))} == index
    segs = (
        TurbulenceSegment(900.0, 240.0, "light"),
        TurbulenceSegment(1300.0, 240.0, "moderate"),
        TurbulenceSegment(1700.0, 240.0, "severe"),
    )
    # flown to a little after the last segment (liftoff is about 15 min after the track starts)
    sc, tr = fly_cached("gva-lhr-a320", turbulence=segs, stop_after_s=3300.0)
    assert tr.t_s[-1] > tr.event_time("liftoff") + 1940.0
    nz = -tr.specific_force_body_mps2[:, 2] / 9.80665
    t_lo = tr.event_time("liftoff")
    dt = 1.0 / tr.fs_hz
    stds, peaks, sigma_w, rel_se = [], [], [], []
    for seg in segs:
        sel = (tr.t_s >= t_lo + seg.start_s + 10.0) & (tr.t_s < t_lo + seg.start_s + seg.duration_s)
        assert set(tr.phase[sel]) == {"cruise"}, "segment not in cruise: move it"
        x = nz[sel] - nz[sel].mean()
        stds.append(float(x.std()))
        peaks.append(float(np.abs(nz[sel] - np.median(nz[sel])).max()))
        alt_ft = float(tr.alt_m[sel].mean()) / FT_M
        sigma_w.append(float(np.interp(alt_ft, POE_ALT_FT, POE_SIGMA_FTPS[index[seg.severity]])))
        # sampling error of a standard deviation from a record of length T of a Gaussian process:
        # var(s^2) / s^4 = 2 tau / T, tau = integral of rho(lag)^2 over all lags (Bendat & Piersol,
        # Random Data, sec. 8.2), so s is good to sqrt(tau / 2T) relative; tau from the record's own
        # autocorrelation (lags to 30 s; about 0.8 s here, i.e. ~4 % per segment)
        n = x.size
        acf = np.fft.irfft(np.abs(np.fft.rfft(x, 2 * n)) ** 2)[:n]
        acf /= acf[0]
        tau = (1.0 + 2.0 * np.sum(acf[1 : int(30.0 / dt)] ** 2)) * dt
        rel_se.append(float(np.sqrt(tau / (2.0 * n * dt))))
    calm = (tr.t_s >= t_lo + 1150.0) & (tr.t_s < t_lo + 1290.0)
    print(f"\nvertical load factor std (g): calm {nz[calm].std():.4f}, light {stds[0]:.4f}, "
          f"moderate {stds[1]:.4f}, severe {stds[2]:.4f}; peak |dn| (g): {[round(p, 3) for p in peaks]}; "
          f"MIL-F-8785C sigma_w (ft/s): {[round(s, 2) for s in sigma_w]}; std rel. error {[round(e, 3) for e in rel_se]}")
    assert nz[calm].std() < stds[0] < stds[1] < stds[2]
    # 1. ICAO/FAA intensity at the CG: light < 0.5 g change, moderate 0.5-1.0 g, severe > 1.0 g
    assert peaks[0] < 0.5
    assert 0.5 <= peaks[1] <= 1.0
    assert peaks[2] > 1.0
    # 2. std ratios = sigma_w ratios (3.2 moderate/light, 1.6 severe/moderate at FL360). The three
    # segments are independent realisations, so each ratio carries the two segments' sampling
    # errors in quadrature; 3 of those (about 18 %) separates every neighbouring curve of the table
    # (curve 5 instead of 6 would halve the first ratio, curve 6 instead of 7 make the second 1.0).
    # The calm-air background (std 0.001 g) adds in quadrature: < 0.1 % on the light segment.
    for i, j in ((0, 1), (1, 2), (0, 2)):
        got, want = stds[j] / stds[i], sigma_w[j] / sigma_w[i]
        tol = 3.0 * float(np.hypot(rel_se[i], rel_se[j]))
        assert abs(got / want - 1.0) <= tol, (segs[i].severity, segs[j].severity, got, want, tol)
