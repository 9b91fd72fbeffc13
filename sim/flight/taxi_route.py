"""Taxi routes: generated airport layouts in a runway frame, the speed each part of them is taxied at,
and pure-pursuit path following.

The runway frame has its origin at the threshold, x along the runway heading and y to the right
(metres); headings are measured from +x toward +y. The taxiway system lies on the left (y < 0): the
parallel taxiway at ``y = -taxiway_offset_m``, the aprons beyond it.

A route is the polyline of the taxiway centre lines it follows, each corner replaced by a circular
arc tangent to both legs (:func:`fillet`: the centre-line curves of ICAO Doc 9157, Aerodrome Design
Manual part 2, ch. 1), with stop points (holds). Its layout varies from flight to flight
(:func:`draw_taxi`, from the flight's ``taxi`` stream):

taxi-out (origin frame): the tug pushes the aircraft back from its stand onto an apron taxilane and
turns it 90 deg (:class:`~flightmode.sim.flight.pilot.ground.Pushback`); the taxilane either runs
parallel to the runway, joining the parallel taxiway through a link (two turns), or toward it (one
turn); along the parallel taxiway the route may change taxiways at junctions (jogs of two turns each
to a neighbouring parallel and back); at the runway end it turns onto the entry taxiway, holds short,
turns onto the runway, lines up and holds.

taxi-in (destination frame): from where the rollout handed over (20 kt, decelerating), along the
runway to an exit (a rapid exit at 30 deg on its 550 m curve, or a 45 or 90 deg exit), onto the
parallel taxiway (forward, or back after a 90 deg exit), jogs, a turn into the apron, and either
straight into the stand, or into a stand beside the apron link (its lead-in), or along an apron
taxilane and into the stand's lead-in (1, 2 or 3 turns on the apron).

The number of turns is drawn from the real tracks' turns per minute (ADS-B anchors of
:mod:`flightmode.sim.flight.taxi_stats`) and the route's expected duration, and the parallel run is
sized so that the route is about ``TaxiPlan.length_m`` long.

Speeds (:meth:`TaxiRoute.speed_at`): each leg's taxi speed (straight, apron, runway), in turns the
least of the lateral-acceleration limit sqrt(a_lat R), the yaw-rate limit r_max R and the
manufacturers' turn speeds, and before every slower part the deceleration that reaches it
(anticipation, one backward pass over a 1 m grid).
"""

from __future__ import annotations

import bisect
import math
from dataclasses import dataclass

import numpy as np

from flightmode.errors import ScenarioError
from flightmode.sim.flight.plan import FlightPlan, TaxiPlan
from flightmode.units import KMH_MPS, KT_MPS

# ICAO Doc 9157 (Aerodrome Design Manual) part 2, taxiway curves: design radius for a taxi speed
# (16 km/h -> 15 m, 32 -> 60, 48 -> 135, 64 -> 240, 80 -> 375, 96 -> 540 m): v^2 / R = 1.32 m/s^2
# (0.134 g) along the whole table, the lateral acceleration taxiway curves are designed for.
ICAO_CURVE_LAT_ACC_MPS2 = (16.0 * KMH_MPS) ** 2 / 15.0
RAPID_EXIT_ANGLE_DEG = 30.0  # ICAO Annex 14 vol. I, 3.8.18: 25-45 deg, preferably 30 deg
RAPID_EXIT_RADIUS_M = 550.0  # ICAO Doc 9157 part 2: rapid-exit turn-off curve, code 3-4 (93 km/h)
HOLD_SHORT_Y_M = -90.0  # ICAO Annex 14 vol. I, Table 3-2: holding position 90 m from a code 3-4 ILS runway
CONNECTOR_X_M = -60.0  # the entry taxiway meets the runway 60 m before the threshold (its turn pad)
LINEUP_X_M = 80.0  # lined up 80 m past the threshold, after the turn onto the runway
# ICAO Annex 14 vol. I, Table 3-1: taxiway centre line to taxiway centre line, code letter C 44 m;
# code D 63 m (the 2018 edition): the offset of a neighbouring parallel taxiway (a jog)
TAXIWAY_SEPARATION_M = (44.0, 63.0)
# Turn radii of taxiway junctions, stand lead-ins and the line-up. The six ADS-B taxi segments'
# median turn speed over their 99th-percentile yaw rate (ADSB_TAXI_ANCHORS) gives 28-69 m (median
# 36 m): real 90 deg turns are flown wider than the ICAO table's minimum for their speed (15-20 m at
# 16-19 km/h).
JUNCTION_RADIUS_M = (28.0, 60.0)
LEAD_IN_RADIUS_M = (30.0, 40.0)  # apron taxilane to stand: a little tighter
# A320 FCOM: at most 20 kt in turns (above 76 t); operators: about 10 kt in 90 deg turns. Between
# these, the cap falls linearly with the turn's angle (the profile's ``taxi_turn_kt`` at 90 deg).
TURN_CAP_WIDE_KT = 20.0
TURN_ANGLE_WIDE_DEG = 30.0
JOG_STRAIGHT_M = 30.0  # between a jog's two opposite turns
ARC_SPACING_M = 2.0  # arcs as chords of at most 2 m (sagitta < 2 cm at 25 m radius)
# turns a taxi-in's exit adds to the count of the real tracks' statistics (taxi_stats): a rapid exit's
# 30 deg on 550 m is never 30 deg within its 20 s window, but the merge onto the parallel taxiway, 30 deg
# back in a few seconds on a junction radius, counts with the exit's tail (driven on the speed schedule:
# tests/sim/test_control_and_routes.py); a 45 or 90 deg exit and its merge are two turns. Flown, pure
# pursuit rounds the merge a little and a 30 deg turn is the statistics' threshold: in 60 flown
# taxi-ins (A320, 737, 787-8) the 27 rapid exits lost 12 turns net (every other layout counted exactly)
EXIT_TURNS_COUNTED = (1, 2, 2)
TURN_LEAD_M = 12.0  # a turn's speed applies this far before its arc (pure pursuit turns in early)
GRID_M = 1.0  # the speed schedule's grid


# ----------------------------------------------------------------------------------------- paths
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
        for i in range(self._seg, min(self._seg + 8, len(self._len))):
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

    def nearest_s(self, x: float, y: float) -> float:
        """Arc length of the path's point nearest (x, y), over the whole path (vectorised; for
        building routes, not for the per-tick loop)."""
        p0 = self.points[:-1]
        u = np.clip(
            ((x - p0[:, 0]) * self.seg_dir[:, 0] + (y - p0[:, 1]) * self.seg_dir[:, 1]), 0.0, self.seg_len
        )
        ex = x - (p0[:, 0] + u * self.seg_dir[:, 0])
        ey = y - (p0[:, 1] + u * self.seg_dir[:, 1])
        i = int(np.argmin(ex * ex + ey * ey))
        return float(self.s_at[i] + u[i])


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


@dataclass(frozen=True, slots=True)
class Filleted:
    """A filleted polyline: the dense points and, per segment between them, the leg it belongs to
    (``2k`` the straight from corner k to k+1, ``2k - 1`` the arc at corner k), its radius (inf on
    straights) and its arc's whole turn (deg, 0 on straights)."""

    points: np.ndarray  # (N, 2)
    seg_leg: np.ndarray  # (N - 1,) int
    seg_radius_m: np.ndarray  # (N - 1,)
    seg_turn_deg: np.ndarray  # (N - 1,)
    radii_m: tuple[float, ...]  # the radii actually used (shrunk where the legs were too short)


def _headings(corners: np.ndarray) -> np.ndarray:
    d = np.diff(corners, axis=0)
    return np.arctan2(d[:, 1], d[:, 0])


def fillet(corners, radii_m, spacing_m: float = ARC_SPACING_M) -> Filleted:
    """Replace each interior corner i of the polyline ``corners`` (n, 2) by the circular arc of radius
    ``radii_m[i - 1]`` tangent to both of its legs (tangent length R tan(|turn| / 2)). Where two
    tangents would overlap on a leg, both radii shrink in proportion until they meet."""
    c = np.asarray(corners, dtype=float)
    n = len(c)
    r = np.asarray(radii_m, dtype=float)
    if c.ndim != 2 or c.shape[1] != 2 or n < 2 or r.shape != (n - 2,):
        raise ScenarioError(f"fillet: {n} corners need {max(n - 2, 0)} radii, got {r.shape}")
    seg = np.diff(c, axis=0)
    leg_len = np.hypot(seg[:, 0], seg[:, 1])
    if (leg_len < 1e-6).any():
        raise ScenarioError("fillet: two consecutive corners of a taxi route coincide")
    hd = _headings(c)
    turn = (np.diff(hd) + math.pi) % (2 * math.pi) - math.pi  # signed, + = right
    tan_half = np.tan(np.abs(turn) / 2.0)
    # shrink radii so that the tangents of the two ends of every leg fit on it (with 1 m to spare)
    for _ in range(3):
        t = r * tan_half
        need = np.concatenate([[0.0], t]) + np.concatenate([t, [0.0]])
        over = np.maximum(need / np.maximum(leg_len - 1.0, 1e-3), 1.0)
        scale = np.maximum(over[:-1], over[1:])  # the corner's two legs
        r = r / np.maximum(scale, 1.0)
    t = r * tan_half
    pts = [c[0]]
    leg, rad, trn = [], [], []
    for k in range(n - 1):
        # straight leg k: from the end of corner k's arc to the start of corner k+1's
        a = c[k] + (t[k - 1] if k > 0 else 0.0) * seg[k] / leg_len[k]
        b = c[k + 1] - (t[k] if k < n - 2 else 0.0) * seg[k] / leg_len[k]
        if np.hypot(*(b - a)) > 1e-6:
            pts.append(b)
            leg.append(2 * k)
            rad.append(math.inf)
            trn.append(0.0)
        if k < n - 2 and abs(turn[k]) > 1e-9:
            sgn = 1.0 if turn[k] > 0 else -1.0
            psi0 = hd[k]
            normal = np.array([-math.sin(psi0), math.cos(psi0)])
            centre = b + sgn * r[k] * normal
            m = max(2, math.ceil(r[k] * abs(turn[k]) / spacing_m))
            psi = psi0 + turn[k] * np.arange(1, m + 1) / m
            arc = centre - sgn * r[k] * np.stack([-np.sin(psi), np.cos(psi)], axis=1)
            pts.extend(arc)
            leg.extend([2 * k + 1] * m)
            rad.extend([r[k]] * m)
            trn.extend([abs(math.degrees(turn[k]))] * m)
    return Filleted(
        np.asarray(pts), np.asarray(leg), np.asarray(rad), np.asarray(trn), tuple(float(v) for v in r)
    )


# ----------------------------------------------------------------------------------------- draws
@dataclass(frozen=True, slots=True)
class TaxiStyle:
    """How this flight's crew taxis (drawn per flight inside the ranges of ``PilotTuning``)."""

    straight_out_mps: float  # on straight taxiways, taxi-out
    straight_in_mps: float  # on straight taxiways and the runway, taxi-in
    apron_mps: float  # on apron taxilanes and stand lead-ins
    lat_acc_mps2: float  # lateral acceleration allowed in turns
    yaw_rate_max_radps: float  # the fastest turn rate flown
    turn_cap_mps: float  # the speed cap in 90 deg turns (the type's taxi_turn_kt)
    decel_mps2: float  # slowing for turns and stops, and at the end of the rollout
    accel_mps2: float  # speeding up after turns and stops

    def turn_speed_mps(self, radius_m: float, turn_deg: float) -> float:
        """The speed a turn of ``radius_m`` through ``turn_deg`` is flown at: the least of
        sqrt(a_lat R), r_max R and the turn-speed cap for its angle."""
        f = min(max((turn_deg - TURN_ANGLE_WIDE_DEG) / (90.0 - TURN_ANGLE_WIDE_DEG), 0.0), 1.0)
        cap = TURN_CAP_WIDE_KT * KT_MPS + f * (self.turn_cap_mps - TURN_CAP_WIDE_KT * KT_MPS)
        return min(math.sqrt(self.lat_acc_mps2 * radius_m), self.yaw_rate_max_radps * radius_m, cap)


@dataclass(frozen=True, slots=True)
class Jog:
    """A change to the neighbouring parallel taxiway at a junction: a turn of ``angle_deg`` away,
    ``offset_m`` across, and a turn back, at ``frac`` of the parallel run."""

    frac: float
    angle_deg: float
    offset_m: float
    radius_m: float


@dataclass(frozen=True, slots=True)
class OutLayout:
    lane: str  # "parallel": the apron taxilane runs along the runway (then a link); "toward": at it
    lane_run_m: float  # along the taxilane before the first turn
    link_m: float  # taxilane to parallel taxiway (the "parallel" lane's link)
    apron_radii_m: tuple[float, ...]  # the taxilane's turn(s) onto the link / the parallel
    jogs: tuple[Jog, ...]
    entry_radius_m: float  # parallel taxiway onto the entry taxiway
    lineup_radius_m: float  # entry taxiway onto the runway


@dataclass(frozen=True, slots=True)
class InLayout:
    exit_angle_deg: float  # 30 (rapid exit), 45 or 90
    exit_radius_m: float
    merge_radius_m: float  # exit taxiway onto the parallel taxiway
    direction: int  # +1: the parallel taxiway is taxied forward (runway heading), -1 back
    jogs: tuple[Jog, ...]
    apron_radius_m: float  # parallel taxiway into the apron
    apron_link_m: float  # from the parallel taxiway to the stand (direct) or to the apron taxilane
    # turns on the apron: 0 none (a 90 deg exit straight across the parallel to the stand), 1 straight
    # into the stand, 2 into a stand's lead-in beside the apron link, 3 along an apron taxilane and
    # into the stand's lead-in
    apron_turns: int
    lane_sign: int  # +1 / -1: the taxilane's direction along x
    lane_run_m: float
    lead_in_radius_m: float
    lead_in_m: float  # the stand's straight lead-in

    @property
    def n_turns(self) -> int:
        """The turns the route is drawn to have, as the real tracks' statistics count them."""
        if self.apron_turns == 0:
            return 1
        exit_kind = (RAPID_EXIT_ANGLE_DEG, 45.0, 90.0).index(self.exit_angle_deg)
        return EXIT_TURNS_COUNTED[exit_kind] + 2 * len(self.jogs) + self.apron_turns


@dataclass(frozen=True, slots=True)
class TaxiDraws:
    """One flight's taxi draws (:func:`draw_taxi`): the crew's style, both layouts, and the
    taxi-out route built from them with the stand it starts from."""

    style: TaxiStyle
    out: OutLayout
    arrival: InLayout
    route_out: TaxiRoute
    stand_xy_m: tuple[float, float]  # the departure stand in the origin runway frame
    stand_heading_rad: float  # relative to the runway heading
    push_straight_m: float  # the tug pushes straight back this far, then turns the aircraft 90 deg

    def as_dict(self) -> dict:
        s = self.style
        return {
            "taxi_speed_out_mps": s.straight_out_mps,
            "taxi_speed_in_mps": s.straight_in_mps,
            "taxi_apron_speed_mps": s.apron_mps,
            "taxi_decel_mps2": s.decel_mps2,
            "taxi_lat_acc_mps2": s.lat_acc_mps2,
            "taxi_yaw_rate_max_dps": math.degrees(s.yaw_rate_max_radps),
            "taxi_out_junction_turns": len(self.out.apron_radii_m) + 2 * len(self.out.jogs) + 2,
            "taxi_in_exit_angle_deg": self.arrival.exit_angle_deg,
            "taxi_in_turns": self.arrival.n_turns,
        }


def _u(rng: np.random.Generator, lo_hi) -> float:
    lo, hi = lo_hi
    return float(rng.uniform(lo, hi))


def _jogs(rng: np.random.Generator, n: int, style_r) -> tuple[Jog, ...]:
    out = []
    for k in range(n):
        frac = (k + 0.5 + rng.uniform(-0.25, 0.25)) / n
        ang = float(rng.uniform(40.0, 60.0))  # junction taxiways meet the parallels obliquely or square
        out.append(Jog(frac, ang, _u(rng, TAXIWAY_SEPARATION_M), _u(rng, style_r)))
    return tuple(out)


# A taxi segment's time without its holds, as the statistics (sim.flight.taxi_stats) time it flown:
# (s per s of length over the straight speed, s), a least-squares line over 25 flown segments of each
# kind (the 20 of a seeded european-trio population and the 5 gate-to-gate built-ins; A320, 737,
# Fokker 100, 787-8): flown over predicted 0.89-1.06 (taxi-out) and 0.82-1.17 (taxi-in). The fixed part
# is the start from rest, the line-up and the apron; a term per turn hardly changed the fit (10 s a
# turn on taxi-out, 0.3 s on taxi-in; taxi-out 0.91-1.08 with it). The earlier fixed fractions of the straight speed (64 % and
# 75 %, medians of 20 A320 routes) overestimated the long routes of the built-ins by up to 29 %: their
# turns per minute, made for the estimate, came out at 0.84-0.93 flown
TAXI_TIME_FIT = {"out": (0.95, 138.0), "in": (1.02, 27.0)}


def turn_count(rate_per_min: float, duration_s: float, band_per_min: tuple[float, float], least: int) -> int:
    """The number of turns of a taxi segment expected to last ``duration_s``: the drawn rate times the
    duration, rounded (a half to the lower count), unless that leaves the rate band (a short segment:
    1 turn in 2.5 min is 0.40 per minute, 2 are 0.80), then the count whose rate lies in the band, or,
    if none does, the one whose rate is nearest to it (by ratio); at least ``least``."""
    t_min = duration_s / 60.0
    if t_min <= 0.0:  # nothing to time a rate over (a taxi plan of no length and no holds)
        return least
    lo, hi = band_per_min

    def outside(k: int) -> float:  # how far k turns' rate lies outside the band, as a log ratio
        r = k / t_min
        return max(math.log(lo / r), math.log(r / hi), 0.0)

    want = rate_per_min * t_min
    ks = range(max(least, math.floor(lo * t_min)), max(least, math.ceil(hi * t_min)) + 1)
    return min(ks, key=lambda k: (outside(k), abs(k - want)))


def draw_taxi(plan: FlightPlan, profile, rng: np.random.Generator) -> TaxiDraws:
    """The flight's taxi draws from its ``taxi`` stream: the crew's speeds and limits (ranges of the
    profile's :class:`~flightmode.sim.flight.aircraft.tuning.PilotTuning`), the number of turns
    (turns per minute of the real tracks times the route's expected duration), both layouts, and
    the taxi-out route (which fixes the stand)."""
    tu = profile.tuning
    style = TaxiStyle(
        straight_out_mps=_u(rng, tu.taxi_speed_out_mps),
        straight_in_mps=_u(rng, tu.taxi_speed_in_mps),
        apron_mps=_u(rng, tu.taxi_apron_speed_mps),
        lat_acc_mps2=_u(rng, tu.taxi_lat_acc_mps2),
        yaw_rate_max_radps=math.radians(_u(rng, tu.taxi_yaw_rate_max_dps)),
        turn_cap_mps=profile.taxi_turn_kt * KT_MPS,
        decel_mps2=_u(rng, tu.taxi_decel_mps2),
        accel_mps2=_u(rng, tu.taxi_accel_mps2),
    )
    rate_out = _u(rng, tu.taxi_turns_per_min)
    rate_in = _u(rng, tu.taxi_turns_per_min)
    # expected durations, as the statistics time a segment (taxi-out up to the takeoff roll, its line-up
    # hold included): TAXI_TIME_FIT's line in the route's length over the straight speed, and the holds
    (k_out, c_out), (k_in, c_in) = TAXI_TIME_FIT["out"], TAXI_TIME_FIT["in"]
    t_out = (
        k_out * plan.taxi_out.length_m / style.straight_out_mps
        + c_out
        + sum(plan.taxi_out.holds_s)
        + plan.taxi_out.lineup_hold_s
    )
    t_in = k_in * plan.taxi_in.length_m / style.straight_in_mps + c_in + sum(plan.taxi_in.holds_s)
    # at least the apron turn and the two at the runway
    n_out = turn_count(rate_out, t_out, tu.taxi_turns_per_min, 3)
    n_in = turn_count(rate_in, t_in, tu.taxi_turns_per_min, 1)

    # taxi-out: apron (1 or 2 turns) + 2 per jog + 2 at the runway
    lane = "toward" if (n_out - 2) % 2 == 1 else "parallel"
    n_apron = 1 if lane == "toward" else 2
    n_jogs_out = max(0, (n_out - 2 - n_apron) // 2)
    r_j = JUNCTION_RADIUS_M
    out = OutLayout(
        lane=lane,
        lane_run_m=float(rng.uniform(40.0, 120.0)),
        link_m=float(rng.uniform(100.0, 160.0)),
        apron_radii_m=tuple(_u(rng, r_j) for _ in range(n_apron)),
        jogs=_jogs(rng, n_jogs_out, r_j),
        entry_radius_m=_u(rng, r_j),
        lineup_radius_m=_u(rng, r_j),
    )
    # taxi-in: exit and merge (EXIT_TURNS_COUNTED), apron (0 when a 90 deg exit leads straight to the
    # stand, 1 straight in, 2 into a stand beside the apron link, 3 by a taxilane), 2 per jog; the apron
    # takes the count's parity, so that every count is flown (the real tracks' taxi-ins turn 1-4 times)
    exit_kind = int(rng.integers(0, 3))
    if n_in == 1:
        exit_kind = 2  # one turn: off the runway at 90 deg and straight across to the stand
    elif n_in < 4:
        exit_kind = 0  # few turns wanted: a rapid exit
    exit_angle = (RAPID_EXIT_ANGLE_DEG, 45.0, 90.0)[exit_kind]
    n_exit = 1 if n_in == 1 else EXIT_TURNS_COUNTED[exit_kind]
    rest = n_in - n_exit
    lane_in = rest >= 3 and bool(rng.random() < 0.7)
    n_apron_in = 0 if rest == 0 else 2 if rest % 2 == 0 else (3 if lane_in else 1)
    n_jogs_in = max(0, (rest - n_apron_in) // 2)
    arrival = InLayout(
        exit_angle_deg=exit_angle,
        exit_radius_m=RAPID_EXIT_RADIUS_M if exit_kind == 0 else _u(rng, r_j),
        merge_radius_m=_u(rng, r_j),
        direction=1 if exit_kind < 2 or rng.random() < 0.5 else -1,
        jogs=_jogs(rng, n_jogs_in, r_j),
        apron_radius_m=_u(rng, r_j),
        apron_link_m=float(rng.uniform(100.0, 160.0)),
        apron_turns=n_apron_in,
        lane_sign=1 if rng.random() < 0.5 else -1,
        lane_run_m=float(rng.uniform(60.0, 150.0)),
        lead_in_radius_m=_u(rng, LEAD_IN_RADIUS_M),
        lead_in_m=float(rng.uniform(30.0, 50.0)),
    )
    route, stand, heading, push = taxi_out_route(
        plan.taxi_out, plan.origin.length_m, out, style, profile.wheelbase_m
    )
    return TaxiDraws(style, out, arrival, route, stand, heading, push)


# ----------------------------------------------------------------------------------------- routes
class TaxiRoute:
    """A taxi route: its path (:class:`Path2D`, stops included) and its speed schedule on a 1 m grid
    (:meth:`speed_at`)."""

    def __init__(
        self,
        fl: Filleted,
        zone_speed_mps: np.ndarray,
        style: TaxiStyle,
        stops: tuple[Stop, ...] = (),
        speed_mps: np.ndarray | None = None,
    ):
        self.path = Path2D(fl.points, stops)
        self.fillet = fl
        self.style = style
        self.zone_speed_mps = zone_speed_mps
        self.speed_mps = (
            _speed_schedule(self.path, fl, zone_speed_mps, style) if speed_mps is None else speed_mps
        )
        self._v = self.speed_mps.tolist()

    def with_stops(self, stops: tuple[Stop, ...]) -> TaxiRoute:
        """The same route with these stops (the speed schedule does not depend on them: the Taxi
        controller brakes for each stop itself)."""
        return TaxiRoute(self.fillet, self.zone_speed_mps, self.style, stops, self.speed_mps)

    def speed_at(self, s_m: float) -> float:
        """The schedule's speed at arc length ``s_m`` (linear between grid points)."""
        v = self._v
        k = min(max(s_m / GRID_M, 0.0), len(v) - 1.000001)
        i = int(k)
        return v[i] + (k - i) * (v[i + 1] - v[i])


def _speed_schedule(path: Path2D, fl: Filleted, seg_speed_mps: np.ndarray, style: TaxiStyle) -> np.ndarray:
    """Speed limit on the 1 m grid: each segment's taxi speed, each turn's speed from its arc's start
    (less ``TURN_LEAD_M``) to its end, then the deceleration that reaches every slower part in time:
    v(s)^2 <= v(s')^2 + 2 a (s' - s) for all s' > s, a reversed running minimum."""
    s = np.arange(0.0, path.length_m + GRID_M, GRID_M)
    seg = np.clip(np.searchsorted(path.s_at, s, side="right") - 1, 0, len(path.seg_len) - 1)
    v = seg_speed_mps[seg].astype(float)
    arcs = np.flatnonzero(np.isfinite(fl.seg_radius_m))
    if arcs.size:
        legs = fl.seg_leg[arcs]
        first = np.concatenate([[True], np.diff(legs) != 0])
        last = np.concatenate([np.diff(legs) != 0, [True]])
        for i0, i1 in zip(arcs[first], arcs[last]):
            v_turn = style.turn_speed_mps(float(fl.seg_radius_m[i0]), float(fl.seg_turn_deg[i0]))
            lo = np.searchsorted(s, path.s_at[i0] - TURN_LEAD_M)
            hi = np.searchsorted(s, path.s_at[i1 + 1], side="right")
            v[lo:hi] = np.minimum(v[lo:hi], v_turn)
    w = v * v + 2.0 * style.decel_mps2 * s
    w = np.minimum.accumulate(w[::-1])[::-1]
    return np.sqrt(np.maximum(w - 2.0 * style.decel_mps2 * s, 0.0))


def _zone_speeds(fl: Filleted, leg_zone: list[str], style: TaxiStyle, straight_mps: float) -> np.ndarray:
    """Per segment: the straight-leg speed of its zone ("apron", "taxiway"); an arc takes the slower of
    its two legs' zones."""
    speed = {"apron": style.apron_mps, "taxiway": straight_mps}
    leg_v = np.array([speed[z] for z in leg_zone])
    k = fl.seg_leg // 2
    arc = fl.seg_leg % 2 == 1
    v = leg_v[np.minimum(k, len(leg_v) - 1)]
    v_next = leg_v[np.minimum(k + 1, len(leg_v) - 1)]
    return np.where(arc, np.minimum(v, v_next), v)


def _jog_corners(x0: float, x1: float, y: float, jogs: tuple[Jog, ...], direction: float, outward: float):
    """Corners of the jogs along a parallel run from x0 to x1 (``direction`` +1/-1 along x), starting
    at y; each jog moves ``outward`` (-1: away from the runway) then the next one back."""
    corners, radii = [], []
    side = outward
    for j in sorted(jogs, key=lambda j: j.frac):
        xj = x0 + j.frac * (x1 - x0)
        th = math.radians(j.angle_deg)
        dx = j.offset_m / math.tan(th)
        corners += [(xj - direction * dx / 2, y), (xj + direction * dx / 2, y + side * j.offset_m)]
        # the two opposite turns keep JOG_STRAIGHT_M of straight between them (the yaw rate reverses)
        r_fit = max(j.offset_m / math.sin(th) - JOG_STRAIGHT_M, 0.0) / (2.0 * math.tan(th / 2.0))
        r = max(min(j.radius_m, r_fit), JUNCTION_RADIUS_M[0] / 2.0)
        radii += [r, r]
        y += side * j.offset_m
        side = -side
    return corners, radii, y


def _jogs_room_m(jogs: tuple[Jog, ...]) -> float:
    """The parallel run the jogs need: each one's length along x, its tangents and straights between."""
    return sum(j.offset_m / math.tan(math.radians(j.angle_deg)) + 2 * j.radius_m + 60.0 for j in jogs) + 60.0


def taxi_out_route(
    plan: TaxiPlan, runway_length_m: float, lay: OutLayout, style: TaxiStyle, wheelbase_m: float
):
    """The taxi-out route, the stand (x, y), its heading relative to the runway, and the pushback's
    straight part. The route starts where the tug leaves the aircraft on the apron taxilane and is
    about ``plan.length_m`` less the pushback long to the line-up point; it runs on to the runway's end."""
    d, a = plan.taxiway_offset_m, plan.apron_depth_m
    r_push = wheelbase_m / math.tan(math.radians(35.0))  # the tug turns the nose wheel 35 deg
    if a < r_push + 5.0:
        raise ScenarioError(
            f"[taxi_out].apron_depth_m = {a:g}: the pushback needs at least "
            f"{r_push + 5.0:.0f} m for the 90 deg turn of this aircraft"
        )
    target = max(plan.length_m - a, 0.0)
    room = _jogs_room_m(lay.jogs)

    def build(x_join: float):
        if lay.lane == "parallel":
            y_lane = -(d + lay.link_m)
            x_rel = x_join + lay.lane_run_m
            corners = [(x_rel, y_lane), (x_join, y_lane), (x_join, -d)]
            zones = ["apron", "apron"]
            stand = (x_rel - r_push, y_lane - a)
            heading = -math.pi / 2  # nose away from the runway; pushed back toward it, turned nose left
        else:
            y_rel = -(d + lay.lane_run_m + 40.0)
            corners = [(x_join, y_rel), (x_join, -d)]
            zones = ["apron"]
            stand = (x_join - a, y_rel + r_push)
            heading = math.pi  # nose toward the threshold; pushed back down the runway, turned nose left
        radii = list(lay.apron_radii_m)
        jc, jr, y_end = _jog_corners(x_join, CONNECTOR_X_M, -d, lay.jogs, -1.0, -1.0)
        corners += jc + [(CONNECTOR_X_M, y_end), (CONNECTOR_X_M, 0.0), (runway_length_m, 0.0)]
        radii += jr + [lay.entry_radius_m, lay.lineup_radius_m]
        zones += ["taxiway"] * (len(corners) - 1 - len(zones))
        fl = fillet(corners, radii)
        route = TaxiRoute(fl, _zone_speeds(fl, zones, style, style.straight_out_mps), style)
        return route, stand, heading, y_end

    x_min = CONNECTOR_X_M + room
    route, *_ = build(x_min + 500.0)
    s_lineup = route.path.nearest_s(LINEUP_X_M, 0.0)
    x_join = max(x_min, x_min + 500.0 + target - s_lineup)
    route, stand, heading, y_end = build(x_join)
    path = route.path
    # holds: evenly along the parallel run, moved off any arc (no stopping in a turn: Boeing 737 FCTM)
    s0, s1 = path.nearest_s(x_join, -d), path.nearest_s(CONNECTOR_X_M, y_end)
    stops = [
        Stop(_off_arcs(route, s0 + (k + 1) * (s1 - s0) / (len(plan.holds_s) + 1)), h, f"hold{k + 1}")
        for k, h in enumerate(plan.holds_s)
    ]
    stops.append(Stop(path.nearest_s(CONNECTOR_X_M, HOLD_SHORT_Y_M), 0.0, "hold_short"))
    stops.append(Stop(path.nearest_s(LINEUP_X_M, 0.0), plan.lineup_hold_s, "lineup"))
    return route.with_stops(tuple(stops)), stand, heading, a - r_push


def _off_arcs(route: TaxiRoute, s_m: float) -> float:
    """``s_m``, or the nearest arc length at least 15 m from any arc."""
    path, fl = route.path, route.fillet
    arc = np.isfinite(fl.seg_radius_m)
    grid = np.arange(0.0, path.length_m, 1.0)
    seg = np.clip(np.searchsorted(path.s_at, grid, side="right") - 1, 0, len(arc) - 1)
    near = np.convolve(arc[seg].astype(float), np.ones(31), mode="same") > 0
    ok = np.flatnonzero(~near)
    if ok.size == 0:
        return s_m
    return float(grid[ok[np.argmin(np.abs(grid[ok] - s_m))]])


def taxi_in_route(
    plan: TaxiPlan, lay: InLayout, style: TaxiStyle, start_x_m: float, start_speed_mps: float
) -> TaxiRoute:
    """The taxi-in route from the runway centreline at ``start_x_m``, where the rollout handed over at
    ``start_speed_mps``, to the arrival stand (the route's end), about ``plan.length_m`` long. Its
    runway part is as long as slowing from the hand-over speed to the exit's turn speed at the crew's
    deceleration takes."""
    d = plan.taxiway_offset_m
    th = math.radians(lay.exit_angle_deg)
    v_exit = min(style.turn_speed_mps(lay.exit_radius_m, lay.exit_angle_deg), style.straight_in_mps)
    t_exit = lay.exit_radius_m * math.tan(th / 2)
    run = max(20.0, (start_speed_mps**2 - v_exit**2) / (2.0 * style.decel_mps2)) + TURN_LEAD_M + 10.0
    x_e1 = start_x_m + run + t_exit
    sgn = lay.direction
    if lay.exit_angle_deg < 90.0:
        x_e2 = x_e1 + d / math.tan(th)
    else:
        x_e2 = x_e1
    room = _jogs_room_m(lay.jogs)

    def build(par_run: float):
        if lay.apron_turns == 0:  # off the runway at 90 deg, across the parallel, straight to the stand
            y_apron = -d - par_run + lay.apron_link_m + lay.lead_in_m  # taxiway speed until the apron
            corners = [(start_x_m, 0.0), (x_e1, 0.0), (x_e1, y_apron), (x_e1, -d - par_run)]
            fl = fillet(corners, [lay.exit_radius_m, 0.0])
            zones = ["taxiway", "taxiway", "apron"]
            return TaxiRoute(fl, _zone_speeds(fl, zones, style, style.straight_in_mps), style), (
                x_e1,
                y_apron,
            )
        x_ap = x_e2 + sgn * par_run
        corners = [(start_x_m, 0.0), (x_e1, 0.0), (x_e2, -d)]
        radii = [lay.exit_radius_m, lay.merge_radius_m]
        jc, jr, y = _jog_corners(x_e2, x_ap, -d, lay.jogs, sgn, -1.0)
        corners += jc + [(x_ap, y)]
        radii += jr
        zones = ["taxiway"] * (len(corners) - 1)
        if lay.apron_turns == 3:
            y_lane = y - lay.apron_link_m
            x_st = x_ap + lay.lane_sign * lay.lane_run_m
            corners += [(x_ap, y_lane), (x_st, y_lane), (x_st, y_lane - lay.lead_in_m)]
            radii += [lay.apron_radius_m, lay.lead_in_radius_m, lay.lead_in_radius_m]
            zones += ["apron"] * 3
        elif lay.apron_turns == 2:
            y_lane = y - lay.apron_link_m
            # the lead-in turns back to the parallel's direction: two opposite turns, which the real
            # tracks' statistics (taxi_stats) count as two
            corners += [(x_ap, y_lane), (x_ap + sgn * lay.lead_in_m, y_lane)]
            radii += [lay.apron_radius_m, lay.lead_in_radius_m]
            zones += ["apron"] * 2
        else:
            corners += [(x_ap, y - lay.apron_link_m - lay.lead_in_m)]
            radii += [lay.apron_radius_m]
            zones += ["apron"]
        fl = fillet(corners, radii)
        return TaxiRoute(fl, _zone_speeds(fl, zones, style, style.straight_in_mps), style), (x_ap, y)

    route, _ = build(room + 200.0)
    least = lay.apron_link_m + lay.lead_in_m if lay.apron_turns == 0 else room
    par = max(least, room + 200.0 + plan.length_m - route.path.length_m)
    route, par_end = build(par)
    path = route.path
    s0, s1 = path.nearest_s(x_e2, -d), path.nearest_s(*par_end)
    stops = tuple(
        Stop(_off_arcs(route, s0 + (k + 1) * (s1 - s0) / (len(plan.holds_s) + 1)), h, f"hold{k + 1}")
        for k, h in enumerate(plan.holds_s)
    )
    return route.with_stops(stops)
