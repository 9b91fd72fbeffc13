"""Recording: what the bag's accelerometer stored, with per-sample truth labels."""

from __future__ import annotations

from dataclasses import asdict, dataclass

import numpy as np

from flightmode.digest import digest
from flightmode.labels import PHASES, SEVERITIES
from flightmode.sim.sensor.carrier import BAG_STATES, CarrierSpec


@dataclass(frozen=True, slots=True)
class Recording:
    """One row per output sample. Shapes (M,) or (M, 3)."""

    t_s: np.ndarray  # FlightTrack time (negative before the track starts, in the terminal)
    counts: np.ndarray  # raw output counts, int32 (zeros for a float 'ideal' sensor)
    acc_g: np.ndarray  # counts in g (calibrated unit sensitivity)
    clipped: np.ndarray  # bool: the sample saturated
    odr_hz: float
    preset: str
    unit: dict  # the drawn per-unit parameters (offsets, sensitivity errors, cross-axis)
    carrier: CarrierSpec
    aircraft: str
    segments: tuple  # the carrier timeline (carrier.Segment): states and true orientations
    phase_code: np.ndarray
    in_flight_window: np.ndarray
    airborne: np.ndarray
    turbulence_code: np.ndarray
    bag_state_code: np.ndarray
    sensor_static: np.ndarray
    gyro_dps: np.ndarray | None = None  # (M, 3) optional gyroscope, deg/s, sensor axes
    # with a barometer fitted: the pressure at the bag (truth: the cabin's, the hold's, or ambient off
    # board) and the barometer read at the accelerometer's rows: baro_pa is
    # the latest reading (held), baro_new marks the rows where a new one arrived (sensing.read_barometer)
    pressure_pa: np.ndarray | None = None
    baro_pa: np.ndarray | None = None
    baro_new: np.ndarray | None = None
    baro: dict | None = None  # {"preset", "odr_hz", "unit": {...}} of the fitted barometer
    # the bag's place on board as drawn (sensing.stowage_record): in-flight placement, orientation, mount
    stowage: dict | None = None

    @property
    def baro_stream(self) -> tuple[np.ndarray, np.ndarray]:
        """The barometer's own stream (t_s, baro_pa): the rows where a new reading arrived."""
        if self.baro_pa is None:
            from flightmode.errors import SensorError

            raise SensorError("the recording has no barometer: fit one ([sensor].baro or --baro PRESET)")
        return self.t_s[self.baro_new], self.baro_pa[self.baro_new]

    @property
    def n(self) -> int:
        return int(self.t_s.shape[0])

    @property
    def phase(self) -> np.ndarray:
        return np.asarray(PHASES, dtype=object)[self.phase_code]

    @property
    def bag_state(self) -> np.ndarray:
        return np.asarray(BAG_STATES, dtype=object)[self.bag_state_code]

    @property
    def turbulence_severity(self) -> np.ndarray:
        return np.asarray(SEVERITIES, dtype=object)[self.turbulence_code]

    def summary(self) -> dict:
        return (
            {
                "preset": self.preset,
                "odr_hz": self.odr_hz,
                "samples": self.n,
                "duration_s": float(self.t_s[-1] - self.t_s[0]),
                "unit": self.unit,
                "carrier": asdict(self.carrier),
                "static_fraction": float(self.sensor_static.mean()),
                "clipped_samples": int(self.clipped.any(axis=1).sum()),
            }
            | ({"baro": self.baro} if self.baro is not None else {})
            | ({"stowage": self.stowage} if self.stowage is not None else {})
        )

    def digest(self) -> str:
        """Equal digests mean bit-identical recordings (:func:`flightmode.digest.digest`)."""
        return digest(self)
