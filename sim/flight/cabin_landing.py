"""The cabin near the ground at the end of a flight, measured on its arrays: the figures a barometric
landing rule sees (issue 50, item 4), and the anchors each type's controller description gives them.

The model is :func:`flightmode.sim.flight.cabin.cabin_pressure`: the cabin reaches its *landing
pressure* (the arrival field's + a small residual overpressure) before touchdown and holds it through
the final approach and the flare; after touchdown the type's outflow valves vent it. Here, on any
flight's arrays (a track, or a synthetic profile):

- the cabin 5 minutes before touchdown (:data:`BEFORE_S`);
- when the landing pressure was reached: the last sample before touchdown whose cabin pressure is
  more than :data:`TOL_PA` from the touchdown value, as seconds before touchdown and the aircraft's
  height above its touchdown altitude;
- the residual overpressure at touchdown (cabin minus ambient);
- the vent: its start (the first sample after touchdown more than :data:`TOL_PA` below the touchdown
  value), its end (the first with the cabin within :data:`TOL_PA` of ambient), the pressure step
  (the cabin at touchdown to the ambient it vents to), and the door's opening (the first door-open sample after touchdown).

Anchors (:data:`VENT_ANCHORS`; docs/research/fleet_loads/OTHER_SOURCES.md section 1 quotes them): the
A320's outflow valve fully open 55 s after landing, the release starting at touchdown; the 787's
valves opening at touchdown (fast: within the 30 s a valve takes over its full travel on the manual
switch); the 737's slow opening while taxiing in (after the rollout, done before the door opens).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from flightmode.labels import AIRBORNE_PHASES, PHASE_CODE
from flightmode.units import FT_M, HPA_PA, PSI_PA

BEFORE_S = 300.0  # the window shown: 5 minutes before touchdown ...
AFTER_S = 120.0  # ... to 2 minutes after (issue 50's must-show)
# "at" a pressure: within 0.1 hPa (0.8 m of altitude near the ground), a tenth of the smallest declared
# residual (0.03 psi, 2.1 hPa) and five times a BMP390's 0.02 hPa RMS noise at its highest resolution
TOL_PA = 10.0
# a landing rule needs the cabin level before the step to see it as a step: at least 10 s, one
# flare-and-touchdown's time (the smallest declared level-off height, 200 ft, is about 16 s of a 3 deg
# final approach at 140 kt; the outflow valve's lag takes a few of them to settle)
LEVEL_AHEAD_MIN_S = 10.0
VENT_START_MAX_S = 5.0  # "at touchdown": within the outflow valve's 5 s lag (cabin.CabinProfile.ofv_tau_s)


@dataclass(frozen=True, slots=True)
class VentAnchor:
    """A type's description of its vent after landing: when it starts (``"touchdown"`` or
    ``"taxi_in"``) and the time by which it is complete (s after touchdown; None: before the door
    opens)."""

    starts: str
    complete_s: float | None
    source: str

    def text(self) -> str:
        """The anchor in a few words ("from touchdown, complete by 55 s")."""
        start = "from touchdown" if self.starts == "touchdown" else "from the taxi-in"
        end = (
            f"complete by {self.complete_s:.0f} s"
            if self.complete_s is not None
            else "complete before the door opens"
        )
        return f"{start}, {end}"


VENT_ANCHORS: dict[str, VentAnchor] = {
    "A320": VentAnchor(
        "touchdown",
        55.0,
        "A320 FCOM DSC-21-20-30 (as paraphrased): remaining pressure released at 500 ft/min from "
        "touchdown, the outflow valve fully open 55 s after landing",
    ),
    "787-8": VentAnchor(
        "touchdown",
        30.0,
        "787 FCOM 2.30.2: 'At touchdown, both outflow valves open'; 30 s, a valve's full travel on the "
        "manual switch",
    ),
    "737": VentAnchor(
        "taxi_in",
        None,
        "737 FCOM 2.40.5: 'While taxiing in, the controller drives the outflow valve slowly to the full "
        "open position'",
    ),
}


def touchdown_index(phase_code) -> int | None:
    """The first sample after the last airborne one (the final touchdown), or None (never airborne,
    or airborne to the end)."""
    code = np.asarray(phase_code)
    air = np.flatnonzero(np.isin(code, [PHASE_CODE[p] for p in AIRBORNE_PHASES]))
    if not air.size or air[-1] + 1 >= code.size:
        return None
    return int(air[-1]) + 1


def _first(mask: np.ndarray) -> int | None:
    i = np.flatnonzero(mask)
    return int(i[0]) if i.size else None


def landing_figures(
    t_s, alt_m, cabin_pressure_pa, ambient_pressure_pa, phase_code, tol_pa: float = TOL_PA
) -> dict:
    """The cabin's figures around the final touchdown (module docstring), times in seconds relative
    to touchdown, pressures in hPa and psi, altitudes in ft; ``{}`` for a flight without one. A figure
    the flight does not reach (a vent not complete by the end) is NaN."""
    t = np.asarray(t_s, float)
    z = np.asarray(alt_m, float)
    pc = np.asarray(cabin_pressure_pa, float)
    pa = np.asarray(ambient_pressure_pa, float)
    code = np.asarray(phase_code)
    td = touchdown_index(code)
    if td is None:
        return {}
    t0 = t[td]
    from flightmode.sim.flight import atmosphere as isa

    b = int(np.searchsorted(t, t0 - BEFORE_S))
    away = np.flatnonzero(np.abs(pc[:td] - pc[td]) > tol_pa)
    lvl = int(away[-1]) + 1 if away.size else 0  # the first sample of the hold
    diff = pc - pa
    start = _first(pc[td:] < pc[td] - tol_pa)
    done = _first(diff[td:] <= tol_pa)
    door = _first(np.isin(code[td:], [PHASE_CODE["gate"], PHASE_CODE["parked"]]))
    taxi = _first(code[td:] == PHASE_CODE["taxi_in"])

    def rel(k: int | None) -> float:
        return float(t[td + k] - t0) if k is not None else math.nan

    return {
        "touchdown_t_s": float(t0),
        "before_t_s": float(t[b] - t0),
        "cabin_altitude_before_ft": float(isa.pressure_altitude_m(pc[b])) / FT_M,
        "cabin_pressure_before_hpa": float(pc[b]) / HPA_PA,
        "aircraft_height_before_ft": float(z[b] - z[td]) / FT_M,
        "level_before_touchdown_s": float(t0 - t[lvl]),
        "level_height_ft": float(z[lvl] - z[td]) / FT_M,
        "cabin_pressure_touchdown_hpa": float(pc[td]) / HPA_PA,
        "residual_hpa": float(diff[td]) / HPA_PA,
        "residual_psi": float(diff[td]) / PSI_PA,
        "vent_start_s": rel(start),
        "vent_complete_s": rel(done),
        "vent_duration_s": rel(done) - rel(start),
        "step_hpa": float(pc[td] - pa[td + done]) / HPA_PA if done is not None else math.nan,
        "taxi_in_s": rel(taxi),
        "door_open_s": rel(door),
        "residual_at_door_hpa": float(diff[td + door]) / HPA_PA if door is not None else math.nan,
        "tol_hpa": tol_pa / HPA_PA,
    }


__all__ = [
    "AFTER_S",
    "BEFORE_S",
    "LEVEL_AHEAD_MIN_S",
    "TOL_PA",
    "VENT_ANCHORS",
    "VENT_START_MAX_S",
    "VentAnchor",
    "landing_figures",
    "touchdown_index",
]
