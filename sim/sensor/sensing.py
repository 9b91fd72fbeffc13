"""Sensing: a FlightTrack plus a carrier timeline plus an accelerometer -> a labelled Recording.

Everything is generated at ``FS_INTERNAL_HZ`` (800 Hz: a multiple of every output data rate of the
presets, 1 to 400 Hz, and above twice the highest line modelled, an N2 shaft at 253 Hz, so every
line is represented and the part's own filter and sampling decide what aliases; the FlightTrack's
channels, at its own rate, are interpolated linearly to it), chunk by chunk with every filter's state carried across chunks, then the
accelerometer's own filter and sampling decide what reaches its output (aliasing included).

Frames: on board, the floor's specific force is the FlightTrack's at the bag's lever arm (body
axes) plus airframe vibration (:mod:`flightmode.sim.sensor.vibration`), passed through the mount of
where the bag rests (:mod:`flightmode.sim.sensor.mount`: support and packing stages); the floor's
level and the mounts are drawn once per flight (:func:`draw_path`); the ground cases add the tug's
jolts in the push to the floor (:mod:`flightmode.sim.sensor.tug`) and the passenger's breathing and
posture shifts to a bag on a lap (:mod:`flightmode.sim.sensor.passenger`); the sensor frame is rotated
from the body frame by the bag's orientation, drawn anew at every put-down. Off board, the bag is in
a local north/east/down frame: specific force = motion - gravity.

Labels per output sample: ``phase`` (the bag's: terminal_walk ... boarding, then the
aircraft's phases while on board, deplaning, arrival_rest), ``in_flight_window``, ``airborne``,
``turbulence_severity`` (from the FlightTrack; false/none outside it), ``bag_state`` and
``sensor_static``: true only while the bag rests (in the terminal or at arrival) or sits stowed
with the engines stopped (before engine start, after engines off), and not within
``SETTLE_S`` of a put-down.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import cast

import numpy as np
from scipy.signal import sosfilt, sosfilt_zi

from flightmode.errors import SensorError, first_nonfinite
from flightmode.labels import PHASE_CODE
from flightmode.sim.flight import atmosphere
from flightmode.sim.flight.aircraft.registry import get_profile
from flightmode.sim.flight.track import FlightTrack
from flightmode.sim.sensor import carrier as car
from flightmode.sim.sensor import mount as mnt
from flightmode.sim.sensor import passenger as pax
from flightmode.sim.sensor import tug
from flightmode.sim.sensor.accelerometer import AccelerometerPreset, SensorChain, UnitDraw, draw_unit
from flightmode.sim.sensor.barometer import BarometerPreset
from flightmode.sim.sensor.gyroscope import GyroSpec
from flightmode.sim.sensor.recording import Recording
from flightmode.sim.sensor.vibration import (
    FloorDraw,
    VibrationModel,
    draw_floor,
    initial_state,
    scaled,
    vibration_g,
)
from flightmode.streams import Streams, as_streams
from flightmode.units import G0_MPS2 as G0

FS_INTERNAL_HZ = 800.0
CHUNK_S = 60.0
SETTLE_S = 2.0
BAG_STATE_CODE = {s: i for i, s in enumerate(car.BAG_STATES)}


def _check_track(track: FlightTrack) -> None:
    if not np.all(np.diff(track.t_s) > 0):
        i = int(np.flatnonzero(np.diff(track.t_s) <= 0)[0])
        raise SensorError(
            f"FlightTrack time is not strictly increasing at sample {i} (t = {track.t_s[i]:.3f} s)"
        )
    for name in ("specific_force_body_mps2", "rates_radps", "ang_acc_radps2", "n1_pct", "tas_mps", "alt_m"):
        if (bad := first_nonfinite(getattr(track, name))) is not None:
            raise SensorError(
                f"FlightTrack.{name} has NaN or inf at sample {bad} (t = {track.t_s[bad]:.3f} s): "
                "re-fly the scenario"
            )


def sense(
    track: FlightTrack,
    spec: car.CarrierSpec,
    preset: AccelerometerPreset,
    streams: Streams | np.random.Generator | int,
    vibration: VibrationModel | None = None,
    unit: UnitDraw | None = None,
    gyro: GyroSpec | None = None,
    mount: mnt.MountDraw | None = None,
    vibration_level: float = 1.0,
    baro: BarometerPreset | None = None,
    overrides: Mapping[str, float] | None = None,
) -> Recording:
    """Sense ``track`` with a bag carried as ``spec`` and an accelerometer ``preset``.

    ``streams``: the sensing stage's random streams (:class:`flightmode.streams.Streams`; a Generator
    or an integer seed is turned into streams), one per draw: ``unit`` (the part's offsets, gains and
    cross-axis coupling), ``timeline`` (handling times, orientations), ``motion`` (gait, handling,
    road), ``vibration``, ``noise`` (the output noise) and ``gyro``. Changing one draw never moves
    another's numbers. Pass ``unit`` to impose a unit instead of drawing one (e.g. a perfect
    ``UnitDraw()``).

    The path from the floor to the sensor is drawn per flight (:func:`draw_path`: streams ``mount``
    and ``floor``): ``mount`` imposes the mount (on every placement), ``vibration`` the floor's
    vibration model as it is (no type, location or flight factor applied); ``vibration_level``
    multiplies the floor's amplitudes (1: as drawn).

    ``baro``: a barometer fitted beside the accelerometer (:func:`read_barometer`, streams
    ``baro/unit`` and ``baro/noise``); it needs a track with pressure truth.

    ``overrides``: the run's uncertain model parameters (a scenario's ``[model]`` table, name ->
    value, :mod:`flightmode.uncertain`), passed to the draws that read them (:func:`draw_path`).
    """
    _check_track(track)
    preset.validate()
    streams = as_streams(streams)
    prof = get_profile(track.aircraft)
    unit = draw_unit(preset, streams.rng("unit")) if unit is None else unit
    events = {e.name: e.t_s for e in track.events}
    cruise_idx = np.flatnonzero(track.phase_code == PHASE_CODE["cruise"])
    cruise = (float(track.t_s[cruise_idx[0]]), float(track.t_s[cruise_idx[-1]])) if cruise_idx.size else None
    segs = car.build_timeline(spec, events, cruise, streams.rng("timeline"))
    rng_motion, rng_vib, rng_noise = streams.rng("motion"), streams.rng("vibration"), streams.rng("noise")
    floor_draw, mount_draws = draw_path(track.aircraft, spec, streams, overrides)
    vibration_imposed = vibration
    vibration = floor_draw.model if vibration is None else vibration
    if vibration_level != 1.0:  # a population's spread of levels (a scenario's [sensor].vibration_level)
        vibration = scaled(vibration, float(vibration_level))
    if mount is not None:
        mount_draws = {p: mount for p in mount_draws}
    seg_t0 = np.array([s.t0_s for s in segs])
    t_start, t_end = segs[0].t0_s, segs[-1].t1_s
    fs = FS_INTERNAL_HZ
    dt = 1.0 / fs
    n_total = int(round((t_end - t_start) * fs))
    # the ground cases (issue 50): the passenger under a bag on a lap (stream ``lap``) and the tug's
    # jolts in the push (stream ``tug``), each drawn only where it acts (its own stream: no other
    # draw moves)
    lap = None
    if any(s.on_board and s.placement == "lap" for s in segs):
        lap = pax.draw_lap(t_start, t_end, streams.rng("lap"), overrides)
    span = tug.push_span(track.t_s, track.phase_code, track.ground_speed_mps)
    tug_draw = None if span is None else tug.draw_tug(span, streams.rng("tug"), overrides)

    # per-segment motion (walks, handling) drawn up front, in segment order
    motion: dict[int, np.ndarray] = {}
    for i, s in enumerate(segs):
        n = int(round((s.t1_s - s.t0_s) * fs)) + 1
        if s.state == "handled":
            motion[i] = car.handling_accel_mps2(n, dt, rng_motion)
        elif s.phase == "truck":
            motion[i] = car.road_accel_mps2(n, dt, rng_motion)
        elif s.walking:
            motion[i] = car.gait_accel_mps2(np.arange(n) * dt, spec, rng_motion)
    # put-down shocks at the start of every resting / stowed segment that follows a carried one,
    # pick-up lifts at the start of every carried / handled segment that follows a resting one
    transients = (car.putdown_pulse_mps2(int(0.25 * fs), dt, spec), car.pickup_pulse_mps2(dt, spec))

    # track channels at the track's rate as rows (channels first), interpolated per chunk row by row
    loc = prof.locations_m[car.LOCATION_OF[spec.placement]]
    qbar = 0.5 * atmosphere.density_kgpm3(track.alt_m) * track.tas_mps**2
    ne = track.n1_pct.shape[1]
    chans = np.vstack(
        [
            track.specific_force_at(loc).T,
            track.n1_pct.T,
            track.n2_pct.T,
            qbar,
            track.ground_speed_mps,
            track.wow,
        ]
    )
    mounts = {p: mnt.mount_sos(m, fs) for p, m in mount_draws.items()}
    mount_zi = {p: [np.zeros((sos.shape[0], 2)) for sos in m] for p, m in mounts.items()}
    mount_running: set[str] = set()  # the placements whose mount ran through the last chunk
    vstate = initial_state(ne, vibration, fs, rng_vib)
    chain = SensorChain(preset, unit, fs)
    meas = []
    for c0 in range(0, n_total, int(CHUNK_S * fs)):
        n = min(int(CHUNK_S * fs), n_total - c0)
        t = t_start + (c0 + np.arange(n)) * dt
        si = np.searchsorted(seg_t0, t, side="right") - 1
        # si is sorted: the segments this chunk touches, each a contiguous run [a, b) of samples
        ks = range(int(si[0]), int(si[-1]) + 1)
        runs = np.searchsorted(si, np.arange(ks.start, ks.stop + 1), side="left")
        if any(segs[k].on_board for k in ks):
            # the mounts the bag rests on in this chunk; one it leaves restarts in its steady state
            # when the bag is next set on it
            # on board and not handled: stowed, so placed (Segment.placement is None only off board)
            resting = {
                cast(str, segs[k].placement) for k in ks if segs[k].on_board and segs[k].state != "handled"
            }
            fl, bag, vstate = _floor_and_bag(
                track,
                chans,
                ne,
                t,
                fs,
                vibration,
                vstate,
                rng_vib,
                {p: mounts[p] for p in resting},
                mount_zi,
                mount_running,
                None if tug_draw is None else tug.tug_accel_mps2(t, tug_draw),
            )
            mount_running = resting
        else:
            # the bag is off the aircraft for the whole chunk: no floor, vibration or mount to run
            mount_running = set()
        f_sensor = np.empty((3, n))  # sensor axes as rows
        for k, a, b in zip(ks, runs[:-1], runs[1:]):
            s = segs[k]
            j = np.round((t[a:b] - s.t0_s) * fs).astype(int)
            if not s.on_board:  # local N/E/Down frame: at rest the specific force is 1 g up
                f_frame = np.zeros((3, b - a))
                f_frame[2] = -G0
                if k in motion:
                    f_frame += motion[k][j].T
            elif s.state == "handled":  # held in the cabin: the floor's force plus the arm's motion
                f_frame = fl[:, a:b] + motion[k][j].T
            else:  # stowed: through the mount of where it rests
                f_frame = bag[s.placement][:, a:b]
                if lap is not None and s.placement == "lap":  # the passenger moves under it
                    f_frame = f_frame + pax.lap_accel_mps2(t[a:b], lap)
            _transients(segs, k, transients, j, f_frame)
            np.matmul(s.orientation.T, f_frame, out=f_sensor[:, a:b])  # sensor <- frame: R^T f
        f_sensor *= 1.0 / G0
        meas.append(chain.rows(f_sensor, t_start, rng_noise))
    t_out = np.concatenate([m.t_s for m in meas])
    counts = np.concatenate([m.counts for m in meas])
    acc = np.concatenate([m.acc_g for m in meas])
    clipped = np.concatenate([m.clipped for m in meas])
    if preset.burst_interval_s is not None:
        # burst recording (e-obs, seed 003 sections 4 and 9): burst_samples per axis at the ODR,
        # one burst every burst_interval_s; nothing is stored in between
        per = int(round(preset.burst_interval_s * preset.odr_hz))
        in_burst = preset.burst_samples
        assert in_burst is not None  # set with burst_interval_s (SensorPreset.__post_init__)
        keep = (np.arange(t_out.shape[0]) % per) < in_burst
        t_out, counts, acc, clipped = t_out[keep], counts[keep], acc[keep], clipped[keep]
    gyro_dps = None if gyro is None else _gyro(t_out, segs, track, gyro, streams.rng("gyro"))
    labels = _labels(t_out, segs, track, events)
    ground = {k: d.as_dict() for k, d in (("lap", lap), ("tug", tug_draw)) if d is not None}
    pressure, baro_cols = None, {}
    if baro is not None:  # the pressure at the bag is the barometer's truth: computed only for one
        pressure = bag_pressure_pa(t_out, segs, track)
        baro_cols = read_barometer(t_out, segs, track, baro, streams)
    return Recording(
        t_s=t_out,
        counts=counts,
        acc_g=acc,
        clipped=clipped,
        odr_hz=preset.odr_hz,
        preset=preset.name,
        unit=unit.as_dict(),
        carrier=spec,
        aircraft=track.aircraft,
        segments=tuple(segs),
        gyro_dps=gyro_dps,
        pressure_pa=pressure,
        **labels,
        **baro_cols,
        stowage=stowage_record(
            segs, events, mount_draws, floor_draw if vibration_imposed is None and mount is None else None
        )
        | ({"ground": ground} if ground else {}),
    )


def stowage_record(
    segs, events: dict[str, float], mount_draws: dict[str, mnt.MountDraw], floor_draw: FloorDraw | None
) -> dict:
    """What the flight drew of the bag's place on board, for the record (run.json, the manifest) and
    for reading seed 000's tables beside it. Over the in-flight window (pushback to engines off, what
    Tables 4 / 5 cover; engine start without a pushback), every segment the bag lay stowed (each
    handling sets it down anew, at a new orientation): its placement, how the sensor lay there
    (:func:`~flightmode.sim.sensor.carrier.orientation_angles`) and the share of the window it covers
    (``in_flight_segments``); ``in_flight``: the one covering most, with its mount's cabin row and
    packing. Also every placement's mount and the floor's vibration factors (None when the caller
    imposed a vibration model or a mount: the record would not be what was felt)."""
    t0 = events.get("pushback", events["engine_start"])
    t1 = events["engines_off"]
    span = max(t1 - t0, 1e-9)
    out: dict = {
        "mounts": {p: m.as_dict() for p, m in mount_draws.items()},
        "floor": None if floor_draw is None else floor_draw.as_dict(),
    }
    parts = []
    for seg in segs:
        cover = min(seg.t1_s, t1) - max(seg.t0_s, t0)
        if seg.on_board and seg.state in ("stowed", "in_hold") and cover > 0.0:
            place = seg.placement or "hold"
            parts.append(
                {"placement": place, **car.orientation_angles(seg.orientation), "share": cover / span}
            )
    if parts:
        out["in_flight_segments"] = parts
        best = max(parts, key=lambda d: d["share"])
        out["in_flight"] = {k: v for k, v in best.items() if k != "share"}
        m = mount_draws.get(best["placement"])
        if m is not None:
            out["in_flight"] |= {"cabin_row": m.cabin_row, "packing": m.packing}
    return out


def _in_hold(seg: car.Segment) -> bool:
    return seg.on_board and (seg.state == "in_hold" or seg.placement == "hold")


def bag_pressure_pa(t: np.ndarray, segs, track: FlightTrack) -> np.ndarray:
    """The true pressure at the bag at times ``t``: the cabin's while on board in the cabin, the
    hold's in the hold, ambient off board (the terminal, the truck: the airport's, the track's ends
    held; a road leg's elevation change is not modelled)."""
    seg_t0 = np.array([s.t0_s for s in segs])
    si = np.clip(np.searchsorted(seg_t0, t, side="right") - 1, 0, len(segs) - 1)
    amb, cab, hold = track.ambient_pressure_pa, track.cabin_pressure_pa, track.hold_pressure_pa
    if amb is None or cab is None or hold is None:
        raise SensorError(
            "a barometer needs the track's pressure truth (ambient, cabin, hold): this track has no pressure "
            "truth (read from an older file); fly the scenario again"
        )
    rows = np.vstack([amb, cab, hold])
    amb, cab, hold = _track_rows_at(rows, track, t)
    where = np.array([2 if _in_hold(s) else 1 if s.on_board else 0 for s in segs], np.intp)[si]
    return np.choose(where, (amb, cab, hold))


def read_barometer(
    t_rows: np.ndarray, segs, track: FlightTrack, preset: BarometerPreset, streams: Streams
) -> dict:
    """A barometer beside the accelerometer: it converts on its own grid ``t_rows[0] + k / ODR``
    (:func:`flightmode.sim.sensor.barometer.measure`: the unit from stream ``baro/unit``, the noise
    from ``baro/noise``) and the tracker reads it at its accelerometer rows: each row holds the
    latest reading, ``baro_new`` marks the rows where a new one arrived (the first row at or after
    each conversion; conversions falling in a gap between rows, e.g. between bursts, are lost but
    the last). The barometer's stream is ``t_rows[baro_new]``, ``baro_pa[baro_new]``: time-stamped
    when the firmware reads it, at most one accelerometer period after the conversion."""
    from flightmode.sim.sensor.barometer import draw_unit as draw_baro_unit
    from flightmode.sim.sensor.barometer import measure, sample_times

    preset.validate()
    ticks = sample_times(t_rows, preset.odr_hz)
    if ticks.shape[0] < 2:
        raise SensorError(f"barometer at {preset.odr_hz:g} Hz: the recording is shorter than two readings")
    unit = draw_baro_unit(preset, streams.rng("baro/unit"))
    p_true = bag_pressure_pa(ticks, segs, track)
    _, y = measure(ticks, p_true, preset, streams.rng("baro/noise"), unit=unit, t0_s=float(ticks[0]))
    k = np.searchsorted(ticks, t_rows, side="right") - 1  # the latest conversion at or before each row
    new = np.empty(t_rows.shape[0], bool)
    new[0] = True
    new[1:] = k[1:] != k[:-1]
    return {
        "baro_pa": y[k],
        "baro_new": new,
        "baro": {"preset": preset.name, "odr_hz": preset.odr_hz, "unit": unit.as_dict()},
    }


def draw_path(
    aircraft: str, spec: car.CarrierSpec, streams: Streams, overrides: Mapping[str, float] | None = None
) -> tuple[FloorDraw, dict[str, mnt.MountDraw]]:
    """One flight's draws of the path from the airframe to the sensor, each from its own stream: the
    mounts (support, packing, cabin row, for the placement and the cruise placement: stream
    ``mount``, :func:`~flightmode.sim.sensor.mount.draw_mounts`), then the floor's vibration at
    that row for that type (stream ``floor``, :func:`~flightmode.sim.sensor.vibration.draw_floor`);
    ``overrides``: the run's uncertain model parameters (the mounts' and the floor's)."""
    spec.validate()
    mounts = mnt.draw_mounts(spec, streams.rng("mount"), overrides)
    floor = draw_floor(aircraft, mounts[spec.placement].cabin_row, streams.rng("floor"), overrides=overrides)
    return floor, mounts


def _track_rows_at(rows: np.ndarray, track: FlightTrack, t: np.ndarray) -> np.ndarray:
    """Rows (channels, track.n) of per-FDM-step values, linearly interpolated at the times ``t``
    (held at the track's ends)."""
    pos = np.clip((t - track.t_s[0]) * track.fs_hz, 0.0, track.n - 1.000001)
    i0 = pos.astype(np.int64)
    i1 = i0 + 1
    w = pos - i0
    out = np.empty((rows.shape[0], t.shape[0]))
    for c, r in enumerate(rows):
        lo = r[i0]
        np.multiply(r[i1] - lo, w, out=out[c])
        out[c] += lo
    return out


def _floor_and_bag(
    track, chans, ne, t, fs, vibration, vstate, rng, mounts, mount_zi, mount_running, jolts=None
):
    """One chunk on board: the floor's specific force at the bag's place (rows x, y, z, body axes,
    m/s^2) from the track plus the tug's ``jolts`` (None: none in this chunk;
    :mod:`flightmode.sim.sensor.tug`) plus airframe vibration, and the bag's through the mount of each placement
    (``mounts``: placement -> per-axis SOS). Updates ``mount_zi`` in place (started in their steady
    state unless in ``mount_running``); returns the floor without vibration (what a handled bag's arm
    adds to), {placement: the bag's}, and the new vibration state."""
    ch = _track_rows_at(chans, track, t)
    fl = ch[0:3] if jolts is None else ch[0:3] + jolts
    n1, n2 = ch[3 : 3 + ne], ch[3 + ne : 3 + 2 * ne]
    qb, gs, wow = ch[3 + 2 * ne], ch[4 + 2 * ne], ch[5 + 2 * ne] > 0.5
    if n1.max() < 1.0 and gs.max() < 0.5:
        floor = fl  # engines stopped, aircraft at rest: no vibration to compute
    else:
        floor, vstate = vibration_g(n1, n2, qb, gs, wow, fs, track.aircraft, vibration, vstate, rng)
        floor *= G0
        floor += fl
    bags = {}
    for p, mount in mounts.items():
        zi = mount_zi[p]
        if p not in mount_running:  # start the mount in its steady state (DC gain 1)
            for ax in range(3):
                zi[ax] = sosfilt_zi(mount[ax]) * floor[ax, 0]
        bag = np.empty_like(floor)
        for ax in range(3):
            bag[ax], zi[ax] = sosfilt(mount[ax], floor[ax], zi=zi[ax])
        bags[p] = bag
    return fl, bags, vstate


def _transients(segs, k, transients, j, f_frame) -> None:
    """Add the transients of segment ``k`` along the frame's down axis (``f_frame`` rows x, y, z):
    the put-down shock at the start of a resting / stowed segment that follows a carry, the
    pick-up lift at the start of a carry that follows a rest. ``transients`` = (put-down, pick-up)."""
    if k == 0:
        return
    state, before = segs[k].state, segs[k - 1].state
    if state in ("resting", "stowed", "in_hold") and before in ("carried", "handled"):
        p = transients[0]
    elif state in ("carried", "handled") and before in ("resting", "stowed", "in_hold"):
        p = transients[1]
    else:
        return
    inside = j < p.shape[0]
    f_frame[2, inside] -= p[j[inside]]


def _gyro(t: np.ndarray, segs, track: FlightTrack, spec: GyroSpec, rng: np.random.Generator) -> np.ndarray:
    """Gyroscope output (M, 3) in deg/s at the output instants ``t`` (sensor axes)."""
    seg_t0 = np.array([s.t0_s for s in segs])
    si = np.clip(np.searchsorted(seg_t0, t, side="right") - 1, 0, len(segs) - 1)
    body = np.degrees(_track_rows_at(track.rates_radps.T, track, t)).T
    fs = 1.0 / float(np.median(np.diff(t))) if t.shape[0] > 1 else 1.0
    out = np.zeros((t.shape[0], 3))
    for k, seg in enumerate(segs):
        sel = si == k
        n = int(sel.sum())
        if n == 0:
            continue
        rate = body[sel] if seg.on_board else np.zeros((n, 3))
        rms = spec.handling_dps if seg.state == "handled" else spec.sway_dps if seg.walking else 0.0
        if rms > 0:
            rate = rate + car.band_noise(n, fs, (0.3, 3.0), rms, rng)
        out[sel] = rate @ seg.orientation  # sensor <- frame
    bias = rng.uniform(-spec.bias_tol_dps, spec.bias_tol_dps, 3)
    out += bias + rng.normal(0.0, spec.noise_rms_dps(fs), out.shape)
    out = np.clip(out, -spec.range_dps, spec.range_dps)
    return out if spec.lsb_dps is None else np.rint(out / spec.lsb_dps) * spec.lsb_dps


def labels_at(t_s: np.ndarray, segments, track: FlightTrack) -> dict:
    """The truth labels (phase code, in-flight window, airborne, turbulence, bag state, sensor static)
    at any times ``t_s`` of a recording's carrier timeline (``Recording.segments``) on its track: what a
    burst recording's own rows cannot say between its bursts (when the bag truly came to rest)."""
    events = {e.name: e.t_s for e in track.events}
    return _labels(np.asarray(t_s, float), list(segments), track, events)


def _labels(t: np.ndarray, segs: list[car.Segment], track: FlightTrack, events: dict[str, float]) -> dict:
    seg_t0 = np.array([s.t0_s for s in segs])
    si = np.clip(np.searchsorted(seg_t0, t, side="right") - 1, 0, len(segs) - 1)
    inside = (t >= track.t_s[0]) & (t <= track.t_s[-1])
    ti = np.clip(np.rint((t - track.t_s[0]) * track.fs_hz).astype(int), 0, track.n - 1)
    phase = track.phase_code[ti].copy()
    state = np.array([BAG_STATE_CODE[s.state] for s in segs], dtype=np.uint8)[si]
    own_phase = np.array([PHASE_CODE[s.phase] if s.phase else 255 for s in segs])[si]
    phase = np.where(own_phase != 255, own_phase, phase).astype(np.uint8)
    in_window = track.in_flight_window[ti] & inside
    airborne = track.airborne[ti] & inside
    turb = np.where(inside, track.turbulence_code[ti], 0).astype(np.uint8)
    engines_stopped = (t < events["engine_start"]) | (t >= events["engines_off"])
    resting = np.isin(state, [BAG_STATE_CODE["resting"]])
    stowed_quiet = np.isin(state, [BAG_STATE_CODE["stowed"], BAG_STATE_CODE["in_hold"]]) & engines_stopped
    since_start = t - seg_t0[si]
    settled = since_start >= SETTLE_S
    static = (resting | stowed_quiet) & settled
    return dict(
        phase_code=phase,
        in_flight_window=in_window,
        airborne=airborne,
        turbulence_code=turb,
        bag_state_code=state,
        sensor_static=static,
    )
