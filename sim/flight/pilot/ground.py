"""The ground phases at the stand: waiting at the gate, the engine start, the pushback by a tug,
the shutdown at the arrival stand and standing parked (taxiing: :mod:`flightmode.sim.flight.pilot.taxi`).

The pushback's speed profile (the tug's speed and how gently it gets there and stops) is declared
uncertain here (:data:`UNCERTAIN`; the profiles' ``AircraftTuning.pushback_mps`` and
``pushback_decel_mps2`` are its nominal values, and :func:`pushback_tuning` puts a run's overrides in
their place). The tug's jolts on top of that smooth profile are the sensing stage's
(:mod:`flightmode.sim.sensor.tug`): they do not move the aircraft's path.
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Mapping

from flightmode.labels import ENGINES_OFF_N2_PCT
from flightmode.sim.flight.pilot.control import rate_limit
from flightmode.sim.flight.pilot.controller import Controller
from flightmode.uncertain import Uncertain, value_of

PUSHBACK_SPEED_MPS = Uncertain(
    "pushback.speed_mps",
    1.2,
    0.55,
    1.4,
    "m/s",
    "Applied Sciences 13(6) 3636 (2023), introduction: the traditional tow or pushback runs at 'about "
    "2-5 km/h' (0.56-1.39 m/s); 1.2 m/s is the profiles' AircraftTuning.pushback_mps",
    "the pushback's speed profile: the tug's pushing speed",
)
PUSHBACK_RAMP_MPS2 = Uncertain(
    "pushback.ramp_mps2",
    0.2,
    0.05,
    0.5,
    "m/s^2",
    "assumption: the tug reaches its 0.5-1.4 m/s in 2-10 s and stops over the end of the turn as gently "
    "(AircraftTuning.pushback_decel_mps2); no measured push profile was found",
    "the pushback's speed profile: the tug's smooth acceleration and deceleration",
)
UNCERTAIN = (PUSHBACK_SPEED_MPS, PUSHBACK_RAMP_MPS2)


def pushback_tuning(tuning, overrides: Mapping[str, float] | None = None):
    """``tuning`` (an :class:`~flightmode.sim.flight.aircraft.tuning.AircraftTuning`) with the run's
    overrides of the pushback's speed and ramp in place of its own; the same object when the
    overrides name neither (a flight at nominal values is bit-identical)."""
    names = {PUSHBACK_SPEED_MPS.name, PUSHBACK_RAMP_MPS2.name}
    if not overrides or not names & set(overrides):
        return tuning
    speed, ramp = PUSHBACK_SPEED_MPS, PUSHBACK_RAMP_MPS2
    return dataclasses.replace(
        tuning,
        pushback_mps=value_of(speed, overrides) if speed.name in overrides else tuning.pushback_mps,
        pushback_decel_mps2=value_of(ramp, overrides)
        if ramp.name in overrides
        else tuning.pushback_decel_mps2,
    )


class Gate(Controller):
    holding = True

    def tick(self, x) -> None:
        self.ap.brakes(1.0)
        self.ap.throttle(0.0)
        if self.p.t - self.p.t_phase >= self.p.plan.gate_wait_s:
            self.p.fire("gate_wait_over")


class EngineStart(Controller):
    """Engines started one by one, the last first: starter on; fuel on at N2 > 15 %; the starter stays
    engaged until the engine runs (releasing it earlier aborts the start)."""

    holding = True

    def enter(self, x) -> None:
        self.engine = self.p.prof.n_engines - 1
        self._start(self.engine)

    def _start(self, i: int) -> None:
        ac = self.ap.ac
        ac.set("propulsion/active_engine", i)
        if ac.get("propulsion/cutoff_cmd") < 0.5:  # fuel off for the next engine (on since the last one)
            ac.set("propulsion/cutoff_cmd", 1)
        ac.set("propulsion/starter_cmd", 1)
        self.p.event("starter", f"engine {i}")

    def tick(self, x) -> None:
        ac, i = self.ap.ac, self.engine
        if ac.get("propulsion/cutoff_cmd") > 0.5 and x[self.p.ix[f"n2_pct_{i}"]] > 15.0:
            ac.set("propulsion/cutoff_cmd", 0)
            self.p.event("fuel_on", f"engine {i}")
        elif ac.get("propulsion/cutoff_cmd") < 0.5 and ac.get(f"propulsion/engine[{i}]/set-running") > 0.5:
            ac.set("propulsion/starter_cmd", 0)
            self.p.event("engine_running", f"engine {i}")
            if i == 0:
                ac.set("propulsion/active_engine", -1)
                self.p.fire("engines_running")
            else:
                self.engine = i - 1
                self._start(self.engine)


class Pushback(Controller):
    """The tug (a body-axis force at the nose gear, a PI loop on ground speed) pushes the aircraft
    straight back from its stand (``TaxiDraws.push_straight_m``), then turns the tail so the nose
    swings 90 deg left onto the apron taxilane (turn radius = wheelbase / tan(35 deg)), slowing to a
    stop over the last of the turn (``pushback_decel_mps2``), and stops."""

    def enter(self, x) -> None:
        ix = self.p.ix
        self.heading0 = x[ix["psi_rad"]]
        self.xy0 = self.ap.origin.to_xy(x[ix["lat_deg"]], x[ix["lon_deg"]])
        self.turning = False
        self.v_tug = 0.0  # the tug's speed target (backwards)
        self.ap.brakes(0.0)
        self.ap.tug_pid.reset()

    def tick(self, x) -> None:
        ap, ix, tu = self.ap, self.p.ix, self.ap.tune
        v = ap.ground_speed_signed(x)
        turned = (x[ix["psi_rad"]] - self.heading0 + math.pi) % (2 * math.pi) - math.pi
        rx, ry = ap.origin.to_xy(x[ix["lat_deg"]], x[ix["lon_deg"]])
        radius = self.p.prof.wheelbase_m / math.tan(math.radians(35.0))
        if math.hypot(rx - self.xy0[0], ry - self.xy0[1]) >= self.p.taxi.push_straight_m:
            self.turning = True
        steering = math.radians(35.0) if self.turning else 0.0
        to_go_m = radius * max(0.0, math.radians(90.0) + turned) if self.turning else math.inf
        done = turned < -math.radians(89.0)
        # the tug starts and stops the push at pushback_decel_mps2 (no jolt)
        speed = max(0.15, min(tu.pushback_mps, math.sqrt(2.0 * tu.pushback_decel_mps2 * to_go_m)))
        self.v_tug = rate_limit(self.v_tug, 0.0 if done else speed, tu.pushback_decel_mps2 * ap.dt)
        ap.ac.set("external_reactions/pushback/magnitude", ap.tug_pid(-self.v_tug - v, ap.dt))
        ap.steer(steering if not done else 0.0)
        if done:
            ap.brakes(0.1)
            if abs(v) < 0.05:
                ap.ac.set("external_reactions/pushback/magnitude", 0.0)
                self.p.event("tug_disconnected")
                self.p.fire("tug_disconnected")


class Shutdown(Controller):
    """Fuel cut off at the stand. The parking brake is set gradually from the taxi brake's hold
    (``PARKING_BRAKE_RATE_PER_S``): set at once, JSBSim's gear friction at rest (a stiff spring)
    kicked the 737 with 0.35 g fore-aft and could leave it rocking on its gear."""

    def enter(self, x) -> None:
        ap = self.ap
        ap.parking_brake = ap.taxi_brake
        ap.brakes(ap.parking_brake)
        ap.throttle(0.0)
        ap.steer(0.0)
        ap.ac.set("propulsion/active_engine", -1)
        ap.ac.set("propulsion/cutoff_cmd", 1)

    def tick(self, x) -> None:
        self.ap.set_parking_brake(PARKING_BRAKE_RATE_PER_S)
        # engines off: every N2 below 5 % after fuel cut-off (the end of the seed's flight time)
        if all(x[self.p.ix[f"n2_pct_{i}"]] < ENGINES_OFF_N2_PCT for i in range(self.p.prof.n_engines)):
            self.p.t_engines_off = self.p.t
            self.p.event("engines_off")
            self.p.fire("engines_off")


PARKING_BRAKE_RATE_PER_S = 0.1


class Parked(Controller):
    holding = True

    def tick(self, x) -> None:
        self.ap.set_parking_brake(PARKING_BRAKE_RATE_PER_S)
        if self.p.t - self.p.t_engines_off >= self.p.plan.post_shutdown_s:
            self.p.fire("recording_over")
