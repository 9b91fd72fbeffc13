"""Shared by the benchmark scripts (run as ``python benchmarks/bench_*.py``, so this directory is on
``sys.path``): best-of-N wall time and one way of printing the figures."""

from __future__ import annotations

import time


def timed(f):
    """(f's result, its wall time in seconds)."""
    t0 = time.perf_counter()
    out = f()
    return out, time.perf_counter() - t0


def best_timed(f, repeat: int = 3):
    """(f's last result, the least wall time of ``repeat`` calls): the machine's noise, and the
    first touch of fresh process memory, only ever add time."""
    out, t_min = None, float("inf")
    for _ in range(repeat):
        out, t = timed(f)
        t_min = min(t_min, t)
    return out, t_min


def best(f, repeat: int = 3) -> float:
    """The least wall time of ``repeat`` calls."""
    return best_timed(f, repeat)[1]


def report(res: dict) -> None:
    width = max(len(k) for k in res)
    for k, v in res.items():
        print(f"{k:>{width}}: {v:,.4g}" if isinstance(v, float) else f"{k:>{width}}: {v}")
