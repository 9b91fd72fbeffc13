"""MEMS gyroscopes: the spec of a part (noise, zero-rate offset, range, quantisation) and named
presets, for the comparative detectors of seed 001 that read angular rate (ARED, SHOD, and the
sum / product inputs). The rates a gyroscope sees are :mod:`flightmode.sim.sensor.sensing`'s (the
aircraft's body rates on board, the bag's own rotation while carried or handled).

Presets and their sources:

- ``bmi270``: Bosch Sensortec BMI270 (datasheet BST-BMI270-DS000, as tabulated by Luxonis's hardware
  documentation of the part): rate noise density 0.007 deg/s/sqrt(Hz) typical in performance mode,
  ranges +-125 ... +-2000 deg/s at 262.144 ... 16.384 LSB/(deg/s); the preset uses +-250 deg/s
  (131.072 LSB/(deg/s): a handled bag's wrist turns stay below 250 deg/s). The RMS noise is the
  density over the output bandwidth, taken as ODR / 2 (the convention ST's datasheets state for
  their RMS figures): 0.049 deg/s at 100 Hz. Zero-rate offset: drawn uniformly within +-0.5 deg/s
  (*recalled, not read*: the datasheet's typical ZRO; the Bosch BMI160's, tabulated beside it in
  public comparisons, is +-3 typical); bias instability (a few deg/h) is far below the noise over
  a flight's minutes and is not modelled.
- ``generic``: the figures sensing used before the presets (0.05 deg/s white noise, +-0.5 deg/s
  offset, +-2000 deg/s, float output).

Earth rotation (0.004 deg/s) is neglected.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from flightmode.errors import SensorError, did_you_mean


@dataclass(frozen=True, slots=True)
class GyroSpec:
    """A gyroscope sampled with the accelerometer: white noise (``noise_density_dps_rthz`` over
    ODR / 2 when given, else ``noise_dps`` RMS), a per-unit offset drawn within +-``bias_tol_dps``,
    saturation at +-``range_dps``, quantisation to ``lsb_dps`` (None: float output), and the bag's
    own rotation rates (RMS) while carried (sway) and handled."""

    noise_dps: float = 0.05
    bias_tol_dps: float = 0.5
    range_dps: float = 2000.0
    sway_dps: float = 20.0  # RMS rotation rate of a carried bag
    handling_dps: float = 30.0  # RMS rotation rate of a handled bag
    name: str = "generic"
    noise_density_dps_rthz: float | None = None
    lsb_dps: float | None = None

    def noise_rms_dps(self, odr_hz: float) -> float:
        """The white noise's RMS at an output data rate (density x sqrt(ODR / 2), or ``noise_dps``)."""
        if self.noise_density_dps_rthz is None:
            return self.noise_dps
        return self.noise_density_dps_rthz * math.sqrt(odr_hz / 2.0)

    def validate(self) -> None:
        for name in ("noise_dps", "bias_tol_dps", "sway_dps", "handling_dps"):
            if not getattr(self, name) >= 0:
                raise SensorError(f"gyroscope '{self.name}': {name} {getattr(self, name)} must be >= 0")
        if not self.range_dps > 0:
            raise SensorError(f"gyroscope '{self.name}': range {self.range_dps} deg/s must be > 0")
        if self.lsb_dps is not None and not self.lsb_dps > 0:
            raise SensorError(f"gyroscope '{self.name}': lsb_dps {self.lsb_dps} must be > 0 (or None)")
        if self.noise_density_dps_rthz is not None and not self.noise_density_dps_rthz >= 0:
            raise SensorError(f"gyroscope '{self.name}': noise density must be >= 0")


PRESETS: dict[str, GyroSpec] = {
    "bmi270": GyroSpec(
        name="bmi270", noise_density_dps_rthz=0.007, bias_tol_dps=0.5, range_dps=250.0, lsb_dps=1.0 / 131.072
    ),
    "generic": GyroSpec(),
}


def get_preset(name: str) -> GyroSpec:
    try:
        return PRESETS[name]
    except KeyError:
        raise SensorError(
            f"unknown gyroscope preset '{name}'{did_you_mean(name, PRESETS)}; presets: {', '.join(PRESETS)}"
        ) from None


__all__ = ["GyroSpec", "PRESETS", "get_preset"]
