"""The one small error hierarchy of flightmode (DESIGN.md, "Conventions").

Every room raises a subclass of :class:`FlightmodeError`; messages name what is wrong, the value,
what is allowed, and how to fix it.
"""

from __future__ import annotations

import difflib
from collections.abc import Iterable


class FlightmodeError(Exception):
    """Base of every error flightmode raises on purpose."""


class AircraftError(FlightmodeError):
    """An aircraft model that flightmode has no profile for, or that JSBSim cannot load."""


class FlightError(FlightmodeError):
    """A simulated flight that failed: NaN, divergence, a crash, an exceeded limit.

    Carries the phase and simulated time at which it happened.
    """

    def __init__(self, cause: str, *, phase: str, t_s: float) -> None:
        self.cause = cause
        self.phase = phase
        self.t_s = t_s
        super().__init__(f"flight failed in phase '{phase}' at t = {t_s:.2f} s: {cause}")


def did_you_mean(name: str, allowed: Iterable[str]) -> str:
    """Return ' (did you mean "x"?)' for the closest allowed name, or '' when none is close."""
    close = difflib.get_close_matches(str(name), [str(a) for a in allowed], n=1, cutoff=0.5)
    return f' (did you mean "{close[0]}"?)' if close else ""
