"""Cabin pressure (sim.flight.cabin) on synthetic altitude profiles: the certification limit and the
schedule in cruise, rate limits, pre-pressurisation and release, door-open ambient, weather, holds,
bad input. No JSBSim flight is flown."""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest

from flightmode.errors import AircraftError, InputDataError, ScenarioError
from flightmode.labels import AIRBORNE_PHASES
from flightmode.sim.flight import atmosphere as isa
from flightmode.sim.flight.aircraft.registry import get_profile
from flightmode.sim.flight.cabin import (
    CABIN_PROFILES,
    Weather,
    ambient_pressure_pa,
    cabin_pressure,
    draw_weather,
    get_cabin_profile,
)
from flightmode.units import FPM_MPS, FT_M, HPA_PA, PSI_PA

FL350 = 35_000 * FT_M
GROUND = ("gate", "engine_start", "pushback", "taxi_out")


def synthetic_flight(
    fs_hz=10.0,
    field_m=0.0,
    arrival_m=None,
    cruise_ft=35_000.0,
    climb_fpm=2000.0,
    descent_fpm=2000.0,
    cruise_s=1200.0,
    ground_s=300.0,
):
    """Gate to gate on a straight-line profile: ground phases at the field, a constant-rate climb to
    the cruise level, cruise, a constant-rate descent, rollout and taxi at the arrival field.
    Returns (t_s, alt_m, phase names)."""
    arr = field_m if arrival_m is None else arrival_m
    top = cruise_ft * FT_M
    segs = [
        ("gate", 120, field_m),
        ("engine_start", 60, field_m),
        ("pushback", 60, field_m),
        ("taxi_out", ground_s, field_m),
        ("takeoff_roll", 40, field_m),
        ("climb", (top - field_m) / (climb_fpm * FPM_MPS), None),
        ("cruise", cruise_s, top),
        ("descent", (top - arr) / (descent_fpm * FPM_MPS), None),
        ("rollout", 30, arr),
        ("taxi_in", ground_s, arr),
        ("shutdown", 30, arr),
        ("parked", 300, arr),
    ]
    ts, hs, ph = [], [], []
    n0 = 0
    for name, dur, level in segs:
        n = round(dur * fs_hz)
        tt = (n0 + np.arange(n)) / fs_hz
        if name == "climb":
            h = np.minimum(field_m + climb_fpm * FPM_MPS * (tt - n0 / fs_hz), top)
        elif name == "descent":
            h = np.maximum(top - descent_fpm * FPM_MPS * (tt - n0 / fs_hz), arr)
        else:
            h = np.full(n, level)
        ts.append(tt), hs.append(h), ph.extend([name] * n)
        n0 += n
    return np.concatenate(ts), np.concatenate(hs), np.array(ph)


def _expected_cruise_cabin_m(model: str, cruise_m: float) -> float:
    """The cruise cabin altitude from the figures alone: as low as the type's maximum differential
    allows at the level, at most its maximum cabin altitude."""
    prof = CABIN_PROFILES[model]
    if model == "737":  # 737 FCOM bands (FACTS): 7.45 / 7.80 / 8.35 psid
        psi = 7.45 if cruise_m <= 28_000 * FT_M else 7.80 if cruise_m <= 37_000 * FT_M else 8.35
        dp = psi * PSI_PA
    else:  # max cabin altitude at the type's certified ceiling
        dp = isa.pressure_pa(prof.max_cabin_alt_ft * FT_M) - isa.pressure_pa(
            get_profile(model).ceiling_ft * FT_M
        )
    return min(prof.max_cabin_alt_ft * FT_M, float(isa.pressure_altitude_m(isa.pressure_pa(cruise_m) + dp)))


@pytest.mark.parametrize("model", sorted(CABIN_PROFILES))
@pytest.mark.parametrize("level", ["FL350", "ceiling"])
def test_cruise_cabin_altitude_is_the_schedule_and_within_the_certification_limit(model, level):
    # at FL350 and at the type's certified maximum operating altitude (the TCDS figure of its profile)
    cruise_ft = 35_000.0 if level == "FL350" else get_profile(model).ceiling_ft
    t, h, ph = synthetic_flight(cruise_ft=cruise_ft)
    c = cabin_pressure(t, h, ph, cruise_ft * FT_M, model)
    limit_ft = 6000.0 if model == "787-8" else 8000.0  # 14 CFR 25.841(a); Boeing's 787 figure
    cruise = np.flatnonzero(ph == "cruise")
    settled = cruise[t[cruise] >= t[cruise[0]] + 300.0]  # 60 outflow-valve time constants into cruise
    expected = _expected_cruise_cabin_m(model, cruise_ft * FT_M)
    assert c.cruise_cabin_altitude_m == pytest.approx(expected, abs=1e-6)
    np.testing.assert_allclose(c.cabin_altitude_m[settled], expected, rtol=0, atol=1e-6)
    assert expected <= limit_ft * FT_M + 1e-9
    assert c.cabin_altitude_m.max() <= limit_ft * FT_M + 1e-6  # never above the limit, anywhere
    # the schedule: never above the aircraft, differential never above the type's maximum; the cabin
    # lags it by at most a / (1 - a) max |dp_sched| (a first-order lag started in steady state;
    # a = exp(-dt / tau)): at the top of climb the differential overshoots by about r tau
    p_sched = isa.pressure_pa(c.schedule_altitude_m)
    dp_max = CABIN_PROFILES[model].max_diff_pa(cruise_ft * FT_M)
    assert (p_sched - c.ambient_pressure_pa).min() >= -1e-6
    assert (p_sched - c.ambient_pressure_pa).max() <= dp_max * (1 + 1e-12)
    a = math.exp(-(t[1] - t[0]) / CABIN_PROFILES[model].ofv_tau_s)
    lag = a / (1 - a) * np.abs(np.diff(p_sched)).max()
    assert np.abs(c.cabin_pressure_pa - p_sched).max() <= lag * (1 + 1e-9)
    diff = c.cabin_pressure_pa - c.ambient_pressure_pa
    assert diff.min() >= -lag and diff.max() <= dp_max + lag


@pytest.mark.parametrize("model", ["A320", "fokker100", "787-8"])
def test_at_the_ceiling_the_cabin_is_at_its_maximum_altitude(model):
    # the types whose maximum differential is derived from it: 8,000 ft (787: 6,000 ft) at the ceiling
    ceiling_m = get_profile(model).ceiling_ft * FT_M
    t, h, ph = synthetic_flight(cruise_ft=get_profile(model).ceiling_ft)
    c = cabin_pressure(t, h, ph, ceiling_m, model)
    assert c.cruise_cabin_altitude_m == pytest.approx(CABIN_PROFILES[model].max_cabin_alt_ft * FT_M, abs=1e-6)


@pytest.mark.parametrize("model", sorted(CABIN_PROFILES))
def test_cabin_rates_respect_the_limits(model):
    prof = CABIN_PROFILES[model]
    t, h, ph = synthetic_flight(climb_fpm=2000.0, descent_fpm=2000.0)
    c = cabin_pressure(t, h, ph, FL350, model)
    air = np.isin(ph, list(AIRBORNE_PHASES))
    step = air[1:] & air[:-1]
    dt = np.diff(t)
    # the controller's schedule: the limits exactly (up to rounding)
    rs = np.diff(c.schedule_altitude_m)[step] / dt[step] / FPM_MPS
    assert rs.max() <= prof.climb_rate_fpm + 1e-6
    assert rs.min() >= -c.descent_rate_fpm - 1e-6
    assert prof.descent_rate_fpm <= c.descent_rate_fpm <= prof.descent_rate_max_fpm
    # the cabin after the outflow-valve lag: a lag never exceeds its input's largest pressure rate; in
    # altitude the rate can exceed the limit by the density ratio across the lag, r tau / H_rho
    # (H_rho = T / (g / R + L), the density scale height: 9.4 km at the coldest cabin, 8,000 ft)
    h_rho = isa.temperature_k(8000 * FT_M) / (isa._c.g / isa.R_AIR + isa.LAPSE_KPM)
    rc = np.diff(c.cabin_altitude_m)[step] / dt[step] / FPM_MPS
    for limit, got in ((prof.climb_rate_fpm, rc.max()), (c.descent_rate_fpm, -rc.min())):
        over = 2.0 * limit * FPM_MPS * prof.ofv_tau_s / h_rho
        assert got <= limit * (1.0 + over)


def test_the_structural_limit_overrides_the_comfort_rate():
    # a 4,000 ft/min climb to FL350 would need an 820 ft/min cabin: rate-limited at 500 ft/min it falls
    # behind until the differential reaches the maximum, and then the safety limit wins
    prof = CABIN_PROFILES["737"]
    t, h, ph = synthetic_flight(climb_fpm=4000.0)
    c = cabin_pressure(t, h, ph, FL350, "737")
    dp_max = prof.max_diff_pa(FL350)
    diff = isa.pressure_pa(c.schedule_altitude_m) - c.ambient_pressure_pa
    assert diff.max() <= dp_max * (1 + 1e-12)
    climb = np.flatnonzero(ph == "climb")
    rs = np.diff(c.schedule_altitude_m)[climb[:-1]] / np.diff(t)[climb[:-1]] / FPM_MPS
    fast = climb[:-1][rs > prof.climb_rate_fpm + 1e-6] + 1
    assert fast.size  # it happens, and only where the cabin sits at the maximum differential
    np.testing.assert_allclose(diff[fast], dp_max, rtol=1e-9)
    assert np.max(rs[rs <= prof.climb_rate_fpm + 1e-6]) == pytest.approx(prof.climb_rate_fpm, rel=1e-9)


def test_a_short_descent_raises_the_cabin_descent_rate_up_to_the_maximum():
    prof = CABIN_PROFILES["fokker100"]
    t, h, ph = synthetic_flight(descent_fpm=1500.0)
    slow = cabin_pressure(t, h, ph, FL350, "fokker100")
    t, h, ph = synthetic_flight(descent_fpm=6000.0)
    fast = cabin_pressure(t, h, ph, FL350, "fokker100")
    # 8,000 ft + the 0.1 psi below the field in a 23 min descent: about 355 ft/min (> 300 default)
    assert prof.descent_rate_fpm < slow.descent_rate_fpm < prof.descent_rate_max_fpm
    assert fast.descent_rate_fpm == prof.descent_rate_max_fpm  # 6 min: 1,370 ft/min needed, 750 allowed


def test_ground_is_ambient_with_the_doors_open_and_on_the_ground():
    t, h, ph = synthetic_flight(field_m=430.0, arrival_m=1230.0)
    c = cabin_pressure(
        t, h, ph, FL350, "A320", weather=Weather(1002.0, 7.0), arrival_weather=Weather(1021.0, -3.0)
    )
    door = np.isin(ph, ["gate", "parked"])
    assert np.array_equal(c.cabin_pressure_pa[door], c.ambient_pressure_pa[door])  # exactly
    before = np.isin(ph, GROUND)
    np.testing.assert_allclose(c.cabin_pressure_pa[before], c.ambient_pressure_pa[before], rtol=1e-12)

    # the ambient at the fields is the QNH's station pressure (ISA law from QNH to the elevation)
    def station(qnh, e):
        return qnh * HPA_PA * ((isa.T0_K + isa.LAPSE_KPM * e) / isa.T0_K) ** isa.BAROMETRIC_EXPONENT

    assert c.ambient_pressure_pa[0] == pytest.approx(station(1002.0, 430.0), rel=1e-12)
    assert c.ambient_pressure_pa[-1] == pytest.approx(station(1021.0, 1230.0), rel=1e-12)


def test_prepressurisation_on_the_takeoff_roll_and_release_after_landing():
    prof = CABIN_PROFILES["A320"]
    t, h, ph = synthetic_flight()
    c = cabin_pressure(t, h, ph, FL350, "A320")
    diff = c.cabin_pressure_pa - c.ambient_pressure_pa
    roll = np.flatnonzero(ph == "takeoff_roll")
    # the schedule reaches the field + 0.1 psi on the roll (A320 FCOM: 0.1 psi at 400 ft/min)
    sched_diff = isa.pressure_pa(c.schedule_altitude_m) - c.ambient_pressure_pa
    assert sched_diff[roll[-1]] == pytest.approx(0.1 * PSI_PA, rel=1e-9)
    # the cabin lags a ramp of rate r by r tau, decaying as exp(-s / tau) once the ramp is over
    r_pa = prof.prepress_rate_fpm * FPM_MPS * float(isa.density_kgpm3(0.0)) * isa._c.g
    t_ramp = 0.1 * PSI_PA / r_pa
    settle = t[roll[-1]] - t[roll[0]] - t_ramp
    lag_err = r_pa * prof.ofv_tau_s * math.exp(-settle / prof.ofv_tau_s)
    assert 0.1 * PSI_PA - lag_err * 1.05 <= diff[roll[-1]] <= 0.1 * PSI_PA
    # at touchdown the cabin is about 0.1 psi above the field (Airbus), released on the ground:
    # A320 FCOM, the residual pressure is gone about 55 s after landing
    td = np.flatnonzero(ph == "rollout")[0]
    r_desc = c.descent_rate_fpm * FPM_MPS * float(isa.density_kgpm3(0.0)) * isa._c.g
    assert 0.1 * PSI_PA - 1.05 * r_desc * prof.ofv_tau_s <= diff[td] <= 0.1 * PSI_PA
    after = np.flatnonzero(t >= t[td] + 55.0)[0]
    assert abs(diff[after]) < 1.0


def test_holds_pressurised_or_not():
    t, h, ph = synthetic_flight()
    p = cabin_pressure(t, h, ph, FL350, "737", hold="pressurised")
    u = cabin_pressure(
        t, h, ph, FL350, "737", hold="unpressurised"
    )  # valid: it changes the schedule of the hold
    assert np.array_equal(p.hold_pressure_pa, p.cabin_pressure_pa)
    assert np.array_equal(u.hold_pressure_pa, u.ambient_pressure_pa)
    assert np.array_equal(u.cabin_pressure_pa, p.cabin_pressure_pa)  # the cabin itself does not change
    assert u.hold_pressure_pa.min() < 240 * HPA_PA  # FL350 ambient, 238 hPa


def test_ambient_pressure_against_the_hypsometric_equation():
    from scipy.integrate import solve_ivp

    # dp/dz = -p g / (R T), T the ISA temperature of the pressure level plus the deviation
    for qnh, dev in ((1013.25, 0.0), (990.0, 15.0), (1035.0, -12.0)):

        def rhs(z, p, dev=dev):
            return [-p[0] * isa._c.g / (isa.R_AIR * (isa.temperature_k(isa.pressure_altitude_m(p[0])) + dev))]

        sol = solve_ivp(rhs, (0.0, 12_000.0), [qnh * HPA_PA], rtol=1e-11, atol=1e-8, dense_output=True)
        for z in (1000.0, 5000.0, 10_000.0, 12_000.0):
            assert float(ambient_pressure_pa(z, qnh, dev)) == pytest.approx(float(sol.sol(z)[0]), abs=0.05)
    # ISA day: the ISA table (FACTS: 8,000 ft 752.6 hPa)
    assert float(ambient_pressure_pa(8000 * FT_M)) / HPA_PA == pytest.approx(752.6, abs=0.05)


def test_weather_draws_are_seeded_and_bounded():
    a = [draw_weather(np.random.default_rng(3)) for _ in range(2)]
    assert a[0] == a[1]
    ws = [draw_weather(np.random.default_rng(i)) for i in range(400)]
    q = np.array([w.qnh_hpa for w in ws])
    assert 950 <= q.min() and q.max() <= 1050
    # the spread is the stated 8 hPa: 400 draws put the sample std within 10 % (chi-square, 99.9 %)
    assert q.std(ddof=1) == pytest.approx(8.0, rel=0.1)


def test_bad_input_raises_typed_one_line_errors():
    t, h, ph = synthetic_flight()
    cases = [
        (AircraftError, 'did you mean "A320"', lambda: cabin_pressure(t, h, ph, FL350, "A32")),
        (
            ScenarioError,
            'did you mean "unpressurised"',
            lambda: cabin_pressure(t, h, ph, FL350, "A320", hold="unpressurized"),
        ),
        (
            InputDataError,
            "NaN",
            lambda: cabin_pressure(t, np.where(t == t[500], np.nan, h), ph, FL350, "A320"),
        ),
        (
            InputDataError,
            "uniformly",
            lambda: cabin_pressure(np.where(t > 100, t + 5.0, t), h, ph, FL350, "A320"),
        ),
        (
            InputDataError,
            'did you mean "cruise"',
            lambda: cabin_pressure(t, h, np.where(ph == "cruise", "cruse", ph), FL350, "A320"),
        ),
        (InputDataError, "cruise_alt_m", lambda: cabin_pressure(t, h, ph, -1.0, "A320")),
    ]
    for err, text, call in cases:
        with pytest.raises(err) as e:
            call()
        assert text in str(e.value) and "\n" not in str(e.value)
    assert get_cabin_profile("787-8").max_cabin_alt_ft == 6000.0
    assert dataclasses.is_dataclass(get_cabin_profile("737"))
