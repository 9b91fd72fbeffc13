"""Benchmark: seed 001's memory-based detectors (MBGTD eq. 9-10, MBCD eq. 12-14), vectorised against
the equations written as a double Python loop over the splits, same run, same input.

    python benchmarks/bench_memory_detectors.py [SECONDS] [WINDOW ...]

The input is |a| of a 100 Hz accelerometer stream (default 60 s = 6,000 samples: half still with 5 mg
of noise, half a 2 Hz 0.5 g oscillation), every window of ``WINDOW`` samples (default 10 and 20;
the seed's best MBGTD/MBCD windows are 6-13 samples at 50 Hz). Timed, best of 3:

- vectorised: ``mbgtd_merits`` / ``mbcd_merits`` over all windows (what the batch detectors run).
- naive: for each window, the distance (or kernel) matrix once, then a Python double loop over the
  splits 1 <= i < j <= N, each C_ij (eq. 9) or S_ij (eq. 13) a NumPy sum over slices. Timed on the
  first ``NAIVE_WINDOWS`` windows and scaled per window (its cost does not depend on the data).

Reports the ratio naive / vectorised (goal >= 20x) and the cost per sample; checks on the timed
windows that both give the same merits (1e-9 relative).
"""

from __future__ import annotations

import sys

import numpy as np
from _bench import best, report

NAIVE_WINDOWS = 300
BANDWIDTH_G = 0.02  # MBCD's kernel width: 4 noise sigmas


def _naive_mbgtd(x: np.ndarray, n: int) -> np.ndarray:
    out = np.empty(x.shape[0] - n + 1)
    for m in range(out.shape[0]):
        w = x[m : m + n]
        d = np.abs(w[:, None] - w[None, :])
        best_c = -np.inf
        for i in range(n):
            for j in range(i + 1, n):
                best_c = max(best_c, d[i:j, j:].sum() / ((j - i) * (n - j)))  # eq. (9)
        out[m] = best_c  # eq. (10)
    return out


def _naive_mbcd(x: np.ndarray, n: int, lam: float) -> np.ndarray:
    out = np.empty(x.shape[0] - n + 1)
    for m in range(out.shape[0]):
        w = x[m : m + n]
        k = np.exp(-0.5 * ((w[:, None] - w[None, :]) / lam) ** 2)  # eq. (12)
        best_s = -np.inf
        for i in range(n):
            for j in range(i + 1, n):
                s = np.sum(np.log(k[j:, j:].mean(axis=1) / k[j:, i:j].mean(axis=1)))  # eq. (13)
                best_s = max(best_s, s)
        out[m] = best_s  # eq. (14)
    return out


def main(seconds: float = 60.0, windows: tuple[int, ...] = (10, 20)) -> dict:
    from flightmode.detector.activity.memory import mbcd_merits, mbgtd_merits

    fs = 100.0
    n_samples = int(seconds * fs)
    rng = np.random.default_rng(0)
    t = np.arange(n_samples) / fs
    still = np.array([0.1, -0.2, 0.97]) / np.linalg.norm([0.1, -0.2, 0.97])
    acc = still + rng.normal(0, 0.005, (n_samples, 3))
    moving = t >= seconds / 2
    acc[moving, 2] += 0.5 * np.sin(2 * np.pi * 2.0 * t[moving])
    x = np.sqrt((acc * acc).sum(axis=1))

    res: dict = {"samples": n_samples}
    ratios = []
    for n in windows:
        n_win = n_samples - n + 1
        sub = x[: NAIVE_WINDOWS + n - 1]
        for name, fast, naive in (
            ("MBGTD", lambda y, n=n: mbgtd_merits(y, n), lambda y, n=n: _naive_mbgtd(y, n)),
            (
                "MBCD",
                lambda y, n=n: mbcd_merits(y, n, BANDWIDTH_G),
                lambda y, n=n: _naive_mbcd(y, n, BANDWIDTH_G),
            ),
        ):
            np.testing.assert_allclose(fast(sub), naive(sub), rtol=1e-9, atol=1e-12)
            t_fast = best(lambda f=fast: f(x))
            t_naive = best(lambda f=naive, y=sub: f(y), 1) * n_win / NAIVE_WINDOWS
            ratio = t_naive / t_fast
            ratios.append(ratio)
            res[f"{name} N={n} vectorised s"] = t_fast
            res[f"{name} N={n} naive s (scaled)"] = t_naive
            res[f"{name} N={n} naive / vectorised (goal >= 20)"] = ratio
            res[f"{name} N={n} vectorised us per sample"] = t_fast / n_samples * 1e6
            res[f"{name} N={n} naive us per sample"] = t_naive / n_samples * 1e6
    report(res)
    print(f"goal: vectorised >= 20x the naive loops -> {'met' if min(ratios) >= 20 else 'NOT met'}")
    return res


if __name__ == "__main__":
    args = [float(a) for a in sys.argv[1:2]]
    if sys.argv[2:]:
        args.append(tuple(int(a) for a in sys.argv[2:]))
    main(*args)
