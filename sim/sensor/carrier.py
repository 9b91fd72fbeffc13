"""The bag around and during the flight: its timeline (segments aligned to the FlightTrack's events),
and the motion models that give its specific force (gait, pick-up and put-down transients, the spring-damper
mount that couples a stowed bag to the airframe).

Timeline of a cabin handbag (the seed 000 case), in FlightTrack time (t = 0: aircraft parked at the
gate, engines off); the recording starts before t = 0 when the terminal part needs it:

    terminal_walk -> terminal_rest -> terminal_walk -> terminal_rest (gate) -> boarding (walk)
    -> stowed (under the seat / overhead bin / on a lap), handled now and then in cruise
    -> deplaning (walk, after engines off) -> arrival_rest

A parcel in the hold: truck (road vibration) -> loading (handled) -> in_hold -> unloading (handled)
-> truck -> arrival_rest. Every put-down gives the sensor a new random orientation.

Gait (carried): vertical, lateral and fore-aft harmonics of the step frequency (1.6-2.2 Hz, drawn per
walk, with a slow random pace variation); amplitudes for a hand-carried bag are assumptions
(named in :class:`CarrierSpec`). Seed 001's synthesizer is the same idea (sums of harmonics with
random frequency and amplitude per activity).
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from flightmode.errors import CarrierError, did_you_mean
from flightmode.units import G0_MPS2 as G0

PLACEMENTS = {  # natural frequency (Hz) and damping ratio of the bag-on-support mount, per axis
    "under_seat": ((12.0, 12.0, 15.0), 0.25),
    "overhead_bin": ((10.0, 10.0, 12.0), 0.2),
    "lap": ((4.0, 4.0, 5.0), 0.45),
    "hold": ((30.0, 30.0, 35.0), 0.1),
}
LOCATION_OF = {
    "under_seat": "cabin_seat_mid",
    "overhead_bin": "overhead_bin_mid",
    "lap": "cabin_seat_mid",
    "hold": "aft_hold",
}
KINDS = ("handbag", "parcel")
BAG_STATES = ("carried", "resting", "stowed", "in_hold", "handled")



@dataclass(frozen=True, slots=True)
class CarrierSpec:
    kind: str = "handbag"
    placement: str = "under_seat"
    terminal_walk_s: float = 240.0
    terminal_rest_s: float = 600.0
    gate_walk_s: float = 120.0
    gate_rest_s: float = 900.0
    boarding_s: float = 150.0
    stow_before_engine_start_s: float = 60.0
    handled_in_cruise: int = 1  # times the passenger takes the bag out and puts it back in cruise
    handling_s: float = 30.0
    deplane_after_engines_off_s: float = 120.0
    deplaning_s: float = 240.0
    arrival_rest_s: float = 900.0
    truck_s: float = 1200.0  # parcel
    gait_vertical_g: float = 0.25
    gait_lateral_g: float = 0.08
    gait_fore_aft_g: float = 0.12
    putdown_peak_g: float = 1.5
    putdown_ms: float = 40.0
    pickup_height_m: float = 0.4  # lifted this far off its support when picked up
    pickup_s: float = 0.8  # over this long (peak 0.37 g with the defaults)

    def validate(self) -> None:
        if self.kind not in KINDS:
            raise CarrierError(f"carrier kind '{self.kind}'{did_you_mean(self.kind, KINDS)}: allowed {', '.join(KINDS)}")
        if self.placement not in PLACEMENTS:
            raise CarrierError(
                f"carrier placement '{self.placement}'{did_you_mean(self.placement, PLACEMENTS)}: "
                f"allowed {', '.join(PLACEMENTS)}"
            )
        if self.kind == "parcel" and self.placement != "hold":
            raise CarrierError("a parcel travels in the hold: set placement = 'hold'")
        for name in ("terminal_walk_s", "terminal_rest_s", "gate_walk_s", "gate_rest_s", "boarding_s",
                     "handling_s", "deplaning_s", "arrival_rest_s", "truck_s"):
            if getattr(self, name) < 0:
                raise CarrierError(f"carrier {name} = {getattr(self, name)}: must be >= 0")
        for name in ("putdown_peak_g", "putdown_ms", "pickup_s"):
            if not getattr(self, name) > 0:
                raise CarrierError(f"carrier {name} = {getattr(self, name)}: must be > 0")
        if not self.pickup_height_m >= 0:
            raise CarrierError(f"carrier pickup_height_m = {self.pickup_height_m}: must be >= 0")


@dataclass(frozen=True, slots=True)
class Segment:
    t0_s: float
    t1_s: float
    state: str  # one of BAG_STATES
    phase: str | None  # bag-level phase label; None: the aircraft's phase
    orientation: np.ndarray = field(repr=False)  # (3, 3) sensor -> frame (world NED, or body)
    on_board: bool = False
    walking: bool = False


def _rot(rng: np.random.Generator) -> np.ndarray:
    from scipy.spatial.transform import Rotation

    return Rotation.random(random_state=rng).as_matrix()


def build_timeline(spec: CarrierSpec, events: dict[str, float], cruise: tuple[float, float] | None,
                   rng: np.random.Generator) -> list[Segment]:
    """Lay the bag's segments on the flight. ``events`` maps event names to times (engine_start,
    engines_off); ``cruise`` is the (start, end) of the cruise phase, where handling happens."""
    spec.validate()
    t_es, t_off = events["engine_start"], events["engines_off"]
    segs: list[Segment] = []
    if spec.kind == "handbag":
        t_stow = t_es - spec.stow_before_engine_start_s
        pre = [("carried", "terminal_walk", spec.terminal_walk_s, True),
               ("resting", "terminal_rest", spec.terminal_rest_s, False),
               ("carried", "terminal_walk", spec.gate_walk_s, True),
               ("resting", "terminal_rest", spec.gate_rest_s, False),
               ("carried", "boarding", spec.boarding_s, True)]
        stow_state = "stowed"
    else:
        t_stow = t_es - spec.stow_before_engine_start_s
        pre = [("carried", "truck", spec.truck_s, False), ("handled", "loading", spec.boarding_s, True)]
        stow_state = "in_hold"
    t = t_stow - sum(p[2] for p in pre)
    for state, phase, dur, walking in pre:
        if dur > 0:
            segs.append(Segment(t, t + dur, state, phase, _rot(rng), False, walking))
        t += dur
    # on board: stowed, with handling events spread over the cruise
    handling = []
    if cruise is not None and spec.handled_in_cruise > 0 and spec.kind == "handbag":
        c0, c1 = cruise
        span = c1 - c0 - spec.handling_s
        if span > 0:
            handling = sorted(rng.uniform(c0, c0 + span, spec.handled_in_cruise))
    t_deplane = t_off + spec.deplane_after_engines_off_s
    cur = t_stow
    for h in handling:
        if h > cur:
            segs.append(Segment(cur, h, stow_state, None, _rot(rng), True))
            segs.append(Segment(h, h + spec.handling_s, "handled", None, _rot(rng), True, True))
            cur = h + spec.handling_s
    segs.append(Segment(cur, t_deplane, stow_state, None, _rot(rng), True))
    post = [("carried", "deplaning", spec.deplaning_s, True)]
    if spec.kind == "parcel":
        post = [("handled", "unloading", spec.deplaning_s, True), ("carried", "truck", spec.truck_s, False)]
    t = t_deplane
    for state, phase, dur, walking in post:
        segs.append(Segment(t, t + dur, state, phase, _rot(rng), False, walking))
        t += dur
    segs.append(Segment(t, t + spec.arrival_rest_s, "resting", "arrival_rest", _rot(rng), False))
    return segs


def gait_accel_mps2(t_s: np.ndarray, spec: CarrierSpec, rng: np.random.Generator) -> np.ndarray:
    """Walking acceleration (N, 3) in a local N/E/Down frame heading north (x fore-aft, y lateral,
    z down): step-frequency harmonics with a slowly wandering pace."""
    n = t_s.shape[0]
    if n == 0:
        return np.zeros((0, 3))
    dt = float(t_s[1] - t_s[0]) if n > 1 else 1.0
    f_step = rng.uniform(1.6, 2.2)
    # pace variation: +-5 % random walk, smoothed (a 5-s moving average of white noise)
    w = rng.standard_normal(n)
    k = max(1, min(n, int(5.0 / dt)))
    c = np.concatenate([[0.0], np.cumsum(w)])
    idx = np.arange(n)
    lo, hi = np.clip(idx - k // 2, 0, n), np.clip(idx + k // 2 + 1, 0, n)
    pace = (c[hi] - c[lo]) / np.sqrt(k) * 0.05 / 3.0  # moving sum over ~5 s, about +-5 % (3 sigma)
    phase = 2 * np.pi * np.cumsum(f_step * (1.0 + pace)) * dt + rng.uniform(0, 2 * np.pi)
    # sines in single precision (30x faster than double here): a phase of up to 1e4 rad in a long
    # walk rounds to within 1e-3 rad, far below the pace variation itself
    phase = phase.astype(np.float32)
    a = np.empty((n, 3))
    a[:, 0] = spec.gait_fore_aft_g * (np.sin(phase) + 0.3 * np.sin(2 * phase + 0.5))
    a[:, 1] = spec.gait_lateral_g * np.sin(0.5 * phase + 0.3)
    a[:, 2] = -spec.gait_vertical_g * (np.sin(phase + 1.0) + 0.4 * np.sin(2 * phase))
    return a * G0


def band_noise(n: int, fs_hz: float, band_hz: tuple[float, float], rms: float, rng: np.random.Generator) -> np.ndarray:
    """(n, 3) white noise band-limited to ``band_hz`` (2nd-order Butterworth, zero phase) and scaled
    to ``rms`` per axis; zeros for fewer than 30 samples."""
    from scipy.signal import butter, sosfiltfilt

    if n < 30:
        return np.zeros((n, 3))
    sos = butter(2, [band_hz[0], min(band_hz[1], 0.45 * fs_hz)], btype="band", fs=fs_hz, output="sos")
    x = sosfiltfilt(sos, rng.standard_normal((n, 3)), axis=0)
    return x * (rms / max(float(x.std()), 1e-12))


def handling_accel_mps2(n: int, dt: float, rng: np.random.Generator) -> np.ndarray:
    """Arm motion while a bag is held (0.5-3 Hz band-limited, about 0.15 g RMS).

    Built as the second derivative of a band-limited *displacement* tapered to zero at both ends
    (a Tukey window), so the bag ends where it started, at rest: a random acceleration alone would
    leave it with a random net velocity (tens of cm/s after 30 s), i.e. flying through the cabin
    for anything that integrates it (nav/)."""
    if n < 30:
        return np.zeros((n, 3))
    from scipy.signal.windows import tukey

    x = band_noise(n, 1.0 / dt, (0.5, 3.0), 1.0, rng) * tukey(n, min(1.0, 2.0 / (n * dt)))[:, None]
    a = np.zeros_like(x)
    a[1:-1] = (x[2:] - 2.0 * x[1:-1] + x[:-2]) / (dt * dt)  # sums to zero velocity change
    return a * (0.15 * G0 / max(float(a.std()), 1e-12))


def road_accel_mps2(n: int, dt: float, rng: np.random.Generator) -> np.ndarray:
    """A parcel in a van: road vibration, 1-15 Hz band-limited, about 0.05 g RMS (assumption)."""
    x = band_noise(n, 1.0 / dt, (1.0, 15.0), 0.05 * G0, rng)
    x[:, 2] *= 1.5  # mostly vertical
    return x


def putdown_pulse_mps2(n: int, dt: float, spec: CarrierSpec) -> np.ndarray:
    """Setting the bag down, along the frame's down axis (positive: upward specific force): the last
    few centimetres of lowering (a gentle negative half-sine over 0.15 s) then the stop, a half-sine
    shock of ``putdown_peak_g`` over ``putdown_ms``. The two impulses cancel, so the bag ends at
    rest (a shock alone would leave it a net 0.4 m/s, which a path estimator would integrate)."""
    m = max(2, int(round(spec.putdown_ms / 1000.0 / dt)))
    m0 = max(2, int(round(0.15 / dt)))
    p = np.zeros(n)
    shock = spec.putdown_peak_g * G0 * np.sin(np.pi * (np.arange(m) + 0.5) / m)
    lower = -np.sin(np.pi * (np.arange(m0) + 0.5) / m0)
    lower *= shock.sum() / -lower.sum()
    pulse = np.concatenate([lower, shock])[:n]
    p[: pulse.shape[0]] = pulse
    return p


def pickup_pulse_mps2(dt: float, spec: CarrierSpec) -> np.ndarray:
    """Picking the bag up, along the frame's down axis with the sign of :func:`putdown_pulse_mps2`
    (positive: upward specific force): raised by ``pickup_height_m`` over ``pickup_s`` along a
    minimum-jerk path (Flash and Hogan's model of a human reach, h = H (10 u^3 - 15 u^4 + 6 u^5)),
    so it first pulls harder than gravity (accelerating up, peak 5.77 H / T^2: 0.37 g with the
    defaults), then less, starting and ending without a jolt. The acceleration is the exact second
    difference of that path, whose first and last steps are equal (it is point-symmetric), so the
    impulses cancel to rounding: the lift leaves no net velocity (nav/ integrates it to a 0.4 m
    rise, not a drift)."""
    m = max(3, int(round(spec.pickup_s / dt)))
    u = np.arange(m + 2) / (m + 1)
    h = spec.pickup_height_m * u**3 * (10.0 - 15.0 * u + 6.0 * u * u)
    return (h[2:] - 2.0 * h[1:-1] + h[:-2]) / (dt * dt)


def mount_sos(placement: str, fs_hz: float) -> list[np.ndarray]:
    """Per-axis base-excitation transmissibility of the spring-damper mount, as SOS (bilinear).

    H(s) = (2 zeta wn s + wn^2) / (s^2 + 2 zeta wn s + wn^2): unity at DC (the bag feels the steady
    specific force of the floor), resonant near fn, and -40 dB/decade... -20 dB/decade above.
    """
    from scipy.signal import bilinear, tf2sos

    fns, zeta = PLACEMENTS[placement]
    out = []
    for fn in fns:
        wn = 2 * np.pi * fn
        b, a = bilinear([2 * zeta * wn, wn * wn], [1.0, 2 * zeta * wn, wn * wn], fs=fs_hz)
        out.append(tf2sos(b, a))
    return out
