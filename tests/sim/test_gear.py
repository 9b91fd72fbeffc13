"""The oleo struts flightmode gives the stock JSBSim models (sim.flight.jsbsim.gear)."""

from __future__ import annotations

import xml.etree.ElementTree as ET

import pytest

from flightmode.sim.flight.jsbsim.gear import MAIN_SHARE, main_strut, nose_gear, soften_nose_gear
from flightmode.sim.flight.jsbsim.model_copy import stock_model_xml


def _model(name: str) -> ET.Element:
    return ET.parse(stock_model_xml(name)).getroot()


@pytest.mark.parametrize(
    "model,nose", [("A320", "NOSE_LG"), ("737", "Nose Gear"), ("fokker100", "NOSE"), ("787-8", "NOSE_GEAR")]
)
def test_the_nose_gear_is_the_one_steerable_contact(model, nose):
    # the models name their nose gear (the A320 also declares nine structural points as BOGEYs)
    assert nose_gear(_model(model)).get("name").strip() == nose


@pytest.mark.parametrize("model", ["A320", "737", "fokker100", "787-8"])
def test_the_nose_strut_damps_like_the_mains_scaled_to_its_weight_and_keeps_its_spring(model):
    """The nose gear's compression damping becomes quadratic, c2 of a main strut times the ratio of
    the weights they carry (1 - MAIN_SHARE against MAIN_SHARE / n_main); its spring and its rebound
    damping stay the stock model's (the stance and the taxiway response are the model's)."""
    from flightmode.sim.flight.aircraft.registry import get_profile
    from flightmode.sim.flight.jsbsim.gear import main_gear

    stock, root = _model(model), _model(model)
    mass_kg = get_profile(model).ref_landing_mass_kg
    c2 = soften_nose_gear(root, mass_kg)
    n_main = len(main_gear(stock))
    _, c2_main = main_strut(mass_kg, n_main)
    assert c2 == pytest.approx(c2_main * (1.0 - MAIN_SHARE) * n_main / MAIN_SHARE, rel=1e-12)
    before, after = nose_gear(stock), nose_gear(root)
    assert after.find("damping_coeff").get("type") == "SQUARE"
    assert float(after.findtext("damping_coeff")) == pytest.approx(c2, abs=5e-4)  # written to 3 decimals
    assert after.findtext("spring_coeff") == before.findtext("spring_coeff")
    rebound = before.find("damping_coeff_rebound")
    assert float(after.findtext("damping_coeff_rebound")) == float(
        (rebound if rebound is not None else before.find("damping_coeff")).text
    )
