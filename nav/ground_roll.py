"""A ground roll (the takeoff roll, the landing rollout) rebuilt from the bag's own accelerometer.

Over a whole flight, double integration of a MEMS unit drifts without bound (a constant offset b
alone gives 0.5 b t^2: 650 km after an hour for 10 mg), which is why ``flightmode path``
needs the truth's frames and the gate positions. A ground roll is the opposite case: it lasts 30-60 s,
runs straight along a runway, and is bracketed by a stop (the line-up hold before the takeoff roll;
after the rollout, the first stop once the aircraft has left the runway). At such a stop the bag
reads gravity plus its offset and nothing else, so their sum, measured there, is removed from the
roll's samples; what is left is the aircraft's kinematic acceleration plus the residuals (noise,
cross-axis coupling, attitude changes between the stop and the roll). Steps, all vectorised:

1. ``rest`` = the mean specific force over the stop (sensor axes, g): gravity and the zero-g offset
   together (they cannot be told apart at rest, and need not be).
2. ``d = acc - rest``: the kinematic acceleration in the bag's axes (f = a - g; the offset cancels).
3. The direction of travel: the bag lies at an unknown yaw, so the along-track axis is taken as the
   direction of the *mean* of ``d`` over the roll, ``u = mean(d) / |mean(d)|``: the aircraft's mean
   acceleration, horizontal on a level runway (the vertical bumps average out) and along the track
   (the lateral centreline corrections, of either sign, average out too). The takeoff roll
   accelerates along its direction of travel: travel = u; the rollout decelerates: travel = -u.
   The horizontal plane is not taken from the stop's "up" (``rest / |rest|``): the offset tilts it
   by |b_horizontal| / 1 g (3 degrees for 50 mg), and projecting on it would lose the cosine of that.
4. ``a = (d . travel) g0``: the along-track acceleration, m/s^2 (components across it are dropped).
5. Speed and distance by seed 002's cubic-spline recurrence (Revesz 2014, section III, eq. 17-19:
   :func:`flightmode.nav.spline_path.recurrence_path`) from one known speed: forward from the start
   of the roll (the takeoff roll starts from the line-up stop: 0 m/s), or backwards from its end
   (time reversed, ``tau = t_end - t``: the acceleration keeps its sign, the velocity flips), for a
   roll whose known speed is at its end (a rollout followed by a stop, or ended at a known speed).

What remains is bounded: an offset residual r over a roll of T seconds moves the speed by r T and
the length by 0.5 r T^2 (T = 40 s: 1 mg gives 0.4 m/s and 7.8 m).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Literal

import numpy as np

from flightmode.errors import NavError
from flightmode.nav.spline_path import recurrence_path
from flightmode.units import G0_MPS2  # the g in which accelerometer samples are expressed


@dataclass(frozen=True, slots=True)
class RollEstimate:
    """A ground roll rebuilt from accelerometer samples (:func:`estimate_roll`); arrays at ``t_s``."""

    t_s: np.ndarray  # (n,) sample times, s
    along_acc_mps2: np.ndarray  # (n,) along-track acceleration, m/s^2 (positive along the travel)
    speed_mps: np.ndarray  # (n,) along-track speed, m/s
    distance_m: np.ndarray  # (n,) distance travelled since the first sample, m
    travel_axis: tuple[float, float, float]  # unit vector of the direction of travel, sensor axes
    rest_specific_force_g: tuple[float, float, float]  # mean over the stop: gravity + zero-g offset, g

    @property
    def length_m(self) -> float:
        return float(self.distance_m[-1])

    @property
    def start_speed_mps(self) -> float:
        return float(self.speed_mps[0])

    @property
    def end_speed_mps(self) -> float:
        return float(self.speed_mps[-1])

    @property
    def peak_speed_mps(self) -> float:
        return float(self.speed_mps.max())


def along_track_acceleration(
    acc_g, rest_acc_g, accelerating: bool
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Steps 1-4 of the module docstring: (along-track acceleration m/s^2 (n,), travel axis (3,),
    rest specific force g (3,)). ``acc_g``: (n, 3) samples of the roll; ``rest_acc_g``: (m, 3)
    samples of the stop, the bag in the same place on the aircraft; ``accelerating``: True when the
    roll speeds up (travel along the mean acceleration), False when it slows down."""
    a = np.asarray(acc_g, float)
    r = np.asarray(rest_acc_g, float)
    for name, x in (("roll", a), ("rest", r)):
        if x.ndim != 2 or x.shape[1] != 3 or x.shape[0] == 0:
            raise NavError(f"the {name} samples must be an (n, 3) array with n >= 1, got shape {x.shape}")
        if not np.isfinite(x).all():
            raise NavError(f"the {name} samples hold NaN or inf: clean or cut the stream first")
    rest = r.mean(axis=0)
    g_read = float(np.linalg.norm(rest))
    if g_read < 0.5:
        raise NavError(
            f"the stop's mean specific force is {g_read:.3f} g: an accelerometer at rest reads about 1 g "
            "(is the stop the bag's, in g?)"
        )
    d = a - rest
    mean = d.mean(axis=0)
    m = float(np.linalg.norm(mean))
    if m == 0.0:
        raise NavError("the roll's mean acceleration is zero: no direction of travel to take")
    travel = mean / m if accelerating else -mean / m
    return (d @ travel) * G0_MPS2, travel, rest


def integrate_along_track(
    t_s, along_acc_mps2, known_speed_mps: float, known_at: Literal["start", "end"]
) -> tuple[np.ndarray, np.ndarray]:
    """Step 5: (speed m/s, distance since the first sample m) at ``t_s``, by seed 002's recurrence
    (section III) from ``known_speed_mps`` at the first sample (``known_at="start"``) or, integrating
    backwards in time, at the last one (``"end"``)."""
    t = np.asarray(t_s, float)
    a = np.asarray(along_acc_mps2, float)
    if known_at == "start":
        p = recurrence_path(t, a, 0.0, known_speed_mps)  # seed 002 eq. 17-18
        return p.derivative()(t), p(t)
    if known_at == "end":
        tau = t[-1] - t[::-1]  # reversed time: x'(tau) = x(t_end - tau) - x(t_end), x'' = x''
        p = recurrence_path(tau, a[::-1], 0.0, -known_speed_mps)
        x = p(tau)[::-1]  # x(t) - x(t_end) at t
        return -p.derivative()(tau)[::-1], x - x[0]
    raise NavError(f"known_at must be 'start' or 'end', got {known_at!r}")


def estimate_roll(
    t_s,
    acc_g,
    rest_acc_g,
    *,
    accelerating: bool,
    known_speed_mps: float,
    known_at: Literal["start", "end"],
) -> RollEstimate:
    """A ground roll from the bag's samples (module docstring): ``acc_g`` (n, 3) over the roll at
    ``t_s``, ``rest_acc_g`` (m, 3) over the stop that gives the offset and the tilt, the known speed
    and where it holds. The takeoff roll: ``accelerating=True, known_speed_mps=0, known_at="start"``."""
    t = np.asarray(t_s, float)
    if t.ndim != 1 or t.shape[0] != np.shape(acc_g)[0]:
        raise NavError(f"time has shape {t.shape} but the roll has {np.shape(acc_g)[0]} samples")
    along, travel, rest = along_track_acceleration(acc_g, rest_acc_g, accelerating)
    speed, dist = integrate_along_track(t, along, known_speed_mps, known_at)
    return RollEstimate(
        t_s=t,
        along_acc_mps2=along,
        speed_mps=speed,
        distance_m=dist,
        travel_axis=(float(travel[0]), float(travel[1]), float(travel[2])),
        rest_specific_force_g=(float(rest[0]), float(rest[1]), float(rest[2])),
    )


__all__ = ["RollEstimate", "along_track_acceleration", "estimate_roll", "integrate_along_track"]
