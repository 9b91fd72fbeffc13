"""Acceptance of seed 000's recommended detector (Table 9: NMV, W_s 1 s, T_sigma 4 sigma^2,
T_th 4 s) on every built-in flight, sensed with the seed's logger (lis302dl-logged16): no final
static inside the in-flight window, and a final static within 10 s of the bag truly coming to rest
after the flight (slow: each flight is flown once per session)."""

from __future__ import annotations

import numpy as np
import pytest

from flightmode.detector.evaluation import evaluate
from flightmode.detector.flight_mode import DetectorParams, sigma2_from_preset

SCENARIOS = ["pattern", "gva-lhr-a320", "hel-zrh-f100", "ist-osl-737", "lhr-jfk-787"]


@pytest.mark.slow
@pytest.mark.parametrize("name", SCENARIOS)
def test_recommended_detector_is_silent_in_flight_and_answers_after(name, fly_cached):
    from flightmode.sim.sensor.accelerometer import get_preset
    from flightmode.sim.sensor.carrier import CarrierSpec
    from flightmode.sim.sensor.sensing import sense

    plan, tr = fly_cached(name)
    rec = sense(tr, CarrierSpec(**(plan.extra.get("carrier") or {})), get_preset("lis302dl-logged16"),
                np.random.default_rng([plan.seed, 0x5E45E]))
    p = DetectorParams()
    s2 = sigma2_from_preset(rec.preset, rec.odr_hz, rec.unit, p.window, np.random.default_rng([plan.seed, 0xCA1]))
    e = evaluate(rec.t_s, rec.acc_g, {"in_flight_window": rec.in_flight_window,
                                      "sensor_static": rec.sensor_static, "phase": rec.phase}, p, s2)
    temp_in_flight = int((e.checks.temporary_static & rec.in_flight_window[e.checks.index]).sum())
    print(f"\n{name}: sigma^2 {s2}, in-flight checks {e.in_flight_checks}, temporary statics in flight "
          f"{temp_in_flight}, final {e.false_static_count}, response {e.response_s} s, "
          f"accuracy {e.accuracy:.4f}, correlation {e.correlation:.4f}")
    assert e.false_static_count == 0, e.false_static_events
    assert e.response_s is not None and e.response_s <= 10.0
