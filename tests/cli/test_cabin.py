"""`flightmode cabin RUN`: the schedule's figures, then the cabin from 5 minutes before touchdown to 2
after beside its anchors; --json the same numbers; --out the figure."""

from __future__ import annotations

import json

import pytest
from typer.testing import CliRunner

from flightmode.cli.main import app


def test_cabin_prints_the_landing_window_beside_its_anchors(pattern_run, tmp_path):
    from flightmode.runs.run_io import read_track
    from flightmode.sim.flight.cabin import LANDING_RESIDUAL, UNCERTAIN
    from flightmode.sim.flight.cabin_landing import VENT_ANCHORS, landing_figures

    run, _ = pattern_run
    r = CliRunner().invoke(app, ["cabin", str(run), "--out", str(tmp_path)], env={"COLUMNS": "220"})
    assert r.exit_code == 0, r.output
    for words in (
        "the cabin near touchdown (737)",
        "landing pressure reached",
        "residual overpressure at touchdown",
        "pressure step after touchdown",
        VENT_ANCHORS["737"].text(),
    ):
        assert words in r.output, words
    assert (tmp_path / "cabin.png").stat().st_size > 10_000  # a drawn figure, not an empty file
    j = CliRunner().invoke(app, ["cabin", str(run), "--json"])
    assert j.exit_code == 0, j.output
    doc = json.loads(j.output)
    # the numbers are the measurement's on the run's own track (JSON round trip: exact floats)
    track, _ = read_track(run)
    f = landing_figures(
        track.t_s, track.alt_m, track.cabin_pressure_pa, track.ambient_pressure_pa, track.phase_code
    )
    assert doc["landing"] == pytest.approx(f, rel=1e-12, nan_ok=True)
    assert doc["landing_anchors"]["landing_residual_psi"] == [LANDING_RESIDUAL.low, LANDING_RESIDUAL.high]
    assert doc["landing_anchors"]["vent"] == VENT_ANCHORS["737"].text()
    # the run's parameter values beside the ranges: the pattern overrides none
    assert doc["landing_anchors"]["run_values"] == {p.name: p.value for p in UNCERTAIN}
    # the table prints what the JSON holds (the residual to 3 decimals)
    assert f"{doc['landing']['residual_psi']:.3f} psi" in r.output
