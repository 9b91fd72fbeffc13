"""How far acceleration alone rebuilds the bag's path: estimates against the FlightTrack truth.

The evaluation span is the time the bag sits on board and is not carried: from the first stowed
sample (plus the settling time after the put-down) to the last one inside the FlightTrack (the bag
is still stowed when the engines stop). Its truth is the bag's seat position, the CG plus the
placement's lever arm (``AircraftProfile.locations_m``) rotated by the attitude; a bag handled in
cruise moves a few centimetres about that point, which counts as error.

Rows (:func:`evaluate`), each with the maximum, RMS and final 3D position error:

- ``truth`` acceleration, integrating samples (``nav.frames.TruthPath.acceleration``), by the
  tridiagonal method with the two gate positions and by the recurrence from the gate at rest;
  and the tridiagonal with *point* samples (what aliasing of the FDM's ground impulses costs);
- per sensor preset: the truth-aided frames, by the tridiagonal method, the recurrence, and the
  recurrence with zero-velocity updates at the detector's final-static periods (ZUPT);
- per sensor preset, tilt-only: the vertical channel only (an accelerometer cannot see heading),
  by the recurrence with ZUPT, against the truth's vertical position.
"""

from __future__ import annotations

import itertools
import math

import numpy as np

from flightmode.intervals import change_points
from flightmode.nav import frames
from flightmode.nav.spline_path import NavError, RecurrencePath, recurrence_path, tridiagonal_path


def errors(t_s, est, truth) -> dict:
    e = np.linalg.norm(np.atleast_2d(np.asarray(est) - np.asarray(truth)).reshape(len(t_s), -1), axis=1)
    return {
        "max_m": float(e.max()),
        "rms_m": float(np.sqrt(np.mean(e * e))),
        "final_m": float(e[-1]),
        "t_max_s": float(np.asarray(t_s)[int(np.argmax(e))]),
    }


def zupt_path(t_s, acc, pos0, static_mask) -> np.ndarray:
    """Positions at the samples by the seed's recurrence with zero-velocity updates: at rest (a
    static period) the velocity is reset to zero and the bag's kinematic acceleration is zero, so
    the position holds; between rests the recurrence runs on the measured acceleration. One push
    per run of samples (O(n), Python work per run, not per sample)."""
    t = np.asarray(t_s, float)
    a = np.asarray(acc, float)
    st = np.asarray(static_mask, bool)
    r = RecurrencePath(pos0, np.zeros_like(np.asarray(pos0, float)))
    edges = change_points(st)
    bounds = [0, *edges.tolist(), t.shape[0]]
    for s, e in itertools.pairwise(bounds):
        if st[s]:
            if s > 0:
                r.restart(0.0)
            r.push(t[s:e], np.zeros_like(a[s:e]))
            r.restart(0.0)
        else:
            r.push(t[s:e], a[s:e])
    return r.position


def span(rec, track, settle_s: float = 3.0) -> tuple[float, float]:
    stowed = [s for s in rec.segments if s.on_board and s.state in ("stowed", "in_hold")]
    if not stowed:
        raise NavError("the bag is never stowed on board in this recording: no path to estimate")
    t0 = max(stowed[0].t0_s + settle_s, track.t_s[0])
    t1 = min(stowed[-1].t1_s, track.t_s[-1])
    if t1 - t0 < 10.0:
        raise NavError("less than 10 s of the bag on board inside the FlightTrack")
    return t0, t1


def estimate_paths(track, rec, lever_arm_body_m, truth: frames.TruthPath | None = None) -> dict:
    """The truth-aided estimates of one recording over the evaluation span: times, the truth, the
    tridiagonal path with the gate positions and the recurrence from the gate at rest (world frame,
    m, at every sample)."""
    t0, t1 = span(rec, track)
    s = (rec.t_s >= t0) & (rec.t_s <= t1)
    tt = rec.t_s[s]
    truth = truth or frames.TruthPath(track, lever_arm_body_m)
    pos = truth.position(tt)
    a = frames.truth_aided_acceleration(rec, track, tt, rec.acc_g[s], truth)
    return {
        "t_s": tt,
        "truth": pos,
        "acc": a,
        "mask": s,
        "tridiagonal": tridiagonal_path(tt, a, pos[0], pos[-1])(tt),
        "recurrence": recurrence_path(tt, a, pos[0], np.zeros(3))(tt),
    }


def evaluate(track, recordings: dict, lever_arm_body_m, checks_of=None) -> list[dict]:
    """Rows of the module docstring. ``recordings``: {label: Recording}; ``checks_of(rec)`` returns
    the detector's Checks for a recording (for ZUPT and tilt-only); None skips those rows."""
    rows = []
    first = next(iter(recordings.values()))
    t0, t1 = span(first, track)
    sel = (first.t_s >= t0) & (first.t_s <= t1)
    t = first.t_s[sel]
    bag = frames.TruthPath(track, lever_arm_body_m)  # one interpolant for every row
    truth = bag.position(t)
    a_int = bag.acceleration(t, integrating=True)
    a_pt = bag.acceleration(t, integrating=False)
    v0 = np.zeros(3)  # the aircraft stands at the gate when the bag is stowed
    rows.append(
        {
            "source": "truth acceleration",
            "method": "tridiagonal (gate positions)",
            **errors(t, tridiagonal_path(t, a_int, truth[0], truth[-1])(t), truth),
        }
    )
    rows.append(
        {
            "source": "truth acceleration",
            "method": "recurrence (gate, at rest)",
            **errors(t, recurrence_path(t, a_int, truth[0], v0)(t), truth),
        }
    )
    rows.append(
        {
            "source": "truth acceleration, point samples",
            "method": "tridiagonal (gate positions)",
            **errors(t, tridiagonal_path(t, a_pt, truth[0], truth[-1])(t), truth),
        }
    )
    for label, rec in recordings.items():
        est = estimate_paths(track, rec, lever_arm_body_m, bag)
        s, tt, tr_pos, a = est["mask"], est["t_s"], est["truth"], est["acc"]
        rows += path_rows(est, label)
        if checks_of is None:
            continue
        c, window = checks_of(rec)
        static = frames.static_periods(c, window, rec.n)
        rows.append(
            {
                "source": f"{label}, truth-aided",
                "method": "recurrence + ZUPT (detector statics)",
                **errors(tt, zupt_path(tt, a, tr_pos[0], static[s]), tr_pos),
            }
        )
        try:
            vert, _ = frames.tilt_only_acceleration(rec.acc_g, static)
        except NavError:
            continue
        v = vert[s]
        if np.isnan(v).any():
            continue
        z = zupt_path(tt, v[:, None], tr_pos[:1, 2], static[s])[:, 0]
        rows.append(
            {
                "source": f"{label}, tilt-only (vertical only)",
                "method": "recurrence + ZUPT",
                **errors(tt, z[:, None], tr_pos[:, 2:3]),
            }
        )
    return rows


def path_rows(est: dict, label: str) -> list[dict]:
    return [
        {
            "source": f"{label}, truth-aided",
            "method": "tridiagonal (gate positions)",
            **errors(est["t_s"], est["tridiagonal"], est["truth"]),
        },
        {
            "source": f"{label}, truth-aided",
            "method": "recurrence (gate, at rest)",
            **errors(est["t_s"], est["recurrence"], est["truth"]),
        },
    ]


def random_walk_exponent(
    noise_mps2: float, fs_hz: float, duration_s: float, runs: int, rng: np.random.Generator
) -> tuple[float, np.ndarray, np.ndarray]:
    """Fit ``rms position error ~ t^p`` for white acceleration noise integrated by the recurrence
    from the true initial state (Monte Carlo over ``runs`` realisations): the random-walk law
    predicts p = 1.5 (sigma_x(t) = sigma_a sqrt(dt) t^1.5 / sqrt(3)). Returns (p, t, rms)."""
    n = int(duration_s * fs_hz)
    t = np.arange(n) / fs_hz
    a = rng.normal(0.0, noise_mps2, (n, runs))
    x = recurrence_path(t, a, np.zeros(runs), np.zeros(runs))(t)
    rms = np.sqrt(np.mean(x * x, axis=1))
    k = np.unique(np.geomspace(fs_hz, n - 1, 30).astype(int))  # from 1 s: past the first samples
    p = float(np.polyfit(np.log(t[k]), np.log(rms[k]), 1)[0])
    return p, t[k], rms[k]


def predicted_random_walk_m(noise_mps2: float, fs_hz: float, t_s) -> np.ndarray:
    return noise_mps2 * math.sqrt(1.0 / fs_hz) * np.asarray(t_s) ** 1.5 / math.sqrt(3.0)
