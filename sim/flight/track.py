"""FlightTrack: the truth of one simulated flight, arrays at the FDM rate (SI units).

Frames: local NED at the origin runway threshold (WGS-84, so the frame is the
tangent plane there) plus geodetic lat/lon/alt; body x forward, y right, z down. Specific force
f = a - g in body axes: a level aircraft at rest reads f_z = -9.81 m/s^2.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from flightmode.digest import digest
from flightmode.labels import PHASES, SEVERITIES


@dataclass(frozen=True, slots=True)
class Event:
    t_s: float
    name: str
    detail: str = ""


@dataclass(frozen=True, slots=True)
class FlightTrack:
    """Truth arrays, one row per FDM step. Shapes: (N,), (N, 3), (N, 4) or (N, n_engines)."""

    aircraft: str
    fs_hz: float
    origin_lat_deg: float
    origin_lon_deg: float
    origin_alt_m: float
    t_s: np.ndarray
    lat_deg: np.ndarray
    lon_deg: np.ndarray
    alt_m: np.ndarray
    agl_m: np.ndarray
    pos_ned_m: np.ndarray
    vel_ned_mps: np.ndarray
    euler_rad: np.ndarray  # roll phi, pitch theta, yaw psi
    quat_wxyz: np.ndarray  # body -> NED rotation
    rates_radps: np.ndarray  # p, q, r
    ang_acc_radps2: np.ndarray
    specific_force_body_mps2: np.ndarray  # at the CG
    n1_pct: np.ndarray
    n2_pct: np.ndarray
    thrust_n: np.ndarray
    wow: np.ndarray
    flap_norm: np.ndarray
    gear_norm: np.ndarray
    speedbrake_norm: np.ndarray
    ias_mps: np.ndarray
    tas_mps: np.ndarray
    mach: np.ndarray
    alpha_rad: np.ndarray
    ground_speed_mps: np.ndarray
    vertical_speed_mps: np.ndarray
    phase_code: np.ndarray  # uint8 into flightmode.labels.PHASES
    in_flight_window: np.ndarray  # pushback start to engines off
    airborne: np.ndarray
    turbulence_code: np.ndarray  # uint8 into flightmode.labels.SEVERITIES
    events: tuple[Event, ...]
    conditions: dict = field(
        default_factory=dict
    )  # the flight's draws (sim.flight.draws.FlightDraws.as_dict)
    # pressure truth (sim.flight.cabin.cabin_pressure; None on a track read from an older file)
    ambient_pressure_pa: np.ndarray | None = None  # static pressure outside, under the airports' weather
    cabin_pressure_pa: np.ndarray | None = None  # the pressurised cabin (ambient while the door is open)
    cabin_altitude_m: np.ndarray | None = None  # its ISA pressure altitude
    hold_pressure_pa: np.ndarray | None = None  # the cargo hold (the cabin's, or ambient when unpressurised)

    @property
    def n(self) -> int:
        return int(self.t_s.shape[0])

    @property
    def duration_s(self) -> float:
        return float(self.t_s[-1] - self.t_s[0])

    @property
    def phase(self) -> np.ndarray:
        """Phase names per sample (object array; use ``phase_code`` in hot paths)."""
        return np.asarray(PHASES, dtype=object)[self.phase_code]

    @property
    def turbulence_severity(self) -> np.ndarray:
        return np.asarray(SEVERITIES, dtype=object)[self.turbulence_code]

    def event_time(self, name: str) -> float:
        """Time (s) of the first event called ``name``; an InputDataError naming the known events otherwise."""
        for ev in self.events:
            if ev.name == name:
                return ev.t_s
        from flightmode.errors import InputDataError, did_you_mean

        names = sorted({e.name for e in self.events})
        raise InputDataError(
            f"the track has no event '{name}'{did_you_mean(name, names)}; events: {', '.join(names)}"
        )

    def specific_force_at(self, lever_arm_body_m) -> np.ndarray:
        """Specific force (N x 3, m/s^2, body axes) at a point ``r`` (body axes, m) from the CG.

        Rigid body: f_P = f_CG + w_dot x r + w x (w x r).
        """
        r = np.asarray(lever_arm_body_m, dtype=float).reshape(3)
        w = self.rates_radps
        return (
            self.specific_force_body_mps2
            + np.cross(self.ang_acc_radps2, r)
            + np.cross(w, np.cross(w, np.broadcast_to(r, w.shape)))
        )

    def digest(self) -> str:
        """Equal digests mean bit-identical tracks (:func:`flightmode.digest.digest`)."""
        return digest(self)


def euler_to_quat_wxyz(euler_rad: np.ndarray) -> np.ndarray:
    """ZYX (yaw-pitch-roll) Euler angles to the body->NED unit quaternion, vectorised."""
    half = 0.5 * np.asarray(euler_rad)
    cr, sr = np.cos(half[:, 0]), np.sin(half[:, 0])
    cp, sp = np.cos(half[:, 1]), np.sin(half[:, 1])
    cy, sy = np.cos(half[:, 2]), np.sin(half[:, 2])
    return np.stack(
        [
            cr * cp * cy + sr * sp * sy,
            sr * cp * cy - cr * sp * sy,
            cr * sp * cy + sr * cp * sy,
            cr * cp * sy - sr * sp * cy,
        ],
        axis=1,
    )
