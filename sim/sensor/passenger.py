"""The passenger under a bag on the lap: breathing and posture shifts move the bag with the thighs.

A bag resting on a seated passenger's lap (placement ``lap``) is not on a still support: the
passenger breathes and now and then shifts in the seat. Both are slow (below 2 Hz), where the lap's
support stage (:mod:`flightmode.sim.sensor.mount`, 4-6 Hz) transmits the motion unchanged, so they
are added to the bag's specific force after the mount (:func:`lap_accel_mps2`: the second derivative
of a displacement, in body axes x forward, y right, z down), wherever the bag lies on a lap, in
every phase.

- Breathing: a quasi-periodic displacement ``A sin(phi(t))`` along a direction in the body's
  fore-aft/vertical plane (drawn per flight: the thighs lift, the abdomen pushes the bag forward),
  at the breathing rate, whose phase wanders slowly (breath-to-breath variability: a sum of slow
  sinusoids added to the phase). Rate: 14 breaths/min mean in quiet breathing (Ragnarsdottir and
  Kristinsdottir, "Breathing movements and breathing patterns among healthy men and women 20-69
  years of age", Respiration 73(1), 2006: 100 adults, results in the abstract); 12-20/min is the
  adult resting range of the vital-sign references. Amplitude: no measurement of the lap's or a
  lap-held object's breathing motion was found; quiet-breathing excursions of the abdominal wall
  are a few millimetres (Kaneko and Horie, "Breathing movements of the chest and abdominal wall in
  healthy subjects", Respiratory Care 57(9), 2012, 1442-1451, 100 adults, sitting and supine: the
  quiet-breathing distances are under a third of the deep-breathing ones; their table was not
  read), so the range is an assumption.
- Posture shifts and fidgets: Poisson events at a rate drawn per flight, each a smooth out-and-back
  displacement pulse (:func:`bump_accel`) of a drawn size and duration along a uniformly random
  direction; its peak acceleration is 4 pi^2 D / T^2 (0.79 m/s^2 for the nominal 2 cm out and back
  within 1 s; breathing's is (2 pi f)^2 A, 0.3 mg at the nominal 1.5 mm and 14/min, below the
  sensor's 2.23 mg noise). Seated people shift posture more the longer they sit and the less comfortable they are
  (in-chair movement measured by seat pressure mats: Fenety, Putnam and Walker, "In-chair
  movement: validity, reliability and implications for measuring sitting discomfort", Applied
  Ergonomics 31, 2000; Akkarakittichoke and Janwantanakul, Safety and Health at Work 8(2), 2017,
  212-219: healthy office workers shift more often than those with low back pain); neither's
  counts were read, so the rate, size and duration are assumptions.

Every parameter is declared in :data:`UNCERTAIN` and read with the run's overrides; per flight, each
is drawn log-uniformly within a factor ``passenger.flight_spread`` of its declared value (people
differ), per shift the size and duration again. Draws come from the one generator the caller gives
(the sensing stage's stream ``lap``), in the order :func:`draw_lap` states.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field

import numpy as np

from flightmode.uncertain import Uncertain, value_of

BREATH_RATE_HZ = Uncertain(
    "passenger.breath_rate_hz",
    14.0 / 60.0,
    12.0 / 60.0,
    20.0 / 60.0,
    "Hz",
    "Ragnarsdottir and Kristinsdottir, Respiration 73(1) 2006 (abstract): mean 14 breaths/min in quiet "
    "breathing, 100 adults; range: the adult resting 12-20/min of vital-sign references",
    "a bag on a lap: the breathing rate (median of the flights')",
)
BREATH_AMPLITUDE_M = Uncertain(
    "passenger.breath_amplitude_m",
    1.5e-3,
    0.3e-3,
    5.0e-3,
    "m",
    "assumption: quiet-breathing abdominal-wall excursions are a few mm (Kaneko and Horie, Respir. Care "
    "57(9) 2012, values not read); a bag on the thighs follows part of it",
    "a bag on a lap: the breathing displacement's amplitude (median of the flights')",
)
BREATH_VARIABILITY = Uncertain(
    "passenger.breath_variability",
    0.1,
    0.02,
    0.3,
    "1",
    "assumption: breath-to-breath rate variation of quiet breathing, a tenth (a fiftieth to a third)",
    "a bag on a lap: the breathing rate's slow wander (relative)",
)
SHIFT_RATE_PER_MIN = Uncertain(
    "passenger.shift_rate_per_min",
    0.5,
    0.1,
    3.0,
    "1/min",
    "assumption: in-chair movements are counted in seated-comfort studies (Fenety et al., Appl. Ergon. "
    "31, 2000; Akkarakittichoke and Janwantanakul, Saf. Health Work 8(2), 2017), their rates not read; "
    "one shift every 20 s to every 10 min",
    "a bag on a lap: how often the passenger shifts or fidgets (median of the flights')",
)
SHIFT_DISPLACEMENT_M = Uncertain(
    "passenger.shift_displacement_m",
    0.02,
    0.005,
    0.06,
    "m",
    "assumption: a posture shift moves the thighs by millimetres (a fidget) to centimetres (resettling)",
    "a bag on a lap: the size of a posture shift's displacement pulse (median)",
)
SHIFT_DURATION_S = Uncertain(
    "passenger.shift_duration_s",
    1.0,
    0.4,
    2.5,
    "s",
    "assumption: a deliberate human movement of a few cm lasts 0.5-2 s (cf. the minimum-jerk reach, "
    "Flash and Hogan, J. Neurosci. 5(7), 1985)",
    "a bag on a lap: the duration of a posture shift's displacement pulse (median)",
)
FLIGHT_SPREAD = Uncertain(
    "passenger.flight_spread",
    1.5,
    1.0,
    2.5,
    "1",
    "assumption: passengers differ; each flight's values lie within this factor of the medians (log-uniform)",
    "a bag on a lap: the spread of the passenger's values between flights and between shifts",
)
UNCERTAIN = (
    BREATH_RATE_HZ,
    BREATH_AMPLITUDE_M,
    BREATH_VARIABILITY,
    SHIFT_RATE_PER_MIN,
    SHIFT_DISPLACEMENT_M,
    SHIFT_DURATION_S,
    FLIGHT_SPREAD,
)
WANDER_HZ = (0.005, 0.03)  # the breathing phase's wander terms' frequencies (a few breaths to minutes)
N_WANDER = 3
# the peak |acceleration| of bump_accel per unit displacement, times T^2: 4 pi^2 (at mid-pulse)
BUMP_PEAK = 4.0 * np.pi**2


def bump_accel(u: np.ndarray) -> np.ndarray:
    """The acceleration shape of a smooth out-and-back displacement pulse d(u) = sin^4(pi u), u in
    [0, 1] the pulse's time over its duration: d''(u) = 4 pi^2 sin^2(pi u) (3 - 4 sin^2(pi u))
    (zero outside [0, 1]). It starts and ends at zero acceleration (no jolt in the acceleration
    itself), leaves no net velocity or displacement (the bag, or the aircraft, ends where it
    started, at rest), and peaks at -4 pi^2 mid-pulse (:data:`BUMP_PEAK`), +2.25 pi^2 at the flanks.
    Multiply by D / T^2 for a displacement D over T seconds."""
    u = np.asarray(u, float)
    s2 = np.sin(np.pi * np.clip(u, 0.0, 1.0)) ** 2
    return np.where((u >= 0.0) & (u <= 1.0), 4.0 * np.pi**2 * s2 * (3.0 - 4.0 * s2), 0.0)


@dataclass(frozen=True, slots=True)
class LapDraw:
    """One flight's passenger (:func:`draw_lap`): the breathing, and the posture shifts over the span
    the draw covers. Directions are unit vectors in body axes (x forward, y right, z down)."""

    breath_rate_hz: float
    breath_amplitude_m: float
    breath_dir: np.ndarray  # (3,)
    breath_phase_rad: float
    wander_hz: np.ndarray  # (N_WANDER,) the phase wander's frequencies
    wander_rad: np.ndarray  # (N_WANDER,) their amplitudes
    wander_phase_rad: np.ndarray  # (N_WANDER,)
    shift_rate_per_s: float
    shift_t_s: np.ndarray = field(repr=False)  # (m,) start times, sorted
    shift_displacement_m: np.ndarray = field(repr=False)  # (m,)
    shift_duration_s: np.ndarray = field(repr=False)  # (m,)
    shift_dir: np.ndarray = field(repr=False)  # (m, 3)

    def as_dict(self) -> dict:
        return {
            "breath_rate_hz": self.breath_rate_hz,
            "breath_amplitude_m": self.breath_amplitude_m,
            "shift_rate_per_min": self.shift_rate_per_s * 60.0,
            "shifts": int(self.shift_t_s.shape[0]),
        }


def _spread(rng: np.random.Generator, k: float, size=None):
    """Log-uniform factors within [1/k, k]."""
    return np.exp(rng.uniform(-np.log(k), np.log(k), size))


def _unit(rng: np.random.Generator, m: int) -> np.ndarray:
    v = rng.standard_normal((m, 3))
    return v / np.maximum(np.linalg.norm(v, axis=1, keepdims=True), 1e-12)


def draw_lap(
    t0_s: float, t1_s: float, rng: np.random.Generator, overrides: Mapping[str, float] | None = None
) -> LapDraw:
    """One flight's passenger over [t0_s, t1_s]. Draws, in this order: the breathing rate, amplitude,
    direction (angle from vertical, uniform 0-90 deg, forward), phase, the wander's frequencies and
    phases; the shift rate, the number of shifts (Poisson), their start times (uniform), sizes and
    durations (log-uniform about the medians) and directions (uniform on the sphere)."""
    k = value_of(FLIGHT_SPREAD, overrides)
    rate = value_of(BREATH_RATE_HZ, overrides) * float(_spread(rng, k))
    amp = value_of(BREATH_AMPLITUDE_M, overrides) * float(_spread(rng, k))
    ang = rng.uniform(0.0, 0.5 * np.pi)
    phase = rng.uniform(0.0, 2.0 * np.pi)
    w_hz = rng.uniform(*WANDER_HZ, N_WANDER)
    w_phase = rng.uniform(0.0, 2.0 * np.pi, N_WANDER)
    # each term's frequency deviation eps nu is variability x rate / sqrt(N): the sum's spread of
    # instantaneous rate is about variability x rate / sqrt(2)
    w_rad = value_of(BREATH_VARIABILITY, overrides) * rate / (w_hz * np.sqrt(N_WANDER))
    shift_rate = value_of(SHIFT_RATE_PER_MIN, overrides) / 60.0 * float(_spread(rng, k))
    m = int(rng.poisson(shift_rate * max(t1_s - t0_s, 0.0)))
    t = np.sort(rng.uniform(t0_s, t1_s, m))
    disp = value_of(SHIFT_DISPLACEMENT_M, overrides) * _spread(rng, k, m)
    dur = value_of(SHIFT_DURATION_S, overrides) * _spread(rng, k, m)
    return LapDraw(
        rate,
        amp,
        np.array([np.sin(ang), 0.0, -np.cos(ang)]),
        phase,
        w_hz,
        w_rad,
        w_phase,
        shift_rate,
        t,
        disp,
        dur,
        _unit(rng, m),
    )


def breathing_accel_mps2(t_s: np.ndarray, d: LapDraw) -> np.ndarray:
    """The breathing's acceleration (3, n), body axes, at times ``t_s``: the exact second derivative
    of A sin(phi), phi = 2 pi f t + phase + sum eps_i sin(2 pi nu_i t + theta_i), a closed form of
    t, so chunks join seamlessly."""
    t = np.asarray(t_s, float)
    arg = 2.0 * np.pi * d.wander_hz[:, None] * t[None, :] + d.wander_phase_rad[:, None]
    w = 2.0 * np.pi * d.wander_hz[:, None]
    phi = (
        2.0 * np.pi * d.breath_rate_hz * t + d.breath_phase_rad + (d.wander_rad[:, None] * np.sin(arg)).sum(0)
    )
    dphi = 2.0 * np.pi * d.breath_rate_hz + (d.wander_rad[:, None] * w * np.cos(arg)).sum(0)
    ddphi = -(d.wander_rad[:, None] * w * w * np.sin(arg)).sum(0)
    acc = d.breath_amplitude_m * (np.cos(phi) * ddphi - np.sin(phi) * dphi * dphi)
    return d.breath_dir[:, None] * acc[None, :]


def shifts_accel_mps2(t_s: np.ndarray, d: LapDraw) -> np.ndarray:
    """The posture shifts' acceleration (3, n), body axes, at times ``t_s`` (sorted): each shift a
    :func:`bump_accel` pulse of its displacement over its duration along its direction."""
    t = np.asarray(t_s, float)
    out = np.zeros((3, t.shape[0]))
    if t.shape[0] == 0 or d.shift_t_s.shape[0] == 0:
        return out
    live = (d.shift_t_s <= t[-1]) & (d.shift_t_s + d.shift_duration_s >= t[0])
    for t0, dur, disp, u in zip(
        d.shift_t_s[live], d.shift_duration_s[live], d.shift_displacement_m[live], d.shift_dir[live]
    ):  # the few shifts of this stretch; each pulse vectorised over its samples
        a, b = np.searchsorted(t, [t0, t0 + dur])
        out[:, a:b] += u[:, None] * (disp / (dur * dur) * bump_accel((t[a:b] - t0) / dur))[None, :]
    return out


def lap_accel_mps2(t_s: np.ndarray, d: LapDraw) -> np.ndarray:
    """The passenger's motion under the bag (3, n), body axes, m/s^2: breathing plus shifts. Added
    to the bag's specific force (f = a - g: the motion's acceleration adds as it is)."""
    return breathing_accel_mps2(t_s, d) + shifts_accel_mps2(t_s, d)


__all__ = [
    "UNCERTAIN",
    "LapDraw",
    "bump_accel",
    "breathing_accel_mps2",
    "draw_lap",
    "lap_accel_mps2",
    "shifts_accel_mps2",
]
