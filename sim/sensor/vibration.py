"""Airframe vibration at the cabin floor / hold, generated at the internal rate (>= 1 kHz) so that
the accelerometer's own filter and sampling decide what survives (aliasing included), and what
varies of it from flight to flight (:func:`draw_floor`).

Components (:class:`VibrationModel`):

- engine lines: each engine's fan (N1) and core (N2) rotation, f = rpm / 60 with the N1 first and
  second harmonics; amplitude ``engine_idle_share`` + (1 - it) (N1/100)^2 of its full-power value
  while running (a fixed residual unbalance m e gives a force m e omega^2, growing as the square of
  the shaft speed: Den Hartog, "Mechanical Vibrations", 4th ed., 1956, ch. 6; the share felt at idle
  is seed 000 section 2's "as soon as the engines are turned on"), fading out below 15 % N1 and
  as N2 runs down to the engines-off mark (5 %);
- airframe structural modes between 10 and 30 Hz (seed 000 section 4.2, Fig. 6: peaks between 10
  and 30 Hz in every flight stage), resonators driven by white noise whose RMS is the sum of an
  engine part (the same N1 law) and an airflow part proportional to the dynamic pressure q (the
  boundary layer's pressure fluctuations: MIL-STD-810G Method 514.6, Annex D, makes the jet-aircraft
  vibration PSD grow as q^2, i.e. the RMS as q);
- runway: roughness (broadband, level proportional to ground speed) and pavement-joint bumps every
  ``joint_spacing_m`` (an impulse train at v / spacing Hz) while on the gear;
- no vibration at all with the engines stopped and the aircraft at rest.

Directions (``axis_share``): vertical 1, lateral 0.6, fore-aft 0.3. The fuselage is stiffest along its
axis, so fore-aft is taken as the lowest; the values themselves are assumptions, set with the mounts
(:mod:`flightmode.sim.sensor.mount`) so that seed 000's Tables 4 and 5 are reproduced.

Magnitudes. No public cabin-floor vibration PSD of a jet airliner was found. Mansfield and
Aggarwal's review of 26 in-aircraft studies (Vibration 5(1), 2022) finds energy at frequencies the
ISO 2631 weighting attenuates and a significant effect of the flight phase, but no magnitudes to
use; MIL-STD-810's jet and cargo curves are test envelopes (several g RMS), far above what a bag in a
cabin feels. The amplitudes are therefore flightmode assumptions (about 20 mg RMS vertical on a
mid-cabin floor in cruise), calibrated together with the mounts against seed 000's Tables 4-5.

What varies between flights (:func:`draw_floor`), each a named parameter:

- the type (``TYPE_LEVEL``): no per-type source was found, all 1.0; types differ by their engines'
  spool speeds (the lines) and by where the engines are (``ENGINE_POSITION``);
- the location (``LOCATION_LEVEL``): the cabin row by engine position, and the hold. The ordering of
  the rows, middle quietest, then front, rear worst, is the in-flight measurement of Li et al.
  ("Evaluation of vibration caused discomfort in passenger aircraft cabin", Acta Aeronautica et
  Astronautica Sinica 43(6), 525945, 2022, ISO 2631-1 comfort by seat position); the factors are
  assumptions, larger at the rear for rear-mounted engines (the Fokker 100's Tay 650s) and for the
  hold (no trim, seats or carpet between the bag and the skin);
- the flight (``FLIGHT_LN_SIGMA``): a lognormal factor of ln-spread 0.2 on every amplitude (load,
  speed, airframe): an assumption, kept modest because seed 000 (section 6) reports the analyses of
  its other flights "similar" to its two tables;
- the mode frequencies (``MODE_JITTER``): within +-10 % per flight (payload and fuel): assumption.

Uncertain parameters (:data:`UNCERTAIN`, overridden by a scenario's ``[model]`` table): the engine
excitation's share at idle (``vibration.engine_idle_share``, 0.5 in 0.25-0.8), which sets how loud
the floor is at the pushback and the taxi holds, where most false statics are.

Engine spool speeds (rpm at 100 %): CFM56-5B N1 5000 / N2 14460 (EASA type certificate data sheet
E.067); CFM56-3 (737) 5490 / 15183; Rolls-Royce Tay 650 (fokker100) 8400 / 12500; Trent 1000 (787-8)
2683 / 13391 (public type certificate data sheets, rounded).
"""

from __future__ import annotations

import dataclasses
from collections.abc import Mapping
from dataclasses import dataclass
from functools import lru_cache

import numpy as np
from scipy.signal import iirpeak, lfilter, sosfilt, zpk2sos

from flightmode.labels import ENGINES_OFF_N2_PCT
from flightmode.uncertain import Uncertain, value_of

ENGINE_IDLE_SHARE = Uncertain(
    "vibration.engine_idle_share",
    0.5,
    0.25,
    0.8,
    "1",
    "assumption: seed 000 section 2 says the vibration starts 'as soon as the engines are turned on', "
    "no level; 0.5 was set with the mounts against seed 000's Tables 4-5 (cruise, not idle); "
    "no public idle cabin-floor level was found",
    "the floor's engine vibration at idle (pushback, taxi holds) relative to full power",
)
UNCERTAIN = (ENGINE_IDLE_SHARE,)

ENGINE_RPM = {  # model -> (N1 rpm at 100 %, N2 rpm at 100 %)
    "A320": (5000.0, 14460.0),
    "737": (5490.0, 15183.0),
    "fokker100": (8400.0, 12500.0),
    "787-8": (2683.0, 13391.0),
}


@dataclass(frozen=True, slots=True)
class VibrationModel:
    """The floor's vibration (module docstring). The defaults are a mid-cabin floor of a type of
    level 1.0 on an average flight; :func:`draw_floor` scales them per flight. With the mounts of
    :mod:`flightmode.sim.sensor.mount` they reproduce seed 000's Tables 4-5 to within a decade per
    cell on the built-in flights gva-lhr-a320 and hel-zrh-f100-calm
    (tests/sim/test_vibration_variability.py)."""

    n1_line_g: float = 4.5e-3  # first N1 harmonic at 100 % N1, per engine
    n1_h2_g: float = 1.5e-3  # second N1 harmonic at 100 % N1
    n2_line_g: float = 1.2e-3  # N2 line at 100 % N2
    mode_hz: tuple[float, ...] = (11.0, 16.5, 22.0, 27.5)  # airframe modes (10-30 Hz)
    mode_q: float = 8.0
    mode_engine_g: float = 6.0e-3  # modal RMS per mode at 100 % N1 (both engines)
    mode_airflow_g: float = 6.0e-3  # modal RMS per mode at q = airflow_q_ref_pa
    roughness_g_per_mps: float = 0.45e-3  # runway roughness RMS per m/s of ground speed
    joint_spacing_m: float = 5.0
    joint_impulse_g: float = 20.0e-3  # peak of one joint bump (decays through the modes)
    axis_share: tuple[float, float, float] = (0.3, 0.6, 1.0)  # x, y, z relative weights
    # engine excitation at 0 % N1 relative to 100 % (the rest grows as N1^2): ENGINE_IDLE_SHARE
    engine_idle_share: float = ENGINE_IDLE_SHARE.value
    airflow_q_ref_pa: float = 15000.0  # dynamic pressure at which the airflow drive is mode_airflow_g


# ---------------------------------------------------------------------- what varies between flights
ENGINE_POSITION = {"A320": "wing", "737": "wing", "fokker100": "rear", "787-8": "wing"}  # type descriptions
TYPE_LEVEL = {"A320": 1.0, "737": 1.0, "fokker100": 1.0, "787-8": 1.0}  # assumption: no per-type source
# floor level by cabin row (or hold) and engine position, relative to a mid-cabin seat; the ordering of
# the cabin rows is Li et al. (2022)'s, the magnitudes are assumptions (module docstring)
LOCATION_LEVEL = {
    "wing": {"front": 1.2, "mid": 1.0, "rear": 1.5, "hold": 1.3},
    "rear": {"front": 1.0, "mid": 1.2, "rear": 2.0, "hold": 1.5},
}
FLIGHT_LN_SIGMA = 0.2  # flight-to-flight spread of the level (ln), same type and place: assumption
MODE_JITTER = 0.1  # airframe mode frequencies drawn within +-10 % per flight: assumption


@dataclass(frozen=True, slots=True)
class FloorDraw:
    """One flight's draw of the floor vibration (:func:`draw_floor`): the factors, and the model."""

    type_level: float
    location_level: float
    flight_level: float
    mode_scale: float
    model: VibrationModel

    def as_dict(self) -> dict:
        return {
            "type_level": self.type_level,
            "location_level": self.location_level,
            "flight_level": self.flight_level,
            "mode_scale": self.mode_scale,
        }


def draw_floor(
    aircraft: str,
    location: str,
    rng: np.random.Generator,
    base: VibrationModel = VibrationModel(),
    overrides: Mapping[str, float] | None = None,
) -> FloorDraw:
    """One flight's floor vibration at ``location`` (a cabin row ``front`` / ``mid`` / ``rear`` or
    ``hold``) of ``aircraft``: ``base`` with its amplitudes scaled by the type's level, the location's
    (by engine position) and a lognormal flight-to-flight factor, and its mode frequencies jittered.
    Draws, in this order: the flight factor (one normal), the mode scale (one uniform). ``overrides``:
    the run's uncertain parameters (:data:`UNCERTAIN`; one overridden replaces ``base``'s value)."""
    if overrides and ENGINE_IDLE_SHARE.name in overrides:
        base = dataclasses.replace(base, engine_idle_share=value_of(ENGINE_IDLE_SHARE, overrides))
    if aircraft not in ENGINE_POSITION:
        from flightmode.errors import SensorError, did_you_mean

        raise SensorError(
            f"no vibration data for aircraft '{aircraft}'{did_you_mean(aircraft, ENGINE_POSITION)}"
        )
    t = TYPE_LEVEL[aircraft]
    loc = LOCATION_LEVEL[ENGINE_POSITION[aircraft]][location]
    fl = float(np.exp(FLIGHT_LN_SIGMA * rng.standard_normal()))
    ms = float(rng.uniform(1.0 - MODE_JITTER, 1.0 + MODE_JITTER))
    model = dataclasses.replace(
        scaled(base, t * loc * fl), mode_hz=tuple(round(f * ms, 6) for f in base.mode_hz)
    )
    return FloorDraw(t, loc, fl, ms, model)


def scaled(model: VibrationModel, k: float) -> VibrationModel:
    """``model`` with every amplitude (engine lines, mode excitations, runway roughness and joints)
    multiplied by ``k``; its frequencies and shares unchanged."""
    m = model
    return dataclasses.replace(
        m,
        n1_line_g=m.n1_line_g * k,
        n1_h2_g=m.n1_h2_g * k,
        n2_line_g=m.n2_line_g * k,
        mode_engine_g=m.mode_engine_g * k,
        mode_airflow_g=m.mode_airflow_g * k,
        roughness_g_per_mps=m.roughness_g_per_mps * k,
        joint_impulse_g=m.joint_impulse_g * k,
    )


@dataclass(frozen=True, slots=True)
class VibrationState:
    """Filter states and oscillator phases carried from one chunk to the next."""

    phases: np.ndarray  # (n_engines, 3) radians: N1, 2*N1, N2
    detune: np.ndarray  # (n_engines,) relative spool-speed offset: real engines never run in sync
    mode_zi: np.ndarray  # (n_modes, 3 axes, 2): state of the mode bank's sections (_mode_bank)
    joint_pos_m: float  # distance rolled since the last joint


def initial_state(
    n_engines: int, model: VibrationModel, fs_hz: float, rng: np.random.Generator
) -> VibrationState:
    return VibrationState(
        phases=rng.uniform(0.0, 2 * np.pi, (n_engines, 3)),
        # the FDM runs both engines at identical N1; with identical frequencies the two lines would
        # add with a fixed random phase (and could cancel). Real engines differ by a few tenths of
        # a percent, so each gets a fixed offset within +-0.3 % (the lines beat instead)
        detune=rng.uniform(-0.003, 0.003, n_engines),
        mode_zi=np.zeros((len(model.mode_hz), 3, 2)),
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
    level_e = _running_level(n1_pct, n2_pct, model)  # (n_engines, N)
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
    level = model.mode_engine_g * power + model.mode_airflow_g * np.clip(
        qbar_pa / model.airflow_q_ref_pa, 0.0, 2.0
    )
    # runway: roughness and joint bumps feed the same modes while rolling
    rolling = on_ground & (ground_speed_mps > 0.5)
    rough = model.roughness_g_per_mps * ground_speed_mps * rolling
    dist = state.joint_pos_m + np.cumsum(ground_speed_mps * rolling) * dt
    joints = np.zeros(n)
    k = np.floor(dist / model.joint_spacing_m)
    hit = np.flatnonzero(
        np.diff(np.concatenate([[np.floor(state.joint_pos_m / model.joint_spacing_m)], k])) > 0
    )
    joints[hit] = model.joint_impulse_g
    new_joint = float(dist[-1] % model.joint_spacing_m) if n else state.joint_pos_m
    # the modes: the sum of unit-RMS resonators (one noise stream per axis drives all modes), run as
    # one cascade of second-order sections (_mode_bank)
    sos = _mode_bank(model.mode_hz, model.mode_q, fs_hz)
    drive = rng.standard_normal((3, n), dtype=np.float32) * (level + rough)
    drive[2] += joints
    y, mode_zi = sosfilt(sos, drive, axis=-1, zi=state.mode_zi)
    # the engine lines and the modes reach the floor through the same fixed axis weights
    # (axis_share: fore-aft 0.3, lateral 0.6, vertical 1)
    y += line
    y *= share[:, None]
    return y, VibrationState(phases, state.detune, mode_zi, new_joint)


def _running_level(n1_pct: np.ndarray, n2_pct: np.ndarray, model: VibrationModel) -> np.ndarray:
    """Engine excitation level relative to full power: ``engine_idle_share`` + (1 - it) (N1/100)^2
    while running (the rotor's unbalance force grows as the square of its speed, m e omega^2; the
    share that does not is what is felt at idle, seed 000 section 2), fading linearly to zero as
    the engine spools down below 15 % N1, and as its N2 runs down from 15 % to the engines-off mark
    (:data:`~flightmode.labels.ENGINES_OFF_N2_PCT`, 5 %), where the truth labels have the engines off
    and a stowed bag at rest. With the N1 fade alone the engines were still felt for seconds after
    it (N1 about 2.5 %, a sixth of the idle level): a bag in the hold was labelled at rest while
    its 1 s variances stood at 5-20 sigma^2, which broke seed 000 Table 2's spread on 3 of 69
    european-trio flights. At 5 % N2 the core turns at a twelfth of its idle speed (60 %), and
    m e omega^2 is under 1 % of its idle value: the fade ends where the force has all but gone."""
    n1 = np.asarray(n1_pct, float)
    s = model.engine_idle_share
    off = ENGINES_OFF_N2_PCT
    spool = np.clip(n1 / 15.0, 0.0, 1.0) * np.clip((np.asarray(n2_pct, float) - off) / (15.0 - off), 0.0, 1.0)
    return (s + (1.0 - s) * (n1 / 100.0) ** 2) * spool


@lru_cache(maxsize=16)
def _mode_bank(mode_hz: tuple[float, ...], q: float, fs_hz: float) -> np.ndarray:
    """The sum of the modes' resonators (each an ``iirpeak`` normalised to unit output RMS for unit
    white input) as one cascade of second-order sections (n_modes, 6): one pass over the samples
    instead of one per mode (a fifth of the time for four modes).

    The sum of the sections b_i / a_i is N(z) / prod a_i. Both polynomials are ill-conditioned (their
    roots lie within 1.5 % of the unit circle): their roots as found from them (scipy's tf2zpk) give a
    response 2e-5 off the bank's. So the poles are the resonators' own (the roots of each a_i), and
    the zeros, the roots of N, are polished by Newton's method on the sum itself, S(z) = sum b_i(z) /
    a_i(z), which is well-conditioned near them (5e-8 off before, 3e-13 after:
    tests/sim/test_vibration_variability.py)."""
    secs = []
    num, den = np.zeros(1), np.ones(1)
    for f0 in mode_hz:
        b, a = iirpeak(f0, q, fs=fs_hz)
        b = b / np.sqrt(_rms_gain(b, a))
        secs.append((b, a))
        num = np.polyadd(np.polymul(num, a), np.polymul(b, den))
        den = np.polymul(den, a)
    z = np.roots(num)
    for _ in range(2):
        s = sum(np.polyval(b, z) / np.polyval(a, z) for b, a in secs)
        ds = sum(
            (
                np.polyval(np.polyder(b), z) * np.polyval(a, z)
                - np.polyval(b, z) * np.polyval(np.polyder(a), z)
            )
            / np.polyval(a, z) ** 2
            for b, a in secs
        )
        z = z - s / ds
    poles = np.concatenate([np.roots(a) for _, a in secs])
    return zpk2sos(z, poles, num[0] / den[0])


def _rms_gain(b: np.ndarray, a: np.ndarray) -> float:
    """Output variance of the filter for unit-variance white input (sum of the squared impulse response)."""
    imp = np.zeros(4096)
    imp[0] = 1.0
    h = lfilter(b, a, imp)
    return float(np.sum(h**2))


__all__ = [
    "ENGINE_POSITION",
    "ENGINE_RPM",
    "LOCATION_LEVEL",
    "TYPE_LEVEL",
    "FloorDraw",
    "VibrationModel",
    "VibrationState",
    "draw_floor",
    "initial_state",
    "vibration_g",
]
