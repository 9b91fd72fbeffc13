"""The bag around and during the flight: its timeline (segments aligned to the FlightTrack's events),
and the motion models that give its specific force (gait, pick-up and put-down transients). What
couples a stowed bag to the airframe (support and packing stages) is :mod:`flightmode.sim.sensor.mount`.

Timeline of a cabin handbag (the seed 000 case), in FlightTrack time (t = 0: aircraft parked at the
gate, engines off); the recording starts before t = 0 when the terminal part needs it:

    terminal_walk -> terminal_rest -> terminal_walk -> terminal_rest (gate) -> boarding (walk)
    -> stowed (under the seat / overhead bin / on a seat / on a lap), handled now and then in cruise
    -> deplaning (walk, after engines off) -> arrival_rest

A parcel in the hold: truck (road vibration) -> loading (handled) -> in_hold -> unloading (handled)
-> truck -> arrival_rest.

Stowage. Carry-on baggage must be stowed for pushback, taxi, takeoff and landing (14 CFR 121.589;
EASA Air OPS CAT.OP.MPA.160): a handbag given a ``cruise_placement`` (the empty seat beside, a lap)
rests at its ``placement`` until the cruise, is moved there ``CRUISE_MOVE_DELAY_S`` into it (a
handling, drawn uniformly) and put back at the end of the cruise (another handling); the in-cruise
handlings fall between the two.

Orientation. Off board and in hand, every put-down gives the sensor a uniformly random orientation.
On board, a handbag rests on its base with the sensor lying level in it, z up (an assumption: seed
000 does not say how its phone lay in flight; its static recordings had the Y axis along gravity),
yawed by ``stowed_yaw_deg`` from the fuselage axis (drawn uniformly when absent) and tilted by a
Rayleigh-distributed angle whose scale is the support's (``mount.PLACEMENTS``: 3 deg on a floor or
bin, 5 deg on a seat cushion, 8 deg on a lap; assumptions). With yaw 0 the sensor's x axis lies along
the fuselage, the axis the soft supports isolate best and seed 000 found quietest. A parcel is packed
any way up: a uniformly random orientation.

Gait (carried): vertical, lateral and fore-aft harmonics of the step frequency (1.6-2.2 Hz, drawn per
walk, with a slow random pace variation); amplitudes for a hand-carried bag are assumptions
(named in :class:`CarrierSpec`). Seed 001's synthesizer is the same idea (sums of harmonics with
random frequency and amplitude per activity).
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from flightmode.errors import CarrierError, did_you_mean
from flightmode.sim.sensor.mount import CABIN_ROWS, PACKINGS, PLACEMENTS
from flightmode.units import G0_MPS2 as G0

DEFAULT_PACKING = {"handbag": "soft", "parcel": "boxed"}
CRUISE_MOVE_DELAY_S = (60.0, 600.0)  # moved 1-10 min into the cruise, the seat-belt sign off: assumption
# placement -> the lever arm (AircraftProfile.locations_m) of its rigid-body motion; the cabin row
# (CarrierSpec.cabin_row) sets only the floor's vibration level, not this lever arm
LOCATION_OF = {
    "under_seat": "cabin_seat_mid",
    "seat": "cabin_seat_mid",
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
    packing: str | None = None  # soft / rigid / boxed; None: the kind's (handbag soft, parcel boxed)
    cabin_row: str | None = None  # front / mid / rear (the floor's vibration level); None: drawn per flight
    stowed_yaw_deg: float | None = None  # sensor x from the fuselage axis when stowed level; None: drawn
    cruise_placement: str | None = None  # where a handbag is moved for the cruise; None: it stays put

    @property
    def packing_name(self) -> str:
        return DEFAULT_PACKING[self.kind] if self.packing is None else self.packing

    def validate(self) -> None:
        if self.kind not in KINDS:
            raise CarrierError(
                f"carrier kind '{self.kind}'{did_you_mean(self.kind, KINDS)}: allowed {', '.join(KINDS)}"
            )
        if self.placement not in PLACEMENTS:
            raise CarrierError(
                f"carrier placement '{self.placement}'{did_you_mean(self.placement, PLACEMENTS)}: "
                f"allowed {', '.join(PLACEMENTS)}"
            )
        if self.kind == "parcel" and self.placement != "hold":
            raise CarrierError("a parcel travels in the hold: set placement = 'hold'")
        for name in (
            "terminal_walk_s",
            "terminal_rest_s",
            "gate_walk_s",
            "gate_rest_s",
            "boarding_s",
            "handling_s",
            "deplaning_s",
            "arrival_rest_s",
            "truck_s",
        ):
            if getattr(self, name) < 0:
                raise CarrierError(f"carrier {name} = {getattr(self, name)}: must be >= 0")
        for name in ("putdown_peak_g", "putdown_ms", "pickup_s"):
            if not getattr(self, name) > 0:
                raise CarrierError(f"carrier {name} = {getattr(self, name)}: must be > 0")
        if not self.pickup_height_m >= 0:
            raise CarrierError(f"carrier pickup_height_m = {self.pickup_height_m}: must be >= 0")
        if self.packing is not None and self.packing not in PACKINGS:
            raise CarrierError(
                f"carrier packing '{self.packing}'{did_you_mean(self.packing, PACKINGS)}: "
                f"allowed {', '.join(PACKINGS)}"
            )
        if self.cabin_row is not None and self.cabin_row not in CABIN_ROWS:
            raise CarrierError(
                f"carrier cabin_row '{self.cabin_row}'{did_you_mean(self.cabin_row, CABIN_ROWS)}: "
                f"allowed {', '.join(CABIN_ROWS)}"
            )
        if self.stowed_yaw_deg is not None and not 0.0 <= self.stowed_yaw_deg <= 360.0:
            raise CarrierError(f"carrier stowed_yaw_deg = {self.stowed_yaw_deg}: must be within 0-360")
        if self.cruise_placement is not None:
            cp = self.cruise_placement
            if cp not in PLACEMENTS:
                raise CarrierError(
                    f"carrier cruise_placement '{cp}'{did_you_mean(cp, PLACEMENTS)}: "
                    f"allowed {', '.join(PLACEMENTS)}"
                )
            if self.kind != "handbag":
                raise CarrierError("carrier cruise_placement: only a handbag is moved for the cruise")
            if LOCATION_OF[cp] != LOCATION_OF[self.placement]:
                same = [p for p in PLACEMENTS if LOCATION_OF[p] == LOCATION_OF[self.placement]]
                raise CarrierError(
                    f"carrier cruise_placement '{cp}': the bag stays at the passenger's seat; "
                    f"with placement '{self.placement}' allowed {', '.join(same)}"
                )


@dataclass(frozen=True, slots=True)
class Segment:
    t0_s: float
    t1_s: float
    state: str  # one of BAG_STATES
    phase: str | None  # bag-level phase label; None: the aircraft's phase
    orientation: np.ndarray = field(repr=False)  # (3, 3) sensor -> frame (world NED, or body)
    on_board: bool = False
    walking: bool = False
    placement: str | None = (
        None  # where a stowed bag rests on board (CarrierSpec.placement or cruise_placement)
    )


def _rot(rng: np.random.Generator) -> np.ndarray:
    from scipy.spatial.transform import Rotation

    return Rotation.random(random_state=rng).as_matrix()


LEVEL = np.diag([1.0, -1.0, -1.0])  # sensor -> body for a sensor lying level, z up, x forward


def stowed_rot(spec: CarrierSpec, rng: np.random.Generator, placement: str | None = None) -> np.ndarray:
    """The sensor's orientation (sensor -> body) when the bag is set down on board at ``placement``
    (default: the spec's; module docstring, "Orientation"): a handbag's sensor lies level (z up),
    yawed by ``stowed_yaw_deg`` (drawn uniformly when None) and tilted by a Rayleigh-distributed angle
    (scale: the support's ``tilt_deg``) about a horizontal axis of uniform direction; a parcel's is
    uniformly random. Draws (handbag): yaw, tilt, tilt direction, in this order (the yaw is drawn
    even when fixed, so that fixing it moves no other draw)."""
    from scipy.spatial.transform import Rotation

    if spec.kind == "parcel":
        return _rot(rng)
    yaw = rng.uniform(0.0, 360.0)
    tilt = rng.rayleigh(PLACEMENTS[placement or spec.placement].tilt_deg)
    az = rng.uniform(0.0, 2.0 * np.pi)
    if spec.stowed_yaw_deg is not None:
        yaw = spec.stowed_yaw_deg
    r = Rotation.from_euler("z", yaw, degrees=True) * Rotation.from_rotvec(
        np.radians(tilt) * np.array([np.cos(az), np.sin(az), 0.0])
    )
    return r.as_matrix() @ LEVEL


def orientation_angles(rot: np.ndarray) -> dict[str, float]:
    """How a stowed sensor lies in the aircraft (``rot``: sensor -> body): its x axis's yaw from the
    fuselage axis (0-360 deg, as ``stowed_yaw_deg``), its z axis's tilt from the up vertical, and the
    angle between its x axis and the fuselage axis folded to 0-90 deg (0: x fore-aft, the axis seed
    000 found quietest in flight; 90: x across the aisle or vertical)."""
    x, z = rot[:, 0], rot[:, 2]
    yaw = float(np.degrees(np.arctan2(x[1], x[0])) % 360.0)
    tilt = float(np.degrees(np.arccos(np.clip(-z[2], -1.0, 1.0))))  # body z is down
    x_fus = float(np.degrees(np.arccos(np.clip(abs(x[0]), 0.0, 1.0))))
    return {"yaw_deg": yaw, "tilt_deg": tilt, "x_from_fuselage_deg": x_fus}


def build_timeline(
    spec: CarrierSpec, events: dict[str, float], cruise: tuple[float, float] | None, rng: np.random.Generator
) -> list[Segment]:
    """Lay the bag's segments on the flight. ``events`` maps event names to times (engine_start,
    engines_off); ``cruise`` is the (start, end) of the cruise phase, where handling happens."""
    spec.validate()
    t_es, t_off = events["engine_start"], events["engines_off"]
    segs: list[Segment] = []
    if spec.kind == "handbag":
        t_stow = t_es - spec.stow_before_engine_start_s
        pre = [
            ("carried", "terminal_walk", spec.terminal_walk_s, True),
            ("resting", "terminal_rest", spec.terminal_rest_s, False),
            ("carried", "terminal_walk", spec.gate_walk_s, True),
            ("resting", "terminal_rest", spec.gate_rest_s, False),
            ("carried", "boarding", spec.boarding_s, True),
        ]
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
    # on board: stowed, with handling events spread over the cruise; a handbag with a cruise placement
    # is moved there after reaching cruise and back before the descent (module docstring, "Stowage")
    u_handling = np.empty(0)
    if cruise is not None and spec.handled_in_cruise > 0 and spec.kind == "handbag":
        c0, c1 = cruise
        if c1 - c0 - spec.handling_s > 0:
            u_handling = rng.uniform(0.0, 1.0, spec.handled_in_cruise)
    moves: list[tuple[float, str | None]] = []  # (t, placement after)
    w0 = w1 = 0.0  # where in-cruise handlings start: read only with a cruise (u_handling is empty without)
    if cruise is not None:
        c0, c1 = cruise
        w0, w1 = c0, c1 - spec.handling_s  # where in-cruise handlings start
        if spec.cruise_placement is not None:
            t_move = c0 + rng.uniform(*CRUISE_MOVE_DELAY_S)
            t_back = c1 - spec.handling_s
            if t_back - t_move > 3.0 * spec.handling_s:
                moves = [(t_move, spec.cruise_placement), (t_back, spec.placement)]
                w0, w1 = t_move + spec.handling_s, t_back - spec.handling_s
    events_on = sorted([(float(w0 + (w1 - w0) * u), None) for u in u_handling] + moves, key=lambda e: e[0])
    t_deplane = t_off + spec.deplane_after_engines_off_s
    cur, where = t_stow, spec.placement
    for h, after in events_on:
        if h > cur:
            segs.append(
                Segment(cur, h, stow_state, None, stowed_rot(spec, rng, where), True, placement=where)
            )
            segs.append(Segment(h, h + spec.handling_s, "handled", None, _rot(rng), True, True))
            cur = h + spec.handling_s
            where = after or where
    segs.append(
        Segment(cur, t_deplane, stow_state, None, stowed_rot(spec, rng, where), True, placement=where)
    )
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


def band_noise(
    n: int, fs_hz: float, band_hz: tuple[float, float], rms: float, rng: np.random.Generator
) -> np.ndarray:
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
