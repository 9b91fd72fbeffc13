"""Seed 000's recommended point is written once (detector/recommended_point.py) and everything that
names it is built from it."""

from __future__ import annotations

import ast
import dataclasses
import inspect

from flightmode.detector import recommended_point
from flightmode.detector.flight_mode import DetectorParams
from flightmode.detector.recommended import RECOMMENDED
from flightmode.detector.recommended_point import POINT


def test_the_point_is_seed_000_table_9():
    # seed 000, Table 9 and section 7: NMV, W_s 1 s, T_sigma 4 sigma^2, T_th 4 s
    assert (POINT.method, POINT.window_s, POINT.k_sigma, POINT.time_threshold_s) == ("nmv", 1.0, 4.0, 4.0)
    assert POINT.text == "NMV, W_s 1 s, 4 sigma^2, T_th 4 s"
    assert POINT.short_text == "NMV, 1 s, 4 sigma^2, 4 s"


def test_the_detector_defaults_recommended_and_the_certify_point_are_the_one_copy():
    d = DetectorParams()
    fields = ("method", "weight", "window_s", "k_sigma", "time_threshold_s")
    assert {f: getattr(d, f) for f in fields} == {f: getattr(POINT, f) for f in fields}
    assert dataclasses.replace(RECOMMENDED, fs_hz=d.fs_hz) == d
    from flightmode.studies.certify import SEED000_POINT

    assert (
        SEED000_POINT
        == POINT.grid_point()
        == {
            "method": "nmv",
            "weight": 1.0,
            "window_s": 1.0,
            "k": 4.0,
            "time_threshold_s": 4.0,
        }
    )


def test_the_point_module_imports_nothing_of_flightmode():
    """A leaf: the detector's own parameters refer to it without an import cycle."""
    tree = ast.parse(inspect.getsource(recommended_point))
    names = [n.module or "" for n in ast.walk(tree) if isinstance(n, ast.ImportFrom)]
    names += [a.name for n in ast.walk(tree) if isinstance(n, ast.Import) for a in n.names]
    assert not [m for m in names if m.startswith("flightmode")]
