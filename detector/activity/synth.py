"""Seed 001's accelerometer and angular-rate synthesizer (section 3.1.1, "Set-Up"; Figure 2): a
sequence of periods of basic activities separated by inactivity, with random intensity, frequency,
amplitude and length, a selectable gravity axis, sensor ranges and white noise, and the true marker.

The seed describes the synthesizer in words only: five basic activities (walking, sitting on a
chair and standing up, lying on a bed and standing up, running, jumping), two "general" ones (a
constant angular rate with no acceleration, a constant acceleration with no angular rate), random
intensity (frequency, amplitude) and length per period, the sensing axis parallel to gravity
selectable, |a| = 1 g at every static instant, random noise, and ranges "similar to those of
commercial MEMS inertial sensors". Everything else below is our choice, stated where it is made
(:class:`Ranges` holds every drawn range with its source). In short:

- The sequence alternates inactivity and activity, starting still: still, A1, still, A2, ..., each
  activity drawn uniformly from the seven. Periods are drawn until ``duration_s`` is filled; the
  last one is cut at the end.
- Sitting and lying are three periods each: the transition down (active), the rest seated / lying
  (inactive: the sensor is still, gravity tilted, |a| = 1 g), the transition up (active). The seed
  calls "sitting down-standing up" one activity; we mark its still middle inactive because the
  detectors' definition of inactivity is "neither acceleration nor angular velocity" (section 1).
- Transitions are abrupt, as the seed's are (section 4.1: "transitions from states in real signals
  are smoother than in synthesized signals"): an activity starts at a random phase of its waveform.
- Walking and running: a gait waveform at the step frequency (vertical, plus a second harmonic, and
  antero-posterior) and at the stride frequency (medio-lateral), and angular rates at both. Within a
  period the amplitude and the step frequency change linearly between two random draws (the seed's
  section 4.1 discusses a subject who "starts to run faster" inside a period). The small tilts of
  the gait's rotation are not fed back into the gravity reading: acceleration and angular rate are
  synthesized as separate "acceleration-like and angular rate-like signals" (section 3.1.1).
- Jumping: repeated cycles of ground contact (a half-sine push whose mean over the cycle is 1 g, as
  the mean specific force of any periodic motion must be) and flight (free fall: the specific force
  is 0), with a pitch rate swing per jump. The period is a whole number of jumps.
- Frames: the body frame is (forward, lateral, up); standing, "up" is the chosen sensor axis
  (``gravity_axis``, e.g. "z" or "-x"), and the body frame maps onto the sensor axes by a proper
  rotation (a signed cyclic permutation). A level sensor with its up axis reads +1 g on it
  (specific force, flightmode's convention).
- Sensor: white Gaussian noise per axis (defaults: 2.23 mg, the LIS302DL's output noise in seed
  000's Table 1; 0.05 deg/s, the total RMS rate noise of the InvenSense MPU-6000/6050 datasheet
  (rev. 3.4, 100 Hz bandwidth); the seed gives no level), then saturation at the ranges of the
  seed's own IMU (section 3.2): +-3 g (ADXL335) and +-500 deg/s (LPR550AL, LY550ALH). The default
  rate is the seed's 50 Hz (section 4.1).

Units: ``acc_g`` in g (specific force), ``gyr_dps`` in deg/s, as the detectors take them
(:mod:`~flightmode.detector.activity.common`).

Randomness: one :class:`numpy.random.Generator` (or :class:`~flightmode.streams.Streams`, or an
integer seed) seeds named streams (:func:`~flightmode.streams.as_streams`): ``schedule`` (the
periods and their parameters), ``noise/acc`` and ``noise/gyr``; a change of noise level never moves
the schedule.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from flightmode.errors import SensorError, did_you_mean

ACTIVITIES = ("walking", "sit_stand", "lie_stand", "running", "jumping", "constant_rate", "constant_acc")
# the kinds of period in a Synth (an activity of ACTIVITIES is one period, or three for sit/lie)
PERIOD_KINDS = (
    "still",
    "walking",
    "sit_down",
    "seated",
    "lie_down",
    "lying",
    "stand_up",
    "running",
    "jumping",
    "constant_rate",
    "constant_acc",
)
GRAVITY_AXES = ("x", "y", "z", "+x", "+y", "+z", "-x", "-y", "-z")
# The activity sequence of the seed's Figure 2 (section 3.1.1): "walking, laying-standing up, walking,
# sitting-standing up, running, no angular rate, jumping, walking, laying-standing up, no acceleration"
# ("no angular rate" is the constant acceleration, "no acceleration" the constant angular rate).
FIGURE2_SEQUENCE = (
    "walking",
    "lie_stand",
    "walking",
    "sit_stand",
    "running",
    "constant_acc",
    "jumping",
    "walking",
    "lie_stand",
    "constant_rate",
)


@dataclass(frozen=True, slots=True)
class Ranges:
    """Every uniform range the synthesizer draws from, (low, high). The seed gives none of these
    figures; each is our choice, with the public figure it follows where there is one."""

    # lengths (s). Ours: the seed's Figure 2 shows ten activities; a still period of 2-8 s and an
    # activity of 3-10 s put ten of each in about two minutes. The seed's best windows (Table 1,
    # AMD: ~97 samples, ~2 s at 50 Hz) need periods several seconds long to be best.
    still_s: tuple[float, float] = (2.0, 8.0)
    activity_s: tuple[float, float] = (3.0, 10.0)
    posture_rest_s: tuple[float, float] = (2.0, 8.0)  # seated / lying still
    transition_s: tuple[float, float] = (1.0, 2.5)  # sit down, lie down, stand up (ours)
    # walking: step frequency 1.5-2.2 Hz = 90-132 steps/min, inside the laboratory range of normal
    # walking cadence, 81-138 steps/min (Tudor-Locke and Rowe 2012, "Using cadence to study
    # free-living ambulatory behaviour", Sports Med 42:381)
    walk_step_hz: tuple[float, float] = (1.5, 2.2)
    walk_acc_g: tuple[float, float] = (0.2, 0.6)  # vertical amplitude at the hip (ours; a few tenths of g)
    walk_gyr_dps: tuple[float, float] = (15.0, 50.0)  # pelvis rotation, +-5-8 deg at ~1 Hz (ours)
    # running: 150-190 steps/min (above the walk-to-run transition at ~140 steps/min: Hum Mov Sci
    # 2023, 90:103117, "Cadence (steps/min) as an indicator of the walk-to-run transition")
    run_step_hz: tuple[float, float] = (2.5, 3.2)
    run_acc_g: tuple[float, float] = (0.8, 2.0)  # vertical amplitude (ours): peaks of 2-3 g reach the range
    run_gyr_dps: tuple[float, float] = (40.0, 150.0)  # (ours)
    # ratio of the amplitude at the end of a walking/running period to that at its start (ours)
    intensity_ratio: tuple[float, float] = (0.6, 1.4)
    # jumping: contact and flight times per jump (ours); a flight of 0.2-0.45 s is a jump height
    # g T^2 / 8 of 5-25 cm; the contact push then peaks at pi T / (2 T_c) = 2.1-5.6 g (clipped at 3 g)
    jump_contact_s: tuple[float, float] = (0.35, 0.6)
    jump_flight_s: tuple[float, float] = (0.2, 0.45)
    jump_gyr_dps: tuple[float, float] = (20.0, 80.0)
    # sitting and lying: trunk tilt and hip drop (ours; a hip-worn sensor, as the seed's IMU, 3.2.1)
    sit_tilt_deg: tuple[float, float] = (20.0, 60.0)
    lie_tilt_deg: tuple[float, float] = (75.0, 95.0)
    sit_drop_m: tuple[float, float] = (0.3, 0.5)
    lie_drop_m: tuple[float, float] = (0.2, 0.5)
    # the two general activities (ours)
    constant_rate_dps: tuple[float, float] = (20.0, 120.0)  # about the vertical, either sign
    constant_acc_g: tuple[float, float] = (0.1, 0.5)  # in a direction uniform on the sphere


DEFAULT_RANGES = Ranges()


@dataclass(frozen=True, slots=True)
class Period:
    """One period of a Synth: samples ``start`` .. ``stop - 1``; ``active`` is its marker; ``params``
    the values drawn for it, as (name, value) pairs."""

    kind: str
    start: int
    stop: int
    active: bool
    params: tuple[tuple[str, float], ...] = ()


@dataclass(frozen=True, slots=True)
class Synth:
    """A synthesized recording: ``t_s`` (n,) s, ``acc_g`` (n, 3) g, ``gyr_dps`` (n, 3) deg/s,
    ``marker`` (n,) int8 (1 = activity), the ``periods`` it was drawn as, and the settings."""

    t_s: np.ndarray
    acc_g: np.ndarray
    gyr_dps: np.ndarray
    marker: np.ndarray
    periods: tuple[Period, ...]
    fs_hz: float
    gravity_axis: str
    sigma_acc_g: float
    sigma_gyr_dps: float
    acc_range_g: float
    gyr_range_dps: float
    ranges: Ranges = field(default=DEFAULT_RANGES)


# ---------------------------------------------------------------- frames
def body_to_sensor(gravity_axis: str) -> np.ndarray:
    """M (3, 3): sensor = M @ body for body axes (forward, lateral, up), the up axis on
    ``gravity_axis``; a proper rotation (det +1) so that angular rates keep their sense."""
    ax = _check_axis(gravity_axis)
    sign = -1.0 if ax.startswith("-") else 1.0
    u = "xyz".index(ax[-1])
    m = np.zeros((3, 3))
    m[(u + 1) % 3, 0] = 1.0  # forward
    m[(u + 2) % 3, 1] = sign  # lateral (flipped with up, so the frame stays right-handed)
    m[u, 2] = sign  # up
    return m


def _check_axis(gravity_axis) -> str:
    if gravity_axis not in GRAVITY_AXES:
        raise SensorError(
            f"gravity_axis = {gravity_axis!r}: use one of {', '.join(GRAVITY_AXES)}"
            f"{did_you_mean(gravity_axis, GRAVITY_AXES)}"
        )
    return gravity_axis


def _tilted_up(theta_rad: np.ndarray) -> np.ndarray:
    """The world's up (a unit specific force) in the body frame of a trunk pitched by theta about its
    lateral axis (R_y(theta)^T (0, 0, 1)): (-sin theta, 0, cos theta)."""
    return np.column_stack([-np.sin(theta_rad), np.zeros_like(theta_rad), np.cos(theta_rad)])


# ---------------------------------------------------------------- one period's waveforms (body frame)
def _u(rng: np.random.Generator, lo_hi: tuple[float, float]) -> float:
    return float(rng.uniform(*lo_hi))


def _still(n: int, theta_rad: float = 0.0):
    return _tilted_up(np.full(n, theta_rad)), np.zeros((n, 3)), ()


def _gait(rng, n: int, fs: float, step_hz, acc_g, gyr_dps, ratio):
    """Walking or running: step-frequency vertical (plus its second harmonic) and antero-posterior
    acceleration, stride-frequency (half) medio-lateral; yaw and roll at the stride frequency, pitch
    at the step frequency. Amplitude and step frequency change linearly across the period."""
    f0, f1 = _u(rng, step_hz), _u(rng, step_hz)
    a0, w0, r = _u(rng, acc_g), _u(rng, gyr_dps), _u(rng, ratio)
    r_ap, r_ml, h2 = _u(rng, (0.3, 0.8)), _u(rng, (0.2, 0.5)), _u(rng, (0.1, 0.4))  # (ours)
    ph = rng.uniform(0.0, 2.0 * math.pi, 7)
    ramp = np.linspace(0.0, 1.0, n)
    step = 2.0 * math.pi * np.cumsum(f0 + (f1 - f0) * ramp) / fs + ph[0]  # phase of the step cycle
    stride = 0.5 * step  # a stride is two steps
    amp = a0 * (1.0 + (r - 1.0) * ramp)
    rate = w0 * (1.0 + (r - 1.0) * ramp)
    f = np.column_stack(
        [
            r_ap * amp * np.sin(step + ph[1]),
            r_ml * amp * np.sin(stride + ph[2]),
            1.0 + amp * (np.sin(step) + h2 * np.sin(2.0 * step + ph[3])),  # mean 1 g: zero-mean swings
        ]
    )
    w = np.column_stack(
        [
            0.5 * rate * np.sin(stride + ph[4]),  # roll
            0.3 * rate * np.sin(step + ph[5]),  # pitch
            rate * np.sin(stride + ph[6]),  # yaw: pelvis rotation
        ]
    )
    params = (
        ("step_hz_start", f0),
        ("step_hz_end", f1),
        ("acc_g", a0),
        ("gyr_dps", w0),
        ("intensity_ratio", r),
    )
    return f, w, params


def _jumps(rng, fs: float, n_min: int, ranges: Ranges):
    """Jumps until at least ``n_min`` samples: per jump a contact push f = F sin(pi tau / T_c) with
    F = pi T / (2 T_c) (mean specific force 1 g over the cycle T = T_c + T_f), then free fall (f = 0)."""
    fs_list, ws_list, n_tot, n_jumps = [], [], 0, 0
    w_amp = _u(rng, ranges.jump_gyr_dps)
    while n_tot < n_min:
        tc, tf = _u(rng, ranges.jump_contact_s), _u(rng, ranges.jump_flight_s)
        nc, nf = max(2, round(tc * fs)), max(1, round(tf * fs))
        tc, tf = nc / fs, nf / fs  # the whole-sample times keep the cycle's mean at exactly ~1 g
        peak = math.pi * (tc + tf) / (2.0 * tc)
        tau = (np.arange(nc) + 0.5) / fs
        f = np.zeros((nc + nf, 3))
        f[:nc, 2] = peak * np.sin(math.pi * tau / tc)
        w = np.zeros((nc + nf, 3))
        w[:, 1] = w_amp * np.sin(2.0 * math.pi * (np.arange(nc + nf) + 0.5) / (nc + nf))  # pitch swing
        fs_list.append(f)
        ws_list.append(w)
        n_tot += nc + nf
        n_jumps += 1
    return np.concatenate(fs_list), np.concatenate(ws_list), (("jumps", float(n_jumps)), ("gyr_dps", w_amp))


def _transition(n: int, fs: float, theta_from: float, theta_to: float, dz_m: float):
    """A posture change over n samples: pitch theta (rad) and hip height (m) follow a raised cosine
    from start to end; the pitch rate and the vertical acceleration are its derivatives."""
    from flightmode.units import G0_MPS2

    d = n / fs
    s = np.arange(n) / fs
    shape = 0.5 * (1.0 - np.cos(math.pi * s / d))
    theta = theta_from + (theta_to - theta_from) * shape
    theta_dot = (theta_to - theta_from) * 0.5 * math.pi / d * np.sin(math.pi * s / d)  # rad/s
    a_up_g = dz_m * 0.5 * (math.pi / d) ** 2 * np.cos(math.pi * s / d) / G0_MPS2
    f = _tilted_up(theta) * (1.0 + a_up_g)[:, None]  # the world's (1 g + a) up, in the tilted body frame
    w = np.zeros((n, 3))
    w[:, 1] = np.degrees(theta_dot)  # about the lateral axis
    return f, w


# ---------------------------------------------------------------- the schedule
def _n(rng, lo_hi, fs: float) -> int:
    return max(1, round(_u(rng, lo_hi) * fs))


def _activity(rng, kind: str, fs: float, r: Ranges):
    """[(period kind, active, f (m, 3), w (m, 3), params)] for one activity (one or three periods)."""
    if kind in ("walking", "running"):
        f, w, p = _gait(
            rng,
            _n(rng, r.activity_s, fs),
            fs,
            *(
                (r.walk_step_hz, r.walk_acc_g, r.walk_gyr_dps)
                if kind == "walking"
                else (r.run_step_hz, r.run_acc_g, r.run_gyr_dps)
            ),
            r.intensity_ratio,
        )
        return [(kind, True, f, w, p)]
    if kind == "jumping":
        f, w, p = _jumps(rng, fs, _n(rng, r.activity_s, fs), r)
        return [(kind, True, f, w, p)]
    if kind == "constant_rate":
        n = _n(rng, r.activity_s, fs)
        rate = _u(rng, r.constant_rate_dps) * (1.0 if rng.random() < 0.5 else -1.0)
        f, _, _ = _still(n)
        w = np.zeros((n, 3))
        w[:, 2] = rate  # about the vertical: the gravity reading does not change
        return [(kind, True, f, w, (("rate_dps", rate),))]
    if kind == "constant_acc":
        n = _n(rng, r.activity_s, fs)
        mag = _u(rng, r.constant_acc_g)
        v = rng.normal(size=3)
        v /= np.linalg.norm(v)  # uniform on the sphere
        f = np.tile(np.array([0.0, 0.0, 1.0]) + mag * v, (n, 1))
        return [(kind, True, f, np.zeros((n, 3)), (("acc_g", mag),))]
    if kind in ("sit_stand", "lie_stand"):
        sit = kind == "sit_stand"
        tilt = math.radians(_u(rng, r.sit_tilt_deg if sit else r.lie_tilt_deg))
        drop = _u(rng, r.sit_drop_m if sit else r.lie_drop_m)
        n_down, n_rest, n_up = (
            _n(rng, r.transition_s, fs),
            _n(rng, r.posture_rest_s, fs),
            _n(rng, r.transition_s, fs),
        )
        p = (("tilt_deg", math.degrees(tilt)), ("drop_m", drop))
        f_d, w_d = _transition(n_down, fs, 0.0, tilt, -drop)
        f_r, w_r, _ = _still(n_rest, tilt)
        f_u, w_u = _transition(n_up, fs, tilt, 0.0, drop)
        return [
            ("sit_down" if sit else "lie_down", True, f_d, w_d, p),
            ("seated" if sit else "lying", False, f_r, w_r, p),
            ("stand_up", True, f_u, w_u, p),
        ]
    raise SensorError(
        f"activity {kind!r}: use one of {', '.join(ACTIVITIES)}{did_you_mean(kind, ACTIVITIES)}"
    )


def _schedule(rng, n_total: int, fs: float, r: Ranges, activities: tuple[str, ...], sequence: bool = False):
    """Still, activity, still, activity, ... until n_total samples (the last period cut there); the
    activities drawn uniformly, or (``sequence``) taken in their order, cycling."""
    pieces, n, i = [], 0, 0
    while n < n_total:
        f, w, _ = _still(_n(rng, r.still_s, fs))
        group = [("still", False, f, w, ())]
        if n + f.shape[0] < n_total:
            kind = (
                activities[i % len(activities)]
                if sequence
                else activities[int(rng.integers(len(activities)))]
            )
            i += 1
            group += _activity(rng, kind, fs, r)
        for piece in group:
            if n >= n_total:
                break
            pieces.append(piece)
            n += piece[2].shape[0]
    return pieces


# ---------------------------------------------------------------- the synthesizer
def synthesize(
    rng,
    duration_s: float,
    *,
    fs_hz: float = 50.0,
    gravity_axis: str = "z",
    sigma_acc_g: float = 2.23e-3,
    sigma_gyr_dps: float = 0.05,
    acc_range_g: float = 3.0,
    gyr_range_dps: float = 500.0,
    ranges: Ranges = DEFAULT_RANGES,
    activities: tuple[str, ...] = ACTIVITIES,
    sequence: bool = False,
) -> Synth:
    """A recording of ``duration_s`` seconds at ``fs_hz`` (module docstring). ``rng``: a numpy
    Generator (or Streams, or an int seed); the same state gives bit-identical arrays.
    ``activities``: the activities to draw from (default all seven of the seed), uniformly; with
    ``sequence`` True, in their order, cycling (e.g. :data:`FIGURE2_SEQUENCE`, the seed's Figure 2:
    its section 3.1.1 draws "the intensity ... and also the length of each activity period" at
    random and says nothing of drawing the activities themselves)."""
    from flightmode.streams import as_streams

    fs = _positive(fs_hz, "fs_hz", "Hz")
    n_total = round(_positive(duration_s, "duration_s", "s") * fs)
    if n_total < 2:
        raise SensorError(
            f"duration_s = {duration_s}: gives {n_total} sample(s) at {fs:g} Hz; need at least 2"
        )
    for name, v, unit in (("sigma_acc_g", sigma_acc_g, "g"), ("sigma_gyr_dps", sigma_gyr_dps, "deg/s")):
        if not (math.isfinite(v) and v >= 0):
            raise SensorError(f"{name} = {v!r}: a noise standard deviation must be finite and >= 0 ({unit})")
    acc_range = _positive(acc_range_g, "acc_range_g", "g")
    gyr_range = _positive(gyr_range_dps, "gyr_range_dps", "deg/s")
    if acc_range <= 1.0:
        raise SensorError(f"acc_range_g = {acc_range_g}: the range must exceed the 1 g of gravity")
    acts = tuple(activities)
    if not acts:
        raise SensorError("activities is empty: give at least one of " + ", ".join(ACTIVITIES))
    for a in acts:
        if a not in ACTIVITIES:
            raise SensorError(
                f"activity {a!r}: use one of {', '.join(ACTIVITIES)}{did_you_mean(a, ACTIVITIES)}"
            )
    m = body_to_sensor(gravity_axis)

    streams = as_streams(rng)
    pieces = _schedule(streams.rng("schedule"), n_total, fs, ranges, acts, bool(sequence))
    f_body = np.concatenate([p[2] for p in pieces])[:n_total]
    w_body = np.concatenate([p[3] for p in pieces])[:n_total]
    periods, start = [], 0
    for kind, active, f, _, params in pieces:
        stop = min(n_total, start + f.shape[0])
        periods.append(Period(kind, start, stop, active, tuple((k, float(v)) for k, v in params)))
        start = stop
    marker = np.zeros(n_total, np.int8)
    for p in periods:
        if p.active:
            marker[p.start : p.stop] = 1

    acc = f_body @ m.T + streams.rng("noise/acc").normal(0.0, sigma_acc_g, (n_total, 3))
    gyr = w_body @ m.T + streams.rng("noise/gyr").normal(0.0, sigma_gyr_dps, (n_total, 3))
    np.clip(acc, -acc_range, acc_range, out=acc)  # saturation: the sensor outputs its rail
    np.clip(gyr, -gyr_range, gyr_range, out=gyr)
    t = np.arange(n_total) / fs
    for arr in (t, acc, gyr, marker):
        arr.flags.writeable = False
    return Synth(
        t,
        acc,
        gyr,
        marker,
        tuple(periods),
        fs,
        gravity_axis,
        float(sigma_acc_g),
        float(sigma_gyr_dps),
        acc_range,
        gyr_range,
        ranges,
    )


def still_recording(
    rng,
    duration_s: float,
    *,
    fs_hz: float = 50.0,
    gravity_axis: str = "z",
    sigma_acc_g: float = 2.23e-3,
    sigma_gyr_dps: float = 0.05,
    acc_range_g: float = 3.0,
    gyr_range_dps: float = 500.0,
) -> Synth:
    """The same sensor lying still for ``duration_s`` (a bench recording: the detectors' noise
    figures come from one, as on a real unit). Marker all 0."""
    from flightmode.streams import as_streams

    fs = _positive(fs_hz, "fs_hz", "Hz")
    n = round(_positive(duration_s, "duration_s", "s") * fs)
    if n < 2:
        raise SensorError(f"duration_s = {duration_s}: gives {n} sample(s) at {fs:g} Hz; need at least 2")
    acc_range = _positive(acc_range_g, "acc_range_g", "g")
    gyr_range = _positive(gyr_range_dps, "gyr_range_dps", "deg/s")
    m = body_to_sensor(gravity_axis)
    streams = as_streams(rng)
    acc = np.tile(m[:, 2], (n, 1)) + streams.rng("noise/acc").normal(0.0, sigma_acc_g, (n, 3))
    gyr = streams.rng("noise/gyr").normal(0.0, sigma_gyr_dps, (n, 3))
    np.clip(acc, -acc_range, acc_range, out=acc)
    np.clip(gyr, -gyr_range, gyr_range, out=gyr)
    return Synth(
        np.arange(n) / fs,
        acc,
        gyr,
        np.zeros(n, np.int8),
        (Period("still", 0, n, False),),
        fs,
        gravity_axis,
        float(sigma_acc_g),
        float(sigma_gyr_dps),
        acc_range,
        gyr_range,
    )


def _positive(v, name: str, unit: str) -> float:
    try:
        x = float(v)
    except (TypeError, ValueError):
        raise SensorError(f"{name} = {v!r}: must be a number ({unit})") from None
    if not (math.isfinite(x) and x > 0):
        raise SensorError(f"{name} = {v!r}: must be finite and > 0 ({unit})")
    return x


__all__ = [
    "ACTIVITIES",
    "DEFAULT_RANGES",
    "FIGURE2_SEQUENCE",
    "GRAVITY_AXES",
    "PERIOD_KINDS",
    "Period",
    "Ranges",
    "Synth",
    "body_to_sensor",
    "still_recording",
    "synthesize",
]
