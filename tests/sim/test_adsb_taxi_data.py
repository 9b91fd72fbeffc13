"""The ADS-B taxi figures ship as package data (sim/flight/data/adsb_taxi.toml), read once."""

from __future__ import annotations

from importlib.resources import files

import flightmode.sim.flight.taxi_stats as ts


def test_the_data_file_states_its_sources_and_reads_once():
    text = files("flightmode.sim.flight").joinpath(ts.ADSB_TAXI_FILE).read_text(encoding="utf-8")
    assert "MIT licence" in text and "TK1745" in text and "N899DN" in text  # the sources, in its header
    a = ts.adsb_taxi_anchors()
    assert a is ts.adsb_taxi_anchors() is ts.ADSB_TAXI_ANCHORS  # functools.cache: one read
    assert {k: len(v) for k, v in a.items()} == {
        "fr24_TK1745_B738_IST-OSL_2024-09-17": 2,
        "readsb_N899DN_B739_DAL_2025-02-04_fullday": 4,
    }
    # every segment has every figure taxi_statistics returns, as floats
    keys = set(next(iter(next(iter(a.values())).values())))
    assert all(
        set(seg) == keys and all(type(v) is float for v in seg.values())
        for t in a.values()
        for seg in t.values()
    )
    assert a["fr24_TK1745_B738_IST-OSL_2024-09-17"]["taxi_out_0755Z"]["duration_s"] == 363.0
