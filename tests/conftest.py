"""Shared fixtures: flights are expensive, so each (scenario, seed) is flown once per session."""

from __future__ import annotations

import dataclasses
import pytest


@pytest.fixture(scope="session")
def fly_cached():
    """fly_cached(name, seed=None, **plan_changes) -> (plan, track), memoised for the session."""
    from flightmode.scenarios.registry import resolve
    from flightmode.sim.flight.simulate import fly

    cache: dict = {}

    def _fly(name: str, seed: int | None = None, **changes):
        key = (name, seed, tuple(sorted(changes.items())))
        if key not in cache:
            plan, _, _ = resolve(name)
            if seed is not None:
                plan = dataclasses.replace(plan, seed=seed)
            if changes:
                plan = dataclasses.replace(plan, **changes)
            cache[key] = (plan, fly(plan))
        return cache[key]

    return _fly


@pytest.fixture(scope="session")
def pattern_run(tmp_path_factory):
    """A run folder written by `flightmode fly pattern` (the CLI, end to end), once per session."""
    from typer.testing import CliRunner

    from flightmode.scenarios.cli import app

    out = tmp_path_factory.mktemp("runs")
    r = CliRunner().invoke(app, ["fly", "pattern", "--out", str(out)])
    assert r.exit_code == 0, r.output
    return out / "pattern-s1", r.output


@pytest.fixture(scope="session")
def default_run(tmp_path_factory):
    """`flightmode fly` (the default scenario, end to end, recording.rrd included), once per session."""
    from typer.testing import CliRunner

    from flightmode.scenarios.cli import app

    out = tmp_path_factory.mktemp("runs")
    r = CliRunner().invoke(app, ["fly", "--out", str(out)])
    assert r.exit_code == 0, r.output
    return out / "gva-lhr-a320-s1", r.output
