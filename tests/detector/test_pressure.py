"""The pressure-rate detector and the redundant rule (detector.pressure) on synthetic flights: the
rate statistics, the climb flagged within the computed response, held through cruise, resumed after
the hold on the ground, streaming == batch, the OR/AND rule and its evaluation by source, bad input."""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest
from scipy.stats import chi2

from flightmode.detector.flight_mode import Checks, DetectorParams, detect
from flightmode.detector.pressure import (
    PressureChecks,
    PressureDetector,
    PressureParams,
    RedundantDetector,
    RedundantRule,
    cabin_rate_pa_s,
    design,
    detect_pressure,
    detect_redundant,
    evaluate_sources,
    lagged_ramp_response_s,
    ramp_response_s,
    rate_sigma_pa_s,
    slope_weights,
)
from flightmode.errors import DetectorError
from flightmode.labels import AIRBORNE_PHASES
from flightmode.sim.flight import atmosphere as isa
from flightmode.sim.flight.cabin import CABIN_PROFILES, cabin_pressure
from flightmode.sim.sensor.barometer import get_preset, measure
from flightmode.units import FPM_MPS, FT_M, PSI_PA
from tests.sim.test_cabin import synthetic_flight

P = PressureParams()  # 25 Hz, 4 s windows, checks every 1 s, 5 Pa/s, 25 hPa, 120 s hold
SIG_G = 2.23e-3
ACC_P = DetectorParams(fs_hz=25.0)  # seed 000's detector on a 25 Hz accelerometer stream
MOVING = ("engine_start", "pushback", "taxi_out", "takeoff_roll", "rollout", "taxi_in", "shutdown")


def _pressure_flight(model="A320", seed=0, profile=None, **kw):
    """A synthetic flight's cabin pressure through a BMP581 (x16, 0.21 Pa, 25 Hz)."""
    t, h, ph = synthetic_flight(**kw)
    c = cabin_pressure(t, h, ph, kw.get("cruise_ft", 35_000.0) * FT_M, profile or model)
    tb, pb = measure(t, c.cabin_pressure_pa, "bmp581", np.random.default_rng(seed))
    return t, ph, c, tb, pb


def _accel(t, ph, seed=1):
    """A 25 Hz accelerometer on an isolated parcel: noise at rest, 20 mg of vibration while the
    engines run on the ground, and nothing in calm air (the accelerometer's false statics)."""
    rng = np.random.default_rng(seed)
    ta = np.arange(t[0], t[-1], 1 / 25)
    moving = np.isin(ph, MOVING)[np.searchsorted(t, ta, side="right") - 1]
    a = rng.normal(0.0, SIG_G, (ta.size, 3)) + [0.0, 0.0, 1.0]
    a[moving] += rng.normal(0.0, 0.02, (int(moving.sum()), 3))
    return ta, a


def _span(t, ph, name):
    i = np.flatnonzero(ph == name)
    return float(t[i[0]]), float(t[i[-1]])


def _chunks(n, rng, hi):
    i = 0
    while i < n:
        k = int(rng.integers(1, hi))
        yield slice(i, min(i + k, n))
        i += k


def _equal(a, b):
    return all(np.array_equal(getattr(a, f.name), getattr(b, f.name)) for f in dataclasses.fields(a))


# -- statistics --------------------------------------------------------------------------------


def test_the_rate_is_the_least_squares_slope():
    rng = np.random.default_rng(0)
    y = rng.normal(1e5, 3.0, 100)
    x = np.arange(100) / 25.0
    assert np.dot(slope_weights(100, 25.0), y) == pytest.approx(np.polyfit(x, y, 1)[0], rel=1e-9)


def test_rate_noise_matches_its_formula():
    # disjoint 4 s windows of white 0.21 Pa noise: the rates are independent N(0, sigma_r)
    p = PressureParams(window_s=4.0, check_s=4.0)
    n = 25 * 4 * 3000
    rng = np.random.default_rng(2)
    c = detect_pressure(np.arange(n) / 25.0, 1e5 + rng.normal(0.0, 0.21, n), p)
    s_r = rate_sigma_pa_s(0.21, 25.0, 4.0)
    k = c.rate_pa_s.size
    stat = (k - 1) * c.rate_pa_s.var(ddof=1) / s_r**2
    assert chi2.ppf(0.0005, k - 1) < stat < chi2.ppf(0.9995, k - 1)


@pytest.mark.parametrize("rate", [6.0, 12.0, 40.0])
def test_ramp_response_formula(rate):
    # every sample a check: the first rate above T is within a sample of the smoothstep formula (the
    # ramp starts after the first whole window)
    p = PressureParams(check_s=0.04)
    t = np.arange(0.0, 100.0, 0.04)
    y = 1e5 - rate * np.maximum(t - 40.0, 0.0)
    c = detect_pressure(t, y, p)
    first = c.t_s[np.flatnonzero(~c.rate_ok)[0]]
    assert first - 40.0 == pytest.approx(
        ramp_response_s(rate, P.rate_threshold_pa_s, P.window_s), abs=0.04 + 1e-9
    )


def test_the_default_thresholds_statistics():
    d = design(get_preset("bmp581").noise_pa)
    # 60 ft/min at 8,000 ft (the thinnest cabin air): 2.88 Pa/s, about three times T
    assert d["slowest_cabin_rate_pa_s"] == pytest.approx(2.878, abs=0.01)
    assert d["threshold_over_sigma"] > 1000 and d["pm_rate"] < 1e-300 and d["pfa_rate"] < 1e-300
    # the rate bound keeps P_M per check below 1e-6 up to 48 Pa of sensor noise (T / sigma_r >= 4.89)
    assert design(48.0)["pm_rate"] < 1e-6 < design(49.0)["pm_rate"]
    assert cabin_rate_pa_s(300.0, 8000 * FT_M) == pytest.approx(
        300 * FPM_MPS * float(isa.density_kgpm3(8000 * FT_M)) * 9.80665
    )


# -- a flight ----------------------------------------------------------------------------------


def test_flags_the_takeoff_roll_holds_cruise_and_resumes_after_the_hold():
    prof = CABIN_PROFILES["A320"]
    t, ph, _, tb, pb = _pressure_flight()
    pc = detect_pressure(tb, pb)
    t_roll, _ = _span(t, ph, "takeoff_roll")
    t_td, _ = _span(t, ph, "rollout")
    # at rest on the ground before the roll (the hold passed long ago)
    assert pc.static[(pc.t_s > 300) & (pc.t_s < t_roll)].all()
    # the cabin's first move is the pre-pressurisation: 400 ft/min at the field, through the valve's lag
    r_pp = cabin_rate_pa_s(prof.prepress_rate_fpm, 0.0)
    bound = (
        lagged_ramp_response_s(r_pp, P.rate_threshold_pa_s, P.window_s, prof.ofv_tau_s)
        + P.check_s
        + 1 / P.fs_hz
    )
    first = pc.t_s[np.flatnonzero((pc.t_s >= t_roll) & ~pc.static)[0]]
    assert t_roll < first <= t_roll + bound
    # suspended from there through the climb, cruise and descent to touchdown
    flight = (pc.t_s >= first) & (pc.t_s <= t_td)
    assert not pc.static[flight].any()
    # in calm cruise the rate is quiet: the level bound holds it (cabin ~6,550 ft, 200 hPa below)
    c0, c1 = _span(t, ph, "cruise")
    cruise = (pc.t_s >= c0 + P.window_s + 30) & (pc.t_s <= c1)  # the window clear of the climb
    assert pc.rate_ok[cruise].all() and not pc.level_ok[cruise].any()
    assert (pc.reference_pa[cruise] - pc.mean_pa[cruise]).min() > 190e2
    # after touchdown: the residual 0.1 psi released at 500 ft/min, the lag's tail below T after
    # tau ln(r / T), the window clear after W more; then the hold
    r_rel = cabin_rate_pa_s(prof.release_rate_fpm, 0.0)
    t_quiet = (
        t_td + 0.1 * PSI_PA / r_rel + prof.ofv_tau_s * math.log(r_rel / P.rate_threshold_pa_s) + P.window_s
    )
    loud = np.flatnonzero(~pc.quiet)
    last_loud = pc.t_s[loud[-1]]
    assert t_td < last_loud <= t_quiet + P.check_s
    first_static = pc.t_s[np.flatnonzero(pc.static & (pc.t_s > t_td))[0]]
    assert first_static == pytest.approx(last_loud + P.checks_needed * P.check_s, abs=1e-9)
    assert pc.static[pc.t_s >= first_static].all()


def test_flags_a_climb_without_prepressurisation_within_the_computed_time():
    # a type without pre-pressurisation: the cabin first moves at liftoff, climbing at the schedule's
    # share of the aircraft's 2,000 ft/min: (C - field) / FL350
    prof = dataclasses.replace(CABIN_PROFILES["A320"], prepress_psi=0.0)
    t, ph, c, tb, pb = _pressure_flight(profile=prof)
    pc = detect_pressure(tb, pb)
    t_lift, _ = _span(t, ph, "climb")
    cabin_fpm = 2000.0 * c.cruise_cabin_altitude_m / (35_000 * FT_M)
    rate = cabin_rate_pa_s(cabin_fpm, 0.0)  # at the field, where it starts
    bound = (
        lagged_ramp_response_s(rate, P.rate_threshold_pa_s, P.window_s, prof.ofv_tau_s)
        + P.check_s
        + 1 / P.fs_hz
    )
    assert pc.static[(pc.t_s > t_lift - 30) & (pc.t_s < t_lift)].all()
    first = pc.t_s[np.flatnonzero((pc.t_s >= t_lift) & ~pc.static)[0]]
    assert t_lift < first <= t_lift + bound


def test_streaming_equals_batch():
    _, _, _, tb_all, pb_all = _pressure_flight()
    # one-sample chunks over the first 5 min (gate to taxi), then any sizes over the whole flight
    for seed, hi, n in ((0, 2, 7500), (1, 40, tb_all.size), (2, 3000, tb_all.size)):
        tb, pb = tb_all[:n], pb_all[:n]
        whole = detect_pressure(tb, pb)
        d = PressureDetector()
        parts = [d.push(tb[s], pb[s]) for s in _chunks(tb.size, np.random.default_rng(seed), hi)]
        got = PressureChecks(
            *(np.concatenate([getattr(p, f.name) for p in parts]) for f in dataclasses.fields(PressureChecks))
        )
        assert _equal(got, whole)


# -- the redundant rule ------------------------------------------------------------------------


def test_the_combined_rule_has_no_false_static_where_the_accelerometer_alone_has_many():
    t, ph, _, tb, pb = _pressure_flight()
    ta, a = _accel(t, ph)
    sigma2 = np.full(3, SIG_G**2)
    acc_only = detect(ta, a, ACC_P, sigma2)
    both = detect_redundant(ta, a, tb, pb, ACC_P, sigma2)
    assert np.array_equal(both.t_s, acc_only.t_s) and np.array_equal(both.accel_static, acc_only.final_static)
    t_push, _ = _span(t, ph, "pushback")
    _, t_off = _span(t, ph, "shutdown")
    window = (both.t_s >= t_push) & (both.t_s <= t_off)  # pushback to engines off
    air = np.isin(ph, list(AIRBORNE_PHASES))
    airborne = (both.t_s >= t[air][0]) & (both.t_s <= t[air][-1])
    assert both.accel_static[airborne].mean() > 0.99  # calm air, isolated parcel: static all the way
    assert not both.allowed[window].any()  # the combined rule: no false static at all
    # OR to suspend, AND to resume, per check
    assert np.array_equal(both.allowed, both.accel_static & both.pressure_static)
    c0, c1 = _span(t, ph, "cruise")
    ev = evaluate_sources(
        both, t_push, [(c0 + P.window_s + 30, c1)], t_end_s=t_off
    )  # the window clear of the climb
    assert ev.first_source == "accelerometer"  # the pushback's motion, long before the takeoff roll
    assert ev.first_suspend_s["pressure"] > _span(t, ph, "takeoff_roll")[0]
    assert ev.held_by["pressure_only"] == ev.cruise_checks and ev.held_by["neither"] == 0
    assert ev.held_by_pressure["level"] > 0.99 * ev.cruise_checks
    # the response at the gate (engines off): the combined rule waits for the later source
    assert ev.resume_s["combined"] == max(ev.resume_s["accelerometer"], ev.resume_s["pressure"])
    assert ev.resume_s["accelerometer"] <= ACC_P.time_threshold_s + ACC_P.window_s


def test_combined_streaming_equals_batch():
    t, ph, _, tb, pb = _pressure_flight(cruise_s=300.0, ground_s=120.0)
    ta, a = _accel(t, ph)
    sigma2 = np.full(3, SIG_G**2)
    whole = detect_redundant(ta, a, tb, pb, ACC_P, sigma2)
    for seed in (0, 1):
        rng = np.random.default_rng(seed)
        d = RedundantDetector(ACC_P, sigma2)
        sa = list(_chunks(ta.size, rng, 5000))
        sb = list(_chunks(tb.size, rng, 800))
        parts = []
        for i in range(max(len(sa), len(sb))):  # the two streams in independent chunks
            x = sa[i] if i < len(sa) else None
            y = sb[i] if i < len(sb) else None
            parts.append(
                d.push(
                    None if x is None else ta[x],
                    None if x is None else a[x],
                    None if y is None else tb[y],
                    None if y is None else pb[y],
                )
            )
        parts.append(d.finish())
        got = type(whole)(
            *(np.concatenate([getattr(p, f.name) for p in parts]) for f in dataclasses.fields(whole))
        )
        assert _equal(got, whole)


def _acc_checks(t, static):
    t = np.asarray(t, float)
    z = np.zeros(t.size, bool)
    return Checks(np.arange(t.size), t, np.zeros((t.size, 3)), np.asarray(static), np.asarray(static), z)


def _p_checks(t, static, rate_ok=None, level_ok=None):
    t = np.asarray(t, float)
    s = np.asarray(static)
    r = s if rate_ok is None else np.asarray(rate_ok)
    lv = np.ones(t.size, bool) if level_ok is None else np.asarray(level_ok)
    return PressureChecks(
        np.arange(t.size), t, np.zeros(t.size), np.zeros(t.size), np.zeros(t.size), r, lv, r & lv, s
    )


def test_the_rule_uses_the_pressure_state_as_of_each_check_and_waits_for_it():
    rule = RedundantRule()
    out = rule.push(accel=_acc_checks([1, 2, 3, 4, 5, 6], [1, 1, 1, 0, 1, 1]))
    assert out.t_s.size == 0  # no pressure check yet: nothing can be decided
    out = rule.push(pressure=_p_checks([0.5, 2.5, 4.5], [True, False, True]))
    assert out.t_s.tolist() == [1, 2, 3, 4]  # decided up to the last pressure check (4.5)
    assert out.pressure_static.tolist() == [True, True, False, False]
    assert out.allowed.tolist() == [True, True, False, False]  # AND to resume, OR to suspend
    rest = rule.finish()
    assert rest.t_s.tolist() == [5, 6] and rest.allowed.tolist() == [True, True]
    with pytest.raises(DetectorError):
        rule.push(accel=_acc_checks([7], [1]))
    # before the pressure source's first check it is not static
    r2 = RedundantRule()
    r2.push(accel=_acc_checks([1, 2], [1, 1]))
    out = r2.push(pressure=_p_checks([1.5], [True]))
    assert out.t_s.tolist() == [1] and out.pressure_static.tolist() == [False]
    assert r2.finish().pressure_static.tolist() == [True]


def test_an_arrival_well_above_the_origin_needs_the_destination_known():
    # London (83 ft) to Geneva (1,411 ft): the arrival ground is 47 hPa below the departure reference
    t, ph, _, tb, pb = _pressure_flight(field_m=83 * FT_M, arrival_m=1411 * FT_M)
    pc = detect_pressure(tb, pb)
    _, t_off = _span(t, ph, "shutdown")
    after = pc.t_s > t_off
    assert pc.rate_ok[after].all() and not pc.level_ok[after].any() and not pc.static[after].any()
    # without the level bound it resumes, and holds cruise by nothing but the accelerometer
    rate_only = detect_pressure(tb, pb, dataclasses.replace(P, level_margin_pa=None))
    assert rate_only.static[after].any()
    c0, c1 = _span(t, ph, "cruise")
    assert rate_only.static[(rate_only.t_s > c0 + P.window_s + P.hold_s + 30) & (rate_only.t_s < c1)].all()
    # the destination known (its ISA ground pressure; this flight's QNH is the standard one): the level
    # bound holds near it too, so the source resumes within the hold (+ a window and a check) of the
    # cabin coming to rest, and still holds the whole cruise (the cabin is ~6,000 ft above Geneva)
    from flightmode.sim.flight.cabin import ambient_pressure_pa

    known = dataclasses.replace(
        P, arrival_ground_pa=float(ambient_pressure_pa(1411 * FT_M, datum_m=1411 * FT_M))
    )
    pk = detect_pressure(tb, pb, known)
    first = pk.t_s[after & pk.static]
    assert first.size and first[0] - t_off <= P.hold_s + P.window_s + P.check_s
    assert not pk.static[(pk.t_s > c0) & (pk.t_s < c1)].any()


# -- bad input ---------------------------------------------------------------------------------


def test_bad_input_raises_typed_one_line_errors():
    t = np.arange(0.0, 60.0, 0.04)
    p = np.full(t.shape, 1e5)
    cases = [
        ("gap", lambda: detect_pressure(np.where(t > 20, t + 3.0, t), p)),
        ("NaN", lambda: detect_pressure(t, np.where(t == t[100], np.nan, p))),
        ("not increasing", lambda: detect_pressure(t[::-1], p)),
        ("set fs_hz", lambda: detect_pressure(t[::2], p[::2])),
        ("rate threshold -1", lambda: PressureDetector(dataclasses.replace(P, rate_threshold_pa_s=-1.0))),
        ("level margin -5", lambda: PressureDetector(dataclasses.replace(P, level_margin_pa=-5.0))),
        ("hold time 0", lambda: PressureDetector(dataclasses.replace(P, hold_s=0.0))),
        ("whole number", lambda: PressureDetector(dataclasses.replace(P, check_s=0.05))),
    ]
    for text, call in cases:
        with pytest.raises(DetectorError) as e:
            call()
        assert text in str(e.value) and "\n" not in str(e.value)
    # a gap across two pushes is caught too
    d = PressureDetector()
    d.push(t[:100], p[:100])
    with pytest.raises(DetectorError, match="gap"):
        d.push(t[200:], p[200:])
