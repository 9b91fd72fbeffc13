"""The profiled aircraft by JSBSim model name (one module per type beside this one), and the lookup
that fails loudly with the nearest name."""

from __future__ import annotations

from flightmode.errors import AircraftError, did_you_mean
from flightmode.sim.flight.aircraft import a320, b737, b787_8, fokker100
from flightmode.sim.flight.aircraft.profile import AircraftProfile

PROFILES: dict[str, AircraftProfile] = {
    "737": b737.PROFILE,
    "A320": a320.PROFILE,
    "fokker100": fokker100.PROFILE,
    "787-8": b787_8.PROFILE,
}


def get_profile(model: str) -> AircraftProfile:
    """The profile of a JSBSim model; an :class:`AircraftError` with a suggestion otherwise."""
    try:
        return PROFILES[model]
    except KeyError:
        raise AircraftError(
            f"no flight profile for aircraft '{model}'{did_you_mean(model, PROFILES)}; "
            f"profiled aircraft: {', '.join(sorted(PROFILES))}"
        ) from None
