"""The two test tiers (README, pyproject's addopts, tests/conftest.py): the README's plain pytest runs
the fast tier, its ``-m ""`` command the full one, which is what .ci/run runs; and a test not marked
slow that asks for a route flown gate to gate fails in one line, before it flies, while a prefix of
the same route and a slow test's request pass."""

from __future__ import annotations

import os
import re
import shlex
import shutil
import subprocess
import sys
import tomllib
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]

PLANTED = """
import pytest
from conftest import guard_flight

from flightmode.runs import pipeline
from flightmode.scenarios.scenario import Scenario


def test_fast_asks_the_cache_for_a_route(fly_cached):
    fly_cached("gva-lhr-a320")


def test_fast_flies_a_route_through_the_pipeline():
    sc = Scenario.builtin("gva-lhr-a320")
    pipeline.fly(sc, pipeline.streams_of(sc.seed).child("flight"))


def test_fast_asks_for_a_prefix_of_a_route():
    guard_flight(Scenario.builtin("gva-lhr-a320"), stop_after_s=600.0)


def test_fast_asks_for_the_pattern():
    guard_flight(Scenario.builtin("pattern"))


@pytest.mark.slow
def test_slow_asks_for_a_route():
    guard_flight(Scenario.builtin("lhr-jfk-787"))
"""


def _readme_test_commands() -> list[str]:
    text = (ROOT / "README.md").read_text(encoding="utf-8")
    blocks = re.findall(r"```bash\n(.*?)```", text, flags=re.S)
    return [line for b in blocks for line in b.splitlines() if "pytest" in line]


def test_the_readme_runs_the_fast_tier_and_ci_runs_its_full_command():
    fast, full = _readme_test_commands()
    assert shlex.split(fast)[-3:] == ["python3", "-m", "pytest"]  # the default: addopts' -m "not slow"
    assert shlex.split(full)[-5:] == ["python3", "-m", "pytest", "-m", ""]
    ci = [line for line in (ROOT / ".ci" / "run").read_text().splitlines() if "pytest" in line]
    assert ci == [full]
    addopts = shlex.split(
        tomllib.loads((ROOT / "pyproject.toml").read_text())["tool"]["pytest"]["ini_options"]["addopts"]
    )
    assert addopts[addopts.index("-m") + 1] == "not slow"


def test_a_fast_test_that_asks_for_a_route_fails_in_one_line_before_it_flies(tmp_path):
    """Planted tests beside a copy of the suite's conftest: the two fast ones asking for
    gva-lhr-a320 gate to gate (from the cache, from the pipeline) fail, each in one line naming the
    test and the flight, in the guard (its message: before anything is flown); a prefix of it, the
    pattern circuit and a slow test's request for the 787 pass."""
    shutil.copy(ROOT / "tests" / "conftest.py", tmp_path / "conftest.py")
    (tmp_path / "test_planted.py").write_text(PLANTED)
    (tmp_path / "pytest.ini").write_text("[pytest]\nmarkers =\n    slow: as the suite's\n")
    r = subprocess.run(
        [sys.executable, "-m", "pytest", "-p", "no:cacheprovider", "-n", "0", "-q", "-rf", "test_planted.py"],
        cwd=tmp_path,
        capture_output=True,
        text=True,
        timeout=600,
        env={**os.environ, "COLUMNS": "1000"},  # the summary's lines whole
    )
    assert "2 failed, 3 passed" in r.stdout, r.stdout[-3000:]
    failed = [line for line in r.stdout.splitlines() if line.startswith("FAILED")]
    assert len(failed) == 2, failed
    for name in ("test_fast_asks_the_cache_for_a_route", "test_fast_flies_a_route_through_the_pipeline"):
        (line,) = [f for f in failed if f"test_planted.py::{name} " in f]
        assert "is not marked slow but flies" in line and "A320" in line and "mark it slow" in line, line
    assert "'gva-lhr-a320'" in next(f for f in failed if "cache" in f)
    assert "LSGG-EGLL" in next(f for f in failed if "pipeline" in f)  # the plan's airports
