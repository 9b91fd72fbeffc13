"""The cabin near the ground (issue 50, item 4) on synthetic profiles: the landing pressure reached
before touchdown and held, each type's vent after it, the rate limits, the declared parameters and
their overrides. The same figures on a JSBSim flight: test_pressure_flight.py."""

from __future__ import annotations

import math

import numpy as np
import pytest

from flightmode.errors import ScenarioError
from flightmode.labels import AIRBORNE_PHASES, PHASE_CODE
from flightmode.sim.flight import atmosphere as isa
from flightmode.sim.flight.cabin import (
    CABIN_PROFILES,
    LANDING_LEVEL_HEIGHT,
    LANDING_RESIDUAL,
    UNCERTAIN,
    VENT_737,
    VENT_787,
    cabin_pressure,
)
from flightmode.sim.flight.cabin_landing import TOL_PA, VENT_ANCHORS, landing_figures, touchdown_index
from flightmode.units import FPM_MPS, FT_M, PSI_PA
from tests.sim.test_cabin import FL350, synthetic_flight

DESCENT_FPM = 1500.0  # the synthetic descent runs straight to the runway at this rate
FS_HZ = 10.0


def _flight(model: str, overrides=None, **kw):
    t, h, ph = synthetic_flight(fs_hz=FS_HZ, descent_fpm=DESCENT_FPM, **kw)
    c = cabin_pressure(t, h, ph, FL350, model, overrides=overrides)
    code = np.array([PHASE_CODE[p] for p in ph])
    return t, h, ph, c, landing_figures(t, h, c.cabin_pressure_pa, c.ambient_pressure_pa, code)


def _landing_alt_m(c, resid_psi: float) -> float:
    # the arrival field's pressure is the ambient at the last sample (on the ground at the field)
    return float(isa.pressure_altitude_m(c.ambient_pressure_pa[-1] + resid_psi * PSI_PA))


@pytest.mark.parametrize("model", sorted(CABIN_PROFILES))
def test_the_landing_pressure_is_reached_at_the_level_off_height_and_held_to_touchdown(model):
    t, h, ph, c, f = _flight(model)
    td = int(np.flatnonzero(ph == "rollout")[0])
    target = _landing_alt_m(c, LANDING_RESIDUAL.value)
    # the schedule reaches the landing pressure where the aircraft is N = 1,000 ft above the field
    # (to one sample's descent, 2.5 ft) and stays there, exactly, to the last airborne sample (the
    # interval into the touchdown sample is the ground's: a vent from touchdown starts there)
    at = np.flatnonzero(np.abs(c.schedule_altitude_m[:td] - target) > 1e-6)[-1] + 1
    assert h[at] / FT_M == pytest.approx(LANDING_LEVEL_HEIGHT.value, abs=DESCENT_FPM / 60 / FS_HZ + 1e-6)
    assert np.all(np.abs(c.schedule_altitude_m[at:td] - target) <= 1e-6)
    # the cabin follows through the outflow valve's lag: a ramp of rate r lags by r tau, decaying as
    # exp(-s / tau) once the ramp ends; r at most the 750 ft/min descent limit (about 46 Pa/s near sea
    # level), so the cabin is within TOL_PA of its landing pressure tau ln(r tau / TOL) = 16 s after the
    # schedule, 40 s (1,000 ft at 1,500 ft/min) before touchdown
    tau = CABIN_PROFILES[model].ofv_tau_s
    r_pa_s = 750.0 * FPM_MPS * float(isa.density_kgpm3(0.0)) * isa._c.g
    settle_s = tau * math.log(r_pa_s * tau / TOL_PA)
    ahead_s = LANDING_LEVEL_HEIGHT.value / DESCENT_FPM * 60.0
    assert ahead_s - settle_s <= f["level_before_touchdown_s"] <= ahead_s + 1.0 / FS_HZ
    # held to touchdown: the residual is the declared 0.1 psi (the lag settled over 8 tau: < 0.1 Pa;
    # the touchdown sample is one interval into a vent from touchdown, through which the lag passes
    # 1 - exp(-dt / tau) = 2 % of the 787's first 14 Pa step: 0.3 Pa)
    assert f["residual_psi"] * PSI_PA == pytest.approx(LANDING_RESIDUAL.value * PSI_PA, abs=0.5)


@pytest.mark.parametrize("model", sorted(CABIN_PROFILES))
def test_the_vent_after_touchdown_per_type(model):
    prof = CABIN_PROFILES[model]
    t, h, ph, c, f = _flight(model)
    td = int(np.flatnonzero(ph == "rollout")[0])
    taxi = int(np.flatnonzero(ph == "taxi_in")[0])
    target = _landing_alt_m(c, LANDING_RESIDUAL.value)
    field = float(isa.pressure_altitude_m(c.ambient_pressure_pa[-1]))
    rise = np.diff(c.schedule_altitude_m)[td:] * FS_HZ / FPM_MPS  # ft/min, interval k -> k+1
    # the whole residual vents, as one step of 0.1 psi (6.9 hPa; the lag has moved the cabin by less
    # than 1 Pa in the touchdown sample), and the cabin is ambient at the door
    assert f["step_hpa"] * 100.0 == pytest.approx(LANDING_RESIDUAL.value * PSI_PA, abs=1.0)
    door = int(np.flatnonzero(ph == "parked")[0])
    assert abs(c.cabin_pressure_pa[door - 1] - c.ambient_pressure_pa[door - 1]) < 1e-3
    if prof.vent_start == "taxi_in":  # 737: held through the rollout, vented from the taxi-in
        assert np.all(np.abs(c.schedule_altitude_m[td:taxi] - target) <= 1e-6)
        assert f["vent_start_s"] >= t[taxi] - t[td]
        rate = (field - target) / FT_M / (VENT_737.value / 60.0)
        assert rise.max() == pytest.approx(rate, rel=1e-9)
        # the ramp lasts the declared vent time (the cabin is within TOL of ambient TOL / residual of it
        # early); the lag then settles within TOL in tau ln(r tau / TOL)
        r_pa_s = LANDING_RESIDUAL.value * PSI_PA / VENT_737.value
        assert (
            VENT_737.value * (1.0 - TOL_PA / (LANDING_RESIDUAL.value * PSI_PA))
            <= f["vent_complete_s"] - (t[taxi] - t[td])
            <= VENT_737.value + prof.ofv_tau_s * math.log(r_pa_s * prof.ofv_tau_s / TOL_PA) + 0.2
        )
        assert f["vent_complete_s"] < f["door_open_s"]
    else:  # from touchdown: A320 and Fokker 100 at 500 ft/min, 787 over its declared vent time
        rate = (
            prof.release_rate_fpm if prof.vent is None else (field - target) / FT_M / (VENT_787.value / 60.0)
        )
        assert rise.max() == pytest.approx(rate, rel=1e-9)
        assert rise[0] == pytest.approx(rate, rel=1e-9)  # the first interval after touchdown
        # the lagged cabin drops TOL below its touchdown value within the lag's time constant
        assert f["vent_start_s"] <= prof.ofv_tau_s
        anchor = VENT_ANCHORS.get(model)
        if anchor is not None:  # A320: 55 s (FCOM); 787: 30 s (a valve's full travel)
            assert f["vent_complete_s"] <= anchor.complete_s
    # never below ambient (the relief valve), never faster than the venting rate
    assert np.all(c.cabin_pressure_pa[td:] >= c.ambient_pressure_pa[td:] - 1e-6)


@pytest.mark.parametrize("model", sorted(CABIN_PROFILES))
def test_the_descent_keeps_its_rate_limit_with_the_earlier_level_off(model):
    # the squeezed end of the schedule asks for a faster cabin: the rate limiter starts the cabin down
    # earlier instead, within the type's limits (the "optimised" rate up to the maximum)
    prof = CABIN_PROFILES[model]
    for fpm in (1500.0, 3000.0):
        t, h, ph = synthetic_flight(fs_hz=FS_HZ, descent_fpm=fpm)
        c = cabin_pressure(t, h, ph, FL350, model)
        air = np.isin(ph, list(AIRBORNE_PHASES))
        step = air[1:] & air[:-1]
        rs = np.diff(c.schedule_altitude_m)[step] * FS_HZ / FPM_MPS
        assert rs.min() >= -c.descent_rate_fpm - 1e-6
        assert c.descent_rate_fpm <= prof.descent_rate_max_fpm


def test_the_schedule_above_twice_the_level_off_height_is_the_proportional_one():
    # above 2N the descent schedule is the cruise cabin to the landing pressure in proportion to the
    # aircraft's altitude, as before the level-off existed (where no rate limit acts)
    t, h, ph, c, f = _flight("A320")
    desc = np.flatnonzero(ph == "descent")
    target = _landing_alt_m(c, LANDING_RESIDUAL.value)
    field = float(isa.pressure_altitude_m(c.ambient_pressure_pa[-1]))
    h_amb = isa.pressure_altitude_m(c.ambient_pressure_pa)
    prop = target + (c.cruise_cabin_altitude_m - target) * (h_amb - field) / (FL350 - field)
    high = desc[h_amb[desc] - field > 2 * LANDING_LEVEL_HEIGHT.value * FT_M]
    # the rate-limited schedule lies at or below it (the limiter only starts the cabin down earlier) ...
    assert np.all(c.schedule_altitude_m[high] <= prop[high] + 1e-6)
    # ... and equals it wherever the limiter does not act (most of a 1,500 ft/min descent: the A320's
    # cabin needs 200-300 ft/min of its 350)
    same = np.abs(c.schedule_altitude_m[high] - prop[high]) <= 1e-6
    assert same.mean() > 0.5


def test_overrides_move_the_landing_figures_and_are_checked_against_their_range():
    o = {
        "cabin.landing_residual_psi": 0.05,
        "cabin.landing_level_height_ft": 2000.0,
        "cabin.vent_737_s": 200.0,
    }
    t, h, ph, c, f = _flight("737", overrides=o)
    assert f["residual_psi"] * PSI_PA == pytest.approx(0.05 * PSI_PA, abs=0.1)
    assert (c.landing_residual_psi, c.landing_level_height_m, c.vent_s) == (0.05, 2000.0 * FT_M, 200.0)
    ahead_s = 2000.0 / DESCENT_FPM * 60.0  # 80 s; the lag settles within 16 s (first test)
    assert ahead_s - 16.0 <= f["level_before_touchdown_s"] <= ahead_s + 0.1
    taxi_s = f["taxi_in_s"]
    # 200 s of ramp, within TOL of ambient TOL / residual of it early; the lag adds at most 15 s
    assert 200.0 * (1.0 - TOL_PA / (0.05 * PSI_PA)) <= f["vent_complete_s"] - taxi_s <= 200.0 + 15.0
    # the defaults are the declared values, and a value outside a declared range is refused
    assert {p.name for p in UNCERTAIN} == {
        "cabin.landing_residual_psi",
        "cabin.landing_level_height_ft",
        "cabin.vent_737_s",
        "cabin.vent_787_s",
    }
    with pytest.raises(ScenarioError, match="outside its declared range"):
        _flight("787-8", overrides={"cabin.vent_787_s": 60.0})


def test_landing_figures_without_a_touchdown_are_empty():
    t, h, ph = synthetic_flight(fs_hz=1.0)
    code = np.array([PHASE_CODE[p] for p in ph])
    assert touchdown_index(np.full(5, PHASE_CODE["gate"])) is None
    ground = np.where(np.isin(ph, list(AIRBORNE_PHASES)), "taxi_out", ph)
    assert landing_figures(t, h, h, h, np.array([PHASE_CODE[p] for p in ground])) == {}
    assert touchdown_index(code) == int(np.flatnonzero(ph == "rollout")[0])
