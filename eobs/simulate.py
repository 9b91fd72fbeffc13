"""Simulated e-obs tags: unit-to-unit constants, the six static recordings of section 7, bursts.

A unit's true constants are drawn around seed 003 section 6's nominal figures (zero-g 2048 counts,
slope 0.0022 g/count for tags > 2241, 0.001 or 0.0027 for older tags by their sensitivity setting)
with the spread of flightmode's ``eobs`` accelerometer preset (sim.sensor.accelerometer: zero-g
+-40 counts and gain +-5 %, uniform; an assumption there, as the note gives no tolerance, only that
"the real values might differ" (section 3) and an illustration whose X zero-g is 1800). A reading is

    n = clip(round(n_zerog + (a + w) / c), 0, 4095),   w ~ N(0, noise_g^2) per sample and axis,

the ADC's quantisation to whole counts and its 0-4095 range (section 6). The note gives no noise
figure: ``noise_g`` is an argument (the ``eobs`` preset's 1 mg, 0.45 count at 0.0022 g/count, is
flightmode's assumption). Section 2: on old tags "the noise signal was increased by the same factor
as the sensitivity", i.e. a noise fixed in g, as modelled here.
"""

from __future__ import annotations

import numpy as np

from flightmode.eobs.burst import AccBurst, check_axes
from flightmode.eobs.calibration import ORIENTATIONS, RECORDING_KEYS, Calibration
from flightmode.eobs.tag import (
    ADC_MAX_COUNT,
    ADC_MIN_COUNT,
    AXES,
    NOMINAL_ZERO_COUNT,
    nominal_slope_g_per_count,
    y_sign,
)
from flightmode.errors import SensorError


def unit_spread() -> tuple[float, float]:
    """(zero-g half-range in counts, relative gain half-range) of the ``eobs`` preset."""
    from flightmode.sim.sensor.accelerometer import PRESETS

    p = PRESETS["eobs"]
    assert p.lsb_g is not None  # the eobs preset is quantised (0.0022 g/count)
    return p.offset_tol_g / p.lsb_g, p.sensitivity_tol


def draw_unit(tag_number: int, rng: np.random.Generator, sensitivity: str | None = None) -> Calibration:
    """One unit's true constants per axis: zero 2048 + U(-40, 40) counts, slope nominal x (1 + U(-5 %, 5 %))."""
    c0 = nominal_slope_g_per_count(tag_number, sensitivity)
    dz, dc = unit_spread()
    zero = NOMINAL_ZERO_COUNT + rng.uniform(-dz, dz, 3)
    slope = c0 * (1.0 + rng.uniform(-dc, dc, 3))
    return Calibration(tuple(zero), tuple(slope), tag_number)


def counts_from_g(
    acc_g: np.ndarray, unit: Calibration, rng: np.random.Generator, noise_g: float
) -> np.ndarray:
    """Raw counts (n, 3) of a specific force ``acc_g`` (n, 3) in g along the tag's own X, Y, Z."""
    a = np.asarray(acc_g, dtype=float)
    if a.ndim != 2 or a.shape[1] != 3:
        raise SensorError(f"specific force: need shape (n, 3) in g along X, Y, Z, got {a.shape}")
    if not noise_g >= 0:
        raise SensorError(f"noise {noise_g} g: must be >= 0")
    w = rng.normal(0.0, noise_g, a.shape) if noise_g > 0 else np.zeros_like(a)
    n = np.rint(np.array(unit.zero_count) + (a + w) / np.array(unit.slope_g_per_count))
    return np.clip(n, ADC_MIN_COUNT, ADC_MAX_COUNT).astype(np.int64)


def six_recordings(
    unit: Calibration, rng: np.random.Generator, n_samples: int, noise_g: float
) -> dict[str, np.ndarray]:
    """The static recordings '+x' .. '-z' (the tag's own axis at +1 g / -1 g, the others at 0 g)."""
    out = {}
    for key in RECORDING_KEYS:
        a = np.zeros((n_samples, 3))
        a[:, "xyz".index(key[1])] = 1.0 if key[0] == "+" else -1.0
        out[key] = counts_from_g(a, unit, rng, noise_g)
    return out


def orientation_recordings(
    unit: Calibration, rng: np.random.Generator, n_samples: int, noise_g: float
) -> dict[str, np.ndarray]:
    """Section 7's recordings keyed A-F: the orientations of chapter 3's images (drawn for the new
    tags); an old tag (unit.tag_number <= 2241) reads its reversed Y the other way round."""
    if unit.tag_number is None:
        raise SensorError("orientation recordings need the unit's tag number (old tags have Y reversed)")
    out = {}
    for letter, (axis, g) in ORIENTATIONS.items():
        a = np.zeros((n_samples, 3))
        a[:, "xyz".index(axis)] = g * (y_sign(unit.tag_number) if axis == "y" else 1)
        out[letter] = counts_from_g(a, unit, rng, noise_g)
    return out


def simulate_burst(
    unit: Calibration,
    acc_g: np.ndarray,
    axes: str,
    rate_hz: float,
    start_time: np.datetime64,
    rng: np.random.Generator,
    noise_g: float,
    tag_id: str | None = None,
) -> AccBurst:
    """A burst of the enabled ``axes`` from a specific force (n, 3) in g along the tag's own axes.
    The checksum is 0: there is no binary record to checksum (flightmode.eobs.movebank)."""
    check_axes(axes)
    counts = counts_from_g(acc_g, unit, rng, noise_g)[:, [AXES.index(a) for a in axes]]
    if tag_id is None:
        if unit.tag_number is None:
            raise SensorError("simulate_burst: give tag_id or a unit with a tag number")
        tag_id = str(unit.tag_number)
    return AccBurst(tag_id, start_time, axes, rate_hz, counts, checksum=0)
