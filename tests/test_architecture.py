"""The house's contract (tests/architecture.py) holds on the repository, and fails on a copy of it
with one violation planted: an upward import, an import cycle, a private name taken across modules."""

from __future__ import annotations

import shutil
from pathlib import Path

import pytest

from tests.architecture import FOLDERS, LAYERS, imports, modules, room_of, violations

ROOT = Path(__file__).resolve().parents[1]


def test_the_repository_keeps_the_contract():
    found = violations(ROOT)
    assert not found, "\n".join(found)


def test_every_module_has_a_room_and_every_room_has_modules():
    mods = modules(ROOT)
    rooms = {room_of(m) for m in mods}
    for floor in LAYERS:
        for room in floor:
            assert room in rooms, f"{room} is in LAYERS but holds no module"
    # the base modules are the plain modules directly under flightmode/ (no physics, no I/O rooms)
    base = sorted(m for m in mods if room_of(m) == "flightmode (base modules)")
    assert "flightmode.errors" in base and "flightmode.units" in base
    assert all(m.count(".") == 1 for m in base), base


def test_lazy_imports_count(tmp_path):
    # an import inside a function is a dependency all the same: the reader finds it
    tree = _copy(tmp_path)
    _plant(tree / "sim/flight/track.py", "def _planted():\n    from flightmode.runs import pipeline\n")
    found = [i for i in imports(tree) if i.importer == "flightmode.sim.flight.track"]
    assert any(i.imported == "flightmode.runs.pipeline" for i in found)


def _copy(tmp_path: Path) -> Path:
    dest = tmp_path / "tree"
    for folder in FOLDERS:
        shutil.copytree(ROOT / folder, dest / folder, ignore=shutil.ignore_patterns("__pycache__", "*.pyc"))
    return dest


def _plant(path: Path, text: str) -> None:
    path.write_text(path.read_text(encoding="utf-8") + "\n\n" + text, encoding="utf-8")


PLANTS = {
    # the flight side reaching up to the run pipeline, lazily
    "upward, lazy": (
        {"sim/flight/track.py": "def _planted():\n    from flightmode.runs import pipeline\n"},
        "upward import: sim/flight/track.py",
    ),
    # viz reaching up to a study
    "upward": (
        {"viz/viewer.py": "from flightmode.studies.sweep import summarise\n"},
        "upward import: viz/viewer.py",
    ),
    # two rooms on one floor: the path estimator reaching into the detectors
    "sideways": (
        {"nav/frames.py": "from flightmode.detector import flight_mode\n"},
        "sideways import: nav/frames.py",
    ),
    # the e-obs toolkit reaching past the public API into the run pipeline's module
    "past the API": (
        {"eobs/tag.py": "def _planted():\n    from flightmode.runs import pipeline\n"},
        "past the public API: eobs/tag.py",
    ),
    # a room below using the face (its lazy names would load the pipeline from the physics)
    "face from below": (
        {"sim/sensor/gyroscope.py": "import flightmode\n"},
        "upward import: sim/sensor/gyroscope.py",
    ),
    # a cycle between two base modules, one half lazy
    "cycle": (
        {
            "flightmode/labels.py": "from flightmode import units\n",
            "flightmode/units.py": "def _planted():\n    from flightmode import labels\n",
        },
        "import cycle: flightmode.labels -> flightmode.units",
    ),
    # a private name imported from another module
    "private": (
        {"detector/grid.py": "from flightmode.detector.moving_variance import _planted_private\n"},
        "private name: detector/grid.py",
    ),
    # a private name reached through a module alias
    "private, by alias": (
        {
            "detector/grid.py": "from flightmode.detector import moving_variance as mv\n\n\ndef _f():\n    return mv._x\n"
        },
        "private name: detector/grid.py",
    ),
}


@pytest.mark.parametrize("case", sorted(PLANTS))
def test_a_planted_violation_fails(tmp_path, case):
    plants, expected = PLANTS[case]
    tree = _copy(tmp_path)
    before = set(violations(tree))
    for where, text in plants.items():
        _plant(tree / where, text)
    new = [v for v in violations(tree) if v not in before]
    assert any(v.startswith(expected) for v in new), new
