"""Small control blocks for the pilot: a clamped PI(D) loop with anti-windup, and rate limits.

Plain scalar Python (the pilot runs at a few tens of hertz; NumPy scalars would be slower).
"""

from __future__ import annotations

from dataclasses import dataclass, field


@dataclass(slots=True)
class PID:
    """u = kp*e + ki*integral(e) + kd*de/dt, clamped to [lo, hi], with conditional integration."""

    kp: float
    ki: float = 0.0
    kd: float = 0.0
    lo: float = -1.0
    hi: float = 1.0
    integral: float = 0.0
    _prev_e: float | None = field(default=None, repr=False)

    def reset(self, integral: float = 0.0) -> None:
        self.integral = integral
        self._prev_e = None

    def __call__(self, e: float, dt_s: float, ff: float = 0.0) -> float:
        de = 0.0 if self._prev_e is None else (e - self._prev_e) / dt_s
        self._prev_e = e
        u_unsat = ff + self.kp * e + self.ki * self.integral + self.kd * de
        # anti-windup: integrate only when not pushing further into saturation
        if (u_unsat < self.hi or e < 0.0) and (u_unsat > self.lo or e > 0.0):
            self.integral += e * dt_s
        u = ff + self.kp * e + self.ki * self.integral + self.kd * de
        return min(self.hi, max(self.lo, u))


def clamp(x: float, lo: float, hi: float) -> float:
    return min(hi, max(lo, x))


def first_order_lag(current: float, target: float, dt_s: float, tau_s: float) -> float:
    """One step of a first-order low-pass of time constant ``tau_s`` (forward Euler, its gain capped at 1)."""
    return current + (target - current) * min(1.0, dt_s / tau_s)


def rate_limit(current: float, target: float, max_step: float) -> float:
    """Move ``current`` toward ``target`` by at most ``max_step``."""
    if target > current + max_step:
        return current + max_step
    if target < current - max_step:
        return current - max_step
    return target
