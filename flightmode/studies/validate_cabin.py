"""`flightmode validate`'s cabin rows: the cabin near the ground at the end of a flight beside its
type's pressure-controller description (issue 50, item 4).

Measured by :func:`flightmode.sim.flight.cabin_landing.landing_figures`; the anchors:

- the cabin at its landing pressure at least :data:`~flightmode.sim.flight.cabin_landing.LEVEL_AHEAD_MIN_S`
  before touchdown (737 FCOM 2.40.5, 787 FCOM 2.30.2: the cabin lands pressurised; a landing rule
  needs it level before the step);
- the residual overpressure at touchdown inside the declared range of ``cabin.landing_residual_psi``;
- the vent's start and end per type (:data:`~flightmode.sim.flight.cabin_landing.VENT_ANCHORS`):
  A320 and 787 from touchdown (within the valve's lag), complete by 55 s (A320) and 30 s (787); 737
  not before the taxi-in, complete before the door opens. A type without a description (Fokker 100)
  shows its vent without an anchor.

The rows are plain dicts of :class:`flightmode.studies.validate.Check`'s fields (validate builds them).
"""

from __future__ import annotations

import math

from flightmode.sim.flight.cabin import LANDING_RESIDUAL
from flightmode.sim.flight.cabin_landing import (
    LEVEL_AHEAD_MIN_S,
    VENT_ANCHORS,
    VENT_START_MAX_S,
    landing_figures,
)

GROUP = "cabin"
LANDED_PRESSURISED_SRC = (
    "737 FCOM 2.40.5 'programs the cabin to land slightly pressurized'; 787 FCOM 2.30.2 'the airplane "
    "lands pressurized'; a landing rule needs the cabin level before the step"
)


def _finite(x: float) -> float | None:
    return x if math.isfinite(x) else None


def cabin_rows(track) -> list[dict]:
    """The cabin rows of a flight's track (module docstring); [] without a cabin or a touchdown."""
    if track.cabin_pressure_pa is None:
        return []
    f = landing_figures(
        track.t_s, track.alt_m, track.cabin_pressure_pa, track.ambient_pressure_pa, track.phase_code
    )
    if not f:
        return []

    def row(figure: str, unit: str, value: float, lo, hi, source: str, note: str = "") -> dict:
        return {
            "group": GROUP,
            "figure": figure,
            "unit": unit,
            "value": float(value),
            "lo": lo,
            "hi": hi,
            "source": source,
            "note": note,
        }

    out = [
        row(
            "cabin at its landing pressure before touchdown",
            "s",
            f["level_before_touchdown_s"],
            LEVEL_AHEAD_MIN_S,
            None,
            LANDED_PRESSURISED_SRC,
            f"reached {f['level_height_ft']:,.0f} ft above the touchdown (within {f['tol_hpa']:.1f} hPa)",
        ),
        row(
            "residual overpressure at touchdown",
            "psi",
            f["residual_psi"],
            LANDING_RESIDUAL.low,
            LANDING_RESIDUAL.high,
            f"the declared range of {LANDING_RESIDUAL.name}",
            f"{f['residual_hpa']:.2f} hPa over the ambient at the aircraft",
        ),
    ]
    a = VENT_ANCHORS.get(track.aircraft)
    src = a.source if a is not None else "no controller description read for this type"
    start_lo: float | None
    start_hi: float | None
    done_hi: float | None
    if a is None:
        start_lo = start_hi = done_hi = None
    elif a.starts == "touchdown":
        start_lo, start_hi, done_hi = None, VENT_START_MAX_S, a.complete_s
    else:  # the taxi-in: not before it starts, done before the door opens
        start_lo, start_hi = _finite(f["taxi_in_s"]), None
        done_hi = a.complete_s if a.complete_s is not None else _finite(f["door_open_s"])
    out.append(
        row(
            "vent starts after touchdown",
            "s",
            f["vent_start_s"],
            start_lo,
            start_hi,
            src,
            f"taxi-in from {f['taxi_in_s']:.0f} s",
        )
    )
    out.append(
        row(
            "vent complete after touchdown",
            "s",
            f["vent_complete_s"],
            None,
            done_hi,
            src,
            f"a step of {f['step_hpa']:.2f} hPa over {f['vent_duration_s']:.0f} s; door open at "
            f"{f['door_open_s']:.0f} s",
        )
    )
    return out


__all__ = ["cabin_rows"]
