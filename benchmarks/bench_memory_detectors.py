"""Benchmark: seed 001's memory-based detectors (MBGTD eq. 9-10, MBCD eq. 12-14) on a flight, and
every detection method's time on it as a ratio to the time of flying it (issue goal: <= 0.5).

    python benchmarks/bench_memory_detectors.py [SCENARIO] [--naive]

Flight (default ``gva-lhr-a320``: 92 min gate to gate, a 142-min recording of 854,350 samples at
100 Hz with the terminal before and after, about two hours): flown in JSBSim as ``flightmode.run``
flies it (timed: the baseline), then sensed with a gyroscope (BMI270) and written to a temporary run
folder (with a BMP581 barometer for the +baro rules), read back as ``flightmode detect`` reads it. Timed in the same run, once each:

- every method of ``flightmode detect --method`` (:mod:`flightmode.detector.methods`): the whole
  detection as the CLI runs it (rest figures from the bench recording, the detector over the stream,
  the checks and the score), as a ratio to the fly time. MBGTD and MBCD run at the study's windows
  (seed 001 Tables 10-11, 0.26 s and 0.25 s: 26 and 25 samples at 100 Hz).
- the memory kernels alone (``mbgtd_merits`` / ``mbcd_merits`` on the flight's |a|, the kernel width
  from the bench as the CLI takes it), per sample.

``--naive``: also the kernels against the equations written as a double Python loop over the splits
(60 s of synthetic |a|, windows 10 and 20; goal >= 20x), checking both give the same merits.
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


def naive_comparison(seconds: float = 60.0, windows: tuple[int, ...] = (10, 20)) -> dict:
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


def flight(scenario: str = "gva-lhr-a320") -> dict:
    """Every method's time on the scenario's flight, and its ratio to the time of flying it."""
    import tempfile
    from pathlib import Path

    from _bench import fly_scenario, timed

    from flightmode.detector import methods
    from flightmode.detector.activity.flight import STUDY_WINDOW_S, ActivityParams, rest_figures
    from flightmode.detector.activity.memory import mbcd_merits, mbgtd_merits
    from flightmode.runs import pipeline
    from flightmode.runs.detect import detect_stream
    from flightmode.runs.run_io import read_samples

    sc, track, t_fly = fly_scenario(scenario)
    res: dict = {"scenario": scenario, "fly s (the baseline)": t_fly}
    with tempfile.TemporaryDirectory() as tmp:
        # a gyroscope (ared, shod, the flexible inputs) and a barometer (the +baro rules): every method runs
        sc = sc.replace(sensor={"baro": "bmp581"})
        pipeline.run(sc, out=tmp, stages=("fly", "sense", "write"), gyro=True, rrd=False, track=track)
        run_dir = Path(tmp) / sc.run_id
        cols, info = read_samples(run_dir)
        fs = float(info["sensor"]["odr_hz"])
        n = cols["t_s"].shape[0]
        res["samples"] = n
        res["recording min"] = n / fs / 60.0
        worst = 0.0
        for name in methods.names():
            _, t = timed(lambda name=name: detect_stream(cols, info, run_dir, name))
            worst = max(worst, t / t_fly)
            res[f"{name} s"] = t
            res[f"{name} / fly (goal <= 0.5)"] = t / t_fly
        # the memory kernels alone, at the windows and kernel width the CLI uses
        bench, _, _ = pipeline.stream_rest("preset", cols, info)
        x = np.sqrt((cols["acc_g"] ** 2).sum(axis=1))
        p = ActivityParams("mbcd", fs_hz=fs)
        lam = rest_figures(p, bench)["bandwidth"]
        n_gtd = ActivityParams("mbgtd", fs_hz=fs).detector_window
        for label, f in (
            (f"MBGTD kernel N={n_gtd}", lambda: mbgtd_merits(x, n_gtd)),
            (f"MBCD kernel N={p.detector_window}", lambda: mbcd_merits(x, p.detector_window, lam)),
        ):
            _, t = timed(f)
            res[f"{label} s"] = t
            res[f"{label} us per sample"] = t / n * 1e6
        gtd_s, cd_s = STUDY_WINDOW_S["mbgtd"]["acc"], STUDY_WINDOW_S["mbcd"]["acc"]
        res["study windows (|a|): MBGTD, MBCD s"] = f"{gtd_s:.4g}, {cd_s:.4g}"
    report(res)
    print(
        f"goal: every method <= 0.5 x the fly time -> {'met' if worst <= 0.5 else 'NOT met'} (worst {worst:.3g})"
    )
    return res


if __name__ == "__main__":
    args = [a for a in sys.argv[1:] if not a.startswith("--")]
    flight(*args[:1])
    if "--naive" in sys.argv:
        naive_comparison()
