"""flightmode's edits to the stock JSBSim models (sim.flight.model_edits), other than the gear's."""

from __future__ import annotations

import xml.etree.ElementTree as ET

import numpy as np
import pytest

from flightmode.errors import AircraftError
from flightmode.sim.flight.jsbsim_adapter import stock_model_xml
from flightmode.sim.flight.model_edits import spread_spoiler_lift_loss


def _model(name: str) -> ET.Element:
    return ET.parse(stock_model_xml(name)).getroot()


def _spoiler_lift_table(root: ET.Element) -> np.ndarray:
    for table in root.iterfind(".//aerodynamics//table"):
        if (table.findtext("independentVar") or "").strip() == "fcs/spoiler-pos-norm":
            return np.array([[float(v) for v in line.split()] for line in table.findtext("tableData").split("\n")
                             if line.strip()])
    raise AssertionError("no spoiler lift table")


def test_the_737_spoilers_lose_their_lift_over_their_whole_travel():
    """The stock 737 loses 40 % of its lift at 10 % of the spoilers' travel; after the edit the same
    40 % is lost at full travel and, linearly, 4 % at 10 % (JSBSim interpolates tables linearly)."""
    stock, root = _spoiler_lift_table(_model("737")), _model("737")
    spread_spoiler_lift_loss(root)
    edited = _spoiler_lift_table(root)
    assert np.interp(0.1, *stock.T) == pytest.approx(0.6, abs=1e-12)
    assert edited[-1].tolist() == pytest.approx([1.0, 0.6], abs=1e-12)
    assert np.interp(0.1, *edited.T) == pytest.approx(0.96, abs=1e-12)
    assert np.interp(0.5, *edited.T) == pytest.approx(0.8, abs=1e-12)


def test_a_model_without_a_spoiler_lift_table_is_refused_by_name():
    # the stock A320 has no lift term for its spoilers: the edit must not pass silently
    with pytest.raises(AircraftError, match="spoiler lift table"):
        spread_spoiler_lift_loss(_model("A320"))


def test_the_737s_load_factor_does_not_drop_when_its_spoilers_open(fly_cached):
    """After the mains touch, the struts take the weight the spoilers take from the wing. Their rebound
    leaves the centre of gravity's load factor at most about 0.15 g under 1 g (30 seeded 737 pattern
    landings with the edit: lowest 0.82 g, median 0.87 g, 0.5 s before to 3 s after the touchdown). The
    stock table's lift loss within 0.06 s let it fall far lower (same 30: median 0.81 g, lowest 0.61 g;
    this flight 0.75 g)."""
    from flightmode.units import G0_MPS2

    sc, tr = fly_cached("pattern")
    assert sc.aircraft == "737"
    t_td = tr.event_time("touchdown")
    near = (tr.t_s >= t_td - 0.5) & (tr.t_s <= t_td + 3.0)
    nz = -tr.specific_force_body_mps2[near, 2] / G0_MPS2
    assert nz.min() > 0.8
