"""docs/cli.md is the app's own help: regenerated here and compared, so it cannot drift; and
`flightmode --help` lists the commands in the panels of the order a user works."""

from __future__ import annotations

from pathlib import Path

from typer.testing import CliRunner

from flightmode.cli.main import app

ROOT = Path(__file__).resolve().parents[2]


def test_docs_cli_md_is_the_apps_help():
    from flightmode.cli.docs import reference

    text = (ROOT / "docs" / "cli.md").read_text(encoding="utf-8")
    assert text == reference(), (
        "docs/cli.md drifted from the app: python -m flightmode.cli.docs > docs/cli.md"
    )


def test_the_reference_holds_every_command():
    from flightmode.cli.docs import reference

    text = reference()
    for cmd in ("scenarios", "family", "fly", "dataset", "view", "path", "cabin", "validate", "detect"):
        assert f"### `flightmode {cmd}`" in text
    for cmd in (
        "sweep",
        "certify",
        "sense",
        "activity synth",
        "eobs detect",
        "eobs calibrate",
        "eobs tradeoff",
    ):
        assert f"`flightmode {cmd}`" in text


def test_help_groups_the_commands_in_the_order_a_user_works():
    r = CliRunner().invoke(app, ["--help"], env={"COLUMNS": "120"})
    assert r.exit_code == 0, r.output
    text = r.output
    panels = ["Make flights:", "Look at them:", "Detect and stress-test:", "Sensors and tags:"]
    at = [text.index(p) for p in panels]
    assert at == sorted(at), at
    # each command under its panel, in the order a user meets them
    order = ["scenarios", "family", "fly", "dataset", "view", "path", "cabin", "validate", "detect", "sweep"]
    order += ["certify", "seeds", "activity", "sense", "eobs"]
    lines = [
        ln.split()[0]
        for ln in text.split("Commands:")[1].splitlines()
        if ln.startswith("    ") and ln[4] != " "
    ]
    assert lines == order, lines
    # seeds are named by what they are, not by number, in the top-level help
    assert "seed 00" not in text
    # no arguments: the help, not an error
    bare = CliRunner().invoke(app, [])
    assert "Make flights:" in bare.output


def test_every_command_has_an_example_and_a_json_or_no_results():
    from flightmode.cli.docs import reference

    blocks = reference().split("### `flightmode ")[1:]
    for b in blocks:
        name = b.split("`")[0]
        if name in ("activity", "eobs"):  # groups: their commands carry the examples
            continue
        assert "Example: flightmode" in b, name
        if name != "view":  # view opens a viewer and prints no results
            assert "--json" in b, name
