"""The verdict with its uncertainty (flightmode.studies.uncertainty, viz.tornado): the worst corner,
the sentence, the tornado's data and chart; and the whole study on a tiny real population (slow)."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from flightmode.errors import ScenarioError
from flightmode.studies.uncertainty import (
    CORNER,
    NOMINAL,
    UncertaintyResult,
    Variant,
    choose_parameters,
    sentence_of,
    tornado_data,
    worst_corner,
)


def _v(label: str, overrides: dict, bound: float, events: int = 1) -> Variant:
    at = {
        "false_statics": events,
        "in_window_h": 3.0,
        "rate_per_h": events / 3.0,
        "rate_upper_per_h": bound,
        "response_p50_s": 5.0,
        "response_p95_s": 6.0,
        "response_max_s": 7.0,
        "availability": 0.9,
        "meets": False,
    }
    rec = {
        "status": "meets",
        "point": "NMV, W_s 1 s, 4 sigma^2, T_th 4 s",
        "false_statics": events,
        "rate_upper_per_h": bound,
        "response_p50_s": 5.0,
        "response_p95_s": 6.0,
        "availability": 0.9,
        "text": "",
    }
    paper = at | {"false_statics": 10 * events, "rate_upper_per_h": 10 * bound}  # seed 000's point
    return Variant(label, overrides, "ds", 4, 3.0, at, rec, paper)


def test_the_worst_corner_takes_each_parameter_to_the_end_that_raised_the_bound():
    params = [
        {"name": "a", "value": 1.0, "low": 0.5, "high": 2.0, "bound_low": 1.0, "bound_high": 3.0},
        {"name": "b", "value": 1.0, "low": 0.5, "high": 2.0, "bound_low": 2.5, "bound_high": 1.5},
        # neither end above the nominal's 2.0: b stays nominal... and c too
        {"name": "c", "value": 1.0, "low": 0.5, "high": 2.0, "bound_low": 2.0, "bound_high": 1.0},
        # the high end is the nominal value itself: never a change
        {"name": "d", "value": 1.0, "low": 0.33, "high": 1.0, "bound_low": 1.0, "bound_high": 2.0},
    ]
    assert worst_corner(params, 2.0) == {"a": 2.0, "b": 0.5}


def test_the_sentence_says_the_recommendation_holds_or_where_it_flips():
    nominal = _v(NOMINAL, {}, 0.8)
    ok = [_v("a=2", {"a": 2.0}, 0.9), _v("a=0.5", {"a": 0.5}, 0.7)]
    holds, text = sentence_of(1.0, nominal, ok, {"a": "Hz"})
    assert holds and text == "the recommendation holds across the model's uncertainty"
    flips = [*ok, _v("b=3", {"b": 3.0}, 1.7), _v("c=9", {"c": 9.0}, 1.2)]
    holds, text = sentence_of(1.0, nominal, flips, {"b": "Hz"})
    assert not holds and text == "it flips when b is at 3 Hz (bound 1.7 /h > target 1 /h)"
    corner_only = [*ok, _v(CORNER, {"a": 2.0, "b": 3.0}, 1.1)]
    holds, text = sentence_of(1.0, nominal, corner_only, {})
    assert not holds and "every parameter is at its worst end together (a = 2, b = 3)" in text
    # a nominal that already misses the target: no verdict to hold, and the spread is said
    holds, text = sentence_of(0.5, nominal, flips, {})
    assert not holds and text.startswith("no verdict to hold") and "1.7 /h (b=3)" in text


def test_an_unknown_parameter_names_the_nearest():
    with pytest.raises(ScenarioError, match='did you mean "mount.seat.fn_v_scale"'):
        choose_parameters(["mount.seat.fn_v"])
    assert choose_parameters(["turbulence.background_scale", "mount.seat.fn_v_scale"]) == [
        "mount.seat.fn_v_scale",  # the registry's order
        "turbulence.background_scale",
    ]


def test_the_tornado_is_drawn_from_plain_data_and_written_atomically(tmp_path):
    from flightmode.viz.tornado import bar_order, fig_tornado, tornado_html

    nominal = _v(NOMINAL, {}, 0.8)
    lo, hi = _v("a=0.5", {"a": 0.5}, 0.6), _v("a=2", {"a": 2.0}, 1.4)
    result = UncertaintyResult(
        1.0,
        0.95,
        "NMV, W_s 1 s, 4 sigma^2, T_th 4 s",
        nominal,
        [lo, hi],
        hi,
        [
            {
                "name": "a",
                "unit": "1",
                "value": 1.0,
                "low": 0.5,
                "high": 2.0,
                "bound_low": 0.6,
                "bound_high": 1.4,
                "seed000_bound_low": 6.0,
                "seed000_bound_high": 14.0,
            },
            {
                "name": "b",
                "unit": "Hz",
                "value": 1.0,
                "low": 0.5,
                "high": 2.0,
                "bound_low": 0.8,
                "bound_high": 0.9,
                "seed000_bound_low": 8.0,
                "seed000_bound_high": None,  # a grid may lack the paper's point
            },
        ],
        False,
        "it flips when a is at 2 (bound 1.4 /h > target 1 /h)",
    )
    data = tornado_data(result)
    assert data.nominal_bound == 0.8 and data.corner_bound == 1.4 and data.target == 1.0
    assert data.bars[0] == ("a", 0.5, 2.0, "1", 0.6, 1.4)
    assert bar_order(data) == [0, 1]  # the widest swing on top
    assert data.seed000 == (8.0, ((6.0, 14.0), (8.0, None)), 14.0)  # the paper's point: its own band
    assert [r["variant"] for r in data.rows] == [NOMINAL, "a=0.5", "a=2", "a=2"]
    png = tmp_path / "figures" / "tornado.png"
    fig_tornado(data, png)
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert not list(png.parent.glob("*.tmp*"))  # renamed into place, no temporary left
    html = "\n".join(tornado_html(data, png.read_bytes()))
    assert "it flips when a is at 2" in html and "data:image/png;base64," in html
    json.dumps(result.as_dict())  # plain numbers all the way down (certify.json, --json)


FAMILY = """
[family]
name = "uncertainty-test"
seed = 77

[aircraft]
fokker100 = 1

[routes]
pairs = [["LSZH", "EDDS"]]

[turbulence]
patch_probability = 0.0

[carrier]
kind = { handbag = 1 }
placement = { lap = 1 }
handled_in_cruise = { 0 = 1 }
"""


@pytest.mark.slow
def test_the_study_on_a_tiny_real_population(tmp_path):
    """One short-hop flight of a bag on a lap (each variant flies the population again: one flight
    keeps the test to three); one sensor-side parameter. Its variant's tracks are
    the nominal's, bit for bit (common random numbers: the lap's mount acts after the flight), its
    recordings are not; the report holds the tornado and certify.json the variants."""
    import pyarrow.parquet as pq

    from flightmode.datasets.make import make_dataset
    from flightmode.detector.grid import grid_from_text
    from flightmode.scenarios.family import Family
    from flightmode.scenarios.scenario import Scenario
    from flightmode.studies.certify import Target
    from flightmode.studies.uncertainty import uncertainty

    ds = tmp_path / "ds"
    make_dataset(Family.from_toml_text(FAMILY), 1, ds, workers=2, truth="full")
    grid = grid_from_text("nmv", "5", "1", "2:6:2", "2:6:2")
    out = tmp_path / "certify"
    cert, study = uncertainty(
        ds, grid, Target(rate_per_h=5.0), parameters=["mount.lap.fn_v_scale"], workers=2, out=out
    )
    labels = [v.label for v in study.variants]
    assert labels == ["mount.lap.fn_v_scale=0.75", "mount.lap.fn_v_scale=2"]
    for v in study.variants:
        vdir = Path(v.dataset)
        assert vdir.parent == ds / "uncertainty" and v.flights_ok == 1
        # the overrides travel with each flight's scenario (the manifest's scenario_toml)
        for row in pq.read_table(vdir / "flights.parquet").to_pylist():
            assert Scenario.from_toml_text(row["scenario_toml"]).overrides == v.overrides
        for part in ("truth", "samples"):
            a = pq.read_table(ds / part).sort_by([("flight_id", "ascending"), ("t_s", "ascending")])
            b = pq.read_table(vdir / part).sort_by([("flight_id", "ascending"), ("t_s", "ascending")])
            if part == "truth":
                assert a.equals(b), "a sensor-side parameter moved the flight"
            else:
                assert not a.column("acc_z_g").equals(b.column("acc_z_g")), "the lap's mount changed nothing"
    assert study.sentence.startswith(("the recommendation holds", "it flips when", "no verdict to hold"))
    saved = json.loads((out / "certify.json").read_text())
    assert [v["label"] for v in saved["uncertainty"]["variants"]] == labels
    assert (out / "figures" / "tornado.png").exists()
    assert "The verdict with its uncertainty" in (out / "report.html").read_text()
    assert cert.recommendation["point"] is not None
