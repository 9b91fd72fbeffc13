"""A simulated flight as an e-obs tag records it: its bursts (seed 003 sections 4 and 9), as a
Movebank file (section 5.4), and the duty-cycled detector (:mod:`flightmode.eobs.duty_cycle`) on
them against the flight's truth labels, for the battery trade-off on flights.

A Recording made with an ``eobs`` preset (:func:`flightmode.sim.sensor.accelerometer.eobs_preset`)
holds only the burst samples: ``burst_samples`` per axis every ``burst_interval_s``. Its raw counts are
the tag's 0-4095 ADC counts (offset binary, zero-g about 2048), so the bursts are the tag's own data.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from flightmode.errors import SensorError

EPOCH = np.datetime64("2026-01-01T00:00:00", "ns")  # the simulated tag's clock at the track's t = 0


def burst_slices(t_s: np.ndarray, odr_hz: float) -> list[slice]:
    """The bursts of a burst recording: runs of samples one ODR period apart."""
    t = np.asarray(t_s, float)
    if t.size == 0:
        return []
    gap = np.flatnonzero(np.diff(t) > 1.5 / odr_hz) + 1
    edges = np.concatenate([[0], gap, [t.size]])
    return [slice(int(a), int(b)) for a, b in zip(edges[:-1], edges[1:])]


def recording_bursts(rec, tag_id: str = "9999", epoch: np.datetime64 = EPOCH) -> list:
    """The recording's bursts as :class:`~flightmode.eobs.burst.AccBurst` (all three axes), times from
    ``epoch`` (the tag's clock at the track's t = 0, to the nanosecond)."""
    from flightmode.eobs.burst import AccBurst

    if not rec.preset.startswith("eobs"):
        raise SensorError(
            f"recording of a {rec.preset!r} sensor: e-obs bursts need the eobs preset (eobs_preset)"
        )
    out = []
    for s in burst_slices(rec.t_s, rec.odr_hz):
        start = epoch + np.timedelta64(int(round(float(rec.t_s[s.start]) * 1e9)), "ns")
        out.append(
            AccBurst(tag_id, start, "XYZ", float(rec.odr_hz), np.asarray(rec.counts[s], np.int64), checksum=0)
        )
    return out


@dataclass(frozen=True)
class DutyCycleOnFlight:
    burst_interval_s: float
    burst_samples: int
    m: int
    k: float
    bursts: int
    in_window_bursts: int
    false_statics: int  # runs of final-static bursts inside the in-flight window
    response_s: float | None  # truly at rest after the flight to the first final-static burst
    samples_per_hour: float  # per axis


def rest_after_window_s(rec, track, step_s: float = 0.01) -> float | None:
    """When the bag truly came to rest after the in-flight window, to ``step_s``: the labels on a dense
    grid of the recording's carrier timeline (:func:`flightmode.sim.sensor.sensing.labels_at`), since a
    burst recording's own rows only see it at the next burst. None if it never does."""
    from flightmode.sim.sensor.sensing import labels_at

    t_end = float(rec.t_s[-1])
    window = np.asarray(rec.in_flight_window, bool)
    if not window.any():
        return None
    t0 = float(rec.t_s[np.flatnonzero(window)[-1]])  # the last recorded in-window sample
    grid = t0 + np.arange(int((t_end - t0) / step_s) + 1) * step_s
    lab = labels_at(grid, rec.segments, track)
    ok = np.flatnonzero(lab["sensor_static"] & ~lab["in_flight_window"])
    return float(grid[ok[0]]) if ok.size else None


def duty_cycle_on_flight(
    rec, sigma2: np.ndarray, k: float, m: int, t_rest_s: float | None = None
) -> DutyCycleOnFlight:
    """The duty-cycled detector over a burst recording, scored against its labels: a burst's truth is
    its last sample's (in the in-flight window, truly static). ``t_rest_s``: when the bag truly came to
    rest after the window (:func:`rest_after_window_s`); the response counts from it. Without it, from
    the first truly static recorded sample after the window (a burst's: up to an interval late)."""
    from flightmode.eobs.duty_cycle import detect_bursts

    sl = burst_slices(rec.t_s, rec.odr_hz)
    t = np.array([float(rec.t_s[s.stop - 1]) for s in sl])
    checks = detect_bursts(t, [rec.acc_g[s] for s in sl], sigma2, k, m)
    last = np.array([s.stop - 1 for s in sl])
    in_w = np.asarray(rec.in_flight_window, bool)[last]
    fin = checks.final_static
    runs = np.diff(np.concatenate([[0], (fin & in_w).astype(np.int8), [0]]))
    response = None
    window = np.asarray(rec.in_flight_window, bool)
    t_rest = t_rest_s
    if t_rest is None and window.any():
        end = int(np.flatnonzero(window)[-1])
        rest = np.flatnonzero(np.asarray(rec.sensor_static, bool)[end:])
        t_rest = float(rec.t_s[end + rest[0]]) if rest.size else None
    if t_rest is not None:
        hit = np.flatnonzero(fin & (t >= t_rest))
        response = float(t[hit[0]] - t_rest) if hit.size else None
    interval = float(np.median(np.diff([float(rec.t_s[s.start]) for s in sl]))) if len(sl) > 1 else math.nan
    n = int(np.median([s.stop - s.start for s in sl]))
    return DutyCycleOnFlight(
        interval,
        n,
        m,
        k,
        len(sl),
        int(in_w.sum()),
        int((runs == 1).sum()),
        response,
        n * 3600.0 / interval if interval > 0 else math.nan,
    )


def tradeoff_on_track(
    track, scenario, intervals_s, byte_count: int, ms, k: float = 4.0, odr_per_axis_hz: float = 10.0
) -> list[DutyCycleOnFlight]:
    """The battery trade-off on one flown track: the scenario's bag re-sensed by an e-obs tag at each
    ACC interval (``byte_count`` sets the burst, seed 003 section 9), its sigma^2 from the unit's bench
    recording cut into bursts of the same length, and the detector at each ``m``."""
    import dataclasses

    import flightmode
    from flightmode.eobs.duty_cycle import calibrate_sigma2_bursts
    from flightmode.sim.sensor.accelerometer import UnitDraw, bench_static, eobs_preset

    rows = []
    for interval in intervals_s:
        preset = eobs_preset(float(interval), byte_count, odr_per_axis_hz)
        streams = flightmode.Streams(scenario.seed)
        rec = flightmode.sense(
            track, scenario.carrier, preset, streams.child("sensor"), overrides=scenario.overrides
        )
        n = preset.burst_samples
        assert n is not None  # eobs_preset sets the burst
        bench = bench_static(
            dataclasses.replace(preset, burst_interval_s=None, burst_samples=None),
            UnitDraw.from_dict(rec.unit),
            streams.rng("detector/bench"),
            duration_s=600.0,
        )
        cut = bench.acc_g[: (bench.acc_g.shape[0] // n) * n].reshape(-1, n, 3)
        s2 = calibrate_sigma2_bursts(list(cut), lsb_g=preset.lsb_g)
        t_rest = rest_after_window_s(rec, track)
        rows += [duty_cycle_on_flight(rec, s2, k, m, t_rest) for m in ms]
    return rows


__all__ = [
    "recording_bursts",
    "burst_slices",
    "duty_cycle_on_flight",
    "rest_after_window_s",
    "tradeoff_on_track",
    "DutyCycleOnFlight",
]
