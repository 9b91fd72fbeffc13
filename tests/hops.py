"""The dataset tests' family: the shortest hop, both ways (the session's reference dataset of it is the
``reference`` fixture, tests/conftest.py)."""

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
