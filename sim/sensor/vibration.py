"""Airframe vibration at the cabin floor / hold, generated at the internal rate (>= 1 kHz) so that
the accelerometer's own filter and sampling decide what survives (aliasing included).

Components (all amplitudes are flightmode assumptions: no public cabin or cargo vibration PSD was
found, and Mansfield and Aggarwal's review of 26 in-aircraft studies (Vibration 5(1), 2022) gives
no usable magnitudes; they are named parameters of :class:`VibrationModel` and documented here):

- engine lines: each engine's fan (N1) and core (N2) rotation, f = rpm / 60 with the N1 first and
  second harmonics; amplitude 0.5 + 0.5 N1/100 of its full-power value while running (idle is
  already felt: seed 000 section 2), fading out below 15 % N1;
- airframe structural modes between 10 and 30 Hz: lightly damped resonators driven by white noise
  whose level rises with engine power and with dynamic pressure (airflow);
- runway: roughness (broadband, level proportional to ground speed) and pavement-joint bumps every
  ``joint_spacing_m`` (an impulse train at v / spacing Hz) while on the gear;
- no vibration at all with the engines stopped and the aircraft at rest.

Directions: body z (vertical) carries the most, then y and x (``axis_share``).

Engine spool speeds (rpm at 100 %): CFM56-5B N1 5000 / N2 14460 (EASA type certificate data sheet E.067); CFM56-3 (737) 5490 /
15183; Rolls-Royce Tay 650 (fokker100) 8400 / 12500; Trent 1000 (787-8) 2683 / 13391 (public type
certificate data sheets, rounded).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from functools import lru_cache

from scipy.signal import iirpeak, lfilter, sosfilt, tf2sos

ENGINE_RPM = {  # model -> (N1 rpm at 100 %, N2 rpm at 100 %)
    "A320": (5000.0, 14460.0),
    "737": (5490.0, 15183.0),
    "fokker100": (8400.0, 12500.0),
    "787-8": (2683.0, 13391.0),
}


@dataclass(frozen=True, slots=True)
class VibrationModel:
    """Amplitudes calibrated against seed 000, the only measured evidence at hand: engines running
    are visible at once (section 2, Fig. 2), and in flight 1 the per-axis moving variance sat below
    4 sigma^2 with probabilities 8e-2 (x), 2e-3 (y), 2e-6 (z) (Table 4). These values do not reproduce
    that table: on the default flight the stowed handbag's per-axis fractions of in-flight checks under
    4 sigma^2 are about 4e-4 (measured; the vibration model is too uniform and the air too still)."""

    n1_line_g: float = 4.5e-3  # first N1 harmonic at 100 % N1, per engine
    n1_h2_g: float = 1.5e-3  # second N1 harmonic at 100 % N1
    n2_line_g: float = 1.2e-3  # N2 line at 100 % N2
    mode_hz: tuple[float, ...] = (11.0, 16.5, 22.0, 27.5)  # airframe modes (10-30 Hz)
    mode_q: float = 8.0
    mode_engine_g: float = 6.0e-3  # modal RMS per mode at 100 % N1 (both engines)
    mode_airflow_g: float = 6.0e-3  # modal RMS per mode at q = 15 kPa (cruise-like)
    roughness_g_per_mps: float = 0.45e-3  # runway roughness RMS per m/s of ground speed
    joint_spacing_m: float = 5.0
    joint_impulse_g: float = 20.0e-3  # peak of one joint bump (decays through the modes)
    axis_share: tuple[float, float, float] = (0.35, 0.5, 1.0)  # x, y, z relative weights


@dataclass(frozen=True, slots=True)
class VibrationState:
    """Filter states and oscillator phases carried from one chunk to the next."""

    phases: np.ndarray  # (n_engines, 3) radians: N1, 2*N1, N2
    detune: np.ndarray  # (n_engines,) relative spool-speed offset: real engines never run in sync
    mode_zi: np.ndarray  # (n_sections, 3 axes, 2): state of the mode bank
    joint_pos_m: float  # distance rolled since the last joint


def initial_state(n_engines: int, model: VibrationModel, fs_hz: float, rng: np.random.Generator) -> VibrationState:
    return VibrationState(
        phases=rng.uniform(0.0, 2 * np.pi, (n_engines, 3)),
        # the FDM runs both engines at identical N1; with identical frequencies the two lines would
        # add with a fixed random phase (and could cancel). Real engines differ by a few tenths of
        # a percent, so each gets a fixed offset within +-0.3 % (the lines beat instead)
        detune=rng.uniform(-0.003, 0.003, n_engines),
        mode_zi=np.zeros((_mode_bank(model.mode_hz, model.mode_q, fs_hz).shape[0], 3, 2)),
        joint_pos_m=float(rng.uniform(0.0, model.joint_spacing_m)),
    )


def vibration_g(
    n1_pct: np.ndarray,
    n2_pct: np.ndarray,
    qbar_pa: np.ndarray,
    ground_speed_mps: np.ndarray,
    on_ground: np.ndarray,
    fs_hz: float,
    aircraft: str,
    model: VibrationModel,
    state: VibrationState,
    rng: np.random.Generator,
) -> tuple[np.ndarray, VibrationState]:
    """Vibration (3, N) in g, body axes x, y, z as rows, for one chunk of inputs at ``fs_hz``;
    returns the new state.

    Inputs are per internal sample, channels first: N1 and N2 (n_engines, N) in %, dynamic pressure
    (N,) in Pa, ground speed (N,) in m/s, weight on wheels (N,) bool.

    The line sines are evaluated in single precision (30x faster than double here): the phase, up
    to 1e5 rad within a 60 s chunk, is accumulated in double and rounded to float32 only for the
    sine, a phase error below 0.004 rad, i.e. below 20 ug on the strongest line (sensor noise:
    2.23 mg).
    """
    n = n1_pct.shape[1]
    rpm1, rpm2 = ENGINE_RPM[aircraft]
    dt = 1.0 / fs_hz
    share = np.asarray(model.axis_share)
    level_e = _running_level(n1_pct)  # (n_engines, N)
    # engine lines: phase = integral of 2 pi f dt, continuous across chunks
    phases = state.phases.copy()
    line = np.zeros(n, dtype=np.float32)
    for e in range(n1_pct.shape[0]):
        w1 = 2.0 * np.pi * dt * rpm1 / 6000.0 * (1.0 + state.detune[e])  # rad per sample per % N1
        w2 = 2.0 * np.pi * dt * rpm2 / 6000.0 * (1.0 + state.detune[e])
        th1 = np.cumsum(n1_pct[e]) * w1  # fan rotation angle since the chunk start
        th2 = np.cumsum(n2_pct[e]) * w2
        wave = model.n1_line_g * np.sin((phases[e, 0] + th1).astype(np.float32))
        wave += model.n1_h2_g * np.sin((phases[e, 1] + 2.0 * th1).astype(np.float32))
        wave += model.n2_line_g * np.sin((phases[e, 2] + th2).astype(np.float32))
        line += level_e[e] * wave
        if n:
            phases[e] = (phases[e] + np.array([th1[-1], 2.0 * th1[-1], th2[-1]])) % (2.0 * np.pi)
    # structural modes: white noise through resonators, excitation level from power and airflow
    power = level_e.mean(axis=0)
    level = model.mode_engine_g * power + model.mode_airflow_g * np.clip(qbar_pa / 15000.0, 0.0, 2.0)
    # runway: roughness and joint bumps feed the same modes while rolling
    rolling = on_ground & (ground_speed_mps > 0.5)
    rough = model.roughness_g_per_mps * ground_speed_mps * rolling
    dist = state.joint_pos_m + np.cumsum(ground_speed_mps * rolling) * dt
    joints = np.zeros(n)
    k = np.floor(dist / model.joint_spacing_m)
    hit = np.flatnonzero(np.diff(np.concatenate([[np.floor(state.joint_pos_m / model.joint_spacing_m)], k])) > 0)
    joints[hit] = model.joint_impulse_g
    new_joint = float(dist[-1] % model.joint_spacing_m) if n else state.joint_pos_m
    # the modes as one parallel bank (each resonator normalised to unit output RMS for unit white
    # input), realised as one filter: one noise stream per axis drives all modes
    sos = _mode_bank(model.mode_hz, model.mode_q, fs_hz)
    drive = rng.standard_normal((3, n), dtype=np.float32) * (level + rough)
    drive[2] += joints
    y, mode_zi = sosfilt(sos, drive, axis=-1, zi=state.mode_zi)
    # the engine lines and the modes reach the floor through the same fixed axis weights
    # (axis_share: fore-aft 0.35, lateral 0.5, vertical 1)
    y += line
    y *= share[:, None]
    return y, VibrationState(phases, state.detune, mode_zi, new_joint)


def _running_level(n1_pct: np.ndarray) -> np.ndarray:
    """Engine excitation level: 0.5 + 0.5 N1/100 while running (N1 >= 15 %: idle is already
    clearly felt in the cabin), fading linearly to zero as the engine spools down below 15 %."""
    n1 = np.asarray(n1_pct, float)
    return (0.5 + 0.005 * n1) * np.clip(n1 / 15.0, 0.0, 1.0)


@lru_cache(maxsize=16)
def _mode_bank(mode_hz: tuple[float, ...], q: float, fs_hz: float) -> np.ndarray:
    """Sum of unit-RMS resonators (parallel form) as one SOS filter."""
    b_tot, a_tot = np.zeros(1), np.ones(1)
    for f0 in mode_hz:
        b, a = iirpeak(f0, q, fs=fs_hz)
        b = b / np.sqrt(_rms_gain(b, a))
        b_tot = np.polyadd(np.polymul(b_tot, a), np.polymul(b, a_tot))
        a_tot = np.polymul(a_tot, a)
    return tf2sos(b_tot, a_tot)


def _rms_gain(b: np.ndarray, a: np.ndarray) -> float:
    """Output variance of the filter for unit-variance white input (sum of the squared impulse response)."""
    imp = np.zeros(4096)
    imp[0] = 1.0
    h = lfilter(b, a, imp)
    return float(np.sum(h**2))


__all__ = ["VibrationModel", "VibrationState", "initial_state", "vibration_g", "ENGINE_RPM"]
