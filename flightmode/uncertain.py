"""Uncertain model parameters: the ones no anchor pins to within 10 %.

A module whose physics uses such a parameter declares it once, beside the physics, as an
:class:`Uncertain` (its nominal value, the range a reader of the sources could defend, the unit, the
source of the range or the word *assumption*, and what it shapes), lists it in its module-level tuple
``UNCERTAIN``, and reads it through :func:`value_of` with the overrides the run was given. The
overrides travel with the scenario (its ``[model]`` table: name -> value), never through global
state, so a flight with the same scenario and seed is the same flight in any process.

Studies vary them (``flightmode certify --uncertainty``: each parameter at each end of its range,
one at a time, with the same seeds, then the worst plausible corner); the registry of every declared
parameter, which the docs print, is :func:`flightmode.scenarios.model.registry`.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass

from flightmode.errors import ScenarioError


@dataclass(frozen=True, slots=True)
class Uncertain:
    """One uncertain model parameter (see the module docstring)."""

    name: str  # unique, dotted by the module that owns it: "mount.seat.fn_v_hz"
    value: float  # the nominal value every run uses unless overridden
    low: float  # the range's ends, low <= value <= high
    high: float
    unit: str  # "Hz", "psi", "1" for a factor...
    source: str  # the public source of the value and range, or "assumption: <why this range>"
    shapes: str  # what it shapes, in a few words ("a bag on a seat cushion: its vertical resonance")

    def __post_init__(self) -> None:
        nums = (self.value, self.low, self.high)
        if not all(isinstance(v, (int, float)) and math.isfinite(v) for v in nums):
            raise ValueError(f"{self.name}: value and range must be finite numbers, got {nums}")
        if not self.low <= self.value <= self.high:
            raise ValueError(
                f"{self.name}: needs low <= value <= high, got {self.low} <= {self.value} <= {self.high}"
            )
        if not self.name or not self.source or not self.shapes:
            raise ValueError(f"{self.name!r}: a name, a source and what it shapes are required")


def value_of(p: Uncertain, overrides: Mapping[str, float] | None = None) -> float:
    """The value of ``p`` in a run given ``overrides`` (name -> value; absent: the nominal value). An
    override outside the declared range is a :class:`ScenarioError`: the range is the model's claim
    of what is plausible, and a study that leaves it studies another model."""
    if not overrides or p.name not in overrides:
        return p.value
    v = overrides[p.name]
    if isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(v):
        raise ScenarioError(f"[model] {p.name} = {v!r}: must be a finite number ({p.unit})")
    if not p.low <= v <= p.high:
        raise ScenarioError(
            f"[model] {p.name} = {v} {p.unit}: outside its declared range {p.low}-{p.high} {p.unit} "
            f"(source: {p.source})"
        )
    return float(v)
