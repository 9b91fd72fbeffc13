"""The oleo struts flightmode gives the stock JSBSim models (sim.flight.gear)."""

from __future__ import annotations

import os
import xml.etree.ElementTree as ET

import pytest

from flightmode.sim.flight.gear import MAIN_SHARE, main_strut, nose_gear, peak_load_factor, soften_nose_gear
from flightmode.units import FT_M, G0_MPS2, LBF_N


def _model(name: str) -> ET.Element:
    import jsbsim

    return ET.parse(os.path.join(jsbsim.get_default_root_dir(), "aircraft", name, name + ".xml")).getroot()


@pytest.mark.parametrize("model,nose", [("A320", "NOSE_LG"), ("737", "Nose Gear"), ("fokker100", "NOSE"),
                                        ("787-8", "NOSE_GEAR")])
def test_the_nose_gear_is_the_one_steerable_contact(model, nose):
    # the models name their nose gear (the A320 also declares nine structural points as BOGEYs)
    assert nose_gear(_model(model)).get("name").strip() == nose


@pytest.mark.parametrize("sink_fps", [2.0, 6.0, 10.0])
def test_the_nose_strut_is_the_main_strut_scaled_to_the_weight_it_carries(sink_fps):
    """Spring and quadratic damper both in proportion to the carried mass leave the 1-DOF strut's
    motion unchanged (m x'' = -(k x + c2 x'|x'|) divided through by the scale): the nose strut's
    peak load on its own share of the weight equals the mains' on theirs, to the ODE solver's
    tolerance (rtol 1e-8; 1e-6 allowed)."""
    mass_kg, n_main = 64_500.0, 2
    root = _model("A320")
    k_n, c2_n = soften_nose_gear(root, mass_kg)
    k_m, c2_m = main_strut(mass_kg, n_main)
    weight = mass_kg * G0_MPS2 / LBF_N
    # the same static deflection under the share each carries (0.35 m)
    assert k_n * 0.35 / FT_M == pytest.approx((1.0 - MAIN_SHARE) * weight, rel=1e-9)
    # peak_load_factor carries MAIN_SHARE of "weight" on n struts: the nose's weight is chosen so that
    # its one strut carries (1 - MAIN_SHARE) of the aircraft's
    nose_weight = (1.0 - MAIN_SHARE) / MAIN_SHARE * weight
    assert peak_load_factor(sink_fps, nose_weight, k_n, c2_n, 1) == pytest.approx(
        peak_load_factor(sink_fps, weight, k_m, c2_m, n_main), rel=1e-6)
    # and the edit is in the model: quadratic compression damping, the stock linear one kept for rebound
    c = nose_gear(root)
    assert c.find("damping_coeff").get("type") == "SQUARE" and c.find("damping_coeff_rebound") is not None
