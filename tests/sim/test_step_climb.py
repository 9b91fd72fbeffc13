"""Step climbs (sim.flight.pilot.step_climb): the optimum-level law against the ISA stratosphere in closed
form, the trigger, and the long built-in flight that climbs a step (slow)."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy import constants

from flightmode.sim.flight.pilot.step_climb import STEP_FT, next_level_m, optimum_alt_m
from flightmode.units import FT_M


def test_optimum_level_rises_as_the_stratosphere_scale_height_says():
    # above the tropopause (11 km) the ISA is isothermal at 216.65 K, so p ~ exp(-g h / (R T)): with
    # p_opt proportional to the weight, a weight ratio w puts the optimum H ln(1/w) higher, H = R T / g
    # (R = R* / M, M = 28.9644 g/mol: U.S. Standard Atmosphere 1976). 2 cm: far above the rounding of
    # the closed-form inverse (sim.flight.atmosphere.pressure_altitude_m).
    scale_m = constants.R / 0.0289644 * 216.65 / constants.g
    for w in (0.97, 0.9, 0.8):
        assert optimum_alt_m(w, 1.0, 11_500.0) - 11_500.0 == pytest.approx(
            scale_m * math.log(1.0 / w), abs=0.02
        )
    assert optimum_alt_m(1.0, 1.0, 9_000.0) == pytest.approx(9_000.0, abs=0.01)  # the reference is optimal


def test_pressure_altitude_inverts_the_isa_pressure_in_both_layers():
    from flightmode.sim.flight.atmosphere import pressure_altitude_m, pressure_pa

    h = np.array([-300.0, 0.0, 5_000.0, 10_999.0, 11_000.0, 11_001.0, 15_000.0, 19_000.0])
    np.testing.assert_allclose(pressure_altitude_m(pressure_pa(h)), h, atol=1e-6)  # float64 rounding


def test_a_step_is_due_half_a_step_below_the_optimum_and_never_above_the_ceiling():
    h = 11_000.0
    scale_m = constants.R / 0.0289644 * 216.65 / constants.g
    w_half = math.exp(-1000.0 * FT_M / scale_m)  # the weight that puts the optimum 1,000 ft higher
    assert next_level_m(h, w_half * 1.001, 1.0, h, 45_000 * FT_M) is None
    assert next_level_m(h, w_half * 0.999, 1.0, h, 45_000 * FT_M) == pytest.approx(h + STEP_FT * FT_M)
    assert next_level_m(h, 0.5, 1.0, h, h + 1000.0 * FT_M) is None  # the next level is above the ceiling


@pytest.mark.slow
def test_the_transatlantic_787_steps_up_2000_ft_and_the_737_stays_below_its_ceiling(fly_cached):
    _, tr = fly_cached("lhr-jfk-787")
    steps = [e for e in tr.events if e.name == "step_climb"]
    assert steps, "a 7 h flight burns over 10 % of its weight: at least one step is due"
    t_step = steps[0].t_s
    before = tr.alt_m[(tr.t_s > t_step - 600) & (tr.t_s < t_step)]
    after = tr.alt_m[(tr.t_s > t_step + 600) & (tr.t_s < t_step + 1200)]
    # one RVSM step, 2,000 ft (609.6 m), held to within the altitude loop's 30 m
    assert np.median(after) - np.median(before) == pytest.approx(STEP_FT * FT_M, abs=30.0)
    assert tr.alt_m.max() < 43_100 * FT_M  # the 787-8's maximum operating altitude
    # the ascent is a cruise-thrust climb, never faster than STEP_VS_MPS (+0.5 m/s for the loop's overshoot)
    s = (tr.t_s > t_step) & (tr.t_s < t_step + 600)
    assert tr.vertical_speed_mps[s].max() < 1000 * FT_M / 60 + 0.5
    _, tr7 = fly_cached("ist-osl-737")
    assert not [
        e for e in tr7.events if e.name == "step_climb"
    ]  # FL371 is at the 737-300's 37,000 ft already
