"""flightmode: physics-simulated, labelled sensor data for a package in an airliner, and the
flight-mode detector that switches a GSM tracker off in flight.

The installed package maps the repository's rooms into one namespace: :mod:`flightmode.scenarios`,
:mod:`flightmode.sim` (``.flight`` and ``.sensor``), :mod:`flightmode.detector`,
:mod:`flightmode.nav` and :mod:`flightmode.viz`. Importing ``flightmode`` imports nothing heavy; the
pipeline API below is loaded on first use:

- :func:`run` (``flightmode.run("pattern", seed=3)``), and its stages :func:`fly`, :func:`sense`,
  :func:`detect`, :func:`estimate_path`, :func:`write`; :class:`RunResult`;
- :class:`Scenario` (``Scenario.builtin(name)``, ``Scenario.from_toml(path)``, ``.replace(...)``,
  ``.to_toml()``) and :class:`Streams` (named random streams).
"""

from __future__ import annotations

__version__ = "0.1.0"

_LAZY = {
    "run": "flightmode.runs.pipeline",
    "fly": "flightmode.runs.pipeline",
    "sense": "flightmode.runs.pipeline",
    "detect": "flightmode.runs.pipeline",
    "estimate_path": "flightmode.runs.pipeline",
    "write": "flightmode.runs.pipeline",
    "RunResult": "flightmode.runs.pipeline",
    "Scenario": "flightmode.scenarios.scenario",
    "SensorChoice": "flightmode.scenarios.scenario",
    "Streams": "flightmode.streams",
}
__all__ = sorted(_LAZY)


def __getattr__(name: str):
    if name in _LAZY:
        import importlib

        value = getattr(importlib.import_module(_LAZY[name]), name)
        globals()[name] = value
        return value
    raise AttributeError(f"module 'flightmode' has no attribute {name!r}")


def __dir__() -> list[str]:
    return sorted(list(globals()) + list(_LAZY))
