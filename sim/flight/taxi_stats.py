"""Taxi statistics: one measurement for real ADS-B tracks and simulated FlightTracks alike.

:func:`taxi_statistics` turns one taxi segment (times, positions, and optionally the reported ground
speed and heading) into figures: ground-speed and yaw-rate percentiles while moving, turns and turns
per taxi minute, duration, distance, and the largest braking and acceleration. It is applied
unchanged to real tracks (:func:`read_adsb_csv`, cut by :func:`adsb_taxi_segments`) and to our flights
(:func:`flight_taxi_statistics`), so the two can be compared figure by figure.

Method (every input goes through exactly these steps, whatever its sampling):

1. Positions to a local north/east plane at the first point (WGS-84, :mod:`..geodesy`).
2. Resampling to a uniform ``GRID_DT_S`` = 1 s grid by linear interpolation: ADS-B arrives every
   0.1-75 s, irregularly; a 120 Hz FlightTrack is point-sampled the same way. The reported heading is
   unwrapped first (``numpy.unwrap``, period 360 deg). Grid points inside an input gap longer than
   ``MAX_GAP_S`` are left out of the percentiles (the interpolation there is invented).
3. Smoothing and differentiation with one Savitzky-Golay filter (Savitzky and Golay, Anal. Chem.
   36 (1964) 1627; ``scipy.signal.savgol_filter``): a quadratic fitted over ``SMOOTH_WINDOW_S`` = 9 s,
   its value for the smoothed signal and its slope for the rate. The window is longer than the
   quantisation steps of ADS-B surface reports (speed 0.5-1 kt, heading 360/128 = 2.8 deg, DO-260B
   surface position message) spread over 1-7 s, and shorter than a 90 deg taxiway turn (10-20 s), so
   a constant-rate turn longer than the window keeps its rate exactly (the slope of a quadratic fitted
   to a ramp is the ramp's slope).
   Speed: the reported ground speed, or the magnitude of the Savitzky-Golay velocity of the
   positions. Heading: the reported heading, or the direction of that velocity (held while slower
   than ``MOVING_MPS``). Yaw rate is the heading rate; acceleration the speed's rate.
4. Figures while moving (smoothed speed > ``MOVING_MPS`` = 1 m/s): speed p50/p90/p99/max and |yaw
   rate| p50/p90/p99/max. Turns: a window of ``TURN_WINDOW_S`` = 20 s whose smoothed heading spans
   more than ``TURN_MIN_DEG`` = 30 deg marks the samples between its heading extremes as turning,
   less the first and last ``TURN_EDGE_DEG`` = 5 deg of that change; contiguous turning samples (over
   all windows) are one turn. Turns per minute divide by the segment's duration (holds included) and
   by its moving time. Braking and acceleration: the extremes of the speed's rate over the segment
   (holds included), in g (g0 from :mod:`flightmode.units`).

ADS-B reports the aircraft's own GNSS ground speed and, on the surface, a heading (in the readsb
track the reported angle keeps pointing at the nose while the tug pushes the aircraft backwards), so
simulated flights are measured with ``ground_speed_mps`` and the yaw angle psi
(:func:`flight_taxi_statistics`). ``ADSB_TAXI_ANCHORS`` holds the figures of the six complete taxi
segments of the two public tracks (tests/sim/test_taxi_stats.py recomputes them on every run):
a FlightRadar24 track of TK1745 (737-800, Istanbul-Oslo, 2024-09-17) and a readsb receiver's day of
N899DN (Delta 737-900, 2025-02-04/05, two arrivals and two departures at Minneapolis), both under the
traffic library's MIT licence (X. Olive).
"""

from __future__ import annotations

import csv
import functools
import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from flightmode.errors import InputDataError
from flightmode.intervals import true_runs_array
from flightmode.sim.flight.geodesy import geodetic_to_ned
from flightmode.units import G0_MPS2, KT_MPS

GRID_DT_S = 1.0  # uniform resampling step
SMOOTH_WINDOW_S = 9.0  # Savitzky-Golay window (quadratic)
SMOOTH_POLYORDER = 2
MOVING_MPS = 1.0  # "moving": smoothed ground speed above this
MAX_GAP_S = 30.0  # grid points inside a longer input gap are not counted in percentiles
TURN_WINDOW_S = 20.0  # a turn: more than TURN_MIN_DEG of heading change within this window
TURN_MIN_DEG = 30.0
TURN_EDGE_DEG = 5.0  # trimmed from each end of a window's change (above ADS-B's 2.8 deg heading step)

# ADS-B segmentation (:func:`adsb_taxi_segments`); speeds in knots as ADS-B reports them
ROLL_KT = 40.0  # surely the takeoff roll: faster than any taxi
ROLL_START_KT = 12.0  # the roll starts at the last sample at or below this before ROLL_KT
TAXI_KT = 5.0  # faster than a tug pushes: taxiing under own power
EXIT_KT = 20.0  # rollout over, taxi-in begins (the pilot's rollout -> taxi_in speed, sim.flight.pilot.phases)
STOP_KT = 1.0  # at rest
PARK_S = 60.0  # at rest (or unreported) this long after taxiing in: at the stand

ADSB_TAXI_FILE = "data/adsb_taxi.toml"  # package data beside this module (its sources in its header)


@functools.cache
def adsb_taxi_anchors() -> dict[str, dict[str, dict[str, float]]]:
    """The figures of the real taxi segments (:data:`ADSB_TAXI_FILE`), read once: source file stem ->
    segment -> figure (keys with units, as :func:`taxi_statistics` returns them). Recomputed from
    the tracks by tests/sim/test_taxi_stats.py (same code, same data: equal to float rounding). The
    cached dict is shared: do not change it."""
    import tomllib
    from importlib.resources import files

    return tomllib.loads(files(__package__).joinpath(ADSB_TAXI_FILE).read_text(encoding="utf-8"))


def __getattr__(name: str):
    """``ADSB_TAXI_ANCHORS``: :func:`adsb_taxi_anchors`, read at first use (PEP 562)."""
    if name == "ADSB_TAXI_ANCHORS":
        return adsb_taxi_anchors()
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


# ---------------------------------------------------------------------------------------------------
# the measurement


def _savgol(x: np.ndarray, deriv: int) -> np.ndarray:
    from scipy.signal import savgol_filter

    n = round(SMOOTH_WINDOW_S / GRID_DT_S) | 1  # odd
    return savgol_filter(x, n, SMOOTH_POLYORDER, deriv=deriv, delta=GRID_DT_S, mode="interp")


def _interp_finite(tg: np.ndarray, t: np.ndarray, x: np.ndarray, name: str) -> np.ndarray:
    ok = np.isfinite(x)
    if ok.sum() < 2:
        raise InputDataError(
            f"taxi_statistics: '{name}' has fewer than 2 finite values; "
            "pass None to derive it from the positions"
        )
    return np.interp(tg, t[ok], x[ok])


def _hold_forward(x: np.ndarray, ok: np.ndarray) -> np.ndarray:
    """x where ok, else the last ok value (the first ok value before any)."""
    if not ok.any():
        return np.zeros_like(x)
    idx = np.where(ok, np.arange(x.size), 0)
    np.maximum.accumulate(idx, out=idx)
    idx[: int(np.argmax(ok))] = int(np.argmax(ok))
    return x[idx]


def _turn_mask(heading_deg: np.ndarray) -> np.ndarray:
    """Samples inside turns. Every window of TURN_WINDOW_S whose heading spans more than TURN_MIN_DEG
    marks its samples between the heading's minimum and maximum, less the first and last
    TURN_EDGE_DEG of that change (so a straight's slow drift never joins two turns); the union over
    the windows is returned."""
    from numpy.lib.stride_tricks import sliding_window_view

    n = heading_deg.size
    mask = np.zeros(n, dtype=bool)
    w = min(round(TURN_WINDOW_S / GRID_DT_S) + 1, n)
    win = sliding_window_view(heading_deg, w)
    lo_i, hi_i = win.argmin(axis=1), win.argmax(axis=1)
    lo = np.take_along_axis(win, lo_i[:, None], 1)
    hi = np.take_along_axis(win, hi_i[:, None], 1)
    k = np.flatnonzero((hi - lo)[:, 0] > TURN_MIN_DEG)
    col = np.arange(w)
    inner = (
        (win[k] > lo[k] + TURN_EDGE_DEG)
        & (win[k] < hi[k] - TURN_EDGE_DEG)
        & (col >= np.minimum(lo_i[k], hi_i[k])[:, None])
        & (col <= np.maximum(lo_i[k], hi_i[k])[:, None])
    )
    rows, cols = np.nonzero(inner)
    mask[k[rows] + cols] = True
    return mask


def taxi_statistics(t_s, lat_deg, lon_deg, ground_speed_mps=None, track_deg=None) -> dict[str, float]:
    """Figures of one taxi segment (see the module docstring for the method).

    Parameters: ``t_s`` (N,) increasing times (s; repeated times keep their first sample);
    ``lat_deg``, ``lon_deg`` (N,) WGS-84; ``ground_speed_mps`` (N,) reported ground speed, or None to
    derive it from the positions; ``track_deg`` (N,) reported heading / track (deg true), or None to
    derive it from the positions. NaN entries of the optional arrays are skipped.

    Returns floats keyed with their units: ``duration_s``, ``moving_s``, ``distance_m``,
    ``speed_{p50,p90,p99,max}_mps``, ``speed_in_turns_p50_mps``, ``yaw_rate_{p50,p90,p99,max}_dps``
    (absolute), ``n_turns``, ``turns_per_min`` (per minute of the segment), ``turns_per_moving_min``,
    ``brake_max_g``, ``accel_max_g``, ``sample_interval_p50_s`` and ``sample_gap_max_s`` (the input's).
    """
    t = np.asarray(t_s, dtype=float)
    given = {
        "lat_deg": lat_deg,
        "lon_deg": lon_deg,
        "ground_speed_mps": ground_speed_mps,
        "track_deg": track_deg,
    }
    arrays = {k: np.asarray(v, dtype=float) for k, v in given.items() if v is not None}
    if t.ndim != 1 or any(a.shape != t.shape for a in arrays.values()):
        shapes = ", ".join(f"{k} {a.shape}" for k, a in arrays.items())
        raise InputDataError(f"taxi_statistics: t_s {t.shape} and {shapes} must be 1-D arrays of one length")
    if not all(np.isfinite(x).all() for x in (t, arrays["lat_deg"], arrays["lon_deg"])):
        raise InputDataError("taxi_statistics: t_s, lat_deg and lon_deg must be finite")
    dt_in = np.diff(t)
    if (dt_in < 0).any():
        i = int(np.argmax(dt_in < 0)) + 1
        raise InputDataError(f"taxi_statistics: t_s must increase (it falls at index {i})")
    keep = np.concatenate([[True], dt_in > 0])
    t = t[keep]
    arrays = {k: a[keep] for k, a in arrays.items()}
    if t.size < 2:
        raise InputDataError(f"taxi_statistics: {t.size} sample(s); a segment needs at least 2")
    if t[-1] - t[0] < SMOOTH_WINDOW_S:
        raise InputDataError(
            f"taxi_statistics: the segment spans {t[-1] - t[0]:.1f} s; at least "
            f"{SMOOTH_WINDOW_S:g} s (the smoothing window) is needed"
        )

    # 1-2. local plane, uniform grid, gap mask
    n_grid = math.floor((t[-1] - t[0]) / GRID_DT_S + 1e-9) + 1
    tg = t[0] + GRID_DT_S * np.arange(n_grid)
    ned = geodetic_to_ned(
        arrays["lat_deg"],
        arrays["lon_deg"],
        0.0,
        float(arrays["lat_deg"][0]),
        float(arrays["lon_deg"][0]),
        0.0,
    )
    north, east = np.interp(tg, t, ned[:, 0]), np.interp(tg, t, ned[:, 1])
    j = np.clip(np.searchsorted(t, tg, side="right") - 1, 0, t.size - 2)
    valid = (t[j + 1] - t[j]) <= MAX_GAP_S

    # 3. speed and heading signals, smoothed and differentiated alike
    vn, ve = _savgol(north, 1), _savgol(east, 1)
    if "ground_speed_mps" in arrays:
        speed_sig = _interp_finite(tg, t, arrays["ground_speed_mps"], "ground_speed_mps")
    else:
        speed_sig = np.hypot(vn, ve)
    if "track_deg" in arrays:
        trk = arrays["track_deg"]
        ok = np.isfinite(trk)
        unwrapped = np.full_like(trk, np.nan)
        unwrapped[ok] = np.unwrap(trk[ok], period=360.0)
        heading_sig = _interp_finite(tg, t, unwrapped, "track_deg")
    else:
        course = np.degrees(np.arctan2(ve, vn))
        course = _hold_forward(course, np.hypot(vn, ve) > MOVING_MPS)
        heading_sig = np.unwrap(course, period=360.0)
    speed = _savgol(speed_sig, 0)
    accel = _savgol(speed_sig, 1)
    heading = _savgol(heading_sig, 0)
    yaw_rate = np.abs(_savgol(heading_sig, 1))

    # 4. figures
    moving = (speed > MOVING_MPS) & valid
    turning = _turn_mask(heading)
    n_turns = int(true_runs_array(turning).shape[0])
    duration = float(t[-1] - t[0])
    moving_s = float(moving.mean() * duration)
    out: dict[str, float] = {
        "duration_s": duration,
        "moving_s": moving_s,
        "distance_m": float(np.trapezoid(np.clip(speed, 0.0, None), dx=GRID_DT_S)),
    }
    sp, yr = speed[moving], yaw_rate[moving]
    q = (50, 90, 99)
    for name, x in (("speed", sp), ("yaw_rate", yr)):
        unit = "mps" if name == "speed" else "dps"
        vals = np.percentile(x, q) if x.size else np.full(3, np.nan)
        for p, v in zip(q, vals):
            out[f"{name}_p{p}_{unit}"] = float(v)
        out[f"{name}_max_{unit}"] = float(x.max()) if x.size else math.nan
    in_turns = speed[moving & turning]
    out["speed_in_turns_p50_mps"] = float(np.median(in_turns)) if in_turns.size else math.nan
    out["n_turns"] = float(n_turns)
    out["turns_per_min"] = n_turns / (duration / 60.0)
    out["turns_per_moving_min"] = n_turns / (moving_s / 60.0) if moving_s > 0 else math.nan
    a = accel[valid]
    out["brake_max_g"] = float(max(0.0, -a.min()) / G0_MPS2)
    out["accel_max_g"] = float(max(0.0, a.max()) / G0_MPS2)
    dt_kept = np.diff(t)
    out["sample_interval_p50_s"] = float(np.median(dt_kept))
    out["sample_gap_max_s"] = float(dt_kept.max())
    return out


# ---------------------------------------------------------------------------------------------------
# real tracks


@dataclass(frozen=True, slots=True)
class AdsbTrack:
    """One ADS-B track: arrays (N,) in SI units, ``track_deg`` NaN where not reported."""

    source: str
    t_s: np.ndarray  # Unix time
    lat_deg: np.ndarray
    lon_deg: np.ndarray
    ground_speed_mps: np.ndarray
    track_deg: np.ndarray
    on_ground: np.ndarray


def _floats(rows: list[dict], key: str) -> np.ndarray:
    return np.array([float(r[key]) if r[key] not in ("", None) else np.nan for r in rows])


def read_adsb_csv(path) -> AdsbTrack:
    """A FlightRadar24 export (timestamp_unix, lat, lon, alt_ft, gs_kt, heading_deg; on the ground when
    alt_ft is 0) or a readsb trace (time_utc, lat, lon, alt_baro_ft ``ground`` on the surface, gs_kt,
    track_deg), as SI arrays."""
    path = Path(path)
    with path.open(newline="") as fh:
        rows = list(csv.DictReader(fh))
    if not rows:
        raise InputDataError(f"{path}: no rows")
    cols = set(rows[0])
    if {"timestamp_unix", "alt_ft", "heading_deg"} <= cols:  # FlightRadar24
        t = _floats(rows, "timestamp_unix")
        on_ground = _floats(rows, "alt_ft") == 0.0
        trk = _floats(rows, "heading_deg")
    elif {"time_utc", "alt_baro_ft", "track_deg"} <= cols:  # readsb
        stamps = [r["time_utc"].removesuffix("+00:00").removesuffix("Z") for r in rows]
        ns = np.array(stamps, dtype="datetime64[ns]").astype(np.int64)
        t = ns // 1_000_000_000 + (ns % 1_000_000_000) * 1e-9
        on_ground = np.array([r["alt_baro_ft"] == "ground" for r in rows])
        trk = _floats(rows, "track_deg")
    else:
        raise InputDataError(
            f"{path}: neither a FlightRadar24 nor a readsb CSV (columns: {', '.join(sorted(cols))})"
        )
    order = np.argsort(t, kind="stable")
    return AdsbTrack(
        source=path.stem,
        t_s=t[order],
        lat_deg=_floats(rows, "lat")[order],
        lon_deg=_floats(rows, "lon")[order],
        ground_speed_mps=_floats(rows, "gs_kt")[order] * KT_MPS,
        track_deg=trk[order],
        on_ground=on_ground[order],
    )


@dataclass(frozen=True, slots=True)
class TaxiSegment:
    kind: str  # "taxi_out" or "taxi_in"
    i0: int  # first sample
    i1: int  # last sample (inclusive)
    t0_s: float
    t1_s: float

    @property
    def slice(self) -> slice:
        return slice(self.i0, self.i1 + 1)


def adsb_taxi_segments(t_s, on_ground, ground_speed_mps) -> tuple[TaxiSegment, ...]:
    """The complete taxi-out and taxi-in segments of a track, in time order.

    Taxi-in (a ground run that follows airborne samples): from the first sample at or below
    ``EXIT_KT`` (the simulated pilot's end of rollout) to the first sample after which the aircraft is
    at rest (below ``STOP_KT``) or unreported for ``PARK_S``, or the end of the data: the stand.
    Taxi-out (a ground run followed by airborne samples): from the last at-rest sample (or the first
    sample after an unreported stretch of ``PARK_S``) before the first sample at ``TAXI_KT`` or faster
    (pushback is slower: it is left out, as the tug's disconnection is), to the last sample at or below
    ``ROLL_START_KT`` before the first at ``ROLL_KT`` (brake release of the takeoff roll).
    A run whose landing never slows to ``EXIT_KT`` or whose departure never reaches ``ROLL_KT`` in the
    data is incomplete and left out.
    """
    t = np.asarray(t_s, dtype=float)
    g = np.asarray(on_ground, dtype=bool)
    kt = np.asarray(ground_speed_mps, dtype=float) / KT_MPS
    n = t.size
    moving = ~(kt < STOP_KT)  # NaN speed counts as moving (not known to be at rest)
    t_ext = np.append(t, np.inf)
    idx_m = np.where(moving, np.arange(n), n)
    nxt = np.minimum.accumulate(idx_m[::-1])[::-1]
    nxt_after = np.append(nxt[1:], n)
    pause_len = np.where(moving, t_ext[np.arange(n) + 1] - t, t_ext[nxt_after] - t)
    parked = pause_len >= PARK_S
    segs: list[TaxiSegment] = []
    for a, b in true_runs_array(g):  # ground runs [a, b)
        region0 = a
        if a > 0:  # a landing
            slow = np.flatnonzero(kt[a:b] <= EXIT_KT)
            if slow.size:
                i0 = a + int(slow[0])
                stop = np.flatnonzero(parked[i0:b])
                i1 = i0 + int(stop[0]) if stop.size else b - 1
                segs.append(TaxiSegment("taxi_in", i0, i1, float(t[i0]), float(t[i1])))
                region0 = i1 + 1
        if b < n:  # a departure
            fast = np.flatnonzero(kt[region0:b] > ROLL_KT)
            taxi = np.flatnonzero(kt[region0:b] >= TAXI_KT)
            if fast.size and taxi.size:
                i_roll = region0 + int(fast[0])
                i_taxi = region0 + int(taxi[0])
                slow = np.flatnonzero(kt[i_taxi:i_roll] <= ROLL_START_KT)
                i1 = i_taxi + int(slow[-1]) if slow.size else i_taxi
                r = np.arange(region0, i_taxi + 1)
                rest = r[~moving[r]]
                after_gap = r[1:][np.diff(t[r]) >= PARK_S]
                i0 = int(max(rest.max(initial=region0), after_gap.max(initial=region0)))
                segs.append(TaxiSegment("taxi_out", i0, i1, float(t[i0]), float(t[i1])))
    return tuple(segs)


def adsb_taxi_statistics(path) -> dict[str, dict[str, float]]:
    """Figures of every complete taxi segment of an ADS-B CSV, keyed ``<kind>_<HHMM>Z`` (segment start,
    UTC), each with ``t_start_unix_s`` and ``t_end_unix_s`` besides :func:`taxi_statistics`'s."""
    tr = read_adsb_csv(path)
    out: dict[str, dict[str, float]] = {}
    for seg in adsb_taxi_segments(tr.t_s, tr.on_ground, tr.ground_speed_mps):
        s = seg.slice
        hhmm = np.datetime64(int(seg.t0_s), "s").astype(object).strftime("%H%M")
        figs = {"t_start_unix_s": seg.t0_s, "t_end_unix_s": seg.t1_s}
        figs.update(
            taxi_statistics(tr.t_s[s], tr.lat_deg[s], tr.lon_deg[s], tr.ground_speed_mps[s], tr.track_deg[s])
        )
        out[f"{seg.kind}_{hhmm}Z"] = figs
    return out


# ---------------------------------------------------------------------------------------------------
# simulated flights


def flight_taxi_segments(track) -> dict[str, slice]:
    """The taxi segments of a FlightTrack by its phase labels: ``taxi_out`` from the tug's
    disconnection (end of pushback) to the start of the takeoff roll, ``taxi_in`` from the end of the
    rollout to the stand. A flight cut short has only the segments it reached; none is an error."""
    from flightmode.labels import PHASE_CODE

    out: dict[str, slice] = {}
    for name in ("taxi_out", "taxi_in"):
        idx = np.flatnonzero(track.phase_code == PHASE_CODE[name])
        if idx.size:
            out[name] = slice(int(idx[0]), int(idx[-1]) + 1)
    if not out:
        raise InputDataError(
            "the track has no taxi_out or taxi_in phase: taxi figures need a flight flown "
            "from the gate (flightmode.run or `flightmode fly`)"
        )
    return out


def flight_taxi_statistics(track) -> dict[str, dict[str, float]]:
    """:func:`taxi_statistics` of each taxi segment of a FlightTrack, fed as ADS-B is: the ground speed
    and the heading (yaw angle psi), point-sampled on the same 1 s grid."""
    out: dict[str, dict[str, float]] = {}
    for name, s in flight_taxi_segments(track).items():
        out[name] = taxi_statistics(
            track.t_s[s],
            track.lat_deg[s],
            track.lon_deg[s],
            ground_speed_mps=track.ground_speed_mps[s],
            track_deg=np.degrees(track.euler_rad[s, 2]),
        )
    return out
