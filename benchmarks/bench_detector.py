"""Benchmark: the flight-mode detector's moving variance and decisions (issue goals in the output).

    python benchmarks/bench_detector.py [HOURS]

All timed in the same run on the same (n, 3) array of 100 Hz samples (default 2 h = 720,000 rows):

- batch ``detect`` (NMV, W_s 1 s, every sample's MV with periodic re-anchoring, decisions every
  second) against a naive reference that calls ``np.var`` on every 100-sample window ending at each
  sample (what a direct transcription of eq. 1 does). Goal: >= 20x faster.
- the physical floor: one ``np.sum`` pass over the same array (reported as a ratio).
- streaming: 1-sample chunks (firmware style; timed on the first 20 s and scaled per sample)
  against 1000-sample chunks (the whole array).
"""

from __future__ import annotations

import sys

import numpy as np
from _bench import best, report


def main(hours: float = 2.0) -> dict:
    from flightmode.detector.flight_mode import DetectorParams, FlightModeDetector, detect

    p = DetectorParams()
    n = int(hours * 3600 * p.fs_hz)
    rng = np.random.default_rng(0)
    t = np.arange(n) / p.fs_hz
    a = rng.normal(0.0, 2.23e-3, (n, 3)) + np.array([0.0, 0.0, -1.0])
    s2 = np.full(3, 2.23e-3**2)
    w = p.window

    t_batch = best(lambda: detect(t, a, p, s2))
    # naive: np.var of every window (each sample's MV), timed on the first 600 s and scaled per sample
    m = min(n, 60_000)

    def naive():
        out = np.empty((m - w + 1, 3))
        for i in range(w - 1, m):
            out[i - w + 1] = np.var(a[i - w + 1 : i + 1], axis=0)
        return out

    t_naive = best(naive, 1) * (n - w + 1) / (m - w + 1)
    t_sum = best(lambda: np.sum(a, axis=0))
    # streaming with 1-sample chunks (scaled from 20 s of data) and 1000-sample chunks (the whole array)
    m1 = 2000

    def stream(chunk, rows):
        det = FlightModeDetector(p, s2)
        for i in range(0, rows, chunk):
            det.push(t[i : i + chunk], a[i : i + chunk])

    t_s1 = best(lambda: stream(1, m1), 1) * n / m1
    t_s1000 = best(lambda: stream(1000, n), 1)
    res = {
        "samples": n,
        "batch_s": t_batch,
        "batch_msamples_per_s": n / t_batch / 1e6,
        "naive_np_var_s (scaled)": t_naive,
        "speedup_vs_naive": t_naive / t_batch,
        "np_sum_floor_s": t_sum,
        "batch_over_np_sum": t_batch / t_sum,
        "stream_1_sample_chunks_s (scaled)": t_s1,
        "stream_1000_sample_chunks_s": t_s1000,
        "stream_1_over_1000": t_s1 / t_s1000,
        "stream_1000_over_batch": t_s1000 / t_batch,
    }
    report(res)
    print(
        f"goal: batch >= 20x the naive reference -> {'met' if res['speedup_vs_naive'] >= 20 else 'NOT met'}"
    )
    return res


if __name__ == "__main__":
    main(*(float(x) for x in sys.argv[1:2]))
