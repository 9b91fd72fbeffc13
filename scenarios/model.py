"""The registry of uncertain model parameters, and the ``[model]`` table that overrides them.

Each physics module declares its uncertain parameters beside its physics
(:class:`flightmode.uncertain.Uncertain`, in its module-level tuple ``UNCERTAIN``) and reads them with
:func:`flightmode.uncertain.value_of` and the run's overrides. :func:`registry` collects the tuples of
the modules listed in :data:`MODULES` (a fixed list: a module that declares parameters is added here),
one name once. A scenario or family file overrides them in its ``[model]`` table:

    [model]
    "mount.seat.fn_v_scale" = 3.0     # a firmer seat cushion
    "turbulence.background_scale" = 0.5

:func:`check_model` validates such a table: an unknown name is a :class:`ScenarioError` naming the
nearest declared one, a value outside the declared range :func:`~flightmode.uncertain.value_of`'s.
``flightmode scenarios --model`` prints the registry (:func:`registry_rows`, :func:`registry_markdown`).
"""

from __future__ import annotations

import importlib
from collections.abc import Mapping
from typing import Any

from flightmode.errors import ScenarioError, did_you_mean
from flightmode.uncertain import Uncertain, value_of

# the modules that declare uncertain parameters (their UNCERTAIN tuples), in the registry's order
MODULES = (
    "flightmode.sim.sensor.mount",
    "flightmode.sim.sensor.vibration",
    "flightmode.sim.flight.turbulence",
    "flightmode.sim.flight.cabin",
    "flightmode.sim.flight.pilot.ground",
    "flightmode.sim.sensor.passenger",
    "flightmode.sim.sensor.tug",
)


def registry() -> dict[str, Uncertain]:
    """Every declared uncertain parameter by name, in :data:`MODULES`' order (each module's in its
    tuple's order). A name declared twice is a :class:`ScenarioError` naming both modules."""
    out: dict[str, Uncertain] = {}
    where: dict[str, str] = {}
    for mod in MODULES:
        for p in getattr(importlib.import_module(mod), "UNCERTAIN", ()):
            if not isinstance(p, Uncertain):
                raise ScenarioError(f"{mod}.UNCERTAIN holds {p!r}, not an Uncertain")
            if p.name in out:
                raise ScenarioError(
                    f"uncertain parameter '{p.name}' is declared twice: {where[p.name]} and {mod}"
                )
            out[p.name] = p
            where[p.name] = mod
    return out


def module_of(name: str) -> str:
    """The module that declares parameter ``name`` (a :class:`ScenarioError` for an unknown name)."""
    for mod in MODULES:
        if any(p.name == name for p in getattr(importlib.import_module(mod), "UNCERTAIN", ())):
            return mod
    raise ScenarioError(f"unknown model parameter '{name}'{did_you_mean(name, registry())}")


def check_model(table: Any, source: str = "<scenario>") -> dict[str, float]:
    """A ``[model]`` table (name -> number) checked against the registry: name -> float, sorted by
    name. Unknown names and values outside the declared range are :class:`ScenarioError`s."""
    if table is None:
        return {}
    if not isinstance(table, Mapping):
        raise ScenarioError(f"{source}: [model] must be a table of parameter name = number")
    reg = registry()
    out: dict[str, float] = {}
    for name in sorted(table):
        if name not in reg:
            raise ScenarioError(
                f"{source}: [model].{name}: unknown model parameter{did_you_mean(name, reg)}; "
                "`flightmode scenarios --model` lists them"
            )
        try:
            out[name] = value_of(reg[name], {name: table[name]})
        except ScenarioError as e:
            raise ScenarioError(f"{source}: {e}") from None
    return out


def registry_rows() -> list[dict[str, Any]]:
    """The registry as plain rows (name, value, low, high, unit, source, shapes, module)."""
    reg = registry()
    return [
        {
            "name": p.name,
            "value": p.value,
            "low": p.low,
            "high": p.high,
            "unit": p.unit,
            "source": p.source,
            "shapes": p.shapes,
            "module": module_of(p.name),
        }
        for p in reg.values()
    ]


def registry_markdown() -> str:
    """The registry as a Markdown table (what docs/modelling.md holds; a test keeps it current)."""
    lines = [
        "| parameter | value | range | unit | what it shapes | source |",
        "|---|---|---|---|---|---|",
    ]
    for r in registry_rows():
        cells = (
            f"`{r['name']}`",
            f"{r['value']:g}",
            f"{r['low']:g}-{r['high']:g}",
            r["unit"],
            r["shapes"],
            r["source"],
        )
        lines.append("| " + " | ".join(str(c).replace("|", "/") for c in cells) + " |")
    return "\n".join(lines) + "\n"


DOCS_BEGIN = "<!-- the registry: python -m flightmode.scenarios.model docs/modelling.md -->"
DOCS_END = "<!-- end of the registry -->"


def with_registry(text: str) -> str:
    """``text`` (docs/modelling.md) with the table between :data:`DOCS_BEGIN` and :data:`DOCS_END`
    replaced by :func:`registry_markdown`."""
    a, b = text.find(DOCS_BEGIN), text.find(DOCS_END)
    if a < 0 or b < a:
        raise ScenarioError(f"the text has no registry markers ({DOCS_BEGIN!r} ... {DOCS_END!r})")
    return text[: a + len(DOCS_BEGIN)] + "\n\n" + registry_markdown() + "\n" + text[b:]


__all__ = [
    "DOCS_BEGIN",
    "DOCS_END",
    "MODULES",
    "check_model",
    "module_of",
    "registry",
    "registry_markdown",
    "registry_rows",
    "with_registry",
]


if __name__ == "__main__":  # python -m flightmode.scenarios.model docs/modelling.md: rewrite its table
    import sys
    from pathlib import Path

    from flightmode.atomic import write_text

    for arg in sys.argv[1:]:
        write_text(with_registry(Path(arg).read_text(encoding="utf-8")), Path(arg))
