"""The gate-to-gate pilot: the phase state machine that flies a JSBSim airliner.

Every control tick the pilot reads the SI state row of
:class:`~flightmode.sim.flight.jsbsim.adapter.JSBSimAircraft`, checks the flight's limits, and runs
the current phase's controller (:mod:`flightmode.sim.flight.pilot.controllers`). A controller ends its phase
by reporting a condition (:meth:`Pilot.fire`); the next phase is the transition table's
(:data:`flightmode.sim.flight.pilot.phases.TRANSITIONS`). Each phase event records the condition that
started it. The pilot also says how turbulent the air is (:attr:`Pilot.gust_sigma_mps`): the
flight's background from liftoff to touchdown, and the plan's patches.

Limits checked every tick raise :class:`~flightmode.errors.FlightDivergedError` naming phase, time and
cause: NaN, bank beyond the limit, a sustained stall, below the ground, divergence, ground contact
off the runway (and, at touchdown, a hard landing; off the taxiway while taxiing).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import cast

from flightmode.errors import FlightDivergedError
from flightmode.labels import AIRBORNE_PHASES, PHASE_CODE, SEVERITIES, SEVERITY_CODE
from flightmode.sim.flight.aircraft.profile import AircraftProfile
from flightmode.sim.flight.pilot.autopilot import Autopilot
from flightmode.sim.flight.pilot.controller import Controller
from flightmode.sim.flight.pilot.controllers import CONTROLLERS
from flightmode.sim.flight.pilot.phases import START, TABLE
from flightmode.sim.flight.plan import FlightPlan
from flightmode.sim.flight.turbulence import background_edr, sigma_high_mps
from flightmode.units import FT_M, KT_MPS

# the flight's limits (_check_limits): the main gear's reference point may sink a little into the runway
# on a hard touchdown (the CG's height above ground, less its settled height); 2 m below the terrain is
# through it. 16 km (52,500 ft) is above every profiled type's ceiling (the 787-8's 43,100 ft), Mach 0.95
# above the profiled types' maximum operating Mach (the fastest, the 787-8's, is 0.90: FAA TCDS T00021SE): a
# state beyond either is a diverged FDM, not a flight
BELOW_GROUND_M = -2.0
MAX_ALT_M = 16000.0
MAX_MACH = 0.95
RUNWAY_BEFORE_M = 50.0  # ground contact this far before the threshold still counts as on the runway
# No progress to the destination (Pilot._check_progress): in these phases the distance to go (the route's,
# then the runway's on the localizer; a go-around's circuit starts a route of its own) must shrink by
# PROGRESS_MIN_M within PROGRESS_WINDOW_S, or the flight ends. flightmode flies no holding and no diversion:
# an aircraft not 1 nm closer after 15 min is circling or flying away (at the slowest airborne speed,
# 130 kt on final, 15 min is 32 nm; a standard holding pattern's lap is 4 min, ICAO Doc 8168 Vol I;
# the longest leg away from the runway flown on purpose is a go-around circuit's upwind and crosswind
# legs, 3 + 3 nm, and the turn back after a departure away from the destination: 2-3 min). It ends such
# a flight while its reserve fuel still flies it (loaded: an hour of the type's mean burn beyond the
# trip, simulate.RESERVE_H), long before the tanks run dry and a glide ends in a stall
PROGRESS_PHASES = frozenset({"climb", "cruise", "descent", "approach", "go_around", "flare"})
PROGRESS_MIN_M = 1852.0
PROGRESS_WINDOW_S = 900.0
PROGRESS_CHECK_S = 10.0  # how often the distance to go is taken
EN_ROUTE = frozenset({"climb", "cruise", "descent"})  # ticked at 5 Hz above 3000 ft (control_every)
LOW_AIRBORNE = frozenset({"flare"})  # airborne, but ticked at 40 Hz at any height


class Pilot:
    """Flies ``plan`` with ``profile`` on ``ac``; call :meth:`tick` every :attr:`control_every` FDM
    steps (``fdm_hz`` steps a second)."""

    def __init__(self, ac, plan: FlightPlan, profile: AircraftProfile, fdm_hz: float, draws, taxi):
        self.ac = ac
        self.plan = plan
        self.prof = profile
        self.fdm_hz = fdm_hz
        self.ix = ac.index
        self.t = 0.0
        self.t_phase = 0.0
        self.t_liftoff: float | None = None
        self.t_engines_off: float | None = None
        self.takeoff_thrust_norm: float | None = None  # set at brake release (takeoff.TakeoffRoll)
        self.events: list[tuple[float, str, str]] = [(0.0, START, "start")]  # (t_s, name, detail)
        self.phase = START
        self.phase_code = PHASE_CODE[START]
        self.severity_code = 0
        self.done = False
        self.draws = draws  # flightmode.sim.flight.draws.FlightDraws
        self.taxi = taxi  # the flight's taxi routes and style (flightmode.sim.flight.taxi_route.TaxiDraws)
        self.ap = Autopilot(ac, plan, profile, draws, self.event)
        self.ap.dt = 3.0 / fdm_hz
        # one controller per phase; the four en-route phases share one (one set of loops)
        shared: dict[type[Controller], Controller] = {}
        self.controllers = {ph: shared.setdefault(cls, cls(self)) for ph, cls in CONTROLLERS.items()}
        self.controller = self.controllers[START]
        self._t_last: float | None = None
        self._t_alpha_high: float | None = None
        self._en_route = False
        self._airborne_high = False
        self._progress: tuple[float, float] | None = None  # (least distance to go so far m, when s)
        self._next_progress_check = 0.0
        self.gust_sigma_mps: float | None = None  # turbulent air: sigma_w above 2000 ft; None: still air
        # the touchdown sink (m/s, down positive) at the last step before the main gear's first contact
        # in this flare: set by the flight loop, which records every step (the pilot sees only its
        # ticks, up to three steps after the contact, when the struts have already slowed the sink).
        # The one measure of a touchdown's sink: the hard-landing check and the touchdown event read it,
        # and flight_metrics' touchdown_sink_mps is the same sample of the track
        self.contact_sink_mps: Callable[[], float] | None = None

    def set_cg_height(self, cg_height_m: float) -> None:
        """The CG's height above ground with the aircraft settled on its gear (measured: it depends
        on the gear, :mod:`flightmode.sim.flight.jsbsim.gear`)."""
        import dataclasses

        self.prof = dataclasses.replace(self.prof, cg_height_m=cg_height_m)
        self.ap.prof = self.prof

    # ------------------------------------------------------------------ phases and events
    def event(self, name: str, detail: str = "") -> None:
        self.events.append((self.t, name, detail))

    def fire(self, condition: str, x=None) -> None:
        """The current phase's controller reports ``condition``: move to the phase the transition table
        gives, log it (the phase event's detail is the condition) and run the new phase's entry."""
        tr = TABLE.get((self.phase, condition))
        if tr is None:
            raise RuntimeError(
                f"no transition from phase '{self.phase}' on '{condition}' in the table "
                "(flightmode.sim.flight.pilot.phases.TRANSITIONS)"
            )
        if tr.target is None:
            self.event("end", condition)
            self.done = True
            return
        if tr.target == "go_around":
            self._progress = None  # the circuit is a route of its own (GoAround.enter)
        self.phase = tr.target
        self.phase_code = PHASE_CODE[tr.target]
        self.t_phase = self.t
        self.event(tr.target, condition)
        self.controller = self.controllers[tr.target]
        self.controller.enter(self._x)

    def fail(
        self,
        cause: str,
        *,
        kind: str,
        quantity: str | None = None,
        value: float | None = None,
        limit: float | None = None,
    ) -> None:
        """End the flight: a :class:`FlightDivergedError` with this phase and time, the limit's ``kind``
        (a row of docs/failures.md), and the ``quantity`` (name and unit) whose ``value`` broke its
        ``limit``."""
        raise FlightDivergedError(
            cause, phase=self.phase, t_s=self.t, kind=kind, quantity=quantity, value=value, limit=limit
        )

    # ------------------------------------------------------------------ tick
    @property
    def control_every(self) -> int:
        """FDM steps between ticks: 40 Hz on the runway and below 1000 ft; 20 Hz pushing back;
        10 Hz taxiing and airborne above 1000 ft; 5 Hz en route (the loops' bandwidths are well
        below 1 Hz there, and the pilot is most of flightmode's cost per step); 4 Hz standing still
        on the brakes or waiting for an engine to spool up."""
        if self.controller.holding:
            return self._steps(4.0)
        if self._en_route:
            return self._steps(5.0)
        if self._airborne_high or self.phase in ("taxi_out", "taxi_in"):
            # 10 Hz: airborne above 1000 ft (climb-out, approach before the last 1000 ft), and on
            # the taxiways (at 20 kt the aircraft moves 1 m per tick; the steering loops' time
            # constants are seconds)
            return self._steps(10.0)
        if self.phase == "pushback":
            return self._steps(20.0)  # the tug's speed loop
        return self._steps(40.0)

    def _steps(self, tick_hz: float) -> int:
        return max(1, round(self.fdm_hz / tick_hz))

    def tick(self, x, t: float) -> None:
        dt = self.ap.dt if self._t_last is None else t - self._t_last
        self._t_last = t
        self.t = t
        self._x = x
        self._check_limits(x)
        self.ap.update(x, t, dt)
        self.controller.tick(x)
        self._turbulence()

    def _check_limits(self, x) -> None:
        if not math.isfinite(sum(x)):
            name = next(n for n, i in self.ix.items() if not math.isfinite(x[i]))
            self.fail(
                f"NaN in the flight state: JSBSim diverged ({name} = {x[self.ix[name]]}, not finite)",
                kind="nan",
                quantity=name,
                value=x[self.ix[name]],
            )
        ix = self.ix
        agl, phi, alpha = x[ix["agl_m"]], x[ix["phi_rad"]], x[ix["alpha_rad"]]
        airborne_phase = self.phase in AIRBORNE_PHASES
        on_wheels = x[ix["wow"]] > 0.5
        self._en_route = self.phase in EN_ROUTE and agl > 3000 * FT_M and not self.ap.loc_mode
        self._airborne_high = airborne_phase and self.phase not in LOW_AIRBORNE and agl > 1000 * FT_M
        max_bank = self.ap.tune.max_bank_deg
        if abs(math.degrees(phi)) > max_bank:
            self.fail(
                f"bank angle {math.degrees(phi):.1f} deg exceeds {max_bank:.0f} deg",
                kind="bank",
                quantity="bank angle, either way (deg)",
                value=abs(math.degrees(phi)),
                limit=max_bank,
            )
        # stall: angle of attack above the type's stall angle for a whole second (gusts in
        # turbulence spike alpha for a fraction of a second without stalling the wing)
        if airborne_phase and not on_wheels and math.degrees(alpha) > self.prof.alpha_stall_deg:
            if self._t_alpha_high is None:
                self._t_alpha_high = self.t
            if self.t - self._t_alpha_high >= 1.0:
                self.fail(
                    f"stall: angle of attack {math.degrees(alpha):.1f} deg above "
                    f"{self.prof.alpha_stall_deg:.0f} deg for 1 s at IAS {x[ix['ias_mps']] / KT_MPS:.0f} kt",
                    kind="stall",
                    quantity="angle of attack (deg)",
                    value=math.degrees(alpha),
                    limit=self.prof.alpha_stall_deg,
                )
        else:
            self._t_alpha_high = None
        if agl < BELOW_GROUND_M:
            self.fail(
                f"below the ground: height above ground {agl:.1f} m, under {BELOW_GROUND_M:.0f} m",
                kind="below_ground",
                quantity="height above ground (m)",
                value=agl,
                limit=BELOW_GROUND_M,
            )
        if x[ix["alt_m"]] > MAX_ALT_M:
            self.fail(
                f"divergence: altitude {x[ix['alt_m']]:.0f} m above {MAX_ALT_M:.0f} m",
                kind="altitude",
                quantity="altitude (m)",
                value=x[ix["alt_m"]],
                limit=MAX_ALT_M,
            )
        if x[ix["mach"]] > MAX_MACH:
            self.fail(
                f"divergence: Mach {x[ix['mach']]:.3f} above {MAX_MACH:.3f}",
                kind="mach",
                quantity="Mach number",
                value=x[ix["mach"]],
                limit=MAX_MACH,
            )
        if airborne_phase and on_wheels and self.phase != "initial_climb":
            fr = self.ap.dest if self.ap.loc_mode or self.phase == "go_around" else self.ap.origin
            rx, ry = fr.to_xy(x[ix["lat_deg"]], x[ix["lon_deg"]])
            half = fr.rwy.width_m / 2
            if abs(ry) > half or not (-RUNWAY_BEFORE_M < rx < fr.rwy.length_m):
                lateral = abs(ry) > half
                what = "distance from the centreline (m)" if lateral else "distance past the threshold (m)"
                self.fail(
                    f"ground contact off the runway at x = {rx:.0f} m, y = {ry:.0f} m from the threshold "
                    f"(the runway: x from {-RUNWAY_BEFORE_M:.0f} to {fr.rwy.length_m:.0f} m, "
                    f"|y| up to {half:.0f} m)",
                    kind="off_runway",
                    quantity=what,
                    value=abs(ry) if lateral else rx,
                    limit=half if lateral else (fr.rwy.length_m if rx > 0 else -RUNWAY_BEFORE_M),
                )
        self._check_progress(x)

    def _check_progress(self, x) -> None:
        """End a flight that no longer comes closer to its runway (PROGRESS_WINDOW_S)."""
        if self.phase not in PROGRESS_PHASES:
            self._progress = None
            return
        if self.t < self._next_progress_check:
            return
        self._next_progress_check = self.t + PROGRESS_CHECK_S
        d = self.ap.distance_to_go_m(x)
        if self._progress is None or d < self._progress[0] - PROGRESS_MIN_M:
            self._progress = (d, self.t)
        elif self.t - self._progress[1] > PROGRESS_WINDOW_S:
            since = self.t - self._progress[1]
            self.fail(
                f"no progress to the runway: {d / 1852.0:.1f} nm to go, not {PROGRESS_MIN_M / 1852.0:.0f} nm "
                f"closer than the {self._progress[0] / 1852.0:.1f} nm of {since:.0f} s ago (limit "
                f"{PROGRESS_WINDOW_S:.0f} s): circling or flying away, and no holding or diversion is flown",
                kind="no_progress",
                quantity="time without coming 1 nm closer to the runway (s)",
                value=since,
                limit=PROGRESS_WINDOW_S,
            )

    def _turbulence(self) -> None:
        """The air is turbulent from liftoff to touchdown (:mod:`flightmode.sim.flight.turbulence`):
        the flight's background EDR (mid or upper levels by altitude) or, inside one of the plan's
        patches, the patch's EDR; below 2000 ft the turbulence model blends in the boundary layer's
        own intensity. The label is the patch's severity, ``none`` for the background."""
        airborne = self.t_liftoff is not None and self.phase in AIRBORNE_PHASES
        if not airborne or self._x[self.ix["wow"]] > 0.5:
            if self.gust_sigma_mps is not None:
                self.gust_sigma_mps = None
                self.severity_code = 0
            return
        since = self.t - cast(float, self.t_liftoff)  # set: airborne
        atm = self.draws.atmosphere
        sev, edr = 0, background_edr(self._x[self.ix["alt_m"]], atm.edr_mid, atm.edr_upper)
        for seg, seg_edr in zip(self.plan.turbulence, atm.patch_edr):
            if seg.start_s <= since < seg.start_s + seg.duration_s:
                sev, edr = SEVERITY_CODE[seg.severity], seg_edr
        if sev != self.severity_code:
            self.event("turbulence", f"{SEVERITIES[sev]} (EDR {edr:.3f})")
        self.severity_code = sev
        self.gust_sigma_mps = sigma_high_mps(edr)
