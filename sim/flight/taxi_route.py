"""Ground paths in a runway frame, generated taxi routes, and pure-pursuit path following.

The runway frame has its origin at the threshold, x along the runway heading and y to the right
(metres). Routes are polylines with stop points (holds). Generated geometry (``TaxiPlan``):

taxi-out: the stand faces the terminal (nose to -y) at ``y = -(offset + apron)``; the tug pushes
the aircraft back onto the parallel taxiway (``y = -offset``) turning it to face the threshold;
it taxis along the taxiway (holds evenly spaced), turns onto a connector 60 m before the
threshold, holds short 75 m from the centreline, lines up and holds on the runway.

taxi-in: from where the rollout slowed down, a 45 degree exit to the left, the taxiway onward,
and a 90 degree left turn into the stand.
"""

from __future__ import annotations

import bisect
import math
from dataclasses import dataclass

import numpy as np

from flightmode.sim.flight.plan import TaxiPlan

CONNECTOR_X_M = -60.0
HOLD_SHORT_Y_M = -75.0
LINEUP_X_M = 80.0


@dataclass(frozen=True, slots=True)
class Stop:
    s_m: float  # arc length along the path where the aircraft stops
    hold_s: float
    name: str


class Path2D:
    """A polyline with arc length, corner positions and stops."""

    def __init__(self, points, stops: tuple[Stop, ...] = ()):
        self.points = np.asarray(points, dtype=float)
        seg = np.diff(self.points, axis=0)
        self.seg_len = np.hypot(seg[:, 0], seg[:, 1])
        self.seg_dir = seg / self.seg_len[:, None]
        self.s_at = np.concatenate([[0.0], np.cumsum(self.seg_len)])
        self.length_m = float(self.s_at[-1])
        headings = np.arctan2(self.seg_dir[:, 1], self.seg_dir[:, 0])
        turn = np.abs((np.diff(headings) + math.pi) % (2 * math.pi) - math.pi)
        self.corners_s = tuple(float(s) for s, a in zip(self.s_at[1:-1], turn) if a > math.radians(20))
        self.stops = tuple(sorted(stops, key=lambda st: st.s_m))
        self._seg = 0
        # plain-float copies for the per-tick scalar math (NumPy scalars cost ~10x a float here)
        self._pts = self.points.tolist()
        self._dir = self.seg_dir.tolist()
        self._len = self.seg_len.tolist()
        self._s = self.s_at.tolist()

    def s_of(self, name: str) -> float:
        return next(st.s_m for st in self.stops if st.name == name)

    def project(self, x: float, y: float) -> tuple[float, float]:
        """Arc length of the nearest point (searching forward from the last segment) and signed
        cross-track distance (positive = right of the path)."""
        best = (math.inf, 0.0, 0.0, self._seg)
        for i in range(self._seg, min(self._seg + 3, len(self._len))):
            px, py = self._pts[i]
            dx, dy = self._dir[i]
            u = (x - px) * dx + (y - py) * dy
            u_c = min(max(u, 0.0), self._len[i])
            ex, ey = x - (px + u_c * dx), y - (py + u_c * dy)
            d2 = ex * ex + ey * ey
            if d2 < best[0] - 1e-9:
                cross = dx * (y - py) - dy * (x - px)
                best = (d2, self._s[i] + u_c, cross, i)
        if best[1] >= self._s[best[3] + 1] - 1e-6 and best[3] + 1 < len(self._len):
            best = (best[0], best[1], best[2], best[3] + 1)
        self._seg = best[3]
        return best[1], best[2]

    def point_at(self, s: float) -> tuple[float, float]:
        if s >= self.length_m:
            i = len(self._len) - 1
        else:
            i = max(0, bisect.bisect_right(self._s, s) - 1)
        u = s - self._s[i]
        px, py = self._pts[i]
        dx, dy = self._dir[i]
        return px + u * dx, py + u * dy


def pure_pursuit_steer_rad(
    x: float, y: float, heading_rad: float, target: tuple[float, float], wheelbase_m: float
) -> tuple[float, float]:
    """Pure-pursuit nose-wheel angle (rad, positive right) toward ``target``, and the bearing
    error (rad) of the target relative to the heading (both in the runway frame)."""
    tx, ty = target
    bearing = math.atan2(ty - y, tx - x)
    alpha = (bearing - heading_rad + math.pi) % (2 * math.pi) - math.pi
    ld = max(math.hypot(tx - x, ty - y), 1.0)
    return math.atan2(2.0 * wheelbase_m * math.sin(alpha), ld), alpha


def gate_position_out(plan: TaxiPlan) -> tuple[float, float, float]:
    """Stand position (x, y) in the origin runway frame and its heading relative to the runway (rad)."""
    x_gate = max(50.0, plan.length_m - plan.taxiway_offset_m - plan.apron_depth_m + CONNECTOR_X_M)
    return x_gate, -(plan.taxiway_offset_m + plan.apron_depth_m), -math.pi / 2


def taxi_out_path(plan: TaxiPlan, start_xy: tuple[float, float], runway_length_m: float) -> Path2D:
    """From where the tug left the aircraft to the far end of the departure runway."""
    x0, y0 = start_xy
    d = plan.taxiway_offset_m
    pts = [
        (x0, y0),
        (x0 - 60.0, -d),
        (CONNECTOR_X_M, -d),
        (CONNECTOR_X_M, 0.0),
        (runway_length_m, 0.0),
    ]
    path = Path2D(pts)
    taxiway_start, taxiway_end = path.s_at[1], path.s_at[2]
    stops = [
        Stop(taxiway_start + (k + 1) * (taxiway_end - taxiway_start) / (len(plan.holds_s) + 1), h, f"hold{k + 1}")
        for k, h in enumerate(plan.holds_s)
    ]
    stops.append(Stop(path.s_at[3] - (0.0 - HOLD_SHORT_Y_M), 0.0, "hold_short"))
    stops.append(Stop(path.s_at[3] + LINEUP_X_M - CONNECTOR_X_M, plan.lineup_hold_s, "lineup"))
    return Path2D(pts, tuple(stops))


def taxi_in_path(plan: TaxiPlan, start_x_m: float) -> Path2D:
    """From the runway centreline at ``start_x_m`` to the arrival stand (the path's end)."""
    d, a = plan.taxiway_offset_m, plan.apron_depth_m
    x_exit = start_x_m + 40.0
    run = max(100.0, plan.length_m - 40.0 - d * math.sqrt(2.0) - a)
    pts = [
        (start_x_m, 0.0),
        (x_exit, 0.0),
        (x_exit + d, -d),
        (x_exit + d + run, -d),
        (x_exit + d + run, -d - a),
    ]
    path = Path2D(pts)
    stops = [
        Stop(path.s_at[2] + (k + 1) * run / (len(plan.holds_s) + 1), h, f"hold{k + 1}")
        for k, h in enumerate(plan.holds_s)
    ]
    return Path2D(pts, tuple(stops))
