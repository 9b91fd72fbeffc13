"""Runway and taxiway roughness felt through the gear: ISO 8608 random profiles under each wheel
(:mod:`flightmode.sim.flight.runway_roughness`), turned into the strut-force changes JSBSim's own gear
would feel on them (the model's forces: :mod:`~flightmode.sim.flight.jsbsim.roughness_model`).

JSBSim's terrain is one flat elevation, so its gear rolls as on glass. Here each surface the aircraft
rolls on (origin taxiway, origin runway, destination runway, destination taxiway) gets a seeded
random profile along its path, and each gear group (nose, left main, right main) feels the profile
under its wheels as an extra vertical force, so that JSBSim computes the heave, pitch and roll
response with its own mass, inertia and gear.

Datum: each wheel's force is k (w - d) + D(w_dot), d its datum: the wheel's own height through a
first-order lag of :data:`DATUM_TAU_S` (d = w where it starts rolling, so the force starts at 0). The
struts carry what the ground does slowly, as the real ones do on a slope; the force carries the
bumps. A fixed datum (the ground where the wheel started) let the profile's long waves build static
forces of thousands of lbf over a taxi route (6,400 lbf lifting an A320's nose wheel: 3/4 of its
static load); at the stand JSBSim's contact then held a 2.6 Hz rocking of 0.025 g after the engines
stopped (3 of 20 A320 flights of a validated dataset, seed 000 Table 2's rest spread 15-18 times the
paper's). Stopped
(below :data:`ROLLING_MIN_MPS`), the wheels stay where they are on the profile and the force decays
with the datum.

Timing: Python works only at the pilot's ticks and only on the ground, from taxi-out to the stand. At
each tick it writes the force *knots* of the tick's interval, 1/40 s apart (one knot at the runway's
40 Hz ticks, four at the taxiway's 10 Hz), into a ring of :data:`RING` slots in the model; JSBSim
interpolates them linearly at every step (``interpolate1d`` of ``simulation/sim-time-sec``), and
consecutive ticks' knots follow on, so a tick writes only its new knots. Each knot is the profile
averaged over the distance rolled between knots (prefix sums): a box filter matched to the speed, so
that no short wave aliases into the rigid-body band, which keeps the force within about 10 Hz.
"""

from __future__ import annotations

import math
from array import array

import numpy as np

from flightmode.errors import AircraftError
from flightmode.sim.flight.jsbsim.roughness_model import KNOT_S, RING
from flightmode.sim.flight.runway_roughness import (
    DX_M,
    PERIOD_SAMPLES,
    PHASE_SURFACE,
    SURFACES,
    RunwayRoughness,
    synthesize_tracks,
)
from flightmode.units import FT_M, LBF_N

MAX_KNOTS = 4  # knots per tick (10 Hz ticks: four)
GROUPS = ("nose", "left", "right")
_MASK = PERIOD_SAMPLES - 1
_RING_MASK = RING - 1
TYRE_DEFLECTION_M = 0.08  # tyre deflection under static load (module docstring)
SQUARE_DAMPING_RATE_MPS = 0.1  # a square-law damper counts as linear at this strut rate in the tyre lag
# Each wheel's datum follows its height with this time constant (module docstring, Datum): the force is
# the profile's change, not its level. Waves longer than 2 pi v tau (63 m at a 5 m/s taxi, 880 m on a
# 70 m/s roll) are slopes the aircraft stands on; at 0.2 Hz the leak keeps 93 % of the force, above
# 1 Hz all of it
DATUM_TAU_S = 2.0
# below this ground speed the wheels are at rest on the profile: no new profile comes under them. A
# stopped aircraft still rocks on its struts at a few mm/s; counted as rolling (a speed's magnitude
# never runs backwards), that would creep the wheels along the profile and step the force at every
# 0.1 m sample crossed. At 0.1 m/s a wheel crosses one sample a second: slower than a tyre's footprint
# would notice
ROLLING_MIN_MPS = 0.1


# ------------------------------------------------------------------------------ in the step loop
class _Surface:
    """One surface's three tracks as flat arrays for per-tick lookups: heights h and prefix sums
    C (C[i] = h[0] + ... + h[i-1]; zero-mean periodic profile, so C wraps seamlessly)."""

    __slots__ = ("c", "h")

    def __init__(self, tracks: np.ndarray):
        self.h = [array("d", t.tobytes()) for t in tracks]
        c = np.zeros_like(tracks)
        np.cumsum(tracks[:, :-1], axis=1, out=c[:, 1:])
        self.c = [array("d", t.tobytes()) for t in c]


class GearRoughness:
    """Sets the roughness forces of a model loaded with
    :func:`~flightmode.sim.flight.jsbsim.roughness_model.add_gear_roughness` at each pilot tick (:meth:`tick`), from the flight's random ``streams`` (one stream per surface,
    :data:`SURFACES`; a profile is made when the aircraft first rolls on its surface).

    Make it with the aircraft at rest on its gear: each group's static load (spring times
    compression) sets its tyre stiffness (:data:`TYRE_DEFLECTION_M`)."""

    def __init__(self, ac, streams, fdm_hz: float, surfaces: dict[str, RunwayRoughness] | None = None):
        pm = ac.fdm.get_property_manager()

        def node(prop: str):
            nd = pm.get_node(prop, False)
            if nd is None:
                raise AircraftError(
                    f"the model has no property '{prop}': load it with roughness_model.add_gear_roughness"
                )
            return nd

        def get(p):
            return node(p).get_double_value()

        self.surfaces = SURFACES if surfaces is None else surfaces
        self.streams = streams
        self.dt_s = 1.0 / fdm_hz
        self.wheelbase_m = get("roughness/left/x") - get("roughness/nose/x")
        self.track_m = get("roughness/right/y") - get("roughness/left/y")
        self.offset = [self.wheelbase_m / DX_M, 0.0, 0.0]  # nose ahead of the mains, in samples
        self.k = [get(f"roughness/{g}/spring") / LBF_N for g in GROUPS]  # lbf per m of profile
        self.law = [
            tuple(get(f"roughness/{g}/{key}") / LBF_N for key in ("damp", "damp2", "rebound", "rebound2"))
            for g in GROUPS
        ]
        # the tyre in series with the strut (massless wheel): the strut sees the profile through a
        # first-order lag tau = c / (k_tyre + k); k_tyre = static load / TYRE_DEFLECTION_M
        self.tau_s = []
        for g in GROUPS:
            units = [int(get(f"roughness/{g}/unit{j}")) for j in range(int(get(f"roughness/{g}/n-units")))]
            comp_m = sum(get(f"gear/unit[{u}]/compression-ft") for u in units) / len(units) * FT_M
            if comp_m <= 0.0:
                raise AircraftError(
                    f"the {g} gear carries no load: make GearRoughness with the aircraft at rest on its gear"
                )
            k_si = get(f"roughness/{g}/spring")
            k_tyre = k_si * comp_m / TYRE_DEFLECTION_M
            cl, cq, rl, rq = (get(f"roughness/{g}/{key}") for key in ("damp", "damp2", "rebound", "rebound2"))
            c_eff = 0.5 * (cl + rl + (cq + rq) * SQUARE_DAMPING_RATE_MPS)
            self.tau_s.append(c_eff / (k_tyre + k_si))
        self._knots = [
            [node(f"roughness/{g}/f{j}-lbf").set_double_value for j in range(RING)] for g in GROUPS
        ]
        self._active = node("roughness/active").set_double_value
        self._t0 = node("roughness/t0-sec").set_double_value
        self._knot_s = node("roughness/knot-sec").set_double_value
        self._time = node("simulation/sim-time-sec").get_double_value
        ix = ac.index
        self._ivn, self._ive, self._iwow = ix["v_north_mps"], ix["v_east_mps"], ix["wow"]
        self._profiles: dict[str, _Surface] = {}
        self._on: str | None = None  # the surface rolled on (None: inactive)
        self._prof: _Surface | None = None
        self._s = 0.0  # main gear's position along the surface, samples
        # per group: last knot boundary (sample index) and its prefix sum, wheel height (the
        # tyre-filtered profile, m), last knot (lbf), datum (the wheel height through DATUM_TAU_S, m)
        self._state = [[0, 0.0, 0.0, 0.0, 0.0] for _ in GROUPS]
        self._every = 0
        self._m, self._inv_dtk, self._dtk_dx, self._dtk, self._beta = 1, 0.0, 0.0, 0.0, 0.0
        self._n = 0  # knots written since the ring's restart (the last one is in slot n mod RING)
        self._anchor = True  # restart the ring at the next tick
        self._alpha = [0.0, 0.0, 0.0]
        self._groups: list[tuple] = []

    def profile(self, surface: str) -> _Surface:
        prof = self._profiles.get(surface)
        if prof is None:
            spec = self.surfaces[surface]
            tracks = synthesize_tracks(spec.gd_n0_m3, self.streams.rng(spec.stream), self.track_m)
            prof = self._profiles[surface] = _Surface(tracks)
        return prof

    def tick(self, x, phase: str, every: int) -> None:
        """Knots for the next ``every`` steps from the state row ``x`` (SI, jsbsim.adapter order)."""
        surface = PHASE_SURFACE[phase]
        if surface is None or x[self._iwow] < 0.5:
            if self._on is not None:
                self._active(0.0)
                self._on = None
            return
        if surface != self._on:
            self._switch(surface)
        if every != self._every:
            self._set_every(every)
        if self._anchor:
            self._reanchor()
        m, n, inv_dtk, beta = self._m, self._n, self._inv_dtk, self._beta
        v = math.hypot(x[self._ivn], x[self._ive])
        ds = v * self._dtk_dx if v >= ROLLING_MIN_MPS else 0.0  # samples rolled per knot
        s = self._s
        if m == 1:  # one knot a tick (40 Hz ticks on the runway): the loop below, unrolled
            slot = (n + 1) & _RING_MASK
            for h, c, k, cl, cq, rl, rq, a, off, knots, st in self._groups:
                i0, c0, w, f, datum = st
                i = int(s + off + 0.5 + ds) & _MASK
                n_in = (i - i0) & _MASK
                c1 = c[i]
                w1 = w + a * (((c1 - c0) / n_in if n_in else h[i]) - w)
                datum += beta * (w1 - datum)
                r = (w1 - w) * inv_dtk
                f = k * (w1 - datum) + (cl * r + cq * r * r if r > 0.0 else rl * r - rq * r * r)
                knots[slot](f)
                st[0] = i
                st[1] = c1
                st[2] = w1
                st[3] = f
                st[4] = datum
            self._s = s + ds
            self._n = n + 1
            return
        for h, c, k, cl, cq, rl, rq, a, off, knots, st in self._groups:
            i0, c0, w, f, datum = st
            b = s + off + 0.5
            for j in range(1, m + 1):
                i = int(b + j * ds) & _MASK
                n_in = (i - i0) & _MASK
                c1 = c[i]
                # the profile averaged over the distance rolled in the knot interval, through the tyre
                w1 = w + a * (((c1 - c0) / n_in if n_in else h[i]) - w)
                datum += beta * (w1 - datum)
                r = (w1 - w) * inv_dtk
                f = k * (w1 - datum) + (cl * r + cq * r * r if r > 0.0 else rl * r - rq * r * r)
                knots[(n + j) & _RING_MASK](f)
                i0, c0, w = i, c1, w1
            st[0], st[1], st[2], st[3], st[4] = i0, c0, w, f, datum
        self._s = s + m * ds
        self._n = n + m

    def _set_every(self, every: int) -> None:
        """Knot spacing for ticks ``every`` steps apart: ``m`` knots a tick, as near :data:`KNOT_S`
        as divides the tick (a new spacing restarts the ring)."""
        span = every * self.dt_s
        m = min(MAX_KNOTS, max(1, round(span / KNOT_S)))
        dtk = span / m
        self._every, self._m, self._inv_dtk, self._dtk_dx = every, m, 1.0 / dtk, dtk / DX_M
        self._beta = 1.0 - math.exp(-dtk / DATUM_TAU_S)
        if dtk != self._dtk:
            self._dtk = dtk
            self._alpha = [1.0 - math.exp(-dtk / tau) for tau in self.tau_s]
            self._anchor = True
            self._bind()

    def _reanchor(self) -> None:
        """Restart the ring: knot 0 (the force now) at the next step's time, ``knot-sec`` apart.
        JSBSim advances its clock before it computes the external forces of a step, so the next step
        computes them at now + dt. Between restarts the knots of consecutive ticks follow on: a
        tick's first knot is the last one written (m knot spacings span the tick exactly)."""
        self._t0(self._time() + self.dt_s)
        self._knot_s(self._dtk)
        for knots, st in zip(self._knots, self._state):
            knots[0](st[3])
        self._n = 0
        self._anchor = False

    def _bind(self) -> None:
        """The per-group constants and state the tick loop reads, for the current surface and spacing."""
        if self._prof is None:
            return
        p = self._prof
        self._groups = [
            (
                p.h[g],
                p.c[g],
                self.k[g],
                *self.law[g],
                self._alpha[g],
                self.offset[g],
                self._knots[g],
                self._state[g],
            )
            for g in range(3)
        ]

    def _switch(self, surface: str) -> None:
        """Start rolling on ``surface`` from its start, continuous in force: each group's wheel keeps
        its height above its datum from the previous surface (0 when starting from rest or touching
        down, so the force starts at 0 and the datum is the ground where the wheel stood)."""
        moving = self._on is not None
        prof = self.profile(surface)
        for g, st in enumerate(self._state):
            i = int(self.offset[g] + 0.5) & _MASK
            rel = st[2] - st[4] if moving else 0.0
            st[0], st[1], st[2], st[4] = i, prof.c[g][i], prof.h[g][i], prof.h[g][i] - rel
            if not moving:
                st[3] = 0.0  # the force starts from 0
        if not moving:
            self._active(1.0)
            self._anchor = True
        self._on, self._prof, self._s = surface, prof, 0.0
        self._bind()


__all__ = [
    "DATUM_TAU_S",
    "GROUPS",
    "MAX_KNOTS",
    "ROLLING_MIN_MPS",
    "SQUARE_DAMPING_RATE_MPS",
    "TYRE_DEFLECTION_M",
    "GearRoughness",
]
