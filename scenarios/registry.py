"""The built-in scenario library (TOML files shipped as package data in ``scenarios/library``)."""

from __future__ import annotations

from importlib import resources
from pathlib import Path

from flightmode.scenarios.spec import ScenarioError, load_scenario
from flightmode.errors import did_you_mean
from flightmode.sim.flight.plan import FlightPlan

DEFAULT_SCENARIO = "gva-lhr-a320"


def builtin_names() -> list[str]:
    lib = resources.files("flightmode.scenarios.library")
    return sorted(p.name[:-5] for p in lib.iterdir() if p.name.endswith(".toml"))


def builtin_path(name: str) -> Path:
    names = builtin_names()
    if name not in names:
        raise ScenarioError(
            f"unknown scenario '{name}'{did_you_mean(name, names)}; built-in scenarios: {', '.join(names)} "
            "(or give the path of a .toml file)"
        )
    return Path(str(resources.files("flightmode.scenarios.library").joinpath(f"{name}.toml")))


def resolve(name_or_path: str) -> tuple[FlightPlan, str, Path]:
    """A built-in name or a path to a .toml file -> (plan, description, file)."""
    p = Path(name_or_path)
    if p.suffix == ".toml" or p.exists():
        path = p
    else:
        path = builtin_path(name_or_path)
    plan, desc = load_scenario(path)
    return plan, desc, path
