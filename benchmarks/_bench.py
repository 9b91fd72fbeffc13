"""Shared by the benchmark scripts (run as ``python benchmarks/bench_*.py``, so this directory is on
``sys.path``): best-of-N wall time and one way of printing the figures."""

from __future__ import annotations

import time


def timed(f):
    """(f's result, its wall time in seconds)."""
    t0 = time.perf_counter()
    out = f()
    return out, time.perf_counter() - t0


def best(f, repeat: int = 3) -> float:
    """The least wall time of ``repeat`` calls (the machine's noise only ever adds time)."""
    return min(timed(f)[1] for _ in range(repeat))


def report(res: dict) -> None:
    width = max(len(k) for k in res)
    for k, v in res.items():
        print(f"{k:>{width}}: {v:,.4g}" if isinstance(v, float) else f"{k:>{width}}: {v}")
