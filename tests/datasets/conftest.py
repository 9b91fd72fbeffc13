"""The dataset tests' shared family and reference dataset: one session fixture, so that test_dataset and
test_faults (one xdist group, one worker) make the uninterrupted reference once between them."""

from __future__ import annotations

from pathlib import Path

import pytest

# the shortest hop (Birmingham - Manchester, 106 km: 45 min gate to gate, about 10 s of wall time)
HOPS = """
[family]
name = "hops"
description = "the shortest hop, both ways"
seed = 5

[aircraft]
A320 = 1

[routes]
pairs = [["EGBB", "EGCC"], ["EGCC", "EGBB"]]

[turbulence]
patch_probability = 0.0
"""
N = 2


@pytest.fixture(scope="session")
def family_file(tmp_path_factory) -> Path:
    p = tmp_path_factory.mktemp("family") / "hops.toml"
    p.write_text(HOPS)
    return p


@pytest.fixture(scope="session")
def reference(tmp_path_factory, family_file) -> Path:
    """The uninterrupted dataset, made through the API on a LocalCluster of two worker processes (tests
    only read it)."""
    from flightmode.datasets.make import make_dataset

    out = tmp_path_factory.mktemp("ref") / "ds"
    rows = make_dataset(str(family_file), N, out, workers=2)
    assert sorted(rows) == list(range(N)) and all(r["status"] == "ok" for r in rows.values())
    return out
