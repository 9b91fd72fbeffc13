"""Barometer models: named presets (frozen; vary them with :func:`with_odr` or ``dataclasses.replace``),
a per-unit draw within the datasheet tolerances, and the measurement chain from the true pressure
at the bag to the stored ``baro_pa``.

Chain, on a true pressure series ``pressure_pa`` at times ``t_s`` (any rate, e.g. the FlightTrack's):

1. sampling at the output data rate (ODR): the pressure interpolated linearly at ``t0 + k / ODR``
   (the conversion time of an oversampled reading, a few ms to 80 ms, is far shorter than any cabin
   or weather change, so the reading is taken as instantaneous; the parts' optional IIR filters are off);
2. the unit's offset (drawn uniformly within the absolute accuracy: datasheets give bounds, not
   spreads) plus its temperature coefficient of offset times (T - 25 degC) when a temperature series
   is given (the TCO drawn uniformly within its datasheet bound);
3. white Gaussian noise of the preset's RMS (the datasheet figure for that oversampling / mode);
4. saturation at the pressure range (an unpressurised hold at cruise is below 260-300 hPa: the
   reading sticks at the range's end, as the part's does);
5. quantisation to the output word's step (``round(p / lsb) lsb``).

Presets and their sources:

- ``bmp581-osrN`` (N = 1 ... 128) and ``bmp581`` (= ``bmp581-osr16``): Bosch Sensortec BMP581 datasheet
  BST-BMP581-DS004-02 (rev. 1.2, January 2022), Table 9 "Oversampling settings": typical pressure RMS
  noise at 100 kPa 0.78 / 0.58 / 0.41 / 0.30 / 0.21 / 0.15 / 0.11 / 0.08 Pa for pressure oversampling
  x1 / x2 / x4 / x8 / x16 / x32 / x64 / x128, with typical CONTINUOUS-mode rates 498 / 374 / 255 / 155 /
  87 / 46 / 24 / 12 Hz. Key parameters: absolute accuracy +-0.5 hPa (max), relative accuracy 0.06 hPa
  per 10 kPa step, temperature-induced offset +-0.5 Pa/K, range 30-125 kPa. Output 24 bits in 1/64 Pa
  (Bosch BMP5 sensor API: ``P = raw / 2^6``). NORMAL-mode ODRs: the BMP5 API's list (240 ... 0.125 Hz);
  a preset accepts those at or below its oversampling's typical continuous rate (*assumption*: the
  datasheet's Table 7, the exact maximum ODR per OSR, was not read).
- ``lps22hh``: ST LPS22HH datasheet (DocID030890 Rev 2, February 2019), feature list: absolute pressure
  accuracy 0.5 hPa, pressure noise 0.65 Pa RMS (its low-noise figure; the per-mode table was not read,
  so every ODR takes it), TCO 0.65 Pa/degC, range 260-1260 hPa, 24-bit output at 4096 LSB/hPa (ST's
  driver: ``hPa = raw / 1048576`` on the 24 bits left-aligned in 32), ODR 1 / 10 / 25 / 50 / 75 / 100 /
  200 Hz (ST's driver enumeration).
- ``ideal``: no noise, offset, saturation or quantisation; 25 Hz.

The Bosch BMP390 (the issue's other example) is not a preset: its per-oversampling noise table was not
read (its summary figures: relative accuracy +-3 Pa, absolute +-50 Pa typ., 0.016 Pa resolution,
datasheet BST-BMP390-DS002-07).
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from flightmode.errors import SensorError, did_you_mean, first_nonfinite
from flightmode.units import HPA_PA


@dataclass(frozen=True, slots=True)
class BarometerPreset:
    name: str
    description: str
    odr_hz: float
    allowed_odr_hz: tuple[float, ...]
    noise_pa: float  # RMS output noise at this setting
    lsb_pa: float | None  # quantisation step; None: float output
    range_pa: tuple[float, float]  # the reading saturates outside
    abs_accuracy_pa: float  # per-unit offset drawn uniformly in +-this
    rel_accuracy_pa: float | None  # datasheet relative accuracy (documentation; None: not read)
    tco_pa_per_k: float  # per-unit temperature coefficient of offset drawn uniformly in +-this

    def validate(self) -> None:
        if self.odr_hz not in self.allowed_odr_hz:
            raise SensorError(
                f"barometer '{self.name}': output data rate {self.odr_hz:g} Hz is not one the part has at this "
                f"setting; allowed: {', '.join(f'{f:g}' for f in self.allowed_odr_hz)} Hz"
            )
        if self.noise_pa < 0 or self.abs_accuracy_pa < 0 or self.tco_pa_per_k < 0:
            raise SensorError(f"barometer '{self.name}': noise, accuracy and TCO must be >= 0")
        if self.lsb_pa is not None and not self.lsb_pa > 0:
            raise SensorError(
                f"barometer '{self.name}': lsb_pa {self.lsb_pa} must be > 0 (or None for float output)"
            )
        if not self.range_pa[0] < self.range_pa[1]:
            raise SensorError(
                f"barometer '{self.name}': range {self.range_pa} must be (low, high) with low < high"
            )


# BMP5 sensor API: NORMAL-mode output data rates (Hz)
BMP581_NORMAL_ODR_HZ: tuple[float, ...] = (
    240.0,
    218.5,
    199.1,
    179.2,
    160.0,
    149.3,
    140.0,
    129.8,
    120.0,
    110.1,
    100.2,
    89.6,
    80.0,
    70.0,
    60.0,
    50.0,
    45.0,
    40.0,
    35.0,
    30.0,
    25.0,
    20.0,
    15.0,
    10.0,
    5.0,
    4.0,
    3.0,
    2.0,
    1.0,
    0.5,
    0.25,
    0.125,
)
# BMP581 datasheet Table 9: pressure oversampling -> (typical RMS noise at 100 kPa, typical continuous ODR)
BMP581_TABLE9: dict[int, tuple[float, float]] = {
    1: (0.78, 498.0),
    2: (0.58, 374.0),
    4: (0.41, 255.0),
    8: (0.30, 155.0),
    16: (0.21, 87.0),
    32: (0.15, 46.0),
    64: (0.11, 24.0),
    128: (0.08, 12.0),
}


def _bmp581(osr: int, odr_hz: float, name: str | None = None) -> BarometerPreset:
    noise, odr_max = BMP581_TABLE9[osr]
    return BarometerPreset(
        name=name or f"bmp581-osr{osr}",
        description=f"Bosch BMP581, pressure oversampling x{osr} ({noise} Pa RMS), NORMAL mode, ODR {odr_hz:g} Hz",
        odr_hz=odr_hz,
        allowed_odr_hz=tuple(f for f in BMP581_NORMAL_ODR_HZ if f <= odr_max),
        noise_pa=noise,
        lsb_pa=1.0 / 64.0,
        range_pa=(30_000.0, 125_000.0),
        abs_accuracy_pa=0.5 * HPA_PA,
        rel_accuracy_pa=0.06 * HPA_PA,  # per 10 kPa step
        tco_pa_per_k=0.5,
    )


PRESETS: dict[str, BarometerPreset] = {
    "bmp581": _bmp581(16, 25.0, "bmp581"),
    **{f"bmp581-osr{o}": _bmp581(o, 25.0 if o <= 32 else 10.0) for o in BMP581_TABLE9},
    "lps22hh": BarometerPreset(
        name="lps22hh",
        description="ST LPS22HH, 0.65 Pa RMS (low-noise figure), ODR 25 Hz",
        odr_hz=25.0,
        allowed_odr_hz=(1.0, 10.0, 25.0, 50.0, 75.0, 100.0, 200.0),
        noise_pa=0.65,
        lsb_pa=HPA_PA / 4096.0,
        range_pa=(260.0 * HPA_PA, 1260.0 * HPA_PA),
        abs_accuracy_pa=0.5 * HPA_PA,
        rel_accuracy_pa=None,
        tco_pa_per_k=0.65,
    ),
    "ideal": BarometerPreset(
        name="ideal",
        description="ideal barometer: the true pressure at the ODR, no noise, offset, saturation or quantisation",
        odr_hz=25.0,
        allowed_odr_hz=(1.0, 5.0, 10.0, 25.0, 50.0, 100.0, 120.0),
        noise_pa=0.0,
        lsb_pa=None,
        range_pa=(0.0, 1e9),
        abs_accuracy_pa=0.0,
        rel_accuracy_pa=0.0,
        tco_pa_per_k=0.0,
    ),
}


def get_preset(name: str) -> BarometerPreset:
    try:
        return PRESETS[name]
    except KeyError:
        raise SensorError(
            f"unknown barometer preset '{name}'{did_you_mean(name, PRESETS)}; presets: {', '.join(PRESETS)}"
        ) from None


def with_odr(preset: BarometerPreset | str, odr_hz: float) -> BarometerPreset:
    """The preset at another of its allowed output data rates (a SensorError naming them otherwise)."""
    p = get_preset(preset) if isinstance(preset, str) else preset
    q = replace(
        p, odr_hz=float(odr_hz), description=f"{p.description.rsplit(', ODR', 1)[0]}, ODR {odr_hz:g} Hz"
    )
    q.validate()
    return q


@dataclass(frozen=True, slots=True)
class BaroUnit:
    """One physical unit's deviations, drawn once per unit."""

    offset_pa: float = 0.0
    tco_pa_per_k: float = 0.0

    def as_dict(self) -> dict:
        return {"offset_pa": self.offset_pa, "tco_pa_per_k": self.tco_pa_per_k}


def draw_unit(preset: BarometerPreset, rng: np.random.Generator) -> BaroUnit:
    """Offset uniform in +-absolute accuracy, TCO uniform in +-its bound (in that order)."""
    off = rng.uniform(-preset.abs_accuracy_pa, preset.abs_accuracy_pa)
    tco = rng.uniform(-preset.tco_pa_per_k, preset.tco_pa_per_k)
    return BaroUnit(float(off), float(tco))


def sample_times(t_s: np.ndarray, odr_hz: float, t0_s: float | None = None) -> np.ndarray:
    """Output sample times t0 + k / ODR within [t_s[0], t_s[-1]] (t0 defaults to t_s[0])."""
    t0 = float(t_s[0]) if t0_s is None else float(t0_s)
    k0 = int(np.ceil((float(t_s[0]) - t0) * odr_hz - 1e-9))
    k1 = int(np.floor((float(t_s[-1]) - t0) * odr_hz + 1e-9))
    return t0 + np.arange(k0, k1 + 1) / odr_hz


def measure(
    t_s,
    pressure_pa,
    preset: BarometerPreset | str,
    rng: np.random.Generator,
    *,
    unit: BaroUnit | None = None,
    temperature_c=None,
    t0_s: float | None = None,
) -> tuple[np.ndarray, np.ndarray]:
    """The barometer's output ``(t_s, baro_pa)`` for a true pressure ``pressure_pa`` at ``t_s`` (module
    docstring). ``unit``: the unit's deviations; None draws one from ``rng`` first (then the noise).
    ``temperature_c``: the part's temperature at ``t_s`` (None: 25 degC, no TCO effect). ``t0_s``: the
    phase of the output grid (default ``t_s[0]``)."""
    p = get_preset(preset) if isinstance(preset, str) else preset
    p.validate()
    t = np.asarray(t_s, float)
    x = np.asarray(pressure_pa, float)
    if t.ndim != 1 or x.shape != t.shape or t.size < 2:
        raise SensorError(
            f"barometer: need t_s and pressure_pa as 1-D arrays of one length >= 2, "
            f"got {t.shape} and {x.shape}"
        )
    for name, v in (("t_s", t), ("pressure_pa", x)):
        if (i := first_nonfinite(v)) is not None:
            raise SensorError(f"barometer: {name} is NaN or inf at sample {i} (t = {t[i]:.3f} s)")
    if np.any(np.diff(t) <= 0):
        i = int(np.flatnonzero(np.diff(t) <= 0)[0])
        raise SensorError(f"barometer: t_s is not increasing at sample {i + 1} (t = {t[i + 1]:.3f} s)")
    unit = draw_unit(p, rng) if unit is None else unit
    t_out = sample_times(t, p.odr_hz, t0_s)
    y = np.interp(t_out, t, x) + unit.offset_pa
    if temperature_c is not None:
        temp = np.asarray(temperature_c, float)
        if temp.shape != t.shape or not np.isfinite(temp).all():
            raise SensorError(
                f"barometer: temperature_c must be finite with the shape of t_s {t.shape}, got {temp.shape}"
            )
        y = y + unit.tco_pa_per_k * (np.interp(t_out, t, temp) - 25.0)
    if p.noise_pa > 0:
        y = y + rng.normal(0.0, p.noise_pa, t_out.shape[0])
    y = np.clip(y, p.range_pa[0], p.range_pa[1])
    if p.lsb_pa is not None:
        y = np.rint(y / p.lsb_pa) * p.lsb_pa
    return t_out, y


__all__ = [
    "PRESETS",
    "BaroUnit",
    "BarometerPreset",
    "draw_unit",
    "get_preset",
    "measure",
    "sample_times",
    "with_odr",
]
