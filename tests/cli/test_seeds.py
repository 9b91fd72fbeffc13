"""``flightmode seeds``: an unknown seed is a one-line error with exit status 2 (the reproduction
itself, an hour of bench data and the section 5.1.1 loop, is tested piece by piece in
tests/detector/test_seed000_tables.py)."""

from __future__ import annotations

from typer.testing import CliRunner

from flightmode.cli.main import app


def test_unknown_seed_is_one_line_and_exit_2():
    r = CliRunner().invoke(app, ["seeds", "001"])
    assert r.exit_code == 2
    assert "reproducible here: 000" in r.output
