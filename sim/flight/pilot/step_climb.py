"""Step climbs on long flights: the cruise level rises 2,000 ft at a time as fuel burns.

Why the optimum level rises: at a given Mach number the lift is L = 0.5 gamma p M^2 S C_L, so
flying at the lift coefficient of best range (the same at every weight) needs a static pressure
proportional to the weight, p_opt = p_ref W / W_ref (any aircraft performance text, e.g. Torenbeek,
"Advanced Aircraft Design", Wiley 2013, ch. 12; Eurocontrol BADA's optimum-altitude model is of the
same form). Taking the level the flight first levels off at as the optimum for the weight it has
then (an assumption: dispatchers file near-optimum levels), the optimum altitude follows from the
ISA pressure (:mod:`flightmode.sim.flight.atmosphere`).

When: a crew asks for the next level once the optimum is ``STEP_TRIGGER_FT`` above the current one
(half a step: the level above is then as close to the optimum as the present one), if the next
level is within the type's maximum operating altitude (its ``ceiling_ft``) and the flight would
stay at it for at least ``STEP_MIN_CRUISE_S`` before the top of descent.

Levels: same-direction cruising levels are 2,000 ft apart under RVSM (ICAO Annex 2, Appendix 3,
table of cruising levels): a step is ``STEP_FT`` = 2,000 ft, flown at ``STEP_VS_MPS`` (1,000 ft/min:
assumption, a typical cruise-thrust climb).
"""

from __future__ import annotations

from flightmode.sim.flight.atmosphere import pressure_altitude_m, pressure_pa
from flightmode.units import FPM_MPS, FT_M

STEP_FT = 2000.0
STEP_TRIGGER_FT = 1000.0
STEP_MIN_CRUISE_S = 20.0 * 60.0
STEP_VS_MPS = 1000.0 * FPM_MPS


def optimum_alt_m(weight: float, ref_weight: float, ref_alt_m: float) -> float:
    """The altitude (m, ISA) whose pressure is p(ref_alt) weight / ref_weight (module docstring)."""
    return float(pressure_altitude_m(float(pressure_pa(ref_alt_m)) * weight / ref_weight))


def next_level_m(
    alt_m: float, weight: float, ref_weight: float, ref_alt_m: float, ceiling_m: float
) -> float | None:
    """The level to step to from the current cruise level ``alt_m``, or None when no step is due yet
    (optimum less than STEP_TRIGGER_FT above) or the next level is above ``ceiling_m``."""
    new = alt_m + STEP_FT * FT_M
    if new > ceiling_m + 1.0:
        return None
    if optimum_alt_m(weight, ref_weight, ref_alt_m) < alt_m + STEP_TRIGGER_FT * FT_M:
        return None
    return new
