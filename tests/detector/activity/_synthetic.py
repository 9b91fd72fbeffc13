"""Synthetic accelerometer + gyroscope streams for the seed 001 detector tests, and one sensible
parameter set per detector for them. Every stream comes from a seeded numpy Generator."""

from __future__ import annotations

import numpy as np

FS_HZ = 100.0
SIGMA_ACC_G = 0.005  # accelerometer white noise per axis (a few mg, a MEMS part)
SIGMA_GYR_DPS = 0.2  # gyroscope white noise per axis
GRAVITY_DIR = np.array([0.1, -0.2, 0.97]) / np.linalg.norm([0.1, -0.2, 0.97])  # a tilted, still sensor
# the activity: a 2 Hz, 0.5 g oscillation (mostly along gravity, so |a| swings 0.5-1.5 g) and a
# 2 Hz, 40 deg/s rotation
ACT_ACC_DIR = np.array([0.3, 0.0, 0.954])
ACT_GYR_DIR = np.array([1.0, 0.3, 0.0])


def stream(segments: list[tuple[float, bool]], rng: np.random.Generator):
    """(t_s, acc_g, gyr_dps, truth) for consecutive (seconds, active) segments at FS_HZ."""
    n_seg = [round(s * FS_HZ) for s, _ in segments]
    n = sum(n_seg)
    t = np.arange(n) / FS_HZ
    acc = GRAVITY_DIR + rng.normal(0.0, SIGMA_ACC_G, (n, 3))
    gyr = rng.normal(0.0, SIGMA_GYR_DPS, (n, 3))
    truth = np.zeros(n, np.int8)
    i = 0
    for k, (_, active) in zip(n_seg, segments):
        if active:
            tb = t[i : i + k]
            acc[i : i + k] += 0.5 * np.sin(2 * np.pi * 2.0 * tb)[:, None] * ACT_ACC_DIR
            gyr[i : i + k] += 40.0 * np.sin(2 * np.pi * 2.0 * tb + 0.5)[:, None] * ACT_GYR_DIR
            truth[i : i + k] = 1
        i += k
    return t, acc, gyr, truth


def cases():
    """(detector name, signal or None) for every detector and every signal it allows."""
    from flightmode.detector.activity import registry

    return [(d.name, s) for d in registry.all_detectors() for s in (d.signals or (None,))]


# Parameters for the synthetic streams above (noise 5 mg and 0.2 deg/s at rest; 0.5 g and 40 deg/s
# in motion). Each threshold sits between the rest level and the motion level of the merit by a
# large factor either way (the rest levels in the comments are for these noise levels).
_FLEX = {"acc": 0, "gyr": 1, "sum": 1, "product": 1}  # acc alone is in g, the others ~deg/s


def params(name: str, signal: str | None) -> dict:
    s = _FLEX[signal] if signal else 0
    p = {
        # rest: 3 sigma^2 = 7.5e-5 g^2; motion: ~0.05 g^2
        "amvd": {"window": 20, "threshold": 1e-3},
        # rest ~1 (noise variances); motion ~4,500
        "amd": {"window": 20, "threshold": 10.0, "sigma_acc_g": SIGMA_ACC_G},
        # rest ~3; motion ~2e4
        "ared": {"window": 20, "threshold": 30.0, "sigma_gyr_dps": SIGMA_GYR_DPS},
        # rest ~6; motion ~2.6e4
        "shod": {"window": 20, "threshold": 50.0, "sigma_acc_g": SIGMA_ACC_G, "sigma_gyr_dps": SIGMA_GYR_DPS},
        # rest 0.004 g / 0.11 deg/s; motion 0.3 g / 11 deg/s
        "frd": {"threshold": (0.05, 2.0)[s]},
        # 0.32 s frames (the seed's best FSD/LTSD frames are 15-20 samples at 50 Hz): rest <= 7 dB,
        # motion >= 25 dB. (16-sample frames, a third of the 2 Hz period, see the frames at the
        # peaks of |a| as a higher constant: FSD-acc falls to 10 dB there.)
        "ltsd": {"window": 32, "shift": 8, "threshold": 12.0},
        # rest <= 4 dB; motion >= 19 dB
        "fsd": {"window": 32, "shift": 8, "threshold": 10.0},
        # rest 0.011 g / 0.29 deg/s; motion 0.29 g / 20 deg/s
        "mbgtd": {"window": 12, "threshold": (0.03, 2.0)[s]},
        # kernel width 4 noise sigmas: rest median 0.6, motion ~1e3-1e4
        "mbcd": {"window": 12, "threshold": 5.0, "bandwidth": (0.02, 0.8)[s]},
    }[name]
    if signal:
        p["signal"] = signal
    return p
